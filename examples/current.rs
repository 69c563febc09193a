//! The fringe in the 3D water: guide chains carry what each slice cannot see. Two
//! pictures, offscreen:
//!
//! - `current`: a row of crystal jellies held in place, swimming, while a current sweeps
//!   through at the depth of their tentacles (a band of water half a bell width below
//!   them): the bells ride still water, their fringes stream downstream.
//! - `turn`: one jellyfish turned a right angle by the game, shown at several times after
//!   the turn, left to right: the fringe first stays where the water holds it, then is
//!   towed in line behind the new axis.
//!
//! `cargo run --release --features examples --example current -- current --out
//! docs/current.png [--size 1500x600]`, or `turn --out docs/turn.png`. Mesa's software
//! Vulkan will do; set `XDG_RUNTIME_DIR` to quiet it.

#[path = "common/offscreen.rs"]
mod screenshot;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::prelude::*;
use screenshot::{Offscreen, OffscreenTarget};
use std::path::PathBuf;
use std::time::Duration;

/// Simulated time per rendered frame: the physics takes its own fixed steps whatever the
/// frame, so big frames only save rendering.
const FRAME: f64 = 0.1;

/// The row's spacing, in bell widths.
const SPACING: f32 = 1.7;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        let i = args.iter().position(|a| a == name)?;
        args.get(i + 1).cloned()
    };
    let turn = args.get(1).is_some_and(|a| a == "turn");
    let default_out = if turn { "turn.png" } else { "current.png" };
    let path = PathBuf::from(value("--out").unwrap_or_else(|| default_out.into()));
    let (width, height) = value("--size").map_or((1500, 600), |s| {
        let (w, h) = s.split_once('x').expect("--size: WIDTHxHEIGHT");
        (
            w.parse().expect("--size width"),
            h.parse().expect("--size height"),
        )
    });
    let mut offscreen = Offscreen::new(width, height, |app| {
        app.add_plugins(JellyfishPlugin::default()).insert_resource(
            TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(FRAME)),
        );
    })
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    println!("rendering offscreen on {}", offscreen.adapter);
    let target = offscreen.world().resource::<OffscreenTarget>().0.clone();
    let species = Species::aequorea();
    let scale = 1.0 / species.diameter;
    let count = 5;
    let row: Vec<Entity> = (0..count)
        .map(|k| {
            let handle = offscreen
                .world_mut()
                .resource_mut::<Assets<Species>>()
                .add(species.clone());
            let spacing = if turn { 40.0 } else { SPACING };
            let x = (k as f32 - 0.5 * (count - 1) as f32) * spacing;
            offscreen
                .world_mut()
                .spawn((
                    Jellyfish::new(handle)
                        .with_seed(11 + k as u32)
                        .with_phase(0.13 * k as f32),
                    Transform::from_xyz(x, 0.0, 0.0).with_scale(Vec3::splat(scale)),
                ))
                .id()
        })
        .collect();
    spawn_view(offscreen.world_mut(), target, count as f32 * SPACING);
    let period = species.period() as f64;
    let start = std::time::Instant::now();
    if turn {
        // Jellyfish k is turned `delays[k]` before the picture (the first never), each
        // framed by its own camera as it swims off.
        let delays = [
            None,
            Some(FRAME),
            Some(0.5 * period),
            Some(1.5 * period),
            Some(3.0 * period),
        ];
        follow_each(offscreen.world_mut(), &row, UVec2::new(width, height));
        let total = 6.0 * period;
        let mut turned = vec![false; count];
        let mut t = 0.0;
        while t < total {
            for (k, &e) in row.iter().enumerate() {
                if !turned[k] && delays[k].is_some_and(|d| total - t <= d) {
                    turned[k] = true;
                    let mut transform = offscreen.world_mut().get_mut::<Transform>(e).unwrap();
                    transform.rotate_z(-std::f32::consts::FRAC_PI_2);
                }
            }
            offscreen.update();
            t += FRAME;
        }
    } else {
        // A band of water streaming along +x half a bell width below the bells, through
        // their fringes: the bells themselves ride still water (no shear to turn them).
        offscreen
            .world_mut()
            .insert_resource(AmbientWater::from_fn(|p, _| {
                let band = (p.y + 0.55) / 0.2;
                Vec3::X * 0.3 * (-band * band).exp()
            }));
        let mut t = 0.0;
        while t < 4.0 * period {
            hold(&mut offscreen, &row);
            offscreen.update();
            t += FRAME;
        }
    }
    println!("rendered in {:.1} s", start.elapsed().as_secs_f64());
    match offscreen.capture(&path) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}

/// Keeps each jellyfish where it started: the game holds them in place, swimming, while
/// the current streams past their fringes.
fn hold(offscreen: &mut Offscreen, row: &[Entity]) {
    for (k, &e) in row.iter().enumerate() {
        let count = row.len();
        let x = (k as f32 - 0.5 * (count - 1) as f32) * SPACING;
        if let Some(mut t) = offscreen.world_mut().get_mut::<Transform>(e) {
            t.translation = Vec3::new(x, 0.0, 0.0);
        }
    }
}

/// A camera per jellyfish, side by side, each keeping its jellyfish in view.
#[derive(Component)]
struct Follow(Entity);

fn follow_each(world: &mut World, row: &[Entity], size: UVec2) {
    let cameras = screenshot::panel_cameras(world, row.len(), size, 300.0);
    for (camera, &jellyfish) in cameras.into_iter().zip(row) {
        world.entity_mut(camera).insert(Follow(jellyfish));
    }
    world.schedule_scope(Update, |_, schedule| {
        schedule.add_systems(follow);
    });
}

fn follow(
    mut cameras: Query<(&Follow, &mut Transform), Without<Jellyfish>>,
    jellyfish: Query<&Transform, With<Jellyfish>>,
) {
    for (follow, mut camera) in &mut cameras {
        if let Ok(jelly) = jellyfish.get(follow.0) {
            let aim = jelly.translation - jelly.up() * 0.3;
            *camera = Transform::from_translation(aim + Vec3::new(0.0, 0.3, 2.6))
                .looking_at(aim, Vec3::Y);
        }
    }
}

fn spawn_view(world: &mut World, target: bevy::camera::RenderTarget, width: f32) {
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let aim = Vec3::new(0.0, -0.6, 0.0);
    world.spawn((
        Camera3d::default(),
        Camera {
            clear_color: ClearColorConfig::Custom(Color::srgb(0.01, 0.03, 0.07)),
            ..default()
        },
        AmbientLight {
            brightness: 300.0,
            ..default()
        },
        target,
        Transform::from_translation(aim + Vec3::new(0.0, 0.4, 0.62 * width))
            .looking_at(aim, Vec3::Y),
    ));
}
