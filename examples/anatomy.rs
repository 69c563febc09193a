//! One jellyfish of each shipped species close up, live: the side view above, the view from
//! below (into the subumbrella) underneath. Shows the anatomy the species files describe:
//! the manubrium and the oral arms swinging in the slice's water, the gonads and canals
//! painted on the subumbrella, the tentacles.
//!
//! `cargo run --release --features examples --example anatomy -- --screenshot anatomy.png
//! [--frames 150] [--size 1500x1000] [--cpu]` (`--cpu`: CPU meshes instead of templates,
//! to compare the two paths). Offscreen, without a window (Mesa's software Vulkan
//! will do; set `XDG_RUNTIME_DIR` to quiet it). Columns: Aurelia, Aequorea, Sarsia.

#[path = "common/offscreen.rs"]
mod screenshot;

use bevy::camera::{RenderTarget, Viewport};
use bevy::prelude::*;
use bevy_jellyfish::prelude::*;
use screenshot::{Offscreen, OffscreenTarget};
use std::path::PathBuf;

/// Each jellyfish stands this far from the next, in bell widths: out of the others' views.
const SPACING: f32 = 40.0;
/// The phase each jellyfish is shown at: late in its refill, the bell relaxed.
const RELAXED: f32 = 0.92;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        let i = args.iter().position(|a| a == name)?;
        args.get(i + 1).cloned()
    };
    let path = PathBuf::from(value("--screenshot").unwrap_or_else(|| "anatomy.png".into()));
    let frames: u32 = value("--frames").map_or(150, |f| f.parse().expect("--frames: a count"));
    let (width, height) = value("--size").map_or((1500, 1000), |s| {
        let (w, h) = s.split_once('x').expect("--size: WIDTHxHEIGHT");
        (
            w.parse().expect("--size width"),
            h.parse().expect("--size height"),
        )
    });
    let surfaces = match args.iter().any(|a| a == "--cpu") {
        true => SurfaceMode::CpuMeshes,
        false => SurfaceMode::Auto,
    };
    let mut offscreen = Offscreen::new(width, height, |app| {
        app.add_plugins(JellyfishPlugin::default())
            .insert_resource(JellyfishSettings {
                surfaces,
                ..default()
            })
            .add_systems(Update, follow);
    })
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    println!("rendering offscreen on {}", offscreen.adapter);
    let target = offscreen.world().resource::<OffscreenTarget>().0.clone();
    let seconds = frames as f32 / 60.0;
    spawn_scene(
        offscreen.world_mut(),
        target,
        UVec2::new(width, height),
        seconds,
    );
    let start = std::time::Instant::now();
    for _ in 0..frames {
        offscreen.update();
    }
    println!("{frames} frames in {:.1} s", start.elapsed().as_secs_f64());
    match offscreen.capture(&path) {
        Ok(()) => println!("wrote {}", path.display()),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}

/// A camera that keeps its jellyfish in view: `offset` from the middle of its extent
/// (world units: a bell is one unit wide), looking at it, `up` its up.
#[derive(Component)]
struct Follow {
    jellyfish: Entity,
    /// How far below the bell's centroid the middle of the jellyfish is, units.
    below: f32,
    offset: Vec3,
    up: Vec3,
}

fn follow(
    mut cameras: Query<(&Follow, &mut Transform), Without<Jellyfish>>,
    jellyfish: Query<&Transform, With<Jellyfish>>,
) {
    for (follow, mut camera) in &mut cameras {
        if let Ok(jelly) = jellyfish.get(follow.jellyfish) {
            let aim = jelly.translation - jelly.up() * follow.below;
            *camera = Transform::from_translation(aim + follow.offset).looking_at(aim, follow.up);
        }
    }
}

/// The jellyfish's top and bottom relative to its bell's centroid, in bell widths: the
/// apex above, the longest of tentacles and manubrium with arms below.
fn extent(species: &Species) -> (f32, f32) {
    let d = species.diameter;
    let hanging = species
        .tentacle_length
        .max(species.manubrium_length + species.oral_arm_length);
    (
        0.65 * species.height / d,
        -(0.35 * species.height + 0.8 * hanging) / d,
    )
}

/// Each species' jellyfish, started so that `seconds` later it is relaxed (late in its
/// refill), as an anatomy plate shows an animal, and its two cameras.
fn spawn_scene(world: &mut World, target: RenderTarget, size: UVec2, seconds: f32) {
    let cell = UVec2::new(size.x / 3, size.y / 2);
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    let presets = Species::presets();
    for (column, species) in presets.into_iter().enumerate() {
        // Every bell one unit wide.
        let scale = 1.0 / species.diameter;
        let (top, bottom) = extent(&species);
        let (middle, span) = (0.5 * (top + bottom), (top - bottom).max(1.2));
        // Bevy's default 45° field of view: the span fills 80% of the height.
        let distance = 1.5 * span;
        let phase = (RELAXED - seconds * species.contraction_frequency).rem_euclid(1.0);
        let handle = world.resource_mut::<Assets<Species>>().add(species);
        let jellyfish = world
            .spawn((
                Jellyfish {
                    seed: Some(7),
                    phase: Some(phase),
                    ..Jellyfish::new(handle)
                },
                Transform::from_xyz(column as f32 * SPACING, 0.0, 0.0)
                    .with_scale(Vec3::splat(scale)),
            ))
            .id();
        let views = [
            (Vec3::new(0.0, 0.1, 1.0).normalize() * distance, Vec3::Y),
            (
                Vec3::new(0.0, -1.0, 0.2).normalize() * distance * 0.8,
                Vec3::Z,
            ),
        ];
        for (row, (offset, up)) in views.into_iter().enumerate() {
            let order = (row * 3 + column) as isize;
            world.spawn((
                Camera3d::default(),
                Camera {
                    order,
                    // The first camera clears the whole image; the others draw over it.
                    clear_color: if order == 0 {
                        ClearColorConfig::Custom(Color::srgb(0.01, 0.03, 0.07))
                    } else {
                        ClearColorConfig::None
                    },
                    viewport: Some(Viewport {
                        physical_position: UVec2::new(column as u32 * cell.x, row as u32 * cell.y),
                        physical_size: cell,
                        ..default()
                    }),
                    ..default()
                },
                AmbientLight {
                    brightness: 300.0,
                    ..default()
                },
                target.clone(),
                Follow {
                    jellyfish,
                    below: -middle,
                    offset,
                    up,
                },
                Transform::default(),
            ));
        }
    }
}
