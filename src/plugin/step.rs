//! Stepping the slices in `FixedUpdate`, in parallel over jellyfish, and carrying each
//! jellyfish through the world step by step: its own swimming along its axis, the water's
//! velocity, half the water's vorticity, and steering turns during power strokes.

use super::JellyfishSystems;
use super::components::{JellyfishSlice, Pose, Resting, SwimMotion};
use super::diagnostics::JellyfishTimings;
use super::steering::Steering;
use super::tank::{TankWater, step_tank};
use super::water::AmbientWater;
use crate::sim::SliceSim;
use bevy::prelude::*;
use std::time::Instant;

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<AmbientWater>().add_systems(
        FixedUpdate,
        (step_tank, step_slices, collect_jets)
            .chain()
            .in_set(JellyfishSystems::StepSlices),
    );
}

/// Each tick adds its time to every slice's clock; a slice takes the fixed steps of its
/// own length that pays for, and after each one the jellyfish travels and the state is
/// recorded for the frames to blend between. The physics sees only the slice's step,
/// never the frame rate or the tick; slices started at different phases step on
/// different ticks, which spreads the cost.
#[allow(clippy::type_complexity)]
fn step_slices(
    mut jellyfish: Query<(
        &mut JellyfishSlice,
        &mut SwimMotion,
        &Transform,
        Option<&Steering>,
        Has<Resting>,
    )>,
    water: Res<AmbientWater>,
    time: Res<Time<Fixed>>,
    timings: Res<JellyfishTimings>,
) {
    let (tick, now) = (time.delta_secs_f64(), time.elapsed_secs_f64());
    let water = &*water;
    jellyfish
        .par_iter_mut()
        .for_each(|(mut slice, mut motion, transform, steering, resting)| {
            let slice = &mut *slice;
            let Some(sim) = slice.sim.as_mut() else {
                return;
            };
            let start = Instant::now();
            if sim.resting() != resting {
                sim.set_resting(resting);
            }
            let (history, motion) = (&mut slice.history, &mut *motion);
            let swum_before = motion.swum;
            let travel = Travel {
                scale: transform.scale,
                water,
                now,
                steering,
            };
            sim.advance_with(tick as f32, |sim| {
                travel.step(sim, motion);
                history.record(sim, tick, motion.pose);
            });
            motion.swim_speed = (motion.swum - swum_before) * transform.scale.y / tick as f32;
            timings.add_simulation(start.elapsed());
        });
}

/// What moves a jellyfish through the world in one slice step.
struct Travel<'a> {
    /// The `Transform`'s scale: world units per metre of slice, per axis.
    scale: Vec3,
    water: &'a AmbientWater,
    /// World time of the tick, s: the water is read at it.
    now: f64,
    steering: Option<&'a Steering>,
}

impl Travel<'_> {
    fn step(&self, sim: &SliceSim, motion: &mut SwimMotion) {
        let species = sim.species();
        let dt = sim.clock().step() as f32;
        let surge = sim.swim_distance() - motion.swum;
        motion.swum = sim.swim_distance();
        let Pose {
            mut position,
            mut rotation,
        } = motion.pose;
        // A small body in a shear spins with half the water's vorticity.
        let size = species.diameter * self.scale.max_element();
        let vorticity = self.water.0.vorticity(position, self.now, size);
        if vorticity.is_finite() && vorticity != Vec3::ZERO {
            rotation = (Quat::from_scaled_axis(0.5 * vorticity * dt) * rotation).normalize();
        }
        if let Some(steering) = self.steering {
            let phase = sim.phase();
            let contracting = !sim.resting() && phase > 0.0 && phase <= species.contraction_duty;
            rotation = steering.turn(rotation, position, surge / species.diameter, contracting);
        }
        let before = position;
        let current = self.water.velocity(position, self.now);
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
