//! Bounds from the slice, and no meshing for what no camera sees.
//!
//! A jellyfish's bounds come from its blended slice (a few dozen points), not from its
//! mesh (thousands of vertices): the entities carry `NoAutoAabb`, so Bevy neither rescans
//! the vertices nor recomputes the box; it culls with ours. The plugin skips the mesh of
//! a jellyfish outside every active camera's frustum; its slice keeps running, and the
//! mesh is rebuilt the frame it comes back into view.

use crate::plugin::interpolation::Snapshot;
use crate::sim::cycle::Reach;
use crate::species::Species;
use bevy::camera::primitives::{Aabb, Frustum};
use bevy::math::Affine3A;
use bevy::prelude::*;

/// How much wider than the bounds the view test looks: the transform it reads is the
/// previous frame's, and a jellyfish moves a little in a frame.
const VIEW_MARGIN: f32 = 1.25;

/// The mesh's bounds in its local frame (metres, origin at the bell's centroid, y along
/// the axis): every slice point swept around the axis, plus the wall, the surface
/// variation and the tentacles' radius or the oral arms' width.
pub(crate) fn slice_bounds(shape: &Snapshot, species: &Species) -> Aabb {
    let pad = species.thickness
        * (1.0 + species.structural_scale + species.compression_scale + species.unstructured_scale)
        + species.tentacle_radius.max(
            species.manubrium_radius * 1.5
                + species.oral_arm_width * (0.5 + species.oral_arm_frill),
        );
    let Some(Reach { radius, low, high }) = shape.reach() else {
        return Aabb::default();
    };
    let r = radius + pad;
    Aabb::from_min_max(Vec3::new(-r, low - pad, -r), Vec3::new(r, high + pad, r))
}

/// Whether any of `frusta` sees `bounds` at `world_from_local`; with no camera at all
/// (headless tools), everything counts as seen.
pub(crate) fn seen(frusta: &[Frustum], bounds: &Aabb, world_from_local: &Affine3A) -> bool {
    if frusta.is_empty() {
        return true;
    }
    let wider = Aabb {
        center: bounds.center,
        half_extents: bounds.half_extents * VIEW_MARGIN,
    };
    frusta
        .iter()
        .any(|f| f.intersects_obb(&wider, world_from_local, true, true))
}

/// The frusta of the active cameras.
pub(crate) fn active_frusta(cameras: &Query<(&Camera, &Frustum)>) -> Vec<Frustum> {
    cameras
        .iter()
        .filter(|(camera, _)| camera.is_active)
        .map(|(_, frustum)| *frustum)
        .collect()
}
