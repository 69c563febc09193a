//! One slice swum and measured, and the tables' shared arithmetic.

use bevy_jellyfish::sim::clock::FixedClock;
use bevy_jellyfish::{SliceSim, Species};
use std::sync::Mutex;
use std::time::Instant;

pub struct Run {
    /// Distance per cycle, diameters, for cycles `from..to`.
    pub per_cycle: Vec<f32>,
    /// CPU seconds per simulated second.
    pub cost: f64,
    pub recoveries: u32,
    /// The subumbrella's least and greatest strain over cycles `from..to`
    /// ([`SliceSim::meridian_strain`]).
    pub meridian: (f32, f32),
}

impl Run {
    pub fn mean(&self) -> f32 {
        self.per_cycle.iter().sum::<f32>() / self.per_cycle.len().max(1) as f32
    }
    pub fn cv(&self) -> f32 {
        let m = self.mean();
        let var = self.per_cycle.iter().map(|x| (x - m).powi(2)).sum::<f32>()
            / self.per_cycle.len().max(1) as f32;
        var.sqrt() / m.abs()
    }
}

/// A slice of `species` taking `finer` times its fixed steps per cycle, rounded (a
/// measurement only: a shipped slice always takes its species' own steps; below 1, fewer).
pub fn slice_in_steps(species: &Species, finer: f32) -> SliceSim {
    let mut sim = SliceSim::new(species).expect("valid species");
    if finer != 1.0 {
        let steps = (SliceSim::steps_per_cycle(species) as f32 * finer).round() as u32;
        sim.set_clock(FixedClock::new(species.period(), steps.max(1)));
    }
    sim
}

/// Distance in `seconds` of swimming from rest, diameters, with `finer` times the
/// species' steps (the paper's Fig. 5 measure).
pub fn distance_in(species: &Species, finer: f32, seconds: f32) -> f32 {
    let mut sim = slice_in_steps(species, finer);
    while sim.time() < seconds {
        sim.advance(0.1);
    }
    sim.swim_distance() / species.diameter
}

/// Swims `species` with `advance(frame)` calls and records the distance at each cycle's
/// first step (exactly phase 0, whatever the frame rate).
pub fn swim(species: &Species, frame: f32, from: u32, to: u32) -> Run {
    swim_in_steps(species, 1.0, frame, from, to)
}

/// [`swim`] with `finer` times the species' fixed steps per cycle (a time-step convergence
/// check: a shipped slice always takes its species' own steps).
pub fn swim_in_steps(species: &Species, finer: f32, frame: f32, from: u32, to: u32) -> Run {
    let mut sim = slice_in_steps(species, finer);
    let mut boundaries = vec![0.0f64];
    let clock = Instant::now();
    let mut frames = 0u64;
    let mut meridian = (f32::MAX, f32::MIN);
    while boundaries.len() <= to as usize {
        frames += 1;
        sim.advance_with(frame, |sim| {
            if sim.phase() == 0.0 {
                boundaries.push(sim.swim_distance() as f64);
            }
            if boundaries.len() > from as usize {
                let strain = sim.meridian_strain();
                meridian = (meridian.0.min(strain), meridian.1.max(strain));
            }
        });
    }
    let cost = clock.elapsed().as_secs_f64() / (frames as f64 * frame as f64);
    let d = species.diameter as f64;
    Run {
        per_cycle: (from as usize..to as usize)
            .map(|c| ((boundaries[c + 1] - boundaries[c]) / d) as f32)
            .collect(),
        cost,
        recoveries: sim.recoveries(),
        meridian,
    }
}

/// Runs the jobs on every core, keeping their order.
pub fn parallel<T: Send + Sync, R: Send>(jobs: Vec<T>, f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let results: Mutex<Vec<Option<R>>> = Mutex::new((0..jobs.len()).map(|_| None).collect());
    let next = Mutex::new(0usize);
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                loop {
                    let i = {
                        let mut n = next.lock().unwrap();
                        *n += 1;
                        *n - 1
                    };
                    let Some(job) = jobs.get(i) else { break };
                    let r = f(job);
                    results.lock().unwrap()[i] = Some(r);
                }
            });
        }
    });
    results
        .into_inner()
        .unwrap()
        .into_iter()
        .map(|r| r.unwrap())
        .collect()
}

pub fn spread(values: &[f32]) -> f32 {
    let max = values.iter().copied().fold(f32::MIN, f32::max);
    let min = values.iter().copied().fold(f32::MAX, f32::min);
    let mean = values.iter().sum::<f32>() / values.len() as f32;
    (max - min) / mean.abs()
}

pub fn row(label: &str, runs: &[Run]) {
    let cells: Vec<String> = runs
        .iter()
        .map(|r| {
            let flag = if r.recoveries > 0 {
                format!(" ({}r)", r.recoveries)
            } else {
                String::new()
            };
            format!("{:.3} ± {:.0}%{flag}", r.mean(), 100.0 * r.cv())
        })
        .collect();
    let means: Vec<f32> = runs.iter().map(Run::mean).collect();
    println!(
        "| {label} | {} | {:.1}% |",
        cells.join(" | "),
        100.0 * spread(&means)
    );
}
