//! The fringe on its own: its drag laws, its pull on the margin, and a chain crushed onto
//! one spot.

use super::tests::body;
use super::*;

/// The paper's body with its tentacles swung sideways, unevenly (their springs and
/// hinges pull), and free to tilt: every point solved.
fn swung() -> Body {
    let mut b = body();
    b.set_mirror_symmetric(false);
    let [left, right] = b.tentacles.clone();
    for (k, i) in left.enumerate() {
        b.points[i].x -= 0.0003 * k as f32;
    }
    for (k, i) in right.enumerate() {
        b.points[i].x += 0.0005 * k as f32;
    }
    b
}

#[test]
fn tentacles_drag_the_margin_and_the_body_stays_force_free() {
    let mut b = swung();
    let x = b.points.clone();
    let n = x.len();
    let (mut forces, mut slip) = (vec![Vec2::ZERO; n], vec![Vec2::ZERO; n]);
    let mass = 1025.0 * 0.004 * 0.004;
    b.implicit_forces(
        None,
        &x,
        0.03,
        &vec![mass / 0.03f32.powi(2); x.len()],
        &mut forces,
        &mut slip,
    );
    let scale: f32 = forces.iter().map(|f| f.length()).sum();
    let net: Vec2 = forces.iter().sum();
    assert!(scale > 0.0);
    assert!(net.length() < 1e-4 * scale, "net {net} of {scale}");
    // The tentacle points slip through the water; the bell's do not.
    assert!(
        b.tentacles
            .iter()
            .flat_map(|r| r.clone())
            .any(|i| slip[i] != Vec2::ZERO)
    );
    assert!(slip[b.bell.clone()].iter().all(|s| *s == Vec2::ZERO));
    // The margins feel the tentacles' pull.
    let margins = [b.bell.start, b.bell.end - 1];
    assert!(
        forces[margins[0]].x < 0.0 && forces[margins[1]].x > 0.0,
        "{:?}",
        [forces[margins[0]], forces[margins[1]]]
    );
}

#[test]
fn a_fringe_pulls_its_margins_water_as_far_as_that_water_can_take_and_the_bell_the_rest() {
    // The bell at rest (no force of its own), its tentacles swung sideways: every force
    // the bell's water gets is the fringe's pull. Where the fringe drags less in a step
    // than the margin's water weighs, that water takes all of it; where more (an 11 mm
    // bell's 200 tentacles beaten slowly: five times), all of it there overshot every step
    // and blew the slice up, so the rest loads the bell, whose implicit solve spreads it
    // over the water the bell drags.
    let light = 1025.0 * 0.004 * 0.004;
    for (mass, whole) in [(light, true), (0.01 * light, false)] {
        let mut b = swung();
        let x = b.points.clone();
        let n = x.len();
        let (mut forces, mut slip) = (vec![Vec2::ZERO; n], vec![Vec2::ZERO; n]);
        let dt = 0.03;
        // What a side's fringe drags in a step, over what its margin's water weighs.
        let dragged: f32 = b.tentacles[1]
            .clone()
            .map(|i| b.tentacle_drag[i] / dt)
            .sum();
        let outweighs = dragged / (mass / (dt * dt));
        assert_eq!(
            outweighs > 1.0,
            !whole,
            "the fringe outweighs its water {outweighs} times"
        );
        b.implicit_forces(
            None,
            &x,
            dt,
            &vec![mass / (dt * dt); n],
            &mut forces,
            &mut slip,
        );
        let margins = [b.bell.start, b.bell.end - 1];
        let mut fringe = Vec2::ZERO;
        for (side, range) in b.tentacles.clone().into_iter().enumerate() {
            let pull: Vec2 = forces[range].iter().sum();
            fringe += pull;
            let share = -forces[margins[side]].dot(pull) / pull.length_squared();
            let expected = if whole { 0.999..1.001 } else { 0.0..0.9 };
            assert!(
                expected.contains(&share),
                "mass {mass}, side {side}: the margin's water takes {share} of the pull"
            );
        }
        let bell: Vec2 = forces[b.bell.clone()].iter().sum();
        assert!(
            (bell + fringe).length() < 1e-4 * fringe.length(),
            "mass {mass}: the bell's water gets {bell}, the fringe's {fringe}"
        );
        let carried = forces[b.bell.clone()]
            .iter()
            .filter(|f| f.length() > 1e-3 * fringe.length())
            .count();
        assert_eq!(
            carried > 2,
            !whole,
            "mass {mass}: {carried} points carry the pull"
        );
    }
}

#[test]
fn a_fringe_of_no_tentacles_hangs_no_chains() {
    // Chains of no tentacles would slip against no drag at all and blow the slice up.
    let mut s = Species::aurelia();
    s.tentacle_count = 0;
    let b = Body::new(&s, Vec2::new(0.2, 0.2), 0.004);
    assert!(
        b.tentacles.iter().all(|r| r.is_empty()),
        "{:?}",
        b.tentacles
    );
    assert_eq!(b.points.len(), b.bell.len());
}

#[test]
fn a_tentacle_drags_less_along_than_across_and_a_dense_fringe_no_more_than_a_sheet() {
    use super::depth::Depth;
    use super::tentacle::TentacleDrag;
    use crate::species::FringeDrag;
    // One point per millimetre of a planar slice's tentacles.
    let segment = 0.001;
    let drag = |s: &Species| {
        let planar = Species {
            slice_geometry: crate::species::SliceGeometry::Planar,
            ..s.clone()
        };
        TentacleDrag::new(&planar, segment, Depth::new(&planar, 0.0, segment))
    };
    let filaments = |s: Species| Species {
        fringe_drag: FringeDrag::Filaments,
        ..s
    };
    for s in [
        Species::sarsia(),
        Species::aurelia(),
        Species::aequorea(),
        filaments(Species::paper()),
    ] {
        let d = drag(&s);
        for speed in [0.005, 0.01, 0.02, 0.08] {
            let (across, along) = (d.at_angle(speed, 0.0), d.at_angle(speed, 1.0));
            let oblique = d.at_angle(speed, 0.5);
            assert_eq!(across, d.at(speed), "{} at {speed} m/s", s.name);
            assert!(
                along < 0.6 * across && along < oblique && oblique < across,
                "{} at {speed} m/s: {along} along, {oblique} oblique, {across} across",
                s.name
            );
        }
    }
    // The moon jelly's and the crystal jelly's fringes are closer than the layers their
    // tentacles drag along are thick: each slides as a porous sheet. Its skin friction
    // (Blasius: 1.328/√Re_L on each face, over the fringe's length) per tentacle's share
    // is of the isolated tentacle's tangential drag (within a factor of three, the sheet's
    // the less as its layers thicken), never the cylinder's drag across.
    for s in [Species::aurelia(), Species::aequorea()] {
        let d = drag(&s);
        let nu = s.kinematic_viscosity();
        let spacing = std::f32::consts::PI * s.diameter / s.tentacle_count as f32;
        let per_point = segment / spacing;
        for speed in [0.005, 0.01, 0.02] {
            let layer = (nu * s.tentacle_length / speed).sqrt();
            assert!(layer > spacing - 2.0 * s.tentacle_radius, "{}", s.name);
            let sheet = s.density * 1.328 * (speed * nu / s.tentacle_length).sqrt() * spacing;
            let along = d.at_angle(speed, 1.0) / per_point;
            let across = d.at_angle(speed, 0.0) / per_point;
            assert!(
                (1.0 / 3.0..3.0).contains(&(along / sheet)) && across > 4.0 * sheet,
                "{} at {speed} m/s: along {along}, sheet {sheet}, across {across} N·s/m²",
                s.name
            );
        }
    }
}

#[test]
fn a_tentacle_on_its_own_drags_the_layer_it_grows_along_its_length() {
    use super::depth::Depth;
    use super::tentacle::TentacleDrag;
    let drag = |s: &Species| TentacleDrag::new(s, 0.001, Depth::new(s, 0.0, 0.001));
    let s = Species::sarsia();
    let (a, length) = (s.tentacle_radius, s.tentacle_length);
    let (mu, nu) = (s.viscosity, s.kinematic_viscosity());
    // Slender-body Stokes drag's tangential half, a metre of one tentacle.
    let stokes_along_of = |s: &Species| {
        2.0 * std::f32::consts::PI * s.viscosity
            / ((s.tentacle_length / s.tentacle_radius).ln() + 0.5)
    };
    let stokes_along = stokes_along_of(&s);
    let d = drag(&s);
    // Glauert & Lighthill's thick layer, halfway down, at the slip *Sarsia*'s swim gives
    // its four tentacles: several times the Stokes limit, whose layer spans the length.
    let speed = 0.03;
    let xi = 4.0 * nu * (0.5 * length) / (speed * a * a);
    let layer = 4.0 * std::f32::consts::PI * mu / (xi.ln() - 0.5772157);
    let one = d.along_one(speed);
    assert!((one / layer - 1.0).abs() < 1e-4, "{one} against {layer}");
    assert!(
        one > 3.0 * stokes_along,
        "{one} against Stokes' {stokes_along}"
    );
    // Slower, the layer thickens towards the length and the drag falls to Stokes', never
    // below it; it never falls as the slip quickens.
    let speeds = [1e-7, 1e-5, 1e-3, 0.003, 0.01, 0.03, 0.1, 0.3];
    let along: Vec<f32> = speeds.iter().map(|&u| d.along_one(u)).collect();
    assert!(along.windows(2).all(|w| w[1] >= w[0]), "{along:?}");
    assert!((along[0] / stokes_along - 1.0).abs() < 1e-4, "{along:?}");
    // Four tentacles a bell's width apart are apart: each drags its own layer, but for
    // the share of the gap between them its layers span (a twelfth), where the fringe
    // slides as a sheet.
    let per_point = d.at(speed) / d.per_length(speed);
    let gap = std::f32::consts::PI * s.diameter / s.tentacle_count as f32 - 2.0 * a;
    let sheet = (nu * length / speed).sqrt() / gap;
    assert!((0.05..0.15).contains(&sheet), "{sheet}");
    let blend = sheet * stokes_along + (1.0 - sheet) * one;
    let along_fringe = d.at_angle(speed, 1.0) / per_point;
    assert!(
        (along_fringe / blend - 1.0).abs() < 1e-4,
        "{along_fringe} against {blend}"
    );
    // As the gaps close the drag along falls continuously to the sheet's, and a fringe
    // whose layers span its gaps (the moon jelly's two hundred) drags the sheet's alone.
    let along_with = |count: u32| {
        let s = Species {
            tentacle_count: count,
            ..Species::sarsia()
        };
        let d = drag(&s);
        d.at_angle(speed, 1.0) / d.at(speed)
    };
    let ratios: Vec<f32> = [4, 16, 64, 128, 256, 1024].map(along_with).to_vec();
    assert!(ratios.windows(2).all(|w| w[1] <= w[0]), "{ratios:?}");
    let sheets = stokes_along / d.per_length(speed);
    assert!(
        (ratios[5] / sheets - 1.0).abs() < 1e-4,
        "{ratios:?} against {sheets}"
    );
    let moon = drag(&Species::aurelia());
    let moon_stokes = stokes_along_of(&Species::aurelia());
    let moon_along = moon.at_angle(0.01, 1.0) / (moon.at(0.01) / moon.per_length(0.01));
    assert!(
        (moon_along / moon_stokes - 1.0).abs() < 1e-4,
        "{moon_along} against {moon_stokes}"
    );
}

#[test]
fn the_papers_curtain_drags_a_dense_fringe_as_much_along_as_across() {
    use super::depth::Depth;
    use super::tentacle::TentacleDrag;
    use crate::species::FringeDrag;
    let drag = |s: &Species| TentacleDrag::new(s, 0.001, Depth::new(s, 0.0, 0.001));
    let curtain = |s: Species| Species {
        fringe_drag: FringeDrag::Curtain,
        ..s
    };
    // The paper's two hundred, closer than the water they drag along is thick: the same
    // drag whichever way the water slips past, to the bit.
    let dense = drag(&Species::paper());
    assert_eq!(Species::paper().fringe_drag, FringeDrag::Curtain);
    for speed in [0.005, 0.02] {
        for along in [0.0, 0.3, 1.0] {
            assert_eq!(dense.at_angle(speed, along), dense.at(speed));
        }
    }
    // Sarsia's four, a bell's width apart, still trail: along them far less.
    let sparse = drag(&curtain(Species::sarsia()));
    for speed in [0.005, 0.02, 0.08] {
        let (across, along) = (sparse.at_angle(speed, 0.0), sparse.at_angle(speed, 1.0));
        assert!(along < 0.6 * across, "at {speed} m/s: {along}, {across}");
    }
    // Between the two the drag along grows continuously as the gaps close.
    let along_with = |count: u32| {
        let s = Species {
            tentacle_count: count,
            ..curtain(Species::sarsia())
        };
        let d = drag(&s);
        d.at_angle(0.02, 1.0) / d.at(0.02)
    };
    let ratios: Vec<f32> = [4, 8, 16, 32, 64].map(along_with).to_vec();
    assert!(ratios.windows(2).all(|w| w[0] <= w[1]), "{ratios:?}");
    assert_eq!(ratios[4], 1.0, "{ratios:?}");
}

/// An r–z bell's muscles are force generators (`Drive::Activation`): let go, they exert
/// nothing however the bell is squeezed or pulled open; activated, they pull as hard as
/// they are activated; and squeezed past the shortest length they pull to, they go slack
/// instead of pushing.

#[test]
fn a_fringe_crushed_onto_one_spot_still_solves() {
    // Points of a fringe pushed out of the bell land on its aperture's chord, two of them
    // once all but on one spot (the paper's bell in r–z, half as stiff, in its 35th
    // stroke): a hinge's gradient is 1/length across its arm, and the solve's factor,
    // handed gradients of 10⁷ per metre, lost its positive pivots and the slice went NaN.
    // Each arm is now read at least a tenth of its rest length long.
    let species = Species {
        slice_geometry: crate::SliceGeometry::Axisymmetric,
        ..Species::paper()
    };
    let h = 0.004;
    for gap in [0.0, 1e-9, 7e-8, 1e-6] {
        let mut b = Body::new(&species, Vec2::new(0.12, 0.15), h);
        let [left, right] = b.tentacles.clone();
        let (k, image) = (left.start + 5, right.start + 5);
        let axis = 0.5 * (b.points[left.start].x + b.points[right.start].x);
        let at = b.points[k - 1] + Vec2::new(gap, 0.0);
        b.points[k] = at;
        b.points[image] = Vec2::new(2.0 * axis - at.x, at.y);
        // The shortest arm at rest, a tenth of it the shortest an arm is read at.
        let rest = Body::new(&species, Vec2::new(0.12, 0.15), h).points;
        let arm = |a: usize, b: usize| (rest[a] - rest[b]).length();
        let least = 0.1
            * b.hinges
                .iter()
                .map(|h| arm(h.a, h.b).min(arm(h.c, h.b)))
                .fold(f32::MAX, f32::min);
        let x = b.points.clone();
        for c in constraints(&b, &x, &Weights::default())
            .iter()
            .filter(|c| c.count == 3)
        {
            let steepest = c.grad.iter().map(|g| g.length()).fold(0.0, f32::max);
            assert!(
                steepest <= 2.0 / least,
                "gap {gap} m: hinge {:?}: {steepest} /m",
                c.idx
            );
        }
        let n = x.len();
        let (mut forces, mut slip) = (vec![Vec2::ZERO; n], vec![Vec2::ZERO; n]);
        let dt = species.step_length();
        let mass: Vec<f32> = x
            .iter()
            .map(|p| 0.5 * 1025.0 * h * h * (p.x - axis).abs().max(0.003) / (dt * dt))
            .collect();
        b.implicit_forces(None, &x, dt, &mass, &mut forces, &mut slip);
        assert!(
            forces.iter().chain(&slip).all(|f| f.is_finite()),
            "gap {gap} m: {:?}",
            &forces[left]
        );
    }
}
