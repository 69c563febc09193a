//! Simulation and meshing time and mesh data per frame as Bevy diagnostics.

use super::components::JellyfishSlice;
use bevy::diagnostic::{Diagnostic, DiagnosticPath, Diagnostics, RegisterDiagnostic};
use bevy::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// The plugin's diagnostic paths. Times are CPU milliseconds per frame summed over all
/// jellyfish (systems run in parallel, so wall time is lower on several cores); divide
/// by [`Self::COUNT`] for the cost of one.
pub struct JellyfishDiagnostics;

impl JellyfishDiagnostics {
    /// Slice stepping and cycle replay, ms.
    pub const SIMULATION: DiagnosticPath = DiagnosticPath::const_new("jellyfish/simulation_ms");
    /// Mesh rebuilding and upload to the mesh assets, ms.
    pub const MESHING: DiagnosticPath = DiagnosticPath::const_new("jellyfish/meshing_ms");
    /// Jellyfish swimming (their species loaded), of any tier.
    pub const COUNT: DiagnosticPath = DiagnosticPath::const_new("jellyfish/count");
    /// Jellyfish at each [`Tier`](super::Tier).
    pub const NEAR: DiagnosticPath = DiagnosticPath::const_new("jellyfish/near");
    /// Jellyfish in the mid tier.
    pub const MID: DiagnosticPath = DiagnosticPath::const_new("jellyfish/mid");
    /// Jellyfish in the far tier.
    pub const FAR: DiagnosticPath = DiagnosticPath::const_new("jellyfish/far");
    /// Jellyfish that changed tier this frame.
    pub const TIER_CHANGES: DiagnosticPath = DiagnosticPath::const_new("jellyfish/tier_changes");
    /// Stepping the tank's water ([`TankWater`](super::TankWater)), all fixed ticks of the
    /// frame, ms.
    pub const WATER: DiagnosticPath = DiagnosticPath::const_new("jellyfish/water_ms");
    /// Bytes written into mesh assets this frame (what the renderer re-uploads), MB.
    pub const MESH_DATA: DiagnosticPath = DiagnosticPath::const_new("jellyfish/mesh_data_mb");
}

/// Time accumulated by the parallel systems during a frame (atomics, so any thread adds).
#[derive(Resource, Default)]
pub(crate) struct JellyfishTimings {
    simulation_ns: AtomicU64,
    meshing_ns: AtomicU64,
    water_ns: AtomicU64,
    mesh_bytes: AtomicU64,
    tier_changes: AtomicU64,
}

impl JellyfishTimings {
    /// Adds time spent stepping slices this frame.
    pub fn add_simulation(&self, d: Duration) {
        self.simulation_ns
            .fetch_add(d.as_nanos() as u64, Ordering::Relaxed);
    }

    /// Adds time spent meshing this frame.
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
}

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<JellyfishTimings>()
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::SIMULATION).with_suffix(" ms"))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::MESHING).with_suffix(" ms"))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::COUNT))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::NEAR))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::MID))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::FAR))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::TIER_CHANGES))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::MESH_DATA).with_suffix(" MB"))
        .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::WATER).with_suffix(" ms"))
        .add_systems(Last, record);
}

fn record(
    mut diagnostics: Diagnostics,
    timings: Res<JellyfishTimings>,
    slices: Query<&JellyfishSlice>,
) {
    let ms = |ns: &AtomicU64| ns.swap(0, Ordering::Relaxed) as f64 * 1e-6;
    let (simulation, meshing) = (ms(&timings.simulation_ns), ms(&timings.meshing_ns));
    diagnostics.add_measurement(&JellyfishDiagnostics::SIMULATION, || simulation);
    diagnostics.add_measurement(&JellyfishDiagnostics::MESHING, || meshing);
    let water = ms(&timings.water_ns);
    diagnostics.add_measurement(&JellyfishDiagnostics::WATER, || water);
    let bytes = timings.mesh_bytes.swap(0, Ordering::Relaxed);
    diagnostics.add_measurement(&JellyfishDiagnostics::MESH_DATA, || bytes as f64 * 1e-6);
    let changes = timings.tier_changes.swap(0, Ordering::Relaxed) as f64;
    diagnostics.add_measurement(&JellyfishDiagnostics::TIER_CHANGES, || changes);
    let mut tiers = [0usize; 3];
    for slice in slices.iter().filter(|s| s.started()) {
        tiers[slice.tier() as usize] += 1;
    }
    let count = tiers.iter().sum::<usize>() as f64;
    diagnostics.add_measurement(&JellyfishDiagnostics::COUNT, || count);
    diagnostics.add_measurement(&JellyfishDiagnostics::NEAR, || tiers[0] as f64);
    diagnostics.add_measurement(&JellyfishDiagnostics::MID, || tiers[1] as f64);
    diagnostics.add_measurement(&JellyfishDiagnostics::FAR, || tiers[2] as f64);
}
