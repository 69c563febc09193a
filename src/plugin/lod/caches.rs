//! The recorded stroke cycles far jellyfish replay and nearer ones resume from.

use crate::plugin::settings::JellyfishSettings;
use crate::sim::cycle::{CycleCache, CycleRecorder};
use crate::species::Species;
use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, block_on};
use std::sync::Arc;

/// The recorded cycle of every species (and its compact-box variant) a far or resuming
/// jellyfish has needed. Recording one costs 10 to 60 cycles of one slice (0.1–0.4 s): it
/// is done when first needed, in that frame, so which jellyfish are far is the same in
/// every run; after an edit it is recorded a few steps a frame
/// ([`DetailLevels::recording_steps_per_frame`](crate::plugin::DetailLevels)) in the
/// background while far jellyfish play the old cycle, so dragging an editor slider
/// neither stalls the app nor, in a game that waits for its display, lengthens its
/// frames.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct CycleCaches {
    #[reflect(ignore)]
    caches: Vec<Arc<CycleCache>>,
    #[reflect(ignore)]
    recording: Vec<Recording>,
}

/// A cycle recorded after an edit, a chunk of steps at a time: each chunk is started at
/// the end of a frame ([`record_cycles`]) and taken up by the next frame's levels of
/// detail ([`CycleCaches::collect`]), running in between on Bevy's async compute pool,
/// while the frame is drawn and the game waits for its display, instead of inside the
/// frame's own work. A chunk is a count of steps and is always waited for, so the cycle
/// arrives on the same frame in every run, however quickly the pool ran it.
struct Recording {
    species: Species,
    chunk: Chunk,
}

/// The cycle once recorded, or the recorder to go on with.
type Outcome = Result<Box<CycleCache>, Box<CycleRecorder>>;

/// Where a [`Recording`] is between two frames.
enum Chunk {
    /// Waiting for its next chunk.
    Idle(Box<CycleRecorder>),
    /// Taking a chunk in the background.
    Running(Task<Outcome>),
    /// Took its chunk in place: no async pool to wait for.
    Took(Outcome),
}

impl Recording {
    /// Starts the next chunk of `steps` steps, if none is under way.
    fn start(self, steps: u32) -> Self {
        let Chunk::Idle(mut recorder) = self.chunk else {
            return self;
        };
        let take = move || recorder.advance(steps).map(Box::new).ok_or(recorder);
        // A pool without threads (or the web's, run between frames) cannot be waited for.
        let chunk = match AsyncComputeTaskPool::try_get() {
            Some(pool) if pool.thread_num() > 0 && cfg!(not(target_arch = "wasm32")) => {
                Chunk::Running(pool.spawn(async move { take() }))
            }
            _ => Chunk::Took(take()),
        };
        Self { chunk, ..self }
    }

    /// Waits for the chunk under way: the cycle once done, or the recording idle again.
    fn finish(self) -> Result<Box<CycleCache>, Box<Self>> {
        let outcome = match self.chunk {
            Chunk::Idle(_) => return Err(Box::new(self)),
            Chunk::Running(task) => block_on(task),
            Chunk::Took(outcome) => outcome,
        };
        outcome.map_err(|recorder| {
            Box::new(Self {
                species: self.species,
                chunk: Chunk::Idle(recorder),
            })
        })
    }
}

/// Starts the next chunk of every recording
/// ([`DetailLevels::recording_steps_per_frame`](crate::plugin::DetailLevels) steps).
pub(super) fn record_cycles(mut caches: ResMut<CycleCaches>, settings: Res<JellyfishSettings>) {
    caches.record(settings.detail.recording_steps_per_frame);
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
            self.recording.push(Recording {
                species: species.clone(),
                chunk: Chunk::Idle(Box::new(recorder)),
            });
        }
        None
    }

    /// Takes up the chunks of steps started last frame ([`Self::record`]), waiting for
    /// any still running, and keeps the cycles that are done, in the order they were
    /// asked for.
    pub fn collect(&mut self) {
        for recording in std::mem::take(&mut self.recording) {
            match recording.finish() {
                Ok(cache) => self.caches.push(Arc::new(*cache)),
                Err(recording) => self.recording.push(*recording),
            }
        }
    }

    /// Starts `steps` more steps (at least one) of every recording, in the background
    /// until the next [`Self::collect`]: a budget of none would hold far jellyfish on the
    /// old cycle, and the tier changes of the edited species, for ever.
    pub fn record(&mut self, steps: u32) {
        let steps = steps.max(1);
        self.recording = std::mem::take(&mut self.recording)
            .into_iter()
            .map(|r| r.start(steps))
            .collect();
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
    /// dropped, which cancels them (a chunk under way is left to end on its own).
    pub(super) fn retain(&mut self, in_use: &[Species]) {
        self.caches.retain(|c| in_use.contains(c.species()));
        self.recording.retain(|r| in_use.contains(&r.species));
    }

    /// Whether the cycle of `species` is being recorded.
    pub fn is_recording(&self, species: &Species) -> bool {
        self.recording.iter().any(|r| &r.species == species)
    }

    /// Heap bytes held.
    pub fn bytes(&self) -> usize {
        self.caches.iter().map(|c| c.bytes()).sum()
    }
}
