//! Stepping the slices each frame by the frame's virtual time, in parallel over
//! jellyfish, and carrying each jellyfish through the world step by step: its own
//! swimming along its axis, the water's velocity, half the water's vorticity, and
//! steering turns during power strokes.
//!
//! Each slice has its own fixed step and clock, so how time is split into frames changes
//! nothing; stepping every frame (not on the app's fixed ticks) keeps the work of each
//! frame even. Pausing or slowing `Time<Virtual>` pauses or slows the jellyfish.

use super::JellyfishSystems;
use super::components::{JellyfishSlice, Pose, Resting, SwimMotion};
use super::detail::Replay;
use super::diagnostics::JellyfishTimings;
use super::events::{Lifecycle, LifecycleQueue, trigger_lifecycle};
use super::steering::Steering;
use super::tank::{TankWater, step_tank};
use super::water::AmbientWater;
use crate::species::Species;
use bevy::prelude::*;
use std::time::Instant;

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<AmbientWater>()
        .init_resource::<LifecycleQueue>()
        .add_systems(FixedUpdate, (step_tank, collect_jets).chain())
        .add_systems(
            PostUpdate,
            (step_slices, trigger_lifecycle)
                .chain()
                .in_set(JellyfishSystems::StepSlices),
        );
}

/// Adds the frame's time to every slice's clock; a slice takes the fixed steps of its
/// own length that pays for (a far one plays them from its species' cycle), and after
/// each one the jellyfish travels and the state is recorded for the frames to blend
/// between. The physics sees only the slice's step, never the frame rate; slices started
/// at different phases step on different frames, which spreads the cost.
#[allow(clippy::type_complexity)]
fn step_slices(
    mut jellyfish: Query<(
        Entity,
        &mut JellyfishSlice,
        &mut SwimMotion,
        &Transform,
        Option<&Steering>,
        Has<Resting>,
    )>,
    water: Res<AmbientWater>,
    time: Res<Time<Virtual>>,
    timings: Res<JellyfishTimings>,
    events: Res<LifecycleQueue>,
) {
    let (frame, now) = (time.delta_secs_f64(), time.elapsed_secs_f64());
    if frame <= 0.0 {
        return;
    }
    let (elapsed, before) = (time.elapsed(), time.elapsed() - time.delta());
    let water = &*water;
    jellyfish.par_iter_mut().for_each(
        |(entity, mut slice, mut motion, transform, steering, resting)| {
            let start = Instant::now();
            let slice = &mut *slice;
            let motion = &mut *motion;
            let swum_before = motion.swum;
            let travel = Travel {
                scale: transform.scale,
                water,
                now,
                steering,
            };
            let Some(clock) = slice.clock() else {
                return;
            };
            let (at, added) = *slice.anchor.get_or_insert((before, clock.added()));
            let until = added + elapsed.saturating_sub(at).as_secs_f64();
            let history = &mut slice.history;
            let mut stepped = 0.0;
            if let Some(sim) = slice.sim.as_mut() {
                if sim.resting() != resting {
                    sim.set_resting(resting);
                }
                let recoveries = sim.recoveries();
                sim.advance_until_with(until, |sim| {
                    let clock = sim.clock();
                    let stroke = Stroke {
                        species: sim.species(),
                        step: clock.step() as f32,
                        swim: sim.swim_distance(),
                        phase: sim.phase(),
                        resting: sim.resting(),
                        behind: clock.added() - clock.time(),
                    };
                    travel.step(&stroke, motion);
                    stepped += stroke.step;
                    history.record(clock, frame, motion.pose, |s| s.capture(sim));
                    if stroke_begins(clock, stroke.resting) {
                        events.push(entity, Lifecycle::Stroke(clock.cycle()));
                    }
                });
                if sim.recoveries() > recoveries {
                    events.push(entity, Lifecycle::Recovered(sim.recoveries()));
                }
            } else if let Some(replay) = slice.replay.as_mut() {
                replay.advance_until(until, resting, |replay: &Replay, cycle| {
                    let clock = &replay.clock;
                    let stroke = Stroke {
                        species: replay.cache.species(),
                        step: clock.step() as f32,
                        swim: replay.swim as f32,
                        phase: clock.phase(),
                        resting,
                        behind: clock.added() - clock.time(),
                    };
                    travel.step(&stroke, motion);
                    stepped += stroke.step;
                    let (time, swim) = (clock.time(), replay.swim as f32);
                    history.record(clock, frame, motion.pose, |s| {
                        s.copy_frame(cycle, time, swim)
                    });
                    if stroke_begins(clock, resting) {
                        events.push(entity, Lifecycle::Stroke(clock.cycle()));
                    }
                });
            } else {
                return;
            }
            if stepped > 0.0 {
                motion.swim_speed = (motion.swum - swum_before) * transform.scale.y / stepped;
            }
            timings.add_simulation(start.elapsed());
        },
    );
}

/// Whether the step just taken ended a cycle: the next one contracts.
fn stroke_begins(clock: &crate::sim::clock::FixedClock, resting: bool) -> bool {
    !resting
        && clock
            .stroke_steps()
            .is_multiple_of(clock.steps_per_cycle() as u64)
}

/// What one step of a slice, live or replayed, tells the travel.
struct Stroke<'a> {
    species: &'a Species,
    /// The step, s.
    step: f32,
    /// Distance swum after the step, m.
    swim: f32,
    phase: f32,
    resting: bool,
    /// How long before the end of the frame the step ends, s.
    behind: f64,
}

/// What moves a jellyfish through the world in one slice step.
struct Travel<'a> {
    /// The `Transform`'s scale: world units per metre of slice, per axis.
    scale: Vec3,
    water: &'a AmbientWater,
    /// World time at the end of the frame, s.
    now: f64,
    steering: Option<&'a Steering>,
}

impl Travel<'_> {
    fn step(&self, stroke: &Stroke, motion: &mut SwimMotion) {
        let species = stroke.species;
        let dt = stroke.step;
        // The water is read when the step ends, whatever the frame.
        let now = self.now - stroke.behind;
        let surge = stroke.swim - motion.swum;
        motion.swum = stroke.swim;
        let Pose {
            mut position,
            mut rotation,
        } = motion.pose;
        // A small body in a shear spins with half the water's vorticity.
        let size = species.diameter * self.scale.max_element();
        let vorticity = self.water.0.vorticity(position, now, size);
        if vorticity.is_finite() && vorticity != Vec3::ZERO {
            rotation = (Quat::from_scaled_axis(0.5 * vorticity * dt) * rotation).normalize();
        }
        if let Some(steering) = self.steering {
            let phase = stroke.phase;
            let contracting = !stroke.resting && phase > 0.0 && phase <= species.contraction_duty;
            rotation = steering.turn(rotation, position, surge / species.diameter, contracting);
        }
        let before = position;
        let current = self.water.velocity(position, now);
        let current = if current.is_finite() {
            current
        } else {
            Vec3::ZERO
        };
        position += rotation * (self.scale * Vec3::Y) * surge + current * dt;
        motion.velocity = (position - before) / dt;
        motion.pose = Pose { position, rotation };
    }
}

/// Each jellyfish's jet pushes the tank's water behind it (if the app has a tank): a blob
/// a bell across, a bell and a half behind the bell, moving back at a share of its surge.
/// Gathered in entity order, so the water is the same in every run.
fn collect_jets(
    tank: Option<ResMut<TankWater>>,
    jellyfish: Query<(Entity, &JellyfishSlice, &SwimMotion, &Transform)>,
) {
    let Some(mut tank) = tank else {
        return;
    };
    if tank.jet_strength <= 0.0 {
        return;
    }
    let mut jets: Vec<(Entity, Vec3, f32, Vec3)> = jellyfish
        .iter()
        .filter_map(|(e, slice, motion, transform)| {
            let species = slice.species()?;
            if motion.swim_speed <= 0.0 {
                return None;
            }
            let axis = motion.pose.rotation * Vec3::Y;
            let size = species.diameter * transform.scale.max_element();
            let at = motion.pose.position - axis * 1.5 * size;
            Some((e, at, size, -axis * motion.swim_speed))
        })
        .collect();
    jets.sort_by_key(|j| j.0);
    let strength = tank.jet_strength;
    for (_, at, size, velocity) in jets {
        tank.stir(at, size, velocity * strength);
    }
}
