//! Lifecycle events a game can observe on a jellyfish entity:
//! `commands.entity(e).observe(|stroke: On<StrokeStarted>| …)` or a global `add_observer`.
//!
//! The parallel stepping queues them; they are triggered once a frame, after
//! [`JellyfishSystems::StepSlices`](super::JellyfishSystems), in entity order, so a replay
//! sees them in the same order.

use bevy::prelude::*;
use bevy::utils::Parallel;

/// A jellyfish's slice has started: its species loaded and validated.
#[derive(EntityEvent, Clone, Copy, Debug, PartialEq, Reflect)]
pub struct JellyfishStarted {
    /// The jellyfish.
    pub entity: Entity,
}

/// A stroke began: the bell starts to contract (the phase came round to zero).
#[derive(EntityEvent, Clone, Copy, Debug, PartialEq, Reflect)]
pub struct StrokeStarted {
    /// The jellyfish.
    pub entity: Entity,
    /// Strokes completed before this one.
    pub cycle: u64,
}

/// A blown-up slice was detected and restarted at rest (see `SliceSim::recoveries`).
#[derive(EntityEvent, Clone, Copy, Debug, PartialEq, Reflect)]
pub struct SliceRecovered {
    /// The jellyfish.
    pub entity: Entity,
    /// Recoveries of this slice so far.
    pub recoveries: u32,
}

/// What happened to a jellyfish during the parallel systems of a frame.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Lifecycle {
    Started,
    Stroke(u64),
    Recovered(u32),
}

/// Filled by any thread, drained once a frame.
#[derive(Resource, Default)]
pub(crate) struct LifecycleQueue(Parallel<Vec<(Entity, Lifecycle)>>);

impl LifecycleQueue {
    pub fn push(&self, entity: Entity, what: Lifecycle) {
        self.0.scope(|v| v.push((entity, what)));
    }
}

pub(super) fn trigger_lifecycle(mut queue: ResMut<LifecycleQueue>, mut commands: Commands) {
    let mut all: Vec<(Entity, Lifecycle)> = queue.0.drain().collect();
    all.sort_by_key(|(e, _)| *e);
    for (entity, what) in all {
        match what {
            Lifecycle::Started => commands.trigger(JellyfishStarted { entity }),
            Lifecycle::Stroke(cycle) => commands.trigger(StrokeStarted { entity, cycle }),
            Lifecycle::Recovered(recoveries) => {
                commands.trigger(SliceRecovered { entity, recoveries })
            }
        }
    }
}
