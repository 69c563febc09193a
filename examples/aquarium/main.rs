//! The aquarium: schools of three species of jellyfish in a lit tank.
//!
//! `cargo run --release --features examples --example aquarium -- [--count N] [--seed S] [--oit]`
//!
//! `--oit` draws the translucent bells with Bevy's order-independent transparency
//! (MSAA off): overlapping bells blend in the right order wherever they cross, at some
//! cost in GPU memory and time; without it they are sorted by their origins.
//!
//! Left drag orbits, right drag pans, scroll zooms, Shift + left drag stirs the water. With the `editor` feature (on by
//! default) panels edit each species live, change the school size and show the frame
//! rate, jellyfish count and the plugin's simulation and meshing time; every few seconds
//! the log prints the same numbers.
//!
//! Offscreen, without a window (Mesa's software Vulkan will do):
//! `cargo run --release --features examples --example aquarium -- --screenshot out.png --frames 120
//! [--size 1280x720]` renders that many frames at 60 simulated frames per second,
//! writes the last one and exits.
//!
//! The headless benchmark, no renderer at all: `cargo run --release --features examples --example aquarium --
//! --bench [--count N] [--frames 600] [--fps 60]` prints the wall and CPU time of a frame,
//! the spread of frame times and the mesh data handed to the renderer.

mod bench;
mod camera;
#[path = "../common/species.rs"]
mod common;
mod scene;
mod school;
#[path = "../common/offscreen.rs"]
mod screenshot;
mod snow;
mod stats;
mod tank;
#[cfg(feature = "editor")]
mod ui;
mod water;

use bevy::diagnostic::DiagnosticsStore;
use bevy::prelude::*;
use bevy_jellyfish::plugin::{DetailLevels, SurfaceMode};
use bevy_jellyfish::{JellyfishDiagnostics, JellyfishSettings};
use scene::AquariumPlugin;
use school::School;
use std::path::PathBuf;
use std::process::ExitCode;

struct Args {
    school: School,
    screenshot: Option<PathBuf>,
    bench: bool,
    /// Frames to render or to benchmark (default 120 and 600).
    frames: Option<usize>,
    /// Frames per second of the benchmark.
    fps: f64,
    /// A scripted stir across the middle of the tank two seconds in (pictures).
    stir: bool,
    /// Offscreen: from this frame on every jellyfish is near (a picture of a transition).
    promote_at: Option<u32>,
    size: (u32, u32),
    /// Where surfaces are built: templates on the GPU (the bench packs them without one)
    /// or CPU meshes.
    surfaces: SurfaceMode,
    /// Levels of detail: how many jellyfish are near and mid.
    detail: DetailLevels,
    /// Order-independent transparency on the camera.
    oit: bool,
}

impl Args {
    fn parse() -> Result<Self, String> {
        let mut args = Args {
            school: School {
                per_species: 100,
                seed: 1,
            },
            screenshot: None,
            bench: false,
            frames: None,
            fps: 60.0,
            stir: false,
            promote_at: None,
            size: (1280, 720),
            surfaces: SurfaceMode::Auto,
            detail: DetailLevels::default(),
            oit: false,
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
                "--bench" => args.bench = true,
                "--stir" => args.stir = true,
                "--oit" => args.oit = true,
                "--promote-at" => {
                    let v = value()?;
                    args.promote_at = Some(v.parse().map_err(|_| bad(&v))?);
                }
                "--near" => {
                    let v = value()?;
                    args.detail.near = v.parse().map_err(|_| bad(&v))?;
                }
                "--mid" => {
                    let v = value()?;
                    args.detail.mid = v.parse().map_err(|_| bad(&v))?;
                }
                "--surfaces" => {
                    let v = value()?;
                    args.surfaces = match v.as_str() {
                        "auto" => SurfaceMode::Auto,
                        "templates" => SurfaceMode::Templates,
                        "cpu" => SurfaceMode::CpuMeshes,
                        _ => return Err(bad(&v)),
                    };
                }
                "--frames" => {
                    let v = value()?;
                    args.frames = Some(v.parse().map_err(|_| bad(&v))?);
                }
                "--fps" => {
                    let v = value()?;
                    args.fps = v.parse().map_err(|_| bad(&v))?;
                    if !(args.fps.is_finite() && args.fps > 0.0) {
                        return Err(bad(&v));
                    }
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
                         [--oit] [--surfaces auto|templates|cpu] [--near N] [--mid N] [--promote-at FRAME] \
                         [--screenshot out.png [--frames 120] [--size 1280x720] [--stir]] \
                         [--bench [--frames 600] [--fps 60]]"
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
    if let Err(e) = species_files_present() {
        eprintln!("aquarium: {e}");
        return ExitCode::FAILURE;
    }
    if args.bench {
        return match bench::run(
            args.school,
            args.frames.unwrap_or(600),
            args.fps,
            JellyfishSettings {
                // Headless, Auto would mean CPU meshes; the windowed app on a GPU that
                // can uses templates, so that is what the bench measures by default.
                surfaces: match args.surfaces {
                    SurfaceMode::Auto => SurfaceMode::Templates,
                    chosen => chosen,
                },
                detail: args.detail.clone(),
                ..scene::settings()
            },
            task_pools(),
        ) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("aquarium --bench: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if let Some(path) = &args.screenshot {
        return match picture(&args, path) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("aquarium: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let mut app = App::new();
    app.add_plugins((
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: Some(Window {
                    title: "bevy_jellyfish aquarium".into(),
                    ..default()
                }),
                ..default()
            })
            .set(task_pools()),
        AquariumPlugin {
            school: args.school,
            surfaces: args.surfaces,
            detail: args.detail.clone(),
        },
    ));
    if args.oit {
        app.insert_resource(camera::OrderIndependent);
    }
    #[cfg(feature = "editor")]
    app.add_plugins(ui::plugin);
    app.run();
    ExitCode::SUCCESS
}

/// Every core for the compute pool, where the plugin steps and meshes jellyfish in
/// parallel. Bevy's default keeps a quarter of the cores each for I/O and async tasks, at
/// least one each: on two cores that leaves the simulation one.
fn task_pools() -> TaskPoolPlugin {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut options = TaskPoolOptions::default();
    options.compute.min_threads = cores;
    TaskPoolPlugin {
        task_pool_options: options,
    }
}

/// Renders `args.frames` frames (default 120) offscreen and writes the last to `path`.
fn picture(args: &Args, path: &std::path::Path) -> Result<(), String> {
    let (width, height) = args.size;
    let school = args.school;
    let frames_to_render = args.frames.unwrap_or(120);
    let (stir, surfaces, detail) = (args.stir, args.surfaces, args.detail.clone());
    let (promote_at, oit) = (args.promote_at, args.oit);
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
        "{} frames at {width}x{height}, {count} jellyfish: {wall:.1} ms per frame (render \
         included), simulation {:.2} ms, meshing {:.2} ms per frame (CPU, summed over jellyfish)",
        frames_to_render,
        simulation / frames,
        meshing / frames,
    );
    if let Some(tank) = offscreen
        .world()
        .get_resource::<bevy_jellyfish::plugin::TankWater>()
    {
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

/// The species files the schools load: a missing one is said at once, with the path and
/// the fix, instead of an empty tank.
fn species_files_present() -> Result<(), String> {
    for (name, _) in school::SPECIES {
        common::find_species_file(name, "aquarium")?;
    }
    Ok(())
}
