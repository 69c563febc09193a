//! Cost of the slice simulation, on one core, against the target in `docs/numerics.md`
//! ("Cost").
//!
//! - `coupled_step/N`: one fixed step of the default species (fluid + body + coupling) at
//!   grid N (60 is the default, ten cells per diameter; 100 the paper's grid);
//! - `axisymmetric_step/N`: the same in the r–z slice (`SliceGeometry::Axisymmetric`), at
//!   the same cells per diameter;
//! - `stam_step/N`: the baseline, a plain Stam fluid step written straightforwardly
//!   (collocated grid, semi-Lagrangian advection, 20 Gauss–Seidel sweeps);
//! - and, printed after the criterion runs: µs per step and per simulated second at the
//!   default grid and at 100, simulated seconds per wall-clock second, and the
//!   coupled/Stam cost ratio.
//!
//! `cargo bench --no-default-features --bench slice_step`

use bevy_jellyfish::{SliceGeometry, SliceSim, Species};
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Instant;

fn warmed_up(grid: u32, slice_geometry: SliceGeometry) -> SliceSim {
    let species = Species {
        grid_resolution: grid,
        slice_geometry,
        ..Species::aurelia()
    };
    let mut sim = SliceSim::new(&species).expect("default species is valid");
    // A stroke in, so the water moves as it does in use.
    sim.advance(species.period());
    sim
}

fn coupled_step(c: &mut Criterion) {
    for (name, geometry) in [
        ("coupled_step", SliceGeometry::Planar),
        ("axisymmetric_step", SliceGeometry::Axisymmetric),
    ] {
        let mut group = c.benchmark_group(name);
        for grid in [60, 90, 100] {
            let mut sim = warmed_up(grid, geometry);
            let dt = SliceSim::step_length(sim.species());
            group.bench_with_input(BenchmarkId::from_parameter(grid), &grid, |b, _| {
                // One fixed step's worth of time: exactly one step.
                b.iter(|| sim.advance(black_box(dt)))
            });
        }
        group.finish();
    }
}

fn stam_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("stam_step");
    for grid in [60, 90, 100] {
        let mut fluid = StamFluid::new(grid);
        group.bench_with_input(BenchmarkId::from_parameter(grid), &grid, |b, _| {
            b.iter(|| fluid.step(black_box(0.02)))
        });
    }
    group.finish();
}

/// Per step and per simulated second, and the cost of a coupled step against Stam's.
fn report(_: &mut Criterion) {
    println!("\n== slice simulation throughput (one core) ==");
    let default = Species::aurelia();
    let paper = Species::aurelia().with_paper_numerics();
    let fine = Species {
        grid_resolution: 100,
        ..Species::aurelia()
    };
    let rings = |s: &Species| Species {
        slice_geometry: SliceGeometry::Axisymmetric,
        ..s.clone()
    };
    let (default_rings, fine_rings) = (rings(&default), rings(&fine));
    for (label, species) in [
        ("default, grid 60 over 6 D", default),
        ("paper's grid 100 over 10 D", paper),
        ("default box at grid 100", fine),
        ("r-z, grid 60 over 6 D", default_rings),
        ("r-z, default box at grid 100", fine_rings),
    ] {
        let grid = species.grid_resolution;
        let mut sim = SliceSim::new(&species).expect("valid species");
        sim.advance(species.period());
        let (t0, steps0) = (sim.time(), sim.steps());
        let start = Instant::now();
        while start.elapsed().as_secs_f32() < 2.0 {
            sim.advance(sim.species().period());
        }
        let wall = start.elapsed().as_secs_f64();
        let steps = sim.steps() - steps0;
        let simulated = (sim.time() - t0) as f64;
        let mut stam = StamFluid::new(grid as usize);
        let baseline = time_of(|| stam.step(0.02));
        println!(
            "{label}: {:.0} us per step, {:.1} ms per simulated s, {:.0} simulated s per \
             wall s ({} steps of {:.1} ms); plain Stam step {:.0} us, ratio {:.2}",
            wall * 1e6 / steps as f64,
            wall * 1e3 / simulated,
            simulated / wall,
            steps,
            simulated * 1e3 / steps as f64,
            baseline * 1e6,
            wall / steps as f64 / baseline,
        );
    }
}

/// Mean wall time of `f` over 400 calls, s.
fn time_of(mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    for _ in 0..400 {
        f();
    }
    start.elapsed().as_secs_f64() / 400.0
}

/// Stam's "Real-Time Fluid Dynamics for Games" velocity step, as most people write it:
/// collocated N×N cells with a ghost border, advect, then project with a fixed 20
/// Gauss–Seidel sweeps.
struct StamFluid {
    n: usize,
    u: Vec<f32>,
    v: Vec<f32>,
    u0: Vec<f32>,
    v0: Vec<f32>,
    p: Vec<f32>,
    div: Vec<f32>,
}

impl StamFluid {
    fn new(n: usize) -> Self {
        let size = (n + 2) * (n + 2);
        let mut f = Self {
            n,
            u: vec![0.0; size],
            v: vec![0.0; size],
            u0: vec![0.0; size],
            v0: vec![0.0; size],
            p: vec![0.0; size],
            div: vec![0.0; size],
        };
        // A swirl so advection has work to do.
        for j in 1..=n {
            for i in 1..=n {
                let (x, y) = (i as f32 / n as f32 - 0.5, j as f32 / n as f32 - 0.5);
                let k = f.ix(i, j);
                f.u[k] = -y;
                f.v[k] = x;
            }
        }
        f
    }

    fn ix(&self, i: usize, j: usize) -> usize {
        ix(self.n, i, j)
    }

    fn step(&mut self, dt: f32) {
        std::mem::swap(&mut self.u, &mut self.u0);
        std::mem::swap(&mut self.v, &mut self.v0);
        self.advect(dt);
        self.project();
    }

    fn advect(&mut self, dt: f32) {
        let n = self.n;
        let dt0 = dt * n as f32;
        for j in 1..=n {
            for i in 1..=n {
                let k = self.ix(i, j);
                let x = (i as f32 - dt0 * self.u0[k]).clamp(0.5, n as f32 + 0.5);
                let y = (j as f32 - dt0 * self.v0[k]).clamp(0.5, n as f32 + 0.5);
                let (i0, j0) = (x as usize, y as usize);
                let (s1, t1) = (x - i0 as f32, y - j0 as f32);
                let (s0, t0) = (1.0 - s1, 1.0 - t1);
                let sample = |f: &[f32]| {
                    s0 * (t0 * f[ix(n, i0, j0)] + t1 * f[ix(n, i0, j0 + 1)])
                        + s1 * (t0 * f[ix(n, i0 + 1, j0)] + t1 * f[ix(n, i0 + 1, j0 + 1)])
                };
                self.u[k] = sample(&self.u0);
                self.v[k] = sample(&self.v0);
            }
        }
        self.set_bnd();
    }

    fn project(&mut self) {
        let n = self.n;
        let h = 1.0 / n as f32;
        for j in 1..=n {
            for i in 1..=n {
                let k = self.ix(i, j);
                self.div[k] = -0.5
                    * h
                    * (self.u[self.ix(i + 1, j)] - self.u[self.ix(i - 1, j)]
                        + self.v[self.ix(i, j + 1)]
                        - self.v[self.ix(i, j - 1)]);
                self.p[k] = 0.0;
            }
        }
        for _ in 0..20 {
            for j in 1..=n {
                for i in 1..=n {
                    let k = self.ix(i, j);
                    self.p[k] = (self.div[k]
                        + self.p[self.ix(i - 1, j)]
                        + self.p[self.ix(i + 1, j)]
                        + self.p[self.ix(i, j - 1)]
                        + self.p[self.ix(i, j + 1)])
                        / 4.0;
                }
            }
        }
        for j in 1..=n {
            for i in 1..=n {
                let k = self.ix(i, j);
                self.u[k] -= 0.5 * (self.p[self.ix(i + 1, j)] - self.p[self.ix(i - 1, j)]) / h;
                self.v[k] -= 0.5 * (self.p[self.ix(i, j + 1)] - self.p[self.ix(i, j - 1)]) / h;
            }
        }
        self.set_bnd();
    }

    /// Free-slip walls: normal component mirrored, tangential copied.
    fn set_bnd(&mut self) {
        let n = self.n;
        for i in 1..=n {
            let (a, b) = (self.ix(0, i), self.ix(1, i));
            self.u[a] = -self.u[b];
            self.v[a] = self.v[b];
            let (a, b) = (self.ix(n + 1, i), self.ix(n, i));
            self.u[a] = -self.u[b];
            self.v[a] = self.v[b];
            let (a, b) = (self.ix(i, 0), self.ix(i, 1));
            self.u[a] = self.u[b];
            self.v[a] = -self.v[b];
            let (a, b) = (self.ix(i, n + 1), self.ix(i, n));
            self.u[a] = self.u[b];
            self.v[a] = -self.v[b];
        }
    }
}

fn ix(n: usize, i: usize, j: usize) -> usize {
    i + (n + 2) * j
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(3));
    targets = coupled_step, stam_step, report
}
criterion_main!(benches);
