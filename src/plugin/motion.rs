//! Swimming in the world: each jellyfish moves along its own +Y axis by its slice's swim
//! distance at the time the frame shows, blended between the fixed steps around it.

use super::JellyfishSystems;
use super::components::{JellyfishSlice, SwimMotion};
use bevy::prelude::*;

pub(super) fn plugin(app: &mut App) {
    app.add_systems(
        PostUpdate,
        write_transforms.in_set(JellyfishSystems::WriteTransforms),
    );
}

/// The translation is `anchor + axis · distance`, not a sum of per-frame increments, so it
/// is bit-identical at any frame rate. A transform changed by someone else (steering)
/// moves the anchor: swimming continues from where it was put, along its new axis.
fn write_transforms(
    mut jellyfish: Query<(&JellyfishSlice, &mut SwimMotion, &mut Transform)>,
    time: Res<Time<Fixed>>,
) {
    let (overstep, tick) = (time.overstep().as_secs_f64(), time.timestep().as_secs_f64());
    jellyfish
        .par_iter_mut()
        .for_each(|(slice, mut motion, mut transform)| {
            if slice.sim.is_none() {
                return;
            }
            let distance = slice.history.swim_at(slice.display_time(overstep, tick));
            let along = |tf: &Transform, d: f32| tf.rotation * (tf.scale * Vec3::Y * d);
            if motion.written != Some(*transform) {
                motion.anchor = transform.translation - along(&transform, motion.distance);
            }
            let translation = motion.anchor + along(&transform, distance);
            transform.translation = translation;
            motion.distance = distance;
            motion.written = Some(*transform);
        });
}
