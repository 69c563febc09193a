//! A touch, offscreen: five crystal jellies started together, side by side, each in its
//! own panel with a camera that stays where it started; jellyfish k was touched
//! `DELAYS[k]` seconds before the picture (the first never). Left to right: its untouched
//! twin, the flash rising, fading, and gone, while the escape carries the touched ones
//! further up their panels than the twin.
//!
//! `cargo run --release --features examples --example flash -- --out docs/flash.png
//! [--size 1500x600]`. Mesa's software Vulkan will do; set `XDG_RUNTIME_DIR` to quiet it.

#[path = "common/offscreen.rs"]
mod screenshot;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::prelude::*;
use screenshot::Offscreen;
use std::path::PathBuf;
use std::time::Duration;

/// Simulated time per rendered frame: the physics takes its own fixed steps whatever the
/// frame, so big frames only save rendering.
const FRAME: f64 = 0.05;

/// How long before the picture each jellyfish was touched, s (the first never).
const DELAYS: [Option<f64>; 5] = [None, Some(0.15), Some(0.6), Some(1.5), Some(4.0)];

/// Panels apart in the world: far enough that no touch or echo reaches a neighbour.
const APART: f32 = 40.0;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        let i = args.iter().position(|a| a == name)?;
        args.get(i + 1).cloned()
    };
    let path = PathBuf::from(value("--out").unwrap_or_else(|| "flash.png".into()));
    let (width, height) = value("--size").map_or((1500, 600), |s| {
        let (w, h) = s.split_once('x').expect("--size: WIDTHxHEIGHT");
        (
            w.parse().expect("--size width"),
            h.parse().expect("--size height"),
        )
    });
    let mut offscreen = Offscreen::new(width, height, |app| {
        // Every jellyfish near, whichever panel's camera ranks them.
        let settings = JellyfishSettings {
            detail: DetailLevels {
                near_size: 0.0,
                ..default()
            },
            ..default()
        };
        app.add_plugins(JellyfishPlugin { settings })
            .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
                FRAME,
            )));
    })
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    println!("rendering offscreen on {}", offscreen.adapter);
    let species = Species::aequorea();
    let scale = 1.0 / species.diameter;
    let row: Vec<Entity> = (0..DELAYS.len())
        .map(|k| {
            let handle = offscreen
                .world_mut()
                .resource_mut::<Assets<Species>>()
                .add(species.clone());
            offscreen
                .world_mut()
                .spawn((
                    Jellyfish::new(handle).with_seed(11).with_phase(0.0),
                    Transform::from_xyz((k as f32 - 2.0) * APART, 0.0, 0.0)
                        .with_scale(Vec3::splat(scale)),
                ))
                .id()
        })
        .collect();
    panels(offscreen.world_mut(), &row, UVec2::new(width, height));
    let total = 3.0 * species.period() as f64 + 0.5;
    let mut touched = [false; DELAYS.len()];
    let mut t = 0.0;
    while t < total - 1e-9 {
        for (k, &e) in row.iter().enumerate() {
            if !touched[k] && DELAYS[k].is_some_and(|d| total - t <= d + 1e-9) {
                touched[k] = true;
                let at = offscreen.world().get::<GlobalTransform>(e).unwrap();
                // From the side, at the margin's height.
                let point = at.translation() + Vec3::X * 0.4 - Vec3::Y * 0.2;
                offscreen
                    .world_mut()
                    .write_message(Disturbance::touch(point, 1.0));
            }
        }
        offscreen.update();
        t += FRAME;
    }
    for (k, &e) in row.iter().enumerate() {
        let flash = offscreen.world().get::<Flash>(e).unwrap();
        let slice = offscreen.world().get::<JellyfishSlice>(e).unwrap();
        println!(
            "touched {:>5}: flash {:.2}, swum {:.2} diameters",
            DELAYS[k].map_or("never".into(), |d| format!("{d} s")),
            flash.brightness,
            slice.swim_distance() / species.diameter
        );
    }
    match offscreen.capture(&path) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}

/// A panel per jellyfish, side by side, each camera aimed where its jellyfish started.
fn panels(world: &mut World, row: &[Entity], size: UVec2) {
    let cameras = screenshot::panel_cameras(world, row.len(), size, 200.0);
    world.spawn((
        DirectionalLight {
            illuminance: 4000.0,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    for (k, camera) in cameras.into_iter().enumerate() {
        let aim = Vec3::new((k as f32 - 2.0) * APART, 0.6, 0.0);
        world.entity_mut(camera).insert(Aim(aim));
    }
    world.schedule_scope(Update, |_, schedule| {
        schedule.add_systems(aim_cameras);
    });
}

/// Where a panel's camera looks: where its jellyfish started.
#[derive(Component)]
struct Aim(Vec3);

fn aim_cameras(mut cameras: Query<(&Aim, &mut Transform)>) {
    for (aim, mut camera) in &mut cameras {
        *camera = Transform::from_translation(aim.0 + Vec3::new(0.0, 0.2, 3.6))
            .looking_at(aim.0, Vec3::Y);
    }
}
