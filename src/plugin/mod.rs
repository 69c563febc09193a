//! The ECS plugin: jellyfish as entities, slices stepped at a fixed rate, meshes rebuilt
//! every frame, species as hot-reloadable assets.
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
//! Order of a frame, in [`JellyfishSystems`]: `Prepare` (PreUpdate) creates slices,
//! applies species edits and chooses each jellyfish's level of detail ([`Tier`]);
//! `StepSlices` (PostUpdate) steps them by the frame's virtual time; `WriteTransforms` and
//! `RebuildMeshes` (PostUpdate) blend the last two steps into the frame. The tank's water
//! ([`TankWater`]) steps on the app's fixed ticks.

mod asset;
mod components;
mod culling;
mod detail;
mod diagnostics;
mod events;
mod geometry;
mod material;
mod meshing;
mod motion;
mod pattern;
mod prepare;
mod settings;
mod steering;
mod step;
mod surface;
mod tank;
mod water;

pub use asset::{SpeciesLoader, SpeciesRejected};
pub use components::{
    Jellyfish, JellyfishGlow, JellyfishMeshes, JellyfishSlice, JellyfishTentacles, Pose, Resting,
    SwimMotion,
};
pub use detail::{CycleCaches, DetailLevels, Tier, tier_species};
pub use diagnostics::JellyfishDiagnostics;
pub use events::{JellyfishStarted, SliceRecovered, StrokeStarted};
pub use geometry::{JellyfishGeometry, WorldSurfaces};
pub use material::{
    GLOW_RADIANCE, JellyfishMaterials, SpeciesMaterials, bell_material, glow_material,
    tentacle_material,
};
pub use pattern::{BellPatterns, PatternImages, pattern_images};
pub use prepare::NEW_SLICES_PER_FRAME;
pub use settings::{JellyfishSettings, SurfaceMode};
pub use steering::{Steering, SteeringTarget};
pub use surface::{
    ShapeBuffers, SurfaceExtension, SurfaceMaterial, SurfaceMaterials, SurfacePath,
    device_supports_templates,
};
pub use tank::{Impulse, TankWater};
pub use water::{AmbientWater, SampledWater, WaterField};

use bevy::asset::{AssetEventSystems, AssetTrackingSystems};
use bevy::prelude::*;
use bevy::transform::TransformSystems;

/// Adds jellyfish to an app. Settings live in the [`JellyfishSettings`] resource; one the
/// app already has is kept.
#[derive(Clone, Debug, Default)]
pub struct JellyfishPlugin {
    /// The settings inserted unless the app already has a `JellyfishSettings`.
    pub settings: JellyfishSettings,
}

/// The plugin's systems, in the order they run within a frame. Order your own systems
/// against these (e.g. steering before `StepSlices`, reading meshes after `RebuildMeshes`).
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JellyfishSystems {
    /// PreUpdate: create slices for new jellyfish, apply species and settings edits,
    /// choose levels of detail.
    Prepare,
    /// PostUpdate: step the slices by the frame's virtual time, in parallel over jellyfish.
    StepSlices,
    /// PostUpdate: move each jellyfish along its axis, blended between fixed steps.
    WriteTransforms,
    /// PostUpdate: rebuild meshes in place, before bounds and render extraction.
    RebuildMeshes,
}

impl Plugin for JellyfishPlugin {
    fn build(&self, app: &mut App) {
        if !app.world().contains_resource::<JellyfishSettings>() {
            app.insert_resource(self.settings.clone());
        }
        app.register_type::<JellyfishSettings>()
            .register_type::<Jellyfish>()
            .register_type::<Steering>()
            .register_type::<Resting>()
            .register_type::<JellyfishSlice>()
            .register_type::<JellyfishTentacles>()
            .register_type::<JellyfishGlow>()
            .register_type::<SwimMotion>()
            .register_type::<AmbientWater>()
            .register_type::<TankWater>()
            .register_type::<ShapeBuffers>()
            .register_type::<SurfacePath>()
            .register_type::<JellyfishMeshes>()
            .register_type::<JellyfishStarted>()
            .register_type::<StrokeStarted>()
            .register_type::<SliceRecovered>()
            .add_plugins((
                asset::plugin,
                diagnostics::plugin,
                material::plugin,
                pattern::plugin,
                prepare::plugin,
                detail::plugin,
                step::plugin,
                motion::plugin,
                meshing::plugin,
                surface::plugin,
            ))
            .configure_sets(
                PreUpdate,
                JellyfishSystems::Prepare.after(AssetTrackingSystems),
            )
            .configure_sets(
                PostUpdate,
                (
                    JellyfishSystems::StepSlices,
                    JellyfishSystems::WriteTransforms,
                    JellyfishSystems::RebuildMeshes,
                )
                    .chain()
                    .before(TransformSystems::Propagate)
                    .before(AssetEventSystems),
            );
    }
}
