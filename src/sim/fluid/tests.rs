//! The fluid on its own: projection, spreading, advection, viscosity.

use super::*;
use crate::sim::coupling::Coupling;
use glam::Vec2;

/// Spreads point forces as the slice does: through the points' stencils (`Coupling`).
fn spread(f: &mut Fluid, points: &[Vec2], forces: &[Vec2]) {
    let mut coupling = Coupling::default();
    coupling.locate(f, points, &[]);
    coupling.spread(f, forces);
}

/// A fluid with some divergent flow in it (the r–z tests start from it too).
pub(super) fn swirl(n: usize) -> Fluid {
    let mut f = Fluid::new(n, 0.01, 1.3e-6, 1000.0);
    for j in 0..n {
        for i in 0..=n {
            f.u[j * (n + 1) + i] = ((i * 31 + j * 17) % 13) as f32 * 0.01 - 0.06;
        }
    }
    for j in 0..=n {
        for i in 0..n {
            f.v[j * n + i] = ((i * 7 + j * 29) % 11) as f32 * 0.01 - 0.05;
        }
    }
    f.enforce_walls();
    f
}

#[test]
fn projection_leaves_no_divergence() {
    for n in [16, 64, 100] {
        let mut f = swirl(n);
        f.project();
        let rel = f.h * f.divergence_max() / f.speed_max();
        assert!(rel <= 1e-4, "n = {n}: h·max|div|/max|u| = {rel}");
    }
}

#[test]
fn projection_is_idempotent() {
    // Planar at an even grid; r–z at an odd one (solved on its half, then mirrored).
    for (geometry, n) in [
        (SliceGeometry::Planar, 32),
        (SliceGeometry::Axisymmetric, 33),
    ] {
        let mut f = swirl(n);
        if geometry == SliceGeometry::Axisymmetric {
            f.set_geometry(geometry);
            f.symmetrise();
        }
        f.project();
        let before = f.u.clone();
        f.project();
        let change =
            f.u.iter()
                .zip(&before)
                .fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            change < 1e-5,
            "{geometry:?}: second projection changed u by {change}"
        );
    }
}

/// A planar slice held mirror-symmetric is solved on its half (the force of the points
/// past the axis spread through their partners, viscosity and pressure on the half, the
/// rest mirrored): on an odd grid, whose box is its own mirror image, that is the whole
/// field's step symmetrised, to round-off; on an even one the half is divergence-free and
/// the field its mirror image.
#[test]
fn a_planar_slice_held_symmetric_is_solved_on_its_half() {
    for n in [41, 40] {
        let mut start = swirl(n);
        start.symmetrise();
        start.project();
        let (mut half, mut whole) = (start.clone(), start);
        half.mirror = true;
        let axis = half.axis();
        let points = [Vec2::new(axis - 0.061, 0.17), Vec2::new(axis - 0.012, 0.23)];
        let mirrored = points.map(|p| Vec2::new(2.0 * axis - p.x, p.y));
        let forces = [Vec2::new(0.4, -1.1), Vec2::new(-0.3, 0.6)];
        let mirrored_forces = forces.map(|f| Vec2::new(-f.x, f.y));
        let all_points = [points, mirrored].concat();
        let all_forces = [forces, mirrored_forces].concat();
        // The half reads the points past the axis as their partners' mirrors.
        let partners = [None, None, Some(0), Some(1)];
        for _ in 0..6 {
            let mut coupling = Coupling::default();
            coupling.locate(&half, &all_points, &partners);
            coupling.spread(&mut half, &all_forces);
            spread(&mut whole, &all_points, &all_forces);
            for f in [&mut half, &mut whole] {
                f.step(0.02);
            }
            whole.symmetrise();
        }
        let speed = half.speed_max();
        let rel = half.h * half.divergence_max() / speed;
        assert!(
            rel <= 1e-4,
            "n = {n}: h·max|div|/max|u| on the half = {rel}"
        );
        let c = n / 2;
        for j in 0..n {
            for i in 1..=c {
                let (l, r) = (half.u[j * (n + 1) + i], half.u[j * (n + 1) + 2 * c + 1 - i]);
                assert!(2 * c + 1 - i >= n || l == -r, "n = {n}: u not mirrored");
            }
        }
        if n % 2 == 1 {
            let gap = half
                .u
                .iter()
                .zip(&whole.u)
                .chain(half.v.iter().zip(&whole.v))
                .fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                gap <= 1e-5 * speed,
                "n = {n}: half and whole differ by {gap} of {speed}"
            );
        }
    }
}

#[test]
fn spreading_conserves_total_force() {
    let mut f = Fluid::new(40, 0.005, 0.0, 1000.0);
    let points = [
        Vec2::new(0.0731, 0.1012),
        Vec2::new(0.1, 0.05),
        Vec2::new(0.0123, 0.187),
    ];
    let forces = [
        Vec2::new(0.3, -1.2),
        Vec2::new(-2.0, 0.7),
        Vec2::new(0.01, 0.5),
    ];
    spread(&mut f, &points, &forces);
    let area = f.h * f.h;
    let total = Vec2::new(f.force_u.iter().sum::<f32>(), f.force_v.iter().sum::<f32>()) * area;
    let expected: Vec2 = forces.iter().sum();
    assert!((total - expected).length() < 1e-5, "{total} vs {expected}");
}

#[test]
fn interpolation_and_spreading_are_adjoint() {
    // <J u, F> over points equals <u, S F> over the grid with the h² inner product.
    let mut f = swirl(24);
    let p = Vec2::new(0.0937, 0.1411);
    let force = Vec2::new(0.7, -0.3);
    let mut coupling = Coupling::default();
    coupling.locate(&f, &[p], &[]);
    let mut read = [Vec2::ZERO];
    coupling.interpolate(&f, &mut read);
    assert_eq!(
        read[0],
        f.velocity_at(p),
        "the coupling reads what the kernel reads"
    );
    let lhs = read[0].dot(force);
    coupling.spread(&mut f, &[force]);
    let area = f.h * f.h;
    let rhs: f32 = f.u.iter().zip(&f.force_u).map(|(u, g)| u * g).sum::<f32>() * area
        + f.v.iter().zip(&f.force_v).map(|(v, g)| v * g).sum::<f32>() * area;
    assert!(
        (lhs - rhs).abs() < 1e-6 * lhs.abs().max(1.0),
        "{lhs} vs {rhs}"
    );
}

#[test]
fn a_tracer_is_carried_by_the_faces_around_it() {
    // A linear flow, which bilinear sampling reproduces exactly inside the box: each
    // component read at its own staggered place, not half a cell off.
    let n = 16;
    let mut f = Fluid::new(n, 0.01, 1e-6, 1000.0);
    let flow = |x: f32, y: f32| Vec2::new(0.3 + 2.0 * x - 5.0 * y, -0.1 + 4.0 * x + 1.5 * y);
    for j in 0..n {
        for i in 0..=n {
            f.u[j * (n + 1) + i] = flow(i as f32 * f.h, (j as f32 + 0.5) * f.h).x;
        }
    }
    for j in 0..=n {
        for i in 0..n {
            f.v[j * n + i] = flow((i as f32 + 0.5) * f.h, j as f32 * f.h).y;
        }
    }
    for p in [
        Vec2::new(0.0437, 0.0911),
        Vec2::new(0.1, 0.05),
        Vec2::new(0.0123, 0.1477),
    ] {
        let (read, exact) = (f.tracer_velocity(p), flow(p.x, p.y));
        assert!(
            (read - exact).length() < 1e-5,
            "at {p}: {read} against {exact}"
        );
        // Where the kernel's stencil lies wholly inside, it reads the same linear flow.
        assert!(
            (f.velocity_at(p) - exact).length() < 1e-4,
            "the kernel at {p}"
        );
    }
    // Outside the box, the nearest faces': finite, never a panic.
    for p in [
        Vec2::new(-1.0, 0.05),
        Vec2::new(0.05, 9.0),
        Vec2::splat(f32::NAN),
    ] {
        let at = f.tracer_velocity(p);
        assert!(at.is_finite() || p.is_nan(), "at {p}: {at}");
    }
    let corner = f.tracer_velocity(Vec2::new(9.0, 9.0));
    assert_eq!(
        corner,
        Vec2::new(f.u[n * (n + 1) - 1], f.v[(n + 1) * n - 1])
    );
}

#[test]
fn uniform_flow_survives_advection() {
    let n = 32;
    let mut f = Fluid::new(n, 0.01, 0.0, 1000.0);
    for j in 0..n {
        for i in 1..n {
            f.u[j * (n + 1) + i] = 0.05;
        }
    }
    f.advect(0.1);
    // Away from the walls, uniform flow is a fixed point of semi-Lagrangian advection.
    let mid = f.u[(n / 2) * (n + 1) + n / 2];
    assert!((mid - 0.05).abs() < 1e-6, "{mid}");
}

#[test]
fn viscosity_dissipates_energy() {
    let mut f = swirl(32);
    f.project();
    f.nu = 1e-4;
    let e0 = f.kinetic_energy();
    f.diffuse(0.5);
    f.project();
    assert!(f.kinetic_energy() < e0);
    assert!(f.is_finite());
}

#[test]
fn viscosity_decays_a_mode_at_the_discrete_and_the_analytic_rate() {
    // u = sin(π·κ·i/n), uniform along y, vanishes on both side walls: an eigenmode of the
    // explicit sweep, which multiplies it by 1 − 4a·sin²(πκ/2n) with a = ν·dt/(h²·sweeps),
    // and of the continuum, where it decays as exp(−ν·k²·t), k = πκ/(n·h).
    let (n, h, kappa) = (32, 0.01, 2.0);
    let mut f = Fluid::new(n, h, 0.0, 1000.0);
    for j in 0..n {
        for i in 0..=n {
            f.u[j * (n + 1) + i] = (std::f32::consts::PI * kappa * i as f32 / n as f32).sin();
        }
    }
    f.nu = 2e-4;
    let (dt, steps) = (0.25, 10);
    let alpha = f.nu * dt / (h * h);
    let sweeps = (alpha / 0.2).ceil();
    let e0 = f.kinetic_energy();
    for _ in 0..steps {
        f.diffuse(dt);
    }
    let decay = (f.kinetic_energy() / e0).ln();
    let theta = std::f32::consts::PI * kappa / (2.0 * n as f32);
    let per_sweep = 1.0 - 4.0 * alpha / sweeps * theta.sin().powi(2);
    let discrete = 2.0 * sweeps * steps as f32 * per_sweep.ln();
    let k = std::f32::consts::PI * kappa / (n as f32 * h);
    let analytic = -2.0 * f.nu * k * k * dt * steps as f32;
    println!("ln(E/E0): measured {decay}, discrete {discrete}, analytic {analytic}");
    assert!(
        (decay / discrete - 1.0).abs() < 1e-3,
        "measured {decay}, the sweep's exact factor {discrete}"
    );
    assert!(
        (decay / analytic - 1.0).abs() < 0.02,
        "measured {decay}, exp(-2νk²t) {analytic}"
    );
}
