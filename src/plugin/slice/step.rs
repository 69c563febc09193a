//! Stepping the slices each frame by the frame's virtual time, in parallel over
//! jellyfish; after each step the jellyfish travels (`plugin::swimming`) and the step is
//! recorded for the frames to blend between (`plugin::interpolation`).
//!
//! Each slice has its own fixed step and clock, so how time is split into frames changes
//! nothing; stepping every frame (not on the app's fixed ticks) keeps the work of each
//! frame even. Pausing or slowing `Time<Virtual>` pauses or slows the jellyfish.

use super::JellyfishSlice;
use super::events::{Lifecycle, LifecycleQueue};
use super::tier::{LiveSlice, Replay};
use crate::plugin::interpolation::SliceHistory;
use crate::plugin::swimming::{
    FarTow, GuideFrame, Pose, Resting, Steering, Stroke, SwimMotion, TentacleGuides, Travel,
};
use crate::plugin::timings::{BatchClock, JellyfishTimings, Spent};
use crate::plugin::water::AmbientWater;
use crate::shape::packed;
use crate::sim::clock::FixedClock;
use bevy::ecs::batching::BatchingStrategy;
use bevy::prelude::*;
use std::time::Duration;

/// One jellyfish as the stepping sees it.
type Stepped = (
    Entity,
    &'static mut JellyfishSlice,
    &'static mut SliceHistory,
    &'static mut SwimMotion,
    Option<&'static mut TentacleGuides>,
    &'static Transform,
    Option<&'static Steering>,
    Has<Resting>,
);

/// The stepping query's item.
type StepItem<'w, 's> = bevy::ecs::query::QueryItem<'w, 's, Stepped>;

/// Adds the frame's time to every slice's clock; a slice takes the fixed steps of its
/// own length that pays for (a far one plays them from its species' cycle), and after
/// each one the jellyfish travels and the state is recorded for the frames to blend
/// between. The physics sees only the slice's step, never the frame rate; slices started
/// at different phases step on different frames, which spreads the cost.
pub(super) fn step_slices(
    mut live: Query<Stepped, With<LiveSlice>>,
    mut rest: Query<Stepped, Without<LiveSlice>>,
    water: Option<Res<AmbientWater>>,
    time: Res<Time<Virtual>>,
    timings: Res<JellyfishTimings>,
    events: Res<LifecycleQueue>,
) {
    let at = FrameTime {
        frame: time.delta_secs_f64(),
        now: time.elapsed_secs_f64(),
        elapsed: time.elapsed(),
        before: time.elapsed() - time.delta(),
    };
    let still = AmbientWater::still();
    let water = water.as_deref().unwrap_or(&still);
    // Boxed: `for_each_init` hands a batch's state through every item by value.
    let batch = || Box::new(BatchClock::new(&timings, Spent::Simulation));
    let step = |batch: &mut Box<BatchClock>, item: StepItem| {
        let tier = item.1.tier as usize;
        batch.time(tier, || {
            step_one(item, &at, water, &events);
        });
    };
    // The costly live slices first, then the rest (the far replays, and any jellyfish not
    // yet started), which even out the threads' ends.
    live.par_iter_mut()
        .batching_strategy(ONE_AT_A_TIME)
        .for_each_init(batch, step);
    rest.par_iter_mut()
        .batching_strategy(SMALL_BATCHES)
        .for_each_init(batch, step);
}

/// The frame's virtual time, as every jellyfish's steps read it.
#[derive(Clone, Copy)]
struct FrameTime {
    /// The frame's length, s.
    frame: f64,
    /// The virtual time at its end, s.
    now: f64,
    /// The same, and where the frame began.
    elapsed: Duration,
    before: Duration,
}

/// One jellyfish's frame: its slice built if it was left pending, the steps the frame
/// pays for, and the time it shows.
fn step_one(
    (entity, mut slice, mut history, mut motion, mut guides, transform, steering, resting): StepItem,
    at: &FrameTime,
    water: &AmbientWater,
    events: &LifecycleQueue,
) {
    let FrameTime {
        frame,
        now,
        elapsed,
        before,
    } = *at;
    let slice = &mut *slice;
    // A species edit left for the live slice this frame is taken here, on every thread.
    if slice.edit.waiting() {
        slice.take_edit(&mut history, &mut motion);
    }
    // Started this frame and left near: its slice is built now.
    if let Err(error) = slice.build_pending(&mut history, motion.pose) {
        error!("jellyfish {entity}: its slice could not be built: {error}");
    }
    let Some(clock) = slice.clock() else {
        return;
    };
    if frame > 0.0 {
        let (anchor, added) = *slice.anchor.get_or_insert((before, clock.added()));
        let until = added + elapsed.saturating_sub(anchor).as_secs_f64();
        let travel = Travel {
            scale: transform.scale,
            water,
            now,
            steering,
        };
        let step = Step {
            entity,
            until,
            frame,
            resting,
            travel: &travel,
            events,
        };
        step.advance(slice, &mut history, &mut motion, guides.as_deref_mut());
    }
    slice.show(&mut history);
    slice.fresh = false;
}

/// A live slice costs tens of microseconds a frame, a replay one: the live ones are
/// handed out one at a time, so that no thread is left with a long batch of them.
pub(crate) const ONE_AT_A_TIME: BatchingStrategy = BatchingStrategy::fixed(1);

/// The far replays, after the live slices: cut into a few batches per thread instead of
/// one, a thread that finishes early takes another batch instead of waiting.
pub(crate) const SMALL_BATCHES: BatchingStrategy = BatchingStrategy {
    batch_size_limits: 1..usize::MAX,
    batches_per_thread: 8,
};

/// One jellyfish's steps in one frame.
struct Step<'a> {
    entity: Entity,
    /// The clock's added time to reach, s.
    until: f64,
    /// The frame's length, s.
    frame: f64,
    resting: bool,
    travel: &'a Travel<'a>,
    events: &'a LifecycleQueue,
}

impl Step<'_> {
    /// Takes the steps the frame pays for, live or replayed.
    fn advance(
        &self,
        slice: &mut JellyfishSlice,
        history: &mut SliceHistory,
        motion: &mut SwimMotion,
        mut guides: Option<&mut TentacleGuides>,
    ) {
        let swum_before = motion.swum;
        let mut stepped = 0.0;
        let (entity, frame, resting) = (self.entity, self.frame, self.resting);
        if let Some(sim) = slice.sim.as_mut() {
            if sim.resting() != resting {
                sim.set_resting(resting);
            }
            let recoveries = sim.recoveries();
            sim.advance_until_with(self.until, |sim| {
                let clock = sim.clock();
                let stroke = Stroke {
                    species: sim.species(),
                    step: clock.step() as f32,
                    swim: sim.swim_distance(),
                    phase: sim.phase(),
                    resting: sim.resting(),
                    behind: clock.added() - clock.time(),
                };
                let (before, surge) = (motion.pose, stroke.swim - motion.swum);
                self.travel.step(&stroke, motion);
                stepped += stroke.step;
                let trail = guides.as_deref_mut().map(|guides| {
                    let view = sim.view();
                    let centroid = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
                    let shape = StepShape {
                        bell: view.bell,
                        tentacles: view.tentacles,
                        oral_arms: view.oral_arms,
                        centroid,
                    };
                    guides.step(
                        &self.guide_frame(&stroke, surge, before, motion, shape),
                        None,
                    );
                    (guides.offsets(), guides.oral_offsets())
                });
                history.record(clock, frame, motion.pose, |s| {
                    s.capture(sim);
                    let (fringe, oral) = trail.unwrap_or_default();
                    s.set_trail(fringe, oral);
                });
                if stroke_begins(clock, stroke.resting) {
                    self.events.push(entity, Lifecycle::Stroke(clock.cycle()));
                }
            });
            if sim.recoveries() > recoveries {
                self.events
                    .push(entity, Lifecycle::Recovered(sim.recoveries()));
            }
        } else if let Some(replay) = slice.replay.as_mut() {
            history.prefetch(replay.clock.steps_due_at(self.until).min(4) as usize);
            replay.advance_until(self.until, resting, |replay: &Replay| {
                let clock = &replay.clock;
                let stroke = Stroke {
                    species: replay.cache.species(),
                    step: clock.step() as f32,
                    swim: replay.swim as f32,
                    phase: clock.phase(),
                    resting,
                    behind: clock.added() - clock.time(),
                };
                let (before, surge) = (motion.pose, stroke.swim - motion.swum);
                self.travel.step_far(&stroke, motion);
                stepped += stroke.step;
                if let Some(guides) = guides.as_deref_mut() {
                    // Hung from the cycle's first step, the bell at rest.
                    let rest = replay.cache.frame(0);
                    let shape = StepShape {
                        bell: &rest.bell,
                        tentacles: [&rest.tentacles[0], &rest.tentacles[1]],
                        oral_arms: [&rest.oral_arms[0], &rest.oral_arms[1]],
                        centroid: Vec2::ZERO,
                    };
                    // Towed at the recorded stroke's mean speed (nothing while resting).
                    let mean = if resting {
                        0.0
                    } else {
                        replay.cache.swim_per_cycle() / stroke.species.period()
                    };
                    let far = FarTow {
                        mean,
                        cycle: &replay.cache,
                    };
                    guides.step(
                        &self.guide_frame(&stroke, surge, before, motion, shape),
                        Some(far),
                    );
                }
                let (time, swim) = (clock.time(), replay.swim as f32);
                // A step that fades from the last tier's shape is drawn as a shape of its
                // own, whole trail and all; any other, only what it draws, read in place.
                let fading = history.fading();
                let far_guides = packed::far_guides_of(stroke.species);
                history.record(clock, frame, motion.pose, |s| {
                    s.copy_frame(&replay.cache, replay.index(), time, swim);
                    match guides.as_deref_mut() {
                        Some(g) if fading => s.set_trail(g.offsets(), g.oral_offsets()),
                        Some(g) => s.set_thin_trail(Some(g.thin_trail(far_guides))),
                        None if fading => s.set_trail(&[], &[]),
                        None => s.set_thin_trail(None),
                    }
                });
                if stroke_begins(clock, resting) {
                    self.events.push(entity, Lifecycle::Stroke(clock.cycle()));
                }
            });
        }
        if stepped > 0.0 {
            motion.swim_speed = (motion.swum - swum_before) * self.travel.scale.y / stepped;
        }
    }

    /// What the guides need of the step just taken, whose `shape` is given.
    fn guide_frame<'a>(
        &'a self,
        stroke: &Stroke<'a>,
        surge: f32,
        before: Pose,
        motion: &SwimMotion,
        shape: StepShape<'a>,
    ) -> GuideFrame<'a> {
        let StepShape {
            bell,
            tentacles,
            oral_arms,
            centroid,
        } = shape;
        GuideFrame {
            species: stroke.species,
            bell,
            tentacles,
            oral_arms,
            centroid,
            dt: stroke.step,
            surge,
            before,
            after: motion.pose,
            scale: self.travel.scale,
            water: self.travel.water,
            time: self.travel.now - stroke.behind,
        }
    }
}

/// The slice's shape after a step, as the guides read it.
struct StepShape<'a> {
    bell: &'a [Vec2],
    tentacles: [&'a [Vec2]; 2],
    oral_arms: [&'a [Vec2]; 2],
    /// The bell's centroid, in the same frame as the points.
    centroid: Vec2,
}

/// Whether the step just taken ended a cycle: the next one contracts.
fn stroke_begins(clock: &FixedClock, resting: bool) -> bool {
    !resting
        && clock
            .stroke_steps()
            .is_multiple_of(clock.steps_per_cycle() as u64)
}
