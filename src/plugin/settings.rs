//! [`JellyfishSettings`]: simulation rate and level of detail for every jellyfish.

use crate::sim::SliceSim;
use crate::species::{Advection, Species};
use bevy::prelude::*;
use std::time::Duration;

/// How the plugin simulates and meshes. Edits apply to living jellyfish.
#[derive(Resource, Clone, Debug, PartialEq, Reflect)]
#[reflect(Resource)]
pub struct JellyfishSettings {
    /// The fewest simulation steps (frames blend between them) per second. Each slice
    /// steps every whole number of `FixedUpdate` ticks, as many as make it cheapest for its
    /// species (it substeps to stay accurate), but at least this often.
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
            simulation_hz: 12.0,
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

    /// Fixed ticks per step for a slice of `species` (as simulated): of the step lengths
    /// `simulation_hz` allows, the one needing the fewest substeps per second. A moon jelly
    /// at 64 Hz ticks steps every 5 ticks in 2 substeps (25.6 per second), where every 2
    /// ticks in 1 would cost 32.
    pub fn ticks_per_step(&self, fixed: Duration, species: &Species) -> u32 {
        let tick = fixed.as_secs_f64().max(1e-9);
        let longest = (1.0 / (self.simulation_hz.max(1e-6) * tick)).round();
        let longest = if longest.is_finite() {
            longest.clamp(1.0, 1000.0) as u32
        } else {
            1
        };
        let cost = |k: u32| substeps_per_second(species, k as f64 * tick);
        (1..=longest)
            .fold((1, f64::INFINITY), |best, k| {
                let c = cost(k);
                if c < best.1 * (1.0 - 1e-9) {
                    (k, c)
                } else {
                    best
                }
            })
            .0
    }
}

/// Substeps per second for steps of `dt` seconds, counted as `SliceSim::advance` does
/// (in f32) when the muscle drive, not the flow, limits the step.
fn substeps_per_second(species: &Species, dt: f64) -> f64 {
    ((dt as f32 / SliceSim::accurate_step(species))
        .ceil()
        .max(1.0) as f64)
        / dt
}

#[cfg(test)]
mod tests {
    use super::*;

    const TICK: Duration = Duration::from_micros(15_625); // Bevy's 64 Hz

    /// Substeps per second for steps of `ticks` ticks.
    fn cost(species: &Species, ticks: u32) -> f64 {
        substeps_per_second(species, ticks as f64 * TICK.as_secs_f64())
    }

    #[test]
    fn a_moon_jelly_steps_less_often_than_every_other_tick() {
        let settings = JellyfishSettings::default();
        let aurelia = Species::aurelia();
        let ticks = settings.ticks_per_step(TICK, &aurelia);
        assert_eq!(ticks, 5);
        assert!(cost(&aurelia, ticks) < 0.81 * cost(&aurelia, 2));
    }

    #[test]
    fn steps_are_the_cheapest_the_rate_floor_allows() {
        for hz in [1.0, 4.0, 12.0, 30.0, 64.0, 500.0] {
            let settings = JellyfishSettings {
                simulation_hz: hz,
                ..Default::default()
            };
            let longest = ((64.0 / hz).round() as u32).max(1);
            for freq in [0.2, 0.6, 0.7, 1.4, 3.0, 9.0] {
                let species = Species {
                    contraction_frequency: freq,
                    ..Species::aurelia()
                };
                let ticks = settings.ticks_per_step(TICK, &species);
                assert!(
                    (1..=longest).contains(&ticks),
                    "{hz} Hz, {freq} Hz: {ticks}"
                );
                let cheapest = cost(&species, ticks);
                for k in 1..=longest {
                    assert!(cheapest <= cost(&species, k) + 1e-9);
                }
            }
        }
    }
}
