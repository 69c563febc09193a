//! Swims one slice headless and prints, per cycle, the distance travelled, the bell's
//! enclosed area at the same phase and the worst relative divergence.
//!
//! `cargo run --release --no-default-features --example swim -- [cycles] [grid] [stagger] [freq] [frame_dt] [tentacle_length] [angular_stiffness] [muscle_cross_section] [maccormack 0|1]`

use bevy_jellyfish::{SliceSim, Species};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: f32| args.get(i).and_then(|a| a.parse().ok()).unwrap_or(default);
    let cycles = arg(0, 15.0) as u32;
    let mut species = Species::aurelia();
    species.grid_resolution = arg(1, 100.0) as u32;
    species.expansion_stagger = arg(2, species.expansion_stagger);
    species.contraction_frequency = arg(3, species.contraction_frequency);
    species.tentacle_length = arg(5, species.tentacle_length);
    if args.get(6).is_some() {
        // The paper's springs: the moon jelly otherwise bends as its mesoglea.
        species.bending = bevy_jellyfish::Bending::Springs;
        species.angular_stiffness = arg(6, species.angular_stiffness);
    }
    species.muscle_cross_section = arg(7, species.muscle_cross_section);
    if arg(8, 0.0) > 0.0 {
        species.advection = bevy_jellyfish::species::Advection::MacCormack;
    }
    let mut sim = match SliceSim::new(&species) {
        Ok(sim) => sim,
        Err(e) => return eprintln!("{e}"),
    };
    let frame: f32 = arg(4, 1.0 / 60.0);
    let period = species.period();
    let start = Instant::now();
    let mut worst_div = 0.0f32;
    let mut last = 0.0;
    println!("cycle  distance/D  area/rest  min_width/D  max|u| m/s  substeps  tilt_deg  x/D");
    let rest_area = sim.bell_area();
    for cycle in 1..=cycles {
        let mut min_width = f32::MAX;
        while sim.time() < cycle as f32 * period {
            sim.advance(frame.min(cycle as f32 * period - sim.time() + 1e-6));
            let rel = sim.fluid().h * sim.fluid_divergence_max() / sim.fluid_speed_max().max(1e-9);
            worst_div = worst_div.max(rel);
            let b = sim.bell_points();
            min_width = min_width.min((b[b.len() - 1] - b[0]).length());
        }
        let d = sim.swim_distance();
        println!(
            "{cycle:5}  {:10.3}  {:9.3}  {:11.3}  {:10.4}  {:8}  {:8.2}  {:5.2}",
            (d - last) / species.diameter,
            sim.bell_area() / rest_area,
            min_width / species.diameter,
            sim.fluid_speed_max(),
            sim.last_substeps(),
            sim.tilt().to_degrees(),
            sim.bell_centroid_world().x / species.diameter
        );
        last = d;
    }
    let wall = start.elapsed().as_secs_f32();
    println!(
        "simulated {:.1} s in {:.2} s wall: {:.1}x real time, {} steps ({:.1} us/step), recoveries {}, worst h|div|/|u| {:.2e}",
        sim.time(),
        wall,
        sim.time() / wall,
        sim.steps(),
        wall * 1e6 / sim.steps() as f32,
        sim.recoveries(),
        worst_div
    );
}
