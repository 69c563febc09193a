//! The umbrella: exumbrella and subumbrella discs joined ring to ring into one closed,
//! two-sided surface, with the margin rim between them.
//!
//! Layout per surface (exumbrella first): an apex vertex, then `rings` rings of
//! `segments + 1` vertices from the apex out to the margin; the last vertex of a ring repeats
//! the first (σ = 2π, for UVs) and shares its position and normal.

use super::buffers::SurfaceBuffers;
use super::discs::Disc;
use super::normals::grid_normals;
use super::profile::Profile;
use super::tissue::{band, relative_thickness, ring_thickness};
use super::variation::{Variation, apex_fade};
use glam::{Vec2, Vec3};

/// Vertices of an umbrella with `rings` rings of `segments` segments.
pub fn vertex_count(rings: usize, segments: usize) -> usize {
    2 * surface_len(rings, segments)
}

fn surface_len(rings: usize, segments: usize) -> usize {
    1 + rings * (segments + 1)
}

/// Index of ring `k` (1-based, from the apex), column `j`, on `surface` (0 exumbrella,
/// 1 subumbrella); ring 0 is the apex vertex.
pub(crate) fn vertex(rings: usize, segments: usize, surface: usize, k: usize, j: usize) -> usize {
    let base = surface * surface_len(rings, segments);
    if k == 0 {
        base
    } else {
        base + 1 + (k - 1) * (segments + 1) + j
    }
}

/// Sizes the buffers and writes the fixed part: triangles and UVs. UVs: u = σ/2π; v runs
/// 0 at the exumbrellar apex, 0.5 at the margin, 1 at the subumbrellar apex.
pub(crate) fn write_topology(rings: usize, segments: usize, buf: &mut SurfaceBuffers) {
    let v = |surface, k, j| vertex(rings, segments, surface, k, j);
    buf.reset(vertex_count(rings, segments));
    for surface in 0..2 {
        let outward_up = surface == 0;
        for j in 0..segments {
            let (a, b) = (v(surface, 1, j), v(surface, 1, j + 1));
            if outward_up {
                buf.triangle(v(surface, 0, 0), b, a);
            } else {
                buf.triangle(v(surface, 0, 0), a, b);
            }
            for k in 1..rings {
                let (a, b) = (v(surface, k, j), v(surface, k, j + 1));
                let (c, d) = (v(surface, k + 1, j), v(surface, k + 1, j + 1));
                if outward_up {
                    buf.quad(a, b, c, d);
                } else {
                    buf.quad(a, c, b, d);
                }
            }
        }
        for k in 0..=rings {
            let lat = 0.5 * k as f32 / rings as f32;
            let vv = if outward_up { lat } else { 1.0 - lat };
            for j in 0..=segments {
                let u = if k == 0 {
                    0.5
                } else {
                    j as f32 / segments as f32
                };
                buf.uvs[v(surface, k, j)] = [u, vv];
            }
        }
    }
    // The margin rim: from the exumbrellar margin ring round to the subumbrellar one.
    for j in 0..segments {
        let (a, b) = (v(0, rings, j), v(0, rings, j + 1));
        let (c, d) = (v(1, rings, j), v(1, rings, j + 1));
        buf.quad(a, b, c, d);
    }
}

/// Latitude and angle of each unstructured-noise sample, in the order `write_surface` reads
/// them.
pub fn noise_samples(
    angles: &[(f32, f32)],
    rings: usize,
) -> impl Iterator<Item = (f32, (f32, f32))> {
    (1..=rings).flat_map(move |k| angles.iter().map(move |&cs| (k as f32 / rings as f32, cs)))
}

/// Per-column variation that depends on σ only, precomputed once a frame: the structural
/// lobe and the compression ripple at full strength.
#[derive(Clone, Copy, Debug, Default)]
pub struct Column {
    /// The structural lobe's offset along the mesoglea normal in this column, metres.
    pub lobe: f32,
    /// The compression ripple's offset in this column at full contraction, metres.
    pub ripple: f32,
}

/// Writes positions and normals for the current slice, in place. `noise` holds QP for
/// ring 1 to `rings`, column by column (see [`noise_samples`]).
///
/// Both surfaces of a ring move together along the swept mesoglea normal by the structural
/// and unstructured variation, so the mesoglea keeps its thickness; the exumbrella also
/// takes the compression ripples.
pub(crate) fn write_surface(
    profile: &Profile,
    angles: &[(f32, f32)],
    columns: &[Column],
    noise: &[f32],
    variation: &Variation,
    buf: &mut SurfaceBuffers,
) {
    let (rings, segments) = (profile.pairs.len() - 1, angles.len());
    let v = |surface, k, j| vertex(rings, segments, surface, k, j);
    let mut radial = Vec2::X;
    let mut apex = 0.0;
    for (k, pair) in profile.pairs.iter().enumerate() {
        let sub = Disc::through(pair.subumbrella[0], pair.subumbrella[1], radial);
        let ex = Disc::through(pair.exumbrella[0], pair.exumbrella[1], sub.radial);
        radial = sub.radial;
        let thickness = ring_thickness(&sub, &ex);
        if k == 0 {
            apex = thickness;
        }
        let tissue = [relative_thickness(thickness, apex), band(pair.contraction)];
        for surface in 0..2 {
            let ring = v(surface, k, 0)..=v(surface, k, if k == 0 { 0 } else { segments });
            buf.tissue[ring].fill(tissue);
        }
        if k == 0 {
            let n = sub.normal(pair.normal, (1.0, 0.0));
            set(buf, v(0, 0, 0), ex.centre, n);
            set(buf, v(1, 0, 0), sub.centre, -n);
            continue;
        }
        let fade = apex_fade(pair.latitude);
        let noise = &noise[(k - 1) * segments..][..segments];
        for (j, ((&cs, col), &qp)) in angles.iter().zip(columns).zip(noise).enumerate() {
            let n = sub.normal(pair.normal, cs);
            let shared = col.lobe * fade + variation.unstructured_with(pair.latitude, qp);
            let ripple = col.ripple * fade * pair.contraction;
            set(buf, v(0, k, j), ex.point(cs) + n * (shared + ripple), n);
            set(buf, v(1, k, j), sub.point(cs) + n * shared, -n);
        }
        for surface in 0..2 {
            let (first, seam) = (v(surface, k, 0), v(surface, k, segments));
            buf.positions[seam] = buf.positions[first];
            buf.normals[seam] = buf.normals[first];
        }
    }
    grid_normals(buf, rings, segments);
}

fn set(buf: &mut SurfaceBuffers, i: usize, position: Vec3, normal: Vec3) {
    buf.positions[i] = position.to_array();
    buf.normals[i] = normal.to_array();
}
