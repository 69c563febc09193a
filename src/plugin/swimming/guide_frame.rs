//! One slice step as the guide chains see it, and the water they read in it: the world's
//! water at a point of the body frame, less the current that carries the bell.

use super::Pose;
use crate::plugin::water::AmbientWater;
use crate::sim::guides::read_along;
use crate::species::Species;
use bevy::prelude::*;

/// One slice step as the guides see it.
pub(crate) struct GuideFrame<'a> {
    pub species: &'a Species,
    /// The bell's subumbrella and the two tentacle chains after the step, slice frame.
    pub bell: &'a [Vec2],
    pub tentacles: [&'a [Vec2]; 2],
    /// The two oral chains after the step, slice frame (empty without oral tubes).
    pub oral_arms: [&'a [Vec2]; 2],
    /// The bell's centroid in the same frame (the body frame's origin).
    pub centroid: Vec2,
    /// The step, s.
    pub dt: f32,
    /// How far the bell swam along its axis in the step, m.
    pub surge: f32,
    /// The pose before and after the step's travel.
    pub before: Pose,
    pub after: Pose,
    /// World units per metre of slice, per axis.
    pub scale: Vec3,
    pub water: &'a AmbientWater,
    /// World time the water is read at, s.
    pub time: f64,
}

/// The water relative to the current carrying the bell at each node of guides drawn at
/// `reference + offsets`, body frame, m/s ([`read_along`]: at each guide's root, middle
/// and tip).
pub(super) fn water_along(
    f: &GuideFrame,
    reference: &[Vec3],
    offsets: &[Vec3],
    out: &mut Vec<Vec3>,
) {
    let carrying = carrying(f);
    read_along(reference, offsets, |p| relative_water(f, carrying, p), out);
}

/// The current carrying the bell, world units per second.
pub(super) fn carrying(f: &GuideFrame) -> Vec3 {
    finite(f.water.velocity(f.after.position, f.time))
}

/// The water at the body-frame point `local` less the current `carrying` the bell, body
/// frame, m/s (zero where the field is not finite).
pub(super) fn relative_water(f: &GuideFrame, carrying: Vec3, local: Vec3) -> Vec3 {
    let (pose, scale) = (f.after, f.scale);
    let world = pose.position + pose.rotation * (scale * local);
    let relative = finite(f.water.velocity(world, f.time)) - carrying;
    finite(pose.rotation.inverse() * relative / scale)
}

fn finite(v: Vec3) -> Vec3 {
    if v.is_finite() { v } else { Vec3::ZERO }
}
