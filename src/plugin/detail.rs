//! Levels of detail: how much of each jellyfish is simulated.
//!
//! - **Near**: the species' own slice, live.
//! - **Mid**: a live slice in a compact box (two thirds of the species' box, same cells,
//!   same step): about 0.6 of the cost, swimming 4 to 9 % slower (measured by
//!   `examples/lod.rs`). A coarser grid would be cheaper still but loses the stroke to
//!   numerical viscosity (grid 40 in the full box swims a fifth as far).
//! - **Far**: the species' recorded stroke cycle ([`CycleCache`]), replayed by phase with
//!   its swim surge step by step; no fluid at all.
//!
//! Tiers are chosen each frame from each jellyfish's size on screen and counts
//! ([`DetailLevels`]), never from measured time, so a replay chooses the same. A
//! jellyfish coming nearer resumes from the recorded slice state for its phase; any
//! difference of shape fades out over a quarter stroke.

use super::components::{JellyfishMeshes, JellyfishSlice, Snapshot, SwimMotion};
use super::diagnostics::JellyfishTimings;
use super::settings::JellyfishSettings;
use crate::sim::clock::FixedClock;
use crate::sim::cycle::{CycleCache, CycleFrame};
use crate::species::Species;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, block_on};
use std::sync::Arc;

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<CycleCaches>()
        .register_type::<Tier>()
        .register_type::<DetailLevels>()
        .register_type::<CycleCaches>();
}

/// How much of a jellyfish is simulated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Reflect)]
pub enum Tier {
    /// The species' slice, live.
    #[default]
    Near,
    /// A live slice in a compact box: cheaper, a few percent slower.
    Mid,
    /// The species' recorded stroke cycle, replayed: no fluid.
    Far,
}

/// How many jellyfish get each tier, and from what size on screen. The largest on screen
/// (bell diameter over the view's height, for the first active camera) are near, the next
/// mid, the rest far; jellyfish no camera sees rank last. With no camera, the lowest
/// entities are nearest.
#[derive(Clone, Debug, PartialEq, Reflect)]
pub struct DetailLevels {
    /// At most this many near jellyfish.
    pub near: usize,
    /// At most this many mid jellyfish.
    pub mid: usize,
    /// Smallest size on screen for near (fraction of the view's height).
    pub near_size: f32,
    /// Smallest size on screen for mid.
    pub mid_size: f32,
    /// A jellyfish keeps its tier until another outranks it by this fraction of its size,
    /// so one at the boundary does not flicker between tiers.
    pub hysteresis: f32,
    /// At most this many jellyfish move to a nearer tier in one frame (each resumes a
    /// slice: a copy and up to three steps).
    pub promotions_per_frame: usize,
}

impl Default for DetailLevels {
    fn default() -> Self {
        Self {
            near: 100,
            mid: 24,
            near_size: 0.0,
            mid_size: 0.0,
            hysteresis: 0.25,
            promotions_per_frame: 12,
        }
    }
}

impl DetailLevels {
    /// Every jellyfish near: no levels of detail.
    pub fn all_near() -> Self {
        Self {
            near: usize::MAX,
            ..default()
        }
    }
}

/// The species a tier simulates: the species itself near and far, its
/// [`Species::compact_box`] mid.
pub fn tier_species(species: &Species, tier: Tier) -> Species {
    if tier == Tier::Mid {
        species.compact_box()
    } else {
        species.clone()
    }
}

/// A far jellyfish's stroke: its species' recorded cycle, played on its own clock.
pub(crate) struct Replay {
    pub cache: Arc<CycleCache>,
    pub clock: FixedClock,
    /// Distance swum, m.
    pub swim: f64,
    /// An edited species whose cycle is being recorded: the old cycle plays until then.
    pub wanted: Option<Species>,
}

impl Replay {
    /// Sets the time added to `added` seconds and plays the steps that pays for;
    /// `after_step` sees each frame. Resting holds the frame where the stroke stopped and
    /// swims nowhere.
    pub fn advance_until(
        &mut self,
        added: f64,
        resting: bool,
        mut after_step: impl FnMut(&Self, &CycleFrame),
    ) {
        let cache = self.cache.clone();
        for _ in 0..self.clock.add_until(added) {
            if resting {
                self.clock.tick_held();
            } else {
                self.clock.tick();
            }
            let frame = cache.frame(self.index());
            if !resting {
                self.swim += frame.surge as f64;
            }
            after_step(self, frame);
        }
    }

    /// The place in the cycle of the state.
    pub fn index(&self) -> u32 {
        (self.clock.stroke_steps() % self.clock.steps_per_cycle() as u64) as u32
    }
}

/// The recorded cycle of every species (and its compact-box variant) a far or resuming
/// jellyfish has needed. Recording one costs 10 to 60 cycles of one slice (0.1–0.4 s): it
/// is done when first needed, in that frame, so which jellyfish are far is the same in
/// every run; after an edit it is recorded in the background while far jellyfish play the
/// old cycle, so dragging an editor slider does not stall the app.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct CycleCaches {
    #[reflect(ignore)]
    caches: Vec<Arc<CycleCache>>,
    #[reflect(ignore)]
    recording: Vec<(Species, Task<Option<CycleCache>>)>,
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

    /// The cycle of `species` if recorded; if not, starts recording it in the background
    /// (see [`Self::collect`]).
    pub fn request(&mut self, species: &Species) -> Option<Arc<CycleCache>> {
        if let Some(c) = self.find(species) {
            return Some(c);
        }
        if !self.recording.iter().any(|(s, _)| s == species) {
            let record = species.clone();
            let task =
                AsyncComputeTaskPool::get().spawn(async move { CycleCache::record(&record).ok() });
            self.recording.push((species.clone(), task));
        }
        None
    }

    /// Keeps the cycles recorded in the background that have finished.
    pub fn collect(&mut self) {
        let (done, running): (Vec<_>, Vec<_>) = std::mem::take(&mut self.recording)
            .into_iter()
            .partition(|(_, task)| task.is_finished());
        self.recording = running;
        for (_, task) in done {
            if let Some(cache) = block_on(task) {
                self.caches.push(Arc::new(cache));
            }
        }
    }

    /// Whether any cycle is still being recorded in the background.
    pub fn recording(&self) -> bool {
        !self.recording.is_empty()
    }

    /// The cycle of `species`, if recorded.
    pub fn find(&self, species: &Species) -> Option<Arc<CycleCache>> {
        self.caches.iter().find(|c| c.species() == species).cloned()
    }

    /// Records the cycles of all of `species` not yet recorded, in parallel.
    fn prepare(&mut self, species: Vec<Species>) {
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
    fn retain(&mut self, in_use: &[Species]) {
        self.caches.retain(|c| in_use.contains(c.species()));
        self.recording.retain(|(s, _)| in_use.contains(s));
    }

    /// Whether the cycle of `species` is being recorded in the background.
    pub fn is_recording(&self, species: &Species) -> bool {
        self.recording.iter().any(|(s, _)| s == species)
    }

    /// Heap bytes held.
    pub fn bytes(&self) -> usize {
        self.caches.iter().map(|c| c.bytes()).sum()
    }
}

/// A jellyfish's claim to detail: its size on screen, boosted for the tier it holds.
struct Rank {
    entity: Entity,
    size: f32,
    tier: Tier,
}

/// Sizes on screen of every started jellyfish, from the first active camera.
fn screen_sizes(
    cameras: &Query<(Entity, &Camera, &GlobalTransform, &Projection)>,
    jellyfish: &Query<Jellyfish>,
) -> Vec<Rank> {
    let camera = cameras
        .iter()
        .filter(|(_, c, ..)| c.is_active)
        .min_by_key(|(e, c, ..)| (c.order, *e));
    jellyfish
        .iter()
        .filter(|(_, slice, ..)| slice.started())
        .map(|(entity, slice, _, meshes, transform)| {
            let diameter = slice.species.diameter * transform.scale().max_element();
            let size = match camera {
                None => f32::INFINITY,
                Some(_) if !meshes.seen() && meshes.bounds.is_some() => 0.0,
                Some((_, _, eye, projection)) => {
                    let distance = eye.translation().distance(transform.translation());
                    match projection {
                        Projection::Perspective(p) => {
                            diameter / (2.0 * distance.max(1e-6) * (0.5 * p.fov).tan())
                        }
                        Projection::Orthographic(o) => diameter / o.area.height().max(1e-6),
                        _ => 1.0,
                    }
                }
            };
            Rank {
                entity,
                size: if size.is_finite() || size == f32::INFINITY {
                    size
                } else {
                    0.0
                },
                tier: slice.tier,
            }
        })
        .collect()
}

/// The tier each jellyfish should have: the `near` largest (with hysteresis) of at least
/// `near_size`, then the `mid` largest of the rest, then far.
fn choose(mut ranks: Vec<Rank>, levels: &DetailLevels) -> Vec<(Entity, Tier)> {
    let boost = 1.0 + levels.hysteresis.max(0.0);
    let mut chosen = Vec::with_capacity(ranks.len());
    for (tier, budget, least) in [
        (Tier::Near, levels.near, levels.near_size),
        (Tier::Mid, levels.mid, levels.mid_size),
    ] {
        let claim = |r: &Rank| {
            if r.tier <= tier {
                r.size * boost
            } else {
                r.size
            }
        };
        ranks.sort_by(|a, b| claim(b).total_cmp(&claim(a)).then(a.entity.cmp(&b.entity)));
        let taken = ranks
            .iter()
            .take(budget)
            .take_while(|r| claim(r) >= least)
            .count();
        chosen.extend(ranks.drain(..taken).map(|r| (r.entity, tier)));
    }
    chosen.extend(ranks.into_iter().map(|r| (r.entity, Tier::Far)));
    chosen
}

type Jellyfish = (
    Entity,
    &'static mut JellyfishSlice,
    &'static mut SwimMotion,
    &'static JellyfishMeshes,
    &'static GlobalTransform,
);

/// Moves jellyfish between tiers: demotions at once, promotions (the costly way) up to
/// [`DetailLevels::promotions_per_frame`], nearest first.
pub(super) fn change_tiers(
    cameras: Query<(Entity, &Camera, &GlobalTransform, &Projection)>,
    mut jellyfish: Query<Jellyfish>,
    settings: Res<JellyfishSettings>,
    mut caches: ResMut<CycleCaches>,
    timings: Res<JellyfishTimings>,
) {
    // Drop cycles of species no jellyfish has any more (after edits).
    let mut distinct: Vec<&Species> = Vec::new();
    for (_, slice, ..) in &jellyfish {
        if !distinct.contains(&&slice.species) {
            distinct.push(&slice.species);
        }
    }
    let in_use: Vec<Species> = distinct
        .into_iter()
        .flat_map(|s| [s.clone(), tier_species(s, Tier::Mid)])
        .collect();
    caches.retain(&in_use);
    caches.collect();
    for (_, mut slice, ..) in &mut jellyfish {
        let wanted = slice.replay.as_ref().and_then(|r| r.wanted.as_ref());
        if let Some(cache) = wanted.and_then(|w| caches.find(w)) {
            switch_cycle(&mut slice, cache);
        }
    }
    let ranked = &jellyfish;
    let levels = &settings.detail;
    let mut changes: Vec<(Entity, Tier)> = choose(screen_sizes(&cameras, ranked), levels)
        .into_iter()
        .filter(|(e, tier)| ranked.get(*e).is_ok_and(|(_, s, ..)| s.tier != *tier))
        .collect();
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
    let mut variants: Vec<(Species, Tier, Species)> = Vec::new();
    for (e, tier) in &changes {
        if let Ok((_, slice, ..)) = ranked.get(*e)
            && !variants
                .iter()
                .any(|(s, t, _)| s == &slice.species && t == tier)
        {
            let simulated = tier_species(&slice.species, *tier);
            variants.push((slice.species.clone(), *tier, simulated));
        }
    }
    // A species being recorded in the background (just edited) changes tier once it is
    // ready, instead of recording it again here and stalling the frame.
    variants.retain(|(.., simulated)| !caches.is_recording(simulated));
    caches.prepare(variants.iter().map(|v| v.2.clone()).collect());
    let plan: HashMap<Entity, (Tier, Arc<CycleCache>)> = changes
        .iter()
        .filter_map(|(e, tier)| {
            let (_, slice, ..) = ranked.get(*e).ok()?;
            let (.., simulated) = variants
                .iter()
                .find(|(s, t, _)| s == &slice.species && t == tier)?;
            Some((*e, (*tier, caches.find(simulated)?)))
        })
        .collect();
    timings.add_tier_changes(plan.len());
    jellyfish
        .par_iter_mut()
        .for_each(|(entity, mut slice, mut motion, ..)| {
            if let Some((tier, cache)) = plan.get(&entity) {
                move_to(&mut slice, &mut motion, *tier, cache.clone());
            }
        });
}

/// A far jellyfish takes another cycle (its species was edited), at the same phase.
pub(super) fn switch_cycle(slice: &mut JellyfishSlice, cache: Arc<CycleCache>) {
    let Some(replay) = slice.replay.as_mut() else {
        return;
    };
    let species = cache.species();
    replay.clock = replay
        .clock
        .retimed(species.period(), species.steps_per_cycle());
    let mut now = Snapshot::default();
    let time = replay.clock.time();
    now.copy_frame(cache.frame(replay.index()), time, replay.swim as f32);
    slice.history.change_tier(&now, time, fade(&replay.clock));
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
    motion: &mut SwimMotion,
    tier: Tier,
    cache: Arc<CycleCache>,
) {
    let Some(clock) = slice.clock().cloned() else {
        return;
    };
    let species = cache.species();
    let clock = clock.retimed(species.period(), species.steps_per_cycle());
    let index = (clock.stroke_steps() % clock.steps_per_cycle() as u64) as u32;
    let mut now = Snapshot::default();
    let fade = fade(&clock);
    if tier == Tier::Far {
        let replay = Replay {
            cache: cache.clone(),
            clock,
            swim: 0.0,
            wanted: None,
        };
        now.copy_frame(cache.frame(index), replay.clock.time(), 0.0);
        motion.swum = 0.0;
        slice.history.change_tier(&now, replay.clock.time(), fade);
        slice.sim = None;
        slice.replay = Some(replay);
    } else {
        let mut sim = cache.resume(index);
        sim.set_clock(clock);
        now.capture(&sim);
        motion.swum = sim.swim_distance();
        slice.history.change_tier(&now, sim.clock().time(), fade);
        slice.sim = Some(sim);
        slice.replay = None;
    }
    slice.tier = tier;
    slice.anchor = None;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ranks(sizes: &[(u32, f32, Tier)]) -> Vec<Rank> {
        sizes
            .iter()
            .map(|&(i, size, tier)| Rank {
                entity: Entity::from_raw_u32(i).unwrap(),
                size,
                tier,
            })
            .collect()
    }

    fn tier_of(chosen: &[(Entity, Tier)], i: u32) -> Tier {
        chosen
            .iter()
            .find(|(e, _)| *e == Entity::from_raw_u32(i).unwrap())
            .unwrap()
            .1
    }

    #[test]
    fn the_largest_are_near_within_the_budgets() {
        let levels = DetailLevels {
            near: 2,
            mid: 1,
            hysteresis: 0.0,
            ..default()
        };
        let far = Tier::Far;
        let chosen = choose(
            ranks(&[(1, 0.1, far), (2, 0.5, far), (3, 0.3, far), (4, 0.2, far)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 2), Tier::Near);
        assert_eq!(tier_of(&chosen, 3), Tier::Near);
        assert_eq!(tier_of(&chosen, 4), Tier::Mid);
        assert_eq!(tier_of(&chosen, 1), Tier::Far);
    }

    #[test]
    fn a_tier_is_kept_until_another_clearly_outranks_it() {
        let levels = DetailLevels {
            near: 1,
            mid: 0,
            hysteresis: 0.25,
            ..default()
        };
        // 2 is near; 1 is a little larger, not enough to take its place.
        let chosen = choose(
            ranks(&[(1, 0.11, Tier::Far), (2, 0.1, Tier::Near)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 2), Tier::Near);
        assert_eq!(tier_of(&chosen, 1), Tier::Far);
        // Clearly larger: it takes the place.
        let chosen = choose(
            ranks(&[(1, 0.13, Tier::Far), (2, 0.1, Tier::Near)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 1), Tier::Near);
        assert_eq!(tier_of(&chosen, 2), Tier::Far);
    }

    #[test]
    fn ties_and_sizes_below_the_threshold() {
        let levels = DetailLevels {
            near: 5,
            mid: 5,
            near_size: 0.2,
            mid_size: 0.05,
            hysteresis: 0.0,
            ..default()
        };
        let far = Tier::Far;
        let chosen = choose(
            ranks(&[(7, 0.3, far), (3, 0.3, far), (5, 0.1, far), (6, 0.01, far)]),
            &levels,
        );
        assert_eq!(tier_of(&chosen, 3), Tier::Near);
        assert_eq!(tier_of(&chosen, 7), Tier::Near);
        assert_eq!(tier_of(&chosen, 5), Tier::Mid);
        assert_eq!(tier_of(&chosen, 6), Tier::Far);
        // The order of the input changes nothing.
        let again = choose(
            ranks(&[(6, 0.01, far), (5, 0.1, far), (3, 0.3, far), (7, 0.3, far)]),
            &levels,
        );
        let mut a = chosen.clone();
        let mut b = again;
        a.sort();
        b.sort();
        assert_eq!(a, b);
    }

    #[test]
    fn the_mid_tier_is_a_compact_box_of_the_same_cells_and_step() {
        let species = Species::default();
        let mid = tier_species(&species, Tier::Mid);
        assert!(mid.grid_resolution < species.grid_resolution);
        assert!((mid.cell_size() - species.cell_size()).abs() < 1e-6 * species.cell_size());
        assert_eq!(mid.steps_per_cycle(), species.steps_per_cycle());
        assert_eq!(tier_species(&species, Tier::Far), species);
    }
}
