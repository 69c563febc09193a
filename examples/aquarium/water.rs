//! The tank's own water: a coarse grid the jellyfish swim in, pushed by their jets and by
//! the mouse (Shift + left drag), and a scripted stir for pictures (`--stir`). Ctrl + left
//! click touches the jellyfish under the cursor.

use crate::camera::Orbit;
use crate::tank::{HALF_DEPTH, HALF_WIDTH, SURFACE};
use bevy::input::mouse::AccumulatedMouseMotion;
use bevy::prelude::*;
use bevy_jellyfish::Jellyfish;
use bevy_jellyfish::plugin::{Disturbance, JellyfishSystems, TankWater};

/// The water's cells, scene units: coarse, a fraction of a millisecond a tick.
const CELL: f32 = 0.75;
/// How far a stir reaches, scene units.
pub const STIR_RADIUS: f32 = 2.0;

/// A stir at a fixed place and tick, for pictures that show the water moving.
#[derive(Resource, Clone, Copy, Debug)]
pub struct ScriptedStir {
    pub tick: u64,
    pub at: Vec3,
    pub velocity: Vec3,
}

impl ScriptedStir {
    /// Two seconds in, across the middle of the tank.
    #[allow(dead_code)] // the example's `--stir`; the render test includes this module too
    pub fn across_the_middle() -> Self {
        Self {
            tick: 128,
            at: Vec3::new(-1.5, 0.45 * SURFACE, 0.0),
            velocity: Vec3::new(4.0, 0.8, 0.0),
        }
    }
}

pub fn tank_water() -> TankWater {
    TankWater::new(
        Vec3::new(-HALF_WIDTH, 0.0, -HALF_DEPTH),
        Vec3::new(HALF_WIDTH, SURFACE, HALF_DEPTH),
        CELL,
    )
}

pub fn plugin(app: &mut App) {
    app.insert_resource(tank_water())
        .add_systems(
            FixedUpdate,
            // Stirred before the water steps, in every run the same tick.
            scripted_stir.before(JellyfishSystems::StepWater),
        )
        .add_systems(Update, (mouse_stir, mouse_touch));
}

fn scripted_stir(
    stir: Option<Res<ScriptedStir>>,
    mut tank: ResMut<TankWater>,
    mut ticks: Local<u64>,
) {
    *ticks += 1;
    if let Some(stir) = stir
        && *ticks == stir.tick
    {
        // Three pushes along a line: a stroke of the hand, not a point.
        for k in 0..3 {
            let along = stir.velocity.normalize_or_zero() * (k as f32 - 1.0) * STIR_RADIUS;
            tank.stir(stir.at + along, STIR_RADIUS, stir.velocity);
        }
    }
}

/// Shift + left drag pushes the water under the cursor the way the mouse moves, in the
/// plane through the point the camera orbits.
fn mouse_stir(
    buttons: Option<Res<ButtonInput<MouseButton>>>,
    keys: Option<Res<ButtonInput<KeyCode>>>,
    motion: Option<Res<AccumulatedMouseMotion>>,
    windows: Query<&Window>,
    cameras: Query<(&Camera, &GlobalTransform, &Orbit)>,
    mut tank: ResMut<TankWater>,
    time: Res<Time>,
) {
    let (Some(buttons), Some(keys), Some(motion)) = (buttons, keys, motion) else {
        return;
    };
    let shift = keys.any_pressed([KeyCode::ShiftLeft, KeyCode::ShiftRight]);
    if !shift || !buttons.pressed(MouseButton::Left) || motion.delta == Vec2::ZERO {
        return;
    }
    let (Ok(window), Ok((camera, at, orbit))) = (windows.single(), cameras.single()) else {
        return;
    };
    let Some(cursor) = window.cursor_position() else {
        return;
    };
    let Ok(ray) = camera.viewport_to_world(at, cursor) else {
        return;
    };
    let normal = at.forward();
    let Some(distance) = ray.intersect_plane(orbit.target, InfinitePlane3d::new(*normal)) else {
        return;
    };
    let point = ray.get_point(distance);
    // Pixels to scene units at that distance, per second of drag.
    let k = orbit.distance * 0.0015 / time.delta_secs().max(1e-3);
    let velocity = (at.right() * motion.delta.x - at.up() * motion.delta.y) * k;
    tank.stir(point, STIR_RADIUS, velocity.clamp_length_max(8.0));
}

/// Ctrl + left click touches the jellyfish nearest the cursor's ray, at the ray's point
/// nearest its centre: it flashes (if its species luminesces) and escapes.
fn mouse_touch(
    buttons: Option<Res<ButtonInput<MouseButton>>>,
    keys: Option<Res<ButtonInput<KeyCode>>>,
    windows: Query<&Window>,
    cameras: Query<(&Camera, &GlobalTransform)>,
    jellyfish: Query<&GlobalTransform, With<Jellyfish>>,
    mut touches: MessageWriter<Disturbance>,
) {
    let (Some(buttons), Some(keys)) = (buttons, keys) else {
        return;
    };
    let ctrl = keys.any_pressed([KeyCode::ControlLeft, KeyCode::ControlRight]);
    if !ctrl || !buttons.just_pressed(MouseButton::Left) {
        return;
    }
    let (Ok(window), Ok((camera, at))) = (windows.single(), cameras.single()) else {
        return;
    };
    let Some(ray) = window
        .cursor_position()
        .and_then(|cursor| camera.viewport_to_world(at, cursor).ok())
    else {
        return;
    };
    let nearest_on_ray = |p: Vec3| ray.get_point((p - ray.origin).dot(*ray.direction).max(0.0));
    let nearest = jellyfish.iter().map(|j| j.translation()).min_by(|a, b| {
        let d = |p: Vec3| p.distance_squared(nearest_on_ray(p));
        d(*a).total_cmp(&d(*b))
    });
    if let Some(centre) = nearest {
        touches.write(Disturbance::touch(nearest_on_ray(centre), 1.0));
    }
}
