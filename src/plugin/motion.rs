//! Drawing the jellyfish where it is: its `Transform` blended between the poses of the
//! slice steps around the frame's time, and a game's own moves of the `Transform` carried
//! into the travel.

use super::JellyfishSystems;
use super::components::{JellyfishSlice, Pose, SwimMotion};
use bevy::prelude::*;

pub(super) fn plugin(app: &mut App) {
    app.add_systems(
        PostUpdate,
        write_transforms.in_set(JellyfishSystems::WriteTransforms),
    );
}

/// The translation and rotation are the poses recorded at slice steps, blended, not a sum
/// of per-frame increments, so a frame rate changes nothing but how often they are drawn.
/// A `Transform` changed by someone else since the plugin wrote it (a game's teleport or
/// turn) moves the travel and every stored pose with it.
fn write_transforms(mut jellyfish: Query<(&mut JellyfishSlice, &mut SwimMotion, &mut Transform)>) {
    jellyfish
        .par_iter_mut()
        .for_each(|(mut slice, mut motion, mut transform)| {
            if !slice.started() {
                return;
            }
            if let Some(written) = motion.written
                && written != *transform
            {
                let (from, to) = (Pose::of(&written), Pose::of(&transform));
                slice.history.move_poses(from, to);
                motion.pose = motion.pose.moved(from, to);
            }
            let Some(pose) = slice.history.pose_at(slice.display_time()) else {
                return;
            };
            transform.translation = pose.position;
            transform.rotation = pose.rotation;
            motion.written = Some(*transform);
        });
}
