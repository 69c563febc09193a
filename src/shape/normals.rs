//! Smooth umbrella normals from its ring grid.
//!
//! The closed umbrella is one sheet of rings between two apex vertices: exumbrella rings from
//! the apex out to the margin, over the rim, subumbrella rings back in to its apex. A vertex's
//! normal is the cross product of its central differences around and along that sheet:
//! smooth across the seam (rings wrap) and over the margin, and a quarter of the cost of
//! summing triangle normals, which was the largest part of a frame. Where the differences
//! vanish (a collapsed slice), and at the two apexes, the analytic normal already in the
//! buffer stays. The template meshes' vertex shader computes the same differences.

use super::buffers::SurfaceBuffers;
use super::umbrella::vertex;
use glam::Vec3;

/// Overwrites the umbrella's normals; the buffer holds `rings` × `segments` per surface.
pub(crate) fn grid_normals(buf: &mut SurfaceBuffers, rings: usize, segments: usize) {
    let sheet = 2 * rings as isize;
    // First vertex of sheet ring `l` and its stride along the ring: -1 and `sheet` are the
    // two apexes, one vertex each.
    let row = |l: isize| match l {
        l if l < 0 => (vertex(rings, segments, 0, 0, 0), 0),
        l if l >= sheet => (vertex(rings, segments, 1, 0, 0), 0),
        l if (l as usize) < rings => (vertex(rings, segments, 0, l as usize + 1, 0), 1),
        l => (vertex(rings, segments, 1, (sheet - l) as usize, 0), 1),
    };
    let positions = &buf.positions;
    let normals = &mut buf.normals;
    let p = |i: usize| Vec3::from_array(positions[i]);
    for l in 0..sheet {
        let ((here, _), (up, us), (down, ds)) = (row(l), row(l - 1), row(l + 1));
        for j in 0..segments {
            let next = if j + 1 == segments { 0 } else { j + 1 };
            let prev = if j == 0 { segments - 1 } else { j - 1 };
            let around = p(here + next) - p(here + prev);
            let along = p(down + ds * j) - p(up + us * j);
            keep(normals, here + j, around.cross(along));
        }
        // The seam twin (σ = 2π) shares the first vertex's normal.
        normals[here + segments] = normals[here];
    }
    // The apexes keep the analytic normal (the swept mesoglea normal, along the axis):
    // where every ring meets, the grid has no "around".
}

/// Writes `n` normalised at `i`, unless it has no direction: then the normal there stays.
/// (A vector whose square is subnormal has none that normalises to unit length: the cross
/// product of two steps of a slice collapsed to a point.)
fn keep(normals: &mut [[f32; 3]], i: usize, n: Vec3) {
    if n.length_squared() >= f32::MIN_POSITIVE {
        normals[i] = n.normalize().to_array();
    }
}
