//! Simulation and meshing time, mesh data and levels of detail per frame, as Bevy
//! diagnostics.

use super::schedule::JellyfishSystems;
use super::slice::JellyfishSlice;
use super::timings::JellyfishTimings;
use bevy::diagnostic::{Diagnostic, DiagnosticPath, Diagnostics, RegisterDiagnostic};
use bevy::prelude::*;

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
    /// Stepping and meshing the near jellyfish, ms (a part of [`Self::SIMULATION`] and
    /// [`Self::MESHING`]; divide by [`Self::NEAR`] for one).
    pub const NEAR_MS: DiagnosticPath = DiagnosticPath::const_new("jellyfish/near_ms");
    /// Stepping and meshing the mid-tier jellyfish, ms.
    pub const MID_MS: DiagnosticPath = DiagnosticPath::const_new("jellyfish/mid_ms");
    /// Replaying and meshing the far jellyfish, ms: what the parallel systems' batches
    /// spent besides their near and mid jellyfish (timed together, not one by one).
    pub const FAR_MS: DiagnosticPath = DiagnosticPath::const_new("jellyfish/far_ms");
    /// Stepping the tank's water ([`TankWater`](super::TankWater)), all fixed ticks of the
    /// frame, ms of wall time.
    pub const WATER: DiagnosticPath = DiagnosticPath::const_new("jellyfish/water_ms");
    /// Bytes written into mesh assets this frame (what the renderer re-uploads), MB.
    pub const MESH_DATA: DiagnosticPath = DiagnosticPath::const_new("jellyfish/mesh_data_mb");
}

/// Registers [`JellyfishDiagnostics`] and records them at the end of every frame.
#[derive(Clone, Copy, Debug, Default)]
pub struct JellyfishDiagnosticsPlugin;

impl Plugin for JellyfishDiagnosticsPlugin {
    fn build(&self, app: &mut App) {
        let ms = |path| Diagnostic::new(path).with_suffix(" ms");
        app.register_diagnostic(ms(JellyfishDiagnostics::SIMULATION))
            .register_diagnostic(ms(JellyfishDiagnostics::MESHING))
            .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::COUNT))
            .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::NEAR))
            .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::MID))
            .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::FAR))
            .register_diagnostic(Diagnostic::new(JellyfishDiagnostics::TIER_CHANGES))
            .register_diagnostic(ms(JellyfishDiagnostics::NEAR_MS))
            .register_diagnostic(ms(JellyfishDiagnostics::MID_MS))
            .register_diagnostic(ms(JellyfishDiagnostics::FAR_MS))
            .register_diagnostic(
                Diagnostic::new(JellyfishDiagnostics::MESH_DATA).with_suffix(" MB"),
            )
            .register_diagnostic(ms(JellyfishDiagnostics::WATER))
            .add_systems(Last, record.in_set(JellyfishSystems::Diagnostics));
    }
}

fn record(
    mut diagnostics: Diagnostics,
    timings: Res<JellyfishTimings>,
    slices: Query<&JellyfishSlice>,
) {
    let frame = timings.take();
    diagnostics.add_measurement(&JellyfishDiagnostics::SIMULATION, || frame.simulation_ms);
    diagnostics.add_measurement(&JellyfishDiagnostics::MESHING, || frame.meshing_ms);
    diagnostics.add_measurement(&JellyfishDiagnostics::WATER, || frame.water_ms);
    let [near_ms, mid_ms, far_ms] = frame.tier_ms;
    diagnostics.add_measurement(&JellyfishDiagnostics::NEAR_MS, || near_ms);
    diagnostics.add_measurement(&JellyfishDiagnostics::MID_MS, || mid_ms);
    diagnostics.add_measurement(&JellyfishDiagnostics::FAR_MS, || far_ms);
    let mb = frame.mesh_bytes as f64 * 1e-6;
    diagnostics.add_measurement(&JellyfishDiagnostics::MESH_DATA, || mb);
    let changes = frame.tier_changes as f64;
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
