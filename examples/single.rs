//! One jellyfish, an orbit camera and a debug overlay of its slice.
//!
//! `cargo run --release --features examples --example single -- [aurelia|aequorea|sarsia]`
//!
//! Drag with the left mouse button to orbit, scroll to zoom. `D` toggles the overlay, drawn
//! in the slice's plane through the bell: fluid velocity arrows, trace particles carried by
//! the water (the paper's Fig. 6), and the body's springs coloured by tension (blue
//! compressed, red stretched). The diagnostics log prints simulation and meshing time.

#[path = "common/species.rs"]
mod common;

use bevy::diagnostic::{FrameTimeDiagnosticsPlugin, LogDiagnosticsPlugin};
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::platform::collections::HashSet;
use bevy::prelude::*;
use bevy_jellyfish::plugin::JellyfishSlice;
use bevy_jellyfish::{Jellyfish, JellyfishDiagnostics, JellyfishPlugin, SliceSim, Species};

/// Scene units per metre: a 40 mm bell is one unit across.
const SCALE: f32 = 25.0;
const PARTICLES: usize = 400;

fn main() -> AppExit {
    let name = std::env::args().nth(1).unwrap_or_else(|| "aurelia".into());
    if let Err(e) = common::find_species_file(&name, "single -- <name>") {
        eprintln!("{e}");
        return AppExit::error();
    }
    App::new()
        .add_plugins((
            DefaultPlugins,
            JellyfishPlugin::default(),
            FrameTimeDiagnosticsPlugin::default(),
            LogDiagnosticsPlugin::filtered(HashSet::from_iter([
                JellyfishDiagnostics::SIMULATION,
                JellyfishDiagnostics::MESHING,
            ])),
        ))
        .insert_resource(ClearColor(Color::srgb(0.01, 0.03, 0.07)))
        .insert_resource(SpeciesFile(format!("species/{name}.species.ron")))
        .init_resource::<Overlay>()
        .add_systems(Startup, setup)
        .add_systems(Update, (orbit, toggle_overlay, draw_overlay).chain())
        .run()
}

#[derive(Resource)]
struct SpeciesFile(String);

/// The camera circles the jellyfish and follows it as it swims.
#[derive(Component)]
struct Orbit {
    yaw: f32,
    pitch: f32,
    distance: f32,
}

#[derive(Resource, Default)]
struct Overlay {
    on: bool,
    /// Trace particles in world slice coordinates (domain + offset), m.
    particles: Vec<Vec2>,
    seed: u32,
}

fn setup(mut commands: Commands, assets: Res<AssetServer>, file: Res<SpeciesFile>) {
    let species: Handle<Species> = assets.load(file.0.clone());
    commands.spawn((
        Jellyfish::new(species).with_phase(0.0),
        Transform::from_scale(Vec3::splat(SCALE)),
    ));
    commands.spawn((
        Camera3d::default(),
        Orbit {
            yaw: 0.4,
            pitch: -0.25,
            distance: 4.0,
        },
        Transform::default(),
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 4000.0,
            ..default()
        },
        Transform::from_xyz(-2.0, 6.0, 3.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight {
        color: Color::srgb(0.3, 0.5, 0.8),
        brightness: 300.0,
        ..default()
    });
    println!("drag: orbit, scroll: zoom, D: slice overlay");
}

fn orbit(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    jellyfish: Query<&GlobalTransform, With<Jellyfish>>,
    mut camera: Query<(&mut Orbit, &mut Transform)>,
) {
    let Ok((mut orbit, mut transform)) = camera.single_mut() else {
        return;
    };
    if buttons.pressed(MouseButton::Left) {
        orbit.yaw -= motion.delta.x * 0.005;
        orbit.pitch = (orbit.pitch - motion.delta.y * 0.005).clamp(-1.5, 1.5);
    }
    orbit.distance = (orbit.distance * (1.0 - 0.1 * scroll.delta.y)).clamp(0.5, 50.0);
    let target = jellyfish
        .iter()
        .next()
        .map_or(Vec3::ZERO, |t| t.translation());
    let rotation = Quat::from_euler(EulerRot::YXZ, orbit.yaw, orbit.pitch, 0.0);
    transform.translation = target + rotation * Vec3::Z * orbit.distance;
    transform.look_at(target, Vec3::Y);
}

fn toggle_overlay(keys: Res<ButtonInput<KeyCode>>, mut overlay: ResMut<Overlay>) {
    if keys.just_pressed(KeyCode::KeyD) {
        overlay.on = !overlay.on;
        overlay.particles.clear();
    }
}

fn draw_overlay(
    mut gizmos: Gizmos,
    mut overlay: ResMut<Overlay>,
    time: Res<Time>,
    jellyfish: Query<(&JellyfishSlice, &GlobalTransform)>,
) {
    if !overlay.on {
        return;
    }
    let Some((slice, global)) = jellyfish.iter().next() else {
        return;
    };
    let Some(sim) = slice.sim() else {
        return;
    };
    let world = |p: Vec2| global.transform_point(slice.to_local(p));
    draw_flow(&mut gizmos, sim, &world);
    draw_particles(&mut gizmos, &mut overlay, sim, time.delta_secs(), &world);
    draw_springs(&mut gizmos, sim, &world);
}

/// Velocity arrows on a coarse lattice over the domain, the fastest one lattice step long.
fn draw_flow(gizmos: &mut Gizmos, sim: &SliceSim, world: &impl Fn(Vec2) -> Vec3) {
    let fluid = sim.fluid();
    let every = (fluid.n / 24).max(1);
    let lattice = || {
        (every / 2..fluid.n).step_by(every).flat_map(move |j| {
            (every / 2..fluid.n)
                .step_by(every)
                .map(move |i| (Vec2::new(i as f32, j as f32) + 0.5) * fluid.h)
        })
    };
    let fastest = lattice()
        .map(|p| fluid.velocity_at(p).length())
        .fold(1e-6f32, f32::max);
    let scale = every as f32 * fluid.h / fastest;
    for p in lattice() {
        let v = fluid.velocity_at(p) * scale;
        if v.length() > 0.05 * fluid.h {
            gizmos.arrow(world(p), world(p + v), Color::srgba(0.5, 0.9, 1.0, 0.7));
        }
    }
}

/// Passive particles carried by the water, reseeded where they leave the domain.
fn draw_particles(
    gizmos: &mut Gizmos,
    overlay: &mut Overlay,
    sim: &SliceSim,
    dt: f32,
    world: &impl Fn(Vec2) -> Vec3,
) {
    let fluid = sim.fluid();
    let (size, offset) = (fluid.size(), sim.offset());
    let centre = sim.bell_centroid_world();
    let spread = 1.5 * sim.species().diameter;
    while overlay.particles.len() < PARTICLES {
        overlay.seed = overlay
            .seed
            .wrapping_mul(1_664_525)
            .wrapping_add(1_013_904_223);
        let a = (overlay.seed >> 8) as f32 / (1 << 24) as f32;
        overlay.seed = overlay
            .seed
            .wrapping_mul(1_664_525)
            .wrapping_add(1_013_904_223);
        let b = (overlay.seed >> 8) as f32 / (1 << 24) as f32;
        overlay
            .particles
            .push(centre + (Vec2::new(a, b) * 2.0 - 1.0) * spread);
    }
    overlay.particles.retain_mut(|p| {
        let d = *p - offset;
        if !(0.0..size).contains(&d.x) || !(0.0..size).contains(&d.y) {
            return false;
        }
        *p += fluid.velocity_at(d) * dt;
        (*p - centre).length() < 4.0 * spread
    });
    for p in &overlay.particles {
        let at = world(*p - offset);
        gizmos.line(at, at + Vec3::Y * 0.01, Color::srgb(1.0, 0.9, 0.4));
    }
}

/// Every spring of the body, coloured by its tension relative to the largest (on a
/// compressed scale: the muscles are far stiffer than the mesoglea).
fn draw_springs(gizmos: &mut Gizmos, sim: &SliceSim, world: &impl Fn(Vec2) -> Vec3) {
    let body = sim.body();
    let max = body
        .tensions()
        .map(|(_, _, t)| t.abs())
        .fold(1e-9f32, f32::max);
    for (a, b, t) in body.tensions() {
        let s = (t / max).clamp(-1.0, 1.0);
        let s = s.signum() * s.abs().powf(0.3);
        let color = if s >= 0.0 {
            Color::srgb(1.0, 1.0 - s, 1.0 - s)
        } else {
            Color::srgb(1.0 + s, 1.0 + s, 1.0)
        };
        gizmos.line(world(a), world(b), color);
    }
}
