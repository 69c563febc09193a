//! The ECS plugin, headless: `MinimalPlugins` + assets + meshes + transforms, with the
//! clock driven by hand. Slices run at the species' own grid and meshes at a reduced
//! resolution, so the debug build stays quick. One file per concern; the helpers they
//! share are here.

use crate::common::app::Headless;
use crate::common::species_files;
use bevy::asset::{AssetLoadFailedEvent, AssetPlugin};
use bevy::camera::visibility::VisibilityPlugin;
use bevy::diagnostic::{DiagnosticPath, DiagnosticsStore};
use bevy::ecs::system::RunSystemOnce;
use bevy::mesh::MeshTag;
use bevy::mesh::VertexAttributeValues;
use bevy::prelude::*;
use bevy::render::storage::ShaderBuffer;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::plugin::{
    CPU_MESH_TAG, CycleCaches, DetailLevels, JellyfishGeometry, JellyfishGlow, JellyfishMeshes,
    JellyfishSlice, PartOf, ShapeBuffers, SurfaceMode, SurfacePath, TENTACLE_SORT_OFFSET, Tier,
};
use bevy_jellyfish::{
    Jellyfish, JellyfishDiagnostics, JellyfishSettings, SliceGeometry, SliceSim, Species,
    SpeciesRejected,
};
use std::path::PathBuf;
use std::time::Duration;

mod debug;
mod detail;
mod lifecycle;
mod order;
mod school;
mod species;
mod surfaces;
mod time;

fn settings() -> JellyfishSettings {
    JellyfishSettings {
        mesh_resolution_scale: 0.5,
        ..default()
    }
}

fn app_with(assets: AssetPlugin) -> App {
    Headless {
        assets,
        settings: settings(),
        frame: frame(60),
    }
    .build(|_| {})
}

fn app() -> App {
    app_with(AssetPlugin::default())
}

fn frame(fps: u32) -> Duration {
    Duration::from_secs_f64(1.0 / fps as f64)
}

fn set_frame(app: &mut App, d: Duration) {
    app.insert_resource(TimeUpdateStrategy::ManualDuration(d));
}

fn run(app: &mut App, frames: usize) {
    for _ in 0..frames {
        app.update();
    }
}

/// Aurelia with a lighter mesh (8 tentacles) for the debug build.
fn species() -> Species {
    Species {
        tentacle_count: 8,
        ..Species::aurelia()
    }
}

fn add_species(app: &mut App, s: Species) -> Handle<Species> {
    app.world_mut().resource_mut::<Assets<Species>>().add(s)
}

/// An app with one jellyfish of the test species at the origin.
fn one_jellyfish() -> (App, Handle<Species>, Entity) {
    let mut app = app();
    let h = add_species(&mut app, species());
    let e = app
        .world_mut()
        .spawn((Jellyfish::new(h.clone()), Transform::default()))
        .id();
    (app, h, e)
}

fn slice(app: &App, e: Entity) -> &JellyfishSlice {
    app.world().get::<JellyfishSlice>(e).unwrap()
}

fn umbrella_positions(app: &App, e: Entity) -> Vec<[f32; 3]> {
    let meshes = app.world().get::<JellyfishMeshes>(e).unwrap();
    let handle = meshes.umbrella.as_ref().expect("umbrella mesh built");
    let mesh = app.world().resource::<Assets<Mesh>>().get(handle).unwrap();
    match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => p.clone(),
        other => panic!("positions: {other:?}"),
    }
}

fn rejections(app: &mut App) -> Vec<SpeciesRejected> {
    app.world_mut()
        .resource_mut::<Messages<SpeciesRejected>>()
        .drain()
        .collect()
}

/// A camera at the origin looking down −z, with the frustum the renderer would compute.
fn spawn_camera(app: &mut App) {
    use bevy::camera::primitives::Frustum;
    let transform = Transform::default();
    let projection = Projection::Perspective(PerspectiveProjection::default());
    let frustum: Frustum = projection.compute_frustum(&GlobalTransform::from(transform));
    app.world_mut()
        .spawn((Camera3d::default(), projection, transform, frustum));
}
