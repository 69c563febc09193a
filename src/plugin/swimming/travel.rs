//! One slice step of travel: the bell's surge along its axis, the water's current and half
//! its vorticity, and the steering turn while the bell contracts.

use super::steering::Steering;
use super::{FAR_REFRESH, Pose, SwimMotion};
use crate::plugin::water::AmbientWater;
use crate::species::Species;
use bevy::prelude::*;

/// What one step of a slice, live or replayed, tells the travel.
pub(crate) struct Stroke<'a> {
    pub species: &'a Species,
    /// The step, s.
    pub step: f32,
    /// Distance swum after the step, m.
    pub swim: f32,
    pub phase: f32,
    pub resting: bool,
    /// How long before the end of the frame the step ends, s.
    pub behind: f64,
}

/// What moves a jellyfish through the world in one slice step.
pub(crate) struct Travel<'a> {
    /// The `Transform`'s scale: world units per metre of slice, per axis.
    pub scale: Vec3,
    pub water: &'a AmbientWater,
    /// World time at the end of the frame, s.
    pub now: f64,
    pub steering: Option<&'a Steering>,
}

/// What a far jellyfish last read of the water around it, held for [`FAR_REFRESH`]
/// seconds of its steps: each read is seven samples of the water (the current and, by
/// central differences, its vorticity), and ten thousand far jellyfish took them every
/// step of a stroke whose water changes over seconds.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct HeldWater {
    current: Vec3,
    vorticity: Vec3,
    /// The turn that vorticity gives in a step of `spun_for` seconds ([`spin`]): a far
    /// jellyfish's steps are all its species' one step, so it is the same every step.
    spin: Option<Quat>,
    spun_for: f32,
    /// Steps it is held for yet.
    steps_left: u32,
}

impl Travel<'_> {
    /// Moves `motion` by one slice step, the water read after it.
    pub fn step(&self, stroke: &Stroke, motion: &mut SwimMotion) {
        motion.held_water = None;
        let (current, vorticity) = self.read_water(stroke, motion);
        self.advance(stroke, motion, current, spin(vorticity, stroke.step));
    }

    /// Moves a far jellyfish's `motion` by one step of its replayed stroke, with the water
    /// it read at most [`FAR_REFRESH`] seconds of steps ago (a whole number of steps, so
    /// the same whatever the frames).
    pub fn step_far(&self, stroke: &Stroke, motion: &mut SwimMotion) {
        let mut held = match motion.held_water {
            Some(held) if held.steps_left > 0 => HeldWater {
                steps_left: held.steps_left - 1,
                ..held
            },
            _ => {
                let (current, vorticity) = self.read_water(stroke, motion);
                let steps = (FAR_REFRESH / stroke.step.max(1e-6)).ceil().clamp(1.0, 1e3) as u32;
                HeldWater {
                    current,
                    vorticity,
                    spin: None,
                    spun_for: f32::NAN,
                    steps_left: steps - 1,
                }
            }
        };
        // (NaN, never equal, until the first step works it out.)
        if held.spun_for != stroke.step {
            (held.spin, held.spun_for) = (spin(held.vorticity, stroke.step), stroke.step);
        }
        motion.held_water = Some(held);
        self.advance(stroke, motion, held.current, held.spin);
    }

    /// The water's current and vorticity where the jellyfish is, when the step ends.
    fn read_water(&self, stroke: &Stroke, motion: &SwimMotion) -> (Vec3, Vec3) {
        // The water is read when the step ends, whatever the frame.
        let now = self.now - stroke.behind;
        let position = motion.pose.position;
        let size = stroke.species.diameter * self.scale.max_element();
        let vorticity = self.water.0.vorticity(position, now, size);
        let current = self.water.velocity(position, now);
        (current, vorticity)
    }

    /// Moves `motion` by one step in water of `current` that turns it by `spin` ([`spin`]).
    fn advance(&self, stroke: &Stroke, motion: &mut SwimMotion, current: Vec3, spin: Option<Quat>) {
        let species = stroke.species;
        let dt = stroke.step;
        let surge = stroke.swim - motion.swum;
        motion.swum = stroke.swim;
        let Pose {
            mut position,
            mut rotation,
        } = motion.pose;
        if let Some(spin) = spin {
            rotation = (spin * rotation).normalize();
        }
        if let Some(steering) = self.steering {
            let phase = stroke.phase;
            let contracting =
                !stroke.resting && phase > 0.0 && phase <= species.contraction_share();
            rotation = steering.turn(rotation, position, surge / species.diameter, contracting);
        }
        let before = position;
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

/// The turn of a small body in water of `vorticity` over a step of `dt` seconds: in a
/// shear it spins with half the water's vorticity. None in still or unreadable water.
fn spin(vorticity: Vec3, dt: f32) -> Option<Quat> {
    (vorticity.is_finite() && vorticity != Vec3::ZERO)
        .then(|| Quat::from_scaled_axis(0.5 * vorticity * dt))
}
