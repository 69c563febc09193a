//! The headless aquarium benchmark: the schools swim, stir the tank's water and mesh as in
//! the windowed app, with no renderer, at a fixed frame rate (60 by default). It prints
//! what a frame costs.

use crate::school::School;
use crate::trace::FrameTrace;
use bevy::asset::{AssetPlugin, LoadState};
use bevy::camera::primitives::Frustum;
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::mesh::MeshPlugin;
use bevy::prelude::*;
use bevy::render::storage::ShaderBuffer;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::plugin::{CycleCaches, JellyfishMeshes, JellyfishSlice, SurfacePath};
use bevy_jellyfish::{
    Jellyfish, JellyfishDiagnostics, JellyfishPlugin, JellyfishSettings, Species,
};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// How long slices may take to start before the bench gives up, s.
const READY_TIMEOUT: Duration = Duration::from_secs(120);

/// How the bench runs.
pub struct Options {
    /// Frames measured, after the warm-up.
    pub frames: usize,
    /// Frames per second of simulated time.
    pub fps: f64,
    /// Jellyfish spawned at once after the run, then a species edited ([`crate::burst`]);
    /// none at 0.
    pub burst: usize,
    /// Each frame starts on its 1/fps tick ([`Pacer`]).
    pub paced: bool,
    /// Where to write every frame's figures ([`crate::trace`]).
    pub trace: Option<PathBuf>,
}

/// Runs `frames` frames at `fps` after a warm-up and prints wall and CPU time per frame,
/// the spread of frame times, and the mesh data handed to the renderer; then, with
/// `burst` above 0, spawns that many more at once and edits a species
/// ([`crate::burst`]). Errors if the schools never start (a species that does not load).
pub fn run(
    school: School,
    options: &Options,
    settings: JellyfishSettings,
    pools: TaskPoolPlugin,
) -> Result<(), String> {
    let Options {
        frames,
        fps,
        burst,
        paced,
        ..
    } = *options;
    let mut app = headless(fps, settings, pools, AssetPlugin::default());
    // (Held for the whole run, so the species are never dropped.)
    let _species = start_schools(&mut app, school)?;
    let start = Instant::now();
    let warm_up_frames = until_started(&mut app, school)?;
    println!(
        "ready: {} jellyfish started in {:.2} s ({warm_up_frames} frames)",
        school.per_species * crate::school::SPECIES.len(),
        start.elapsed().as_secs_f64()
    );
    for _ in 0..(fps as usize) {
        app.update();
    }
    let (mut simulation, mut meshing, mut mesh_data, mut water) = (0.0, 0.0, 0.0, 0.0);
    let mut tier_changes = 0.0;
    let mut tier_ms = [0.0; 3];
    let steps_before = steps(&mut app);
    let mut frame_ms = Vec::with_capacity(frames);
    let mut pacer = Pacer::new(fps, paced);
    let mut trace = (options.trace.as_deref()).map(|path| FrameTrace::new(path, &app));
    let start = Instant::now();
    for _ in 0..frames {
        pacer.wait();
        let frame = Instant::now();
        app.update();
        frame_ms.push(frame.elapsed().as_secs_f64() * 1e3);
        if let (Some(trace), Some(ms)) = (&mut trace, frame_ms.last()) {
            trace.record(&app, *ms);
        }
        let store = app.world().resource::<DiagnosticsStore>();
        simulation += value(store, &JellyfishDiagnostics::SIMULATION);
        meshing += value(store, &JellyfishDiagnostics::MESHING);
        mesh_data += value(store, &JellyfishDiagnostics::MESH_DATA);
        water += value(store, &JellyfishDiagnostics::WATER);
        tier_changes += value(store, &JellyfishDiagnostics::TIER_CHANGES);
        let tiers = [
            JellyfishDiagnostics::NEAR_MS,
            JellyfishDiagnostics::MID_MS,
            JellyfishDiagnostics::FAR_MS,
        ];
        for (sum, path) in tier_ms.iter_mut().zip(&tiers) {
            *sum += value(store, path);
        }
    }
    let n = frames.max(1) as f64;
    let jellyfish = count(&app).max(1.0);
    let store = app.world().resource::<DiagnosticsStore>();
    let tier = |p| value(store, &p) as usize;
    let (near, mid, far) = (
        tier(JellyfishDiagnostics::NEAR),
        tier(JellyfishDiagnostics::MID),
        tier(JellyfishDiagnostics::FAR),
    );
    let live = (near + mid).max(1);
    let steps_per_second = (steps(&mut app) - steps_before) as f64 / live as f64 / (n / fps);
    let wall = start.elapsed().as_secs_f64() * 1e3 / n;
    let threads = bevy::tasks::ComputeTaskPool::get().thread_num();
    println!(
        "headless aquarium: {} jellyfish, {fps} fps, {threads} threads, {steps_per_second:.1} \
         steps per live jellyfish-second, {frames} frames: {wall:.2} ms wall per frame; CPU per \
         frame: simulation {:.2} ms, meshing {:.2} ms ({:.3} ms per jellyfish)",
        count(&app),
        simulation / n,
        meshing / n,
        (simulation + meshing) / n / jellyfish,
    );
    frame_ms.sort_by(f64::total_cmp);
    let p99 = frame_ms[((frame_ms.len() as f64 * 0.99) as usize).min(frame_ms.len() - 1)];
    let mean = frame_ms.iter().sum::<f64>() / n;
    println!(
        "frame time: mean {mean:.2} ms, p99 {p99:.2} ms: {:.0}% and {:.0}% of a 1/{fps} s frame",
        100.0 * mean * fps / 1e3,
        100.0 * p99 * fps / 1e3,
    );
    let per = |ms: f64, count: usize| {
        if count == 0 {
            "-".to_string()
        } else {
            format!("{:.1} µs", 1e3 * ms / n / count as f64)
        }
    };
    println!(
        "CPU per jellyfish and frame, stepping and meshing: near {}, mid {}, far {}",
        per(tier_ms[0], near),
        per(tier_ms[1], mid),
        per(tier_ms[2], far),
    );
    println!(
        "tiers: near {near}, mid {mid}, far {far}; {:.2} changes per frame; recorded cycles {:.1} MB",
        tier_changes / n,
        app.world().resource::<CycleCaches>().bytes() as f64 * 1e-6,
    );
    let path = app.world().get_resource::<SurfacePath>().copied();
    println!("surfaces: {path:?}");
    let (seen, all) = seen(&mut app);
    println!("in view: {seen} of {all} meshed in the last frame");
    println!("mesh data: {:.2} MB changed per frame", mesh_data / n);
    println!("tank water: {:.2} ms of wall time per frame", water / n);
    println!("state hash: {:016x}", state_hash(&mut app));
    if let Some(trace) = trace {
        trace.finish()?;
    }
    if burst > 0 {
        crate::burst::edit(&mut app, p99, fps, &mut pacer)?;
        crate::burst::spawn(&mut app, burst, fps, &mut pacer)?;
    }
    Ok(())
}

/// Starts each frame on the next tick of 1/fps s, as a game held to its display does,
/// leaving the rest of the tick idle (work in the background may use it); or, unpaced,
/// frames back to back. Either way a frame's time is its update's own.
pub struct Pacer {
    period: Option<Duration>,
    next: Option<Instant>,
}

impl Pacer {
    pub fn new(fps: f64, paced: bool) -> Self {
        Self {
            period: paced.then(|| Duration::from_secs_f64(1.0 / fps)),
            next: None,
        }
    }

    /// Waits for the next tick (none unpaced; none if the last frame overran it).
    pub fn wait(&mut self) {
        let Some(period) = self.period else {
            return;
        };
        let now = Instant::now();
        let tick = self.next.map_or(now, |next| next.max(now));
        std::thread::sleep(tick - now);
        self.next = Some(tick + period);
    }
}

/// FNV-1a over every jellyfish's seed, tier, phase and pose, to the bit, in an order that
/// does not depend on how entities were allocated: the same for any thread count.
pub fn state_hash(app: &mut App) -> u64 {
    let mut q = app.world_mut().query::<(&JellyfishSlice, &Transform)>();
    let mut states: Vec<Vec<u32>> = q
        .iter(app.world())
        .map(|(slice, t)| {
            let mut bits = vec![slice.seed(), slice.tier() as u32];
            bits.push(slice.phase().map_or(u32::MAX, f32::to_bits));
            bits.extend(t.translation.to_array().map(f32::to_bits));
            bits.extend(t.rotation.to_array().map(f32::to_bits));
            bits
        })
        .collect();
    states.sort_unstable();
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for word in states.iter().flatten() {
        for byte in word.to_le_bytes() {
            hash = (hash ^ byte as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
    hash
}

/// The aquarium without a renderer: the plugin, the schools' steering and the tank's
/// water, `fps` frames a second of game time whatever the wall clock.
pub fn headless(
    fps: f64,
    settings: JellyfishSettings,
    pools: TaskPoolPlugin,
    assets: AssetPlugin,
) -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins.set(pools),
        assets,
        MeshPlugin,
        TransformPlugin,
        JellyfishPlugin { settings },
        crate::school::plugin,
    ))
    // No renderer here, so no storage buffers unless we ask: templates pack their shapes
    // into them as in the window (what reaches the GPU is what the bench counts).
    .init_asset::<ShaderBuffer>()
    .insert_resource(crate::water::tank_water())
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        1.0 / fps,
    )));
    spawn_camera(&mut app);
    app.finish();
    app.cleanup();
    app
}

/// Loads the species, then spawns the schools. The species load first, with the game's
/// clock paused: how many frames a file takes to load depends on the disk and the
/// threads, and a jellyfish's slice starts when its species is there, the schools'
/// steering reads the clock. Returns the species' handles, to be held.
pub fn start_schools(app: &mut App, school: School) -> Result<Vec<Handle<Species>>, String> {
    app.world_mut().resource_mut::<Time<Virtual>>().pause();
    let species = load_species(app)?;
    app.world_mut().resource_mut::<Time<Virtual>>().unpause();
    app.insert_resource(school);
    Ok(species)
}

/// Frames until every jellyfish of `school` has its slice; errors if they never do.
pub fn until_started(app: &mut App, school: School) -> Result<usize, String> {
    let expected = (school.per_species * crate::school::SPECIES.len()) as f64;
    // Slices start a few dozen a frame, and a frame of ten thousand jellyfish is long:
    // the wait grows with the school.
    let timeout = READY_TIMEOUT + Duration::from_secs_f64(0.04 * expected);
    let start = Instant::now();
    let mut frames = 0;
    while count(app) < expected {
        app.update();
        frames += 1;
        if let Some(error) = load_failure(app) {
            return Err(format!(
                "{error}; run it from the repository (`cargo run --release --features \
                 examples --example aquarium -- --bench`) or set BEVY_ASSET_ROOT to the folder \
                 holding assets/"
            ));
        }
        if start.elapsed() > timeout {
            return Err(format!(
                "only {} of {expected} jellyfish started in {} s: do the species files in \
                 {}/assets/species load?",
                count(app),
                timeout.as_secs(),
                std::env::current_dir().map_or("?".into(), |d| d.display().to_string()),
            ));
        }
    }
    Ok(frames)
}

/// A camera where the windowed app's starts, 16:9, with its frustum (no renderer here to
/// compute it), so the plugin culls as it would on screen.
fn spawn_camera(app: &mut App) {
    let transform = crate::camera::home().transform();
    let projection = Projection::Perspective(PerspectiveProjection {
        aspect_ratio: 16.0 / 9.0,
        ..default()
    });
    let frustum: Frustum = projection.compute_frustum(&GlobalTransform::from(transform));
    app.world_mut()
        .spawn((Camera3d::default(), projection, transform, frustum));
}

/// Loads the shipped species the schools use, frame by frame, until all have loaded.
fn load_species(app: &mut App) -> Result<Vec<Handle<Species>>, String> {
    let server = app.world().resource::<AssetServer>().clone();
    let handles: Vec<Handle<Species>> = crate::school::SPECIES
        .iter()
        .map(|name| server.load(format!("species/{name}.species.ron")))
        .collect();
    let start = Instant::now();
    loop {
        let states: Vec<_> = handles.iter().map(|h| server.get_load_state(h)).collect();
        if let Some(Some(LoadState::Failed(error))) = states
            .iter()
            .find(|s| matches!(s, Some(LoadState::Failed(_))))
        {
            return Err(format!(
                "a species did not load: {error}; run it from the repository (`cargo run \
                 --release --features examples --example aquarium -- --bench`) or set \
                 BEVY_ASSET_ROOT to the folder holding assets/"
            ));
        }
        if states.iter().all(|s| matches!(s, Some(LoadState::Loaded))) {
            return Ok(handles);
        }
        if start.elapsed() > READY_TIMEOUT {
            return Err(format!(
                "the species files did not load in {} s",
                READY_TIMEOUT.as_secs()
            ));
        }
        app.update();
    }
}

/// Why a jellyfish's species failed to load, if one did.
fn load_failure(app: &mut App) -> Option<String> {
    let mut jellyfish = app.world_mut().query::<&Jellyfish>();
    let server = app.world().resource::<AssetServer>();
    jellyfish
        .iter(app.world())
        .find_map(|j| match server.get_load_state(&j.species) {
            Some(LoadState::Failed(error)) => Some(format!("a species did not load: {error}")),
            _ => None,
        })
}

/// How many jellyfish the last frame meshed, of all with a slice.
fn seen(app: &mut App) -> (usize, usize) {
    let mut q = app
        .world_mut()
        .query::<(&JellyfishSlice, &JellyfishMeshes)>();
    let all: Vec<bool> = q
        .iter(app.world())
        .filter(|(s, _)| s.started())
        .map(|(_, m)| m.seen())
        .collect();
    (all.iter().filter(|s| **s).count(), all.len())
}

/// The latest value of a diagnostic, 0 before the first.
pub fn value(store: &DiagnosticsStore, path: &DiagnosticPath) -> f64 {
    store.get(path).and_then(|d| d.value()).unwrap_or(0.0)
}

pub fn count(app: &App) -> f64 {
    value(
        app.world().resource::<DiagnosticsStore>(),
        &JellyfishDiagnostics::COUNT,
    )
}

/// Coupled steps taken so far, summed over live slices.
fn steps(app: &mut App) -> u64 {
    let mut slices = app.world_mut().query::<&JellyfishSlice>();
    slices
        .iter(app.world())
        .filter_map(|s| s.sim().map(|sim| sim.steps()))
        .sum()
}
