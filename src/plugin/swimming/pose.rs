//! Where a jellyfish is and which way it points.

use bevy::prelude::*;

/// Where a jellyfish is and which way it points, world.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Pose {
    /// World position.
    pub position: Vec3,
    /// World rotation: local +Y is the swimming axis.
    pub rotation: Quat,
}

impl Default for Pose {
    fn default() -> Self {
        Self {
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
        }
    }
}

impl Pose {
    /// The pose a transform holds.
    pub fn of(transform: &Transform) -> Self {
        Self {
            position: transform.translation,
            rotation: transform.rotation,
        }
    }

    /// Between `self` (t = 0) and `other` (t = 1).
    pub fn blend(&self, other: &Pose, t: f32) -> Pose {
        Pose {
            position: self.position.lerp(other.position, t),
            // Unturned stays bit for bit unturned.
            rotation: if self.rotation == other.rotation {
                self.rotation
            } else {
                self.rotation.slerp(other.rotation, t)
            },
        }
    }

    /// This pose carried along with a rigid move that takes `from` to `to`.
    pub fn moved(&self, from: Pose, to: Pose) -> Pose {
        let turn = to.rotation * from.rotation.inverse();
        Pose {
            position: to.position + turn * (self.position - from.position),
            rotation: (turn * self.rotation).normalize(),
        }
    }
}
