//! [`JellyfishSettings`]: how every jellyfish is drawn. Nothing here changes the physics:
//! a slice's step, grid and numerics belong to its species.

use crate::species::Species;
use bevy::prelude::*;

/// How the plugin meshes. Edits apply to living jellyfish on the next frame.
#[derive(Resource, Clone, Debug, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct JellyfishSettings {
    /// Multiplies the species' mesh rings and segments (clamped to what validation allows).
    pub mesh_resolution_scale: f32,
}

impl Default for JellyfishSettings {
    fn default() -> Self {
        Self {
            mesh_resolution_scale: 1.0,
        }
    }
}

impl JellyfishSettings {
    /// The species a mesh is built with: the slice's, with the resolution scaled.
    pub fn meshed(&self, species: &Species) -> Species {
        let mut s = species.clone();
        let scale = if self.mesh_resolution_scale.is_finite() {
            self.mesh_resolution_scale.max(0.0)
        } else {
            1.0
        };
        let scaled = |n: u32, lo: u32, hi: u32| ((n as f32 * scale).round() as u32).clamp(lo, hi);
        s.mesh_rings = scaled(s.mesh_rings, 2, 256);
        s.mesh_segments = scaled(s.mesh_segments, 3, 512);
        s
    }
}
