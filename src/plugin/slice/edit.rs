//! Species edits reaching living jellyfish: a changed asset, or a new species handle.

use super::JellyfishSlice;
use super::pool::SpeciesPool;
use super::tier::{Tier, tier_species};
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

/// Applies edited species assets and a jellyfish's new species handle to living slices:
/// an invalid species is refused before anything changes; a live slice takes a valid one
/// through [`SliceSim::set_species`](crate::sim::SliceSim::set_species) when it next
/// steps. A far jellyfish wants the new species' recorded cycle (the levels of detail
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
    // Each edited species is checked against its limits once (and its mid tier's variant
    // once), not once for each of the hundreds of jellyfish it reaches.
    let mut checked: HashMap<(AssetId<Species>, Tier), Result<(), SpeciesError>> =
        HashMap::default();
    // The cycles wanted: one for each species edited, however many live slices it reaches.
    let mut announced: Vec<AssetId<Species>> = Vec::new();
    for (jelly, mut slice, mut history, mut motion) in &mut jellyfish {
        let id = jelly.species.id();
        let Some(simulated) = species.get(id) else {
            continue;
        };
        let slice = &mut *slice;
        if !slice.started() || *simulated == *slice.species {
            continue;
        }
        let valid = checked
            .entry((id, slice.tier))
            .or_insert_with(|| {
                simulated.validate()?;
                match slice.tier {
                    Tier::Mid => tier_species(simulated, Tier::Mid).validate(),
                    _ => Ok(()),
                }
            })
            .clone();
        match valid {
            Ok(()) => {
                if slice.sim.is_some() && !announced.contains(&id) {
                    announced.push(id);
                    edited.write(SliceEdited(simulated.clone()));
                }
                apply(slice, &mut history, &mut motion, simulated);
                slice.species = pool.intern(simulated);
            }
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

/// One jellyfish's slice (or replay) takes `species`, validated, at its tier. A live
/// slice takes it when it is next used ([`PendingEdit`](super::PendingEdit)), in
/// parallel with the others; its cycle is wanted for when it moves away, recorded a few
/// steps a frame from now (`SliceEdited`).
fn apply(
    slice: &mut JellyfishSlice,
    history: &mut SliceHistory,
    motion: &mut SwimMotion,
    species: &Species,
) {
    let simulated = tier_species(species, slice.tier);
    slice.anchor = None;
    if slice.sim.is_some() {
        // One left and not yet taken (the slices did not step since) is taken first.
        if slice.edit.waiting() {
            slice.take_edit(history, motion);
        }
        slice.edit.leave(simulated);
    } else if let Some(replay) = slice.replay.as_mut() {
        replay.wanted = Some(simulated);
    } else if let Some(clock) = slice.pending.as_mut() {
        *clock = clock.retimed(simulated.period(), SliceSim::steps_per_cycle(&simulated));
    }
}
