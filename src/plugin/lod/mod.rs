//! Levels of detail: how much of each jellyfish is simulated.
//!
//! - **Near**: the species' own slice, live.
//! - **Mid**: a live slice in a compact box (two thirds of the species' box, same cells,
//!   same step): about 0.6 of the cost, swimming 4 to 9 % slower (measured by
//!   `examples/lod.rs`). A coarser grid would be cheaper still but loses the stroke to
//!   numerical viscosity (grid 40 in the full box swims a fifth as far).
//! - **Far**: the species' recorded stroke cycle ([`CycleCache`]), replayed by phase with
//!   its swim surge step by step; no fluid at all.
//!
//! Tiers are chosen each frame from each jellyfish's size on screen and counts
//! ([`DetailLevels`]), never from measured time, so a replay chooses the same. A
//! jellyfish coming nearer resumes from the recorded slice state for its phase; any
//! difference of shape fades out over a quarter stroke.

mod caches;
mod choose;
mod tiers;

pub use crate::plugin::settings::DetailLevels;
pub use caches::CycleCaches;

use crate::plugin::schedule::JellyfishSystems;
use bevy::prelude::*;

/// Levels of detail: chooses each jellyfish's [`Tier`](crate::plugin::Tier) every frame and moves it there.
/// Without it every jellyfish stays near.
#[derive(Clone, Copy, Debug, Default)]
pub struct DetailPlugin;

impl Plugin for DetailPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<CycleCaches>()
            .register_type::<DetailLevels>()
            .register_type::<CycleCaches>()
            .add_systems(
                PreUpdate,
                tiers::change_tiers.in_set(JellyfishSystems::ChooseDetail),
            )
            .add_systems(
                Last,
                caches::record_cycles.in_set(JellyfishSystems::RecordCycles),
            );
    }
}
