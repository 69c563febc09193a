//! Marine snow: about a thousand small pale flecks sinking slowly and carried by the tank's
//! water, moved on the CPU, drawn stretched along their motion (streaks) so a stir shows.
//! One mesh and one material for all, so Bevy draws them as one batch.

use crate::tank::{HALF_DEPTH, HALF_WIDTH, SURFACE};
use bevy::prelude::*;
use bevy_jellyfish::plugin::AmbientWater;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

const FLAKES: usize = 1200;
/// How much of its travel a flake is drawn stretched over, s: long enough for a stir to
/// read as streaks across the tank, short enough that still water leaves dots.
const STREAK_SECONDS: f32 = 0.25;
/// The volume the flakes fill: the tank and some water in front of it, towards the camera.
const MIN: Vec3 = Vec3::new(-HALF_WIDTH - 3.0, 0.0, -HALF_DEPTH - 2.0);
const MAX: Vec3 = Vec3::new(HALF_WIDTH + 3.0, SURFACE, HALF_DEPTH + 4.0);

pub fn plugin(app: &mut App) {
    app.add_systems(Startup, setup).add_systems(Update, drift);
}

#[derive(Component)]
struct Flake {
    sink: f32,
    phase: f32,
    size: f32,
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let mesh = meshes.add(Sphere::new(0.02).mesh().ico(0).expect("ico sphere"));
    let material = materials.add(StandardMaterial {
        base_color: Color::srgb(0.75, 0.85, 0.9),
        emissive: LinearRgba::rgb(0.3, 0.4, 0.45),
        unlit: true,
        ..default()
    });
    // Seeded: the same snow every run.
    let mut rng = StdRng::seed_from_u64(0x5eed);
    for _ in 0..FLAKES {
        let at = MIN + (MAX - MIN) * Vec3::from_array(rng.random());
        let size = 0.5 + rng.random::<f32>();
        commands.spawn((
            Mesh3d(mesh.clone()),
            MeshMaterial3d(material.clone()),
            Transform::from_translation(at).with_scale(Vec3::splat(size)),
            Flake {
                sink: 0.04 + 0.08 * rng.random::<f32>(),
                phase: rng.random_range(0.0..std::f32::consts::TAU),
                size,
            },
        ));
    }
}

fn drift(time: Res<Time>, water: Res<AmbientWater>, mut flakes: Query<(&Flake, &mut Transform)>) {
    let (t, dt) = (time.elapsed_secs(), time.delta_secs());
    let now = time.elapsed_secs_f64();
    let water = &*water;
    flakes.par_iter_mut().for_each(|(flake, mut transform)| {
        let p = transform.translation;
        let current = water.velocity(p, now);
        let own = Vec3::new(
            0.06 * (0.3 * t + flake.phase).sin(),
            -flake.sink,
            0.05 * (0.23 * t + 2.0 * flake.phase).cos(),
        );
        let v = current + own;
        let mut p = p + v * dt;
        if p.y < MIN.y {
            p.y = MAX.y;
        }
        p = p.clamp(MIN, MAX);
        // A streak as long as a quarter of a second of travel, at least the flake.
        let speed = current.length();
        let stretch = 1.0 + speed * STREAK_SECONDS / (0.02 * flake.size);
        let along = current.try_normalize().unwrap_or(Vec3::Y);
        *transform = Transform::from_translation(p)
            .with_rotation(Quat::from_rotation_arc(Vec3::Y, along))
            .with_scale(Vec3::new(flake.size, flake.size * stretch, flake.size));
    });
}
