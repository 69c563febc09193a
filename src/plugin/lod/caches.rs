//! The recorded stroke cycles far jellyfish replay and nearer ones resume from.

use crate::sim::cycle::{CycleCache, CycleRecorder};
use crate::species::Species;
use bevy::prelude::*;
use bevy::tasks::ComputeTaskPool;
use std::sync::Arc;

/// The recorded cycle of every species (and its compact-box variant) a far or resuming
/// jellyfish has needed. Recording one costs 10 to 60 cycles of one slice (0.1–0.4 s): it
/// is done when first needed, in that frame, so which jellyfish are far is the same in
/// every run; after an edit it is recorded a few steps a frame
/// ([`DetailLevels::recording_steps_per_frame`](crate::plugin::DetailLevels)) while far
/// jellyfish play the old cycle, so dragging an editor slider neither stalls the app nor
/// lengthens its frames by more than those steps.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct CycleCaches {
    #[reflect(ignore)]
    caches: Vec<Arc<CycleCache>>,
    #[reflect(ignore)]
    recording: Vec<CycleRecorder>,
}

impl CycleCaches {
    /// The cycle of `species`, recorded now if it is new. `None` for an invalid species.
    pub fn get(&mut self, species: &Species) -> Option<Arc<CycleCache>> {
        if let Some(c) = self.find(species) {
            return Some(c);
        }
        let cache = Arc::new(CycleCache::record(species).ok()?);
        self.caches.push(cache.clone());
        Some(cache)
    }

    /// The cycle of `species` if recorded; if not, starts recording it a few steps a frame
    /// (see [`Self::collect`]).
    pub fn request(&mut self, species: &Species) -> Option<Arc<CycleCache>> {
        if let Some(c) = self.find(species) {
            return Some(c);
        }
        if !self.is_recording(species)
            && let Ok(recorder) = CycleRecorder::new(species)
        {
            self.recording.push(recorder);
        }
        None
    }

    /// Takes `steps` more steps (at least one) of every recording, side by side, and keeps
    /// the cycles that are done: a budget of none would hold far jellyfish on the old
    /// cycle, and the tier changes of the edited species, for ever.
    pub fn collect(&mut self, steps: u32) {
        if self.recording.is_empty() {
            return;
        }
        let steps = steps.max(1);
        let done = ComputeTaskPool::get().scope(|scope| {
            for recorder in &mut self.recording {
                scope.spawn(async move { recorder.advance(steps) });
            }
        });
        // One result per recorder, in the order they were spawned (directly from the
        // scope's closure, so the order is deterministic).
        let (mut done, caches) = (done.into_iter(), &mut self.caches);
        self.recording.retain(|_| match done.next().flatten() {
            Some(cache) => {
                caches.push(Arc::new(cache));
                false
            }
            None => true,
        });
    }

    /// Whether any cycle is still being recorded.
    pub fn recording(&self) -> bool {
        !self.recording.is_empty()
    }

    /// The cycle of `species`, if recorded.
    pub fn find(&self, species: &Species) -> Option<Arc<CycleCache>> {
        self.caches.iter().find(|c| c.species() == species).cloned()
    }

    /// Records the cycles of all of `species` not yet recorded, in parallel.
    pub(super) fn prepare(&mut self, species: Vec<Species>) {
        let mut missing: Vec<Species> = Vec::new();
        for s in species {
            if !self.caches.iter().any(|c| c.species() == &s) && !missing.contains(&s) {
                missing.push(s);
            }
        }
        let recorded = bevy::tasks::ComputeTaskPool::get().scope(|scope| {
            for species in &missing {
                scope.spawn(async move { CycleCache::record(species).ok() });
            }
        });
        self.caches
            .extend(recorded.into_iter().flatten().map(Arc::new));
    }

    /// Forgets cycles no jellyfish uses (edited species), keeping `in_use`.
    /// Recordings of species no jellyfish has any more (an editor slider dragged on) are
    /// dropped, which cancels them.
    pub(super) fn retain(&mut self, in_use: &[Species]) {
        self.caches.retain(|c| in_use.contains(c.species()));
        self.recording.retain(|r| in_use.contains(r.species()));
    }

    /// Whether the cycle of `species` is being recorded.
    pub fn is_recording(&self, species: &Species) -> bool {
        self.recording.iter().any(|r| r.species() == species)
    }

    /// Heap bytes held.
    pub fn bytes(&self) -> usize {
        self.caches.iter().map(|c| c.bytes()).sum()
    }
}
