//! Moving jellyfish between tiers, continuing from where each is in its stroke: a far one
//! takes its species' recorded cycle at its phase, a nearer one resumes the recorded slice
//! state; what differs in shape fades out over a quarter stroke.

use super::caches::CycleCaches;
use super::choose::{Eye, Rank, changes};
use crate::plugin::interpolation::{SliceHistory, Snapshot};
use crate::plugin::render::JellyfishMeshes;
use crate::plugin::settings::JellyfishSettings;
use crate::plugin::slice::{
    JellyfishSlice, LiveSlice, Replay, SliceEdited, Tier, same, tier_species,
};
use crate::plugin::swimming::SwimMotion;
use crate::plugin::timings::JellyfishTimings;
use crate::sim::clock::FixedClock;
use crate::sim::cycle::CycleCache;
use crate::species::Species;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::utils::Parallel;
use std::sync::Arc;

/// A jellyfish as the levels of detail see it.
type Detailed = (
    Entity,
    &'static mut JellyfishSlice,
    &'static mut SliceHistory,
    &'static mut SwimMotion,
    Option<&'static JellyfishMeshes>,
    &'static GlobalTransform,
    Has<LiveSlice>,
);

/// Moves jellyfish between tiers: demotions at once, promotions (the costly way) up to
/// [`DetailLevels::promotions_per_frame`], nearest first.
#[allow(clippy::too_many_arguments)]
pub(super) fn change_tiers(
    cameras: Query<(Entity, &Camera, &GlobalTransform, &Projection)>,
    mut jellyfish: Query<Detailed>,
    settings: Res<JellyfishSettings>,
    mut caches: ResMut<CycleCaches>,
    mut edited: MessageReader<SliceEdited>,
    timings: Res<JellyfishTimings>,
    mut commands: Commands,
    mut survey: Local<Parallel<Survey>>,
) {
    // One look over every jellyfish, side by side: the species in use, the live marks to
    // mend, the far ones waiting for an edited cycle, and each one's size on screen.
    let eye = Eye::of(&cameras);
    jellyfish.par_iter().for_each_init(
        || survey.borrow_local_mut(),
        |local, (entity, slice, _, _, meshes, transform, marked)| {
            let live = is_live(slice);
            if live != marked {
                local.marks.push((entity, live));
            }
            if !local.species.iter().any(|s| same(s, &slice.species)) {
                local.species.push(slice.species.clone());
            }
            if slice.replay.as_ref().is_some_and(|r| r.wanted.is_some()) {
                local.wanting.push(entity);
            }
            local
                .ranks
                .extend(eye.rank(entity, slice, meshes, transform));
        },
    );
    let (mut marks, mut wanting, mut ranks) = (Vec::new(), Vec::new(), Vec::new());
    let mut in_use: Vec<Species> = Vec::new();
    for local in survey.iter_mut() {
        for species in local.species.drain(..) {
            if !in_use.contains(&*species) {
                in_use.push(Species::clone(&species));
                in_use.push(tier_species(&species, Tier::Mid));
            }
        }
        marks.append(&mut local.marks);
        wanting.append(&mut local.wanting);
        ranks.append(&mut local.ranks);
    }
    // Threads split the work differently each run: entity order makes it one order.
    marks.sort_unstable_by_key(|&(e, _)| e);
    wanting.sort_unstable();
    for (entity, live) in marks {
        mark(&mut commands, entity, live);
    }
    // Drop cycles of species no jellyfish has any more (after edits).
    caches.retain(&in_use);
    // The cycles of live slices just edited, for when they move away: recorded a few
    // steps a frame from now, the mid tier's compact variant too (recorded in the frame a
    // jellyfish first moved to it, it stalled that frame by a tenth of a second or more).
    let mut edits: Vec<Species> = Vec::new();
    for SliceEdited(species) in edited.read() {
        if !edits.contains(species) {
            edits.push(species.clone());
        }
    }
    // Far jellyfish of an edited species take its cycle once it is recorded: asked for
    // once a frame for each species wanted, not once for each of its far jellyfish.
    caches.collect();
    let mut asked: Vec<(Species, Option<Arc<CycleCache>>)> = Vec::new();
    let mut waiting = jellyfish.iter_many_mut(&wanting);
    while let Some((_, mut slice, mut history, ..)) = waiting.fetch_next() {
        let Some(wanted) = slice.replay.as_ref().and_then(|r| r.wanted.as_ref()) else {
            continue;
        };
        let answer = match asked.iter().find(|(s, _)| s == wanted) {
            Some((_, answer)) => answer.clone(),
            None => {
                let answer = caches.request(wanted);
                if answer.is_none() && !edits.contains(wanted) {
                    edits.push(wanted.clone());
                }
                asked.push((wanted.clone(), answer.clone()));
                answer
            }
        };
        if let Some(cache) = answer {
            switch_cycle(&mut slice, &mut history, cache);
        }
    }
    for species in &edits {
        caches.request(species);
        caches.request(&tier_species(species, Tier::Mid));
    }
    let ranked = &jellyfish;
    let levels = &settings.detail;
    let mut changes = changes(ranks, levels);
    if changes.is_empty() {
        return;
    }
    // Nearer tiers first; at most so many promotions.
    let mut promotions = 0;
    changes.retain(|(e, tier)| {
        let from = ranked.get(*e).map_or(Tier::Far, |(_, s, ..)| s.tier);
        if *tier < from {
            promotions += 1;
            promotions <= levels.promotions_per_frame
        } else {
            true
        }
    });
    // What each tier of each species simulates (deciding it validates a species).
    let mut variants: Vec<(Arc<Species>, Tier, Species)> = Vec::new();
    for (e, tier) in &changes {
        if let Ok((_, slice, ..)) = ranked.get(*e)
            && !variants
                .iter()
                .any(|(s, t, _)| same(s, &slice.species) && t == tier)
        {
            let simulated = tier_species(&slice.species, *tier);
            variants.push((slice.species.clone(), *tier, simulated));
        }
    }
    // A species being recorded (just edited) changes tier once it is ready, instead of
    // recording it again here and stalling the frame.
    variants.retain(|(.., simulated)| !caches.is_recording(simulated));
    caches.prepare(variants.iter().map(|v| v.2.clone()).collect());
    let plan: HashMap<Entity, (Tier, Arc<CycleCache>)> = changes
        .iter()
        .filter_map(|(e, tier)| {
            let (_, slice, ..) = ranked.get(*e).ok()?;
            let (.., simulated) = variants
                .iter()
                .find(|(s, t, _)| same(s, &slice.species) && t == tier)?;
            Some((*e, (*tier, caches.find(simulated)?)))
        })
        .collect();
    timings.add_tier_changes(plan.len());
    jellyfish
        .par_iter_mut()
        .for_each(|(entity, mut slice, mut history, mut motion, ..)| {
            if let Some((tier, cache)) = plan.get(&entity) {
                move_to(&mut slice, &mut history, &mut motion, *tier, cache.clone());
            }
        });
    // Whatever the first pass queued for them, their new tiers decide.
    for (entity, slice, ..) in jellyfish.iter_many(plan.keys()) {
        mark(&mut commands, entity, is_live(slice));
    }
}

/// Whether a jellyfish is a live slice ([`LiveSlice`]): started, and near or mid.
fn is_live(slice: &JellyfishSlice) -> bool {
    slice.started() && slice.tier != Tier::Far
}

/// Marks a jellyfish a live slice, or not ([`LiveSlice`]).
fn mark(commands: &mut Commands, entity: Entity, live: bool) {
    if live {
        commands.entity(entity).try_insert(LiveSlice);
    } else {
        commands.entity(entity).try_remove::<LiveSlice>();
    }
}

/// What one look over every jellyfish finds, on one thread.
#[derive(Default)]
pub(super) struct Survey {
    species: Vec<Arc<Species>>,
    marks: Vec<(Entity, bool)>,
    wanting: Vec<Entity>,
    ranks: Vec<Rank>,
}

/// A far jellyfish takes another cycle (its species was edited), at the same phase.
fn switch_cycle(slice: &mut JellyfishSlice, history: &mut SliceHistory, cache: Arc<CycleCache>) {
    let Some(replay) = slice.replay.as_mut() else {
        return;
    };
    let species = cache.species();
    replay.clock = replay
        .clock
        .retimed(species.period(), species.steps_per_cycle());
    let mut now = Snapshot::default();
    let time = replay.clock.time();
    now.copy_frame(&cache, replay.index(), time, replay.swim as f32);
    history.change_tier(&now, time, fade(&replay.clock));
    slice.rest_bell = cache.rest_bell().to_vec();
    replay.cache = cache;
    replay.wanted = None;
    slice.anchor = None;
}

/// Steps over which a change of shape fades out: a quarter stroke.
fn fade(clock: &FixedClock) -> u32 {
    (clock.steps_per_cycle() / 4).max(1)
}

/// Moves one jellyfish to `tier`, continuing from where it is in its stroke.
fn move_to(
    slice: &mut JellyfishSlice,
    history: &mut SliceHistory,
    motion: &mut SwimMotion,
    tier: Tier,
    cache: Arc<CycleCache>,
) {
    // It leaves its tier as the edited species it is.
    if slice.edit.waiting() {
        slice.take_edit(history, motion);
    }
    let Some(clock) = slice.clock().cloned() else {
        return;
    };
    let species = cache.species();
    let from = clock.steps_per_cycle();
    let clock = clock.retimed(species.period(), species.steps_per_cycle());
    let index = (clock.stroke_steps() % clock.steps_per_cycle() as u64) as u32;
    // An escape under way carries on at the new level, as far along.
    let escape = match (&slice.sim, &slice.replay) {
        (Some(sim), _) => sim.escaping().cloned(),
        (None, Some(replay)) => replay.escape.clone(),
        _ => None,
    }
    .map(|e| e.retimed(from, clock.steps_per_cycle()));
    let mut now = Snapshot::default();
    let fade = fade(&clock);
    if tier == Tier::Far {
        let replay = Replay {
            cache: cache.clone(),
            clock,
            swim: 0.0,
            wanted: None,
            escape,
        };
        now.copy_frame(&cache, index, replay.clock.time(), 0.0);
        motion.swum = 0.0;
        if slice.fresh {
            history.restart_at(&replay.clock, &now, motion.pose);
            slice.rest_bell = cache.rest_bell().to_vec();
        } else {
            history.change_tier(&now, replay.clock.time(), fade);
        }
        slice.sim = None;
        slice.replay = Some(replay);
    } else {
        let mut sim = cache.resume(index);
        sim.set_clock(clock);
        sim.resume_escape(escape);
        now.capture(&sim);
        motion.swum = sim.swim_distance();
        if slice.fresh {
            history.restart_at(sim.clock(), &now, motion.pose);
            slice.rest_bell = sim.view().rest_bell.to_vec();
        } else {
            history.change_tier(&now, sim.clock().time(), fade);
        }
        slice.sim = Some(sim);
        slice.replay = None;
    }
    slice.tier = tier;
    slice.anchor = None;
    slice.pending = None;
}
