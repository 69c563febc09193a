//! The paper's Fig. 11: the morphology of each shipped species through one contraction
//! cycle — the subumbrella (with its tentacles) at eight phases, drawn where the bell is
//! in the world, so the picture shows both the shape and the forward movement.
//!
//! Writes `stroke.png` into `--out` (default `docs/`).
//!
//! `cargo run --release --no-default-features --example stroke -- [--cycle 20] [--out docs] [--set field=value …]`

#[path = "common/species.rs"]
mod common;

#[path = "sweep/plot.rs"]
mod plot;

use bevy_jellyfish::{SliceSim, Species};
use common::{overrides, shipped_species, with_overrides};
use plot::{Chart, Series};
use std::path::PathBuf;

const PHASES: usize = 8;

/// Outlines of one cycle, in bell diameters, world positions relative to the first.
fn stroke(species: &Species, cycle: u32) -> Chart {
    let mut sim = SliceSim::new(species).expect("valid species");
    let period = species.period();
    while sim.time() < cycle as f32 * period {
        sim.advance(1.0 / 60.0);
    }
    let d = species.diameter;
    let origin = sim.offset();
    let start = sim.swim_distance();
    let mut series = Vec::new();
    for k in 0..PHASES {
        let target = (cycle as f32 + k as f32 / PHASES as f32) * period;
        while sim.time() < target - 1e-5 {
            sim.advance(1.0 / 60.0);
        }
        let shade = (255.0 * k as f32 / PHASES as f32) as u8;
        let color = [shade / 2, 60 + shade / 2, 255 - shade];
        let to_plot = |p: &glam::Vec2| {
            let w = *p + sim.offset() - origin;
            (w.x / d, w.y / d)
        };
        let view = sim.view();
        series.push(Series {
            label: format!("phase {:.2}", k as f32 / PHASES as f32),
            points: view.bell.iter().map(to_plot).collect(),
            color,
            markers: false,
        });
        for chain in view.tentacles {
            series.push(Series {
                label: String::new(),
                points: chain.iter().map(to_plot).collect(),
                color: [180, 180, 180],
                markers: false,
            });
        }
    }
    while sim.time() < (cycle + 1) as f32 * period - 1e-5 {
        sim.advance(1.0 / 60.0);
    }
    Chart {
        title: format!(
            "{} cycle {cycle}: {:.2} D swum",
            species.name,
            (sim.swim_distance() - start) / d
        ),
        x_label: "x (bell diameters)".into(),
        y_label: "y (bell diameters)".into(),
        series,
        equal_aspect: true,
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str| common::value(&args, name);
    let cycle: u32 = value("--cycle").and_then(|v| v.parse().ok()).unwrap_or(20);
    let out = PathBuf::from(value("--out").map_or("docs", |v| v.as_str()));
    let overrides = overrides(&args);
    let charts: Vec<Chart> = shipped_species()
        .into_iter()
        .map(|s| stroke(&with_overrides(s, &overrides), cycle))
        .collect();
    let path = out.join("stroke.png");
    match plot::write_png(&path, &charts, charts.len(), 420, 640) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(e) => eprintln!("stroke: cannot write {}: {e}", path.display()),
    }
}
