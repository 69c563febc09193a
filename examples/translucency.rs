//! Do overlapping jellyfish pop? One of each species side by side, overlapping in the
//! view, the clock stopped, the camera orbiting slowly across the angle where their
//! distances to it swap. Every frame is drawn twice: with translucent meshes sorted by
//! their bounding boxes' centres (Bevy's default) and with order-independent transparency
//! (OIT, sorted per fragment: the reference).
//!
//! Sorted by centres, where two translucent surfaces overlap the order of the whole meshes
//! decides what is in front: when two centres swap, a patch of the picture changes at once,
//! in one frame (a pop). Smooth camera motion changes the picture steadily, so a frame is
//! close to the mean of its neighbours; a pop is not. Thin tentacles stepping from pixel to
//! pixel (no MSAA: OIT does not combine with it) are off that mean too, but identically in
//! both renders, so what the sorted render has off the mean *beyond* the OIT render's is
//! the popping alone. Printed per frame: that excess (the largest 8×8 block, of 255), and
//! the frames where it stands above three times its median.
//!
//! `cargo run --release --features examples --example translucency -- [--frames 48]
//! [--out DIR] [--still]`; `--still` holds the camera at the swap (the control: nothing
//! may change). `--out` keeps the frames (`sorted-NNN.png`, `oit-NNN.png`). Offscreen
//! (Mesa's software Vulkan will do).

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
    let still = args.iter().any(|a| a == "--still");
    // A frame is judged against the mean of its two neighbours: three at least.
    let frames = match value("--frames").map_or(Ok(48), |f| f.parse::<usize>()) {
        Ok(n) if n >= 3 => n,
        _ => {
            eprintln!(
                "translucency: --frames takes a count of 3 or more (a frame is judged against its two neighbours)"
            );
            std::process::exit(2)
        }
    };
    let out = value("--out").map(PathBuf::from);
    let mut offscreen = Offscreen::new(WIDTH, HEIGHT, |app| {
        app.add_plugins(JellyfishPlugin::default());
    })
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1)
    });
    println!("rendering offscreen on {}", offscreen.adapter);
    let target = offscreen.world().resource::<OffscreenTarget>().0.clone();
    spawn_scene(offscreen.world_mut(), target);
    // Two seconds of swimming, then the clock stops: only the camera moves.
    for _ in 0..120 {
        offscreen.update();
    }
    offscreen
        .world_mut()
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::ZERO));
    let world = offscreen.world_mut();
    let mut jellyfish: Vec<(u32, Vec3)> = world
        .query::<(&Jellyfish, &Transform)>()
        .iter(world)
        .map(|(j, t)| (j.seed.unwrap_or(0), t.translation))
        .collect();
    jellyfish.sort_by_key(|j| j.0);
    let centre =
        jellyfish.iter().map(|j| j.1).sum::<Vec3>() / jellyfish.len() as f32 - Vec3::Y * 0.3;
    let eye_at = |angle: f32| centre + Quat::from_rotation_y(angle) * Vec3::new(0.0, 0.3, 3.2);
    // Where the origins of the two in front are equally deep in the view, found from where
    // they swam to in those two seconds. Bevy sorts by the meshes' bounding-box centres,
    // which lie a little off the origins: their swap is near, not at, this angle.
    let gap = |angle: f32| (centre - eye_at(angle)).dot(jellyfish[0].1 - jellyfish[1].1);
    let swap = bisect(gap, -0.5, 0.5);
    println!(
        "the origins of the two in front are equally deep at {:.2}°",
        swap.to_degrees()
    );
    let dir = out.clone().unwrap_or_else(std::env::temp_dir);
    std::fs::create_dir_all(&dir).expect("the output folder");
    let (mut sorted, mut oit) = (Vec::new(), Vec::new());
    // One frame of each first, unmeasured: OIT's buffers start on its first frame.
    for frame in std::iter::once(None).chain((0..frames).map(Some)) {
        // 8° in all, a few pixels a frame, across the swap.
        let sweep = match frame {
            Some(frame) if !still => frame as f32 / frames as f32 - 0.5,
            _ => 0.0,
        };
        let eye = eye_at(swap + (8.0 * sweep).to_radians());
        let world = offscreen.world_mut();
        let camera = world
            .query_filtered::<Entity, With<Orbit>>()
            .single(world)
            .expect("one camera");
        world
            .entity_mut(camera)
            .insert(Transform::from_translation(eye).looking_at(centre, Vec3::Y));
        for (name, pictures) in [("sorted", &mut sorted), ("oit", &mut oit)] {
            let mut camera = offscreen.world_mut().entity_mut(camera);
            if name == "oit" {
                camera.insert(OrderIndependentTransparencySettings::default());
            } else {
                camera.remove::<OrderIndependentTransparencySettings>();
            }
            let path = match frame {
                Some(frame) => dir.join(format!("{name}-{frame:03}.png")),
                None => dir.join(format!("{name}-warm-up.png")),
            };
            offscreen.capture(&path).unwrap_or_else(|e| {
                eprintln!("{e}");
                std::process::exit(1)
            });
            if frame.is_some() {
                pictures.push(block_means(&read(&path)));
            }
            if out.is_none() || frame.is_none() {
                let _ = std::fs::remove_file(&path);
            }
        }
    }
    let excess: Vec<f64> = off_the_mean(&sorted)
        .iter()
        .zip(off_the_mean(&oit))
        .map(|(s, o)| s.iter().zip(&o).map(|(s, o)| s - o).fold(0.0, f64::max))
        .collect();
    let mut by_size = excess.clone();
    by_size.sort_by(f64::total_cmp);
    let median = by_size[by_size.len() / 2];
    let largest = by_size[by_size.len() - 1];
    // Half a level of 255 is below what a picture can show.
    let pops: Vec<usize> = (0..excess.len())
        .filter(|&k| excess[k] > 3.0 * median.max(0.5))
        .map(|k| k + 1)
        .collect();
    println!(
        "sorted by centres beyond OIT, the largest 8×8 block off the mean of its neighbours \
         (of 255), over {} frames: median {median:.1}, largest {largest:.1}; frames above 3× \
         the median: {pops:?}",
        excess.len()
    );
    println!(
        "per frame: {:?}",
        excess
            .iter()
            .map(|e| (e * 10.0).round() / 10.0)
            .collect::<Vec<_>>()
    );
}

fn spawn_scene(world: &mut World, target: bevy::camera::RenderTarget) {
    world.spawn((
        DirectionalLight {
            illuminance: 6000.0,
            ..default()
        },
        Transform::from_xyz(1.0, 3.0, 2.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    // Two side by side half a bell apart (their distances swap as the camera crosses
    // 0°), one behind them: bells, arms and tentacles overlap in the view. The one behind
    // is *Sarsia*, which jets about 1.4 diameters in the two seconds before the clock
    // stops (the rowers a tenth of that): it starts that much lower, to end just above
    // and behind the other two.
    let places = [
        Vec3::new(-0.3, 0.0, 0.0),
        Vec3::new(0.3, 0.0, 0.0),
        Vec3::new(0.0, -1.0, -0.7),
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
    world.spawn((
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

/// A root of `f` between `a` and `b` (where it changes sign; else the middle).
fn bisect(f: impl Fn(f32) -> f32, mut a: f32, mut b: f32) -> f32 {
    if f(a).signum() == f(b).signum() {
        return 0.5 * (a + b);
    }
    for _ in 0..40 {
        let m = 0.5 * (a + b);
        if f(m).signum() == f(a).signum() {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// Per-channel means of the picture's [`BLOCK`]² blocks (blocks, so that thin tentacles
/// stepping from one pixel to the next average out).
fn block_means(pixels: &[u8]) -> Vec<[f64; 3]> {
    let (w, h) = (WIDTH as usize, HEIGHT as usize);
    let mut means = Vec::with_capacity((w / BLOCK) * (h / BLOCK));
    for by in 0..h / BLOCK {
        for bx in 0..w / BLOCK {
            let mut sum = [0u32; 3];
            for y in by * BLOCK..(by + 1) * BLOCK {
                for x in bx * BLOCK..(bx + 1) * BLOCK {
                    for (k, s) in sum.iter_mut().enumerate() {
                        *s += pixels[3 * (y * w + x) + k] as u32;
                    }
                }
            }
            means.push(sum.map(|s| s as f64 / (BLOCK * BLOCK) as f64));
        }
    }
    means
}

/// For every frame but the first and last, each block's largest channel distance from the
/// mean of the same block in the frames before and after.
fn off_the_mean(frames: &[Vec<[f64; 3]>]) -> Vec<Vec<f64>> {
    frames
        .windows(3)
        .map(|w| {
            (0..w[1].len())
                .map(|i| {
                    (0..3)
                        .map(|k| (w[1][i][k] - 0.5 * (w[0][i][k] + w[2][i][k])).abs())
                        .fold(0.0, f64::max)
                })
                .collect()
        })
        .collect()
}
