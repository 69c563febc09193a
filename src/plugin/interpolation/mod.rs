//! The frame between fixed steps: each jellyfish's last few slice steps
//! ([`SliceHistory`]), blended at the time the frame shows into its `Transform` here and
//! into its meshes by the render part; a game's own moves of the `Transform` carried into
//! the travel.

mod history;
mod snapshot;

pub(crate) use history::SliceHistory;
pub(crate) use snapshot::Snapshot;

use super::jellyfish::Jellyfish;
use super::schedule::JellyfishSystems;
use super::swimming::{Pose, SwimMotion, TentacleGuides};
use bevy::prelude::*;

/// Keeps each jellyfish's recent steps and writes its `Transform` between them.
#[derive(Clone, Copy, Debug, Default)]
pub struct InterpolationPlugin;

impl Plugin for InterpolationPlugin {
    fn build(&self, app: &mut App) {
        app.register_required_components::<Jellyfish, SliceHistory>()
            .add_systems(
                PostUpdate,
                write_transforms.in_set(JellyfishSystems::WriteTransforms),
            );
    }
}

/// The translation and rotation are the poses recorded at slice steps, blended, not a sum
/// of per-frame increments, so a frame rate changes nothing but how often they are drawn.
/// A `Transform` changed by someone else since the plugin wrote it (a game's teleport or
/// turn) moves the travel and every stored pose with it; the fringe stays in the water
/// and is dragged after it (a jump of a few tentacle lengths starts it afresh).
fn write_transforms(
    mut jellyfish: Query<(
        &mut SliceHistory,
        &mut SwimMotion,
        &mut Transform,
        Option<&mut TentacleGuides>,
    )>,
) {
    jellyfish
        .par_iter_mut()
        .for_each(|(mut history, mut motion, mut transform, guides)| {
            if history.newest().is_none() {
                return;
            }
            if let Some(written) = motion.written
                && written != *transform
            {
                let (from, to) = (Pose::of(&written), Pose::of(&transform));
                history.move_poses(from, to);
                let moved = motion.pose.moved(from, to);
                if let Some(mut guides) = guides {
                    guides.moved(motion.pose, moved, transform.scale);
                }
                motion.pose = moved;
                // Moved elsewhere: the water a far jellyfish held is not where it is now.
                motion.held_water = None;
            }
            let Some(pose) = history.shown_pose() else {
                return;
            };
            transform.translation = pose.position;
            transform.rotation = pose.rotation;
            motion.written = Some(*transform);
        });
}
