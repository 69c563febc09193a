//! The slice: each jellyfish's 2D simulation (or, far from the camera, its species'
//! recorded stroke cycle), created when its species has loaded, told of species edits,
//! and stepped by the frame's virtual time.

mod create;
mod edit;
mod events;
mod pool;
mod step;
mod tier;

pub(crate) use edit::SliceEdited;
pub use events::{JellyfishStarted, SliceRecovered, StrokeStarted};
pub(crate) use pool::{SpeciesPool, same};
pub(crate) use step::{ONE_AT_A_TIME, SMALL_BATCHES};
pub use tier::Tier;
pub(crate) use tier::{LiveSlice, Replay, tier_species};

use super::interpolation::SliceHistory;
use super::jellyfish::Jellyfish;
use super::schedule::JellyfishSystems;
use super::swimming::{Pose, SwimMotion};
use crate::sim::SliceSim;
use crate::sim::clock::FixedClock;
use crate::species::{Species, SpeciesError};
use bevy::math::Vec2;
use bevy::prelude::*;
use std::sync::Arc;

/// Builds, edits and steps every jellyfish's slice, and triggers its lifecycle events.
#[derive(Clone, Copy, Debug, Default)]
pub struct SlicePlugin;

impl Plugin for SlicePlugin {
    fn build(&self, app: &mut App) {
        app.register_required_components::<Jellyfish, JellyfishSlice>()
            .register_type::<Jellyfish>()
            .register_type::<JellyfishSlice>()
            .register_type::<Tier>()
            .register_type::<JellyfishStarted>()
            .register_type::<StrokeStarted>()
            .register_type::<SliceRecovered>()
            .init_resource::<events::LifecycleQueue>()
            .init_resource::<SpeciesPool>()
            .add_message::<SliceEdited>()
            .add_systems(
                PreUpdate,
                (edit::apply_edits, create::create_slices)
                    .chain()
                    .in_set(JellyfishSystems::Prepare),
            )
            .add_systems(
                PostUpdate,
                (step::step_slices, events::trigger_lifecycle)
                    .chain()
                    .in_set(JellyfishSystems::StepSlices),
            );
    }
}

/// A species edit on its way to a live slice. `apply_edits` only leaves it here; the slice
/// takes it where it is next used (stepped, moved between tiers, startled), so that the
/// hundred slices an edit reaches take it in parallel, while they step. Nothing reads a
/// live slice in between, so the result is the same bits as taking it at once.
#[derive(Default)]
pub(crate) struct PendingEdit {
    /// The tier's variant of the edited species, validated.
    species: Option<Species>,
    /// The clock before the edit taken last, until the history has seen that edit.
    unseen: Option<FixedClock>,
}

impl PendingEdit {
    /// Leaves `species` for the slice, which has taken any edit left before
    /// ([`JellyfishSlice::take_edit`]).
    pub(crate) fn leave(&mut self, species: Species) {
        debug_assert!(!self.waiting(), "an edit left before was not taken");
        self.species = Some(species);
    }

    /// Whether anything is left for the slice or its history.
    pub(crate) fn waiting(&self) -> bool {
        self.species.is_some() || self.unseen.is_some()
    }

    /// The slice takes the edit left for it.
    fn take_into(&mut self, sim: Option<&mut SliceSim>) {
        let (Some(species), Some(sim)) = (self.species.take(), sim) else {
            return;
        };
        let before = sim.clock().clone();
        match sim.set_valid_species(&species) {
            Ok(()) => {
                self.unseen.get_or_insert(before);
            }
            // Validated when it was left: only a failure to build the slice lands here.
            Err(error) => error!("a live slice could not take its species edit: {error}"),
        }
    }
}

/// The simulated slice (or, far from the camera, its species' recorded stroke cycle).
///
/// Empty until the species asset has loaded.
#[derive(Component, Default, Reflect)]
#[reflect(Component, Default)]
pub struct JellyfishSlice {
    /// The live slice (near and mid tiers).
    #[reflect(ignore)]
    pub(crate) sim: Option<SliceSim>,
    /// The replayed cycle (far tier).
    #[reflect(ignore)]
    pub(crate) replay: Option<Replay>,
    /// A species edit the live slice has not taken yet (its tier's variant, validated),
    /// and the clock it had before the last one it took that its history has not seen.
    #[reflect(ignore)]
    pub(crate) edit: PendingEdit,
    /// Started this frame, neither slice nor replay built yet: its clock, at its phase.
    /// The levels of detail start it in the tier they give it (a far one never builds a
    /// slice); one still waiting when the slices step starts near.
    #[reflect(ignore)]
    pub(crate) pending: Option<FixedClock>,
    pub(crate) tier: Tier,
    /// The species as simulated: the last valid one it was given (shared by every slice
    /// of an equal species, see [`SpeciesPool`]).
    #[reflect(ignore)]
    pub(crate) species: Arc<Species>,
    pub(crate) seed: u32,
    /// Distance swum and the bell's centroid at the newest recorded step.
    pub(crate) newest: (f32, Vec2),
    /// The bell at rest, which meshes measure contraction against.
    pub(crate) rest_bell: Vec<Vec2>,
    /// Virtual time and the clock's added time at one moment: the clock is set from the
    /// virtual time elapsed since (an exact count of nanoseconds), so frames that split
    /// the same time differently end at the same state. Reset when the clock is replaced.
    #[reflect(ignore)]
    pub(crate) anchor: Option<(std::time::Duration, f64)>,
    /// Started since the slices last stepped: no frame has shown it yet, so a change of
    /// tier before then has nothing to fade from (a school spawned at once starts each
    /// member in the tier the levels of detail give it).
    pub(crate) fresh: bool,
}

impl JellyfishSlice {
    /// The live slice, once its species has loaded and while it is near or mid (for debug
    /// overlays and tools; built when the slices first step it); `None` while it replays
    /// its species' cycle (far). A species edit reaches it when the slices step
    /// (`JellyfishSystems::StepSlices`), in the frame of the edit.
    pub fn sim(&self) -> Option<&SliceSim> {
        self.sim.as_ref()
    }

    /// The live slice, mutable: for testing recovery (`SliceSim::poison_for_tests`).
    /// Anything changed here is physics, outside the species' calibration.
    #[doc(hidden)]
    pub fn sim_mut_for_tests(&mut self) -> Option<&mut SliceSim> {
        self.sim.as_mut()
    }

    /// Whether it swims yet: its species has loaded (its slice or replay is built by the
    /// time the slices step, in the frame it starts).
    pub fn started(&self) -> bool {
        self.sim.is_some() || self.replay.is_some() || self.pending.is_some()
    }

    /// How much of it is simulated (see [`Tier`]).
    pub fn tier(&self) -> Tier {
        self.tier
    }

    /// The species the slice runs with: the last valid one it was given.
    pub fn species(&self) -> Option<&Species> {
        self.started().then_some(&self.species)
    }

    /// Its clock: the live slice's or the replay's.
    pub(crate) fn clock(&self) -> Option<&FixedClock> {
        match (&self.sim, &self.replay) {
            (Some(sim), _) => Some(sim.clock()),
            (None, Some(replay)) => Some(&replay.clock),
            _ => self.pending.as_ref(),
        }
    }

    /// Startles it with a touch of `strength` (0 to 1): live, its slice escapes
    /// (`SliceSim::escape`: deeper, quicker strokes); far, its replay plays the recorded
    /// cycle at the escape's quicker rhythm.
    pub fn escape(&mut self, strength: f32) {
        // The escape's rhythm is the edited species'.
        self.edit.take_into(self.sim.as_mut());
        if let Some(sim) = self.sim.as_mut() {
            sim.escape(strength);
        } else if let Some(replay) = self.replay.as_mut() {
            replay.escape(strength);
        }
    }

    /// Whether it is escaping (a touch quickened its strokes, and they have not eased
    /// back yet).
    pub fn escaping(&self) -> bool {
        match (&self.sim, &self.replay) {
            (Some(sim), _) => sim.escaping().is_some(),
            (None, Some(replay)) => replay.escape.is_some(),
            _ => false,
        }
    }

    /// Where it is in its stroke, in cycles [0, 1).
    pub fn phase(&self) -> Option<f32> {
        self.clock().map(FixedClock::phase)
    }

    /// The seed its surface noise was drawn with.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// Swim distance after the last step, m.
    pub fn swim_distance(&self) -> f32 {
        self.newest.0
    }

    /// A domain point of the newest step in the mesh's local frame (metres, origin at the
    /// bell's centroid): for overlays drawn over the jellyfish.
    pub fn to_local(&self, p: Vec2) -> Vec3 {
        (p - self.newest.1).extend(0.0)
    }

    /// The slice time a frame shows, s: the time added to the slice less one step, so
    /// that two stored steps always bracket it and a frame never waits for a step.
    pub fn display_time(&self) -> f64 {
        self.clock().map_or(0.0, |c| c.added() - c.step())
    }

    /// Starts it on `clock` (its phase offset, which also picks the frames it steps on),
    /// near unless the levels of detail move it before its first step; nothing is built
    /// yet ([`Self::pending`]).
    pub(crate) fn start(
        &mut self,
        history: &mut SliceHistory,
        clock: FixedClock,
        species: Arc<Species>,
        seed: u32,
    ) {
        self.pending = Some(clock);
        self.sim = None;
        self.replay = None;
        self.edit = PendingEdit::default();
        self.tier = Tier::Near;
        self.anchor = None;
        self.species = species;
        self.seed = seed;
        self.fresh = true;
        self.show(history);
    }

    /// Builds the live slice of a jellyfish started this frame and still waiting (near),
    /// at rest on its clock, its history starting there at `pose`.
    pub(crate) fn build_pending(
        &mut self,
        history: &mut SliceHistory,
        pose: Pose,
    ) -> Result<(), SpeciesError> {
        let Some(clock) = self.pending.take() else {
            return Ok(());
        };
        let mut sim = SliceSim::new(&self.species)?;
        sim.set_clock(clock);
        history.restart(&sim, pose);
        self.rest_bell = sim.view().rest_bell.to_vec();
        self.sim = Some(sim);
        self.show(history);
        Ok(())
    }

    /// Gives the live slice the species edit waiting for it, if any, and restarts its
    /// history where the edit changed its shape or its step.
    pub(crate) fn take_edit(&mut self, history: &mut SliceHistory, motion: &mut SwimMotion) {
        self.edit.take_into(self.sim.as_mut());
        let (Some(before), Some(sim)) = (self.edit.unseen.take(), self.sim.as_ref()) else {
            return;
        };
        let topology = history
            .newest()
            .is_none_or(|s| s.shape().bell.len() != sim.view().bell.len());
        // A new shape or a new step (the stored times are the old clock's).
        if topology || *sim.clock() != before {
            history.restart(sim, motion.pose);
        }
        self.rest_bell = sim.view().rest_bell.to_vec();
        motion.swum = sim.swim_distance();
        self.show(history);
    }

    /// Tells the history which time the frame shows, and keeps what its newest step says.
    pub(crate) fn show(&mut self, history: &mut SliceHistory) {
        history.show(self.display_time());
        self.newest = history
            .newest()
            .map_or((0.0, Vec2::ZERO), |s| (s.swim, s.centroid()));
    }
}
