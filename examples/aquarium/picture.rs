//! Offscreen pictures (`--screenshot`): the aquarium rendered without a window, frame by
//! frame at 60 simulated frames per second, the last frame written to a PNG.

use crate::scene::AquariumPlugin;
use crate::{Args, bench, camera, screenshot, water};
use bevy::diagnostic::DiagnosticsStore;
use bevy::prelude::*;
use bevy_jellyfish::plugin::TankWater;
use bevy_jellyfish::{JellyfishDiagnostics, JellyfishSettings};
use std::path::Path;

/// Renders `args.frames` frames (default 120) offscreen and writes the last to `path`.
pub fn render(args: &Args, path: &Path) -> Result<(), String> {
    let (width, height) = args.size;
    let frames_to_render = args.frames.unwrap_or(120);
    let (school, surfaces, detail) = (args.school(), args.surfaces, args.detail());
    let (stir, promote_at, oit) = (args.stir, args.promote_at, args.oit);
    let mut offscreen = screenshot::Offscreen::new(width, height, |app| {
        app.add_plugins(AquariumPlugin {
            school,
            surfaces,
            detail: detail.clone(),
        });
        if stir {
            app.insert_resource(water::ScriptedStir::across_the_middle());
        }
        if oit {
            app.insert_resource(camera::OrderIndependent);
        }
        if let Some(frame) = promote_at {
            app.add_systems(First, promote_all_at(frame));
        }
    })
    .map_err(|e| e.to_string())?;
    println!("rendering offscreen on {}", offscreen.adapter);
    let start = std::time::Instant::now();
    let (mut simulation, mut meshing) = (0.0, 0.0);
    for _ in 0..frames_to_render {
        offscreen.update();
        let store = offscreen.world().resource::<DiagnosticsStore>();
        simulation += bench::value(store, &JellyfishDiagnostics::SIMULATION);
        meshing += bench::value(store, &JellyfishDiagnostics::MESHING);
    }
    let frames = frames_to_render.max(1) as f64;
    let wall = start.elapsed().as_secs_f64() * 1e3 / frames;
    let store = offscreen.world().resource::<DiagnosticsStore>();
    let count = bench::value(store, &JellyfishDiagnostics::COUNT);
    println!(
        "{frames_to_render} frames at {width}x{height}, {count} jellyfish: {wall:.1} ms per \
         frame (render included), simulation {:.2} ms, meshing {:.2} ms per frame (CPU, \
         summed over jellyfish)",
        simulation / frames,
        meshing / frames,
    );
    if let Some(tank) = offscreen.world().get_resource::<TankWater>() {
        println!("tank water: fastest {:.2} units/s", tank.speed_max());
    }
    offscreen.capture(path)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// A system that makes every jellyfish near from frame `at` on, all at once.
fn promote_all_at(at: u32) -> impl FnMut(ResMut<JellyfishSettings>, Local<u32>) {
    move |mut settings, mut frame| {
        *frame += 1;
        if *frame == at {
            settings.detail.near = usize::MAX;
            settings.detail.promotions_per_frame = usize::MAX;
        }
    }
}
