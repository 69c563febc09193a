//! One slice step of travel: the bell's surge along its axis, the water's current and half
//! its vorticity, and the steering turn while the bell contracts.

use super::steering::Steering;
use super::{Pose, SwimMotion};
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

impl Travel<'_> {
    /// Moves `motion` by one slice step.
    pub fn step(&self, stroke: &Stroke, motion: &mut SwimMotion) {
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
