//! The limits' cost model against measured slices: every shipped species and the paper's
//! model, in both slice geometries, with each advection scheme, on grids from 40 to 160,
//! each run timed (the least of `--repeat` runs of `--cycles` strokes), beside what
//! `limits::simulation_cost` estimates for it. Then the three prices (per cell, per cell
//! and viscosity sweep, per body point) that fit the runs best on their relative error,
//! and those raised by half, the margin the shipped constants keep over the fit.
//!
//! Run it on the reference machine with nothing else running: it times wall clock on one
//! core.
//!
//! `cargo run --release --no-default-features --example cost_fit -- [--cycles 3] [--repeat 2] [--grids 40,60,80,100,120,160]`

#[path = "common/species.rs"]
mod common;

use bevy_jellyfish::species::Advection;
use bevy_jellyfish::species::limits::{simulation_cost, simulation_cost_terms};
use bevy_jellyfish::{SliceGeometry, SliceSim, Species};
use common::shipped_species;
use std::time::Instant;

/// One configuration, timed.
struct Timed {
    label: String,
    /// What the cost model counts in a simulated second: cells, cell sweeps, points.
    terms: [f64; 3],
    /// Seconds of one core per simulated second, measured.
    measured: f64,
    /// The same, estimated by the shipped constants.
    estimated: f64,
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
    };
    let cycles: u32 = flag("--cycles").and_then(|v| v.parse().ok()).unwrap_or(3);
    let repeat: u32 = flag("--repeat").and_then(|v| v.parse().ok()).unwrap_or(2);
    let grids: Vec<u32> = flag("--grids")
        .map(|v| v.split(',').filter_map(|g| g.parse().ok()).collect())
        .unwrap_or_else(|| vec![40, 60, 80, 100, 120, 160]);
    let mut species = shipped_species();
    species.push(Species::paper());
    // Water ten and a hundred times as viscous, where the explicit viscosity takes more
    // sweeps a step than the shipped species' one: the sweeps' price apart from the cells'.
    for factor in [10.0, 100.0] {
        let base = Species::aurelia();
        species.push(Species {
            name: format!("{} in water {factor}× as viscous", base.name),
            viscosity: base.viscosity * factor,
            ..base
        });
    }

    println!(
        "| species | geometry | advection | grid | cells, sweeps, points a second | measured ms/s | estimated ms/s | measured / estimated |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let mut runs = Vec::new();
    for base in &species {
        for geometry in SliceGeometry::ALL {
            for advection in Advection::ALL {
                for &grid in &grids {
                    let s = Species {
                        slice_geometry: geometry,
                        advection,
                        grid_resolution: grid,
                        ..base.clone()
                    };
                    let label = format!("{} | {geometry:?} | {advection:?} | {grid}", s.name);
                    let Some(measured) = (0..repeat)
                        .filter_map(|_| time(&s, cycles))
                        .reduce(f64::min)
                    else {
                        println!("| {label} | | refused or recovered | | |");
                        continue;
                    };
                    let (estimated, terms) = (simulation_cost(&s), simulation_cost_terms(&s));
                    println!(
                        "| {label} | {:.3e}, {:.3e}, {:.3e} | {:.2} | {:.2} | {:.2} |",
                        terms[0],
                        terms[1],
                        terms[2],
                        1e3 * measured,
                        1e3 * estimated,
                        measured / estimated
                    );
                    runs.push(Timed {
                        label,
                        terms,
                        measured,
                        estimated,
                    });
                }
            }
        }
    }
    report(&runs);
}

/// Seconds of one core per simulated second over `cycles` strokes from rest, 60 Hz frames;
/// `None` where the species is refused or the slice had to recover.
fn time(s: &Species, cycles: u32) -> Option<f64> {
    let mut sim = SliceSim::new(s).ok()?;
    let seconds = cycles as f64 * s.period() as f64;
    let frame = 1.0 / 60.0;
    let frames = (seconds / frame as f64).ceil() as u32;
    let clock = Instant::now();
    for _ in 0..frames {
        sim.advance(frame);
    }
    let took = clock.elapsed().as_secs_f64();
    (sim.recoveries() == 0).then_some(took / (frames as f64 * frame as f64))
}

/// The fit and the shipped constants' margins.
fn report(runs: &[Timed]) {
    let ratios = |price: &dyn Fn(&Timed) -> f64| {
        let r: Vec<f64> = runs.iter().map(|t| t.measured / price(t)).collect();
        let (lo, hi) = r
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(*x), hi.max(*x)));
        (lo, hi)
    };
    let (lo, hi) = ratios(&|t| t.estimated);
    println!(
        "\n{} runs; measured / estimated by the shipped constants: {lo:.2} to {hi:.2}",
        runs.len()
    );
    let Some(fit) = relative_fit(runs) else {
        println!("no fit: the runs do not tell the three prices apart");
        return;
    };
    let raised = fit.map(|c| 1.5 * c);
    let priced =
        |c: [f64; 3]| move |t: &Timed| c.iter().zip(&t.terms).map(|(c, x)| c * x).sum::<f64>();
    let (flo, fhi) = ratios(&priced(fit));
    let (rlo, rhi) = ratios(&priced(raised));
    println!(
        "fitted on the relative error: per cell {:.3e} s, per cell sweep {:.3e} s, per point {:.3e} s; \
         measured / fitted {flo:.2} to {fhi:.2}",
        fit[0], fit[1], fit[2]
    );
    println!(
        "raised by half: per cell {:.3e} s, per cell sweep {:.3e} s, per point {:.3e} s; \
         measured / estimated {rlo:.2} to {rhi:.2}",
        raised[0], raised[1], raised[2]
    );
    let worst = runs.iter().max_by(|a, b| {
        (a.measured / priced(raised)(a)).total_cmp(&(b.measured / priced(raised)(b)))
    });
    if let Some(w) = worst {
        println!("dearest against the raised prices: {}", w.label);
    }
}

/// The prices `c` minimising `Σ (c·terms / measured − 1)²`: least squares on the relative
/// error, so the cheap runs count as much as the dear ones. `None` if the normal
/// equations are singular.
fn relative_fit(runs: &[Timed]) -> Option<[f64; 3]> {
    // Each column scaled to a mean of one, so the normal equations are well conditioned.
    let mut scale = [0.0f64; 3];
    for t in runs {
        for (s, x) in scale.iter_mut().zip(&t.terms) {
            *s += x / t.measured / runs.len() as f64;
        }
    }
    let mut a = [[0.0f64; 3]; 3];
    let mut b = [0.0f64; 3];
    for t in runs {
        let row: [f64; 3] = std::array::from_fn(|i| t.terms[i] / t.measured / scale[i]);
        for i in 0..3 {
            b[i] += row[i];
            for j in 0..3 {
                a[i][j] += row[i] * row[j];
            }
        }
    }
    let y = solve3(a, b)?;
    Some(std::array::from_fn(|i| y[i] / scale[i]))
}

/// `a·x = b` by Cramer's rule.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    if d.abs() < 1e-300 || !d.is_finite() {
        return None;
    }
    let mut x = [0.0; 3];
    for (k, x) in x.iter_mut().enumerate() {
        let mut m = a;
        for i in 0..3 {
            m[i][k] = b[i];
        }
        *x = det(m) / d;
    }
    Some(x)
}
