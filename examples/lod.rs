//! Level of detail: how far each shipped species swims per stroke, and what a second of
//! swimming costs, at a few grid resolutions with each advection scheme: what a cheaper
//! slice would cost and how far its swimming would be from the full one's.
//!
//! `cargo run --release --no-default-features --example lod -- [strokes] [grid...]`

use bevy_jellyfish::SliceSim;
use bevy_jellyfish::Species;
use bevy_jellyfish::species::Advection;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let strokes: u32 = args.first().and_then(|a| a.parse().ok()).unwrap_or(8);
    let mut grids: Vec<u32> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    if grids.is_empty() {
        grids = vec![30, 45, 60];
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/species");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("assets/species")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    files.sort();
    println!(
        "species    grid  advection        D/stroke (strokes 2..{strokes})  ms per simulated s"
    );
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable species file");
        let base = match Species::from_ron(&text) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{}: {e}", file.display());
                continue;
            }
        };
        for &grid in &grids {
            for advection in Advection::ALL {
                let species = Species {
                    grid_resolution: grid,
                    advection,
                    ..base.clone()
                };
                let (per_stroke, cost) = swim(&species, strokes);
                println!(
                    "{:<10} {grid:>4}  {:<16} {per_stroke:>8.3}                {cost:>8.1}",
                    species.name,
                    format!("{advection:?}"),
                );
            }
        }
    }
}

/// Mean diameters per stroke after the first (the start-up stroke), and CPU ms per
/// simulated second.
fn swim(species: &Species, strokes: u32) -> (f32, f64) {
    let mut sim = SliceSim::new(species).expect("valid species");
    let period = species.period();
    sim.advance(period);
    let start_distance = sim.swim_distance();
    let start = Instant::now();
    while sim.time() < strokes as f32 * period {
        sim.advance(1.0 / 60.0);
    }
    let cost = start.elapsed().as_secs_f64() * 1e3 / (sim.time() - period) as f64;
    let per_stroke =
        (sim.swim_distance() - start_distance) / species.diameter / (strokes - 1).max(1) as f32;
    (per_stroke, cost)
}
