//! The headless aquarium benchmark: the schools swim and mesh as in the windowed app, with
//! no renderer, at 60 simulated frames per second. It prints what a frame costs.

use crate::school::School;
use bevy::asset::AssetPlugin;
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::mesh::MeshPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::plugin::JellyfishSlice;
use bevy_jellyfish::{JellyfishDiagnostics, JellyfishPlugin, JellyfishSettings};
use std::time::{Duration, Instant};

/// Runs `frames` frames after a warm-up and prints wall and CPU time per frame.
pub fn run(school: School, frames: usize, settings: JellyfishSettings, pools: TaskPoolPlugin) {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins.set(pools),
        AssetPlugin::default(),
        MeshPlugin,
        TransformPlugin,
        JellyfishPlugin {
            settings: settings.clone(),
        },
        crate::school::plugin,
    ))
    .insert_resource(school)
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / 60.0,
    )));
    app.finish();
    app.cleanup();
    // Load the species and build every slice (a slice plans its solver when created).
    let expected = (school.per_species * crate::school::SPECIES.len()) as f64;
    let start = Instant::now();
    while count(&app) < expected {
        app.update();
        if start.elapsed() > Duration::from_secs(120) {
            eprintln!(
                "bench: only {} of {expected} jellyfish started",
                count(&app)
            );
            break;
        }
    }
    for _ in 0..60 {
        app.update();
    }
    let (mut simulation, mut meshing) = (0.0, 0.0);
    let steps_before = steps(&mut app);
    let start = Instant::now();
    for _ in 0..frames {
        app.update();
        let store = app.world().resource::<DiagnosticsStore>();
        simulation += value(store, &JellyfishDiagnostics::SIMULATION);
        meshing += value(store, &JellyfishDiagnostics::MESHING);
    }
    let n = frames.max(1) as f64;
    let substeps_per_second =
        (steps(&mut app) - steps_before) as f64 / count(&app).max(1.0) / (n / 60.0);
    let wall = start.elapsed().as_secs_f64() * 1e3 / n;
    let threads = bevy::tasks::ComputeTaskPool::get().thread_num();
    println!(
        "headless aquarium: {} jellyfish, grid {}, {substeps_per_second:.1} substeps per \
         jellyfish-second, {frames} frames at 60 fps on {threads} threads: {wall:.2} ms wall \
         per frame; CPU per frame: simulation {:.2} ms, meshing {:.2} ms ({:.3} ms per jellyfish)",
        count(&app),
        settings
            .grid_override
            .map_or("per species".into(), |g| g.to_string()),
        simulation / n,
        meshing / n,
        (simulation + meshing) / n / count(&app).max(1.0),
    );
}

/// The latest value of a diagnostic, 0 before the first.
pub fn value(store: &DiagnosticsStore, path: &DiagnosticPath) -> f64 {
    store.get(path).and_then(|d| d.value()).unwrap_or(0.0)
}

fn count(app: &App) -> f64 {
    value(
        app.world().resource::<DiagnosticsStore>(),
        &JellyfishDiagnostics::COUNT,
    )
}

/// Coupled steps taken so far, summed over jellyfish.
fn steps(app: &mut App) -> u64 {
    let mut slices = app.world_mut().query::<&JellyfishSlice>();
    slices
        .iter(app.world())
        .filter_map(|s| s.sim().map(|sim| sim.steps()))
        .sum()
}
