//! The paper's Fig. 9 rendered offscreen: rows expanded (rest) and contracted, columns plain
//! disc extrapolation, structural, compression, unstructured, and all of the paper's
//! variation together (`Species::with_paper_variations`), each on the paper's dome
//! (`Species::paper`); the last column is the shipped moon jelly, its saucer and its
//! smoother surface.
//!
//! `cargo run --release --features examples --example variations -- --out variations.png [--elevation 22]` (degrees the
//! camera looks down; negative looks up into the subumbrella).
//! Headless: no window; with no GPU it runs on Mesa's software Vulkan (`mesa-vulkan-drivers`,
//! set `XDG_RUNTIME_DIR` to quiet it). The slices are hand-made ([`SliceOutline`]): the
//! contracted row pulls opposite pairs towards the axis, to its `contraction_ratio` of the rest
//! span at the margin.

#[path = "common/offscreen.rs"]
mod screenshot;

use bevy::{
    asset::RenderAssetUsages,
    camera::{RenderTarget, ScalingMode},
    mesh::{Indices, PrimitiveTopology},
    prelude::*,
};
use bevy_jellyfish::Species;
use bevy_jellyfish::shape::{JellyMesh, SliceOutline, SurfaceBuffers};
use screenshot::{Offscreen, OffscreenTarget};
use std::path::PathBuf;

const WIDTH: u32 = 1800;
const HEIGHT: u32 = 720;
/// Metres to scene units: a 40 mm bell becomes one unit wide.
const SCALE: f32 = 25.0;
const SEED: u32 = 7;

fn main() {
    let out = PathBuf::from(arg("--out").unwrap_or_else(|| "variations.png".into()));
    let elevation: f32 =
        arg("--elevation").map_or(22.0, |e| e.parse().expect("--elevation: degrees"));
    let mut offscreen = Offscreen::new(WIDTH, HEIGHT, |_| {}).unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    let target = offscreen.world().resource::<OffscreenTarget>().0.clone();
    spawn_scene(offscreen.world_mut(), target, elevation);
    // Pipelines compile synchronously, so a few frames are enough before the capture.
    for _ in 0..3 {
        offscreen.update();
    }
    match offscreen.capture(&out) {
        Ok(()) => println!("wrote {}", out.display()),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}

/// The value after `--name` on the command line.
fn arg(name: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    let i = args.iter().position(|a| a == name)?;
    Some(
        args.get(i + 1)
            .unwrap_or_else(|| panic!("{name} needs a value"))
            .clone(),
    )
}

/// The five columns of Fig. 9 (the paper's model with only the named variation of the
/// paper left on), then the shipped moon jelly as it is.
fn columns() -> [(&'static str, Species); 6] {
    let all = Species::paper().with_paper_variations();
    let plain = Species {
        structural_scale: 0.0,
        compression_scale: 0.0,
        unstructured_scale: 0.0,
        ..all.clone()
    };
    [
        ("3D extrapolation", plain.clone()),
        (
            "structural",
            Species {
                structural_scale: all.structural_scale,
                ..plain.clone()
            },
        ),
        (
            "compression",
            Species {
                compression_scale: all.compression_scale,
                ..plain.clone()
            },
        ),
        (
            "unstructured",
            Species {
                unstructured_scale: all.unstructured_scale,
                ..plain
            },
        ),
        ("all (paper)", all),
        ("shipped", Species::aurelia()),
    ]
}

fn spawn_scene(world: &mut World, target: RenderTarget, elevation: f32) {
    // Each column's own bell: the paper's dome, and last the moon jelly's saucer.
    let rows = [("expanded", 0.0, 0.95), ("contracted", 1.0, -1.05)];
    let bell = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial {
            base_color: Color::srgb(0.72, 0.82, 0.95),
            perceptual_roughness: 0.55,
            reflectance: 0.3,
            ..default()
        });
    let tentacle = world
        .resource_mut::<Assets<StandardMaterial>>()
        .add(StandardMaterial {
            base_color: Color::srgb(0.95, 0.7, 0.75),
            perceptual_roughness: 0.7,
            ..default()
        });
    for (row, amount, y) in rows {
        for (col, (name, sp)) in columns().iter().enumerate() {
            let slice = SliceOutline::contracted(sp, 25, 12, amount);
            let jelly = JellyMesh::from_slice(&slice.view(), sp, SEED, 0.0)
                .unwrap_or_else(|e| panic!("{row}/{name}: {e}"));
            let x = (col as f32 - 2.5) * 1.45;
            let at = Transform::from_xyz(x, y, 0.0).with_scale(Vec3::splat(SCALE));
            for (buffers, material) in [(&jelly.umbrella, &bell), (&jelly.tentacles, &tentacle)] {
                let mesh = world.resource_mut::<Assets<Mesh>>().add(to_mesh(buffers));
                world.spawn((Mesh3d(mesh), MeshMaterial3d(material.clone()), at));
            }
            println!(
                "{row:>10} / {name:<16}: umbrella {} vertices, tentacles {} vertices",
                jelly.umbrella.vertex_count(),
                jelly.tentacles.vertex_count()
            );
        }
    }
    // A low key light from the side brings out the relief of the variations.
    world.spawn((
        DirectionalLight {
            illuminance: 10000.0,
            ..default()
        },
        Transform::from_xyz(-6.0, 2.5, 3.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let elevation = elevation.to_radians();
    let eye = Vec3::new(0.0, elevation.sin(), elevation.cos()) * 20.0 + Vec3::Y * -0.1;
    world.spawn((
        Camera3d::default(),
        Camera {
            clear_color: ClearColorConfig::Custom(Color::srgb(0.02, 0.04, 0.08)),
            ..default()
        },
        Projection::Orthographic(OrthographicProjection {
            scaling_mode: ScalingMode::FixedVertical {
                viewport_height: 4.1,
            },
            ..OrthographicProjection::default_3d()
        }),
        AmbientLight {
            brightness: 400.0,
            ..default()
        },
        target,
        Transform::from_translation(eye).looking_at(Vec3::new(0.0, -0.1, 0.0), Vec3::Y),
    ));
}

/// Copies shape buffers into a Bevy mesh (the plugin updates such meshes in place).
fn to_mesh(b: &SurfaceBuffers) -> Mesh {
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions.clone())
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals.clone())
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs.clone())
    .with_inserted_indices(Indices::U32(b.indices.clone()))
}
