//! Presets, files and errors of a species.

#[test]
fn each_preset_is_its_shipped_file() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/species");
    for preset in Species::presets() {
        let file = dir.join(format!("{}.species.ron", preset.name.to_lowercase()));
        let text = std::fs::read_to_string(&file).expect("shipped species file");
        assert_eq!(
            Species::from_ron(&text).unwrap(),
            preset,
            "{}",
            file.display()
        );
        preset.validate().unwrap();
    }
}

#[test]
fn an_unknown_field_is_an_error_naming_it_and_where() {
    let error = Species::from_ron("(\n    name: \"X\",\n    diamter: 0.05,\n)").unwrap_err();
    let text = error.to_string();
    assert!(text.contains("diamter"), "{text}");
    assert!(text.contains("3:"), "names the line: {text}");
}

use super::*;

#[test]
fn the_paper_model_is_the_papers_fig_12() {
    let s = Species::paper();
    s.validate().unwrap();
    assert_eq!(s.contraction_frequency, 0.7);
    assert_eq!(s.diameter, 0.040);
    assert_eq!(s.height, 0.028);
    assert_eq!(s.thickness, 0.004);
    assert_eq!(s.elastic_modulus, 1186.0);
    assert_eq!(s.contraction_ratio, 0.56);
    assert_eq!(s.tentacle_cross_section, 0.01);
    // The compact co-moving box keeps the paper's resolution, ten cells per diameter.
    assert_eq!((s.grid_resolution, s.domain_diameters), (60, 6.0));
    assert!((s.cell_size() - 0.004).abs() < 1e-7);
    // The paper's own numerics stay one call away.
    let paper = Species::paper().with_paper_numerics();
    paper.validate().unwrap();
    assert_eq!((paper.grid_resolution, paper.domain_diameters), (100, 10.0));
    assert_eq!(paper.kernel, Kernel::Bilinear);
    assert!((paper.cell_size() - 0.004).abs() < 1e-7);
}

#[test]
fn the_moon_jelly_is_a_saucer_timed_as_the_animal() {
    let s = Species::aurelia();
    s.validate().unwrap();
    // A saucer (docs/physics.md section 5): its subumbrella 0.26 D deep, as Dabiri's
    // 15.5 cm animal and Aurelia's 0.25–0.3, under a thinner apex than the record's lens;
    // its muscle a band on the margin's quarter that pulls to 0.62 of its length (the
    // animal's radius varies by about 36%); 0.80 s of contraction in a 2.87 s cycle.
    assert!((s.height / s.diameter - 0.26).abs() < 0.005);
    assert!(s.thickness < 0.125 * s.diameter);
    assert_eq!((s.muscle_extent, s.contraction_ratio), (0.25, 0.62));
    assert!((s.contraction_duty - 0.80 / 2.87).abs() < 0.005);
    // Its muscle lets go well before the bell has refilled; the recoil is the bell's.
    assert!(s.relaxation_span <= 0.5);
    assert_eq!(s.slice_geometry, SliceGeometry::Axisymmetric);
    // A force-generating muscle in a mesoglea that returns 58% of its strain energy
    // (DeMont & Gosline 1988).
    assert_eq!(s.muscle_law, crate::species::MuscleLaw::Force);
    assert_eq!(s.mesoglea_resilience, 0.58);
    // Seventeen cells per diameter on the paper's grid (3.5 diameters of 60 cells).
    assert!((s.diameter / s.cell_size() - 60.0 / 3.5).abs() < 1e-3);
    // The paper's model keeps its own plate: the same bending law, a thinner wall.
    let paper = Species::paper();
    let plate = |s: &Species| s.elastic_modulus * s.thickness.powi(3) / 12.0 / 0.002;
    assert!((s.angular_stiffness / plate(&s) - 1.0).abs() < 1e-5);
    assert!((paper.angular_stiffness / plate(&paper) - 1.0).abs() < 1e-5);
}

#[test]
fn the_animals_bend_as_their_mesoglea_and_the_paper_as_its_springs() {
    use crate::species::Bending;
    for s in Species::presets() {
        assert_eq!(s.bending, Bending::Mesoglea, "{}", s.name);
        // The plate law gives the very number the springs' constant holds at this size:
        // the animals swim to the bit as before.
        assert_eq!(
            s.bending_stiffness().to_bits(),
            s.angular_stiffness.to_bits(),
            "{}",
            s.name
        );
        // The springs' constant is not read; the wall's modulus and thickness are.
        let springs_changed = Species {
            angular_stiffness: 0.5,
            ..s.clone()
        };
        assert_eq!(springs_changed.bending_stiffness(), s.bending_stiffness());
        let stiffer = Species {
            elastic_modulus: 2.0 * s.elastic_modulus,
            ..s.clone()
        };
        let close = |a: f32, b: f32| (a / b - 1.0).abs() < 1e-5;
        assert!(close(
            stiffer.bending_stiffness(),
            2.0 * s.bending_stiffness()
        ));
        let thicker = Species {
            thickness: 2.0 * s.thickness,
            ..s.clone()
        };
        assert!(close(
            thicker.bending_stiffness(),
            8.0 * s.bending_stiffness()
        ));
        // Made larger by its lengths alone, it bends as `resized` makes it bend.
        let big = s.resized(2.0 * s.diameter);
        let by_hand = Species {
            diameter: big.diameter,
            height: big.height,
            thickness: big.thickness,
            ..s.clone()
        };
        assert!(close(by_hand.bending_stiffness(), big.bending_stiffness()));
    }
    let paper = Species::paper();
    assert_eq!(paper.bending, Bending::Springs);
    let springs_changed = Species {
        angular_stiffness: 0.5,
        ..paper.clone()
    };
    assert_eq!(springs_changed.bending_stiffness(), 0.5);
    let thicker = Species {
        thickness: 2.0 * paper.thickness,
        ..paper.clone()
    };
    assert_eq!(thicker.bending_stiffness(), paper.bending_stiffness());
}

#[test]
fn the_bending_reads_and_writes_and_a_wrong_one_is_named() {
    let s = Species::from_ron("(bending: Springs)").unwrap();
    assert_eq!(s.bending, crate::species::Bending::Springs);
    let back = Species::from_ron(&s.to_ron().unwrap()).unwrap();
    assert_eq!(back.bending, crate::species::Bending::Springs);
    let msg = Species::from_ron("(bending: Rubber)")
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("Rubber") && msg.contains("Mesoglea"),
        "the message names the bad value and the good ones: {msg}"
    );
}

#[test]
fn a_grown_animal_may_bend_as_stiffly_as_its_size_holds() {
    use crate::species::limits::stiffest_bending;
    // An adult moon jelly of 30 cm and one a metre wide, resized: the plate grows as the
    // size cubed, and so does what the implicit step holds.
    for d in [0.3, 1.0] {
        let big = Species::aurelia().resized(d);
        assert_eq!(big.validate(), Ok(()), "{d} m");
        assert!(
            big.bending_stiffness() as f64 <= 0.8 * stiffest_bending(d),
            "{d} m"
        );
    }
    // Springs stiffer than a 40 mm bell holds are refused by name, and the reason says
    // what the bell's size allows.
    let paper = Species {
        angular_stiffness: 5.0,
        ..Species::paper()
    };
    let err = paper.validate().unwrap_err();
    assert_eq!(err.field(), Some("angular_stiffness"));
    assert!(err.to_string().contains("at most 1 N·m/rad"), "{err}");
}

#[test]
fn a_mesoglea_too_stiff_to_bend_is_named() {
    // A 25 cm moon jelly with a wall of 8 cm: E·ϑ³/12 per 2 mm is 25 N·m/rad.
    let s = Species {
        diameter: 0.25,
        height: 0.1,
        thickness: 0.08,
        ..Species::aurelia()
    };
    let err = s.validate().unwrap_err().to_string();
    assert!(err.contains("bending") && err.contains("plate"), "{err}");
    assert!(err.contains("thinner or softer"), "{err}");
    // A wall of a tenth of a millimetre hardly bends at all: refused the other way.
    let thin = Species {
        thickness: 1e-4,
        ..Species::aurelia()
    };
    let err = thin.validate().unwrap_err().to_string();
    assert!(
        err.contains("bending") && err.contains("thicker or stiffer"),
        "{err}"
    );
    // With the paper's springs the same wall takes `angular_stiffness` and is valid.
    let springs = Species {
        bending: crate::species::Bending::Springs,
        ..s
    };
    assert_eq!(springs.validate(), Ok(()));
}

#[test]
fn ron_round_trip() {
    let mut s = Species::aurelia();
    s.name = "Test".into();
    s.expansion_stagger = 0.25;
    let text = s.to_ron().unwrap();
    assert_eq!(Species::from_ron(&text).unwrap(), s);
}

#[test]
fn missing_fields_take_defaults() {
    let s = Species::from_ron("(name: \"Short\", contraction_frequency: 0.5)").unwrap();
    assert_eq!(s.contraction_frequency, 0.5);
    assert_eq!(s.diameter, Species::aurelia().diameter);
}

fn field_of(s: &Species) -> &'static str {
    s.validate().unwrap_err().field().unwrap()
}

#[test]
fn every_bad_value_names_its_field() {
    type Mutation = Box<dyn Fn(&mut Species)>;
    let cases: Vec<(&str, Mutation)> = vec![
        ("grid_resolution", Box::new(|s| s.grid_resolution = 8)),
        ("grid_resolution", Box::new(|s| s.grid_resolution = 1024)),
        ("viscosity", Box::new(|s| s.viscosity = -1.0)),
        ("density", Box::new(|s| s.density = 0.0)),
        ("diameter", Box::new(|s| s.diameter = f32::NAN)),
        ("diameter", Box::new(|s| s.diameter = -0.04)),
        ("height", Box::new(|s| s.height = 0.0)),
        ("height", Box::new(|s| s.height = f32::INFINITY)),
        ("thickness", Box::new(|s| s.thickness = 0.0)),
        ("thickness", Box::new(|s| s.thickness = 0.03)),
        ("elastic_modulus", Box::new(|s| s.elastic_modulus = -5.0)),
        (
            "angular_stiffness",
            Box::new(|s| s.angular_stiffness = -1.0),
        ),
        ("muscle_modulus", Box::new(|s| s.muscle_modulus = 0.0)),
        (
            "contraction_frequency",
            Box::new(|s| s.contraction_frequency = 0.0),
        ),
        (
            "contraction_frequency",
            Box::new(|s| s.contraction_frequency = -1.0),
        ),
        ("contraction_ratio", Box::new(|s| s.contraction_ratio = 1.5)),
        ("expansion_stagger", Box::new(|s| s.expansion_stagger = 2.0)),
        ("tentacle_length", Box::new(|s| s.tentacle_length = -0.01)),
        ("mesh_segments", Box::new(|s| s.mesh_segments = 2)),
        ("bell_color[3]", Box::new(|s| s.bell_color[3] = 2.0)),
    ];
    for (field, mutate) in cases {
        let mut s = Species::aurelia();
        mutate(&mut s);
        assert_eq!(field_of(&s), field, "{:?}", s.validate());
        let msg = s.validate().unwrap_err().to_string();
        assert!(msg.contains(field), "message `{msg}` names `{field}`");
    }
}

#[test]
fn bad_ron_is_an_error_not_a_panic() {
    assert!(matches!(
        Species::from_ron("(diameter: \"wide\")"),
        Err(SpeciesError::Parse(_))
    ));
    let err = Species::from_ron("(diameter: -1.0)").unwrap_err();
    assert_eq!(err.field(), Some("diameter"));
}

#[test]
fn the_slice_geometry_reads_and_writes_and_a_wrong_one_is_named() {
    let s = Species::from_ron("(slice_geometry: Axisymmetric)").unwrap();
    assert_eq!(s.slice_geometry, SliceGeometry::Axisymmetric);
    let back = Species::from_ron(&s.to_ron().unwrap()).unwrap();
    assert_eq!(back.slice_geometry, SliceGeometry::Axisymmetric);
    assert_eq!(Species::paper().slice_geometry, SliceGeometry::Planar);
    assert_eq!(
        Species::aurelia().slice_geometry,
        SliceGeometry::Axisymmetric
    );
    let err = Species::from_ron("(slice_geometry: Spherical)").unwrap_err();
    let msg = err.to_string();
    println!("{msg}");
    assert!(matches!(err, SpeciesError::Parse(_)), "{msg}");
    assert!(
        msg.contains("Spherical") && msg.contains("Axisymmetric"),
        "the message names the bad value and the good ones: {msg}"
    );
}

#[test]
fn the_bell_coupling_reads_and_writes_and_a_wrong_one_is_named() {
    let s = Species::from_ron("(bell_coupling: WaterResponse)").unwrap();
    assert_eq!(s.bell_coupling, BellCoupling::WaterResponse);
    let back = Species::from_ron(&s.to_ron().unwrap()).unwrap();
    assert_eq!(back.bell_coupling, BellCoupling::WaterResponse);
    // Every shipped species and the paper's model are calibrated with the added mass.
    for species in [
        Species::aurelia(),
        Species::paper(),
        Species::aequorea(),
        Species::sarsia(),
    ] {
        assert_eq!(
            species.bell_coupling,
            BellCoupling::AddedMass,
            "{}",
            species.name
        );
    }
    let err = Species::from_ron("(bell_coupling: Exact)").unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, SpeciesError::Parse(_)), "{msg}");
    assert!(
        msg.contains("Exact") && msg.contains("WaterResponse"),
        "the message names the bad value and the good ones: {msg}"
    );
}

/// The limits' cost model counts what the advection scheme costs: the dearer schemes
/// estimate dearer in proportion to the cells, so a species that is cheap only because
/// the model ignored its scheme is refused as too slow.
#[test]
fn the_cost_model_counts_the_advection_scheme() {
    use super::limits::{MAX_COST_PER_SECOND, simulation_cost};
    let with = |advection, grid_resolution| {
        let s = Species {
            advection,
            grid_resolution,
            ..Species::aurelia()
        };
        (simulation_cost(&s), s)
    };
    for grid in [60, 120] {
        let (plain, _) = with(Advection::SemiLagrangian, grid);
        let (maccormack, _) = with(Advection::MacCormack, grid);
        let (cubic, _) = with(Advection::Cubic, grid);
        assert!(
            plain < cubic && cubic < maccormack,
            "grid {grid}: {plain} {maccormack} {cubic}"
        );
    }
    // Where the cells are most of the cost, near the measured ratios of a cell's step
    // (1.85 and 3.7; the sweeps and points, which no scheme changes, dilute them).
    let (plain, _) = with(Advection::SemiLagrangian, 192);
    let (maccormack, _) = with(Advection::MacCormack, 192);
    let (cubic, s) = with(Advection::Cubic, 192);
    assert!((1.6..1.85).contains(&(cubic / plain)), "{}", cubic / plain);
    assert!(
        (3.0..3.7).contains(&(maccormack / plain)),
        "{}",
        maccormack / plain
    );
    // A grid the plain step affords and bicubic sampling does not.
    let grid = (60..=192)
        .find(|&g| with(Advection::Cubic, g).0 > MAX_COST_PER_SECOND)
        .map(|g| (g, with(Advection::SemiLagrangian, g).0));
    if let Some((g, plain)) = grid {
        assert!(plain <= MAX_COST_PER_SECOND, "grid {g}: {plain}");
        assert_eq!(s.validate().is_err(), cubic > MAX_COST_PER_SECOND);
    }
}

#[test]
fn the_animals_mesoglea_keeps_its_viscosity_at_any_pulse_rate() {
    let own = Species::aurelia();
    let faster = Species {
        contraction_frequency: 2.0 * own.contraction_frequency,
        ..own.clone()
    };
    assert!(own.mesoglea_damping_time() > 0.0);
    assert!((faster.mesoglea_damping_time() / own.mesoglea_damping_time() - 1.0).abs() < 1e-6);
    // The paper's reading: the resilience is over whatever cycle it beats.
    let cycle = Species {
        muscle_timing: crate::species::MuscleTiming::Cycle,
        ..own.clone()
    };
    let cycle_faster = Species {
        contraction_frequency: 2.0 * own.contraction_frequency,
        ..cycle.clone()
    };
    let ratio = cycle_faster.mesoglea_damping_time() / cycle.mesoglea_damping_time();
    assert!((ratio - 0.5).abs() < 1e-6, "{ratio}");
}

#[test]
fn the_natural_rate_falls_as_the_root_of_the_size() {
    let s = Species::aurelia();
    let larger = Species {
        diameter: 4.0 * s.diameter,
        ..s.clone()
    };
    assert!((larger.natural_pulse_rate() - 0.5 * s.natural_pulse_rate()).abs() < 1e-6);
}

/// Every shipped animal resized: each length of its body scaled, its mesoglea's plate
/// bending as the cube, beating at its own rate for the new size; everything else (its
/// materials, its box in diameters, its shares) kept. Resized to its own size, itself.
#[test]
fn a_resized_animal_keeps_its_shape_and_beats_at_its_rate_for_the_size() {
    for s in [Species::aurelia(), Species::aequorea(), Species::sarsia()] {
        assert_eq!(s.resized(s.diameter), s, "{}", s.name);
        let big = s.resized(2.5 * s.diameter);
        let close = |a: f32, b: f32| (a - b).abs() <= 1e-5 * b.abs();
        for (name, grown, own, power) in [
            ("height", big.height, s.height, 1),
            ("thickness", big.thickness, s.thickness, 1),
            ("tentacle_length", big.tentacle_length, s.tentacle_length, 1),
            ("tentacle_radius", big.tentacle_radius, s.tentacle_radius, 1),
            (
                "manubrium_length",
                big.manubrium_length,
                s.manubrium_length,
                1,
            ),
            ("oral_arm_length", big.oral_arm_length, s.oral_arm_length, 1),
            (
                "angular_stiffness",
                big.angular_stiffness,
                s.angular_stiffness,
                3,
            ),
        ] {
            assert!(
                close(grown, own * 2.5f32.powi(power)),
                "{}: {name} {grown} from {own}",
                s.name
            );
        }
        assert!(close(
            big.contraction_frequency,
            s.natural_pulse_rate() / 2.5f32.sqrt()
        ));
        assert_eq!(big.contraction_frequency, big.natural_pulse_rate());
        assert_eq!(big.cycle_stretch(), 1.0, "{}: at its own rate", s.name);
        assert_eq!(
            (big.elastic_modulus, big.domain_diameters, big.muscle_extent),
            (s.elastic_modulus, s.domain_diameters, s.muscle_extent)
        );
        assert_eq!(big.validate(), Ok(()), "{}", s.name);
    }
}

/// Oral tubes that hang no deeper than the subumbrella follow the slice alone: the moon
/// jelly's long arms and *Sarsia*'s manubrium reach out below the bell and get a guide
/// each, *Aequorea*'s short lips stay in its cavity and get none, until they are made
/// longer than the cavity is deep.
#[test]
fn only_oral_tubes_that_reach_out_of_the_cavity_get_guides() {
    assert_eq!(Species::aurelia().oral_guide_count(), 5);
    assert_eq!(Species::sarsia().oral_guide_count(), 1);
    let lips = Species::aequorea();
    assert!(lips.oral_tubes_within_cavity());
    assert_eq!(lips.oral_guide_count(), 0);
    let longer = Species {
        oral_arm_length: lips.height,
        ..lips.clone()
    };
    assert_eq!(
        longer.oral_guide_count(),
        13,
        "its manubrium and twelve arms"
    );
    // No guides at all: none for the tubes either, however long.
    let unguided = Species {
        tentacle_guides: 0,
        ..Species::aurelia()
    };
    assert_eq!(unguided.oral_guide_count(), 0);
}

/// A count rounded without libm is `f32::round`'s, ties and their neighbours included,
/// over the range a mesh's rings ask for and well past it.
#[test]
fn a_count_rounds_as_f32_round_does() {
    let mut xs: Vec<f32> = (0..=4096).map(|k| k as f32 / 16.0).collect();
    for k in 0..=300 {
        let tie = k as f32 + 0.5;
        xs.extend([tie, tie.next_down(), tie.next_up(), (k as f32).next_up()]);
    }
    xs.extend([0.49999997, 8_388_607.5, 8_388_608.0]);
    for x in xs {
        assert_eq!(
            super::limits::rounded(x),
            x.round() as usize,
            "{x} ({:#x})",
            x.to_bits()
        );
    }
}
