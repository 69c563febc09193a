//! The bench's bursts, after its steady run: a species edited so that its stroke is
//! recorded again, measured against the steady run's p99; then a crowd spawned at once,
//! measured against the p99 of the crowd settled. A game must not feel either.

use crate::bench::{Pacer, count, value};
use crate::school::{SCALE, SPECIES, water_box};
use bevy::prelude::*;
use bevy_jellyfish::plugin::{CycleCaches, JellyfishSchool};
use bevy_jellyfish::{JellyfishDiagnostics, Species};
use std::time::Instant;

/// Frames measured after each burst has settled, beyond its own start.
const SETTLE_SECONDS: f64 = 2.0;

/// Spawns `crowd` more jellyfish at once (a school of each species), frames until every
/// one has started, then `SETTLE_SECONDS` to settle and as long again as the crowd's own
/// steady state, and prints the start against that state's p99.
pub fn spawn(app: &mut App, crowd: usize, fps: f64, pacer: &mut Pacer) -> Result<(), String> {
    let before = count(app);
    let per_species = crowd.div_ceil(SPECIES.len());
    let server = app.world().resource::<AssetServer>().clone();
    let (centre, half) = water_box();
    for (k, name) in SPECIES.iter().enumerate() {
        let species: Handle<Species> = server.load(format!("species/{name}.species.ron"));
        app.world_mut().spawn((
            JellyfishSchool {
                scale: SCALE,
                ..JellyfishSchool::new(species, per_species, half).with_seed(7919 + k as u64)
            },
            Transform::from_translation(centre),
        ));
    }
    let expected = before + (per_species * SPECIES.len()) as f64;
    let mut start = Frames::default();
    while count(app) < expected {
        start.update(app, pacer);
        if start.ms.len() > 100 * settle(fps) {
            return Err(format!("{} of {expected} jellyfish started", count(app)));
        }
    }
    let mut settled = Frames::default();
    for _ in 0..2 * settle(fps) {
        settled.update(app, pacer);
    }
    let steady = Frames {
        ms: settled.ms.split_off(settle(fps)),
        mesh_mb: settled.mesh_mb.split_off(settle(fps)),
        cpu: settled.cpu.split_off(settle(fps)),
        tiers: settled.tiers.split_off(settle(fps)),
    };
    let p99 = steady.p99();
    steady.print(&format!("burst, the {expected} settled"), p99);
    start.print(
        &format!(
            "burst: {} spawned at once, until all started",
            per_species * SPECIES.len(),
        ),
        p99,
    );
    settled.print("burst, the next seconds", p99);
    Ok(())
}

/// Edits a species' muscle as the editor would, so that its stroke is recorded again (in
/// the background) and its live slices take the new muscle; frames until the new cycle
/// is in use and `SETTLE_SECONDS` more, printed against `p99` (ms).
pub fn edit(app: &mut App, p99: f64, fps: f64, pacer: &mut Pacer) -> Result<(), String> {
    let server = app.world().resource::<AssetServer>().clone();
    let handle: Handle<Species> = server.load("species/aequorea.species.ron");
    let recording = |app: &App| app.world().resource::<CycleCaches>().recording();
    {
        let mut assets = app.world_mut().resource_mut::<Assets<Species>>();
        let mut species = assets
            .get_mut(&handle)
            .ok_or("the crystal jelly is not loaded")?;
        species.muscle_modulus *= 1.05;
    }
    let mut frames = Frames::default();
    let (mut began, mut recorded_at) = (false, None);
    while recorded_at.is_none() || frames.ms.len() < recorded_at.unwrap_or(0) + settle(fps) {
        frames.update(app, pacer);
        began |= recording(app);
        if began && recorded_at.is_none() && !recording(app) {
            recorded_at = Some(frames.ms.len());
        }
        if frames.ms.len() > 100 * settle(fps) {
            return Err("the edited species' stroke was never recorded again".into());
        }
    }
    frames.print(
        &format!(
            "edit: the crystal jelly's muscle 5 % stronger, its stroke recorded again in {} \
             frames",
            recorded_at.unwrap_or(0)
        ),
        p99,
    );
    // Collected in the frame before `recorded_at`; in use from then on.
    if let Some(at) = recorded_at {
        for at in at.saturating_sub(1)..=at + 1 {
            println!("edit: the new cycle, {}", frames.frame(at));
        }
    }
    println!(
        "state hash after the edit: {:016x}",
        crate::bench::state_hash(app)
    );
    Ok(())
}

fn settle(fps: f64) -> usize {
    (SETTLE_SECONDS * fps) as usize
}

/// Each frame's wall time and mesh data, and the worst frame's CPU.
#[derive(Default)]
struct Frames {
    ms: Vec<f64>,
    mesh_mb: Vec<f64>,
    /// Simulation and meshing CPU (ms) and tier changes of each frame.
    cpu: Vec<[f64; 3]>,
    /// The near, mid and far tiers' CPU (ms) of each frame.
    tiers: Vec<[f64; 3]>,
}

impl Frames {
    fn update(&mut self, app: &mut App, pacer: &mut Pacer) {
        pacer.wait();
        let start = Instant::now();
        app.update();
        self.ms.push(start.elapsed().as_secs_f64() * 1e3);
        let store = app.world().resource::<bevy::diagnostic::DiagnosticsStore>();
        self.mesh_mb
            .push(value(store, &JellyfishDiagnostics::MESH_DATA));
        self.cpu.push([
            value(store, &JellyfishDiagnostics::SIMULATION),
            value(store, &JellyfishDiagnostics::MESHING),
            value(store, &JellyfishDiagnostics::TIER_CHANGES),
        ]);
        self.tiers.push([
            value(store, &JellyfishDiagnostics::NEAR_MS),
            value(store, &JellyfishDiagnostics::MID_MS),
            value(store, &JellyfishDiagnostics::FAR_MS),
        ]);
    }

    /// Frame `at`'s wall time and where its CPU went, as a line's clause.
    fn frame(&self, at: usize) -> String {
        let ms = self.ms.get(at).copied().unwrap_or_default();
        let [simulation, meshing, changes] = self.cpu.get(at).copied().unwrap_or_default();
        let [near, mid, far] = self.tiers.get(at).copied().unwrap_or_default();
        format!(
            "frame {at}: {ms:.2} ms; CPU simulation {simulation:.1} ms, meshing {meshing:.1} \
             ms (near {near:.1}, mid {mid:.1}, far {far:.1}), {changes} tier changes"
        )
    }

    fn p99(&self) -> f64 {
        let mut sorted = self.ms.clone();
        sorted.sort_by(f64::total_cmp);
        sorted[((sorted.len() as f64 * 0.99) as usize).min(sorted.len() - 1)]
    }

    fn print(&self, what: &str, p99: f64) {
        let (at, worst) = self
            .ms
            .iter()
            .copied()
            .enumerate()
            .fold((0, 0.0), |w, (i, ms)| if ms > w.1 { (i, ms) } else { w });
        let over = self.ms.iter().filter(|&&ms| ms > p99).count();
        let mean = self.ms.iter().sum::<f64>() / self.ms.len().max(1) as f64;
        let data = self.mesh_mb.iter().copied().fold(0.0, f64::max);
        // Where an edit or a spawn lands: its own frame, and the ones just after.
        let first: Vec<String> = self
            .ms
            .iter()
            .take(3)
            .map(|ms| format!("{ms:.2}"))
            .collect();
        println!(
            "{what}: {} frames, mean {mean:.2} ms, worst {worst:.2} ms ({}), frames 0-2 {} \
             ms, {over} over the p99 ({p99:.2} ms){}; at most {data:.2} MB of mesh data in a \
             frame",
            self.ms.len(),
            self.frame(at),
            first.join(", "),
            runs(self.ms.iter().map(|&ms| ms > p99)),
        );
    }
}

/// The frames where `over` holds, as runs (" at frames 3, 17-20"): where a burst's cost
/// falls tells what it is.
fn runs(over: impl Iterator<Item = bool>) -> String {
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for (i, _) in over.enumerate().filter(|(_, o)| *o) {
        match runs.last_mut() {
            Some((_, end)) if *end + 1 == i => *end = i,
            _ => runs.push((i, i)),
        }
    }
    if runs.is_empty() {
        return String::new();
    }
    let runs: Vec<String> = runs
        .iter()
        .map(|&(a, b)| {
            if a == b {
                a.to_string()
            } else {
                format!("{a}-{b}")
            }
        })
        .collect();
    format!(" at frames {}", runs.join(", "))
}
