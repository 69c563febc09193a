//! The bench's frame trace (`--frame-trace FILE`): every measured frame's wall time beside
//! the plugin's own figures and the fixed ticks it ran, written as CSV, and the frames
//! summed up by how many fixed ticks they took. A slow frame whose every figure is up
//! with it was the host; one that is slow in one figure, or took two ticks, was work.

use bevy::diagnostic::DiagnosticsStore;
use bevy::prelude::*;
use bevy_jellyfish::JellyfishDiagnostics;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The figures of each frame, as measured.
pub struct FrameTrace {
    path: PathBuf,
    rows: Vec<Row>,
    /// The fixed clock's elapsed time before the frame, s.
    fixed_before: f64,
}

/// One frame: its wall time and the plugin's CPU time in it, ms, and its fixed ticks.
struct Row {
    wall: f64,
    ticks: u32,
    simulation: f64,
    meshing: f64,
    water: f64,
    tiers: [f64; 3],
}

impl FrameTrace {
    /// A trace to be written to `path`, starting with the next frame.
    pub fn new(path: &Path, app: &App) -> Self {
        Self {
            path: path.to_path_buf(),
            rows: Vec::new(),
            fixed_before: fixed_elapsed(app),
        }
    }

    /// Records the frame that just ran in `app`, `wall` ms long.
    pub fn record(&mut self, app: &App, wall: f64) {
        let fixed = fixed_elapsed(app);
        let step = app
            .world()
            .resource::<Time<Fixed>>()
            .timestep()
            .as_secs_f64();
        let ticks = ((fixed - self.fixed_before) / step.max(1e-9)).round() as u32;
        self.fixed_before = fixed;
        let store = app.world().resource::<DiagnosticsStore>();
        let value = |p| crate::bench::value(store, &p);
        self.rows.push(Row {
            wall,
            ticks,
            simulation: value(JellyfishDiagnostics::SIMULATION),
            meshing: value(JellyfishDiagnostics::MESHING),
            water: value(JellyfishDiagnostics::WATER),
            tiers: [
                value(JellyfishDiagnostics::NEAR_MS),
                value(JellyfishDiagnostics::MID_MS),
                value(JellyfishDiagnostics::FAR_MS),
            ],
        });
    }

    /// Writes the CSV and prints the frames by their fixed ticks: how many, and their mean
    /// wall time and figures.
    pub fn finish(self) -> Result<(), String> {
        let mut csv = String::from(
            "frame,wall_ms,fixed_ticks,simulation_cpu_ms,meshing_cpu_ms,tank_water_ms,\
             near_cpu_ms,mid_cpu_ms,far_cpu_ms\n",
        );
        for (k, r) in self.rows.iter().enumerate() {
            let [near, mid, far] = r.tiers;
            let _ = writeln!(
                csv,
                "{k},{:.3},{},{:.3},{:.3},{:.3},{near:.3},{mid:.3},{far:.3}",
                r.wall, r.ticks, r.simulation, r.meshing, r.water
            );
        }
        std::fs::write(&self.path, csv)
            .map_err(|e| format!("--frame-trace {}: {e}", self.path.display()))?;
        let most = self.rows.iter().map(|r| r.ticks).max().unwrap_or(0);
        for ticks in 0..=most {
            let rows: Vec<&Row> = self.rows.iter().filter(|r| r.ticks == ticks).collect();
            if rows.is_empty() {
                continue;
            }
            let mean =
                |f: fn(&Row) -> f64| rows.iter().map(|r| f(r)).sum::<f64>() / rows.len() as f64;
            println!(
                "frames with {ticks} fixed tick(s): {} ({:.1}%), mean wall {:.2} ms, simulation \
                 {:.2} ms, meshing {:.2} ms, tank water {:.2} ms",
                rows.len(),
                100.0 * rows.len() as f64 / self.rows.len().max(1) as f64,
                mean(|r| r.wall),
                mean(|r| r.simulation),
                mean(|r| r.meshing),
                mean(|r| r.water),
            );
        }
        println!("frame trace: {}", self.path.display());
        Ok(())
    }
}

fn fixed_elapsed(app: &App) -> f64 {
    app.world()
        .resource::<Time<Fixed>>()
        .elapsed()
        .as_secs_f64()
}
