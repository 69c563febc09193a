//! New jellyfish started once their species has loaded: each on its own clock, its slice
//! or replay built once the levels of detail have given it a tier.

use super::JellyfishSlice;
use super::events::{Lifecycle, LifecycleQueue};
use super::pool::SpeciesPool;
use crate::plugin::interpolation::SliceHistory;
use crate::plugin::jellyfish::Jellyfish;
use crate::plugin::species_asset::{Refusals, SpeciesRejected};
use crate::plugin::swimming::{Pose, SwimMotion};
use crate::sim::SliceSim;
use crate::sim::clock::FixedClock;
use crate::species::{Species, SpeciesError};
use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;
use bevy::utils::Parallel;
use std::sync::Arc;

/// At most this many jellyfish start in one frame: a school of hundreds spawned at once
/// starts over a few frames instead of in one long one (each near or mid one builds a
/// slice). A count, not a time budget, so which jellyfish start when is the same in every
/// run.
pub(crate) const NEW_SLICES_PER_FRAME: usize = 32;

/// Starts each jellyfish whose species has loaded (validated, or refused with the reason),
/// the lowest entities first, at most [`NEW_SLICES_PER_FRAME`] a frame. The phase offset
/// starts the clock mid-stroke, which also decides which frames the slice steps on,
/// spreading the load. Nothing is built yet: the levels of detail start a far one on its
/// species' recorded cycle and a mid one from it; one left near builds its slice when the
/// slices step (`JellyfishSlice::build_pending`).
#[allow(clippy::too_many_arguments)] // a system's parameters
pub(super) fn create_slices(
    mut jellyfish: Query<(
        Entity,
        &Jellyfish,
        &mut JellyfishSlice,
        &mut SliceHistory,
        &mut SwimMotion,
        &Transform,
    )>,
    species: Res<Assets<Species>>,
    mut edits: MessageReader<AssetEvent<Species>>,
    mut refused: Local<Refused>,
    mut refusals: ResMut<Refusals>,
    mut rejected: MessageWriter<SpeciesRejected>,
    events: Res<LifecycleQueue>,
    mut pool: ResMut<SpeciesPool>,
) {
    let Refused { queue, failed } = &mut *refused;
    // A refused species is retried only after an edit, so the error is logged once.
    if edits.read().count() > 0 {
        failed.clear();
    }
    let mut waiting: Vec<Entity> = jellyfish
        .iter()
        .filter(|(e, jelly, slice, ..)| {
            !slice.started() && !failed.contains(e) && species.contains(&jelly.species)
        })
        .map(|(e, ..)| e)
        .collect();
    waiting.sort_unstable();
    waiting.truncate(NEW_SLICES_PER_FRAME);
    let chosen: HashSet<Entity> = waiting.into_iter().collect();
    // Each chosen jellyfish's species, interned.
    let interned: HashMap<AssetId<Species>, Arc<Species>> = chosen
        .iter()
        .filter_map(|e| jellyfish.get(*e).ok())
        .filter_map(|(_, jelly, ..)| {
            let id = jelly.species.id();
            Some((id, pool.intern(species.get(id)?)))
        })
        .collect();
    jellyfish.par_iter_mut().for_each(
        |(entity, jelly, mut slice, mut history, mut motion, transform)| {
            if !chosen.contains(&entity) {
                return;
            }
            let Some(simulated) = interned.get(&jelly.species.id()) else {
                return;
            };
            match simulated.validate() {
                Ok(()) => {
                    let seed = jelly.seed_for(entity);
                    let mut clock =
                        FixedClock::new(simulated.period(), SliceSim::steps_per_cycle(simulated));
                    clock.start_at((jelly.phase_for(seed) * simulated.period()) as f64);
                    *motion = SwimMotion {
                        pose: Pose::of(transform),
                        ..default()
                    };
                    slice.start(&mut history, clock, simulated.clone(), seed);
                    events.push(entity, Lifecycle::Started);
                }
                Err(e) => queue.scope(|v| v.push((entity, jelly.species.id(), e))),
            }
        },
    );
    for (entity, id, error) in queue.drain() {
        failed.insert(entity);
        if refusals.say(id, &error, &mut rejected) {
            error!("jellyfish species {id} refused: {error}");
        }
    }
    failed.retain(|e| jellyfish.contains(*e));
}

/// Slices that could not be built; they are retried once a species is edited.
#[derive(Default)]
pub(super) struct Refused {
    queue: Parallel<Vec<(Entity, AssetId<Species>, SpeciesError)>>,
    failed: HashSet<Entity>,
}
