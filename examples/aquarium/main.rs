//! The aquarium: schools of three species of jellyfish in a lit tank.
//!
//! `cargo run --release --example aquarium -- [--count N] [--seed S]`
//!
//! Left drag orbits, right drag pans, scroll zooms. Every few seconds the log prints the
//! frame rate, the number of jellyfish and the plugin's simulation and meshing time.
//!
//! Offscreen, without a window (Mesa's software Vulkan will do):
//! `cargo run --release --example aquarium -- --screenshot out.png --frames 120
//! [--size 1280x720]` renders that many frames at 60 simulated frames per second,
//! writes the last one and exits.

mod camera;
mod scene;
mod school;
mod screenshot;
mod snow;
mod stats;
mod tank;

use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::prelude::*;
use bevy_jellyfish::JellyfishDiagnostics;
use scene::AquariumPlugin;
use school::School;
use std::path::PathBuf;
use std::process::ExitCode;

struct Args {
    school: School,
    screenshot: Option<PathBuf>,
    frames: usize,
    size: (u32, u32),
}

impl Args {
    fn parse() -> Result<Self, String> {
        let mut args = Args {
            school: School {
                per_species: 6,
                seed: 1,
            },
            screenshot: None,
            frames: 120,
            size: (1280, 720),
        };
        let mut it = std::env::args().skip(1);
        while let Some(flag) = it.next() {
            let mut value = || it.next().ok_or(format!("{flag} needs a value"));
            let bad = |v: &str| format!("{flag}: cannot read {v:?}");
            match flag.as_str() {
                "--count" => {
                    let v = value()?;
                    args.school.per_species = v.parse().map_err(|_| bad(&v))?;
                }
                "--seed" => {
                    let v = value()?;
                    args.school.seed = v.parse().map_err(|_| bad(&v))?;
                }
                "--screenshot" => args.screenshot = Some(value()?.into()),
                "--frames" => {
                    let v = value()?;
                    args.frames = v.parse().map_err(|_| bad(&v))?;
                }
                "--size" => {
                    let v = value()?;
                    let (w, h) = v.split_once('x').ok_or_else(|| bad(&v))?;
                    args.size = (
                        w.parse().map_err(|_| bad(&v))?,
                        h.parse().map_err(|_| bad(&v))?,
                    );
                }
                _ => {
                    return Err(format!(
                        "unknown argument {flag:?}; usage: aquarium [--count N] [--seed S] \
                         [--screenshot out.png [--frames 120] [--size 1280x720]]"
                    ));
                }
            }
        }
        Ok(args)
    }
}

fn main() -> ExitCode {
    let args = match Args::parse() {
        Ok(args) => args,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    if let Some(path) = &args.screenshot {
        return match picture(&args, path) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("aquarium: {e}");
                ExitCode::FAILURE
            }
        };
    }
    App::new()
        .add_plugins((
            DefaultPlugins.set(WindowPlugin {
                primary_window: Some(Window {
                    title: "bevy_jellyfish aquarium".into(),
                    ..default()
                }),
                ..default()
            }),
            AquariumPlugin {
                school: args.school,
            },
        ))
        .run();
    ExitCode::SUCCESS
}

/// Renders `args.frames` frames offscreen and writes the last to `path`.
fn picture(args: &Args, path: &std::path::Path) -> Result<(), String> {
    let (width, height) = args.size;
    let school = args.school;
    let mut offscreen = screenshot::Offscreen::new(width, height, |app| {
        app.add_plugins(AquariumPlugin { school });
    })
    .map_err(|e| e.to_string())?;
    println!("rendering offscreen on {}", offscreen.adapter);
    let start = std::time::Instant::now();
    let (mut simulation, mut meshing) = (0.0, 0.0);
    for _ in 0..args.frames {
        offscreen.update();
        let store = offscreen.world().resource::<DiagnosticsStore>();
        let value = |p: &DiagnosticPath| store.get(p).and_then(|d| d.value()).unwrap_or(0.0);
        simulation += value(&JellyfishDiagnostics::SIMULATION);
        meshing += value(&JellyfishDiagnostics::MESHING);
    }
    let frames = args.frames.max(1) as f64;
    let wall = start.elapsed().as_secs_f64() * 1e3 / frames;
    let store = offscreen.world().resource::<DiagnosticsStore>();
    let count = store
        .get(&JellyfishDiagnostics::COUNT)
        .and_then(|d| d.value())
        .unwrap_or(0.0);
    println!(
        "{} frames at {width}x{height}, {count} jellyfish: {wall:.1} ms per frame (render \
         included), simulation {:.2} ms, meshing {:.2} ms per frame (CPU, summed over jellyfish)",
        args.frames,
        simulation / frames,
        meshing / frames,
    );
    offscreen.capture(path)?;
    println!("wrote {}", path.display());
    Ok(())
}
