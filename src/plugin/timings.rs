//! What the parallel systems spend during a frame, gathered for the diagnostics.

use bevy::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// Time and data accumulated by the parallel systems during a frame (atomics, so any
/// thread adds); read and reset once a frame by the diagnostics.
#[derive(Resource, Default)]
pub(crate) struct JellyfishTimings {
    simulation_ns: AtomicU64,
    meshing_ns: AtomicU64,
    /// Stepping and meshing of one tier's jellyfish (near, mid, far), a part of the two
    /// above; what they share (uploads, mesh assets) is in no tier.
    tier_ns: [AtomicU64; 3],
    water_ns: AtomicU64,
    mesh_bytes: AtomicU64,
    tier_changes: AtomicU64,
}

/// One frame's figures, taken out of [`JellyfishTimings`].
pub(crate) struct FrameFigures {
    pub simulation_ms: f64,
    pub meshing_ms: f64,
    /// Near, mid and far jellyfish's stepping and meshing.
    pub tier_ms: [f64; 3],
    pub water_ms: f64,
    pub mesh_bytes: u64,
    pub tier_changes: u64,
}

impl JellyfishTimings {
    /// Adds time spent stepping a jellyfish of tier `tier` (`Tier as usize`: the slices
    /// import the timings, not the other way) this frame.
    pub fn add_simulation(&self, tier: usize, d: Duration) {
        let ns = d.as_nanos() as u64;
        self.simulation_ns.fetch_add(ns, Ordering::Relaxed);
        self.tier_ns[tier.min(2)].fetch_add(ns, Ordering::Relaxed);
    }

    /// Adds time spent meshing a jellyfish of tier `tier` this frame.
    pub fn add_meshing_of(&self, tier: usize, d: Duration) {
        let ns = d.as_nanos() as u64;
        self.meshing_ns.fetch_add(ns, Ordering::Relaxed);
        self.tier_ns[tier.min(2)].fetch_add(ns, Ordering::Relaxed);
    }

    /// Adds time spent meshing this frame for all jellyfish together.
    pub fn add_meshing(&self, d: Duration) {
        self.meshing_ns
            .fetch_add(d.as_nanos() as u64, Ordering::Relaxed);
    }

    /// Adds time spent on the tank's water this frame.
    pub fn add_water(&self, d: Duration) {
        self.water_ns
            .fetch_add(d.as_nanos() as u64, Ordering::Relaxed);
    }

    /// Counts jellyfish that changed tier this frame.
    pub fn add_tier_changes(&self, count: usize) {
        self.tier_changes.fetch_add(count as u64, Ordering::Relaxed);
    }

    /// Counts mesh bytes written this frame.
    pub fn add_mesh_bytes(&self, bytes: usize) {
        self.mesh_bytes.fetch_add(bytes as u64, Ordering::Relaxed);
    }

    /// The frame's figures, starting the next frame from zero.
    pub fn take(&self) -> FrameFigures {
        let ms = |ns: &AtomicU64| ns.swap(0, Ordering::Relaxed) as f64 * 1e-6;
        FrameFigures {
            simulation_ms: ms(&self.simulation_ns),
            meshing_ms: ms(&self.meshing_ns),
            tier_ms: self.tier_ns.each_ref().map(ms),
            water_ms: ms(&self.water_ns),
            mesh_bytes: self.mesh_bytes.swap(0, Ordering::Relaxed),
            tier_changes: self.tier_changes.swap(0, Ordering::Relaxed),
        }
    }
}
