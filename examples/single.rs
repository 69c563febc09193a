//! One jellyfish, an orbit camera and a debug overlay of its slice.
//!
//! `cargo run --release --features examples --example single -- [aurelia|aequorea|sarsia]`
//!
//! Drag with the left mouse button to orbit, scroll to zoom. `D` toggles the library's
//! debug overlay (`JellyfishDebugPlugin`), drawn in the slice's plane through the bell:
//! fluid velocity arrows, trace particles carried by the water (the paper's Fig. 6), the
//! body's springs coloured by tension (blue compressed, red stretched), and the
//! jellyfish's reach coloured by its level of detail. The diagnostics log prints
//! simulation and meshing time.

#[path = "common/species.rs"]
mod common;

use bevy::diagnostic::{FrameTimeDiagnosticsPlugin, LogDiagnosticsPlugin};
use bevy::gizmos::config::GizmoConfigStore;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::platform::collections::HashSet;
use bevy::prelude::*;
use bevy_jellyfish::plugin::{JellyfishDebugPlugin, JellyfishGizmos, ShowSlice};
use bevy_jellyfish::{Jellyfish, JellyfishDiagnostics, JellyfishPlugin, Species};

/// Scene units per metre: a 40 mm bell is one unit across.
const SCALE: f32 = 25.0;

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
            JellyfishDebugPlugin,
            FrameTimeDiagnosticsPlugin::default(),
            LogDiagnosticsPlugin::filtered(HashSet::from_iter([
                JellyfishDiagnostics::SIMULATION,
                JellyfishDiagnostics::MESHING,
            ])),
        ))
        .insert_resource(ClearColor(Color::srgb(0.01, 0.03, 0.07)))
        .insert_resource(SpeciesFile(format!("species/{name}.species.ron")))
        .add_systems(Startup, (setup, hide_overlay))
        .add_systems(Update, (orbit, toggle_overlay).chain())
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

fn setup(mut commands: Commands, assets: Res<AssetServer>, file: Res<SpeciesFile>) {
    let species: Handle<Species> = assets.load(file.0.clone());
    commands.spawn((
        Jellyfish::new(species).with_phase(0.0),
        Transform::from_scale(Vec3::splat(SCALE)),
        ShowSlice,
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

/// `D` shows or hides the library's overlay (`JellyfishDebugPlugin`).
fn toggle_overlay(keys: Res<ButtonInput<KeyCode>>, mut store: ResMut<GizmoConfigStore>) {
    if keys.just_pressed(KeyCode::KeyD) {
        let (config, _) = store.config_mut::<JellyfishGizmos>();
        config.enabled = !config.enabled;
    }
}

/// The overlay starts hidden.
fn hide_overlay(mut store: ResMut<GizmoConfigStore>) {
    store.config_mut::<JellyfishGizmos>().0.enabled = false;
}
