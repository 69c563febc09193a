//! Levels of detail: for each shipped species, what each tier costs and how far it swims
//! against the near tier, once the bell has come up to speed.
//!
//! - near: the species' slice, live;
//! - mid: the same cells in a compact box (`Species::compact_box`), live;
//! - far: the near slice's recorded cycle (`CycleCache`), replayed;
//! - and, for the record, the coarser grid the mid tier does not use.
//!
//! `cargo run --release --no-default-features --example lod -- [cycles]`

#[path = "common/species.rs"]
mod common;

use bevy_jellyfish::Species;
use bevy_jellyfish::sim::{CycleCache, SliceSim};
use common::species_files;
use std::time::Instant;

fn main() {
    let cycles: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(6);
    let files = species_files();
    println!(
        "species    tier             grid  box D  D/cycle  vs near  ms per sim. s  recorded in  cycle MB"
    );
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable species file");
        let near = match Species::from_ron(&text) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{}: {e}", file.display());
                continue;
            }
        };
        let coarse = Species {
            grid_resolution: near.grid_resolution * 2 / 3,
            ..near.clone()
        };
        let mut reference = None;
        for (tier, species) in [
            ("near (live)", near.clone()),
            ("mid (live)", near.compact_box()),
            ("coarser grid", coarse),
        ] {
            let start = Instant::now();
            let cache = CycleCache::record(&species).expect("valid species");
            let recorded = start.elapsed().as_secs_f64();
            let (per_cycle, cost) = live(&cache, cycles);
            let per_cycle = per_cycle / species.diameter;
            let reference = *reference.get_or_insert(per_cycle);
            println!(
                "{:<10} {tier:<16} {:>4}  {:>5.1}  {per_cycle:>7.3}  {:>+6.1}%  {cost:>13.1}  {recorded:>9.2} s  {:>8.1}",
                species.name,
                species.grid_resolution,
                species.domain_diameters,
                100.0 * (per_cycle / reference - 1.0),
                cache.bytes() as f64 * 1e-6,
            );
            if tier.starts_with("near") {
                let replay = cache.swim_per_cycle() / species.diameter;
                let start = Instant::now();
                let mut swum = 0.0;
                let steps = 100 * cache.steps_per_cycle();
                for i in 0..steps {
                    swum += std::hint::black_box(cache.frame(i)).surge;
                }
                let cost = start.elapsed().as_secs_f64() * 1e3 / (100.0 * species.period() as f64);
                std::hint::black_box(swum);
                println!(
                    "{:<10} far (replay)     {:>4}  {:>5.1}  {replay:>7.3}  {:>+6.1}%  {cost:>13.4}",
                    species.name,
                    "-",
                    "-",
                    100.0 * (replay / reference - 1.0),
                );
            }
        }
    }
}

/// Distance per cycle of the live slice over `cycles` cycles from the recorded state, m,
/// and CPU ms per simulated second.
fn live(cache: &CycleCache, cycles: u32) -> (f32, f64) {
    let mut sim: SliceSim = cache.resume(0);
    let start_distance = sim.swim_distance();
    let start = Instant::now();
    let period = cache.species().period();
    sim.advance(cycles as f32 * period);
    let cost = start.elapsed().as_secs_f64() * 1e3 / (cycles as f64 * period as f64);
    ((sim.swim_distance() - start_distance) / cycles as f32, cost)
}
