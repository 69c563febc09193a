//! The numerics tables of `docs/numerics.md`: how far a slice swims per cycle at different
//! frame rates, grids (each puts the bell at another offset to the cells) and resolutions,
//! for every shipped species.
//!
//! *Swim per cycle* is the mean distance per cycle in bell diameters over cycles 10–30;
//! *spread* of a set of runs is (max − min) / mean; *cv* is the cycle-to-cycle coefficient
//! of variation over the same cycles.
//!
//! `calibration` shows the paper's findings on [`Species::paper`].
//!
//! `fingerprint` runs every shipped species and the paper's model in both slice geometries
//! for `--to` cycles and prints a hash of every cycle's distance, bit for bit, and the
//! cost: a refactor meant to leave the physics alone must leave the hashes alone. With
//! `--species` (the paper's model is `paper`) and `--geometry planar|axisymmetric` it
//! runs only those, as a profiler wants.
//!
//! `cargo run --release --no-default-features --example numerics -- [frames|grids|convergence|stagger|timestep|calibration|fingerprint|all] [--from 10] [--to 30] [--species name] [--geometry name] [--set field=value ...] [--sizes 0.25,2,...]`
//!
//! `--sizes` runs each species resized to those multiples of its diameter, its pulse rate its
//! animal's at each size (`Species::resized`).

#[path = "common/species.rs"]
mod common;

use bevy_jellyfish::sim::clock::FixedClock;
use bevy_jellyfish::{SliceGeometry, SliceSim, Species};
use common::{overrides, shipped_species, with_overrides};
use std::sync::Mutex;
use std::time::Instant;

struct Run {
    /// Distance per cycle, diameters, for cycles `from..to`.
    per_cycle: Vec<f32>,
    /// CPU seconds per simulated second.
    cost: f64,
    recoveries: u32,
    /// The subumbrella's least and greatest strain over cycles `from..to`
    /// ([`SliceSim::meridian_strain`]).
    meridian: (f32, f32),
}

impl Run {
    fn mean(&self) -> f32 {
        self.per_cycle.iter().sum::<f32>() / self.per_cycle.len().max(1) as f32
    }
    fn cv(&self) -> f32 {
        let m = self.mean();
        let var = self.per_cycle.iter().map(|x| (x - m).powi(2)).sum::<f32>()
            / self.per_cycle.len().max(1) as f32;
        var.sqrt() / m.abs()
    }
}

/// Swims `species` with `advance(frame)` calls and records the distance at each cycle's
/// first step (exactly phase 0, whatever the frame rate).
fn swim(species: &Species, frame: f32, from: u32, to: u32) -> Run {
    swim_in_steps(species, 1, frame, from, to)
}

/// [`swim`] with `finer` times the species' fixed steps per cycle (a time-step convergence
/// check: a shipped slice always takes its species' own steps).
fn swim_in_steps(species: &Species, finer: u32, frame: f32, from: u32, to: u32) -> Run {
    let mut sim = SliceSim::new(species).expect("valid species");
    if finer > 1 {
        let steps = SliceSim::steps_per_cycle(species) * finer;
        sim.set_clock(FixedClock::new(species.period(), steps));
    }
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
fn parallel<T: Send + Sync, R: Send>(jobs: Vec<T>, f: impl Fn(&T) -> R + Sync) -> Vec<R> {
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

fn spread(values: &[f32]) -> f32 {
    let max = values.iter().copied().fold(f32::MIN, f32::max);
    let min = values.iter().copied().fold(f32::MAX, f32::min);
    let mean = values.iter().sum::<f32>() / values.len() as f32;
    (max - min) / mean.abs()
}

fn row(label: &str, runs: &[Run]) {
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

fn frames(species: &[Species], from: u32, to: u32) {
    const RATES: [f32; 4] = [20.0, 30.0, 60.0, 144.0];
    println!(
        "\n### Frame rate: swim per cycle (cycles {from}–{to}) ± cycle-to-cycle cv, spread over rates\n"
    );
    println!("| species (grid) | 20 Hz | 30 Hz | 60 Hz | 144 Hz | spread |");
    println!("|---|---|---|---|---|---|");
    for s in species {
        let runs = parallel(RATES.to_vec(), |hz| swim(s, 1.0 / hz, from, to));
        row(&format!("{} ({})", s.name, s.grid_resolution), &runs);
    }
}

fn grids(species: &[Species], from: u32, to: u32) {
    println!("\n### Grid offset: swim per cycle at grids G..G+3 (60 Hz frames), spread\n");
    println!("| species | G | G+1 | G+2 | G+3 | spread |");
    println!("|---|---|---|---|---|---|");
    for s in species {
        let g = s.grid_resolution;
        let jobs: Vec<Species> = (0..4)
            .map(|k| Species {
                grid_resolution: g + k,
                ..s.clone()
            })
            .collect();
        let runs = parallel(jobs, |s| swim(s, 1.0 / 60.0, from, to));
        row(&format!("{} (G = {g})", s.name), &runs);
    }
}

/// The paper's Fig. 5 finding on each species: its staggered release against every band
/// letting go in unison.
fn stagger(species: &[Species], from: u32, to: u32) {
    println!("\n### Staggered against unison: swim per cycle (cycles {from}–{to}, 60 Hz frames)\n");
    println!("| species | staggered | unison | gain |");
    println!("|---|---|---|---|");
    for s in species {
        let [staggered, unison] = against_unison(s, from, to);
        let (a, b) = (staggered.mean(), unison.mean());
        println!(
            "| {} | {a:.3} ± {:.0}% | {b:.3} ± {:.0}% | {:+.0}% |",
            s.name,
            100.0 * staggered.cv(),
            100.0 * unison.cv(),
            100.0 * (a / b - 1.0)
        );
    }
}

/// `s` as it is and with every band letting go in unison, side by side (60 Hz frames).
fn against_unison(s: &Species, from: u32, to: u32) -> [Run; 2] {
    let unison = Species {
        expansion_stagger: 0.0,
        ..s.clone()
    };
    let mut runs = parallel(vec![s.clone(), unison], |s| swim(s, 1.0 / 60.0, from, to));
    let unison = runs.pop().expect("two runs");
    [runs.pop().expect("two runs"), unison]
}

fn convergence(species: &[Species], from: u32, to: u32) {
    println!(
        "\n### Convergence: swim per cycle against grid (60 Hz frames), cost in ms per simulated s\n"
    );
    for s in species {
        let g = s.grid_resolution as f32;
        let grids: Vec<u32> = [0.5, 0.75, 1.0, 1.5, 2.0]
            .iter()
            .map(|f| (f * g).round() as u32)
            .collect();
        let jobs: Vec<Species> = grids
            .iter()
            .map(|&grid| Species {
                grid_resolution: grid,
                ..s.clone()
            })
            .collect();
        let runs = parallel(jobs, |s| swim(s, 1.0 / 60.0, from, to));
        println!(
            "| {} grid | swim per cycle | cv | ms per simulated s |",
            s.name
        );
        println!("|---|---|---|---|");
        for (grid, r) in grids.iter().zip(&runs) {
            println!(
                "| {grid} | {:.3} | {:.0}% | {:.1} |",
                r.mean(),
                100.0 * r.cv(),
                1e3 * r.cost
            );
        }
        let at = |f: f32| {
            runs[grids
                .iter()
                .position(|&x| x == (f * g).round() as u32)
                .unwrap()]
            .mean()
        };
        println!(
            "\nG against 1.5·G: {:+.1}%\n",
            100.0 * (at(1.5) / at(1.0) - 1.0)
        );
    }
}

fn timestep(species: &[Species], from: u32, to: u32) {
    const FINER: [u32; 5] = [1, 2, 4, 8, 16];
    println!(
        "\n### Time step: swim per cycle (cycles {from}–{to}) with the species' fixed step, \
         and 2, 4, 8 and 16 times finer (60 Hz frames)\n"
    );
    println!("| species (grid, steps per cycle) | 1× | 2× | 4× | 8× | 16× | spread |");
    println!("|---|---|---|---|---|---|---|");
    let runs: Vec<Vec<Run>> = species
        .iter()
        .map(|s| {
            parallel(FINER.to_vec(), |&k| {
                swim_in_steps(s, k, 1.0 / 60.0, from, to)
            })
        })
        .collect();
    let label = |s: &Species| {
        format!(
            "{} ({}, {})",
            s.name,
            s.grid_resolution,
            SliceSim::steps_per_cycle(s)
        )
    };
    for (s, runs) in species.iter().zip(&runs) {
        row(&label(s), runs);
    }
    println!(
        "\nThe subumbrella's strain over the same cycles, least and greatest \
         (`SliceSim::meridian_strain`):\n"
    );
    println!("| species | 1× | 2× | 4× | 8× | 16× |");
    println!("|---|---|---|---|---|---|");
    for (s, runs) in species.iter().zip(&runs) {
        let cells: Vec<String> = runs
            .iter()
            .map(|r| {
                format!(
                    "{:+.1}% to {:+.1}%",
                    100.0 * r.meridian.0,
                    100.0 * r.meridian.1
                )
            })
            .collect();
        println!("| {} | {} |", label(s), cells.join(" | "));
    }
}

/// Whole bells: crumpled samples (every 3rd 60 Hz frame), the smallest area, the drift of
/// the area at phase 0 from its value at cycle 5, and recoveries.
fn crumples(species: &[Species], cycles: u32) {
    println!("\n### Whole bells over {cycles} cycles (60 Hz frames, every 3rd sampled)\n");
    println!(
        "| species (grid) | crumpled samples | smallest area/rest | phase-0 area drift | recoveries | swim per cycle (cv), cycles 20–40 |"
    );
    println!("|---|---|---|---|---|---|");
    let rows = parallel(species.to_vec(), |s| {
        let mut sim = SliceSim::new(s).expect("valid species");
        let (mut samples, mut crumpled, mut smallest) = (0u64, 0u64, f32::MAX);
        let (mut reference, mut drift) = (None, 0.0f32);
        let mut per_cycle = Vec::new();
        let mut last = (0u64, 0.0f32);
        let mut frame = 0u64;
        while sim.cycle() < cycles as u64 {
            // Each cycle's first step is exactly phase 0, at any frame rate.
            sim.advance_with(1.0 / 60.0, |sim| {
                if sim.phase() != 0.0 {
                    return;
                }
                let a = sim.outline().area_ratio;
                if sim.cycle() == 5 {
                    reference = Some(a);
                }
                if let Some(r) = reference {
                    drift = drift.max((a / r - 1.0).abs());
                }
                if (21..=40).contains(&sim.cycle()) {
                    per_cycle.push((sim.swim_distance() - last.1) / s.diameter);
                }
                last = (sim.cycle(), sim.swim_distance());
            });
            frame += 1;
            if frame.is_multiple_of(3) {
                let o = sim.outline();
                samples += 1;
                crumpled += o.crumpled() as u64;
                smallest = smallest.min(o.area_ratio);
            }
        }
        let run = Run {
            per_cycle,
            cost: 0.0,
            recoveries: sim.recoveries(),
            meridian: (0.0, 0.0),
        };
        format!(
            "| {} ({}) | {crumpled} of {samples} | {smallest:.2} | {:.1}% | {} | {:.3} ({:.0}%) |",
            s.name,
            s.grid_resolution,
            100.0 * drift,
            sim.recoveries(),
            run.mean(),
            100.0 * run.cv()
        )
    });
    rows.iter().for_each(|r| println!("{r}"));
}

/// Distance in `seconds` of swimming, diameters (the paper's Fig. 5 measure).
fn distance_in(species: &Species, seconds: f32) -> f32 {
    let mut sim = SliceSim::new(species).expect("valid species");
    while sim.time() < seconds {
        sim.advance(0.1);
    }
    sim.swim_distance() / species.diameter
}

fn calibration(base: &Species) {
    let [staggered, unison] = against_unison(base, 20, 40);
    println!("\n### Calibration ({})\n", base.name);
    println!(
        "- swim per cycle, cycles 20–40: staggered {:.3} (cv {:.1}%), unison {:.3} (cv {:.1}%): staggered {:+.0}%",
        staggered.mean(),
        100.0 * staggered.cv(),
        unison.mean(),
        100.0 * unison.cv(),
        100.0 * (staggered.mean() / unison.mean() - 1.0)
    );
    let re =
        |s: &Species| s.density * s.contraction_frequency * s.diameter * s.diameter / s.viscosity;
    for target in [1.0f32, 10.0, 100.0] {
        let viscosity =
            base.density * base.contraction_frequency * base.diameter * base.diameter / target;
        let s = Species {
            viscosity,
            ..base.clone()
        };
        let r = swim(&s, 1.0 / 60.0, 10, 20);
        println!(
            "- Re {:.0} (viscosity {viscosity:.3e} Pa·s): {:.3} D per cycle",
            re(&s),
            r.mean()
        );
    }
    println!(
        "- Re {:.0} (sea water): {:.3} D per cycle",
        re(base),
        staggered.mean()
    );
    let frequencies: Vec<f32> = (2..=16).map(|k| k as f32 / 10.0).collect();
    for (label, modulus) in [
        ("E = 1186 Pa", base.elastic_modulus),
        ("E × 2", 2.0 * base.elastic_modulus),
        ("E / 2", 0.5 * base.elastic_modulus),
    ] {
        let jobs: Vec<Species> = frequencies
            .iter()
            .map(|&f| Species {
                contraction_frequency: f,
                elastic_modulus: modulus,
                ..base.clone()
            })
            .collect();
        let d = parallel(jobs, |s| distance_in(s, 20.0));
        let (peak, best) = d
            .iter()
            .enumerate()
            .fold((0, f32::MIN), |m, (i, &x)| if x > m.1 { (i, x) } else { m });
        let cells: Vec<String> = frequencies
            .iter()
            .zip(&d)
            .map(|(f, x)| format!("{f:.1}:{x:.2}"))
            .collect();
        println!(
            "- sweep {label}: peak {:.1} Hz ({best:.2} D in 20 s; ends {:.2} and {:.2}: {:+.0}% / {:+.0}%)\n  {}",
            frequencies[peak],
            d[0],
            d[d.len() - 1],
            100.0 * (best / d[0] - 1.0),
            100.0 * (best / d[d.len() - 1] - 1.0),
            cells.join(" ")
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str, default: u32| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (from, to) = (flag("--from", 10), flag("--to", 30));
    let which = args.first().map(String::as_str).unwrap_or("all");
    let overrides = overrides(&args);
    let only: Option<&String> = args
        .iter()
        .position(|a| a == "--species")
        .and_then(|i| args.get(i + 1));
    let species: Vec<Species> = shipped_species()
        .into_iter()
        .filter(|s| only.is_none_or(|o| s.name.eq_ignore_ascii_case(o)))
        .map(|s| with_overrides(s, &overrides))
        .flat_map(|s| at_sizes(&s, &args))
        .collect();
    // The paper's findings (staggering, Reynolds numbers) are shown on the paper's model.
    let paper = with_overrides(Species::paper(), &overrides);
    if matches!(which, "frames" | "all") {
        frames(&species, from, to);
    }
    if matches!(which, "grids" | "all") {
        grids(&species, from, to);
    }
    if matches!(which, "series") {
        let to = flag("--to", 60);
        for s in &species {
            let r = swim(s, 1.0 / 60.0, 0, to);
            let groups: Vec<String> = r
                .per_cycle
                .chunks(5)
                .map(|c| format!("{:.3}", c.iter().sum::<f32>() / c.len() as f32))
                .collect();
            println!(
                "{} ({}): per-cycle means by 5s: {}",
                s.name,
                s.grid_resolution,
                groups.join(" ")
            );
        }
    }
    if matches!(which, "fingerprint") {
        let named = |flag: &str| {
            args.iter()
                .position(|a| a == flag)
                .and_then(|i| args.get(i + 1))
                .map(|v| v.to_ascii_lowercase())
        };
        let mut all = species.clone();
        if only.is_none_or(|o| o.eq_ignore_ascii_case("paper")) {
            all.push(paper.clone());
        }
        let geometries: Vec<SliceGeometry> = [SliceGeometry::Planar, SliceGeometry::Axisymmetric]
            .into_iter()
            .filter(|g| {
                named("--geometry").is_none_or(|n| format!("{g:?}").to_ascii_lowercase() == n)
            })
            .collect();
        fingerprint(&all, &geometries, flag("--to", 10));
    }
    if matches!(which, "stagger") {
        stagger(&species, from, to);
    }
    if matches!(which, "timestep") {
        timestep(&species, from, to);
    }
    if matches!(which, "calibration") {
        calibration(&paper);
    }
    if matches!(which, "crumples") {
        crumples(&species, flag("--cycles", 300));
    }
    if matches!(which, "convergence" | "all") {
        convergence(&species, from, to);
    }
}

/// `s` resized (`Species::resized`: every length, and its animal's pulse rate at the size)
/// to each multiple of its diameter that `--sizes 0.25,2,...` lists, named with its size;
/// `s` itself without the flag.
fn at_sizes(s: &Species, args: &[String]) -> Vec<Species> {
    let Some(list) = common::value(args, "--sizes") else {
        return vec![s.clone()];
    };
    list.split(',')
        .map(|k| match k.trim().parse::<f32>() {
            Ok(k) if k > 0.0 => Species {
                name: format!("{} {:.1} mm", s.name, 1000.0 * k * s.diameter),
                ..s.resized(k * s.diameter)
            },
            _ => common::refuse(&format!(
                "numerics: --sizes takes positive multiples of the diameter, not {k:?}"
            )),
        })
        .collect()
}

/// A hash of each cycle's distance (every bit) in both geometries, and the cost, one
/// species at a time (so the costs are comparable on a busy machine), beside what the
/// limits' cost model estimates for it (`limits::simulation_cost`, the reference
/// machine's one core).
fn fingerprint(species: &[Species], geometries: &[SliceGeometry], cycles: u32) {
    use bevy_jellyfish::species::limits::simulation_cost;
    use std::hash::{Hash, Hasher};
    println!(
        "| species | geometry | fingerprint | ms per simulated second | estimated | measured / estimated |"
    );
    println!("|---|---|---|---|---|---|");
    for s in species {
        for &geometry in geometries {
            let s = Species {
                slice_geometry: geometry,
                ..s.clone()
            };
            let run = swim(&s, 1.0 / 60.0, 0, cycles);
            let mut hasher = std::collections::hash_map::DefaultHasher::new();
            for d in &run.per_cycle {
                d.to_bits().hash(&mut hasher);
            }
            let estimated = simulation_cost(&s);
            println!(
                "| {} | {geometry:?} | {:016x} | {:.2} | {:.2} | {:.2} |",
                s.name,
                hasher.finish(),
                1000.0 * run.cost,
                1000.0 * estimated,
                run.cost / estimated
            );
        }
    }
}
