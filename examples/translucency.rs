//! Do overlapping jellyfish pop? Three moon jellies one behind another, the clock stopped,
//! the camera orbiting slowly past them; each frame is compared with the one before.
//!
//! Alpha-blended meshes are drawn back to front by their origins only, so where two
//! translucent surfaces overlap, the order of the whole meshes decides what is in front:
//! when two origins swap distance, a patch of the picture changes at once, in one frame
//! (a pop). Smooth camera motion changes few pixels, frame after frame. Printed: pixels
//! changed per frame (median, largest, and frames with more than three times the median).
//!
//! `cargo run --release --features examples --example translucency -- [--oit] [--frames 48]
//! [--out DIR]`. `--oit` turns on Bevy's order-independent transparency on the camera
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
/// A pixel counts as changed when a channel moves by more than this (of 255).
const THRESHOLD: i32 = 8;

#[derive(Component)]
struct Orbit;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str| {
        let i = args.iter().position(|a| a == name)?;
        args.get(i + 1).cloned()
    };
    let oit = args.iter().any(|a| a == "--oit");
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
    let dir = out.clone().unwrap_or_else(std::env::temp_dir);
    std::fs::create_dir_all(&dir).expect("the output folder");
    let mut previous: Option<Vec<u8>> = None;
    let mut changed = Vec::new();
    for frame in 0..frames {
        // 30° in all, across the line where the jellyfish line up behind each other.
        let angle = (-15.0 + 30.0 * frame as f32 / frames as f32).to_radians();
        let eye = Quat::from_rotation_y(angle) * Vec3::new(0.0, 0.4, 4.5);
        for mut camera in offscreen
            .world_mut()
            .query_filtered::<&mut Transform, With<Orbit>>()
            .iter_mut(offscreen.world_mut())
        {
            *camera =
                Transform::from_translation(eye).looking_at(Vec3::new(0.0, -0.2, -0.8), Vec3::Y);
        }
        let path = dir.join(format!("translucency-{frame:03}.png"));
        offscreen.capture(&path).unwrap_or_else(|e| {
            eprintln!("{e}");
            std::process::exit(1)
        });
        let pixels = read(&path);
        if let Some(before) = &previous {
            changed.push(count_changed(before, &pixels));
        }
        previous = Some(pixels);
        if out.is_none() {
            let _ = std::fs::remove_file(&path);
        }
    }
    let mut sorted = changed.clone();
    sorted.sort_unstable();
    let median = sorted[sorted.len() / 2].max(1);
    let largest = *sorted.last().unwrap();
    let pops = changed.iter().filter(|&&c| c > 3 * median).count();
    println!(
        "{}: pixels changed per frame over {} frames: median {median}, largest {largest} \
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
    let handle = world
        .resource_mut::<Assets<Species>>()
        .add(Species::aurelia());
    let scale = 1.0 / Species::aurelia().diameter;
    // One behind another, each a little to the side: their bells overlap in the view.
    for (i, position) in [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.35, 0.1, -0.8),
        Vec3::new(-0.3, -0.05, -1.6),
    ]
    .into_iter()
    .enumerate()
    {
        world.spawn((
            Jellyfish {
                seed: Some(i as u32),
                phase: Some(0.3 * i as f32),
                ..Jellyfish::new(handle.clone())
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

fn count_changed(a: &[u8], b: &[u8]) -> usize {
    a.chunks_exact(3)
        .zip(b.chunks_exact(3))
        .filter(|(p, q)| {
            p.iter()
                .zip(*q)
                .any(|(x, y)| (*x as i32 - *y as i32).abs() > THRESHOLD)
        })
        .count()
}
