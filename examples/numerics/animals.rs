//! Issue 28's checks of an animal, on one species at a series of sizes, in seconds: the
//! measures of `tests/slice.rs` (its stroke, its refill, its margin, its sweep, its
//! stagger and its fringe at each size, and how the stroke spreads across the sizes), for a
//! candidate calibration (`--set field=value`, `--steps f`) before the long tests are run
//! on it. Each line says which check of the tests it reads, and its bounds.

use crate::common::refuse;
use crate::run::{distance_in, parallel, slice_in_steps, spread, swim_in_steps};
use bevy_jellyfish::Species;

/// What one size of the animal does.
struct Size {
    /// Cycles 12–20 from rest: D a stroke, the slowest speed while it refills (D/s), the
    /// margin's least width over its rest width, and the share of the stroke it swims
    /// while it refills (its coast and its stopping vortex's push).
    stroke: f32,
    refill: f32,
    margin: f32,
    refilling: f32,
    /// The same stroke without its fringe.
    bare: f32,
    /// Cycles 20–40: its own fringe, none, one three times as long; staggered and unison.
    fringe: [f32; 3],
    unison: f32,
    /// The sweep's peak and its bell's twice as stiff (none where that bell is not a
    /// valid species: too stiff to bend, grown large), over its own rate; its longest
    /// 20 s over the shorter of its two ends'.
    peak: f32,
    stiffer: Option<f32>,
    above_ends: f32,
    /// How far the sweep went, times its own rate (2.5 unless the species' limit on the
    /// pulse rate stopped it).
    swept_to: f32,
}

/// The scorecard of `sizes` (one animal, resized), each taking `steps` times its own
/// steps per cycle.
pub fn animals(sizes: &[Species], steps: f32) {
    for s in sizes {
        if let Err(e) = s.validate() {
            refuse(&format!(
                "numerics animals: {} is not a valid species: {e}",
                s.name
            ));
        }
    }
    println!(
        "\n### {}: the animal's checks (`tests/slice.rs`), {steps}× its steps\n",
        sizes[0].name.split(' ').next().unwrap_or_default()
    );
    println!(
        "| size | D a stroke, bare (12–20) | slowest refill, D/s (> 0) | margin, least / rest | \
         swum refilling | sweep peak / own rate (0.75–1.5), stiffer | longest / ends (≥ 1.15) | \
         staggered / unison (≥ +20%) | its fringe slows it (5–30%), 3× (+5 more) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let runs: Vec<Size> = sizes.iter().map(|s| size(s, steps)).collect();
    for (s, r) in sizes.iter().zip(&runs) {
        let slower = |d: f32| 100.0 * (1.0 - d / r.fringe[1]);
        println!(
            "| {:.0} mm | {:.3}, {:.3} | {:+.3} | {:.2} | {:.0}% | {:.2}, {}{} | {:.2} | {:+.0}% | {:.1}%, {:.1}% |",
            1000.0 * s.diameter,
            r.stroke,
            r.bare,
            r.refill,
            r.margin,
            100.0 * r.refilling,
            r.peak,
            r.stiffer
                .map_or("(twice as stiff: invalid)".into(), |f| format!("{f:.2}")),
            if r.swept_to < 2.5 {
                format!(" (swept to {:.1}×, the pulse rate's limit)", r.swept_to)
            } else {
                String::new()
            },
            r.above_ends,
            100.0 * (r.fringe[0] / r.unison - 1.0),
            slower(r.fringe[0]),
            slower(r.fringe[2]),
        );
    }
    if sizes.len() < 2 {
        return;
    }
    let strokes: Vec<f32> = runs.iter().map(|r| r.stroke).collect();
    let bare: Vec<f32> = runs.iter().map(|r| r.bare).collect();
    let speed = |i: usize| strokes[i] * sizes[i].diameter * sizes[i].contraction_frequency;
    let last = sizes.len() - 1;
    let exponent = (speed(last) / speed(0)).ln() / (sizes[last].diameter / sizes[0].diameter).ln();
    println!(
        "\nAcross the sizes: a stroke spreads {:.1}% (≤ 20%), bare {:.1}% (≤ 15%); speed as the \
         diameter to the {exponent:.2} (0.2–0.9).",
        100.0 * spread(&strokes),
        100.0 * spread(&bare),
    );
}

/// Every run of one size, on every core.
fn size(s: &Species, steps: f32) -> Size {
    let with = |f: &dyn Fn(&mut Species)| {
        let mut v = s.clone();
        f(&mut v);
        v
    };
    // A sixth to two and a half times its own rate, as far as a species may beat (a small
    // bell's own rate is high: its sweep stops at the limit).
    let natural = s.natural_pulse_rate();
    let at = |f: f32| Species {
        contraction_frequency: f,
        ..s.clone()
    };
    let rates: Vec<f32> = (1..=15)
        .map(|k| natural * k as f32 / 6.0)
        .filter(|&f| at(f).validate().is_ok())
        .collect();
    let stiffer = Some(with(&|v| v.elastic_modulus *= 2.0)).filter(|v| v.validate().is_ok());
    let mut jobs = vec![
        Job::Stroke(s.clone()),
        Job::Stroke(with(&|v| v.tentacle_length = 0.0)),
    ];
    for k in [1.0, 0.0, 3.0] {
        jobs.push(Job::Cycles(with(&|v| v.tentacle_length *= k)));
    }
    jobs.push(Job::Cycles(with(&|v| v.expansion_stagger = 0.0)));
    for base in std::iter::once(s).chain(&stiffer) {
        for &f in &rates {
            jobs.push(Job::Seconds(Species {
                contraction_frequency: f,
                ..base.clone()
            }));
        }
    }
    let out = parallel(jobs, |job| job.run(steps));
    let sweep = |at: usize| &out[at..at + rates.len()];
    let own = sweep(6);
    let longest = own.iter().map(|r| r[0]).fold(f32::MIN, f32::max);
    Size {
        stroke: out[0][0],
        refill: out[0][1],
        margin: out[0][2],
        refilling: out[0][3],
        bare: out[1][0],
        fringe: [out[2][0], out[3][0], out[4][0]],
        unison: out[5][0],
        peak: peak(&rates, own) / natural,
        stiffer: stiffer.map(|_| peak(&rates, sweep(6 + rates.len())) / natural),
        above_ends: longest / own[0][0].max(own[rates.len() - 1][0]),
        swept_to: rates[rates.len() - 1] / natural,
    }
}

enum Job {
    /// Cycles 12–20 from rest: stroke, slowest refill, least margin.
    Stroke(Species),
    /// Cycles 20–40: D a stroke.
    Cycles(Species),
    /// The distance in 20 s, diameters (the paper's Fig. 5 measure).
    Seconds(Species),
}

impl Job {
    fn run(&self, steps: f32) -> [f32; 4] {
        match self {
            Job::Stroke(s) => stroke_and_refill(s, steps),
            Job::Cycles(s) => [
                swim_in_steps(s, steps, 1.0 / 60.0, 20, 40).mean(),
                0.0,
                0.0,
                0.0,
            ],
            Job::Seconds(s) => [distance_in(s, steps, 20.0), 0.0, 0.0, 0.0],
        }
    }
}

/// Cycles 12–20 from rest at 60 Hz frames: D a stroke, the slowest speed while the bell
/// refills (D/s), the margin's least width over its rest width, and the share of the
/// stroke swum after the contraction.
fn stroke_and_refill(s: &Species, steps: f32) -> [f32; 4] {
    let (from, to) = (12, 20);
    let mut sim = slice_in_steps(s, steps);
    let width = |b: &[glam::Vec2]| (b[b.len() - 1] - b[0]).length();
    let rest = width(sim.bell_points());
    let (share, d) = (s.contraction_share(), s.diameter);
    let (mut start, mut end, mut slowest, mut least) = (0.0, 0.0, f32::MAX, f32::MAX);
    let mut refilling = 0.0;
    let (mut time, mut distance) = (0.0f32, 0.0f32);
    while sim.cycle() < to {
        sim.advance_with(1.0 / 60.0, |sim| {
            let (x, t, cycle) = (sim.swim_distance() / d, sim.time(), sim.cycle());
            if sim.phase() == 0.0 && cycle == from {
                start = x;
            }
            if sim.phase() == 0.0 && cycle == to {
                end = x;
            }
            if (from..to).contains(&cycle) {
                least = least.min(width(sim.bell_points()) / rest);
                if sim.phase() > share {
                    slowest = slowest.min((x - distance) / (t - time));
                }
                // The frame that ends the cycle (phase 0) closes its refill.
                if sim.phase() > share || sim.phase() == 0.0 {
                    refilling += x - distance;
                }
            }
            (time, distance) = (t, x);
        });
    }
    let stroke = (end - start) / (to - from) as f32;
    [
        stroke,
        slowest,
        least,
        refilling / (to - from) as f32 / stroke,
    ]
}

/// Where `distances` (one per frequency, evenly spaced) peak: the vertex of the parabola
/// through the longest and its neighbours, as the tests read it.
fn peak(frequencies: &[f32], runs: &[[f32; 4]]) -> f32 {
    let d: Vec<f32> = runs.iter().map(|r| r[0]).collect();
    let (i, best) = d
        .iter()
        .enumerate()
        .fold((0, f32::MIN), |m, (i, &x)| if x > m.1 { (i, x) } else { m });
    if i == 0 || i + 1 == d.len() {
        return frequencies[i];
    }
    let curvature = d[i - 1] - 2.0 * best + d[i + 1];
    if curvature >= 0.0 {
        return frequencies[i];
    }
    let step = frequencies[i + 1] - frequencies[i];
    frequencies[i] + 0.5 * (d[i - 1] - d[i + 1]) / curvature * step
}
