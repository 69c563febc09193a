//! The whole aquarium as one plugin, shared by the windowed app, offscreen pictures and
//! the render test.

use crate::school::School;
use bevy::prelude::*;
use bevy_jellyfish::plugin::{DetailLevels, SurfaceMode};
use bevy_jellyfish::{JellyfishPlugin, JellyfishSettings};

pub struct AquariumPlugin {
    pub school: School,
    /// Where surfaces are built (`--surfaces`).
    pub surfaces: SurfaceMode,
    /// How many are near and mid (`--near`, `--mid`).
    pub detail: DetailLevels,
}

impl Plugin for AquariumPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(JellyfishPlugin {
            settings: JellyfishSettings {
                surfaces: self.surfaces,
                detail: self.detail.clone(),
                ..settings()
            },
        })
        .insert_resource(self.school)
        .add_plugins((
            crate::tank::plugin,
            crate::snow::plugin,
            crate::school::plugin,
            crate::camera::plugin,
            crate::stats::plugin,
            crate::water::plugin,
        ));
    }
}

/// The aquarium's drawing settings: the physics is each species' own.
pub fn settings() -> JellyfishSettings {
    JellyfishSettings::default()
}
