//! The aquarium: schools of three species of jellyfish in a lit tank.
//!
//! `cargo run --release --features examples --example aquarium -- --count 4`
//! (`-- --help` lists every flag).
//!
//! Left drag orbits, right drag pans, scroll zooms, Shift + left drag stirs the water,
//! Ctrl + left click touches a jellyfish (it flashes, if its species luminesces, and escapes).
//! Panels (the `editor` feature, part of `examples`) edit each species live, change the
//! school size and show the frame rate, jellyfish count and the plugin's simulation and
//! meshing time; every few seconds the log prints the same numbers.
//!
//! `--oit` draws the translucent bells with Bevy's order-independent transparency
//! (MSAA off): overlapping bells blend in the right order wherever they cross, at some
//! cost in GPU memory and time; without it they are sorted by their bounding-box centres.
//!
//! Offscreen, without a window (Mesa's software Vulkan will do), `--screenshot` renders
//! `--frames` frames at 60 simulated frames per second, writes the last one and exits:
//! `cargo run --release --features examples --example aquarium -- --screenshot out.png
//! --frames 120 --size 1280x720`.
//!
//! The headless benchmark, no renderer at all, prints the wall and CPU time of a frame,
//! the spread of frame times and the mesh data handed to the renderer:
//! `cargo run --release --features examples --example aquarium -- --bench --count 100
//! --frames 600 --fps 60`. It ends with a hash of every jellyfish's pose, phase and tier:
//! with `--threads N` (N threads in the compute pool), the same for any N. With `--burst
//! 1000` it then spawns a thousand more at once and edits a species, and prints those
//! frames against the run's p99. With `--paced` each frame starts on its 1/fps tick, as
//! in a game held to its display, instead of back to back. With `--frame-trace FILE` it
//! writes every frame's wall time, fixed ticks and the plugin's figures to a CSV, and
//! sums the frames up by their fixed ticks (what a slow frame was made of).
//!
//! The soak, `-- --soak SECONDS --count 334`: the same for longer, with churn (jellyfish
//! despawned and spawned, species edited, a species file rewritten valid and broken, the
//! tank stirred), ending with one line of memory and failures.

mod bench;
mod burst;
mod camera;
#[path = "../common/species.rs"]
mod common;
mod picture;
mod scene;
mod school;
#[path = "../common/offscreen.rs"]
mod screenshot;
mod snow;
mod soak;
mod stats;
mod tank;
mod trace;
#[cfg(feature = "editor")]
mod ui;
mod water;

use argh::FromArgs;
use bevy::prelude::*;
use bevy_jellyfish::JellyfishSettings;
use bevy_jellyfish::plugin::{DetailLevels, SurfaceMode};
use scene::AquariumPlugin;
use school::School;
use std::path::PathBuf;
use std::process::ExitCode;

/// Schools of three species of jellyfish in a lit tank: in a window, rendered offscreen to
/// a picture (--screenshot) or benchmarked headless (--bench).
#[derive(FromArgs)]
struct Args {
    /// jellyfish of each species (default 100)
    #[argh(option, default = "100")]
    count: usize,
    /// the seed that places the schools (default 1)
    #[argh(option, default = "1")]
    seed: u32,
    /// order-independent transparency for the bells (MSAA off)
    #[argh(switch)]
    oit: bool,
    /// where surfaces are built: auto, templates (on the GPU; the bench packs them without
    /// one) or cpu (default auto)
    #[argh(option, default = "SurfaceMode::Auto", from_str_fn(surfaces))]
    surfaces: SurfaceMode,
    /// at most this many jellyfish near, simulated live (default 100)
    #[argh(option, default = "DetailLevels::default().near")]
    near: usize,
    /// at most this many jellyfish mid, live in a compact box (default 24)
    #[argh(option, default = "DetailLevels::default().mid")]
    mid: usize,
    /// offscreen: from this frame on every jellyfish is near (a picture of a transition)
    #[argh(option)]
    promote_at: Option<u32>,
    /// render offscreen, without a window, and write the last frame to this PNG
    #[argh(option)]
    screenshot: Option<PathBuf>,
    /// frames to render (default 120) or to benchmark (default 600)
    #[argh(option)]
    frames: Option<usize>,
    /// offscreen picture size, WIDTHxHEIGHT (default 1280x720)
    #[argh(option, default = "(1280, 720)", from_str_fn(size))]
    size: (u32, u32),
    /// offscreen: a scripted stir across the middle of the tank two seconds in
    #[argh(switch)]
    stir: bool,
    /// the headless benchmark: no renderer, prints what a frame costs
    #[argh(switch)]
    bench: bool,
    /// the benchmark, after its run: spawn this many more jellyfish at once, then edit a
    /// species so its stroke is recorded again, each measured against the run's p99
    #[argh(option, default = "0")]
    burst: usize,
    /// the benchmark: start each frame on its 1/fps tick, as a game held to its display
    /// does, instead of back to back (frame times are still the update's own)
    #[argh(switch)]
    paced: bool,
    /// the benchmark: write every measured frame's wall time, fixed ticks and the plugin's
    /// CPU figures to this CSV file, and sum the frames up by their fixed ticks
    #[argh(option)]
    frame_trace: Option<PathBuf>,
    /// benchmark frames per second (default 60)
    #[argh(option, default = "60.0", from_str_fn(fps))]
    fps: f64,
    /// the soak: this many seconds of the headless aquarium with jellyfish despawned and
    /// spawned, species edited and files rewritten, the tank stirred; prints memory and
    /// failures in one line
    #[argh(option)]
    soak: Option<f64>,
    /// threads in Bevy's compute pool, where jellyfish are stepped and meshed (default:
    /// every core)
    #[argh(option, from_str_fn(threads))]
    threads: Option<usize>,
}

impl Args {
    fn school(&self) -> School {
        School {
            per_species: self.count,
            seed: self.seed,
        }
    }

    /// The settings of the headless runs (bench and soak). Headless, `Auto` would mean CPU
    /// meshes; the windowed app on a GPU that can uses templates, so that is what they
    /// run by default.
    fn headless(&self) -> JellyfishSettings {
        JellyfishSettings {
            surfaces: match self.surfaces {
                SurfaceMode::Auto => SurfaceMode::Templates,
                chosen => chosen,
            },
            detail: self.detail(),
            ..scene::settings()
        }
    }

    fn detail(&self) -> DetailLevels {
        DetailLevels {
            near: self.near,
            mid: self.mid,
            ..default()
        }
    }
}

fn surfaces(value: &str) -> Result<SurfaceMode, String> {
    match value {
        "auto" => Ok(SurfaceMode::Auto),
        "templates" => Ok(SurfaceMode::Templates),
        "cpu" => Ok(SurfaceMode::CpuMeshes),
        _ => Err("expected auto, templates or cpu".into()),
    }
}

fn size(value: &str) -> Result<(u32, u32), String> {
    let reason = || "expected WIDTHxHEIGHT in pixels, both above 0, e.g. 1280x720".to_string();
    let (w, h) = value.split_once('x').ok_or_else(reason)?;
    match (w.parse(), h.parse()) {
        (Ok(w), Ok(h)) if w > 0 && h > 0 => Ok((w, h)),
        _ => Err(reason()),
    }
}

fn threads(value: &str) -> Result<usize, String> {
    match value.parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        Ok(_) => Err("threads must be at least 1".into()),
        Err(e) => Err(e.to_string()),
    }
}

fn fps(value: &str) -> Result<f64, String> {
    match value.parse::<f64>() {
        Ok(fps) if fps.is_finite() && fps > 0.0 => Ok(fps),
        Ok(_) => Err("frames per second must be finite and above 0".into()),
        Err(e) => Err(e.to_string()),
    }
}

fn main() -> ExitCode {
    let args: Args = argh::from_env();
    if let Err(e) = species_files_present() {
        eprintln!("aquarium: {e}");
        return ExitCode::FAILURE;
    }
    let result = if let Some(seconds) = args.soak {
        soak::run(
            args.school(),
            seconds,
            args.headless(),
            task_pools(args.threads),
        )
        .map_err(|e| format!("aquarium --soak: {e}"))
    } else if args.bench {
        let options = bench::Options {
            frames: args.frames.unwrap_or(600),
            fps: args.fps,
            burst: args.burst,
            paced: args.paced,
            trace: args.frame_trace.clone(),
        };
        bench::run(
            args.school(),
            &options,
            args.headless(),
            task_pools(args.threads),
        )
        .map_err(|e| format!("aquarium --bench: {e}"))
    } else if let Some(path) = &args.screenshot {
        picture::render(&args, path).map_err(|e| format!("aquarium: {e}"))
    } else {
        window(&args);
        Ok(())
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}

/// The aquarium in a window, with the panels.
fn window(args: &Args) {
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
            .set(task_pools(args.threads)),
        AquariumPlugin {
            school: args.school(),
            surfaces: args.surfaces,
            detail: args.detail(),
        },
    ));
    if args.oit {
        app.insert_resource(camera::OrderIndependent);
    }
    #[cfg(feature = "editor")]
    app.add_plugins(ui::plugin);
    app.run();
}

/// Every core for the compute pool, where the plugin steps and meshes jellyfish in
/// parallel (Bevy's default keeps a quarter of the cores each for I/O and async tasks, at
/// least one each: on two cores that leaves the simulation one); or exactly `threads`
/// there.
fn task_pools(threads: Option<usize>) -> TaskPoolPlugin {
    let mut options = TaskPoolOptions::default();
    match threads {
        Some(n) => {
            options.compute.min_threads = n;
            options.compute.max_threads = n;
        }
        None => {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            options.compute.min_threads = cores;
        }
    }
    TaskPoolPlugin {
        task_pool_options: options,
    }
}

/// The species files the schools load: a missing one is said at once, with the path and
/// the fix, instead of an empty tank.
fn species_files_present() -> Result<(), String> {
    for name in school::SPECIES {
        common::find_species_file(name, "aquarium")?;
    }
    Ok(())
}
