//! The far tier's recorded frames, packed once each.
//!
//! Every far jellyfish of a species plays the same recorded cycle, and a frame shows one
//! of its steps (the nearest, not a blend: [`shown_step`]). So the step's frame is packed
//! the first time a far jellyfish shows it (`shape::packed::pack_frame`) and uploaded once
//! (the template upload's recorded buffer), and every far jellyfish showing that step
//! reads it: its own block is its seed, noise time and trails
//! (`shape::packed::pack_instance`), a few dozen values instead of a few kilobytes.

use crate::plugin::interpolation::Snapshot;
use crate::plugin::slice::same;
use crate::shape::mesh::Resolution;
use crate::shape::packed;
use crate::sim::SliceView;
use crate::sim::cycle::CycleCache;
use crate::species::Species;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use std::sync::{Arc, OnceLock, RwLock, Weak};

/// Each recorded cycle's steps as packed blocks, by cycle and resolution.
#[derive(Resource, Default)]
pub(crate) struct RecordedFrames {
    cycles: RwLock<HashMap<(usize, Resolution), Arc<PackedCycle>>>,
}

/// One cycle's packed steps, for the species they were packed with.
struct PackedCycle {
    /// Keeps the cycle's allocation, so no other cycle takes its address (the key) while
    /// this entry lives; gone when no jellyfish plays it.
    cache: Weak<CycleCache>,
    species: Arc<Species>,
    /// `None` where the step could not be packed.
    steps: Vec<OnceLock<Option<Arc<[f32]>>>>,
}

impl RecordedFrames {
    /// Step `index` of `cache` packed for `species` at `res`: `pack` packs it the first
    /// time (any seed and time; `None` if it cannot).
    pub(crate) fn step(
        &self,
        cache: &Arc<CycleCache>,
        index: u32,
        species: &Arc<Species>,
        res: Resolution,
        pack: impl FnOnce() -> Option<Vec<f32>>,
    ) -> Option<Arc<[f32]>> {
        let key = (Arc::as_ptr(cache) as usize, res);
        let current = |c: &Arc<PackedCycle>| same(&c.species, species);
        let known = self
            .cycles
            .read()
            .ok()?
            .get(&key)
            .filter(|c| current(c))
            .cloned();
        let cycle = match known {
            Some(cycle) => cycle,
            None => {
                let mut cycles = self.cycles.write().ok()?;
                let entry = cycles
                    .entry(key)
                    .or_insert_with(|| PackedCycle::new(cache, species));
                // A species edited without a new recording (its looks): pack again.
                if !current(entry) {
                    *entry = PackedCycle::new(cache, species);
                }
                entry.clone()
            }
        };
        cycle
            .steps
            .get(index as usize)?
            .get_or_init(|| pack().map(Arc::from))
            .clone()
    }

    /// Forgets the cycles no jellyfish plays any more.
    pub(crate) fn prune(&self) {
        if let Ok(mut cycles) = self.cycles.write() {
            cycles.retain(|_, c| c.cache.strong_count() > 0);
        }
    }
}

impl PackedCycle {
    fn new(cache: &Arc<CycleCache>, species: &Arc<Species>) -> Arc<Self> {
        Arc::new(Self {
            cache: Arc::downgrade(cache),
            species: species.clone(),
            steps: (0..cache.steps_per_cycle())
                .map(|_| OnceLock::new())
                .collect(),
        })
    }
}

/// The step a far jellyfish shows of the two around its frame's time, `t` of the way
/// between them: the nearer. A recorded step is shared, a blend of two is not; the frame
/// shows the step's shape at most half a step early or late.
pub(crate) fn shown_step<'a>(a: &'a Snapshot, b: &'a Snapshot, t: f32) -> &'a Snapshot {
    if t < 0.5 { a } else { b }
}

/// What a jellyfish's frame is drawn from, on either path and for picking alike:
/// `shown`'s view, its fringe's trail thinned (`Trail::thin_into`, into `thin`) where a far
/// jellyfish shows a recorded step.
pub(crate) fn drawn_view<'a>(
    shown: &'a Snapshot,
    far: bool,
    rest_bell: &'a [Vec2],
    res: &Resolution,
    thin: &'a mut Vec<Vec3>,
) -> SliceView<'a> {
    let mut view = shown.view(rest_bell);
    if far && shown.recorded.is_some() {
        view.trail = view.trail.thin_into(packed::far_guides(res), thin);
    }
    view
}
