//! The hanging parts' vertices as the vertex shader builds them: tentacles, then the
//! manubrium and oral arms, each a run of tubes (`tentacles::write_topology`'s layout).

use super::layout::*;
use super::{Block, Vertex};
use crate::shape::oral::{self, ORAL_SIDES, OralStyle};
use crate::shape::tentacles::{self, SIDEWAYS, TentacleLayout};
use crate::shape::tissue;
use crate::shape::variation::tentacle_reach;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// Centre of tentacle `t`'s ring `m`, as `tentacles::write_surface` places it.
fn tentacle_centre(b: Block, t: usize, m: usize) -> Vec3 {
    let (count, points) = (b.count(H_TENTACLES), b.count(H_POINTS));
    let sigma = TAU * t as f32 / count as f32;
    let (sin, cos) = sigma.sin_cos();
    let cs = (cos, sin);
    let aperture = b.disc(H_APERTURE);
    let normal = aperture.normal(b.normals(H_MARGIN_NORMALS), cs);
    let sideways = aperture.direction((-sin, cos));
    let fraction = m as f32 / (points - 1) as f32;
    let lat = 1.0 + fraction;
    let amplitude = b.individual(H_UNSTRUCTURED);
    let along = b.lobe(sigma) + amplitude * b.noise(lat, cs);
    let side = amplitude * fraction * b.noise(lat + SIDEWAYS, cs);
    // tentacles::along, between the two discs around the drawn length.
    let reach = tentacle_reach(
        b.individual(H_SEED).to_bits(),
        t as u32,
        b.value(H_TENTACLE_SPREAD),
    );
    let x = fraction * reach * (points - 1) as f32;
    let i = (x as usize).min(points - 2);
    let first = b.ring(b.rings() + 1);
    let (p, q) = (
        b.disc(first + i * DISC).point(cs),
        b.disc(first + (i + 1) * DISC).point(cs),
    );
    let trail = trail_offset(b, sigma, fraction * reach);
    p + (q - p) * (x - i as f32) + trail + normal * along + sideways * side
}

/// The guides' offset at angle `sigma` and `fraction` of the chain, as `Trail::at`
/// interpolates it (a guide's root, not stored, is zero).
fn trail_offset(b: Block, sigma: f32, fraction: f32) -> Vec3 {
    let guides = b.count(H_GUIDES);
    if guides == 0 {
        return Vec3::ZERO;
    }
    let (start, nodes) = (b.trail_start(), b.trail_nodes());
    crate::sim::guides::between(guides, nodes, sigma, fraction, |g, m| {
        b.trail_node(start, g, m)
    })
}

/// The oral tube `t`'s offset `f` of the way down, as `Trail::along` reads its guide.
fn oral_trail_offset(b: Block, t: usize, f: f32) -> Vec3 {
    if b.count(H_ORAL_GUIDES) == 0 {
        return Vec3::ZERO;
    }
    let nodes = b.trail_nodes();
    let start = b.trail_start() + b.count(H_GUIDES) * trail_values(nodes);
    crate::sim::guides::along(nodes, f, |m| b.trail_node(start, t, m))
}

/// Where a vertex of a run of tubes lies: tube `tube`, ring `ring` along it, and on the
/// ring, `part`. The shader's `tube_index` is this function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct TubeIndex {
    tube: usize,
    ring: usize,
    part: TubePart,
}

/// A tube vertex's place on its ring.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TubePart {
    /// The cap before ring 0.
    Start,
    /// Column `i` of the ring's `sides + 1` (the last repeats the first, for the UVs).
    Side(usize),
    /// The cap after the last ring.
    End,
}

/// Vertices per tube of `sides` sides and `points` rings: a cap, the rings, a cap.
fn tube_len(layout: &TentacleLayout) -> usize {
    2 + layout.points * (layout.sides + 1)
}

/// Vertex `index` of a run of tubes in `tentacles::write_topology`'s layout (which the
/// oral tubes share).
fn tube_index(layout: &TentacleLayout, index: usize) -> TubeIndex {
    let per = tube_len(layout);
    let (tube, r) = (index / per, index % per);
    let (ring, part) = if r == 0 {
        (0, TubePart::Start)
    } else if r == per - 1 {
        (layout.points - 1, TubePart::End)
    } else {
        let r = r - 1;
        (
            r / (layout.sides + 1),
            TubePart::Side(r % (layout.sides + 1)),
        )
    };
    TubeIndex { tube, ring, part }
}

/// Vertex `index` of the hanging parts' template (the layout of
/// `tentacles::write_topology`: the tentacles, then the oral tubes), as the vertex shader
/// computes it.
pub fn tentacle_vertex(b: Block, index: usize) -> Vertex {
    let layout = TentacleLayout {
        count: b.count(H_TENTACLES),
        sides: b.count(H_SIDES),
        points: b.count(H_POINTS),
    };
    let tentacles = layout.count * tube_len(&layout);
    if index >= tentacles {
        return oral_vertex(b, index - tentacles);
    }
    let TubeIndex {
        tube: t,
        ring: m,
        part,
    } = tube_index(&layout, index);
    let last = layout.points - 1;
    let centre = tentacle_centre(b, t, m);
    let tangent = (tentacle_centre(b, t, (m + 1).min(last))
        - tentacle_centre(b, t, m.saturating_sub(1)))
    .normalize_or(Vec3::NEG_Y);
    let thin = tissue::taper(m as f32 / last as f32);
    let radius = b.value(H_TENTACLE_RADIUS) * thin;
    let solid = |position, normal| Vertex {
        position,
        normal,
        tissue: Vec2::new(thin, 0.0),
    };
    let i = match part {
        TubePart::Start => return solid(centre - radius * tangent, -tangent),
        TubePart::End => return solid(centre + radius * tangent, tangent),
        TubePart::Side(i) => i,
    };
    let sigma = TAU * t as f32 / layout.count as f32;
    let (sin, cos) = sigma.sin_cos();
    let outward = b.disc(H_APERTURE).direction((cos, sin));
    let n = tentacles::across(outward, tangent);
    let (sin_phi, cos_phi) = (TAU * (i % layout.sides) as f32 / layout.sides as f32).sin_cos();
    let out = cos_phi * n + sin_phi * tangent.cross(n);
    solid(centre + radius * out, out)
}

/// Centre of oral tube `t`'s ring `m`, as `oral::centre` places it.
fn oral_centre(b: Block, layout: &TentacleLayout, style: &OralStyle, t: usize, m: usize) -> Vec3 {
    let discs = b.ring(b.rings() + 1) + b.count(H_POINTS) * DISC;
    // oral::centre, between the two discs around ring m.
    let n = oral::disc_count(layout);
    let x = oral::fraction(layout, m) * (n - 1) as f32;
    let i = (x as usize).min(n - 2);
    let w = x - i as f32;
    let trail = oral_trail_offset(b, t, oral::fraction(layout, m));
    if style.is_manubrium(t) {
        let p = b.disc(discs + i * DISC).centre;
        let q = b.disc(discs + (i + 1) * DISC).centre;
        return p + (q - p) * w + trail;
    }
    let (sin, cos) = style.arm_angle(t, layout).1.sin_cos();
    let p = b.disc(discs + (n + i) * DISC).point((cos, sin));
    let q = b.disc(discs + (n + i + 1) * DISC).point((cos, sin));
    p + (q - p) * w + trail
}

/// Oral tube vertex `index` (counted from the first oral vertex), as
/// `oral::write_surface` places it.
fn oral_vertex(b: Block, index: usize) -> Vertex {
    let layout = TentacleLayout {
        count: b.count(H_ORAL),
        sides: ORAL_SIDES,
        points: b.count(H_ORAL_POINTS),
    };
    let style = OralStyle {
        manubrium: b.value(H_MANUBRIUM) > 0.5,
        manubrium_radius: b.value(H_MANUBRIUM_RADIUS),
        stalk: 0.0,
        arm_width: b.value(H_ARM_WIDTH),
        frill: b.value(H_ARM_FRILL),
        waves: b.value(H_ARM_WAVES),
    };
    let TubeIndex {
        tube: t,
        ring: m,
        part,
    } = tube_index(&layout, index);
    let last = layout.points - 1;
    let centre = |m| oral_centre(b, &layout, &style, t, m);
    let c = centre(m);
    let tangent =
        (centre((m + 1).min(last)) - centre(m.saturating_sub(1))).normalize_or(Vec3::NEG_Y);
    let manubrium = style.is_manubrium(t);
    let f = oral::fraction(&layout, m);
    let solid = |(position, normal)| Vertex {
        position,
        normal,
        tissue: Vec2::new(style.thickness(manubrium, f), 0.0),
    };
    let i = match part {
        TubePart::Start => {
            return solid((c - style.section(manubrium, 0.0).1 * tangent, -tangent));
        }
        TubePart::End => return solid((c + style.section(manubrium, 1.0).1 * tangent, tangent)),
        TubePart::Side(i) => i,
    };
    let (arm, sigma) = if manubrium {
        (0, 0.0)
    } else {
        style.arm_angle(t, &layout)
    };
    let (sin, cos) = sigma.sin_cos();
    let n = tentacles::across(b.disc(H_APERTURE).direction((cos, sin)), tangent);
    let (o, e) = (TAU * (i % layout.sides) as f32 / layout.sides as f32).sin_cos();
    solid(oral::section_vertex(
        &style,
        manubrium,
        arm,
        f,
        c,
        tangent,
        n,
        (e, o),
    ))
}
