//! A headless app with the plugin: `MinimalPlugins`, assets, meshes, transforms, and a
//! clock that advances a fixed step per update, so tests replay exactly.

use bevy::asset::AssetPlugin;
use bevy::mesh::MeshPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::{Jellyfish, JellyfishPlugin, JellyfishSettings, Species};
use std::time::Duration;

/// How to build the app; `Headless::default()` is 60 Hz with light meshes.
pub struct Headless {
    pub assets: AssetPlugin,
    pub settings: JellyfishSettings,
    /// Virtual time per `app.update()`.
    pub frame: Duration,
}

impl Default for Headless {
    fn default() -> Self {
        Self {
            assets: AssetPlugin::default(),
            settings: JellyfishSettings {
                mesh_resolution_scale: 0.25,
                ..default()
            },
            frame: Duration::from_secs_f64(1.0 / 60.0),
        }
    }
}

impl Headless {
    /// The finished app; `extra` adds what a test needs before plugins finish.
    pub fn build(self, extra: impl FnOnce(&mut App)) -> App {
        self.build_on(App::new(), extra)
    }

    /// [`Self::build`] on `app`, which may hold what must come before the plugins (an
    /// asset source).
    pub fn build_on(self, mut app: App, extra: impl FnOnce(&mut App)) -> App {
        app.add_plugins((
            MinimalPlugins,
            self.assets,
            MeshPlugin,
            TransformPlugin,
            JellyfishPlugin {
                settings: self.settings,
            },
        ))
        .insert_resource(TimeUpdateStrategy::ManualDuration(self.frame));
        extra(&mut app);
        app.finish();
        app.cleanup();
        app
    }
}

/// The pairs of systems in `world`'s schedules that touch the same data in an order left
/// to the executor, where either is the plugin's or its data is (Bevy's own ambiguities
/// are Bevy's): one line each, with the data they share. Such a pair runs one way or the
/// other as the threads happen to finish, so what it decides (the frame an edit or a new
/// material shows, a part placed with last frame's transform) depends on the machine's
/// load. Builds each schedule not yet built, as its first run would, but those `skip`
/// names (as their labels print).
pub fn ambiguities_of_ours(world: &mut World, skip: &[&str]) -> Vec<String> {
    use bevy::ecs::schedule::{
        LogLevel, ScheduleBuildError, ScheduleBuildSettings, ScheduleBuildWarning, Schedules,
    };
    let Some(mut schedules) = world.remove_resource::<Schedules>() else {
        return Vec::new();
    };
    // A schedule's build reads the ignored ambiguities from the world's `Schedules`.
    let mut stand_in = Schedules::default();
    stand_in.ignored_scheduling_ambiguities = schedules.ignored_scheduling_ambiguities.clone();
    world.insert_resource(stand_in);
    let mut found = Vec::new();
    for (label, schedule) in schedules.iter_mut() {
        if skip.contains(&format!("{label:?}").as_str()) {
            continue;
        }
        let before = schedule.get_build_settings();
        schedule.set_build_settings(ScheduleBuildSettings {
            ambiguity_detection: LogLevel::Error,
            use_shortnames: false,
            report_sets: false,
            ..before.clone()
        });
        if let Err(error) = schedule.initialize(world) {
            let report = error.to_string(schedule.graph(), world);
            if !matches!(
                error,
                ScheduleBuildError::Elevated(ScheduleBuildWarning::Ambiguity(_))
            ) {
                // Not built for another reason (a cycle): that is a finding too.
                found.push(format!("{label:?}: {report}"));
            }
            found.extend(
                report
                    .split("\n -- ")
                    .skip(1)
                    .filter(|pair| pair.contains("bevy_jellyfish"))
                    .map(|pair| {
                        format!(
                            "{label:?}: {}",
                            pair.split_whitespace().collect::<Vec<_>>().join(" ")
                        )
                    }),
            );
        }
        schedule.set_build_settings(before);
    }
    world.insert_resource(schedules);
    found
}

/// World units per metre: the aquarium's scale (a 40 mm bell is 1.2 units across).
pub const SCALE: f32 = 30.0;

/// Spawns `species` at `at` with `extra` components, at phase 0 and seed 3, at the
/// aquarium's scale: one jellyfish as the plugin tests place it.
pub fn spawn(app: &mut App, species: &Species, at: Vec3, extra: impl Bundle) -> Entity {
    let h = app
        .world_mut()
        .resource_mut::<Assets<Species>>()
        .add(species.clone());
    app.world_mut()
        .spawn((
            Jellyfish::new(h).with_phase(0.0).with_seed(3),
            Transform::from_translation(at).with_scale(Vec3::splat(SCALE)),
            extra,
        ))
        .id()
}
