//! Species edits reaching living jellyfish: a changed asset, or a new species handle.

use super::JellyfishSlice;
use super::pool::SpeciesPool;
use super::tier::tier_species;
use crate::plugin::interpolation::SliceHistory;
use crate::plugin::jellyfish::Jellyfish;
use crate::plugin::species_asset::{Refusals, SpeciesRejected};
use crate::plugin::swimming::SwimMotion;
use crate::sim::SliceSim;
use crate::species::{Species, SpeciesError};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;

/// A jellyfish given another species handle, or whose species asset changed.
type SpeciesChanged = Or<(Changed<Jellyfish>, AssetChanged<Jellyfish>)>;

/// A live slice took an edited species: its cycle is wanted for when it moves away (the
/// levels of detail record it a few steps a frame).
#[derive(Message, Clone, Debug)]
pub(crate) struct SliceEdited(pub Species);

/// Applies edited species assets and a jellyfish's new species handle to living slices
/// through [`SliceSim::set_species`](crate::sim::SliceSim::set_species), which refuses an invalid species before changing
/// anything. A far jellyfish wants the new species' recorded cycle (the levels of detail
/// switch it once recorded). Only jellyfish whose species asset or handle changed are
/// visited (`AssetChanged`), not every one each frame.
pub(super) fn apply_edits(
    mut jellyfish: Query<
        (
            &Jellyfish,
            &mut JellyfishSlice,
            &mut SliceHistory,
            &mut SwimMotion,
        ),
        SpeciesChanged,
    >,
    species: Res<Assets<Species>>,
    mut edited: MessageWriter<SliceEdited>,
    mut refusals: ResMut<Refusals>,
    mut rejected: MessageWriter<SpeciesRejected>,
    mut pool: ResMut<SpeciesPool>,
) {
    // Each edited species is checked against its limits once, not once for each of the
    // hundreds of jellyfish it reaches.
    let mut checked: HashMap<AssetId<Species>, Result<(), SpeciesError>> = HashMap::default();
    for (jelly, mut slice, mut history, mut motion) in &mut jellyfish {
        let id = jelly.species.id();
        let Some(simulated) = species.get(id) else {
            continue;
        };
        let slice = &mut *slice;
        if !slice.started() || *simulated == *slice.species {
            continue;
        }
        let valid = checked.entry(id).or_insert_with(|| simulated.validate());
        match valid
            .clone()
            .and_then(|()| apply(slice, &mut history, &mut motion, simulated, &mut edited))
        {
            Ok(()) => slice.species = pool.intern(simulated),
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

/// One jellyfish's slice (or replay) takes `species`, validated, at its tier.
fn apply(
    slice: &mut JellyfishSlice,
    history: &mut SliceHistory,
    motion: &mut SwimMotion,
    species: &Species,
    edited: &mut MessageWriter<SliceEdited>,
) -> Result<(), SpeciesError> {
    let simulated = tier_species(species, slice.tier);
    slice.anchor = None;
    if let Some(sim) = slice.sim.as_mut() {
        // Its cycle, for when it moves away: recorded a few steps a frame from now.
        edited.write(SliceEdited(species.clone()));
        let clock = sim.clock().clone();
        sim.set_species(&simulated)?;
        let topology = history
            .newest()
            .is_none_or(|s| s.shape().bell.len() != sim.view().bell.len());
        // A new shape or a new step (the stored times are the old clock's).
        if topology || *sim.clock() != clock {
            history.restart(sim, motion.pose);
        }
        slice.rest_bell = sim.view().rest_bell.to_vec();
        motion.swum = sim.swim_distance();
        slice.show(history);
    } else if let Some(replay) = slice.replay.as_mut() {
        replay.wanted = Some(simulated);
    } else if let Some(clock) = slice.pending.as_mut() {
        *clock = clock.retimed(simulated.period(), SliceSim::steps_per_cycle(&simulated));
    }
    Ok(())
}
