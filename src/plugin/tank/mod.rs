//! [`TankWater`]: the water of a whole tank (a coarse 3D stable-fluids grid,
//! [`TankFluid`]), stirred by the game and by the jellyfish's own jets, that becomes the
//! [`AmbientWater`] every jellyfish swims in.
//!
//! The water steps on the app's fixed ticks, once every [`TankWater::ticks_per_step`] of
//! them by their time together, and takes the jets gathered in the tick before, in entity
//! order, so a replay is the same water. A step's work is split over its tick and the
//! next (about half on each), so that no frame carries a whole step and the next none.
//! The game's own stirs ([`TankWater::stir`]) also disturb the jellyfish near them
//! ([`Disturbance`]); their own jets do not.

use super::schedule::JellyfishSystems;
use super::slice::JellyfishSlice;
use super::swimming::SwimMotion;
use super::timings::JellyfishTimings;
use super::touch::{Disturbance, feel_disturbances};
use super::water::{AmbientWater, SampledWater};
use crate::sim::tank::TankFluid;
use bevy::prelude::*;
use bevy::tasks::ComputeTaskPool;
use bevy::utils::Parallel;

/// Steps a [`TankWater`] the app inserts and lets the jellyfish's jets stir it. Leave it
/// out to keep a `TankWater` still or step it yourself.
#[derive(Clone, Copy, Debug, Default)]
pub struct TankWaterPlugin;

impl Plugin for TankWaterPlugin {
    fn build(&self, app: &mut App) {
        app.register_type::<TankWater>()
            .add_message::<Disturbance>()
            .add_systems(
                FixedUpdate,
                step_tank
                    .in_set(JellyfishSystems::StepWater)
                    .run_if(resource_exists::<TankWater>),
            )
            .add_systems(
                FixedUpdate,
                collect_jets
                    .in_set(JellyfishSystems::StirWater)
                    .run_if(resource_exists::<TankWater>),
            )
            .add_systems(
                PostUpdate,
                disturb
                    .in_set(JellyfishSystems::Touch)
                    .before(feel_disturbances)
                    .run_if(resource_exists::<TankWater>),
            );
    }
}

/// The tank's water, as a game adds it: `app.insert_resource(TankWater::new(min, max, cell))`.
/// World units; the fluid's fields (`min`, `cell`, `size`, `damping`) are reached through it.
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(Resource)]
pub struct TankWater {
    /// How much of a jellyfish's surge speed its jet gives the water behind it (0: the
    /// jellyfish do not stir the water).
    pub jet_strength: f32,
    /// The water steps once every this many fixed ticks (at least one), by their time
    /// together. A coarse tank's water crosses a cell in many ticks (the aquarium's, at a
    /// unit a second in cells of 0.75, in about fifty), and the stable-fluids step holds
    /// at any length: stepped at 32 a second instead of 64 the water is the same to within
    /// a percent of its speed, and at 10,002 jellyfish a step and its jets cost about a
    /// tenth of the frame. Default 2. Above one, a step begun on its tick is finished on
    /// the next, and the jellyfish swim in it from then ([`TankFluid::begin_step`]).
    pub ticks_per_step: u32,
    #[reflect(ignore)]
    fluid: TankFluid,
    /// The game's stirs since the last frame, to disturb the jellyfish with.
    #[reflect(ignore)]
    stirs: Vec<Disturbance>,
    /// Fixed ticks since the last step, and their time.
    #[reflect(ignore)]
    ticks: u32,
    #[reflect(ignore)]
    held: std::time::Duration,
}

impl std::ops::Deref for TankWater {
    type Target = TankFluid;

    fn deref(&self) -> &TankFluid {
        &self.fluid
    }
}

impl std::ops::DerefMut for TankWater {
    fn deref_mut(&mut self) -> &mut TankFluid {
        &mut self.fluid
    }
}

impl TankWater {
    /// Still water filling the box from `min` to `max` (world) in cells of about `cell`.
    pub fn new(min: Vec3, max: Vec3, cell: f32) -> Self {
        Self {
            jet_strength: 0.5,
            ticks_per_step: 2,
            fluid: TankFluid::new(min, max, cell),
            stirs: Vec::new(),
            ticks: 0,
            held: std::time::Duration::ZERO,
        }
    }

    /// Stirs the water: pushes it at `at` within `radius` towards `velocity` (applied at
    /// the next tick; a non-finite or empty push is ignored), and disturbs the jellyfish
    /// near it ([`Disturbance`]) as strongly as the stir is quick: fully at
    /// [`STIR_FOR_A_FULL_TOUCH`] radii a second.
    pub fn stir(&mut self, at: Vec3, radius: f32, velocity: Vec3) {
        if !(at.is_finite() && velocity.is_finite() && radius.is_finite() && radius > 0.0) {
            return;
        }
        self.fluid.stir(at, radius, velocity);
        let strength = (velocity.length() / (STIR_FOR_A_FULL_TOUCH * radius)).min(1.0);
        // Without the plugin nothing takes them: keep the last few.
        if self.stirs.len() >= 256 {
            self.stirs.remove(0);
        }
        self.stirs.push(Disturbance {
            point: at,
            strength,
            radius,
        });
    }

    /// Counts a fixed tick of `delta`: on every [`TankWater::ticks_per_step`]th, the
    /// length of the step then due, s (none for a step of no length).
    fn count_tick(&mut self, delta: std::time::Duration) -> Option<f32> {
        self.ticks += 1;
        self.held += delta;
        if self.ticks < self.ticks_per_step.max(1) {
            return None;
        }
        let dt = self.held.as_secs_f32();
        (self.ticks, self.held) = (0, std::time::Duration::ZERO);
        (dt > 0.0).then_some(dt)
    }

    /// Whether the tick now ending is the last before the water's next step, whose jets
    /// that step takes.
    fn steps_next_tick(&self) -> bool {
        self.ticks + 1 >= self.ticks_per_step.max(1)
    }

    /// The water as a field for the jellyfish.
    pub fn snapshot(&self) -> SampledWater {
        SampledWater {
            origin: self.min + Vec3::splat(0.5 * self.cell),
            spacing: self.cell,
            size: self.size,
            velocities: self.velocities().to_vec(),
        }
    }
}

/// Steps the tank, on every [`TankWater::ticks_per_step`]th fixed tick by the ticks' time
/// together, and hands it to the jellyfish as their water. Above one tick a step, the
/// step's work is split: begun on its tick (the jets' pushes, the advection, the
/// pressure's first sweeps) and finished on the next (its last sweeps), then handed on;
/// the same water, bit for bit, as a step taken at once, a tick later. The jets' pushes,
/// most of a crowded tank's step, are applied in slabs side by side: the same water on any
/// number of threads.
fn step_tank(
    mut tank: ResMut<TankWater>,
    mut ambient: ResMut<AmbientWater>,
    time: Res<Time<Fixed>>,
    timings: Res<JellyfishTimings>,
) {
    let start = std::time::Instant::now();
    if tank.step_in_flight() {
        hand_on(&mut tank, &mut ambient);
    }
    if let Some(dt) = tank.count_tick(time.delta()) {
        let pool = ComputeTaskPool::get();
        let slabs = tank.begin_step(pool.thread_num());
        pool.scope(|scope| {
            for slab in slabs {
                scope.spawn(async move { slab.apply() });
            }
        });
        tank.advance_pushed(dt);
        if tank.ticks_per_step <= 1 {
            hand_on(&mut tank, &mut ambient);
        }
    }
    timings.add_water(start.elapsed());
}

/// Finishes the step in flight and hands the water to the jellyfish.
fn hand_on(tank: &mut TankWater, ambient: &mut AmbientWater) {
    tank.finish_step();
    *ambient = AmbientWater::field(tank.snapshot());
}

/// Each jellyfish's jet pushes the tank's water behind it: a blob a bell across, a bell
/// and a half behind the bell, moving back at a share of its surge. Gathered in the tick
/// before the water steps (a jet pushes the water towards a velocity, so one gathering a
/// step is the step's jet), side by side, then put in entity order, so the water is the
/// same in every run.
fn collect_jets(
    mut tank: ResMut<TankWater>,
    jellyfish: Query<(Entity, &JellyfishSlice, &SwimMotion, &Transform)>,
    mut gathered: Local<Parallel<Vec<Jet>>>,
    mut jets: Local<Vec<Jet>>,
) {
    if tank.jet_strength <= 0.0 || !tank.steps_next_tick() {
        return;
    }
    jellyfish
        .par_iter()
        .for_each(|(e, slice, motion, transform)| {
            let Some(species) = slice.species() else {
                return;
            };
            if motion.swim_speed <= 0.0 {
                return;
            }
            let axis = motion.pose.rotation * Vec3::Y;
            let size = species.diameter * transform.scale.max_element();
            let at = motion.pose.position - axis * 1.5 * size;
            let jet = (e, at, size, -axis * motion.swim_speed);
            gathered.borrow_local_mut().push(jet);
        });
    jets.clear();
    gathered.drain_into(&mut jets);
    // Entities are unique: an unstable sort gives the one order.
    jets.sort_unstable_by_key(|j| j.0);
    let strength = tank.jet_strength;
    for &(_, at, size, velocity) in jets.iter() {
        tank.fluid.stir(at, size, velocity * strength);
    }
}

/// A jet as gathered: whose, where, how wide, how fast.
type Jet = (Entity, Vec3, f32, Vec3);

/// How quick a stir is a full-strength touch, in its radii a second.
pub const STIR_FOR_A_FULL_TOUCH: f32 = 4.0;

/// The game's stirs disturb the jellyfish near them.
fn disturb(mut tank: ResMut<TankWater>, mut disturbances: MessageWriter<Disturbance>) {
    if !tank.stirs.is_empty() {
        disturbances.write_batch(std::mem::take(&mut tank.stirs));
    }
}
