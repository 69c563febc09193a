//! A jellyfish's shape in a few kilobytes: what a template mesh's vertex shader builds the
//! surface from.
//!
//! The full surface is thousands of vertices; what makes it is much less: one disc pair per
//! ring of the [`Profile`], one disc per ring of the tentacles, the variation's amplitudes
//! and the individual's seed. [`ShapePacker::pack`] writes that block of `f32`s; the
//! template surfaces' vertex shader (`src/plugin/render/templates/surface.wgsl`) turns a
//! template vertex's index into its position and normal from it. [`umbrella_vertex`] and
//! [`tentacle_vertex`] are the same functions on the CPU, line for line, so the GPU's
//! arithmetic is tested against [`build_into`] without a GPU.
//!
//! Block layout (`f32` offsets; counts stored as `u32` bits): the header (`H_*`), then
//! `rings + 1` rings of `RING` values (subumbrella disc, exumbrella disc, the two
//! mesoglea normals, latitude, contraction), then `points` tentacle discs of `DISC`,
//! then, if the species has oral tubes, [`oral::disc_count`] manubrium discs and as many
//! arm discs, then the trails. The header's first `INSTANCE` values are the individual's
//! (seed, noise time and amplitude, `H_FRAME`); the rest of it, the rings and the discs are
//! the *frame*, which depends on the slice and the species alone: a far jellyfish sends
//! only its own words and trails ([`pack_instance`]) and reads the frame of the recorded
//! step it shows ([`pack_frame`], packed once for all). The offsets and sizes are one
//! table (`packed::layout`), which the plugin
//! also hands the shader as the WGSL module `bevy_jellyfish::packed`: the shader imports
//! them rather than copying them.
//!
//! [`build_into`]: super::build_into

use super::discs::Disc;
use super::input::{ShapeError, check};
use super::mesh::Resolution;
use super::oral::{self, OralStyle};
use super::perlin::perlin4;
use super::profile::Profile;
use super::tentacles;
use super::tissue;
use super::variation::{Variation, apex_fade};
use crate::sim::SliceView;
use crate::sim::guides::{GUIDE_NODES, Trail};
use crate::species::Species;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

pub(crate) mod layout;
mod shared;
mod tubes;

pub use shared::{
    FAR_GUIDES, MAX_INSTANCE, far_guides, far_guides_of, instance_len, pack_frame, pack_instance,
    write_instance_words,
};
pub use tubes::tentacle_vertex;

use layout::*;

/// The length of the longest block for a resolution: its guides' trails included. A
/// block carries only the trails that move something (none for a far jellyfish's oral
/// arms, which it does not follow, nor in still water).
pub fn block_len(res: &Resolution) -> usize {
    trailing_block_len(res, res.guides, oral_guides(res))
}

/// The length of a block for a resolution carrying `guides` and `oral_guides` trails.
fn trailing_block_len(res: &Resolution, guides: usize, oral_guides: usize) -> usize {
    let trails = trail_len(guides) + trail_len(oral_guides);
    trail_start(res.rings, res.tentacles.points, oral_discs(res)) + trails
}

/// The guides of `trail` the block carries: the resolution's `guides` where the view
/// follows them (not thinned) and one of them is off where the slice draws it, else none (a far
/// jellyfish does not follow its oral arms; in still water nothing trails), which the
/// shader reads as zero offsets.
fn trailing(trail: Trail, guides: usize) -> usize {
    let followed = trail.guides() == guides && trail.nodes == GUIDE_NODES;
    match followed && trail.offsets.iter().any(|d| *d != Vec3::ZERO) {
        true => guides,
        false => 0,
    }
}

/// Where the trail starts: after the header, the rings, the tentacle and the oral discs.
fn trail_start(rings: usize, points: usize, oral_discs: usize) -> usize {
    HEADER + (rings + 1) * RING + (points + oral_discs) * DISC
}

/// Values of the trail of `guides` guide chains.
fn trail_len(guides: usize) -> usize {
    guides * TRAIL
}

/// Guides of the oral tubes in the block: one per tube, or none.
fn oral_guides(res: &Resolution) -> usize {
    match res.oral_guides == res.oral.count {
        true => res.oral_guides,
        false => 0,
    }
}

/// Discs of the manubrium and the arms in the block.
fn oral_discs(res: &Resolution) -> usize {
    if res.oral.count > 0 {
        2 * oral::disc_count(&res.oral)
    } else {
        0
    }
}

/// Scratch reused between jellyfish and frames.
#[derive(Clone, Debug, Default)]
pub struct ShapePacker {
    profile: Profile,
    discs: Vec<Disc>,
    oral_discs: Vec<Disc>,
}

impl ShapePacker {
    /// Appends the block of one slice to `out`, for a template of resolution `res`.
    /// `seed` picks the individual, `time` (s) moves its noise. On error nothing is
    /// appended.
    pub fn pack(
        &mut self,
        view: &SliceView,
        species: &Species,
        res: Resolution,
        seed: u32,
        time: f32,
        out: &mut Vec<f32>,
    ) -> Result<(), ShapeError> {
        check(view, species, time)?;
        let variation = Variation::new(species, seed, time);
        self.profile
            .build(view.bell, view.rest_bell, species, res.rings);
        let n = view.bell.len();
        let margin = self.profile.margin();
        let aperture = tentacles::chain_discs(
            &res.tentacles,
            view.tentacles,
            [view.bell[0], view.bell[n - 1]],
            margin,
            &mut self.discs,
        );
        let trails = carried_trails(view.trail, view.oral_trail, &res);
        let start = out.len();
        out.resize(start + HEADER, 0.0);
        let header = &mut out[start..];
        let bits = |v: usize| f32::from_bits(v as u32);
        header[H_SEED] = f32::from_bits(seed);
        header[H_RINGS] = bits(res.rings);
        header[H_SEGMENTS] = bits(res.segments);
        header[H_TENTACLES] = bits(res.tentacles.count);
        header[H_SIDES] = bits(res.tentacles.sides);
        header[H_POINTS] = bits(res.tentacles.points);
        header[H_STRUCTURAL] = species.structural_scale * species.thickness;
        header[H_STRUCTURAL_FREQUENCY] = species.structural_frequency;
        header[H_STRUCTURAL_ABS] = if species.structural_abs { 1.0 } else { 0.0 };
        header[H_COMPRESSION] = species.compression_scale * species.thickness;
        header[H_COMPRESSION_FREQUENCY] = species.compression_frequency;
        header[H_UNSTRUCTURED] = variation.unstructured_amplitude();
        header[H_LAT_FREQUENCY] = species.noise_frequency_lat;
        header[H_LON_RADIUS] = species.noise_frequency_lon / TAU;
        header[H_TAU] = variation.time_coordinate() as f32;
        header[H_TENTACLE_RADIUS] = species.tentacle_radius;
        header[H_TENTACLE_SPREAD] = species.tentacle_length_spread;
        let style = OralStyle::of(species);
        header[H_ORAL] = bits(res.oral.count);
        header[H_ORAL_POINTS] = bits(res.oral.points);
        header[H_MANUBRIUM] = if style.manubrium { 1.0 } else { 0.0 };
        header[H_MANUBRIUM_RADIUS] = style.manubrium_radius;
        header[H_ARM_WIDTH] = style.arm_width;
        header[H_ARM_FRILL] = style.frill;
        header[H_ARM_WAVES] = style.waves;
        header[H_GUIDES] = bits(trails[0].1);
        header[H_ORAL_GUIDES] = bits(trails[1].1);
        header[H_FRAME] = bits(0);
        header[H_TRAILS] = bits(trail_start(
            res.rings,
            res.tentacles.points,
            oral_discs(&res),
        ));
        header[H_TRAIL_NODES] = bits(GUIDE_NODES);
        write_disc(&mut header[H_APERTURE..], &aperture);
        write_normals(&mut header[H_MARGIN_NORMALS..], margin.normal);
        let mut radial = Vec2::X;
        for pair in &self.profile.pairs {
            let sub = Disc::through(pair.subumbrella[0], pair.subumbrella[1], radial);
            let ex = Disc::through(pair.exumbrella[0], pair.exumbrella[1], sub.radial);
            radial = sub.radial;
            let at = out.len();
            out.resize(at + RING, 0.0);
            let ring = &mut out[at..];
            write_disc(&mut ring[RING_SUBUMBRELLA..], &sub);
            write_disc(&mut ring[RING_EXUMBRELLA..], &ex);
            write_normals(&mut ring[RING_NORMALS..], pair.normal);
            ring[RING_LATITUDE] = pair.latitude;
            ring[RING_CONTRACTION] = pair.contraction;
        }
        if res.oral.count > 0 {
            oral::chain_discs(
                &res.oral,
                &style,
                view.oral_arms,
                view.bell[n / 2],
                &mut self.oral_discs,
            );
        } else {
            self.oral_discs.clear();
        }
        for disc in self.discs.iter().chain(&self.oral_discs) {
            let at = out.len();
            out.resize(at + DISC, 0.0);
            write_disc(&mut out[at..], disc);
        }
        write_trails(trails, out);
        debug_assert_eq!(
            out.len() - start,
            trailing_block_len(&res, trails[0].1, trails[1].1)
        );
        Ok(())
    }
}

/// The fringe's and the oral tubes' trails, each with the guides of it the block
/// carries ([`trailing`]).
fn carried_trails<'a>(
    fringe: Trail<'a>,
    oral: Trail<'a>,
    res: &Resolution,
) -> [(Trail<'a>, usize); 2] {
    [
        (fringe, trailing(fringe, res.guides)),
        (oral, trailing(oral, oral_guides(res))),
    ]
}

/// Appends the carried guides of each trail, as halves, two to a value.
fn write_trails(trails: [(Trail, usize); 2], out: &mut Vec<f32>) {
    for (trail, guides) in trails {
        for nodes in trail.offsets.chunks_exact(trail.nodes).take(guides) {
            write_halves(&nodes[1..], out);
        }
    }
}

/// Rounds each offset of a trail to the nearest half, as a packed shape carries it: a
/// surface built from the rounded trail on the CPU is the one the templates draw, to the
/// bit of their input, and packing it again loses nothing.
pub fn round_to_halves(offsets: &mut [Vec3]) {
    use half::slice::HalfFloatSliceExt;
    // A few offsets at a time, each way in one call (the conversions' vector forms).
    const CHUNK: usize = 16;
    let mut values = [0.0f32; 3 * CHUNK];
    let mut halves = [half::f16::ZERO; 3 * CHUNK];
    for chunk in offsets.chunks_mut(CHUNK) {
        let len = 3 * chunk.len();
        for (value, d) in values.chunks_exact_mut(3).zip(chunk.iter()) {
            value.copy_from_slice(&d.to_array());
        }
        halves[..len].convert_from_f32_slice(&values[..len]);
        halves[..len].convert_to_f32_slice(&mut values[..len]);
        for (d, value) in chunk.iter_mut().zip(values.chunks_exact(3)) {
            *d = Vec3::from_slice(value);
        }
    }
}

/// A guide's halves (`TRAIL` values of two), rounded up to whole eights: the widest
/// conversion the `half` crate has.
const HALVES_PADDED: usize = (2 * TRAIL).next_multiple_of(8);

/// Appends one guide's node offsets (its root's left out) as `trail_values` values of two
/// halves each.
fn write_halves(nodes: &[Vec3], out: &mut Vec<f32>) {
    use half::slice::HalfFloatSliceExt;
    let len = 3 * nodes.len();
    let mut values = [0.0f32; HALVES_PADDED];
    for (value, d) in values.chunks_exact_mut(3).zip(nodes) {
        value.copy_from_slice(&d.to_array());
    }
    let mut halves = [half::f16::ZERO; HALVES_PADDED];
    // Whole eights of the zeroed padding converted too: a remainder goes through a copy
    // into a buffer (a `memcpy` call a guide, 1.5% of a 10,002 frame); the same bits.
    let converted = len.next_multiple_of(8);
    halves[..converted].convert_from_f32_slice(&values[..converted]);
    let pair =
        |h: &[half::f16]| f32::from_bits(h[0].to_bits() as u32 | (h[1].to_bits() as u32) << 16);
    out.extend(halves[..len].chunks_exact(2).map(pair));
}

fn write_disc(out: &mut [f32], d: &Disc) {
    out[..DISC].copy_from_slice(&[d.centre.x, d.centre.y, d.radius, d.radial.x, d.radial.y]);
}

fn write_normals(out: &mut [f32], n: [Vec2; 2]) {
    out[..NORMALS].copy_from_slice(&[n[0].x, n[0].y, n[1].x, n[1].y]);
}

/// A read-only view of one packed block as the vertex shader sees it: the individual's
/// own words (`H_SEED` to `H_FRAME`, then its trails) and the frame they draw (the rest of
/// the header, the rings and the discs). A block as packed is both; a far jellyfish's
/// instance ([`pack_instance`]) reads its recorded step's frame.
#[derive(Clone, Copy)]
pub struct Block<'a> {
    instance: &'a [f32],
    frame: &'a [f32],
}

impl<'a> Block<'a> {
    /// A block as [`ShapePacker::pack`] writes it: its own frame.
    pub fn own(block: &'a [f32]) -> Self {
        Self {
            instance: block,
            frame: block,
        }
    }

    /// A far jellyfish's `instance` drawing the recorded `frame` it shows.
    pub fn far(instance: &'a [f32], frame: &'a [f32]) -> Self {
        Self { instance, frame }
    }

    /// A value of the frame.
    fn value(&self, at: usize) -> f32 {
        self.frame[at]
    }

    /// One of the individual's own words.
    fn individual(&self, at: usize) -> f32 {
        self.instance[at]
    }

    fn count(&self, at: usize) -> usize {
        self.frame[at].to_bits() as usize
    }

    fn disc(&self, at: usize) -> Disc {
        let d = &self.frame[at..at + DISC];
        Disc {
            centre: Vec3::new(d[0], d[1], 0.0),
            radius: d[2],
            radial: Vec2::new(d[3], d[4]),
        }
    }

    fn normals(&self, at: usize) -> [Vec2; 2] {
        let n = &self.frame[at..at + NORMALS];
        [Vec2::new(n[0], n[1]), Vec2::new(n[2], n[3])]
    }

    /// Where ring `k` starts in the frame: right after the header.
    fn ring(&self, k: usize) -> usize {
        HEADER + k * RING
    }

    fn rings(&self) -> usize {
        self.count(H_RINGS)
    }

    fn segments(&self) -> usize {
        self.count(H_SEGMENTS)
    }

    /// Nodes of each guide of the trails, the root included.
    fn trail_nodes(&self) -> usize {
        self.count(H_TRAIL_NODES)
    }

    /// Where the trails start in the individual's words.
    fn trail_start(&self) -> usize {
        self.count(H_TRAILS)
    }

    /// Node `m` of guide `g` of the trail starting at `start` (a root, not stored, is
    /// zero).
    fn trail_node(&self, start: usize, g: usize, m: usize) -> Vec3 {
        if m == 0 {
            return Vec3::ZERO;
        }
        let stride = trail_values(self.trail_nodes());
        let half = |h: usize| {
            let value = self.instance[start + g * stride + h / 2].to_bits();
            half::f16::from_bits((value >> (16 * (h % 2))) as u16).to_f32()
        };
        let h = 3 * (m - 1);
        Vec3::new(half(h), half(h + 1), half(h + 2))
    }

    /// The unstructured noise QP at latitude coordinate `lat`, angle `cs`.
    fn noise(&self, lat: f32, (cos, sin): (f32, f32)) -> f32 {
        let b = self.frame;
        let r = b[H_LON_RADIUS];
        perlin4(
            self.individual(H_SEED).to_bits(),
            [
                b[H_LAT_FREQUENCY] * lat,
                r * cos,
                r * sin,
                self.individual(H_TAU),
            ],
        )
    }

    /// Structural lobes at full strength (see [`Variation::structural`]).
    fn lobe(&self, sigma: f32) -> f32 {
        let b = self.frame;
        let s = (b[H_STRUCTURAL_FREQUENCY] * sigma).sin();
        let s = if b[H_STRUCTURAL_ABS] > 0.5 {
            s.abs()
        } else {
            s
        };
        b[H_STRUCTURAL] * s
    }

    /// Compression ripple at full strength (see [`Variation::compression`]).
    fn ripple(&self, sigma: f32) -> f32 {
        let b = self.frame;
        b[H_COMPRESSION] * 0.5 * (1.0 + (b[H_COMPRESSION_FREQUENCY] * sigma).sin())
    }
}

/// `(cos σ, sin σ)` and σ of column `j` of `segments`, as `discs::angles` computes them.
fn column(j: usize, segments: usize) -> ((f32, f32), f32) {
    let sigma = TAU * (j % segments) as f32 / segments as f32;
    let (s, c) = sigma.sin_cos();
    ((c, s), sigma)
}

/// A template vertex as the shader builds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// Position, metres in the jellyfish's frame.
    pub position: Vec3,
    /// Unit normal, outward.
    pub normal: Vec3,
    /// What the tissue material reads ([`super::tissue`]).
    pub tissue: Vec2,
}

/// Ring `k`'s tissue: its thickness relative to the apex's, and its glow band.
fn ring_tissue(b: Block, k: usize) -> Vec2 {
    let thickness = |k| {
        let at = b.ring(k);
        tissue::ring_thickness(
            &b.disc(at + RING_SUBUMBRELLA),
            &b.disc(at + RING_EXUMBRELLA),
        )
    };
    Vec2::new(
        tissue::relative_thickness(thickness(k), thickness(0)),
        tissue::band(b.value(b.ring(k) + RING_CONTRACTION)),
    )
}

/// Ring `k` of surface `surface` (0 exumbrella, 1 subumbrella), column `j`: position and
/// the analytic (swept mesoglea) normal, outward.
fn umbrella_point(b: Block, surface: usize, k: usize, j: usize) -> (Vec3, Vec3) {
    let at = b.ring(k);
    let (sub, ex) = (b.disc(at + RING_SUBUMBRELLA), b.disc(at + RING_EXUMBRELLA));
    let normals = b.normals(at + RING_NORMALS);
    let (latitude, contraction) = (b.value(at + RING_LATITUDE), b.value(at + RING_CONTRACTION));
    let side = if surface == 0 { 1.0 } else { -1.0 };
    if k == 0 {
        let n = sub.normal(normals, (1.0, 0.0));
        let centre = if surface == 0 { ex.centre } else { sub.centre };
        return (centre, n * side);
    }
    let (cs, sigma) = column(j, b.segments());
    let n = sub.normal(normals, cs);
    let fade = apex_fade(latitude);
    let shared =
        b.lobe(sigma) * fade + b.individual(H_UNSTRUCTURED) * latitude * b.noise(latitude, cs);
    let position = if surface == 0 {
        ex.point(cs) + n * (shared + b.ripple(sigma) * fade * contraction)
    } else {
        sub.point(cs) + n * shared
    };
    (position, n * side)
}

/// Sheet ring `l` (the closed umbrella as one sheet: -1 the exumbrellar apex, then
/// exumbrella rings out to the margin, subumbrella rings back in, `2·rings` the
/// subumbrellar apex) as (surface, ring).
fn sheet(l: isize, rings: usize) -> (usize, usize) {
    let r = rings as isize;
    match l {
        l if l < 0 => (0, 0),
        l if l >= 2 * r => (1, 0),
        l if l < r => (0, l as usize + 1),
        l => (1, (2 * r - l) as usize),
    }
}

/// Umbrella vertex `index` of the template (the layout of `umbrella::write_topology`), as
/// the vertex shader computes it.
pub fn umbrella_vertex(b: Block, index: usize) -> Vertex {
    let (rings, segments) = (b.rings(), b.segments());
    let surface_len = 1 + rings * (segments + 1);
    let (surface, r) = (index / surface_len, index % surface_len);
    if r == 0 {
        let (position, normal) = umbrella_point(b, surface, 0, 0);
        let tissue = ring_tissue(b, 0);
        return Vertex {
            position,
            normal,
            tissue,
        };
    }
    let (k, j) = (1 + (r - 1) / (segments + 1), (r - 1) % (segments + 1));
    let (position, analytic) = umbrella_point(b, surface, k, j);
    // Central differences around the ring and along the sheet, as `grid_normals`.
    let l = if surface == 0 {
        k as isize - 1
    } else {
        2 * rings as isize - k as isize
    };
    let at = |l: isize, j: usize| {
        let (s, k) = sheet(l, rings);
        umbrella_point(b, s, k, j).0
    };
    let around = at(l, j + 1) - at(l, j + segments - 1);
    let along = at(l + 1, j) - at(l - 1, j);
    // As `grid_normals`: a subnormal square has no unit direction (the GPU flushes it).
    let n = around.cross(along);
    let normal = if n.length_squared() >= f32::MIN_POSITIVE {
        n.normalize()
    } else {
        analytic
    };
    Vertex {
        position,
        normal,
        tissue: ring_tissue(b, k),
    }
}

#[cfg(test)]
mod tests;
