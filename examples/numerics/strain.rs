//! The subumbrella's length through a stroke, by phase: how far the coupled step lets the
//! wall give at each point of the cycle, with the species' own step and finer ones
//! (`docs/numerics.md`, "The meridian through a stroke, by phase").

use crate::run::{parallel, slice_in_steps};
use bevy_jellyfish::Species;

/// How many parts of the cycle the strain is averaged over.
const PARTS: usize = 10;
/// The steps per cycle measured, in multiples of the species' own.
const FINER: [f32; 3] = [1.0, 4.0, 16.0];

/// `SliceSim::meridian_strain`, percent, averaged over each tenth of the cycle through
/// cycles `from..to` (60 Hz frames), and its least and greatest there.
pub fn by_phase(species: &[Species], from: u32, to: u32) {
    println!(
        "\n### The subumbrella's strain by phase (cycles {from}–{to}, 60 Hz frames), percent\n"
    );
    let header: Vec<String> = (0..PARTS)
        .map(|k| format!("{:.1}", k as f32 / PARTS as f32))
        .collect();
    println!(
        "| species, steps | {} | least | greatest |",
        header.join(" | ")
    );
    println!("|---|{}---|---|", "---|".repeat(PARTS));
    for s in species {
        let rows = parallel(FINER.to_vec(), |&finer| strain_by_phase(s, finer, from, to));
        for (finer, (means, least, greatest)) in FINER.iter().zip(rows) {
            let cells: Vec<String> = means.iter().map(|m| format!("{:+.1}", 100.0 * m)).collect();
            println!(
                "| {} {finer}× | {} | {:+.1} | {:+.1} |",
                s.name,
                cells.join(" | "),
                100.0 * least,
                100.0 * greatest
            );
        }
    }
}

/// Each part's mean strain, and the least and greatest, over cycles `from..to`.
fn strain_by_phase(s: &Species, finer: f32, from: u32, to: u32) -> ([f32; PARTS], f32, f32) {
    let mut sim = slice_in_steps(s, finer);
    let (mut sums, mut counts) = ([0.0f64; PARTS], [0u32; PARTS]);
    let (mut least, mut greatest) = (f32::MAX, f32::MIN);
    while sim.cycle() < to as u64 {
        sim.advance_with(1.0 / 60.0, |sim| {
            if sim.cycle() < from as u64 {
                return;
            }
            let part = ((sim.phase() * PARTS as f32) as usize).min(PARTS - 1);
            let strain = sim.meridian_strain();
            sums[part] += strain as f64;
            counts[part] += 1;
            least = least.min(strain);
            greatest = greatest.max(strain);
        });
    }
    let means = std::array::from_fn(|k| (sums[k] / counts[k].max(1) as f64) as f32);
    (means, least, greatest)
}
