//! What the parallel systems spend during a frame, gathered for the diagnostics.

use bevy::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

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

/// What a [`BatchClock`] times.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Spent {
    Simulation,
    Meshing,
}

/// Times one batch of a parallel system's jellyfish with few clock reads and atomic adds:
/// the near and mid ones (a hundred or so) one by one, the far ones (thousands, each a
/// microsecond or two, where two clock reads and two contended adds a jellyfish were a
/// measurable share of the frame) together, as what the batch spent besides. Adds it all
/// to the [`JellyfishTimings`] when the batch ends (dropped).
pub(crate) struct BatchClock<'a> {
    timings: &'a JellyfishTimings,
    spent: Spent,
    start: Instant,
    /// Near and mid jellyfish's time in the batch.
    live: [Duration; 2],
}

impl<'a> BatchClock<'a> {
    pub fn new(timings: &'a JellyfishTimings, spent: Spent) -> Self {
        Self {
            timings,
            spent,
            start: Instant::now(),
            live: [Duration::ZERO; 2],
        }
    }

    /// Runs `work` for a jellyfish of tier `tier` (`Tier as usize`): timed alone if near
    /// or mid.
    pub fn time<R>(&mut self, tier: usize, work: impl FnOnce() -> R) -> R {
        let Some(live) = self.live.get_mut(tier) else {
            return work();
        };
        let start = Instant::now();
        let result = work();
        *live += start.elapsed();
        result
    }
}

impl Drop for BatchClock<'_> {
    fn drop(&mut self) {
        let total = self.start.elapsed();
        let far = total.saturating_sub(self.live[0] + self.live[1]);
        let t = self.timings;
        let ns = |d: Duration| d.as_nanos() as u64;
        let sum = match self.spent {
            Spent::Simulation => &t.simulation_ns,
            Spent::Meshing => &t.meshing_ns,
        };
        sum.fetch_add(ns(total), Ordering::Relaxed);
        for (tier, d) in [self.live[0], self.live[1], far].into_iter().enumerate() {
            if !d.is_zero() {
                t.tier_ns[tier].fetch_add(ns(d), Ordering::Relaxed);
            }
        }
    }
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
