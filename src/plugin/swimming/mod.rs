//! How a jellyfish travels through the world: its own swimming along its axis (what its
//! slice computes), carried by the water, turned by the water's vorticity and, during power
//! strokes, by its [`Steering`]; held still by [`Resting`]. Its fringe trails in the water
//! around it ([`TentacleGuides`]).

mod fringe;
mod guide_frame;
mod oral_guides;
mod pose;
mod steering;
mod travel;

pub(crate) use fringe::FarTow;
pub use fringe::TentacleGuides;
pub(crate) use guide_frame::GuideFrame;
pub use pose::Pose;
pub use steering::{Steering, SteeringTarget};
pub(crate) use travel::{Stroke, Travel};

use super::jellyfish::Jellyfish;
use bevy::prelude::*;

/// Gives every jellyfish a [`SwimMotion`] and registers the swimming components.
#[derive(Clone, Copy, Debug, Default)]
pub struct SwimmingPlugin;

impl Plugin for SwimmingPlugin {
    fn build(&self, app: &mut App) {
        app.register_required_components::<Jellyfish, SwimMotion>()
            .register_required_components::<Jellyfish, TentacleGuides>()
            .register_type::<SwimMotion>()
            .register_type::<Steering>()
            .register_type::<Resting>();
    }
}

/// How the jellyfish travels: its pose after the newest slice step (the physics; the
/// `Transform` shows it blended between steps) and its ground velocity. Moving or turning
/// the `Transform` yourself moves this with it: travel continues from where it was put.
#[derive(Component, Clone, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct SwimMotion {
    /// Pose after the newest step, world.
    pub pose: Pose,
    /// Ground velocity over the newest step (the water's plus its own swimming), world
    /// units per second.
    pub velocity: Vec3,
    /// Its own swimming along its axis over the steps of the last frame that took any,
    /// world units per second (negative while the bell recoils).
    pub swim_speed: f32,
    /// Swim distance at the newest step, m.
    #[reflect(ignore)]
    pub(crate) swum: f32,
    /// What the plugin last wrote into the `Transform`, to see a game's own edits.
    #[reflect(ignore)]
    pub(crate) written: Option<Transform>,
    /// The water a far jellyfish read last, while it holds it (`Travel::step_far`).
    #[reflect(ignore)]
    pub(crate) held_water: Option<travel::HeldWater>,
}

/// A far jellyfish works out the water around it about this often, s: its trailing and
/// its drift. The water around it changes over seconds, and it is a few pixels.
pub(crate) const FAR_REFRESH: f32 = 0.25;

/// A jellyfish with this holds its stroke: it drifts with the water, its bell at rest,
/// and resumes the stroke where it stopped when the component goes.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct Resting;
