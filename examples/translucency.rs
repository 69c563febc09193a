//! Do overlapping jellyfish pop? One of each species side by side, overlapping in the
//! view, the clock stopped, the camera orbiting slowly across the angle where their
//! distances to it swap; each frame is compared with its two neighbours.
//!
//! Alpha-blended meshes are drawn back to front by their origins only, so where two
//! translucent surfaces overlap, the order of the whole meshes decides what is in front:
//! when two origins swap distance, a patch of the picture changes at once, in one frame
//! (a pop). Smooth camera motion changes the picture steadily, so a frame is close to the
//! mean of its neighbours; a pop is not. Printed per frame: the 8×8 blocks that differ from
//! that mean, their median, the largest and the frames above three times the median.
//!
//! `cargo run --release --features examples --example translucency -- [--oit] [--frames 48]
//! [--out DIR] [--still]`; `--still` holds the camera at the swap (the noise floor: nothing
//! should change). `--oit` turns on Bevy's order-independent transparency on the camera
//! (which needs MSAA off; both modes run without MSAA so only the sorting differs).
//! Offscreen (Mesa's software Vulkan will do).

#[path = "common/offscreen.rs"]
mod screenshot;

use bevy::core_pipeline::oit::OrderIndependentTransparencySettings;
use bevy::prelude::*;
use bevy::render::view::Msaa;
use bevy::time::TimeUpdateStrategy;
use bevy_jellyfish::prelude::*;
use screenshot::{Offscreen, OffscreenTarget};
use std::path::{Path, PathBuf};
use std::time::Duration;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 360;
/// A block counts as off when a channel's mean is further than this (of 255) from the mean
/// of its neighbours in time.
const THRESHOLD: i32 = 3;
/// Side of the blocks compared, pixels.
const BLOCK: usize = 8;

#[derive(Component)]
struct Orbit;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        let i = args.iter().position(|a| a == name)?;
        args.get(i + 1).cloned()
    };
    let oit = args.iter().any(|a| a == "--oit");
    // The control: the same frames with the camera held at the swap (nothing may change).
    let still = args.iter().any(|a| a == "--still");
    let frames: usize = value("--frames").map_or(48, |f| f.parse().expect("--frames: a count"));
    let out = value("--out").map(PathBuf::from);
    let mut offscreen = Offscreen::new(WIDTH, HEIGHT, |app| {
        app.add_plugins(JellyfishPlugin::default());
    })
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    let target = offscreen.world().resource::<OffscreenTarget>().0.clone();
    spawn_scene(offscreen.world_mut(), target, oit);
    // Two seconds of swimming, then the clock stops: only the camera moves.
    for _ in 0..120 {
        offscreen.update();
    }
    offscreen
        .world_mut()
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
    let world = offscreen.world_mut();
    let positions: Vec<Vec3> = world
        .query_filtered::<&Transform, With<Jellyfish>>()
        .iter(world)
        .map(|t| t.translation)
        .collect();
    let centre = positions.iter().sum::<Vec3>() / positions.len() as f32 - Vec3::Y * 0.3;
    let dir = out.clone().unwrap_or_else(std::env::temp_dir);
    std::fs::create_dir_all(&dir).expect("the output folder");
    let mut pictures = Vec::new();
    for frame in 0..frames {
        // 8° in all, a few pixels a frame, across the angle (0°) where the two in front
        // swap distances.
        let sweep = if still {
            0.0
        } else {
            frame as f32 / frames as f32 - 0.5
        };
        let angle = (8.0 * sweep).to_radians();
        let eye = centre + Quat::from_rotation_y(angle) * Vec3::new(0.0, 0.3, 3.2);
        for mut camera in offscreen
            .world_mut()
            .query_filtered::<&mut Transform, With<Orbit>>()
            .iter_mut(offscreen.world_mut())
        {
            *camera = Transform::from_translation(eye).looking_at(centre, Vec3::Y);
        }
        let path = dir.join(format!("translucency-{frame:03}.png"));
        offscreen.capture(&path).unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(1)
        });
        pictures.push(read(&path));
        if out.is_none() {
            let _ = std::fs::remove_file(&path);
        }
    }
    let changed: Vec<usize> = pictures
        .windows(3)
        .map(|w| off_the_mean(&w[0], &w[1], &w[2]))
        .collect();
    let mut sorted = changed.clone();
    sorted.sort_unstable();
    let median = sorted[sorted.len() / 2].max(1);
    let largest = *sorted.last().unwrap();
    let pops = changed.iter().filter(|&&c| c > 3 * median).count();
    println!(
        "{}: 8×8 blocks off the mean of their neighbours, over {} frames: median {median}, largest {largest} \
         ({:.1}× the median), frames above 3× the median: {pops}",
        if oit {
            "order-independent"
        } else {
            "sorted by origin"
        },
        changed.len(),
        largest as f64 / median as f64,
    );
    println!("per frame: {changed:?}");
}

fn spawn_scene(world: &mut World, target: bevy::camera::RenderTarget, oit: bool) {
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // Two side by side half a bell apart (their distances swap as the camera crosses
    // 0°), one behind them: bells, arms and tentacles overlap in the view.
    let places = [
        Vec3::new(-0.3, 0.0, 0.0),
        Vec3::new(0.3, 0.0, 0.0),
        Vec3::new(0.0, 0.3, -0.7),
    ];
    for (i, (species, position)) in Species::presets().into_iter().zip(places).enumerate() {
        let scale = 1.0 / species.diameter;
        let handle = world.resource_mut::<Assets<Species>>().add(species);
        world.spawn((
            Jellyfish {
                seed: Some(i as u32),
                phase: Some(0.3 * i as f32),
                ..Jellyfish::new(handle)
            },
            Transform::from_translation(position).with_scale(Vec3::splat(scale)),
        ));
    }
    let mut camera = world.spawn((
        Camera3d::default(),
        Camera {
            clear_color: ClearColorConfig::Custom(Color::srgb(0.01, 0.03, 0.07)),
            ..default()
        },
        Msaa::Off,
        AmbientLight {
            brightness: 300.0,
            ..default()
        },
        target,
        Orbit,
        Transform::default(),
    ));
    if oit {
        camera.insert(OrderIndependentTransparencySettings::default());
    }
}

fn read(path: &Path) -> Vec<u8> {
    let file = std::io::BufReader::new(std::fs::File::open(path).expect("the frame"));
    let mut reader = png::Decoder::new(file).read_info().expect("a PNG");
    let mut bytes = vec![0; reader.output_buffer_size().expect("its size")];
    let info = reader.next_frame(&mut bytes).expect("its pixels");
    let stride = match info.color_type {
        png::ColorType::Rgba => 4,
        _ => 3,
    };
    bytes.truncate(info.buffer_size());
    bytes
        .chunks_exact(stride)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect()
}

/// Blocks of [`BLOCK`]² pixels whose mean in `b` is further than [`THRESHOLD`] from the
/// mean of `a`'s and `c`'s in a channel (blocks, so that thin tentacles stepping from one
/// pixel to the next without MSAA average out).
fn off_the_mean(a: &[u8], b: &[u8], c: &[u8]) -> usize {
    let (w, h) = (WIDTH as usize, HEIGHT as usize);
    let mean = |img: &[u8], bx: usize, by: usize, k: usize| -> f64 {
        let mut sum = 0u32;
        for y in by * BLOCK..(by + 1) * BLOCK {
            for x in bx * BLOCK..(bx + 1) * BLOCK {
                sum += img[3 * (y * w + x) + k] as u32;
            }
        }
        sum as f64 / (BLOCK * BLOCK) as f64
    };
    let mut off = 0;
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            if (0..3).any(|k| {
                let m = 0.5 * (mean(a, bx, by, k) + mean(c, bx, by, k));
                (mean(b, bx, by, k) - m).abs() > THRESHOLD as f64
            }) {
                off += 1;
            }
        }
    }
    off
}
