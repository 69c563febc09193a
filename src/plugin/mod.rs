//! The ECS plugin: jellyfish as entities, slices stepped by the frame's virtual time,
//! meshes rebuilt every frame, species as hot-reloadable assets.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_jellyfish::{Jellyfish, JellyfishPlugin, Species};
//!
//! fn spawn(mut commands: Commands, assets: Res<AssetServer>) {
//!     let species: Handle<Species> = assets.load("species/aurelia.species.ron");
//!     commands.spawn((Jellyfish::new(species), Transform::from_xyz(0.0, 0.0, 0.0)));
//! }
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, JellyfishPlugin::default()))
//!     .add_systems(Startup, spawn)
//!     .run();
//! ```
//!
//! [`JellyfishPlugin`] adds [`JellyfishPlugins`], one plugin per concern, each in its own
//! module and each owning its state; data flows one way, from the species down to the
//! pictures:
//!
//! | plugin | what it does |
//! |---|---|
//! | [`JellyfishSchedulePlugin`] | the [`JellyfishSystems`] sets in order, the settings |
//! | [`SpeciesAssetPlugin`] | `*.species.ron` loaded and validated, [`SpeciesRejected`] |
//! | [`WaterPlugin`] | the [`AmbientWater`] every jellyfish swims in |
//! | [`SwimmingPlugin`] | travel: surge, current, vorticity, [`Steering`], [`Resting`] |
//! | [`InterpolationPlugin`] | the last steps kept, the `Transform` blended between them |
//! | [`SlicePlugin`] | slices created, edited, stepped; lifecycle events |
//! | [`TankWaterPlugin`] | a [`TankWater`] stepped and stirred by the jellyfish's jets |
//! | [`TouchPlugin`] | a [`Disturbance`] makes jellyfish [`Flash`] and escape; echoes |
//! | [`JellyfishRenderPlugin`] | surfaces rebuilt each frame (CPU meshes or templates), bounds |
//! | [`JellyfishMaterialPlugin`] | our two-layer material and its patterns |
//! | [`DetailPlugin`] | levels of detail ([`Tier`]) and the recorded cycles |
//! | [`JellyfishDiagnosticsPlugin`] | [`JellyfishDiagnostics`] each frame |
//!
//! A game leaves out what it does not want:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_jellyfish::plugin::{DetailPlugin, JellyfishPlugins, TankWaterPlugin};
//!
//! App::new().add_plugins((
//!     DefaultPlugins,
//!     JellyfishPlugins::default()
//!         .build()
//!         .disable::<DetailPlugin>()
//!         .disable::<TankWaterPlugin>(),
//! ));
//! ```
//!
//! The schedule, the species assets, swimming, interpolation and the slice are the core
//! every other part builds on; the rest may be left out.

#[cfg(feature = "debug")]
mod debug;
mod diagnostics;
mod interpolation;
mod jellyfish;
mod lod;
mod render;
mod schedule;
mod school;
mod settings;
mod slice;
mod species_asset;
mod swimming;
mod tank;
mod timings;
mod touch;
mod water;

#[cfg(feature = "debug")]
pub use debug::{JellyfishDebugPlugin, JellyfishGizmos, ShowSlice, TraceParticles};
pub use diagnostics::{JellyfishDiagnostics, JellyfishDiagnosticsPlugin};
pub use interpolation::InterpolationPlugin;
pub use jellyfish::Jellyfish;
pub use lod::{CycleCaches, DetailPlugin};
pub use render::{
    BellPatterns, CPU_MESH_TAG, FLASH_SPREAD, GLOW_RADIANCE, GLOW_SORT_AHEAD, JellyfishGeometry,
    JellyfishGlow, JellyfishMaterialPlugin, JellyfishMeshes, JellyfishParts, JellyfishRenderPlugin,
    JellyfishTentacles, PartOf, PatternImages, ShapeBuffers, SpeciesMaterials, SurfaceExtension,
    SurfaceMaterial, SurfacePath, TENTACLE_SORT_OFFSET, Tissue, WorldSurfaces, bell_material,
    glow_material, glow_tissue, tentacle_material, tentacle_material_at,
};
pub use schedule::{JellyfishSchedulePlugin, JellyfishSystems};
pub use school::{JellyfishSchool, MemberOf, SchoolMembers, SchoolPlugin};
pub use settings::{DetailLevels, JellyfishSettings, SurfaceMode};
pub use slice::{
    JellyfishSlice, JellyfishStarted, SlicePlugin, SliceRecovered, StrokeStarted, Tier,
};
pub use species_asset::{SpeciesAssetPlugin, SpeciesLoader, SpeciesRejected};
pub use swimming::{
    Pose, Resting, Steering, SteeringTarget, SwimMotion, SwimmingPlugin, TentacleGuides,
};
pub use tank::{STIR_FOR_A_FULL_TOUCH, TankWater, TankWaterPlugin};
pub use touch::{Disturbance, ECHO_SHARE, FLASH_RISE, Flash, TouchPlugin};
pub use water::{AmbientWater, SampledWater, WaterField, WaterPlugin};

use bevy::app::PluginGroupBuilder;
use bevy::prelude::*;

/// Every part of the plugin, in the order they build. `JellyfishPlugins::default()`
/// gives them all with default settings; `.build().disable::<…>()` leaves one out.
#[derive(Clone, Debug, Default)]
pub struct JellyfishPlugins {
    /// The settings inserted unless the app already has a `JellyfishSettings`.
    pub settings: JellyfishSettings,
}

impl PluginGroup for JellyfishPlugins {
    fn build(self) -> PluginGroupBuilder {
        PluginGroupBuilder::start::<Self>()
            .add(JellyfishSchedulePlugin {
                settings: self.settings,
            })
            .add(SpeciesAssetPlugin)
            .add(WaterPlugin)
            .add(SwimmingPlugin)
            .add(SchoolPlugin)
            .add(InterpolationPlugin)
            .add(SlicePlugin)
            .add(TankWaterPlugin)
            .add(TouchPlugin)
            .add(JellyfishRenderPlugin)
            .add(JellyfishMaterialPlugin)
            .add(DetailPlugin)
            .add(JellyfishDiagnosticsPlugin)
    }
}

/// Adds jellyfish to an app: all of [`JellyfishPlugins`] in one line. Settings live in
/// the [`JellyfishSettings`] resource; one the app already has is kept.
#[derive(Clone, Debug, Default)]
pub struct JellyfishPlugin {
    /// The settings inserted unless the app already has a `JellyfishSettings`.
    pub settings: JellyfishSettings,
}

impl Plugin for JellyfishPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(JellyfishPlugins {
            settings: self.settings.clone(),
        });
    }
}
