//! The tank: deep-blue water, a sandy floor with a few rocks, a bright surface overhead,
//! light shafts that sway gently, and the lights.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;

/// Half the tank's width (x) and depth (z), scene units.
pub const HALF_WIDTH: f32 = 7.0;
pub const HALF_DEPTH: f32 = 5.0;
/// The floor is at y = 0, the surface at this height.
pub const SURFACE: f32 = 9.0;
/// The colour far water fades to (also the clear colour).
pub const WATER: Color = Color::srgb(0.0, 0.07, 0.16);

pub fn plugin(app: &mut App) {
    app.insert_resource(ClearColor(WATER))
        .insert_resource(GlobalAmbientLight {
            color: Color::srgb(0.35, 0.6, 0.9),
            brightness: 250.0,
            ..default()
        })
        .add_systems(Startup, setup)
        .add_systems(Update, sway);
}

/// A light shaft, swaying about its top around a rest orientation.
#[derive(Component)]
struct Shaft {
    rest: Quat,
    phase: f32,
    speed: f32,
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    // Floor and a few rocks.
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(300.0, 300.0))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.4, 0.37, 0.3),
            perceptual_roughness: 0.95,
            ..default()
        })),
    ));
    let rock = meshes.add(Sphere::new(1.0).mesh().ico(2).expect("ico sphere"));
    let rock_material = materials.add(StandardMaterial {
        base_color: Color::srgb(0.22, 0.24, 0.26),
        perceptual_roughness: 0.9,
        ..default()
    });
    for (x, z, r, flat) in [
        (-4.5, -3.0, 1.1, 0.5),
        (-3.4, -3.6, 0.6, 0.6),
        (5.0, -2.0, 0.9, 0.45),
        (2.0, -4.5, 1.4, 0.4),
        (-6.0, 1.5, 0.7, 0.55),
    ] {
        commands.spawn((
            Mesh3d(rock.clone()),
            MeshMaterial3d(rock_material.clone()),
            Transform::from_xyz(x, 0.0, z)
                .with_scale(Vec3::new(r, r * flat, r * 0.8))
                .with_rotation(Quat::from_rotation_y(x + z)),
        ));
    }

    // The surface seen from below: a bright, translucent sheet that fades into the fog.
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::new(Vec3::NEG_Y, Vec2::splat(150.0)).mesh())),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgba(0.4, 0.8, 1.0, 0.35),
            emissive: LinearRgba::rgb(0.1, 0.35, 0.5),
            alpha_mode: AlphaMode::Blend,
            unlit: true,
            ..default()
        })),
        Transform::from_xyz(0.0, SURFACE, 0.0),
    ));

    // Light shafts: additive, brightest at the top and fading out towards the floor.
    let shaft_material = materials.add(StandardMaterial {
        base_color: Color::srgba(0.55, 0.85, 1.0, 1.0),
        alpha_mode: AlphaMode::Add,
        unlit: true,
        double_sided: true,
        cull_mode: None,
        fog_enabled: false,
        ..default()
    });
    // Down to the floor, where the light has faded out.
    let height = SURFACE + 0.5;
    let shaft_mesh = meshes.add(shaft(height));
    for (i, (x, z, tilt_x, tilt_z)) in [
        (-4.0, -2.0, 0.10, 0.20),
        (-1.0, 1.0, -0.05, 0.18),
        (2.5, -1.5, 0.08, 0.22),
        (5.0, 2.0, -0.1, 0.15),
        (0.5, -4.0, 0.12, 0.2),
    ]
    .into_iter()
    .enumerate()
    {
        let rest = Quat::from_euler(EulerRot::XYZ, tilt_x, 0.0, tilt_z);
        commands.spawn((
            Mesh3d(shaft_mesh.clone()),
            MeshMaterial3d(shaft_material.clone()),
            Transform::from_xyz(x, SURFACE + 0.5, z).with_rotation(rest),
            Shaft {
                rest,
                phase: i as f32 * 1.7,
                speed: 0.25 + 0.07 * i as f32,
            },
        ));
    }

    // Sunlight through the surface.
    commands.spawn((
        DirectionalLight {
            illuminance: 3500.0,
            color: Color::srgb(0.75, 0.92, 1.0),
            ..default()
        },
        Transform::from_xyz(1.0, 10.0, 2.0).looking_at(Vec3::ZERO, Vec3::Z),
    ));
}

/// An open cone of light hanging from its narrow end (local origin at the top, pointing
/// down), no caps, with vertex alpha fading from the top to nothing part-way down.
fn shaft(height: f32) -> Mesh {
    const SEGMENTS: usize = 24;
    const RINGS: usize = 12;
    let (top, bottom) = (0.45, 2.0);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut colors = Vec::new();
    for ring in 0..=RINGS {
        let t = ring as f32 / RINGS as f32;
        let radius = top + (bottom - top) * t;
        let alpha = 0.05 * (1.0 - t).powi(3);
        for seg in 0..=SEGMENTS {
            let a = seg as f32 / SEGMENTS as f32 * std::f32::consts::TAU;
            let (s, c) = a.sin_cos();
            positions.push([radius * c, -height * t, radius * s]);
            normals.push([c, 0.0, s]);
            colors.push([1.0, 1.0, 1.0, alpha]);
        }
    }
    let row = SEGMENTS as u32 + 1;
    let mut indices = Vec::new();
    for ring in 0..RINGS as u32 {
        for seg in 0..SEGMENTS as u32 {
            let (a, b) = (ring * row + seg, (ring + 1) * row + seg);
            indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_COLOR, colors)
    .with_inserted_indices(Indices::U32(indices))
}

fn sway(time: Res<Time>, mut shafts: Query<(&Shaft, &mut Transform)>) {
    let t = time.elapsed_secs();
    for (shaft, mut transform) in &mut shafts {
        let a = (t * shaft.speed + shaft.phase).sin() * 0.05;
        let b = (t * shaft.speed * 0.7 + shaft.phase * 2.0).cos() * 0.04;
        transform.rotation = Quat::from_euler(EulerRot::XYZ, a, 0.0, b) * shaft.rest;
    }
}
