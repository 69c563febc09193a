//! The soak: the headless aquarium for a long while with everything a game does to it,
//! watching memory and the physics. Each simulated second about 5 % of the jellyfish are
//! despawned and as many spawned, a species is edited and the tank is stirred; every few
//! seconds a species file is rewritten, in turn valid and broken, and reloaded. It ends
//! with one line: `soak: <frames> frames, <n> jellyfish, rss <after warm-up> MB -> <end>
//! MB, non-finite <count>, recoveries <count>`, and fails if memory grew by more than
//! 10 % + 8 MB (soaks of two minutes or more), if anything went non-finite, or if the
//! last valid file did not apply.

use crate::school::{SCALE, SPECIES, School, water_box};
use bevy::asset::AssetPlugin;
use bevy::prelude::*;
use bevy_jellyfish::plugin::{JellyfishSlice, SliceRecovered, Steering, TankWater};
use bevy_jellyfish::{Jellyfish, JellyfishSettings, Species};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// Simulated frames per second.
const FPS: f64 = 60.0;
/// The share of the jellyfish replaced every second.
const CHURN: f64 = 0.05;
/// Seconds between two rewrites of the species file.
const REWRITE_EVERY: u64 = 3;
/// The file rewritten: its species is never edited in memory, so the last valid text is
/// what it must read at the end.
const REWRITTEN: &str = "sarsia";
/// Memory is measured after this share of the run (slices, caches and meshes built).
const WARM_UP: f64 = 0.1;
/// Shorter soaks are not judged on memory: replacing jellyfish raises the allocator's
/// high-water mark for the first minutes (measured: +20 MB over 300 s for 102 jellyfish,
/// flat after), which a short run would read as a leak.
const MEMORY_JUDGED_AFTER: f64 = 120.0;

/// Runs the soak for `seconds` of game time.
pub fn run(
    school: School,
    seconds: f64,
    settings: JellyfishSettings,
    pools: TaskPoolPlugin,
) -> Result<(), String> {
    let assets = AssetCopy::new()?;
    let mut app = crate::bench::headless(
        FPS,
        settings,
        pools,
        AssetPlugin {
            file_path: assets.root.display().to_string(),
            ..default()
        },
    );
    let recoveries = Arc::new(AtomicU64::new(0));
    let counted = recoveries.clone();
    app.add_observer(move |_: On<SliceRecovered>| {
        counted.fetch_add(1, Ordering::Relaxed);
    });
    let _species = crate::bench::start_schools(&mut app, school)?;
    crate::bench::until_started(&mut app, school)?;

    let mut rng = StdRng::seed_from_u64(u64::from(school.seed) ^ 0x50a4);
    let (total, warm_up) = ((seconds * FPS) as u64, (seconds * WARM_UP * FPS) as u64);
    let (mut non_finite, mut rss_start, mut last_valid) = (0u64, None, None);
    for frame in 1..=total {
        app.update();
        non_finite += count_non_finite(&mut app);
        if frame % FPS as u64 == 0 {
            let second = frame / FPS as u64;
            churn(&mut app, &mut rng);
            edit_species(&mut app, second);
            stir(&mut app, &mut rng);
            if second.is_multiple_of(REWRITE_EVERY) {
                let valid = (second / REWRITE_EVERY).is_multiple_of(2);
                let pulse = valid.then_some(1.3 + 0.01 * (second % 20) as f32);
                if let Some(text) = assets.rewrite(&mut app, pulse, second)? {
                    last_valid = Some(text);
                }
            }
        }
        if frame == warm_up.max(1) {
            rss_start = Some(rss_mb()?);
        }
    }
    // The last rewrite, valid and with a pulse no other has, then time to load it.
    last_valid = assets.rewrite(&mut app, Some(1.25), 0)?.or(last_valid);
    for _ in 0..2 * FPS as u64 {
        app.update();
    }
    let rss_end = rss_mb()?;
    let rss_start = rss_start.unwrap_or(rss_end);
    let jellyfish = app
        .world_mut()
        .query::<&JellyfishSlice>()
        .iter(app.world())
        .count();
    println!(
        "soak: {total} frames, {jellyfish} jellyfish, rss {rss_start:.0} MB -> {rss_end:.0} MB, \
         non-finite {non_finite}, recoveries {}",
        recoveries.load(Ordering::Relaxed)
    );
    if seconds >= MEMORY_JUDGED_AFTER && rss_end > rss_start * 1.1 + 8.0 {
        return Err(format!(
            "memory grew from {rss_start:.0} to {rss_end:.0} MB"
        ));
    }
    if non_finite > 0 {
        return Err(format!("{non_finite} non-finite transforms"));
    }
    let expected = last_valid.map(|text| Species::from_ron(&text)).transpose();
    let expected = expected.map_err(|e| format!("the soak's own valid file: {e}"))?;
    if let Some(expected) = expected
        && rewritten_species(&mut app).as_ref() != Some(&expected)
    {
        return Err(format!(
            "the last valid {REWRITTEN} file did not apply after it was rewritten"
        ));
    }
    Ok(())
}

/// The shipped species files, copied to a folder of the soak's own so that rewriting them
/// leaves the repository's untouched; removed at the end.
struct AssetCopy {
    root: PathBuf,
}

impl AssetCopy {
    fn new() -> Result<Self, String> {
        let root = std::env::temp_dir().join(format!("jellyfish-soak-{}", std::process::id()));
        let species = root.join("species");
        std::fs::create_dir_all(&species).map_err(|e| format!("{}: {e}", species.display()))?;
        for name in SPECIES {
            let from = crate::common::find_species_file(name, "aquarium")?;
            let to = species.join(format!("{name}.species.ron"));
            std::fs::copy(&from, &to).map_err(|e| format!("{}: {e}", to.display()))?;
        }
        Ok(Self { root })
    }

    fn path(&self) -> PathBuf {
        self.root.join(format!("species/{REWRITTEN}.species.ron"))
    }

    /// Rewrites the file (with `pulse`, the species pulsing at that frequency, Hz; else
    /// broken text, the kind chosen by `second`) and asks the asset server to reload it.
    /// Returns the text if valid.
    fn rewrite(
        &self,
        app: &mut App,
        pulse: Option<f32>,
        second: u64,
    ) -> Result<Option<String>, String> {
        let path = self.path();
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let written = match pulse {
            Some(hz) => {
                let mut species = Species::from_ron(&text).unwrap_or_else(|_| Species::sarsia());
                species.contraction_frequency = hz;
                Some(species.to_ron().map_err(|e| e.to_string())?)
            }
            None => None,
        };
        let out = written.clone().unwrap_or_else(|| broken(&text, second));
        std::fs::write(&path, &out).map_err(|e| format!("{}: {e}", path.display()))?;
        let server = app.world().resource::<AssetServer>();
        server.reload(Path::new("species").join(format!("{REWRITTEN}.species.ron")));
        Ok(written)
    }
}

impl Drop for AssetCopy {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

/// A broken species file: in turn cut short, a value out of range, a field unknown.
fn broken(text: &str, second: u64) -> String {
    match second % 3 {
        0 => text[..text.len() / 2].to_string(),
        1 => "(name: \"Sarsia\", diameter: -1.0)".to_string(),
        _ => "(name: \"Sarsia\", no_such_field: 1)".to_string(),
    }
}

/// Jellyfish whose transform is not finite, this frame.
fn count_non_finite(app: &mut App) -> u64 {
    app.world_mut()
        .query_filtered::<&Transform, With<Jellyfish>>()
        .iter(app.world())
        .filter(|t| !(t.translation.is_finite() && t.rotation.is_finite()))
        .count() as u64
}

/// Despawns about 5 % of the jellyfish and spawns as many, of random species and places,
/// heading up (newcomers swim on their own, outside the schools).
fn churn(app: &mut App, rng: &mut StdRng) {
    let mut swimmers: Vec<Entity> = app
        .world_mut()
        .query_filtered::<Entity, With<Jellyfish>>()
        .iter(app.world())
        .collect();
    swimmers.sort_unstable();
    let replaced = ((swimmers.len() as f64 * CHURN).round() as usize).max(1);
    for _ in 0..replaced.min(swimmers.len()) {
        let k = rng.random_range(0..swimmers.len());
        app.world_mut().despawn(swimmers.swap_remove(k));
    }
    let server = app.world().resource::<AssetServer>().clone();
    for _ in 0..replaced {
        let name = SPECIES[rng.random_range(0..SPECIES.len())];
        let species: Handle<Species> = server.load(format!("species/{name}.species.ron"));
        let at = somewhere(rng);
        app.world_mut().spawn((
            Jellyfish::new(species).with_seed(rng.random()),
            Steering::heading(Vec3::Y),
            Transform::from_translation(at).with_scale(Vec3::splat(SCALE)),
        ));
    }
}

/// Edits one species in memory, as the editor does: the moon jelly and the crystal jelly in
/// turn, their stroke's depth nudged and back.
fn edit_species(app: &mut App, second: u64) {
    let name = ["aurelia", "aequorea"][(second % 2) as usize];
    let server = app.world().resource::<AssetServer>().clone();
    let handle: Handle<Species> = server.load(format!("species/{name}.species.ron"));
    let mut assets = app.world_mut().resource_mut::<Assets<Species>>();
    if let Some(mut species) = assets.get_mut(&handle) {
        let nudge = if (second / 2).is_multiple_of(2) {
            0.02
        } else {
            -0.02
        };
        species.contraction_ratio = (species.contraction_ratio + nudge).clamp(0.4, 0.9);
    }
}

/// A random place in the schools' water.
fn somewhere(rng: &mut StdRng) -> Vec3 {
    let (centre, half) = water_box();
    centre + Vec3::from_array(rng.random::<[f32; 3]>().map(|u| 2.0 * u - 1.0)) * half
}

/// A stir somewhere in the tank.
fn stir(app: &mut App, rng: &mut StdRng) {
    let at = somewhere(rng);
    let velocity = Vec3::from_array(rng.random::<[f32; 3]>()) * 2.0 - 1.0;
    app.world_mut()
        .resource_mut::<TankWater>()
        .stir(at, crate::water::STIR_RADIUS, velocity);
}

/// The species the rewritten file holds now, as loaded.
fn rewritten_species(app: &mut App) -> Option<Species> {
    let server = app.world().resource::<AssetServer>().clone();
    let handle: Handle<Species> = server.load(format!("species/{REWRITTEN}.species.ron"));
    app.world()
        .resource::<Assets<Species>>()
        .get(&handle)
        .cloned()
}

/// This process's resident memory, MB (Linux: `/proc/self/statm`).
fn rss_mb() -> Result<f64, String> {
    let statm = std::fs::read_to_string("/proc/self/statm")
        .map_err(|e| format!("resident memory (Linux only, /proc/self/statm): {e}"))?;
    let pages: f64 = statm
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .ok_or("resident memory: /proc/self/statm unreadable")?;
    Ok(pages * 4096.0 / 1e6)
}
