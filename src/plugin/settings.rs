//! [`JellyfishSettings`]: how every jellyfish is drawn, and how many are simulated in
//! full. A slice's step, grid and numerics belong to its species; the levels of detail
//! only choose which jellyfish replay their species' recorded stroke instead (see
//! [`DetailLevels`]). The tuning of every part lives here, in one resource, so the parts
//! read it without reaching into each other.

use crate::shape::Resolution;
use crate::species::Species;
use bevy::prelude::*;

/// How the plugin meshes. Edits apply to living jellyfish on the next frame.
#[derive(Resource, Clone, Debug, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct JellyfishSettings {
    /// Multiplies the species' mesh rings and segments (clamped to what validation allows).
    pub mesh_resolution_scale: f32,
    /// Where surfaces are built: on the GPU from shared template meshes, or on the CPU.
    pub surfaces: SurfaceMode,
    /// How many jellyfish are simulated in full, in a compact box, or replayed.
    pub detail: DetailLevels,
}

impl Default for JellyfishSettings {
    fn default() -> Self {
        Self {
            mesh_resolution_scale: 1.0,
            surfaces: SurfaceMode::Auto,
            detail: DetailLevels::default(),
        }
    }
}

/// Where jellyfish surfaces are built (the picture is the same either way).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Reflect)]
pub enum SurfaceMode {
    /// Templates where the GPU can read storage buffers in its vertex shaders (and the app
    /// renders), CPU meshes elsewhere (WebGL2, headless apps).
    #[default]
    Auto,
    /// One template mesh per resolution shared by all; each jellyfish uploads a shape of a
    /// few kilobytes a frame and the vertex shader builds its surface. Falls back to CPU
    /// meshes, with a warning, on a device that cannot.
    Templates,
    /// Every jellyfish's meshes rebuilt on the CPU and re-uploaded each frame (~280 KB for
    /// a moon jelly): the reference, and what a custom `StandardMaterial` needs.
    CpuMeshes,
}

impl JellyfishSettings {
    /// The resolution a species is drawn at: its own, scaled by `mesh_resolution_scale`.
    pub fn resolution(&self, species: &Species) -> Resolution {
        Resolution::scaled(species, self.mesh_resolution_scale)
    }
}

/// How many jellyfish get each tier, and from what size on screen. The largest on screen
/// (bell diameter over the view's height, for the first active camera) are near, the next
/// mid, the rest far; jellyfish no camera sees rank last. With no camera, the lowest
/// entities are nearest.
#[derive(Clone, Debug, PartialEq, Reflect)]
pub struct DetailLevels {
    /// At most this many near jellyfish.
    pub near: usize,
    /// At most this many mid jellyfish.
    pub mid: usize,
    /// Smallest size on screen for near (fraction of the view's height).
    pub near_size: f32,
    /// Smallest size on screen for mid.
    pub mid_size: f32,
    /// A jellyfish keeps its tier until another outranks it by this fraction of its size,
    /// so one at the boundary does not flicker between tiers.
    pub hysteresis: f32,
    /// At most this many jellyfish move to a nearer tier in one frame (each resumes a
    /// slice: a copy and up to three steps).
    pub promotions_per_frame: usize,
    /// Steps a frame of each cycle recorded after an edit (a species' far cycle and its
    /// compact variant), taken in the background from the end of one frame to the next
    /// frame's levels of detail: more records sooner, fewer leaves more of the cores to
    /// the frames (at least one is taken). A count, not a time, so the new cycle arrives on the same
    /// frame in every run.
    pub recording_steps_per_frame: u32,
}

impl Default for DetailLevels {
    fn default() -> Self {
        Self {
            near: 100,
            mid: 24,
            near_size: 0.0,
            mid_size: 0.0,
            hysteresis: 0.25,
            promotions_per_frame: 12,
            recording_steps_per_frame: 24,
        }
    }
}
