//! Tentacles: the slice's two tentacle chains swept around the 3D aperture with the same
//! disc scheme as the bell, as closed tubes.
//!
//! Each chain is resampled to `points` positions by arc index; the pair of chain points at
//! the same fraction defines a disc, and tentacle `k` takes the point at σ_k = 2πk/count, so
//! tentacle 0 is the right chain and, for an even count, tentacle count/2 the left one.
//! Layout per tentacle: a root cap vertex, `points` rings of `sides + 1` vertices (the last
//! repeats the first, for UVs), a tip cap vertex.

use super::buffers::SurfaceBuffers;
use super::discs::{Disc, angles};
use super::profile::RingPair;
use super::spline::catmull_rom;
use super::tissue::taper;
use super::variation::Variation;
use crate::sim::guides::Trail;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// Tube and count of the tentacle surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TentacleLayout {
    /// Tentacles around the margin.
    pub count: usize,
    /// Sides of each tentacle's tube.
    pub sides: usize,
    /// Rings along each tentacle, root to tip (at least 2).
    pub points: usize,
}

impl TentacleLayout {
    fn per_tentacle(&self) -> usize {
        2 + self.points * (self.sides + 1)
    }

    /// Vertices of all tentacles with chains of `points` points.
    pub fn vertex_count(&self) -> usize {
        self.count * self.per_tentacle()
    }

    pub(crate) fn ring(&self, t: usize, m: usize, i: usize) -> usize {
        t * self.per_tentacle() + 1 + m * (self.sides + 1) + i
    }

    pub(crate) fn root(&self, t: usize) -> usize {
        t * self.per_tentacle()
    }

    pub(crate) fn tip(&self, t: usize) -> usize {
        self.root(t) + self.per_tentacle() - 1
    }
}

/// Writes the triangles and UVs (u around the tube, v root to tip) of `layout`'s tubes,
/// numbering their vertices from `first`, into buffers already sized for them.
pub(crate) fn write_topology(layout: &TentacleLayout, first: usize, buf: &mut SurfaceBuffers) {
    let l = layout;
    let ring = |t, m, i| first + l.ring(t, m, i);
    let root = |t| first + l.root(t);
    let tip = |t| first + l.tip(t);
    for t in 0..l.count {
        for i in 0..l.sides {
            buf.triangle(root(t), ring(t, 0, i + 1), ring(t, 0, i));
            for m in 0..l.points - 1 {
                let (a, b) = (ring(t, m, i), ring(t, m, i + 1));
                buf.quad(a, b, ring(t, m + 1, i), ring(t, m + 1, i + 1));
            }
            let last = l.points - 1;
            buf.triangle(ring(t, last, i), ring(t, last, i + 1), tip(t));
        }
        buf.uvs[root(t)] = [0.5, 0.0];
        buf.uvs[tip(t)] = [0.5, 1.0];
        for m in 0..l.points {
            for i in 0..=l.sides {
                let uv = [i as f32 / l.sides as f32, m as f32 / (l.points - 1) as f32];
                buf.uvs[ring(t, m, i)] = uv;
            }
        }
    }
}

/// Latitude offset of the second (sideways) noise channel: far enough along the field to
/// be uncorrelated with the first.
pub const SIDEWAYS: f32 = 7.3;

/// Latitude and angle of each noise sample, tentacle by tentacle, root to tip, two per
/// point: latitude runs on from 1 at the margin to 2 at the tip, and again offset by
/// [`SIDEWAYS`] for the sideways channel.
pub fn noise_samples(layout: &TentacleLayout) -> impl Iterator<Item = (f32, (f32, f32))> {
    let l = *layout;
    (0..l.count).flat_map(move |t| {
        let (sin, cos) = (TAU * t as f32 / l.count as f32).sin_cos();
        (0..l.points).flat_map(move |m| {
            let lat = 1.0 + m as f32 / (l.points - 1) as f32;
            [(lat, (cos, sin)), (lat + SIDEWAYS, (cos, sin))]
        })
    })
}

/// Per-frame scratch: the chain discs and one tentacle's centreline.
#[derive(Clone, Debug, Default)]
pub struct TentacleScratch {
    discs: Vec<Disc>,
    centre: Vec<Vec3>,
    tangent: Vec<Vec3>,
    /// `(cos φ, sin φ)` around the tube.
    around: Vec<(f32, f32)>,
}

/// The discs a tentacle ring sweeps, root to tip, from the slice's two chains (an empty
/// chain hangs from its margin point `roots` with zero length), and the aperture's disc.
pub fn chain_discs(
    layout: &TentacleLayout,
    chains: [&[Vec2]; 2],
    roots: [Vec2; 2],
    margin: &RingPair,
    out: &mut Vec<Disc>,
) -> Disc {
    let chains = [0, 1].map(|side| {
        if chains[side].is_empty() {
            std::slice::from_ref(&roots[side])
        } else {
            chains[side]
        }
    });
    let aperture = super::mesh::aperture_disc(margin);
    out.clear();
    let mut radial = aperture.radial;
    for m in 0..layout.points {
        let at = |c: &[Vec2]| catmull_rom(c, fraction(layout, m) * (c.len() - 1) as f32);
        let disc = Disc::through(at(chains[0]), at(chains[1]), radial);
        radial = disc.radial;
        out.push(disc);
    }
    aperture
}

/// Where the slice draws each guide chain's tentacle (`sim::guides`): for `guides`
/// angles `GuideChains::angle`, `GUIDE_NODES` points from the root down the chain discs
/// (as [`chain_discs`] sweeps them), relative to `origin` (the bell's centroid), guide by
/// guide. Without variation: the guides carry the water, the noise is drawn on top.
pub fn guide_reference(
    chains: [&[Vec2]; 2],
    roots: [Vec2; 2],
    origin: Vec2,
    guides: usize,
    out: &mut Vec<Vec3>,
) {
    use crate::sim::guides::{GUIDE_NODES, GuideChains};
    let chains = [0, 1].map(|side| {
        if chains[side].is_empty() {
            std::slice::from_ref(&roots[side])
        } else {
            chains[side]
        }
    });
    let mut radial = Disc::through(roots[0], roots[1], Vec2::X).radial;
    let origin = Vec3::new(origin.x, origin.y, 0.0);
    let mut discs = [Disc::through(roots[0], roots[1], radial); GUIDE_NODES];
    for (m, disc) in discs.iter_mut().enumerate() {
        let f = m as f32 / (GUIDE_NODES - 1) as f32;
        let at = |c: &[Vec2]| linear(c, f * (c.len() - 1) as f32);
        *disc = Disc::through(at(chains[0]), at(chains[1]), radial);
        radial = disc.radial;
    }
    out.clear();
    for g in 0..guides {
        let (sin, cos) = GuideChains::angle(g, guides).sin_cos();
        out.extend(discs.iter().map(|d| d.point((cos, sin)) - origin));
    }
}

/// The point at index `u` of a polyline, straight between its points.
pub(crate) fn linear(points: &[Vec2], u: f32) -> Vec2 {
    let i = (u.max(0.0) as usize).min(points.len().saturating_sub(2));
    match points.get(i + 1) {
        Some(next) => points[i].lerp(*next, u - i as f32),
        None => points[0],
    }
}

/// The point at `fraction` of the way down the chain's discs (0 the root, 1 the tip), at
/// angle `cs` around the axis: a tentacle drawn shorter than the chain stops between two
/// of its discs.
pub fn along(discs: &[Disc], fraction: f32, cs: (f32, f32)) -> Vec3 {
    let x = fraction * (discs.len() - 1) as f32;
    let i = (x as usize).min(discs.len() - 2);
    let (a, b) = (discs[i].point(cs), discs[i + 1].point(cs));
    a + (b - a) * (x - i as f32)
}

/// How far along its tentacle ring `m` lies, 0 at the root, 1 at the tip.
fn fraction(layout: &TentacleLayout, m: usize) -> f32 {
    m as f32 / (layout.points - 1) as f32
}

/// Writes positions and (analytic, tube-radial) normals in place.
///
/// `chains` are the slice's left and right chains (see [`chain_discs`]), `trail` the
/// guides' offsets in the water the slice does not see. `noise` holds QP per
/// [`noise_samples`]. Each centreline moves with the margin above it (structural and
/// unstructured variation along the margin's mesoglea normal), the noise running on down
/// the tentacle; a second channel, zero at the root, sways it sideways, so tentacles wave
/// across the view as well as along it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_surface(
    layout: &TentacleLayout,
    chains: [&[Vec2]; 2],
    trail: &Trail,
    roots: [Vec2; 2],
    margin: &RingPair,
    radius: f32,
    noise: &[f32],
    variation: &Variation,
    buf: &mut SurfaceBuffers,
    s: &mut TentacleScratch,
) {
    let l = layout;
    let aperture = chain_discs(l, chains, roots, margin, &mut s.discs);
    angles(l.sides, &mut s.around);
    for t in 0..l.count {
        let sigma = TAU * t as f32 / l.count as f32;
        let (sin, cos) = sigma.sin_cos();
        let cs = (cos, sin);
        let normal = aperture.normal(margin.normal, cs);
        let lobe = variation.structural(sigma, 1.0);
        let sideways = aperture.direction((-sin, cos));
        let noise = &noise[2 * t * l.points..][..2 * l.points];
        let reach = variation.tentacle_reach(t);
        s.centre.clear();
        for (m, qp) in noise.chunks_exact(2).enumerate() {
            let c = lobe + variation.unstructured_with(1.0, qp[0]);
            let side = variation.unstructured_with(fraction(l, m), qp[1]);
            let drawn = fraction(l, m) * reach;
            let on_chain = along(&s.discs, drawn, cs) + trail.at(sigma, drawn);
            s.centre.push(on_chain + normal * c + sideways * side);
        }
        tangents(&s.centre, &mut s.tangent);
        let outward = aperture.direction(cs);
        for m in 0..l.points {
            let tm = s.tangent[m];
            let n = across(outward, tm);
            let b = tm.cross(n);
            let thin = taper(fraction(l, m));
            for (i, &(cp, sp)) in s.around.iter().enumerate() {
                let out = cp * n + sp * b;
                let v = l.ring(t, m, i);
                buf.positions[v] = (s.centre[m] + radius * thin * out).to_array();
                buf.normals[v] = out.to_array();
                buf.tissue[v] = [thin, 0.0];
            }
            let (first, seam) = (l.ring(t, m, 0), l.ring(t, m, l.sides));
            buf.positions[seam] = buf.positions[first];
            buf.normals[seam] = buf.normals[first];
            buf.tissue[seam] = buf.tissue[first];
        }
        let last = l.points - 1;
        let (root, tip) = (s.tangent[0], s.tangent[last]);
        let tip_radius = radius * taper(1.0);
        buf.positions[l.root(t)] = (s.centre[0] - radius * root).to_array();
        buf.normals[l.root(t)] = (-root).to_array();
        buf.tissue[l.root(t)] = [1.0, 0.0];
        buf.positions[l.tip(t)] = (s.centre[last] + tip_radius * tip).to_array();
        buf.normals[l.tip(t)] = tip.to_array();
        buf.tissue[l.tip(t)] = [taper(1.0), 0.0];
    }
}

/// The tube's frame at a ring: `outward` (the aperture's radial direction at the
/// tentacle) made perpendicular to the tangent, so the tube's seam faces out from the
/// bell along its whole length. Each ring's frame depends on that ring alone, so the GPU
/// builds any vertex without walking the tentacle; where the tentacle runs along
/// `outward` a fixed perpendicular stands in.
pub fn across(outward: Vec3, tangent: Vec3) -> Vec3 {
    let n = outward - outward.dot(tangent) * tangent;
    if n.length_squared() > 1e-12 {
        n.normalize()
    } else {
        perpendicular(tangent)
    }
}

/// A unit vector perpendicular to the unit vector `v`.
pub fn perpendicular(v: Vec3) -> Vec3 {
    let other = if v.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    v.cross(other).normalize()
}

/// Unit tangent at point `i` of a polyline by central differences; where it has no
/// length, straight down (-y), the way a limp tentacle hangs.
pub fn tangent(points: &[Vec3], i: usize) -> Vec3 {
    let n = points.len();
    let d = points[(i + 1).min(n - 1)] - points[i.saturating_sub(1)];
    d.normalize_or(Vec3::NEG_Y)
}

fn tangents(points: &[Vec3], out: &mut Vec<Vec3>) {
    out.clear();
    out.extend((0..points.len()).map(|i| tangent(points, i)));
}
