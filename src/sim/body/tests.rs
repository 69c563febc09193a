//! The body on its own: rest, balance of forces, implicit forces, muscles (the fringe in
//! `fringe_tests`).

use super::*;

/// The paper's planar bell, where every element's forces balance (rings in r–z feel
/// their hoops as a net radial force).
pub(super) fn body() -> Body {
    Body::new(&Species::paper(), Vec2::new(0.2, 0.2), 0.004)
}

#[test]
fn rest_shape_feels_no_force() {
    let b = body();
    let mut f = vec![Vec2::ZERO; b.points.len()];
    b.forces(&mut f);
    let max = f.iter().fold(0.0f32, |m, v| m.max(v.length()));
    assert!(max < 1e-4, "{max}");
}

fn deformed(b: &mut Body) {
    for (i, p) in b.points.iter_mut().enumerate() {
        *p += Vec2::new((i as f32 * 1.3).sin(), (i as f32 * 0.7).cos()) * 0.001;
    }
    for m in &mut b.muscles {
        m.rest = 0.6 * m.relaxed;
    }
}

#[test]
fn internal_forces_sum_to_zero() {
    let mut b = body();
    deformed(&mut b);
    let mut f = vec![Vec2::ZERO; b.points.len()];
    b.forces(&mut f);
    let scale: f32 = f.iter().map(|v| v.length()).sum();
    let net: Vec2 = f.iter().sum();
    let torque: f32 = b.points.iter().zip(&f).map(|(p, f)| p.perp_dot(*f)).sum();
    assert!(scale > 1.0, "the deformation loads the springs");
    assert!(net.length() < 1e-5 * scale, "net {net}, scale {scale}");
    assert!(torque.abs() < 1e-5 * scale, "torque {torque}");
}

/// In both geometries (the paper's planar bell, free to tilt and held symmetric; the moon
/// jelly's r–z one). A symmetric body is solved on its half, as its partners' mirror
/// images, so it is deformed as a symmetric body deforms, symmetrically.
#[test]
fn implicit_forces_match_explicit_ones_for_tiny_steps_and_soften_for_large() {
    for (species, symmetric) in [
        (Species::paper(), false),
        (Species::paper(), true),
        (Species::aurelia(), true),
    ] {
        let species = Species {
            tentacle_length: 0.0,
            ..species
        };
        implicit_forces_match_explicit_ones_in(species, symmetric);
    }
}

fn implicit_forces_match_explicit_ones_in(species: Species, symmetric: bool) {
    let geometry = species.slice_geometry;
    let mut b = Body::new(&species, Vec2::new(0.2, 0.2), 0.004);
    b.set_mirror_symmetric(symmetric);
    deformed(&mut b);
    if symmetric {
        let axis = b.bell_points()[b.apex_index()].x;
        b.symmetrise(axis);
    }
    assert_eq!(!b.mirror_partners().is_empty(), symmetric, "{geometry:?}");
    let x = b.points.clone();
    let n = x.len();
    let mut explicit = vec![Vec2::ZERO; n];
    b.forces(&mut explicit);
    let (mut small_dt, mut large_dt, mut slip) = (
        vec![Vec2::ZERO; n],
        vec![Vec2::ZERO; n],
        vec![Vec2::ZERO; n],
    );
    let mass = 1025.0 * 0.004 * 0.004;
    b.implicit_forces(
        None,
        &x,
        1e-6,
        &vec![mass / 1e-12; x.len()],
        &mut small_dt,
        &mut slip,
    );
    b.implicit_forces(
        None,
        &x,
        0.05,
        &vec![mass / 0.05f32.powi(2); x.len()],
        &mut large_dt,
        &mut slip,
    );
    let norm = |f: &[Vec2]| f.iter().map(|v| v.length_squared()).sum::<f32>().sqrt();
    // Tiny step: implicit equals explicit. Large step: the stiff modes are damped.
    let diff: f32 = explicit
        .iter()
        .zip(&small_dt)
        .map(|(a, b)| (*a - *b).length_squared())
        .sum::<f32>()
        .sqrt();
    assert!(
        diff < 1e-3 * norm(&explicit),
        "{geometry:?}, symmetric {symmetric}: {diff}"
    );
    assert!(norm(&large_dt) < norm(&explicit));
    let net: Vec2 = large_dt.iter().sum();
    assert!(
        net.length() < 1e-4 * norm(&large_dt),
        "{geometry:?}: net {net}"
    );
}

/// A body held symmetric is solved on its half: the elements wholly past the axis are
/// left out and their mirror images count twice. Every element left out has an image
/// counted twice (the weights add up to the number of elements), and the forces and the
/// fringe's slip are those with every element counted once, to rounding: every shipped
/// species and the paper's, in both geometries, tentacles and all.
#[test]
fn a_symmetric_body_solves_its_half_as_the_whole() {
    use crate::species::SliceGeometry;
    for species in [
        Species::aurelia(),
        Species::aequorea(),
        Species::sarsia(),
        Species::paper(),
    ] {
        for geometry in [SliceGeometry::Planar, SliceGeometry::Axisymmetric] {
            let species = Species {
                slice_geometry: geometry,
                ..species.clone()
            };
            let name = format!("{} {geometry:?}", species.name);
            let mut b = Body::new(&species, Vec2::new(0.2, 0.2), 0.004);
            b.set_mirror_symmetric(true);
            deformed(&mut b);
            let axis = b.bell_points()[b.apex_index()].x;
            b.symmetrise(axis);
            let x = b.points.clone();
            let weights: Vec<f32> = b.weights.all().collect();
            let elements = b.springs.len() + b.muscles.len() + b.hinges.len();
            assert_eq!(weights.len(), elements + b.hoop_bends.len(), "{name}");
            let (left_out, doubled) = (
                weights.iter().filter(|w| **w == 0.0).count(),
                weights.iter().filter(|w| **w == 2.0).count(),
            );
            assert!(left_out > 0, "{name}: nothing past the axis left out");
            assert_eq!(
                left_out, doubled,
                "{name}: each left out has an image counted twice"
            );
            assert!(
                weights.iter().all(|w| [0.0, 1.0, 2.0].contains(w)),
                "{name}"
            );
            let counted = constraints(&b, &x, &b.weights).len();
            assert_eq!(counted, weights.len() - left_out, "{name}");

            let mut whole = b.clone();
            whole.weights = half::Weights::default();
            let dt = 0.01;
            let mass = vec![1025.0 * 0.004 * 0.004 / (dt * dt); x.len()];
            let solve = |b: &mut Body| {
                let (mut forces, mut slip) = (vec![Vec2::ZERO; x.len()], vec![Vec2::ZERO; x.len()]);
                b.implicit_forces(None, &x, dt, &mass, &mut forces, &mut slip);
                (forces, slip)
            };
            let (half, whole) = (solve(&mut b), solve(&mut whole));
            let largest = |v: &[Vec2]| v.iter().fold(0.0f32, |m, f| m.max(f.length()));
            let apart = |a: &[Vec2], b: &[Vec2]| {
                a.iter()
                    .zip(b)
                    .fold(0.0f32, |m, (a, b)| m.max((*a - *b).length()))
            };
            assert!(
                largest(&whole.0) > 0.0,
                "{name}: the deformation loads the body"
            );
            let (forces, slip) = (apart(&half.0, &whole.0), apart(&half.1, &whole.1));
            assert!(
                forces <= 1e-4 * largest(&whole.0),
                "{name}: forces {forces}"
            );
            assert!(
                slip <= 1e-4 * largest(&whole.1).max(1e-12),
                "{name}: slip {slip}"
            );
        }
    }
}

#[test]
fn relaxed_muscles_hold_the_rest_shape() {
    let mut b = body();
    let rest = b.points.clone();
    for m in &mut b.muscles {
        m.rest = 0.56 * m.relaxed;
    }
    let mut f = vec![Vec2::ZERO; b.points.len()];
    b.forces(&mut f);
    // Contracted rest lengths pull opposite margins together...
    let (l, r) = (b.muscles[0].a, b.muscles[0].b);
    assert!(f[l].x > 0.0 && f[r].x < 0.0);
    // ...and relaxed ones leave the rest shape alone.
    for m in &mut b.muscles {
        m.rest = m.relaxed;
    }
    b.forces(&mut f);
    assert!(f.iter().all(|v| v.length() < 1e-4));
    assert_eq!(b.points, rest);
}

#[test]
fn points_are_spaced_by_the_kernel_not_by_a_finer_grid() {
    // The paper's bell's boundary is 0.3 D = 12 mm wide: three cells of 4 mm.
    let s = Species::paper();
    let at = |h: f32| {
        let b = Body::new(&s, Vec2::new(0.2, 0.2), h);
        (b.bell.len(), b.points.len())
    };
    let kernel_cell = 0.3 * s.diameter / 3.0;
    let (bell, all) = at(kernel_cell);
    // Finer cells under the same kernel: the same body.
    for finer in [1.5, 2.0, 3.0] {
        assert_eq!(at(kernel_cell / finer), (bell, all), "cells {finer}× finer");
    }
    // Coarser cells than the kernel's: about half a cell apart, so fewer points.
    let (coarse, _) = at(2.0 * kernel_cell);
    assert!(coarse < bell * 2 / 3, "{coarse} points against {bell}");
}

#[test]
fn hoop_bending_is_the_gradient_of_its_energy_and_stiffest_near_the_axis() {
    // A shell of revolution bends around its axis by sin ψ / r: energy ½·D·Δs/r·(Δ sin ψ)²
    // per radian, so a segment's stiffness falls as 1/r away from the axis.
    let s = Species::aurelia();
    let mut b = Body::new(&s, Vec2::new(0.2, 0.2), s.cell_size());
    let apex = b.apex_index();
    let bends = b.hoop_bends.clone();
    assert_eq!(bends.len(), b.bell.len() - 1);
    let stiffness_at = |k: usize| bends[k].stiffness;
    assert!(stiffness_at(apex) > 3.0 * stiffness_at(apex + b.bell.len() / 4));
    let energy = |b: &Body| -> f64 {
        b.hoop_bends
            .iter()
            .map(|h| {
                let d = (b.points[h.b] - b.points[h.a]).as_dvec2();
                let change = d.y / d.length() - h.rest as f64;
                0.5 * h.stiffness as f64 * change * change
            })
            .sum()
    };
    // At rest, and moved along the axis, it holds no energy (to rounding).
    assert!(energy(&b) < 1e-18);
    for p in &mut b.points {
        p.y += 0.003;
    }
    assert!(energy(&b) < 1e-18);
    // Bent by a tenth of the points' spacing.
    for (i, p) in b.points.iter_mut().enumerate() {
        *p += Vec2::new((i as f32 * 1.3).sin(), (i as f32 * 0.7).cos()) * 1.5e-4;
    }
    // The force each hoop bend adds is minus the gradient of its energy.
    b.springs.clear();
    b.hinges.clear();
    b.muscles.clear();
    let mut f = vec![Vec2::ZERO; b.points.len()];
    b.forces(&mut f);
    let e = 1e-5;
    for i in [apex, apex + 3, 2, 1] {
        for axis in [Vec2::X, Vec2::Y] {
            let mut plus = b.clone();
            plus.points[i] += e * axis;
            let mut minus = b.clone();
            minus.points[i] -= e * axis;
            let numeric = -(energy(&plus) - energy(&minus)) / (2.0 * e as f64);
            let analytic = f[i].dot(axis) as f64;
            assert!(
                (numeric - analytic).abs() <= 0.01 * analytic.abs().max(1e-6),
                "point {i} {axis}: {analytic} against {numeric}"
            );
        }
    }
    // The plane has no hoop curvature.
    let planar = Body::new(&Species::paper(), Vec2::new(0.2, 0.2), 0.004);
    assert!(planar.hoop_bends.is_empty());
}

#[test]
fn an_axisymmetric_muscle_pulls_as_hard_as_it_is_activated_and_never_pushes() {
    let species = Species::aurelia();
    let ratio = species.contraction_ratio;
    let mut b = Body::new(&species, Vec2::new(0.0, 0.2), 0.002);
    assert!(!b.muscles.is_empty());
    assert!(
        b.muscles
            .iter()
            .all(|m| m.drive == elements::Drive::Activation)
    );
    // Pulled open by a tenth, then squeezed to half its width: the rings' hoops and the
    // bending push back either way, the muscles only where they are activated.
    let rest = b.points.clone();
    let muscle_forces = |b: &mut Body, factor: f32, squeeze: f32| {
        for (p, r) in b.points.iter_mut().zip(&rest) {
            *p = Vec2::new(r.x * squeeze, r.y);
        }
        for m in &mut b.muscles {
            m.contract(factor, ratio);
        }
        let mut with = vec![Vec2::ZERO; b.points.len()];
        b.forces(&mut with);
        let muscles = std::mem::take(&mut b.muscles);
        let mut without = vec![Vec2::ZERO; b.points.len()];
        b.forces(&mut without);
        b.muscles = muscles;
        let (l, r) = (b.muscles[0].a, b.muscles[0].b);
        // The margin's inward pull: along +x on the left (x < 0), −x on the right.
        ((with[l] - without[l]).x, (with[r] - without[r]).x)
    };
    for squeeze in [1.1, 0.5] {
        assert_eq!(muscle_forces(&mut b, 1.0, squeeze), (0.0, 0.0), "let go");
    }
    let (half_l, half_r) = muscle_forces(&mut b, 1.0 - 0.5 * (1.0 - ratio), 1.1);
    let (full_l, full_r) = muscle_forces(&mut b, ratio, 1.1);
    assert!(half_l > 0.0 && half_r < 0.0, "pulls the margins together");
    assert!(
        (full_l / half_l - 2.0).abs() < 1e-3 && (full_r / half_r - 2.0).abs() < 1e-3,
        "twice as hard at twice the activation: {half_l} {full_l}"
    );
    let squeezed = muscle_forces(&mut b, ratio, 0.5 * ratio);
    assert_eq!(squeezed, (0.0, 0.0), "slack below its shortest length");
}

/// The circular muscle lines the subumbrella from the margin up `muscle_extent` of its
/// arc and no further, in both geometries: the margin's ring always, every ring to the
/// apex when it is 1, more rings the further it reaches.
#[test]
fn the_muscle_lines_the_bell_from_the_margin_as_far_as_its_extent() {
    for base in [Species::paper(), Species::aurelia()] {
        let levels = |extent: f32| -> Vec<f32> {
            let s = Species {
                muscle_extent: extent,
                ..base.clone()
            };
            let b = Body::new(&s, Vec2::new(0.0, 0.2), 0.002);
            b.muscles.iter().map(|m| m.level).collect()
        };
        let rings = rings_to_apex(&base);
        let mut counts = Vec::new();
        for extent in [0.1, 0.3, 0.5, 0.75, 1.0] {
            let l = levels(extent);
            assert!(
                l.contains(&1.0),
                "{}: the margin's ring at {extent}",
                base.name
            );
            assert!(
                l.iter().all(|&level| level >= 1.0 - extent),
                "{}: a muscle above {extent} of the arc: {l:?}",
                base.name
            );
            counts.push(l.len());
        }
        assert!(
            counts.windows(2).all(|w| w[0] < w[1]),
            "{}: {counts:?}",
            base.name
        );
        assert_eq!(counts[4], rings, "{}: every ring to the apex", base.name);
    }
}

/// Rings from the margin to the apex (the apex's own point excluded): half the
/// subumbrellar chain.
fn rings_to_apex(species: &Species) -> usize {
    Body::new(species, Vec2::new(0.0, 0.2), 0.002).bell.len() / 2
}

/// A half circle is a half-dome (depth half its width), a straight line no cavity, and an
/// empty bell measures nothing rather than panicking.
#[test]
fn a_half_circle_is_a_cavity_half_as_deep_as_wide() {
    let arc: Vec<Vec2> = (0..=24)
        .map(|k| {
            let a = std::f32::consts::PI * k as f32 / 24.0;
            Vec2::new(-a.cos(), a.sin())
        })
        .collect();
    let (depth, margin) = super::cavity(&arc);
    assert!((depth - 0.5).abs() < 1e-5 && (margin - 2.0).abs() < 1e-5);
    let flat: Vec<Vec2> = (0..5).map(|k| Vec2::new(k as f32, 0.0)).collect();
    assert_eq!(super::cavity(&flat).0, 0.0);
    assert_eq!(super::cavity(&[]), (0.0, 0.0));
}
