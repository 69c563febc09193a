//! A headless app with the plugin: `MinimalPlugins`, assets, meshes, transforms, and a
//! clock that advances a fixed step per update, so tests replay exactly.

use bevy::asset::AssetPlugin;
use bevy::mesh::MeshPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::{JellyfishPlugin, JellyfishSettings};
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
        let mut app = App::new();
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
