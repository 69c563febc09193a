//! Steering by the stroke: a jellyfish turns towards a commanded heading only while it
//! contracts, by an angle that grows with what the contraction does.
//!
//! Real medusae turn by contracting one side of the bell harder than the other; the turn
//! comes with the power stroke and stops while the bell coasts and refills. The slice is
//! mirror-symmetric (see `SliceSim::set_mirror_symmetry`): its two halves share the
//! muscle springs that span the bell, so one side cannot be made to pull harder than the
//! other without a second set of muscles, and a free, asymmetric slice tipped over from
//! round-off alone (the paper also failed to steer this way). So the turn is an impulse per
//! power stroke: each step of the contraction turns the axis by `agility` radians per
//! bell diameter the bell surged forward in that step. A stronger stroke surges further
//! and turns more; the coasting half of the cycle does not turn at all.

use bevy::prelude::*;

/// Where a jellyfish wants to go. It turns only while it strokes (see the module); leave
/// it off, or rotate the `Transform` yourself, for full control.
#[derive(Component, Clone, Copy, Debug, PartialEq, Reflect)]
#[reflect(Component)]
pub struct Steering {
    /// Where it heads.
    pub target: SteeringTarget,
    /// Radians turned per bell diameter the bell surges forward during contraction.
    pub agility: f32,
}

/// A heading or a place to head for.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub enum SteeringTarget {
    /// A world direction (need not be normalised).
    Heading(Vec3),
    /// A world point to swim towards.
    Point(Vec3),
}

impl Steering {
    /// About 25° per stroke for the default moon jelly once it swims at speed (its bell
    /// surges about a seventh of a diameter while contracting), less in its first strokes
    /// from rest: a right angle in about five strokes from rest.
    pub const DEFAULT_AGILITY: f32 = 3.0;

    /// Head in a world direction.
    pub fn heading(direction: Vec3) -> Self {
        Self {
            target: SteeringTarget::Heading(direction),
            agility: Self::DEFAULT_AGILITY,
        }
    }

    /// Head for a world point.
    pub fn towards(point: Vec3) -> Self {
        Self {
            target: SteeringTarget::Point(point),
            agility: Self::DEFAULT_AGILITY,
        }
    }

    /// How strongly it turns per stroke (see `agility`).
    pub fn with_agility(mut self, agility: f32) -> Self {
        self.agility = agility;
        self
    }

    /// The desired axis from `position`, if there is one.
    pub fn desired(&self, position: Vec3) -> Option<Vec3> {
        let d = match self.target {
            SteeringTarget::Heading(h) => h,
            SteeringTarget::Point(p) => p - position,
        };
        d.try_normalize()
    }

    /// `rotation` turned towards the target by at most the step's budget: `surge` is how
    /// far forward the bell moved in the step, in diameters (nothing while it coasts or
    /// recoils), `contracting` whether the step is in the power stroke.
    pub fn turn(&self, rotation: Quat, position: Vec3, surge: f32, contracting: bool) -> Quat {
        // (Asked in this order: most steps do not contract, and need no heading.)
        if !contracting || surge.is_nan() || surge <= 0.0 || !self.agility.is_finite() {
            return rotation;
        }
        let Some(desired) = self.desired(position) else {
            return rotation;
        };
        let axis = rotation * Vec3::Y;
        let angle = axis.angle_between(desired);
        if angle.is_nan() || angle <= 1e-6 {
            return rotation;
        }
        let budget = (self.agility * surge).max(0.0);
        let arc = if angle > std::f32::consts::PI - 1e-3 {
            // Straight behind: turn about any axis across the bell.
            Quat::from_axis_angle((rotation * Vec3::X).normalize(), angle)
        } else {
            Quat::from_rotation_arc(axis, desired)
        };
        let step = Quat::IDENTITY.slerp(arc, (budget / angle).min(1.0));
        (step * rotation).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_only_while_contracting_and_never_past_the_target() {
        let s = Steering::heading(Vec3::X);
        let up = Quat::IDENTITY;
        assert_eq!(s.turn(up, Vec3::ZERO, 0.1, false), up, "coasting");
        assert_eq!(s.turn(up, Vec3::ZERO, -0.1, true), up, "recoiling");
        let turned = s.turn(up, Vec3::ZERO, 0.1, true);
        let angle = (turned * Vec3::Y).angle_between(Vec3::Y);
        assert!((angle - 0.1 * s.agility).abs() < 1e-4, "{angle}");
        let done = s.turn(up, Vec3::ZERO, 100.0, true);
        assert!(
            ((done * Vec3::Y) - Vec3::X).length() < 1e-4,
            "stops at the target"
        );
        // A point target: towards it.
        let p = Steering::towards(Vec3::new(0.0, 0.0, 5.0)).turn(up, Vec3::ZERO, 100.0, true);
        assert!(((p * Vec3::Y) - Vec3::Z).length() < 1e-4);
    }
}
