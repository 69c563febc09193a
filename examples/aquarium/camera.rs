//! The camera: HDR with bloom, tonemapping and underwater fog; it orbits a point (left
//! drag), pans it (right drag) and zooms (scroll), unless the pointer is on a panel.

use crate::screenshot::OffscreenTarget;
use crate::tank::{SURFACE, WATER};
use bevy::camera::Hdr;
use bevy::core_pipeline::oit::OrderIndependentTransparencySettings;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::pbr::{DistanceFog, FogFalloff};
use bevy::post_process::bloom::Bloom;
use bevy::prelude::*;
use bevy::render::view::Msaa;

#[derive(Component, Debug)]
pub struct Orbit {
    pub target: Vec3,
    pub yaw: f32,
    pub pitch: f32,
    pub distance: f32,
}

impl Orbit {
    pub fn transform(&self) -> Transform {
        let rotation = Quat::from_euler(EulerRot::YXZ, self.yaw, self.pitch, 0.0);
        Transform::from_translation(self.target + rotation * Vec3::Z * self.distance)
            .looking_at(self.target, Vec3::Y)
    }
}

pub fn plugin(app: &mut App) {
    app.add_systems(Startup, spawn)
        .add_systems(Update, control.run_if(not(pointer_over_ui)));
}

/// The mouse belongs to the editor's panels while it is over them or dragging a widget.
#[cfg(feature = "editor")]
fn pointer_over_ui(wants: Option<Res<bevy_egui::input::EguiWantsInput>>) -> bool {
    wants.is_some_and(|w| w.wants_any_pointer_input())
}

#[cfg(not(feature = "editor"))]
fn pointer_over_ui() -> bool {
    false
}

/// Where the camera starts: looking at the middle of the tank from the front.
pub fn home() -> Orbit {
    Orbit {
        target: Vec3::new(0.0, 0.45 * SURFACE, 0.0),
        yaw: 0.0,
        pitch: 0.02,
        distance: 15.0,
    }
}

/// Present: the camera draws translucent surfaces order-independently (`--oit`).
#[derive(Resource)]
pub struct OrderIndependent;

fn spawn(
    mut commands: Commands,
    offscreen: Option<Res<OffscreenTarget>>,
    oit: Option<Res<OrderIndependent>>,
) {
    let orbit = home();
    let mut camera = commands.spawn((
        Camera3d::default(),
        Hdr,
        Tonemapping::TonyMcMapface,
        Bloom::NATURAL,
        DistanceFog {
            color: WATER,
            directional_light_color: Color::srgba(0.3, 0.6, 0.8, 0.3),
            directional_light_exponent: 20.0,
            falloff: FogFalloff::ExponentialSquared { density: 0.05 },
        },
        orbit.transform(),
        orbit,
    ));
    if let Some(offscreen) = offscreen {
        camera.insert(offscreen.0.clone());
    }
    if oit.is_some() {
        // Bevy's OIT does not combine with MSAA.
        camera.insert((OrderIndependentTransparencySettings::default(), Msaa::Off));
    }
}

fn control(
    buttons: Option<Res<ButtonInput<MouseButton>>>,
    keys: Option<Res<ButtonInput<KeyCode>>>,
    motion: Option<Res<AccumulatedMouseMotion>>,
    scroll: Option<Res<AccumulatedMouseScroll>>,
    mut camera: Query<(&mut Orbit, &mut Transform)>,
) {
    let (Some(buttons), Some(motion), Some(scroll)) = (buttons, motion, scroll) else {
        return;
    };
    let Ok((mut orbit, mut transform)) = camera.single_mut() else {
        return;
    };
    // Shift + left drag stirs the water (see `water`), it does not orbit.
    let stirring = keys.is_some_and(|k| k.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]));
    if buttons.pressed(MouseButton::Left) && !stirring {
        orbit.yaw -= motion.delta.x * 0.005;
        orbit.pitch = (orbit.pitch - motion.delta.y * 0.005).clamp(-1.45, 1.45);
    }
    if buttons.pressed(MouseButton::Right) {
        // Move the target in the view plane, by an amount that keeps the point under the
        // cursor roughly fixed.
        let k = orbit.distance * 0.0015;
        let (right, up) = (transform.right(), transform.up());
        orbit.target += (right * -motion.delta.x + up * motion.delta.y) * k;
    }
    if scroll.delta.y != 0.0 {
        orbit.distance = (orbit.distance * (1.0 - 0.1 * scroll.delta.y)).clamp(1.0, 60.0);
    }
    if orbit.is_changed() {
        *transform = orbit.transform();
    }
}
