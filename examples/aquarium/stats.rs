//! Every few seconds: frames per second, jellyfish count, and the plugin's simulation and
//! meshing time per frame (CPU time summed over jellyfish).

use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore, FrameTimeDiagnosticsPlugin};
use bevy::prelude::*;
use bevy::time::common_conditions::on_real_timer;
use bevy_jellyfish::JellyfishDiagnostics;
use std::time::Duration;

pub fn plugin(app: &mut App) {
    if !app.is_plugin_added::<FrameTimeDiagnosticsPlugin>() {
        app.add_plugins(FrameTimeDiagnosticsPlugin::default());
    }
    app.add_systems(Last, report.run_if(on_real_timer(Duration::from_secs(3))));
}

/// One line of the current numbers, smoothed.
pub fn line(store: &DiagnosticsStore) -> String {
    let get = |p: &DiagnosticPath| store.get(p).and_then(|d| d.smoothed()).unwrap_or(0.0);
    format!(
        "{:.1} fps ({:.1} ms/frame), {} jellyfish ({} near, {} mid, {} far), simulation {:.2} ms, \
         meshing {:.2} ms per frame",
        get(&FrameTimeDiagnosticsPlugin::FPS),
        get(&FrameTimeDiagnosticsPlugin::FRAME_TIME),
        get(&JellyfishDiagnostics::COUNT) as u32,
        get(&JellyfishDiagnostics::NEAR) as u32,
        get(&JellyfishDiagnostics::MID) as u32,
        get(&JellyfishDiagnostics::FAR) as u32,
        get(&JellyfishDiagnostics::SIMULATION),
        get(&JellyfishDiagnostics::MESHING),
    )
}

fn report(store: Res<DiagnosticsStore>) {
    info!("{}", line(&store));
}
