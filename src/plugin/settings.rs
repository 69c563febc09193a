//! [`JellyfishSettings`]: simulation rate and level of detail for every jellyfish.

use crate::species::{Advection, Species};
use bevy::prelude::*;
use std::time::Duration;

/// How the plugin simulates and meshes. Edits apply to living jellyfish.
#[derive(Resource, Clone, Debug, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct JellyfishSettings {
    /// Simulation steps per second. A step takes a whole number of `FixedUpdate` ticks
    /// (at least one), so the rate is rounded to the nearest divisor of the fixed rate;
    /// a slice's stable step is about 1/32 of a stroke, so ~32 Hz costs one substep.
    pub simulation_hz: f64,
    /// Fluid cells per side for every slice instead of the species' own (`None`): the
    /// cost knob, about quadratic (64 is the aquarium's resolution, 100 the paper's).
    pub grid_override: Option<u32>,
    /// Advection scheme for every slice instead of the species' own (`None`). With a coarse
    /// `grid_override`, [`Advection::MacCormack`] keeps jellyfish swimming: at grid 64 the
    /// moon jelly swims ~0.16 diameters per stroke with it and ~0.01 without
    /// (`examples/lod.rs`).
    pub advection_override: Option<Advection>,
    /// Multiplies the species' mesh rings and segments (clamped to what validation allows).
    pub mesh_resolution_scale: f32,
}

impl Default for JellyfishSettings {
    fn default() -> Self {
        Self {
            simulation_hz: 32.0,
            grid_override: None,
            advection_override: None,
            mesh_resolution_scale: 1.0,
        }
    }
}

impl JellyfishSettings {
    /// The species a slice is simulated with: the asset's, with the overrides.
    pub fn simulated(&self, species: &Species) -> Species {
        let mut s = species.clone();
        if let Some(grid) = self.grid_override {
            s.grid_resolution = grid;
        }
        if let Some(advection) = self.advection_override {
            s.advection = advection;
        }
        s
    }

    /// The species a mesh is built with: [`Self::simulated`] with the resolution scaled.
    pub fn meshed(&self, species: &Species) -> Species {
        let mut s = self.simulated(species);
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

    /// Fixed ticks per simulation step at the given fixed timestep.
    pub fn ticks_per_step(&self, fixed: Duration) -> u32 {
        let fixed_hz = 1.0 / fixed.as_secs_f64().max(1e-9);
        let ticks = (fixed_hz / self.simulation_hz.max(1e-6)).round();
        if ticks.is_finite() {
            ticks.clamp(1.0, 1000.0) as u32
        } else {
            1
        }
    }
}
