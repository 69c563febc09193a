//! Properties of the coupled slice simulation, through the headless API (`docs/usage.md`).
//! What each long check requires, and where its numbers come from: `docs/physics.md`.
//! Fast ones run by default; the long ones (calibration, convergence, 1000 strokes) are
//! `#[ignore]`d: `cargo test --release --no-default-features --test slice -- --ignored
//! --nocapture` prints every figure they check.

mod common;

use bevy_jellyfish::shape::profile::Profile;
use bevy_jellyfish::sim::clock::FixedClock;
use bevy_jellyfish::sim::inspect::{Outline, cavity, contains};
use bevy_jellyfish::{BellCoupling, MuscleLaw, MuscleTiming, SliceGeometry, SliceSim, Species};
use glam::Vec2;

/// The shipped species in `geometry`.
fn shipped(geometry: SliceGeometry) -> Vec<Species> {
    common::shipped_species()
        .into_iter()
        .map(|s| Species {
            slice_geometry: geometry,
            ..s
        })
        .collect()
}

/// The moon jelly calibrated in `geometry`: the animal ([`Species::aurelia`]) in r–z, the
/// geometry it is calibrated in, and the paper's ([`Species::paper`]) in the plane, where
/// the paper calibrated it (a saucer's shallow stroke hardly carries in the plane: 0.09
/// diameters per cycle, `docs/numerics.md`).
fn aurelia(geometry: SliceGeometry) -> Species {
    match geometry {
        SliceGeometry::Axisymmetric => Species::aurelia(),
        SliceGeometry::Planar => Species::paper(),
    }
}

/// Every species calibrated in `geometry`, shipped or the paper's: the checks of how a
/// species swims (convergence, its fringe's drag) hold each in the geometry it uses.
fn calibrated_in(geometry: SliceGeometry) -> Vec<Species> {
    let mut all = common::shipped_species();
    all.push(Species::paper());
    all.retain(|s| s.slice_geometry == geometry);
    all
}

/// [`calibrated_in`], each also grown to twice and shrunk to half its diameter
/// (`Species::resized`: every length, and the pulse rate its animal's at the size).
fn calibrated_at_three_sizes(geometry: SliceGeometry) -> Vec<Species> {
    calibrated_in(geometry)
        .iter()
        .flat_map(three_sizes)
        .collect()
}

/// `s` shrunk to half its diameter, itself, and grown to twice it (`Species::resized`).
fn three_sizes(s: &Species) -> [Species; 3] {
    let d = s.diameter;
    [s.resized(0.5 * d), s.clone(), s.resized(2.0 * d)]
}

/// Each species' speed under way, m/s, from its `stroke_and_refill` run: the distance a
/// stroke times its diameter and its pulse rate.
fn speeds(species: &[Species], runs: &[(f32, f32, u32)]) -> Vec<f32> {
    species
        .iter()
        .zip(runs)
        .map(|(s, (stroke, ..))| stroke * s.diameter * s.contraction_frequency)
        .collect()
}

/// A species' name and its diameter in millimetres, as "Sarsia 8 mm".
fn sized(s: &Species) -> String {
    format!("{} {:.0} mm", s.name, 1000.0 * s.diameter)
}

/// The paper's Fig. 12 moon jelly in `geometry`: its findings are checked on it.
fn paper(geometry: SliceGeometry) -> Species {
    Species {
        slice_geometry: geometry,
        ..Species::paper()
    }
}

/// Runs a check in the planar slice only, as `name::planar`: a claim of the paper's planar
/// calibration, or an invariant the axisymmetric slice does not meet yet
/// (`docs/numerics.md`, "The axisymmetric slice": what it does not meet, with figures).
macro_rules! in_the_planar_slice {
    ($(#[$attr:meta])* fn $name:ident) => {
        mod $name {
            use super::*;
            #[test]
            $(#[$attr])*
            fn planar() {
                super::$name(SliceGeometry::Planar)
            }
        }
    };
}

/// Runs a check once per slice geometry, as `name::planar` and `name::axisymmetric`.
macro_rules! in_both_geometries {
    ($(#[$attr:meta])* fn $name:ident) => {
        mod $name {
            use super::*;
            #[test]
            $(#[$attr])*
            fn planar() {
                super::$name(SliceGeometry::Planar)
            }
            #[test]
            $(#[$attr])*
            fn axisymmetric() {
                super::$name(SliceGeometry::Axisymmetric)
            }
        }
    };
}

/// `run` on each of `items`, each on a thread of its own; the results in their order.
fn in_parallel<T: Sync, R: Send>(items: &[T], run: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let run = &run;
    std::thread::scope(|scope| {
        let handles: Vec<_> = items.iter().map(|x| scope.spawn(move || run(x))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    })
}

fn run_cycles(sim: &mut SliceSim, cycles: f32) {
    let end = sim.time() + cycles / sim.species().contraction_frequency;
    while sim.time() < end - 1e-4 {
        sim.advance((end - sim.time()).min(0.1));
    }
}

/// Every state the slice has that a split of time could change: bits of the bell, the
/// water and the distance.
fn state_bits(sim: &SliceSim) -> (Vec<u32>, Vec<u32>, u32) {
    let bell = sim
        .view()
        .bell
        .iter()
        .chain(sim.view().tentacles.iter().flat_map(|t| t.iter()))
        .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
        .collect();
    let fluid = sim
        .fluid()
        .u
        .iter()
        .chain(&sim.fluid().v)
        .map(|x| x.to_bits())
        .collect();
    (bell, fluid, sim.swim_distance().to_bits())
}

in_both_geometries!(fn no_jet_along_the_axis_grows_with_the_grid);
/// The water on the bell's axis (a planar slice's mirror line) runs as fast, within a
/// quarter, on a grid twice as fine, for every species calibrated in the geometry and the
/// paper's model: rings near the axis spread by their own radius drove a jet one column
/// wide along it that grew with each refinement (the paper's model in r–z 0.075 and
/// 0.271 m/s at 60 and 120 cells, the moon jelly 0.053 and 0.092, where their margins
/// close at a few centimetres a second; `docs/numerics.md`, "The axis").
fn no_jet_along_the_axis_grows_with_the_grid(geometry: SliceGeometry) {
    let mut species = calibrated_in(geometry);
    if geometry == SliceGeometry::Axisymmetric {
        species.push(paper(geometry));
    }
    let on_axis = |s: &Species| {
        let mut sim = SliceSim::new(s).unwrap();
        let mut fastest = 0.0f32;
        while sim.cycle() < 3 {
            sim.advance_with(1.0 / 60.0, |sim| {
                let f = sim.fluid();
                if sim.cycle() >= 1 {
                    let (n, axis) = (f.n, f.n / 2);
                    let column = f.v.iter().skip(axis).step_by(n);
                    fastest = column.fold(fastest, |m, v| m.max(v.abs()));
                }
            });
        }
        fastest
    };
    let runs = in_parallel(&species, |s| {
        let fine = Species {
            grid_resolution: 2 * s.grid_resolution,
            ..s.clone()
        };
        (on_axis(s), on_axis(&fine))
    });
    for (s, (coarse, fine)) in species.iter().zip(runs) {
        println!(
            "{}: fastest on the axis, cycles 1-3: {coarse:.4} m/s at G, {fine:.4} at 2·G",
            s.name
        );
        assert!(coarse > 0.0 && coarse.is_finite(), "{}: {coarse}", s.name);
        assert!(
            (fine / coarse - 1.0).abs() <= 0.25,
            "{}: {coarse} m/s on the axis at grid G, {fine} at 2·G",
            s.name
        );
    }
}

in_both_geometries!(fn swims_apex_first);
fn swims_apex_first(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    let start = sim.bell_centroid_world();
    run_cycles(&mut sim, 4.0);
    let moved = sim.bell_centroid_world() - start;
    assert!(
        sim.swim_distance() > 0.3 * sim.species().diameter,
        "swam {}",
        sim.swim_distance()
    );
    assert!(
        moved.y > 0.0,
        "the bell moves towards its apex (+y): {moved}"
    );
    assert_eq!(sim.recoveries(), 0);
}

in_both_geometries!(fn stays_incompressible);
fn stays_incompressible(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    for _ in 0..60 {
        sim.advance(1.0 / 30.0);
        let h = sim.fluid().h;
        let relative = h * sim.fluid_divergence_max() / sim.fluid_speed_max().max(1e-9);
        assert!(
            relative <= 1e-4,
            "h·max|div u|/max|u| = {relative} at t = {}",
            sim.time()
        );
    }
    assert!(sim.fluid_speed_max() > 1e-3, "the bell stirs the water");
}

in_both_geometries!(fn invalid_species_is_an_error_naming_the_field);
fn invalid_species_is_an_error_naming_the_field(geometry: SliceGeometry) {
    let bad = Species {
        diameter: -0.04,
        ..aurelia(geometry)
    };
    let err = SliceSim::new(&bad)
        .err()
        .expect("negative diameter is refused");
    assert_eq!(err.field(), Some("diameter"));
    let bad = Species {
        contraction_frequency: f32::NAN,
        ..aurelia(geometry)
    };
    assert_eq!(
        SliceSim::new(&bad).err().unwrap().field(),
        Some("contraction_frequency")
    );
}

in_both_geometries!(fn meaningless_time_steps_do_nothing);
fn meaningless_time_steps_do_nothing(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    for dt in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        sim.advance(dt);
    }
    assert_eq!(sim.time(), 0.0);
    assert_eq!(sim.steps(), 0);
    assert!(sim.bell_points().iter().all(|p| p.is_finite()));
}

in_both_geometries!(fn a_long_frame_takes_fixed_steps_of_the_species);
fn a_long_frame_takes_fixed_steps_of_the_species(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    let step = SliceSim::step_length(sim.species());
    sim.advance(0.5);
    assert_eq!(sim.last_substeps(), (0.5 / step).floor() as usize);
    assert!((sim.clock().added() - 0.5).abs() < 1e-12);
    assert!(sim.time() <= 0.5 && sim.time() > 0.5 - step);
    // A short frame adds time and may take no step at all.
    let steps = sim.steps();
    sim.advance(0.2 * step);
    assert!(sim.steps() - steps <= 1);
    assert!(sim.bell_points().iter().all(|p| p.is_finite()));
}

in_both_geometries!(fn any_binary_split_of_the_same_time_gives_the_same_state);
fn any_binary_split_of_the_same_time_gives_the_same_state(geometry: SliceGeometry) {
    let species = aurelia(geometry);
    let run = |parts: &[f32], repeat: usize| {
        let mut sim = SliceSim::new(&species).unwrap();
        for _ in 0..repeat {
            for &dt in parts {
                sim.advance(dt);
            }
        }
        sim
    };
    // 8 s three ways: 1/32 s × 256, 1/64 s × 512, and 1/128 + 3/128 + 1/16 + 1/32 s × 64.
    let a = run(&[1.0 / 32.0], 256);
    let b = run(&[1.0 / 64.0], 512);
    let c = run(&[1.0 / 128.0, 3.0 / 128.0, 1.0 / 16.0, 1.0 / 32.0], 64);
    assert!(a.steps() > 200, "{} steps", a.steps());
    assert_eq!(
        state_bits(&a),
        state_bits(&b),
        "1/32 s against 1/64 s frames"
    );
    assert_eq!(
        state_bits(&a),
        state_bits(&c),
        "1/32 s against mixed frames"
    );
    assert!(a.swim_distance() > 0.0);
}

in_both_geometries!(fn thirty_sixty_and_144_hz_frames_agree);
fn thirty_sixty_and_144_hz_frames_agree(geometry: SliceGeometry) {
    let species = aurelia(geometry);
    let swim = |hz: f32| {
        let mut sim = SliceSim::new(&species).unwrap();
        let frames = (24.0 * hz).round() as usize;
        for _ in 0..frames {
            sim.advance(1.0 / hz);
        }
        sim.swim_distance()
    };
    let (a, b, c) = (swim(30.0), swim(60.0), swim(144.0));
    for (hz, d) in [(60, b), (144, c)] {
        assert!(
            (d / a - 1.0).abs() <= 0.02,
            "24 s at 30 Hz swam {a} m, at {hz} Hz {d} m"
        );
    }
    assert!(a > 2.0 * species.diameter, "swam {a} m in 24 s");
}

in_both_geometries!(fn with_the_waters_response_the_wall_holds_and_time_splits_alike);
/// `BellCoupling::WaterResponse`: the subumbrella keeps its length under the stroke at the
/// species' own step, where the added mass lets it stretch by a tenth and more (so a
/// solve that lost the response would show), the bell swims apex first, and the slice is
/// still deaf to how its caller splits time: frames of 1/32 s and of 1/64 s, the same bits.
fn with_the_waters_response_the_wall_holds_and_time_splits_alike(geometry: SliceGeometry) {
    let added = aurelia(geometry);
    let water = Species {
        bell_coupling: BellCoupling::WaterResponse,
        ..added.clone()
    };
    let most_stretched = |s: &Species| {
        let mut sim = SliceSim::new(s).unwrap();
        let mut most = f32::MIN;
        while sim.cycle() < 4 {
            sim.advance_with(1.0 / 60.0, |sim| {
                if sim.cycle() >= 2 {
                    most = most.max(sim.meridian_strain());
                }
            });
        }
        (most, sim.swim_distance())
    };
    let [(give, _), (held, swum)] = [&added, &water].map(most_stretched);
    println!(
        "cycles 2-4, the subumbrella at most {:+.1}% of its length with the added mass, \
         {:+.1}% with the water's response; {:.3} D swum",
        100.0 * give,
        100.0 * held,
        swum / added.diameter
    );
    assert!(
        give >= held + 0.03,
        "the added mass's give {give}, the response's {held}"
    );
    assert!(held.abs() <= 0.05, "with the water's response: {held}");
    assert!(swum > 0.5 * added.diameter, "swam {swum} m in four strokes");
    let run = |dt: f32, frames: usize| {
        let mut sim = SliceSim::new(&water).unwrap();
        (0..frames).for_each(|_| sim.advance(dt));
        sim
    };
    let (a, b) = (run(1.0 / 32.0, 96), run(1.0 / 64.0, 192));
    assert_eq!(
        state_bits(&a),
        state_bits(&b),
        "1/32 s against 1/64 s frames"
    );
}

in_both_geometries!(fn the_box_follows_the_bell_without_jumps);
fn the_box_follows_the_bell_without_jumps(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    let start = sim.bell_centroid_world();
    let home = sim.bell_points().iter().sum::<Vec2>() / sim.bell_points().len() as f32;
    let mut previous = sim.swim_distance();
    let mut farthest = 0.0f32;
    for _ in 0..(15.0 * sim.species().period() * 60.0) as usize {
        sim.advance(1.0 / 60.0);
        // Whole-cell recentring (2.7 mm here) showed as jumps; a stroke moves a quarter as
        // far in a frame at its fastest.
        let step = (sim.swim_distance() - previous).abs();
        assert!(step < 0.5 * sim.fluid().h, "distance jumped by {step} m");
        previous = sim.swim_distance();
        let c = sim.bell_points().iter().sum::<Vec2>() / sim.bell_points().len() as f32;
        farthest = farthest.max((c - home).length());
    }
    let d = sim.species().diameter;
    assert!(sim.offset().y > 2.0 * d, "the box moved with the bell");
    assert!(
        farthest < 0.5 * d,
        "the bell stays near home in the box: {farthest} m"
    );
    // With the mirror symmetry the axis stays +y, so distance is the world rise.
    let rise = sim.bell_centroid_world().y - start.y;
    assert!((sim.swim_distance() - rise).abs() < 1e-3 * d.max(rise.abs()));
    assert!(sim.frame_velocity().y > 0.0, "the box moves apex-first");
}

in_both_geometries!(fn stays_mirror_symmetric_about_a_cell_centre);
fn stays_mirror_symmetric_about_a_cell_centre(geometry: SliceGeometry) {
    for grid in [60, 61] {
        let species = Species {
            grid_resolution: grid,
            ..aurelia(geometry)
        };
        let mut sim = SliceSim::new(&species).unwrap();
        run_cycles(&mut sim, 1.5);
        let axis = sim.fluid().axis();
        let h = sim.fluid().h;
        assert!(
            ((axis / h).fract() - 0.5).abs() < 1e-4,
            "grid {grid}: axis at {axis}"
        );
        let bell = sim.bell_points();
        for i in 0..bell.len() / 2 {
            let (l, r) = (bell[i], bell[bell.len() - 1 - i]);
            assert!(((l.x + r.x) - 2.0 * axis).abs() < 1e-5 && (l.y - r.y).abs() < 1e-5);
        }
    }
}

/// A planar slice let tilt solves every point and the whole grid; held symmetric, only its
/// half. Over two strokes (too few for round-off to tip it) both swim alike; over four the
/// free one's halves drift apart, as a free planar wake does, while the held one stays its
/// own mirror image; either way the water stays divergence-free where it is solved.
#[test]
fn a_planar_slice_swims_alike_let_tilt_or_held_symmetric() {
    let species = paper(SliceGeometry::Planar);
    let mut held = SliceSim::new(&species).unwrap();
    let mut free = SliceSim::new(&species).unwrap();
    free.set_mirror_symmetry(false);
    // The largest gap between the bell and its mirror image about the apex, m.
    let asymmetry = |sim: &SliceSim| {
        let bell = sim.bell_points();
        let axis = bell[bell.len() / 2].x;
        (0..bell.len() / 2)
            .map(|i| (bell[i].x + bell[bell.len() - 1 - i].x - 2.0 * axis).abs())
            .fold(0.0f32, f32::max)
    };
    for stroke in 1..=4 {
        for sim in [&mut held, &mut free] {
            run_cycles(sim, 1.0);
            let h = sim.fluid().h;
            let relative = h * sim.fluid_divergence_max() / sim.fluid_speed_max().max(1e-9);
            assert!(relative <= 1e-4, "h·max|div u|/max|u| = {relative}");
            assert_eq!(sim.recoveries(), 0);
        }
        if stroke == 2 {
            let (a, b) = (held.swim_distance(), free.swim_distance());
            assert!(a > 0.2 * species.diameter, "held symmetric, swam {a}");
            assert!((a - b).abs() < 0.02 * a, "held {a}, let tilt {b}");
        }
    }
    let d = species.diameter;
    assert!(asymmetry(&held) < 1e-5 * d, "held: {}", asymmetry(&held));
    assert!(
        asymmetry(&free) > 2e-4 * d,
        "let tilt: {}",
        asymmetry(&free)
    );
    // Held symmetric again, it is its own mirror image again.
    free.set_mirror_symmetry(true);
    run_cycles(&mut free, 1.0);
    assert!(
        asymmetry(&free) < 1e-5 * d,
        "held again: {}",
        asymmetry(&free)
    );
    assert_eq!(free.recoveries(), 0);
}

in_both_geometries!(fn a_blow_up_is_detected_and_recovered_where_the_bell_was);
fn a_blow_up_is_detected_and_recovered_where_the_bell_was(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    run_cycles(&mut sim, 2.5);
    let (distance, world) = (sim.swim_distance(), sim.bell_centroid_world());
    sim.poison_for_tests();
    sim.advance(SliceSim::step_length(sim.species()));
    assert_eq!(sim.recoveries(), 1);
    assert!(sim.bell_points().iter().all(|p| p.is_finite()));
    assert!(sim.fluid_speed_max().is_finite());
    assert!((sim.swim_distance() - distance).abs() < 0.01);
    let d = sim.species().diameter;
    assert!(
        (sim.bell_centroid_world() - world).length() < 0.3 * d,
        "kept where it was: {} m away",
        (sim.bell_centroid_world() - world).length()
    );
    run_cycles(&mut sim, 1.0);
    assert!(sim.bell_points().iter().all(|p| p.is_finite()));
}

in_both_geometries!(fn a_crossed_outline_is_crumpled_and_recovered);
fn a_crossed_outline_is_crumpled_and_recovered(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    run_cycles(&mut sim, 1.0);
    assert!(!sim.outline().crumpled());
    sim.fold_for_tests();
    assert!(sim.outline().crossed, "the fold crosses the outline");
    assert!(sim.outline().crumpled());
    sim.advance(SliceSim::step_length(sim.species()));
    assert_eq!(sim.recoveries(), 1, "the health check saw the fold");
    assert!(!sim.outline().crumpled());
}

in_both_geometries!(fn same_input_same_result);
fn same_input_same_result(geometry: SliceGeometry) {
    let mut a = SliceSim::new(&aurelia(geometry)).unwrap();
    let mut b = SliceSim::new(&aurelia(geometry)).unwrap();
    for _ in 0..40 {
        a.advance(1.0 / 60.0);
        b.advance(1.0 / 60.0);
    }
    assert_eq!(state_bits(&a), state_bits(&b));
}

in_both_geometries!(fn no_tentacles_by_count_is_no_tentacles_by_length);
fn no_tentacles_by_count_is_no_tentacles_by_length(geometry: SliceGeometry) {
    // A fringe of no tentacles once hung chains that slipped against no drag and blew up.
    let none = |s: Species| {
        let mut sim = SliceSim::new(&s).unwrap();
        run_cycles(&mut sim, 3.0);
        assert_eq!(sim.recoveries(), 0, "{}", s.tentacle_count);
        state_bits(&sim)
    };
    let by_count = none(Species {
        tentacle_count: 0,
        ..aurelia(geometry)
    });
    let by_length = none(Species {
        tentacle_length: 0.0,
        ..aurelia(geometry)
    });
    assert_eq!(by_count, by_length);
}

in_both_geometries!(fn muscles_contract_the_bell_towards_the_ratio);
fn muscles_contract_the_bell_towards_the_ratio(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    let width = |sim: &SliceSim| {
        let b = sim.bell_points();
        (b[b.len() - 1] - b[0]).length() / sim.species().diameter
    };
    let mut narrowest = f32::MAX;
    for _ in 0..60 {
        sim.advance(sim.species().period() / 30.0);
        narrowest = narrowest.min(width(&sim));
    }
    assert!(
        narrowest < 0.75 && narrowest > 0.3,
        "narrowest aperture {narrowest} of rest"
    );
}

in_both_geometries!(fn tentacles_stay_outside_the_bell);
fn tentacles_stay_outside_the_bell(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    for frame in 0..(4.0 * sim.species().period() * 30.0) as usize {
        sim.advance(1.0 / 30.0);
        let view = sim.view();
        for chain in view.tentacles {
            for p in &chain[1..] {
                assert!(
                    !contains(view.bell, *p),
                    "frame {frame}: tentacle point {p} inside the bell"
                );
            }
        }
    }
}

in_both_geometries!(fn a_fringe_that_outweighs_the_water_at_its_margin_stays_whole);
/// The paper's 200 tentacles on an 11 mm bell beaten at half its rate drag, over a step,
/// several times the water at the margin they hang from. Their pull is a load on the bell,
/// spread over its water by its stiffness; given to the margin's water alone it overshot
/// every step, and the slice was restarted in nearly every stroke (found by random
/// combined edits of every species, `docs/numerics.md`).
fn a_fringe_that_outweighs_the_water_at_its_margin_stays_whole(geometry: SliceGeometry) {
    let small = paper(geometry).resized(0.011);
    let slow = Species {
        contraction_frequency: 0.5 * small.contraction_frequency,
        ..small
    };
    let mut sim = SliceSim::new(&slow).unwrap();
    run_cycles(&mut sim, 6.0);
    assert_eq!(sim.recoveries(), 0, "{}", sized(&slow));
    assert!(sim.swim_distance() > 0.0, "{}", sim.swim_distance());
}

in_both_geometries!(fn species_edits_reach_a_living_slice);
fn species_edits_reach_a_living_slice(geometry: SliceGeometry) {
    let mut sim = SliceSim::new(&aurelia(geometry)).unwrap();
    run_cycles(&mut sim, 0.5);
    let (phase, d) = (sim.phase(), sim.swim_distance());
    let mut faster = aurelia(geometry);
    faster.contraction_frequency = 1.4;
    sim.set_species(&faster).unwrap();
    assert_eq!(sim.species().contraction_frequency, 1.4);
    assert!(
        (sim.phase() - phase).abs() < 0.03,
        "the stroke carries on in phase"
    );
    let world = sim.bell_centroid_world();
    let mut bigger = faster.clone();
    bigger.diameter = 0.05;
    sim.set_species(&bigger).unwrap();
    assert_eq!(sim.swim_distance(), d, "a rebuild keeps the distance");
    assert!(
        (sim.bell_centroid_world() - world).length() < 1e-4,
        "and the place"
    );
    let bad = Species {
        height: -1.0,
        ..bigger
    };
    assert_eq!(sim.set_species(&bad).err().unwrap().field(), Some("height"));
    assert_eq!(
        sim.species().diameter,
        0.05,
        "a refused edit changes nothing"
    );
}

in_both_geometries!(fn an_edit_that_moves_the_points_rebuilds_the_slice);
/// The band's width sets how far apart the bell's points sit, and a fringe added or taken
/// away adds or takes away points: a living slice so edited starts again at rest in its
/// place, as one given a new size does, instead of forcing the old positions onto the new
/// body (a narrower band on a living moon jelly indexed past its points).
fn an_edit_that_moves_the_points_rebuilds_the_slice(geometry: SliceGeometry) {
    let base = aurelia(geometry);
    let bare = Species {
        tentacle_count: 0,
        ..base.clone()
    };
    let edits = [
        (
            base.clone(),
            Species {
                boundary_width: 0.1,
                ..base.clone()
            },
        ),
        (
            base.clone(),
            Species {
                boundary_width: 0.6,
                ..base.clone()
            },
        ),
        (base.clone(), bare.clone()),
        (bare, base.clone()),
    ];
    for (from, to) in edits {
        let mut sim = SliceSim::new(&from).unwrap();
        run_cycles(&mut sim, 0.5);
        let (distance, world) = (sim.swim_distance(), sim.bell_centroid_world());
        sim.set_species(&to).unwrap();
        let fresh = SliceSim::new(&to).unwrap();
        assert_eq!(sim.bell_points().len(), fresh.bell_points().len());
        assert_eq!(
            sim.body().tensions().count(),
            fresh.body().tensions().count()
        );
        assert_eq!(sim.swim_distance(), distance, "the distance is kept");
        assert!(
            (sim.bell_centroid_world() - world).length() < 1e-4,
            "and the place"
        );
        run_cycles(&mut sim, 1.0);
        assert_eq!(sim.recoveries(), 0);
        assert!(sim.bell_points().iter().all(|p| p.is_finite()));
        assert!(!sim.outline().crumpled(), "{:?}", sim.outline());
    }
}

// --- Long checks: run in release with `--ignored --nocapture`; each prints its figures. ---

/// Distance per cycle in diameters for cycles `from..to`, at 60 Hz frames, measured at
/// each cycle's first step (exactly phase 0).
fn per_cycle(species: &Species, from: u64, to: u64) -> Vec<f32> {
    let mut sim = SliceSim::new(species).unwrap();
    let mut out = Vec::new();
    let mut last = 0.0;
    while sim.cycle() < to {
        sim.advance_with(1.0 / 60.0, |sim| {
            if sim.phase() == 0.0 && sim.cycle() <= to {
                if sim.cycle() > from {
                    out.push((sim.swim_distance() - last) / species.diameter);
                }
                last = sim.swim_distance();
            }
        });
    }
    out
}

fn mean_and_cv(v: &[f32]) -> (f32, f32) {
    let mean = v.iter().sum::<f32>() / v.len() as f32;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / v.len() as f32;
    (mean, var.sqrt() / mean.abs())
}

fn spread(v: &[f32]) -> f32 {
    let (max, min) = v
        .iter()
        .fold((f32::MIN, f32::MAX), |(a, b), &x| (a.max(x), b.min(x)));
    (max - min) / (v.iter().sum::<f32>() / v.len() as f32)
}

in_the_planar_slice!(#[ignore = "long: 2 × 40 strokes"] fn the_paper_model_swims_and_staggering_pays);
/// The paper's Fig. 5 finding, on the paper's model.
fn the_paper_model_swims_and_staggering_pays(geometry: SliceGeometry) {
    let (s, s_cv) = mean_and_cv(&per_cycle(&paper(geometry), 20, 40));
    let unison = Species {
        expansion_stagger: 0.0,
        ..paper(geometry)
    };
    let (u, _) = mean_and_cv(&per_cycle(&unison, 20, 40));
    println!(
        "cycles 20-40, diameters per cycle: staggered {s:.3} (cv {:.1}%), unison {u:.3}: \
         staggered {:+.0}%",
        100.0 * s_cv,
        100.0 * (s / u - 1.0)
    );
    assert!(
        (0.3..=0.6).contains(&s),
        "staggered {s} diameters per cycle"
    );
    assert!(s_cv < 0.05, "cycle-to-cycle variation {s_cv}");
    assert!(u > 0.0, "unison still swims forward");
    assert!(s >= 1.2 * u, "staggered {s} vs unison {u}");
}

#[test]
#[ignore = "long: the three animals at their size and half it, staggered and in unison, 40 strokes each"]
/// Issue 28: the paper's finding holds for every shipped animal in the geometry it swims
/// in: a staggered release (the band nearest the margin letting go later) carries it
/// further a stroke than every band letting go in unison, by at least a fifth, as the
/// paper's test asks of its model, and the stagger's share is the animal's, not a no-op
/// (*Sarsia* let every band go over the whole refill until 2026-12-05, and the stagger
/// did nothing: the same bits in unison). So it does shrunk to half its size, beating at
/// that size's rate. Grown, the rowers' share fades (*Aequorea* at twice its size +16%,
/// the moon jelly at three times +17%): their water's inertia outgrows their mesoglea
/// and muscle, whose moduli a resized animal keeps (`docs/physics.md`, "The stagger
/// across sizes").
fn every_animals_staggered_release_pays() {
    let animals: Vec<Species> = common::shipped_species()
        .iter()
        .flat_map(|s| [s.clone(), s.resized(0.5 * s.diameter)])
        .collect();
    let runs = in_parallel(&animals, |s| {
        let unison = Species {
            expansion_stagger: 0.0,
            ..s.clone()
        };
        let staggered = mean_and_cv(&per_cycle(s, 20, 40)).0;
        (staggered, mean_and_cv(&per_cycle(&unison, 20, 40)).0)
    });
    for (s, (staggered, unison)) in animals.iter().zip(runs) {
        println!(
            "{} ({:?}), cycles 20-40: staggered {staggered:.3}, unison {unison:.3} D a \
             stroke: {:+.0}%",
            sized(s),
            s.slice_geometry,
            100.0 * (staggered / unison - 1.0)
        );
        assert!(s.expansion_stagger > 0.0, "{}: staggered", s.name);
        assert!(
            staggered >= 1.2 * unison,
            "{}: staggered {staggered} against unison {unison}",
            s.name
        );
    }
}

in_both_geometries!(#[ignore = "long: every species, 4 grids × 30 strokes"] fn the_stroke_does_not_depend_on_where_the_bell_sits_in_a_cell);
/// Every species calibrated in the geometry, at its size and at half and twice it: grids
/// G..G+3 put the bell at four offsets to the cells, and its stroke may not tell them apart
/// by more than 5%.
fn the_stroke_does_not_depend_on_where_the_bell_sits_in_a_cell(geometry: SliceGeometry) {
    for base in calibrated_at_three_sizes(geometry) {
        let runs: Vec<f32> = (0..4)
            .map(|k| {
                let s = Species {
                    grid_resolution: base.grid_resolution + k,
                    ..base.clone()
                };
                mean_and_cv(&per_cycle(&s, 10, 30)).0
            })
            .collect();
        let name = sized(&base);
        println!(
            "{name}: grids G..G+3, diameters per cycle (cycles 10-30): {runs:?}, spread {:.1}%",
            100.0 * spread(&runs)
        );
        assert!(spread(&runs) <= 0.05, "{name}: {runs:?}");
    }
}

in_both_geometries!(#[ignore = "long: every species at three sizes, grids G and 1.5·G, 30 strokes"] fn the_stroke_converges_with_the_grid);
/// Every species calibrated in the geometry, at its size and at half and twice it: its
/// stroke on a grid half as fine again is within 15%.
fn the_stroke_converges_with_the_grid(geometry: SliceGeometry) {
    for base in calibrated_at_three_sizes(geometry) {
        let at = |grid: u32| {
            let s = Species {
                grid_resolution: grid,
                ..base.clone()
            };
            mean_and_cv(&per_cycle(&s, 10, 30)).0
        };
        let (coarse, fine) = (at(base.grid_resolution), at(base.grid_resolution * 3 / 2));
        let name = sized(&base);
        println!(
            "{name}: grid G: {coarse:.3}, 1.5·G: {fine:.3} diameters per cycle ({:+.1}%)",
            100.0 * (fine / coarse - 1.0)
        );
        assert!(
            (fine / coarse - 1.0).abs() <= 0.15,
            "{name}: {coarse} vs {fine}"
        );
    }
}

in_both_geometries!(#[ignore = "long: every species in its own box and one 1.4 times as wide, 30 strokes"] fn the_wake_does_not_feel_the_box_walls);
/// Every species calibrated in the geometry: its box grown 1.4 times as wide, the cells
/// grown with it (the same cells a diameter), changes its stroke by under 5%. A box whose
/// open walls its wake still reached (too few `domain_diameters`, or walls that reflect
/// it) would read the walls, not the water. (Forced planar, the animals' strokes grow with
/// the box for tens of strokes; `docs/numerics.md`, "The forced-planar animals against
/// their box".)
fn the_wake_does_not_feel_the_box_walls(geometry: SliceGeometry) {
    for base in calibrated_in(geometry) {
        let grid = (base.grid_resolution as f32 * 1.4).round() as u32;
        let wider = Species {
            grid_resolution: grid,
            domain_diameters: base.domain_diameters * grid as f32 / base.grid_resolution as f32,
            ..base.clone()
        };
        let (own, (wide, cv)) = (
            mean_and_cv(&per_cycle(&base, 10, 30)).0,
            mean_and_cv(&per_cycle(&wider, 10, 30)),
        );
        let name = sized(&base);
        println!(
            "{name}: box {:.1} D: {own:.3}, {:.1} D: {wide:.3} ± {:.0}% diameters per cycle ({:+.1}%)",
            base.domain_diameters,
            wider.domain_diameters,
            100.0 * cv,
            100.0 * (wide / own - 1.0)
        );
        assert!((wide / own - 1.0).abs() <= 0.05, "{name}: {own} vs {wide}");
    }
}

in_both_geometries!(#[ignore = "long: every species at its own step, 16 and 64 times finer, 12 strokes"] fn the_bell_keeps_its_length_as_the_step_shrinks);
/// The mesoglea hardly stretches under a stroke's loads (a percent or two: the moon
/// jelly's 3 mm wall, pulled in by a band on its margin, about 2%), so as the step shrinks
/// the subumbrella must keep its length: the coupled step's give (the water carries the
/// points a step before their springs' force reaches it) falls with the step. At the
/// species' own step it is a known error, bounded here so that it cannot grow unseen
/// (`docs/numerics.md`, "Time step").
fn the_bell_keeps_its_length_as_the_step_shrinks(geometry: SliceGeometry) {
    // The subumbrella's greatest strain over strokes 8-12 with `finer` times the steps.
    let stretched = |s: &Species, finer: u32| {
        let mut sim = SliceSim::new(s).unwrap();
        if finer > 1 {
            let steps = SliceSim::steps_per_cycle(s) * finer;
            sim.set_clock(FixedClock::new(s.period(), steps));
        }
        let mut most = f32::MIN;
        while sim.cycle() < 12 {
            sim.advance_with(1.0 / 60.0, |sim| {
                if sim.cycle() >= 8 {
                    most = most.max(sim.meridian_strain());
                }
            });
        }
        most
    };
    for base in calibrated_in(geometry) {
        let (own, fine, finer) = (
            stretched(&base, 1),
            stretched(&base, 16),
            stretched(&base, 64),
        );
        println!(
            "{}: the subumbrella at most {:+.1}% of its length with the species' step, \
             {:+.1}% with 16 times the steps, {:+.1}% with 64",
            base.name,
            100.0 * own,
            100.0 * fine,
            100.0 * finer
        );
        assert!(
            finer <= 0.03,
            "{}: {finer} with 64 times the steps",
            base.name
        );
        assert!(own <= 0.2, "{}: {own} with its own step", base.name);
        assert!(fine < own / 3.0, "{}: {own} then {fine}", base.name);
        // With the water's response in the solve most of the give is gone at the own
        // step: at most half of the added mass's is left, and the wall within 6%.
        let water = Species {
            bell_coupling: BellCoupling::WaterResponse,
            ..base.clone()
        };
        let (held_own, held_fine) = (stretched(&water, 1), stretched(&water, 16));
        println!(
            "{}, with the water's response: at most {:+.1}% with its own step, {:+.1}% with \
             16 times the steps",
            base.name,
            100.0 * held_own,
            100.0 * held_fine
        );
        let (give, left) = (own - fine, held_own - held_fine);
        assert!(
            held_own <= 0.06,
            "{}: {held_own} with its own step",
            base.name
        );
        assert!(
            left.abs() <= 0.05 && left <= 0.5 * give,
            "{}: {held_own} with its own step, {held_fine} with 16 times the steps; the \
             added mass's give {give}",
            base.name
        );
    }
}

#[test]
#[ignore = "long: the two rowers at 1, 3/4 and 1/2 of their steps, each coupling, 20 strokes"]
/// The coupled step's give, not the water, is what holds a rower to its steps: with the
/// added mass half the steps lose a fifth of the stroke and more, while with the water's
/// response in the solve the stroke holds within a few percent at three quarters and at
/// half of them (the water's Courant number stays under a cell a step). A response that
/// lost part of itself fails it: without the relaxation's taps the moon jelly swims 0.016
/// D a stroke (`docs/numerics.md`, "Fewer steps with the water's response").
fn on_the_waters_response_a_rower_keeps_its_stroke_with_fewer_steps() {
    let stroke = |(s, multiple): &(Species, f32)| {
        let mut sim = SliceSim::new(s).unwrap();
        let steps = (SliceSim::steps_per_cycle(s) as f32 * multiple).round() as u32;
        sim.set_clock(FixedClock::new(s.period(), steps));
        let mut at_phase_0 = Vec::new();
        while sim.cycle() < 20 {
            sim.advance_with(1.0 / 60.0, |sim| {
                if sim.phase() == 0.0 && sim.cycle() >= 10 {
                    at_phase_0.push(sim.swim_distance());
                }
            });
        }
        let swum = at_phase_0.last().unwrap() - at_phase_0.first().unwrap();
        swum / ((at_phase_0.len() - 1) as f32 * s.diameter)
    };
    for added in [Species::aurelia(), Species::aequorea()] {
        let water = Species {
            bell_coupling: BellCoupling::WaterResponse,
            ..added.clone()
        };
        let runs = [
            (added.clone(), 1.0),
            (added.clone(), 0.5),
            (water.clone(), 1.0),
            (water.clone(), 0.75),
            (water, 0.5),
        ];
        let [own, half, held, three_quarters, held_half] = in_parallel(&runs, stroke)[..] else {
            unreachable!()
        };
        println!(
            "{}: the added mass {own:.3} D a stroke with its steps, {half:.3} with half; the \
             water's response {held:.3}, {three_quarters:.3} with three quarters, \
             {held_half:.3} with half",
            added.name
        );
        assert!(
            half < 0.85 * own,
            "{}: the added mass {own} then {half}",
            added.name
        );
        assert!(
            (three_quarters / held - 1.0).abs() <= 0.04,
            "{}: the response {held} then {three_quarters}",
            added.name
        );
        assert!(
            (held_half / held - 1.0).abs() <= 0.08,
            "{}: the response {held} then {held_half}",
            added.name
        );
    }
}

in_both_geometries!(#[ignore = "long: 20 strokes at Re 1 and at sea water's"] fn a_stroke_hardly_swims_where_viscosity_rules);
fn a_stroke_hardly_swims_where_viscosity_rules(geometry: SliceGeometry) {
    let base = aurelia(geometry);
    // Re = ρ·f·D²/μ (IB2d's definition, `docs/physics.md`): about 880 for the default in sea water.
    let viscosity = base.density * base.contraction_frequency * base.diameter * base.diameter;
    let syrup = Species {
        viscosity,
        ..base.clone()
    };
    let (slow, _) = mean_and_cv(&per_cycle(&syrup, 5, 20));
    let (fast, _) = mean_and_cv(&per_cycle(&base, 5, 20));
    println!("Re 1: {slow:.4} diameters per cycle; sea water: {fast:.3}");
    assert!(
        slow.abs() < 0.1 * fast,
        "Re 1 swam {slow}, sea water {fast}"
    );
}

in_both_geometries!(#[ignore = "long: every species at three sizes with no, its own and a 3× longer fringe, 40 strokes"] fn tentacles_slow_the_bell_down);
/// Tentacles add drag and slow the bell, the longer the more (Miles & Battista 2019): each
/// species' own fringe costs it 5–30% at its own size, and a fringe three times as long at
/// least 5% more than its own. Each species at half and twice its size too, where a fringe
/// weighs more on the smaller bell and less on the bigger (its drag against the bell's
/// inertia goes as 1/Re): there, in r–z, within 30% either way, for a short dense fringe
/// can row as a skirt (the moon jelly's 5 mm one did: 1% faster than bare on the paper's
/// bell, `docs/physics.md` section 5) and on a bell twice as big a fringe costs a few
/// percent (*Aequorea*'s and *Sarsia*'s 3–4%).
fn tentacles_slow_the_bell_down(geometry: SliceGeometry) {
    for base in calibrated_in(geometry) {
        for (i, s) in three_sizes(&base).iter().enumerate() {
            fringe_slows_the_bell(geometry, s, i == 1);
        }
    }
}

/// [`tentacles_slow_the_bell_down`] for one species at one size.
fn fringe_slows_the_bell(geometry: SliceGeometry, s: &Species, at_own_size: bool) {
    let speed = |length: f32| {
        let fringe = Species {
            tentacle_length: length,
            ..s.clone()
        };
        mean_and_cv(&per_cycle(&fringe, 20, 40)).0
    };
    let (with, without) = (speed(s.tentacle_length), speed(0.0));
    let slower = 1.0 - with / without;
    let longer = 1.0 - speed(3.0 * s.tentacle_length) / without;
    let name = sized(s);
    println!(
        "{name}: {with:.3} diameters per cycle with tentacles, {without:.3} without: {:.1}% \
         slower; with a fringe 3× as long, {:.1}% slower",
        100.0 * slower,
        100.0 * longer
    );
    let own = match geometry {
        SliceGeometry::Axisymmetric if !at_own_size => -0.30..=0.30,
        _ => 0.05..=0.30,
    };
    assert!(own.contains(&slower), "{name}: {slower}");
    assert!(longer >= slower + 0.05, "{name}: {longer} against {slower}");
}

#[test]
#[ignore = "long: every shipped species with and without its fringe under three advection schemes, 20 strokes"]
/// A fringe's share of the stroke is the water's drag on its tentacles, not the grid's:
/// whichever scheme carries the water, each shipped species with its fringe swims the
/// same fraction of its bare stroke (within 0.1), though the bare stroke itself moves by a
/// fifth between schemes at these grids. A fringe that dragged along its length as a wall
/// (`FringeDrag::Curtain`) kept 0.82 of *Aequorea*'s stroke with semi-Lagrangian
/// advection and 0.29 with Cubic.
fn a_fringes_share_of_the_stroke_does_not_depend_on_the_advection_scheme() {
    use bevy_jellyfish::species::Advection;
    for s in common::shipped_species() {
        let shares: Vec<f32> = Advection::ALL
            .iter()
            .map(|&advection| {
                let with = Species {
                    advection,
                    ..s.clone()
                };
                let bare = Species {
                    tentacle_count: 0,
                    ..with.clone()
                };
                let (w, b) = (
                    mean_and_cv(&per_cycle(&with, 15, 20)).0,
                    mean_and_cv(&per_cycle(&bare, 15, 20)).0,
                );
                println!(
                    "{} {advection:?}: {w:.3} diameters per cycle with its fringe, {b:.3} bare: {:.3}",
                    s.name,
                    w / b
                );
                w / b
            })
            .collect();
        let (max, min) = shares
            .iter()
            .fold((f32::MIN, f32::MAX), |(a, b), &x| (a.max(x), b.min(x)));
        assert!(max - min < 0.1, "{}: {shares:?}", s.name);
    }
}

/// The stroke whose phase-0 area later strokes are held to: after the start-up. A planar
/// wake takes about fifty strokes to settle (*Aequorea* forced into the plane swims 0.12 D
/// a stroke at the fifth, 0.20 at the fiftieth), and a bell's phase-0 area, taken on the
/// refill's steepest slope, follows it (0.07 of rest per 2.6% of the cycle); what is held
/// is creep over the strokes after it.
const SETTLED_STROKE: u64 = 100;

/// Whole bells over `cycles` strokes at `hz` frames: crumpled samples (every third
/// frame), the largest change of the area at phase 0 (the step that starts a cycle) from
/// that of [`SETTLED_STROKE`], recoveries, and the distance swum, diameters a stroke.
fn whole_bell(species: &Species, cycles: u64, hz: f32) -> (u64, u64, f32, u32, f32) {
    let mut sim = SliceSim::new(species).unwrap();
    let (mut samples, mut crumpled, mut drift) = (0u64, 0u64, 0.0f32);
    let mut reference = None;
    let mut frame = 0u64;
    while sim.cycle() < cycles {
        sim.advance_with(1.0 / hz, |sim| {
            if sim.phase() == 0.0 {
                let area = sim.outline().area_ratio;
                if sim.cycle() == SETTLED_STROKE {
                    reference = Some(area);
                }
                if let Some(r) = reference {
                    drift = drift.max((area / r - 1.0).abs());
                }
            }
        });
        frame += 1;
        if frame.is_multiple_of(3) {
            let outline: Outline = sim.outline();
            samples += 1;
            crumpled += outline.crumpled() as u64;
        }
    }
    let swum = sim.swim_distance() / species.diameter / cycles as f32;
    (crumpled, samples, drift, sim.recoveries(), swum)
}

in_both_geometries!(#[ignore = "long: 1000 strokes of every species at three frame rates, 2000 of the default"] fn bells_stay_whole_for_a_thousand_strokes);
fn bells_stay_whole_for_a_thousand_strokes(geometry: SliceGeometry) {
    let mut runs: Vec<(Species, u64)> = shipped(geometry).into_iter().map(|s| (s, 1000)).collect();
    runs.push((aurelia(geometry), 2000));
    for (species, cycles) in runs {
        for hz in [30.0, 60.0, 144.0] {
            let (crumpled, samples, drift, recoveries, _) = whole_bell(&species, cycles, hz);
            println!(
                "{} {cycles} strokes at {hz} Hz: {crumpled} of {samples} samples crumpled, \
                 phase-0 area within {:.1}% of stroke {SETTLED_STROKE}'s, {recoveries} recoveries",
                species.name,
                100.0 * drift
            );
            assert_eq!(crumpled, 0, "{}", species.name);
            assert!(drift <= 0.05, "{}: area drifted {drift}", species.name);
            assert_eq!(recoveries, 0, "{}", species.name);
        }
    }
}

in_both_geometries!(#[ignore = "long: every species at 1.5, 2 and 2.25 times its grid, 20 strokes"] fn bells_stay_whole_on_finer_grids);
/// A finer grid under the same kernel refines the water, not the body: before the body kept
/// its points, the moon jelly's outline crossed itself at 2·G (planar) and 2.25·G (r–z).
fn bells_stay_whole_on_finer_grids(geometry: SliceGeometry) {
    for base in shipped(geometry) {
        for scale in [1.5, 2.0, 2.25] {
            let species = Species {
                grid_resolution: (base.grid_resolution as f32 * scale).round() as u32,
                ..base.clone()
            };
            let (crumpled, samples, _, recoveries, _) = whole_bell(&species, 20, 60.0);
            println!(
                "{} at grid {}: {crumpled} of {samples} samples crumpled, {recoveries} recoveries",
                species.name, species.grid_resolution
            );
            assert_eq!(
                (crumpled, recoveries),
                (0, 0),
                "{} at grid {}",
                species.name,
                species.grid_resolution
            );
        }
    }
}

in_both_geometries!(#[ignore = "long: every species in eleven variants, 200 strokes each"] fn bells_stay_whole_in_every_variant);
/// Not only the shipped bells: each species grown and shrunk (a quarter to four times its
/// diameter, its pulse rate the size's), bare and with a fringe three times as long, beaten
/// at half and twice its rate, its mesoglea half and twice as stiff, on a grid a quarter
/// coarser, stays whole for 200 strokes without a recovery and its area at phase 0 within
/// 5% of stroke 100's, in either geometry. In the geometry it is calibrated in, each also
/// swims apex first. Forced into the other it need not: the paper's tall dome in r–z is
/// pumped backwards by its fringe in some of them, and *Sarsia*'s under-resolved planar
/// jet by half its stiffness (`docs/numerics.md`).
fn bells_stay_whole_in_every_variant(geometry: SliceGeometry) {
    let own: Vec<String> = calibrated_in(geometry)
        .into_iter()
        .map(|s| s.name)
        .collect();
    let mut bases = shipped(geometry);
    bases.push(paper(geometry));
    let runs: Vec<(String, Species, bool)> = bases
        .iter()
        .flat_map(|base| {
            let calibrated = own.contains(&base.name);
            variants(base)
                .into_iter()
                .map(move |(name, s)| (name, s, calibrated))
        })
        .collect();
    let results: Vec<_> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..2)
            .map(|w| {
                let runs = &runs;
                scope.spawn(move || {
                    runs.iter()
                        .skip(w)
                        .step_by(2)
                        .map(|(name, s, own)| (name.clone(), *own, whole_bell(s, 200, 60.0)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap())
            .collect()
    });
    assert_eq!(results.len(), 4 * 11);
    let mut failed = Vec::new();
    for (name, own, (crumpled, samples, drift, recoveries, swum)) in results {
        println!(
            "{name}{}: {crumpled} of {samples} samples crumpled, phase-0 area within {:.1}% \
             of stroke {SETTLED_STROKE}'s, {recoveries} recoveries, {swum:.3} diameters a \
             stroke",
            if own { "" } else { " (forced)" },
            100.0 * drift
        );
        let whole = (crumpled, recoveries) == (0, 0) && drift <= 0.05;
        // NaN swims nowhere.
        let forward = swum > 0.0;
        if !whole || (own && !forward) {
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "{failed:?}");
}

/// Eleven variants of `base`, each named.
fn variants(base: &Species) -> Vec<(String, Species)> {
    let named = |what: &str, s: Species| (format!("{} {what}", base.name), s);
    let edited = |what: &str, edit: fn(&mut Species)| {
        let mut s = base.clone();
        edit(&mut s);
        named(what, s)
    };
    let mut out: Vec<_> = [0.25f32, 0.5, 2.0, 4.0]
        .into_iter()
        .map(|k| {
            named(
                &format!("at {k}× its size"),
                base.resized(k * base.diameter),
            )
        })
        .collect();
    out.extend([
        edited("bare", |s| s.tentacle_count = 0),
        edited("with a fringe 3× as long", |s| s.tentacle_length *= 3.0),
        edited("at half its rate", |s| s.contraction_frequency *= 0.5),
        edited("at twice its rate", |s| s.contraction_frequency *= 2.0),
        edited("half as stiff", |s| s.elastic_modulus *= 0.5),
        edited("twice as stiff", |s| s.elastic_modulus *= 2.0),
        edited("on a grid a quarter coarser", |s| {
            s.grid_resolution = s.grid_resolution * 3 / 4
        }),
    ]);
    out
}

#[test]
#[ignore = "long: 100 compound edits of every shipped species and of the paper's in both geometries, 40 strokes each"]
/// Edits compound: a species edited in four of its physics fields at once (each scaled
/// between half and twice, the enumerations switched, half of them also grown or shrunk a
/// quarter to four times), as a user tuning one in the editor makes it, stays whole for 40
/// strokes and is not restarted: every shipped animal in the geometry it is calibrated in
/// and the paper's model in both, 100 edits each. Edits stacked at their edges can still
/// fold a bell, so the restarted are counted and printed: at most one in a hundred. Before
/// a fringe's pull was shared with the bell, 8 of these 495 were restarted, 7 of them the
/// paper's model at a quarter to 0.6 of its size (`docs/numerics.md`, "A fringe heavier
/// than its margin's water"); since, one: *Aequorea* at 77 mm pulled to 0.42 of its width,
/// under the bilinear kernel, MacCormack's advection and a lossless mesoglea, crumples.
/// Forced into the plane, large thin saucers fold too: not asked here.
fn compound_edits_stay_whole() {
    let mut bases = calibrated_in(SliceGeometry::Axisymmetric);
    bases.push(paper(SliceGeometry::Planar));
    bases.push(paper(SliceGeometry::Axisymmetric));
    let mut rng = 0x9e37_79b9_7f4a_7c15_u64;
    let mut unit = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut runs = Vec::new();
    for base in &bases {
        for _ in 0..100 {
            let mut s = base.clone();
            let mut what = format!("{} {:?}", s.name, s.slice_geometry);
            if unit() < 0.5 {
                let k = 0.25 * 16f32.powf(unit());
                s = s.resized(k * s.diameter);
                what += &format!(" at {k:.2}× its size");
            }
            for _ in 0..4 {
                let (k, u) = (0.5 * 4f32.powf(unit()), unit());
                what += &compound_edit(&mut s, (unit() * 16.0) as usize, k, u);
            }
            runs.push((what, s));
        }
    }
    let valid: Vec<&(String, Species)> =
        runs.iter().filter(|(_, s)| s.validate().is_ok()).collect();
    let results = in_parallel(&valid, |(_, s)| whole_bell(s, 40, 60.0));
    let mut failed = Vec::new();
    for ((what, _), (crumpled, samples, _, recoveries, swum)) in valid.iter().zip(results) {
        println!(
            "{what}: {crumpled} of {samples} samples crumpled, {recoveries} recoveries, \
             {swum:.3} diameters a stroke"
        );
        if crumpled > 0 || recoveries > 0 || !swum.is_finite() {
            failed.push(what.clone());
        }
    }
    println!(
        "{} of {} compound edits valid, {} of them restarted or crumpled",
        valid.len(),
        runs.len(),
        failed.len()
    );
    assert!(valid.len() * 10 >= runs.len() * 9, "{} valid", valid.len());
    assert!(failed.len() * 100 <= valid.len(), "{failed:?}");
}

/// Applies edit number `which` (of 16) to `s`: a field scaled by `k` (within its limits),
/// or an enumeration chosen by `u` in [0, 1); names it.
fn compound_edit(s: &mut Species, which: usize, k: f32, u: f32) -> String {
    use bevy_jellyfish::species::{Advection, Bending, Kernel};
    let scaled = |v: f32, lo: f32, hi: f32| (v * k).clamp(lo, hi);
    let name = match which {
        0 => {
            s.elastic_modulus *= k;
            "elastic_modulus"
        }
        1 => {
            s.contraction_frequency *= k;
            "contraction_frequency"
        }
        2 => {
            s.tentacle_length *= k;
            "tentacle_length"
        }
        3 => {
            s.contraction_ratio = (s.contraction_ratio * k.sqrt()).clamp(0.3, 1.0);
            "contraction_ratio"
        }
        4 => {
            s.contraction_duty = scaled(s.contraction_duty, 0.1, 0.9);
            "contraction_duty"
        }
        5 => {
            s.relaxation_span = scaled(s.relaxation_span, 0.1, 1.0);
            "relaxation_span"
        }
        6 => {
            s.expansion_stagger = u;
            "expansion_stagger"
        }
        7 => {
            s.muscle_extent = scaled(s.muscle_extent, 0.1, 1.0);
            "muscle_extent"
        }
        8 => {
            s.grid_resolution = ((s.grid_resolution as f32 * k.sqrt()) as u32).clamp(24, 192);
            "grid_resolution"
        }
        9 => {
            s.tentacle_count = ((s.tentacle_count as f32 * k * k) as u32).min(256);
            "tentacle_count"
        }
        10 => {
            s.tentacle_radius *= k;
            "tentacle_radius"
        }
        11 => {
            s.thickness *= k.sqrt();
            "thickness"
        }
        12 => {
            s.muscle_law = either(u, MuscleLaw::Force, MuscleLaw::Length);
            "muscle_law"
        }
        13 => {
            s.muscle_timing = either(u, MuscleTiming::Twitch, MuscleTiming::Cycle);
            "muscle_timing"
        }
        14 => {
            s.advection = Advection::ALL[(u * Advection::ALL.len() as f32) as usize];
            s.kernel = Kernel::ALL[(u * 7.0) as usize % Kernel::ALL.len()];
            "advection and kernel"
        }
        _ => {
            s.bending = either(u, Bending::Mesoglea, Bending::Springs);
            s.mesoglea_resilience = scaled(s.mesoglea_resilience, 0.05, 1.0);
            "bending and resilience"
        }
    };
    format!(", {name} (×{k:.2}, {u:.2})")
}

/// `a` for `u` below a half, else `b`.
fn either<T>(u: f32, a: T, b: T) -> T {
    if u < 0.5 { a } else { b }
}

/// Where `distances` (one per frequency, evenly spaced) peak, and the longest of them. The
/// peak is the vertex of the parabola through the longest and its two neighbours, not the
/// longest's own frequency: a sweep's top is flat within a percent over a step of its
/// frequencies, so which sample is longest says little about where the peak moved (the
/// moon jelly's 80 mm bell twice as stiff swims 2.074 and 2.066 D at 0.57 and 0.65 Hz).
fn peak(frequencies: &[f32], distances: &[f32]) -> (f32, f32) {
    let (i, best) = distances
        .iter()
        .enumerate()
        .fold((0, f32::MIN), |m, (i, &x)| if x > m.1 { (i, x) } else { m });
    if i == 0 || i + 1 == distances.len() {
        return (frequencies[i], best);
    }
    let (below, above) = (distances[i - 1], distances[i + 1]);
    let curvature = below - 2.0 * best + above;
    if curvature >= 0.0 {
        return (frequencies[i], best);
    }
    let offset = 0.5 * (below - above) / curvature;
    let step = frequencies[i + 1] - frequencies[i];
    (frequencies[i] + offset * step, best)
}

/// Distance in 20 s, diameters, at each of `frequencies` (the paper's Fig. 5 measure).
fn sweep(base: &Species, frequencies: &[f32]) -> Vec<f32> {
    in_parallel(frequencies, |&f| {
        let species = Species {
            contraction_frequency: f,
            ..base.clone()
        };
        let mut sim = SliceSim::new(&species).unwrap();
        while sim.time() < 20.0 {
            sim.advance(0.1);
        }
        sim.swim_distance() / species.diameter
    })
}

in_both_geometries!(#[ignore = "long: 2 × 15 runs of 20 s"] fn the_sweep_peaks_at_the_bells_resonance);
/// The paper's Fig. 5 finding, on the paper's model.
fn the_sweep_peaks_at_the_bells_resonance(geometry: SliceGeometry) {
    let frequencies: Vec<f32> = (2..=16).map(|k| k as f32 / 10.0).collect();
    let peak = |d: &[f32]| peak(&frequencies, d);
    let base = paper(geometry);
    let d = sweep(&base, &frequencies);
    let (f, best) = peak(&d);
    let (low, high) = (d[0], d[d.len() - 1]);
    println!(
        "the paper's model: peak {f:.2} Hz, {best:.2} D in 20 s; ends {low:.2} and {high:.2} D: {d:.2?}"
    );
    assert!((0.4..=1.2).contains(&f), "peak at {f} Hz");
    assert!(best >= 1.15 * low && best >= 1.15 * high);
    // The peak comes from the bell: a stiffer bell resonates, and swims best, higher.
    let stiffer = Species {
        elastic_modulus: 2.0 * base.elastic_modulus,
        ..base
    };
    let (f_stiff, _) = peak(&sweep(&stiffer, &frequencies));
    println!("bell twice as stiff: peak {f_stiff:.2} Hz");
    assert!(
        f_stiff > f,
        "stiffer peaks at {f_stiff} Hz, the paper's model at {f} Hz"
    );
}

#[test]
#[ignore = "long: 12 × 15 runs of 20 s"]
/// Issue 28: each animal swims fastest near the rate it pulses at, in the geometry it is
/// calibrated in, at its size and at half and twice it (where it pulses at the size's own
/// rate). Its muscle's twitch keeps its seconds at any rate and its mesoglea its
/// viscosity, so beaten much faster the bell no longer refills; a stiffer bell that its
/// own recoil refills (the rowers' force generators) refills sooner and peaks higher, as
/// the paper's resonance does, and *Sarsia*'s commanded length peaks a little higher.
fn every_animal_swims_fastest_near_its_own_pulse_rate() {
    let animals: Vec<Species> = calibrated_at_three_sizes(SliceGeometry::Axisymmetric)
        .into_iter()
        .filter(|s| s.muscle_timing == MuscleTiming::Twitch)
        .collect();
    assert_eq!(
        animals.len(),
        3 * 3,
        "the three shipped animals, at three sizes each, beat with a twitch"
    );
    for base in animals {
        let name = sized(&base);
        // From a sixth of its own rate to two and a half times it.
        let natural = base.natural_pulse_rate();
        let frequencies: Vec<f32> = (1..=15).map(|k| natural * k as f32 / 6.0).collect();
        let d = sweep(&base, &frequencies);
        let (f, best) = peak(&frequencies, &d);
        let (low, high) = (d[0], d[d.len() - 1]);
        println!(
            "{name}: own rate {natural:.2} Hz, peak {f:.2} Hz, {best:.2} D in 20 s; ends {low:.2} and {high:.2} D"
        );
        assert!(
            (0.75 * natural..=1.5 * natural).contains(&f),
            "{name}: peak at {f} Hz, its animal pulses at {natural} Hz"
        );
        assert!(best >= 1.15 * low && best >= 1.15 * high, "{name}: {d:?}");
        // Where the bell's own recoil refills it (a force generator), a stiffer bell
        // refills sooner and peaks higher. *Sarsia*'s commanded length lets go in its
        // twitch's seconds whatever its stiffness, and its peak moves only 2–3% (the
        // stiffer wall yields less to the muscle; `docs/physics.md`, section 5, "The
        // stagger, and the stiffness"), but it must not move down.
        let stiffer = Species {
            elastic_modulus: 2.0 * base.elastic_modulus,
            ..base.clone()
        };
        let (f_stiff, _) = peak(&frequencies, &sweep(&stiffer, &frequencies));
        println!(
            "{name} ({:?}), its bell twice as stiff: peak {f_stiff:.2} Hz",
            base.muscle_law
        );
        assert!(
            f_stiff > f,
            "{name}: stiffer peaks at {f_stiff} Hz, the animal at {f} Hz"
        );
    }
}

/// Cycles 12 to 20 from rest at 60 Hz frames: the mean distance a cycle in diameters, and
/// the slowest speed while the bell refills (after its contraction) in diameters a second
/// (negative: drawn back), and the times the slice was restarted.
fn stroke_and_refill(species: &Species) -> (f32, f32, u32) {
    let (from, to) = (12, 20);
    let mut sim = SliceSim::new(species).unwrap();
    let d = species.diameter;
    let share = species.contraction_share();
    let (mut start, mut end, mut slowest) = (0.0f32, 0.0f32, f32::MAX);
    let (mut time, mut distance) = (0.0f32, 0.0f32);
    while sim.cycle() < to {
        sim.advance_with(1.0 / 60.0, |sim| {
            let (x, t) = (sim.swim_distance() / d, sim.time());
            let cycle = sim.cycle();
            if sim.phase() == 0.0 && cycle == from {
                start = x;
            }
            if sim.phase() == 0.0 && cycle == to {
                end = x;
            }
            if (from..to).contains(&cycle) && sim.phase() > share {
                slowest = slowest.min((x - distance) / (t - time));
            }
            (time, distance) = (t, x);
        });
    }
    (
        (end - start) / (to - from) as f32,
        slowest,
        sim.recoveries(),
    )
}

#[test]
/// The moon jelly as the headless API draws it (`bell_points`, its subumbrella): a saucer
/// whose cavity is a quarter to three tenths as deep as it is wide at rest, contracting
/// to about a half-dome with its margin at 0.6–0.8 of its rest width (*Aurelia*:
/// 0.25–0.3, about 0.5, 0.64–0.76; `docs/physics.md` section 5); and as a video sees it,
/// its outline (the exumbrella the shape layer draws around that subumbrella) narrowing to
/// 0.64–0.8 of its own width at rest (Bajcar et al. 2009: 0.64; Dabiri's animal: 0.757).
/// The moon jelly before 2026-12-04 fails it: a cavity 0.14 deep drawn 0.76 deep, its
/// margin at 0.57.
fn the_moon_jelly_contracts_from_a_saucer_to_about_a_half_dome() {
    let s = Species::aurelia();
    let mut sim = SliceSim::new(&s).unwrap();
    let mut profile = Profile::default();
    let mut widest = |sim: &SliceSim| {
        let b = sim.bell_points();
        profile.build(b, b, sim.species(), b.len() / 2);
        profile.widest()
    };
    let shape = |sim: &SliceSim| cavity(sim.bell_points());
    let (rest, rest_margin) = shape(&sim);
    let rest_outline = widest(&sim);
    let (mut deepest, mut narrowest, mut outline) = (0.0f32, f32::MAX, f32::MAX);
    while sim.cycle() < 12 {
        sim.advance_with(1.0 / 60.0, |sim| {
            if sim.cycle() >= 8 {
                let (cavity, margin) = shape(sim);
                deepest = deepest.max(cavity);
                narrowest = narrowest.min(margin / rest_margin);
                outline = outline.min(widest(sim) / rest_outline);
            }
        });
    }
    println!(
        "cavity {rest:.3} at rest, {deepest:.3} contracted; margin {narrowest:.3}; \
         outline {outline:.3} of its {:.3} D at rest",
        rest_outline / s.diameter
    );
    assert!((0.25..=0.3).contains(&rest), "at rest {rest}");
    assert!((0.45..=0.7).contains(&deepest), "contracted {deepest}");
    assert!((0.6..=0.8).contains(&narrowest), "margin {narrowest}");
    assert!((0.64..=0.8).contains(&outline), "outline {outline}");
    assert_eq!(sim.recoveries(), 0);
}

#[test]
#[ignore = "long: the moon jelly at 40 and 155 mm, 12 strokes each"]
/// Issue 28: the moon jelly refills as Dabiri's *Aurelia* does, its margin back to its
/// width when the next stroke begins (at least 0.95 of it; the record: 0.99 at phase 0.97)
/// and past three quarters of it at phase 0.8 (the record 0.88), at its own size and
/// scaled to the recorded animal's (1.01 and 0.79 at 40 mm, 0.97 and 0.79 at 155 mm). With
/// the paper's staggered release it reached 0.92 and 0.74 (`docs/physics.md` section 5).
fn the_moon_jelly_refills_by_the_next_stroke_as_its_record_does() {
    let animal = Species::aurelia();
    for s in [animal.clone(), animal.resized(0.155)] {
        let mut sim = SliceSim::new(&s).unwrap();
        let rest = cavity(sim.bell_points()).1;
        // The margin's width over its rest width over strokes 8 to 11: the least at phase
        // 0.8, and the least of each stroke's widest in its last twentieth (as the next
        // stroke begins).
        let (mut at_08, mut at_end) = (f32::MAX, f32::MAX);
        let (mut end_of_stroke, mut ends) = (0.0f32, 0);
        while sim.cycle() < 12 {
            sim.advance_with(1.0 / 60.0, |sim| {
                let phase = sim.phase();
                if sim.cycle() < 8 {
                    return;
                }
                let margin = cavity(sim.bell_points()).1 / rest;
                if (0.78..0.82).contains(&phase) {
                    at_08 = at_08.min(margin);
                } else if phase >= 0.95 {
                    end_of_stroke = end_of_stroke.max(margin);
                } else if phase < 0.05 && end_of_stroke > 0.0 {
                    at_end = at_end.min(end_of_stroke);
                    (end_of_stroke, ends) = (0.0, ends + 1);
                }
            });
        }
        let name = sized(&s);
        println!("{name}: margin at phase 0.8 {at_08:.3}, as the next stroke begins {at_end:.3}");
        assert!(
            at_end >= 0.95,
            "{name}: the margin at {at_end} as the stroke ends"
        );
        assert!(at_08 >= 0.75, "{name}: the margin at {at_08} at phase 0.8");
        assert!(ends >= 3, "{name}: {ends} strokes ended");
        assert_eq!(sim.recoveries(), 0);
    }
}

#[test]
#[ignore = "long: the two rowers at three and four sizes, 20 strokes each"]
/// Issue 28: a rower grown or shrunk (`Species::resized`: every length scaled, beating at
/// its animal's rate for the size) still rows as the animal does. Its bare bell's distance
/// a stroke stays within 15% across sizes, as McHenry & Jed (2003) find *Aurelia*'s
/// kinematics nearly similar through growth; with its fringe within 20%, for a fringe's
/// drag weighs more on a smaller bell (against the bell's inertia as 1/Re: the moon
/// jelly's own slows it 11% at 20 mm and 4% at 80 mm, `tentacles_slow_the_bell_down`).
/// Its speed rises with size, but more slowly than in proportion (the pulse rate falls as
/// it grows: their speed scales below kinematic similarity); and under way it never
/// drifts backwards while its bell refills. (*Sarsia* is not held to this: its stroke
/// shrinks at small sizes where Katija et al. 2015 find the animal's does not,
/// `docs/physics.md` section 5.)
fn a_rower_rows_alike_at_every_size() {
    let rowers = [
        (Species::aurelia(), [0.5, 1.0, 2.0, 3.875].as_slice()),
        (Species::aequorea(), [0.5, 1.0, 2.0].as_slice()),
    ];
    for (animal, scales) in rowers {
        let sized: Vec<Species> = scales
            .iter()
            .map(|k| animal.resized(k * animal.diameter))
            .collect();
        let runs = in_parallel(&sized, stroke_and_refill);
        let strokes: Vec<f32> = runs.iter().map(|r| r.0).collect();
        let bare: Vec<Species> = sized
            .iter()
            .map(|s| Species {
                tentacle_length: 0.0,
                ..s.clone()
            })
            .collect();
        let bare: Vec<f32> = in_parallel(&bare, stroke_and_refill)
            .iter()
            .map(|r| r.0)
            .collect();
        let speeds = speeds(&sized, &runs);
        for ((s, (stroke, refill, _)), speed) in sized.iter().zip(&runs).zip(&speeds) {
            println!(
                "{} at {:.0} mm, {:.2} Hz: {stroke:.3} D a stroke, {:.1} mm/s, slowest {refill:+.3} D/s refilling",
                animal.name,
                1000.0 * s.diameter,
                s.contraction_frequency,
                1000.0 * speed
            );
        }
        println!(
            "{}: a stroke spread {:.1}% across sizes, bare {:.1}% ({bare:.3?})",
            animal.name,
            100.0 * spread(&strokes),
            100.0 * spread(&bare)
        );
        assert!(spread(&bare) <= 0.15, "{} bare: {bare:?}", animal.name);
        assert!(spread(&strokes) <= 0.20, "{}: {strokes:?}", animal.name);
        assert!(
            speeds.windows(2).all(|w| w[1] > w[0]),
            "{}: {speeds:?}",
            animal.name
        );
        let (first, last) = (0, speeds.len() - 1);
        let exponent = (speeds[last] / speeds[first]).ln() / (scales[last] / scales[first]).ln();
        println!(
            "{}: speed as the diameter to the {exponent:.2}",
            animal.name
        );
        assert!(
            (0.2..0.9).contains(&exponent),
            "{}: {exponent}",
            animal.name
        );
        assert!(
            runs.iter().all(|r| r.1 > 0.0),
            "{}: drawn back while refilling: {runs:?}",
            animal.name
        );
    }
}

#[test]
#[ignore = "long: Sarsia at three sizes, 20 strokes each"]
/// Issue 28: the jetter grown or shrunk (`Species::resized`) from half to twice its size
/// still glides forwards while its bell refills once under way, and swims faster the
/// larger it is. Smaller than about 6.3 mm the water's viscosity takes its glide and the
/// refill draws it back (`examples/kinematics.rs`, `docs/physics.md`, "How small it can be
/// and still glide"); its stroke is not held alike across sizes (no velum, above).
fn the_jetter_glides_while_it_refills_from_half_to_twice_its_size() {
    let sarsia = Species::sarsia();
    let sizes = three_sizes(&sarsia);
    let runs = in_parallel(&sizes, stroke_and_refill);
    let speeds = speeds(&sizes, &runs);
    for ((s, (stroke, refill, restarts)), speed) in sizes.iter().zip(&runs).zip(&speeds) {
        println!(
            "{}: {stroke:.3} D a stroke, {:.1} mm/s, slowest {refill:+.3} D/s refilling, {restarts} restarts",
            sized(s),
            1000.0 * speed
        );
    }
    assert!(
        runs.iter().all(|r| r.1 > 0.0 && r.2 == 0),
        "drawn back while refilling, or restarted: {runs:?}"
    );
    assert!(speeds.windows(2).all(|w| w[1] > w[0]), "{speeds:?}");
}

#[test]
#[ignore = "long: the three animals at two or three sizes, twice, 20 strokes each"]
/// A game makes a bigger or smaller jellyfish by its lengths alone (diameter, height,
/// thickness, tentacle length) and its pulse rate, as `Species::resized` makes every length
/// and its bending. The animals bend as a plate of their mesoglea (`Bending::Mesoglea`), so
/// such a bell keeps a rigidity that fits its size and swims as the resized one does (what
/// still differs are the lengths left as they were: its manubrium, carried one way). With
/// the springs' constant left at the small bell's, a 155 mm moon jelly was restarted ten
/// times in fourteen strokes and swam a sixth as far. The tentacles' thickness is held the
/// same in both: a thicker tentacle drags more along its length (the layer it drags is
/// thinner for it, `TentacleDrag::along_one`), so *Sarsia* made 8 mm by its lengths alone,
/// its 0.3 mm tentacles unscaled, swims a fifth less than the resized animal, whose are half
/// as thick: a real difference, not the bending this checks, and checked apart.
fn a_bell_resized_by_its_lengths_alone_swims_as_the_resized_animal() {
    let animals = [
        // 20 mm to an adult's 30 cm.
        (Species::aurelia(), [0.5, 2.0, 3.875, 7.5].as_slice()),
        (Species::aequorea(), [0.5, 2.0, 4.0].as_slice()),
        // Smaller still, its 0.3 mm tentacles are more than a twentieth of the diameter:
        // that is refused, named.
        (Species::sarsia(), [0.5, 2.0].as_slice()),
    ];
    for (animal, scales) in animals {
        let pairs: Vec<(Species, Species)> = scales
            .iter()
            .map(|&k| {
                let resized = Species {
                    tentacle_radius: animal.tentacle_radius,
                    ..animal.resized(k * animal.diameter)
                };
                let by_hand = Species {
                    diameter: resized.diameter,
                    height: animal.height * k,
                    thickness: animal.thickness * k,
                    tentacle_length: animal.tentacle_length * k,
                    contraction_frequency: resized.contraction_frequency,
                    ..animal.clone()
                };
                (by_hand, resized)
            })
            .collect();
        let runs = in_parallel(&pairs, |(a, b)| {
            (stroke_and_refill(a), stroke_and_refill(b))
        });
        for ((by_hand, _), ((hand, _, restarts), (resized, ..))) in pairs.iter().zip(&runs) {
            println!(
                "{} at {:.0} mm: by its lengths {hand:.3} D a stroke ({restarts} restarts), \
                 resized {resized:.3} ({:+.1}%)",
                animal.name,
                1000.0 * by_hand.diameter,
                100.0 * (hand / resized - 1.0)
            );
            assert_eq!(*restarts, 0, "{} at {} m", animal.name, by_hand.diameter);
            assert!(
                (hand / resized - 1.0).abs() <= 0.1,
                "{} at {} m: {hand} against {resized}",
                animal.name,
                by_hand.diameter
            );
        }
    }
    // Four tentacles apart each drag their own layer, the thicker the harder: at 8 mm,
    // tentacles of the 16 mm animal's thickness cost the bell at least a tenth more of its
    // stroke than the resized animal's (Stokes drag along them, whose layer spans the
    // length, told the two apart by 9%).
    let sarsia = Species::sarsia();
    let thin = sarsia.resized(0.5 * sarsia.diameter);
    let thick = Species {
        tentacle_radius: sarsia.tentacle_radius,
        ..thin.clone()
    };
    let strokes = in_parallel(&[thin, thick], |s| stroke_and_refill(s).0);
    println!(
        "Sarsia at 8 mm: {:.3} D a stroke with 0.15 mm tentacles, {:.3} with 0.3 mm",
        strokes[0], strokes[1]
    );
    assert!(strokes[1] < 0.9 * strokes[0], "{strokes:?}");
}

#[test]
/// A fringe point's drag is taken at its last step's slip, and a cylinder drags harder the
/// faster it goes: hair-thin tentacles on a big bell slipped far one step, hardly the
/// next, and the swing grew until the slice blew up. *Sarsia* made 62 mm by its lengths
/// alone (its 0.3 mm tentacles 97 mm long) was restarted twice in fourteen strokes.
fn thin_trailing_tentacles_do_not_ring_the_slice() {
    let animal = Species::sarsia();
    let k = 3.875;
    let big = Species {
        diameter: animal.diameter * k,
        height: animal.height * k,
        thickness: animal.thickness * k,
        tentacle_length: animal.tentacle_length * k,
        contraction_frequency: animal.resized(animal.diameter * k).contraction_frequency,
        ..animal
    };
    let mut sim = SliceSim::new(&big).unwrap();
    while sim.cycle() < 14 {
        sim.advance(1.0 / 60.0);
    }
    let strokes = sim.swim_distance() / big.diameter / 14.0;
    println!(
        "Sarsia by hand at 62 mm: {strokes:.3} D a stroke over 14, {} restarts",
        sim.recoveries()
    );
    assert_eq!(sim.recoveries(), 0);
}

in_both_geometries!(fn a_startled_slice_escapes_then_eases_back);
/// A touch makes every shipped species beat deeper and quicker: over the strokes its
/// escape lasts it takes more strokes, then beats at its own rhythm again; a touch
/// without strength changes nothing, to the bit. Each species swims further for it in the
/// geometry it is calibrated in: a saucer forced into the plane hardly swims (the moon
/// jelly 0.09 diameters a cycle, ± 7% from stroke to stroke; its escape gains 8% there),
/// and what its quicker refills give back is within the stroke's noise.
fn a_startled_slice_escapes_then_eases_back(geometry: SliceGeometry) {
    let calibrated: Vec<String> = calibrated_in(geometry)
        .into_iter()
        .map(|s| s.name)
        .collect();
    for species in shipped(geometry) {
        let mut calm = SliceSim::new(&species).unwrap();
        run_cycles(&mut calm, 2.0);
        let mut startled = calm.clone();
        let mut untouched = calm.clone();
        startled.escape(1.0);
        untouched.escape(0.0);
        untouched.escape(f32::NAN);
        assert!(startled.escaping().is_some(), "{}", species.name);
        assert!(untouched.escaping().is_none());
        let (d0, c0) = (calm.swim_distance(), calm.cycle());
        let strokes = species.escape_strokes as f32 + 1.0;
        for sim in [&mut calm, &mut startled, &mut untouched] {
            run_cycles(sim, strokes);
        }
        let (calm_swim, startled_swim) = (calm.swim_distance() - d0, startled.swim_distance() - d0);
        println!(
            "{} ({geometry:?}): over {strokes} strokes' time calm {:.2} D in {} strokes, \
             startled {:.2} D in {}",
            species.name,
            calm_swim / species.diameter,
            calm.cycle() - c0,
            startled_swim / species.diameter,
            startled.cycle() - c0
        );
        let per_cycle = calm.clock().steps_per_cycle() as f32;
        let gained = (startled.clock().stroke_steps() - calm.clock().stroke_steps()) as f32;
        println!("  {:.2} strokes more", gained / per_cycle);
        assert!(
            startled.escaping().is_none(),
            "{}: eased back",
            species.name
        );
        assert!(gained > 0.25 * per_cycle, "{}: quicker", species.name);
        assert!(
            startled_swim > 1.1 * calm_swim || !calibrated.contains(&species.name),
            "{}: startled {startled_swim} m against {calm_swim} m",
            species.name
        );
        assert_eq!(
            state_bits(&untouched),
            state_bits(&calm),
            "{}",
            species.name
        );
        // Its own rhythm again: a stroke takes the species' period.
        let (t, c) = (startled.time(), startled.cycle());
        run_cycles(&mut startled, 2.0);
        assert_eq!(startled.cycle() - c, 2, "{} at {t} s", species.name);
    }
}

in_both_geometries!(fn an_escape_is_the_same_however_time_is_split);
fn an_escape_is_the_same_however_time_is_split(geometry: SliceGeometry) {
    let species = Species {
        slice_geometry: geometry,
        ..Species::sarsia()
    };
    let run = |dt: f32| {
        let mut sim = SliceSim::new(&species).unwrap();
        for k in 0..(3.0 / dt) as usize {
            sim.advance(dt);
            if k + 1 == (1.0 / dt) as usize {
                sim.escape(0.8);
            }
        }
        sim
    };
    let (a, b) = (run(1.0 / 32.0), run(1.0 / 128.0));
    assert!(a.cycle() > 0);
    assert_eq!(
        state_bits(&a),
        state_bits(&b),
        "1/32 s against 1/128 s frames"
    );
}
