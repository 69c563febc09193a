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
//! `animals` reads issue 28's checks of an animal (`tests/slice.rs`: its stroke, refill,
//! margin, sweep, stagger and fringe) at each of `--sizes` (half, once and twice its size
//! without it), and how its stroke spreads across them, in seconds: a candidate
//! calibration (`--set`, `--steps`) read before the long tests are run on it.
//!
//! `fingerprint` runs every shipped species and the paper's model in both slice geometries
//! for `--to` cycles and prints a hash of every cycle's distance, bit for bit, and the
//! cost: a refactor meant to leave the physics alone must leave the hashes alone. With
//! `--species` (the paper's model is `paper`) and `--geometry planar|axisymmetric` it
//! runs only those, as a profiler wants.
//!
//! `cargo run --release --no-default-features --example numerics -- [frames|grids|convergence|stagger|timestep|strain|calibration|animals|fingerprint|all] [--from 10] [--to 30] [--species name] [--geometry name] [--set field=value ...] [--sizes 0.25,2,...] [--steps 0.5,1,2,...]`
//!
//! `--sizes` runs each species resized to those multiples of its diameter, its pulse rate its
//! animal's at each size (`Species::resized`). `--steps` sets the multiples of each
//! species' own steps per cycle that `timestep` runs (1, 2, 4, 8 and 16 without it; below
//! 1, fewer).

mod animals;
mod calibration;
#[path = "../common/species.rs"]
mod common;
mod fingerprint;
mod run;
mod strain;
mod tables;

use animals::animals;
use bevy_jellyfish::{SliceGeometry, Species};
use calibration::calibration;
use common::{overrides, shipped_species, with_overrides};
use fingerprint::fingerprint;
use tables::{convergence, crumples, frames, grids, stagger, timestep};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str, default: u32| {
        common::value(&args, name)
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (from, to) = (flag("--from", 10), flag("--to", 30));
    let which = args.first().map(String::as_str).unwrap_or("all");
    let overrides = overrides(&args);
    let only = common::value(&args, "--species");
    let animals_at_sizes: Vec<Vec<Species>> = shipped_species()
        .into_iter()
        .filter(|s| only.is_none_or(|o| s.name.eq_ignore_ascii_case(o)))
        .map(|s| {
            let s = with_overrides(s, &overrides);
            match which {
                // An animal is read at half, once and twice its size unless told otherwise.
                "animals" if common::value(&args, "--sizes").is_none() => [0.5, 1.0, 2.0]
                    .map(|k| Species {
                        name: format!("{} {:.1} mm", s.name, 1000.0 * k * s.diameter),
                        ..s.resized(k * s.diameter)
                    })
                    .to_vec(),
                _ => at_sizes(&s, &args),
            }
        })
        .collect();
    let species: Vec<Species> = animals_at_sizes.iter().flatten().cloned().collect();
    // The paper's findings (staggering, Reynolds numbers) are shown on the paper's model.
    let paper = with_overrides(Species::paper(), &overrides);
    if matches!(which, "frames" | "all") {
        frames(&species, from, to);
    }
    if matches!(which, "grids" | "all") {
        grids(&species, from, to);
    }
    if matches!(which, "series") {
        tables::series(&species, flag("--to", 60));
    }
    if matches!(which, "fingerprint") {
        let mut all = species.clone();
        if only.is_none_or(|o| o.eq_ignore_ascii_case("paper")) {
            all.push(paper.clone());
        }
        let geometries: Vec<SliceGeometry> = [SliceGeometry::Planar, SliceGeometry::Axisymmetric]
            .into_iter()
            .filter(|g| {
                common::value(&args, "--geometry")
                    .is_none_or(|n| format!("{g:?}").eq_ignore_ascii_case(n))
            })
            .collect();
        fingerprint(&all, &geometries, flag("--to", 10));
    }
    if matches!(which, "stagger") {
        stagger(&species, from, to);
    }
    if matches!(which, "timestep") {
        timestep(&species, &step_multiples(&args), from, to);
    }
    if matches!(which, "strain") {
        strain::by_phase(&species, from, to);
    }
    if matches!(which, "calibration") {
        calibration(&paper);
    }
    if matches!(which, "animals") {
        let steps = common::value(&args, "--steps").map_or(1.0, |_| step_multiples(&args)[0]);
        for sizes in &animals_at_sizes {
            animals(sizes, steps);
        }
    }
    if matches!(which, "crumples") {
        crumples(&species, flag("--cycles", 300));
    }
    if matches!(which, "convergence" | "all") {
        convergence(&species, from, to);
    }
}

/// The multiples of each species' own steps per cycle that `--steps 0.5,1,2,...` lists
/// (1, 2, 4, 8 and 16 without it).
fn step_multiples(args: &[String]) -> Vec<f32> {
    let Some(list) = common::value(args, "--steps") else {
        return vec![1.0, 2.0, 4.0, 8.0, 16.0];
    };
    list.split(',')
        .map(|k| match k.trim().parse::<f32>() {
            Ok(k) if k > 0.0 && k <= 1024.0 => k,
            _ => common::refuse(&format!(
                "numerics: --steps takes multiples of the species' steps per cycle above 0 \
                 and at most 1024, not {k:?}"
            )),
        })
        .collect()
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
