//! The axisymmetric fluid on its own: projection, spreading, the viscous operator against
//! the textbook's pipe flow and Bessel modes.

use super::*;
use crate::sim::coupling::Coupling;
use glam::Vec2;

/// An axisymmetric fluid with some symmetric, divergent flow in it.
fn swirl(n: usize) -> Fluid {
    let mut f = super::tests::swirl(n);
    f.set_geometry(SliceGeometry::Axisymmetric);
    f.symmetrise();
    f
}

/// The mirror image of a point about the fluid's axis.
fn mirrored(f: &Fluid, p: Vec2) -> Vec2 {
    Vec2::new(2.0 * f.axis() - p.x, p.y)
}

#[test]
fn projection_leaves_no_r_weighted_divergence() {
    for n in [16, 63, 64, 100] {
        let mut f = swirl(n);
        f.project();
        let rel = f.h * f.divergence_max() / f.speed_max();
        assert!(rel <= 1e-4, "n = {n}: h·max|div|/max|u| = {rel}");
        // Mirror-symmetric: no radial velocity through the axis, axial velocity even.
        let c = n / 2;
        for j in 0..n {
            let row = &f.u[j * (n + 1)..][..n + 1];
            assert_eq!(row[c], -row[c + 1], "n = {n}: u odd about the axis");
        }
    }
}

/// The axial force per radian the grid holds: each face's density times its volume per
/// radian, `r·h²`, over the whole mirrored grid (which holds every ring twice).
fn axial_force(f: &Fluid) -> f32 {
    let rings = f.rings().unwrap();
    let n = f.n;
    let sum: f32 = f
        .force_v
        .chunks_exact(n)
        .flat_map(|row| row.iter().zip(&rings.cell).map(|(g, r)| g * r))
        .sum();
    0.5 * sum * f.h * f.h
}

#[test]
fn ring_forces_spread_exactly_even_across_the_axis() {
    let mut f = Fluid::new(41, 0.005, 0.0, 1000.0);
    f.set_geometry(SliceGeometry::Axisymmetric);
    let axis = f.axis();
    // Rings far out, a cell out and a third of a cell from the axis: the kernel of the
    // last two reaches across it, and what lands there is the same ring's.
    let points = [
        Vec2::new(axis + 0.061, 0.101),
        Vec2::new(axis + 0.005, 0.05),
        Vec2::new(axis + 0.0017, 0.15),
    ];
    let forces = [
        Vec2::new(0.3, -1.2),
        Vec2::new(-2.0, 0.7),
        Vec2::new(0.01, 0.5),
    ];
    let mut coupling = Coupling::default();
    let both: Vec<Vec2> = points.iter().flat_map(|p| [*p, mirrored(&f, *p)]).collect();
    let mirrored_forces: Vec<Vec2> = forces
        .iter()
        .flat_map(|g| [*g, Vec2::new(-g.x, g.y)])
        .collect();
    coupling.locate(&f, &both, &[]);
    coupling.spread(&mut f, &mirrored_forces);
    let expected: f32 = forces.iter().map(|g| g.y).sum();
    let total = axial_force(&f);
    assert!(
        (total - expected).abs() < 1e-5,
        "axial force per radian {total} vs {expected}"
    );
}

#[test]
fn a_ring_on_the_axis_spreads_as_a_point_and_a_far_one_as_a_ring() {
    // Spread by ring radius, a ring on the axis put four times the kernel's share of
    // force density on the axis column's faces against one column out (the disc's
    // volume h/4 against h): a density ∝ 1/r, which drove a jet along the axis as narrow
    // as the grid. Weighed by volume near the axis it is the kernel's own profile.
    // A ring and its mirror image, each an axial newton per radian.
    let spread = |p: Vec2, f: &mut Fluid| {
        let mut coupling = Coupling::default();
        coupling.locate(f, &[p, mirrored(f, p)], &[]);
        coupling.spread(f, &[Vec2::Y, Vec2::Y]);
    };
    let mut f = Fluid::new(41, 0.005, 0.0, 1000.0);
    f.set_geometry(SliceGeometry::Axisymmetric);
    let (n, axis) = (f.n, f.axis());
    spread(Vec2::new(axis, 0.1), &mut f);
    let row = 20; // the point's row of `v` faces: y = 0.1 = 20·h
    let density = |column: usize| f.force_v[row * n + column];
    let (on, next) = (density(n / 2), density(n / 2 + 1));
    // The kernel's own weights there, read on a planar grid.
    let kernel = Fluid::new(41, 0.005, 0.0, 1000.0).stencil(Component::V, Vec2::new(axis, 0.1));
    let (centre, beside) = {
        let weights: Vec<(usize, f32)> = kernel.iter().filter(|(i, _)| i / n == row).collect();
        (weights[1].1, weights[0].1)
    };
    assert!(
        (on / next - centre / beside).abs() < 1e-4,
        "on the axis {on}, a column out {next}: {} where the kernel's is {}",
        on / next,
        centre / beside
    );
    assert!((axial_force(&f) - 1.0).abs() < 1e-5, "{}", axial_force(&f));
    // A ring twice the kernel's reach out spreads by its radius, as before: 1/r across.
    let mut g = Fluid::new(41, 0.005, 0.0, 1000.0);
    g.set_geometry(SliceGeometry::Axisymmetric);
    let far = Vec2::new(axis - 0.04, 0.1);
    spread(far, &mut g);
    let planar = Fluid::new(41, 0.005, 0.0, 1000.0).stencil(Component::V, far);
    let taps: Vec<(usize, f32)> = g.stencil(Component::V, far).iter().collect();
    assert_eq!(
        taps,
        planar.iter().collect::<Vec<_>>(),
        "the kernel's own taps"
    );
    let rings = g.rings().unwrap();
    for (face, w) in taps {
        let expected = w / (rings.cell[face % n] * g.h * g.h);
        let image = face - face % n + Component::V.mirrored_column(face % n, n).unwrap();
        for face in [face, image] {
            let got = g.force_v[face];
            assert!(
                (got - expected).abs() <= 1e-6 * expected,
                "face {face}: {got}"
            );
        }
    }
}

#[test]
fn a_stencil_the_axis_test_passes_over_is_one_the_reweighing_leaves_alone() {
    // `Fluid::locate` reweighs a stencil near the axis only where
    // `Rings::within_reach_of_axis` says it may reach there: a bound on the taps, which
    // must never skip a stencil the reweighing would have changed. Even and odd grids,
    // the kernel at several widths, both components, points across the box and past it.
    for (n, stretch) in [
        (41, 1.0),
        (40, 1.0),
        (60, 1.42),
        (61, 2.7),
        (40, 4.0),
        (16, 1.0),
    ] {
        let mut f = Fluid::new(n, 0.005, 0.0, 1000.0);
        f.set_geometry(SliceGeometry::Axisymmetric);
        f.kernel_stretch = stretch;
        let reach = crate::sim::kernel::reach(f.kernel, stretch) * f.h;
        let rings = f.rings().unwrap();
        let (mut skipped, mut changed) = (0, 0);
        for k in -40..=(n as i32 * 10 + 40) {
            let p = Vec2::new(k as f32 * f.h / 10.0, 0.0513);
            for c in [Component::U, Component::V] {
                let mut s = crate::sim::kernel::Stencil::default();
                let (at, faces) = f.in_faces(c, p);
                s.locate(f.kernel, at, faces, stretch);
                let before: Vec<(usize, f32)> = s.iter().collect();
                rings.weigh_by_volume_near_axis(c, &mut s, reach);
                let moved = s.iter().collect::<Vec<_>>() != before;
                changed += usize::from(moved);
                if !rings.within_reach_of_axis(p.x, reach) {
                    skipped += 1;
                    assert!(!moved, "n {n}, stretch {stretch}, {c:?} at x = {}", p.x);
                }
            }
        }
        assert!(
            skipped > 0 && changed > 0,
            "n {n}: {skipped} skipped, {changed} changed"
        );
    }
}

#[test]
fn points_past_the_axis_out_of_reach_are_their_partners_mirrors() {
    let mut f = swirl(41);
    f.project();
    let axis = f.axis();
    // Pairs far out (read as mirrors) and within a kernel of the axis (located).
    let before: Vec<Vec2> = [12.0, 6.0, 2.5, 1.1, 0.1]
        .iter()
        .enumerate()
        .map(|(k, cells)| Vec2::new(axis - cells * f.h, (11.3 + 1.7 * k as f32) * f.h))
        .collect();
    let mut points = before.clone();
    points.extend(before.iter().map(|p| mirrored(&f, *p)));
    let partners: Vec<Option<usize>> = (0..points.len())
        .map(|i| (i >= before.len()).then(|| i - before.len()))
        .collect();
    let forces: Vec<Vec2> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let g = Vec2::new(0.3 - 0.1 * (i % 5) as f32, 0.7 + 0.05 * (i % 5) as f32);
            if p.x > axis { Vec2::new(-g.x, g.y) } else { g }
        })
        .collect();
    let (mut all, mut half) = (Coupling::default(), Coupling::default());
    all.locate(&f, &points, &[]);
    half.locate(&f, &points, &partners);
    assert_eq!(half.mirrored(), (5, 3), "every partner, three within reach");
    let (mut read_all, mut read_half) = (vec![Vec2::ZERO; 10], vec![Vec2::ZERO; 10]);
    all.interpolate(&f, &mut read_all);
    half.interpolate(&f, &mut read_half);
    let scale = f.speed_max();
    for (a, b) in read_all.iter().zip(&read_half) {
        assert!((*a - *b).abs().max_element() <= 1e-5 * scale, "{a} vs {b}");
    }
    // What reaches the solved half is the same, to rounding (a partner's stencil mirrored
    // is the point's own, computed from a position mirrored in f32); the rest is dropped.
    let mut g = f.clone();
    all.spread(&mut f, &forces);
    half.spread(&mut g, &forces);
    let (n, solved) = (f.n, f.rings().unwrap().solved);
    for (field, other, row, columns) in [
        (&f.force_u, &g.force_u, n + 1, solved + 1),
        (&f.force_v, &g.force_v, n, solved),
    ] {
        let scale = field.iter().fold(0.0f32, |m, x| m.max(x.abs()));
        assert!(scale > 0.0);
        for (a, b) in field.chunks_exact(row).zip(other.chunks_exact(row)) {
            for (x, y) in a[..columns].iter().zip(&b[..columns]) {
                assert!((x - y).abs() <= 1e-5 * scale, "{x} vs {y}");
            }
        }
    }
}

#[test]
fn interpolation_and_spreading_are_adjoint_in_the_r_weighted_product() {
    // <J u, F> over the rings equals <u, S F> over the grid with the r·h² inner product.
    let mut f = swirl(25);
    f.project();
    let p = Vec2::new(f.axis() + 0.013, 0.1411);
    let force = Vec2::new(0.7, -0.3);
    let points = [p, mirrored(&f, p)];
    let forces = [force, Vec2::new(-force.x, force.y)];
    let mut coupling = Coupling::default();
    coupling.locate(&f, &points, &[]);
    let mut read = [Vec2::ZERO; 2];
    coupling.interpolate(&f, &mut read);
    let lhs = read[0].dot(forces[0]) + read[1].dot(forces[1]);
    coupling.spread(&mut f, &forces);
    let rings = f.rings().unwrap();
    let weighted = |field: &[f32], force: &[f32], radii: &[f32]| -> f32 {
        field
            .chunks_exact(radii.len())
            .zip(force.chunks_exact(radii.len()))
            .flat_map(|(a, b)| a.iter().zip(b).zip(radii).map(|((a, b), r)| a * b * r))
            .sum()
    };
    let rhs = (weighted(&f.u, &f.force_u, &rings.face) + weighted(&f.v, &f.force_v, &rings.cell))
        * f.h
        * f.h;
    assert!(
        (lhs - rhs).abs() < 1e-5 * lhs.abs().max(1.0),
        "{lhs} vs {rhs}"
    );
}

/// The first zero of the Bessel function J₁ (the first extremum of J₀).
const J1_ZERO: f64 = 3.831_705_970_207_512;

/// J₀ and J₁ by their power series (enough terms for arguments below 5).
fn bessel(x: f64) -> (f64, f64) {
    let (mut j0, mut j1) = (0.0, 0.0);
    let (mut t0, mut t1) = (1.0, 0.5 * x);
    for k in 0..30 {
        j0 += t0;
        j1 += t1;
        let k = k as f64;
        t0 *= -(0.25 * x * x) / ((k + 1.0) * (k + 1.0));
        t1 *= -(0.25 * x * x) / ((k + 1.0) * (k + 2.0));
    }
    (j0, j1)
}

/// Copies the top row of `v` onto the inflow face: the ends of a long pipe, where the
/// flow is fully developed, instead of the slice's inflow.
fn hold_fully_developed(f: &mut Fluid) {
    let n = f.n;
    let (below, top) = f.v.split_at_mut(n * n);
    top.copy_from_slice(&below[(n - 1) * n..]);
}

/// Diffuses a mode uniform along the axis for `sweeps` single sweeps and returns the
/// measured decay rate of its amplitude (1/s) in the middle row, against `rate`.
fn decay_rate(n: usize, set: impl Fn(&mut Fluid, f32), read: impl Fn(&Fluid) -> f32) -> f32 {
    let h = 0.001;
    let mut f = Fluid::new(n, h, 1e-6, 1000.0);
    f.set_geometry(SliceGeometry::Axisymmetric);
    set(&mut f, (n / 2) as f32 * h + 0.5 * h);
    let dt = 0.09 * h * h / f.nu;
    let a0 = read(&f);
    let sweeps = 2000;
    for _ in 0..sweeps {
        f.diffuse(dt);
        hold_fully_developed(&mut f);
    }
    -(read(&f) / a0).ln() / (sweeps as f32 * dt)
}

#[test]
fn a_bessel_mode_of_axial_flow_decays_at_its_rate() {
    // v = J₀(k r), k = j₁,₁/R: free slip at the wall r = R (∂v/∂r = 0), an eigenmode of
    // the r-weighted Laplacian decaying as exp(−ν k² t). The scheme is second order in h:
    // with R 31.5 cells the rate is off by about (k h)²/12 ≈ 1e-3; the open top drifts
    // in less than 8 cells in the time measured, 23 from the middle row.
    let n = 63;
    let c = n / 2;
    let read = |f: &Fluid| f.v[(n / 2) * n + c];
    let set = |f: &mut Fluid, radius: f32| {
        let k = J1_ZERO / radius as f64;
        for j in 0..=n {
            for i in 0..n {
                let r = (i as f64 - c as f64) * f.h as f64;
                f.v[j * n + i] = bessel(k * r.abs()).0 as f32;
            }
        }
    };
    let measured = decay_rate(n, set, read);
    let radius = (c as f64 + 0.5) * 0.001;
    let expected = (1e-6 * (J1_ZERO / radius).powi(2)) as f32;
    let error = measured / expected - 1.0;
    println!("J₀ mode: decay rate {measured:.6} 1/s, exact {expected:.6} ({error:+.2e})");
    assert!(error.abs() < 5e-3, "{measured} vs {expected}");
}

#[test]
fn a_bessel_mode_of_radial_flow_decays_at_its_rate_hoop_term_included() {
    // u = J₁(k r), k = j₁,₁/R: zero at the axis and on the wall, an eigenmode of
    // ∇²u − u/r² (the hoop term) decaying as exp(−ν k² t); without the hoop term it
    // would not be a mode at all.
    let n = 63;
    let c = n / 2;
    let read = |f: &Fluid| f.u[(n / 2) * (n + 1) + c / 2];
    let set = |f: &mut Fluid, radius: f32| {
        let k = J1_ZERO / radius as f64;
        for j in 0..n {
            for i in 0..=n {
                let x = (i as f64 - c as f64 - 0.5) * f.h as f64;
                f.u[j * (n + 1) + i] = (x.signum() * bessel(k * x.abs()).1) as f32;
            }
        }
        f.enforce_walls();
    };
    let measured = decay_rate(n, set, read);
    let radius = (c as f64 + 0.5) * 0.001;
    let expected = (1e-6 * (J1_ZERO / radius).powi(2)) as f32;
    let error = measured / expected - 1.0;
    println!("J₁ mode: decay rate {measured:.6} 1/s, exact {expected:.6} ({error:+.2e})");
    assert!(error.abs() < 1e-2, "{measured} vs {expected}");
}

#[test]
fn pipe_flow_reaches_poiseuille() {
    // A uniform pressure gradient G along a pipe with no-slip walls: from rest, the flow
    // settles to v = G(R² − r²)/4μ, centreline G·R²/4μ. The r-weighted operator is exact
    // on r², so what is left is the wall's ghost cell, second order: (h/R)² ≈ 0.4% at
    // 15.5 cells. The ends are held fully developed (the top row copied onto the inflow
    // face: a pipe, not the slice's channel).
    for n in [31, 63] {
        let h = 0.001;
        let (mu, rho, gradient) = (1e-3, 1000.0, 0.5);
        let mut f = Fluid::new(n, h, mu / rho, rho);
        f.set_geometry(SliceGeometry::Axisymmetric);
        f.rings.as_mut().unwrap().no_slip_wall = true;
        let c = n / 2;
        let radius = (c as f32 + 0.5) * h;
        let dt = 0.09 * h * h / f.nu;
        let settle = 2.5 * radius * radius / f.nu;
        let steps = (settle / dt) as usize;
        for _ in 0..steps {
            f.force_v.fill(gradient);
            f.force_in_rows(0..n + 1);
            f.apply_force(dt);
            hold_fully_developed(&mut f);
            f.diffuse(dt);
            hold_fully_developed(&mut f);
        }
        let centre = f.v[(n / 2) * n + c];
        let expected = gradient * radius * radius / (4.0 * mu);
        let error = centre / expected - 1.0;
        println!(
            "Poiseuille, R = {} cells: centreline {centre:.5} m/s, G·R²/4μ {expected:.5} ({error:+.2e})",
            c as f32 + 0.5
        );
        assert!(
            error.abs() < 4.0 * (h / radius).powi(2),
            "n = {n}: {centre} vs {expected}"
        );
    }
}
