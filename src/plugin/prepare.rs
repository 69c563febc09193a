//! Slices for new jellyfish, and species edits reaching living ones.

use super::JellyfishSystems;
use super::asset::{Refusals, SpeciesRejected};
use super::components::{Jellyfish, JellyfishSlice, Pose, SwimMotion};
use super::detail::{CycleCaches, switch_cycle, tier_species};
use super::events::{Lifecycle, LifecycleQueue};
use crate::sim::SliceSim;
use crate::species::{Species, SpeciesError};
use bevy::platform::collections::HashSet;
use bevy::prelude::*;
use bevy::utils::Parallel;

pub(super) fn plugin(app: &mut App) {
    app.add_systems(
        PreUpdate,
        (apply_edits, create_slices, super::detail::change_tiers)
            .chain()
            .in_set(JellyfishSystems::Prepare)
            .after(super::asset::forget_changed),
    );
}

/// At most this many slices are built in one frame: a school of hundreds spawned at once
/// starts over a few frames instead of in one long one. A count, not a time budget, so
/// which jellyfish start when is the same in every run.
pub const NEW_SLICES_PER_FRAME: usize = 32;

/// Builds the slice of each jellyfish whose species has loaded, in parallel, the lowest
/// entities first, at most [`NEW_SLICES_PER_FRAME`] a frame. The phase offset starts the
/// clock mid-stroke, which also decides which frames the slice steps on, spreading
/// the load.
fn create_slices(
    mut jellyfish: Query<(
        Entity,
        &Jellyfish,
        &mut JellyfishSlice,
        &mut SwimMotion,
        &Transform,
    )>,
    species: Res<Assets<Species>>,
    mut edits: MessageReader<AssetEvent<Species>>,
    mut refused: Local<Refused>,
    mut refusals: ResMut<Refusals>,
    mut rejected: MessageWriter<SpeciesRejected>,
    events: Res<LifecycleQueue>,
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
    jellyfish
        .par_iter_mut()
        .for_each(|(entity, jelly, mut slice, mut motion, transform)| {
            if !chosen.contains(&entity) {
                return;
            }
            let Some(simulated) = species.get(&jelly.species) else {
                return;
            };
            match SliceSim::new(simulated) {
                Ok(mut sim) => {
                    let seed = jelly.seed_for(entity);
                    sim.set_time(jelly.phase_for(seed) * simulated.period());
                    let pose = Pose::of(transform);
                    *motion = SwimMotion {
                        pose,
                        swum: sim.swim_distance(),
                        ..default()
                    };
                    slice.start(sim, simulated.clone(), seed, pose);
                    events.push(entity, Lifecycle::Started);
                }
                Err(e) => queue.scope(|v| v.push((entity, jelly.species.id(), e))),
            }
        });
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
struct Refused {
    queue: Parallel<Vec<(Entity, AssetId<Species>, SpeciesError)>>,
    failed: HashSet<Entity>,
}

/// A jellyfish given another species handle, or whose species asset changed.
type SpeciesChanged = Or<(Changed<Jellyfish>, AssetChanged<Jellyfish>)>;

/// Applies edited species assets and a jellyfish's new species handle to living slices
/// through [`SliceSim::set_species`], which refuses an invalid species before changing
/// anything. A far jellyfish takes the new species' recorded cycle. Only jellyfish whose
/// species asset or handle changed are visited (`AssetChanged`), not every one each frame.
fn apply_edits(
    mut jellyfish: Query<(&Jellyfish, &mut JellyfishSlice, &mut SwimMotion), SpeciesChanged>,
    species: Res<Assets<Species>>,
    mut caches: ResMut<CycleCaches>,
    mut refusals: ResMut<Refusals>,
    mut rejected: MessageWriter<SpeciesRejected>,
) {
    for (jelly, mut slice, mut motion) in &mut jellyfish {
        let id = jelly.species.id();
        let Some(simulated) = species.get(id) else {
            continue;
        };
        let slice = &mut *slice;
        if !slice.started() || *simulated == slice.species {
            continue;
        }
        match apply(slice, &mut motion, simulated, &mut caches) {
            Ok(()) => slice.species = simulated.clone(),
            Err(error) => {
                if refusals.say(id, &error, &mut rejected) {
                    error!(
                        "jellyfish species {id} edit refused, keeping the last valid parameters: {error}"
                    );
                }
            }
        }
    }
}

/// One jellyfish's slice (or replay) takes `species`, at its tier.
fn apply(
    slice: &mut JellyfishSlice,
    motion: &mut SwimMotion,
    species: &Species,
    caches: &mut CycleCaches,
) -> Result<(), SpeciesError> {
    species.validate()?;
    let simulated = tier_species(species, slice.tier);
    slice.anchor = None;
    if let Some(sim) = slice.sim.as_mut() {
        // Its cycle, for when it moves away: recorded in the background from now.
        caches.request(species);
        let clock = sim.clock().clone();
        sim.set_species(&simulated)?;
        let topology = slice
            .history
            .newest()
            .is_none_or(|s| s.bell.len() != sim.view().bell.len());
        // A new shape or a new step (the stored times are the old clock's).
        if topology || *sim.clock() != clock {
            slice.history.restart(sim, motion.pose);
        }
        slice.rest_bell = sim.view().rest_bell.to_vec();
        motion.swum = sim.swim_distance();
    } else if let Some(replay) = slice.replay.as_mut() {
        match caches.request(&simulated) {
            Some(cache) => switch_cycle(slice, cache),
            None => replay.wanted = Some(simulated),
        }
    }
    Ok(())
}
