//! The tables of swim per cycle: frame rates, grid offsets, staggering, convergence in
//! the grid and in the step, and whole bells over many strokes.

use crate::run::{Run, parallel, row, swim, swim_in_steps};
use bevy_jellyfish::{SliceSim, Species};

pub fn frames(species: &[Species], from: u32, to: u32) {
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

pub fn grids(species: &[Species], from: u32, to: u32) {
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
pub fn stagger(species: &[Species], from: u32, to: u32) {
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
pub fn against_unison(s: &Species, from: u32, to: u32) -> [Run; 2] {
    let unison = Species {
        expansion_stagger: 0.0,
        ..s.clone()
    };
    let mut runs = parallel(vec![s.clone(), unison], |s| swim(s, 1.0 / 60.0, from, to));
    let unison = runs.pop().expect("two runs");
    [runs.pop().expect("two runs"), unison]
}

pub fn convergence(species: &[Species], from: u32, to: u32) {
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

/// Swim per cycle with each multiple of the species' own steps per cycle in `multiples`
/// (fewer below 1), and the subumbrella's strain.
pub fn timestep(species: &[Species], multiples: &[f32], from: u32, to: u32) {
    let names: Vec<String> = multiples.iter().map(|k| format!("{k}×")).collect();
    println!(
        "\n### Time step: swim per cycle (cycles {from}–{to}) with {} the species' fixed \
         steps per cycle (60 Hz frames)\n",
        names.join(", ")
    );
    println!(
        "| species (grid, steps per cycle) | {} | spread |",
        names.join(" | ")
    );
    println!("|---|{}---|", "---|".repeat(names.len()));
    let runs: Vec<Vec<Run>> = species
        .iter()
        .map(|s| {
            parallel(multiples.to_vec(), |&k| {
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
    println!("| species | {} |", names.join(" | "));
    println!("|---|{}", "---|".repeat(names.len()));
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
pub fn crumples(species: &[Species], cycles: u32) {
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

/// Each species' distance a stroke from rest, in means of five strokes (a planar bell's
/// slow start shows here).
pub fn series(species: &[Species], to: u32) {
    for s in species {
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
