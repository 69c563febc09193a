//! Touch: a [`Disturbance`] in the water makes the jellyfish within its reach flash in
//! their species' colour ([`Flash`]) and escape (deeper, quicker strokes through the
//! slice's own muscles, `SliceSim::escape`); neighbours echo a flash after a short delay,
//! at most half as bright.
//!
//! Disturbances are felt after the frame's steps ([`JellyfishSystems::Touch`]), when
//! every slice has taken the steps that end at or before the frame's time, and where each
//! jellyfish is at its newest step: an escape then starts at the same fixed step, as
//! strongly, however the time before was split into frames. A far
//! jellyfish replays its species' recorded cycle at the escape's quicker rhythm (not the
//! deeper stroke, which only a live slice has).

mod flash;

pub use flash::{FLASH_RISE, Flash};

use super::jellyfish::Jellyfish;
use super::schedule::JellyfishSystems;
use super::slice::JellyfishSlice;
use super::swimming::SwimMotion;
use bevy::prelude::*;

/// Flashes and escapes when the water is disturbed; echoes between neighbours.
#[derive(Clone, Copy, Debug, Default)]
pub struct TouchPlugin;

impl Plugin for TouchPlugin {
    fn build(&self, app: &mut App) {
        app.register_required_components::<Jellyfish, Flash>()
            .register_type::<Flash>()
            .register_type::<Disturbance>()
            .add_message::<Disturbance>()
            .init_resource::<Echoes>()
            .add_systems(
                PostUpdate,
                (feel_disturbances, echo, flash::fade)
                    .chain()
                    .in_set(JellyfishSystems::Touch),
            );
    }
}

/// A touch in the water at a world `point`: every jellyfish whose bell centre is within
/// `radius` plus its species' `touch_reach` (in its own bell diameters) of it feels it,
/// the more the nearer, flashes and escapes. Send it as a message
/// (`MessageWriter<Disturbance>`); the tank's stirs send their own. One with a point,
/// strength or radius that is not finite is refused with a warning.
#[derive(Message, Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Disturbance {
    /// Where, in world space.
    pub point: Vec3,
    /// How strong, 0 to 1 (more is taken as 1).
    pub strength: f32,
    /// How far the disturbance itself spreads, world units (0 for a point, a stir's
    /// radius for a stir).
    pub radius: f32,
}

impl Disturbance {
    /// A touch at a point.
    pub fn touch(point: Vec3, strength: f32) -> Self {
        Self {
            point,
            strength,
            radius: 0.0,
        }
    }

    /// Why it cannot be felt, if it cannot.
    fn refused(&self) -> Option<&'static str> {
        if !self.point.is_finite() {
            Some("its point is not finite")
        } else if !self.strength.is_finite() {
            Some("its strength is not finite")
        } else if !self.radius.is_finite() || self.radius < 0.0 {
            Some("its radius is not finite and at least 0")
        } else {
            None
        }
    }

    /// How strongly a bell centred at `at`, reaching `reach` world units, feels it: 1 at
    /// the point (times the strength), falling to 0 at the reach's edge.
    fn felt_at(&self, at: Vec3, reach: f32) -> f32 {
        let d = (at.distance(self.point) - self.radius).max(0.0);
        let near = (1.0 - d / reach.max(1e-9)).clamp(0.0, 1.0);
        self.strength.clamp(0.0, 1.0) * near
    }
}

/// Flashes owed to neighbours: when, who, how bright and from where (world).
#[derive(Resource, Default)]
pub(crate) struct Echoes(Vec<(f64, Entity, f32, Vec3)>);

/// One jellyfish as touch sees it.
type Touched = (
    Entity,
    &'static mut JellyfishSlice,
    &'static mut Flash,
    Stepped,
);

/// What says where a jellyfish is at its newest step (see [`stepped_at`]).
type Stepped = (
    &'static Transform,
    &'static SwimMotion,
    Option<&'static ChildOf>,
);

/// Where a jellyfish is in the world at its newest step: the pose its last step left
/// (`SwimMotion::pose`), in its parent's frame if it has one. The drawn
/// `GlobalTransform` is the previous frame's, between older steps, so a touch at a fixed
/// point felt against it would weigh more or less with the frame's length; the newest
/// step is the same however the time was split into frames.
fn stepped_at(
    (transform, motion, parent): (&Transform, &SwimMotion, Option<&ChildOf>),
    parents: &Query<&GlobalTransform>,
) -> GlobalTransform {
    let local = Transform {
        translation: motion.pose.position,
        rotation: motion.pose.rotation,
        scale: transform.scale,
    };
    match parent.and_then(|p| parents.get(p.parent()).ok()) {
        Some(parent) => parent.mul_transform(local),
        None => GlobalTransform::from(local),
    }
}

/// Reads the frame's disturbances: who feels each, in entity order.
pub(crate) fn feel_disturbances(
    mut disturbances: MessageReader<Disturbance>,
    mut jellyfish: Query<Touched>,
    parents: Query<&GlobalTransform>,
    mut echoes: ResMut<Echoes>,
    time: Res<Time<Virtual>>,
) {
    let now = time.elapsed_secs_f64();
    for d in disturbances.read() {
        if let Some(why) = d.refused() {
            warn!("jellyfish: a disturbance was refused: {why} ({d:?})");
            continue;
        }
        let mut felt: Vec<(Entity, f32)> = Vec::new();
        for (entity, mut slice, mut flash, stepped) in &mut jellyfish {
            let Some(reach) = slice.species().map(|s| s.touch_reach * s.diameter) else {
                continue;
            };
            let at = &stepped_at(stepped, &parents);
            let strength = d.felt_at(at.translation(), reach * world_scale(at));
            if strength <= 0.0 {
                continue;
            }
            slice.escape(strength);
            let species = &slice.species;
            if flash.start(species, now, strength, d.point, at) {
                felt.push((entity, species.flash * strength));
            }
        }
        felt.sort_by_key(|f| f.0);
        for (source, peak) in felt {
            owe_echoes(source, peak, &jellyfish, &parents, &mut echoes, now);
        }
    }
}

/// The neighbours within the flasher's `echo_reach` owe it an echo, at most half as
/// bright, fading with distance, after its `echo_delay`.
fn owe_echoes(
    source: Entity,
    peak: f32,
    jellyfish: &Query<Touched>,
    parents: &Query<&GlobalTransform>,
    echoes: &mut Echoes,
    now: f64,
) {
    let Ok((_, slice, _, stepped)) = jellyfish.get(source) else {
        return;
    };
    let at = &stepped_at(stepped, parents);
    let Some(species) = slice.species() else {
        return;
    };
    let reach = species.echo_reach * species.diameter * world_scale(at);
    if reach <= 0.0 || peak <= 0.0 {
        return;
    }
    let (from, due) = (at.translation(), now + species.echo_delay as f64);
    for (entity, _, _, other) in jellyfish.iter() {
        let d = stepped_at(other, parents).translation().distance(from);
        if entity != source && d < reach {
            let brightness = ECHO_SHARE * peak * (1.0 - d / reach);
            echoes.0.push((due, entity, brightness, from));
        }
    }
}

/// An echo's brightness at most, as a share of the flash it answers.
pub const ECHO_SHARE: f32 = 0.5;

/// Flashes the echoes that are due (they escape no one, and echo no further).
fn echo(
    mut echoes: ResMut<Echoes>,
    mut jellyfish: Query<Touched>,
    parents: Query<&GlobalTransform>,
    time: Res<Time<Virtual>>,
) {
    let now = time.elapsed_secs_f64();
    if echoes.0.is_empty() {
        return;
    }
    echoes
        .0
        .sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let due = echoes.0.partition_point(|e| e.0 <= now);
    for (_, entity, brightness, from) in echoes.0.drain(..due) {
        if let Ok((_, slice, mut flash, stepped)) = jellyfish.get_mut(entity)
            && let Some(species) = slice.species()
            && species.flash > 0.0
        {
            let strength = brightness / species.flash;
            flash.start(species, now, strength, from, &stepped_at(stepped, &parents));
        }
    }
}

/// A jellyfish's size in the world: its transform's scale along its axis.
fn world_scale(at: &GlobalTransform) -> f32 {
    at.affine().matrix3.y_axis.length()
}
