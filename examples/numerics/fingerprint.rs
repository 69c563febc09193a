//! The bits of every cycle's distance, and the cost beside the limits' estimate.

use crate::run::swim;
use bevy_jellyfish::{SliceGeometry, Species};

/// A hash of each cycle's distance (every bit) in both geometries, and the cost, one
/// species at a time (so the costs are comparable on a busy machine), beside what the
/// limits' cost model estimates for it (`limits::simulation_cost`, the reference
/// machine's one core).
pub fn fingerprint(species: &[Species], geometries: &[SliceGeometry], cycles: u32) {
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
