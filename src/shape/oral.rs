//! The manubrium and the oral arms: the slice's two oral chains (`sim::oral_arms`) swept
//! around the axis, drawn after the tentacles in the same buffers (one mesh, one draw).
//!
//! Tube 0 is the manubrium, if the species has one: round, on the axis, over the chains'
//! first `stalk_fraction` and widening to the mouth. The arms follow, arm `a` at
//! σ = 2π·a/count over the rest of the chains: blades wide in the radial direction and
//! thin across, narrow at the mouth, widest a third of the way down, tapering to the tip,
//! with edges ruffled in waves about two blade widths long (`oral_arm_frill`), but no more
//! than one wave to eight rings. Each tube has a tentacle's layout ([`TentacleLayout`])
//! with [`ORAL_SIDES`] sides and twice the rings.

use super::buffers::SurfaceBuffers;
use super::discs::Disc;
use super::spline::catmull_rom;
use super::tentacles::{TentacleLayout, across, along, linear, tangent};
use super::tissue::relative_thickness;
use crate::sim::guides::{GUIDE_NODES, Trail};
use crate::sim::oral_arms::stalk_fraction;
use crate::species::Species;
pub use crate::species::limits::ORAL_SIDES;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// How the tubes are shaped: what the packed block's header carries for them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OralStyle {
    /// Whether tube 0 is a manubrium.
    pub manubrium: bool,
    /// The manubrium's radius, m.
    pub manubrium_radius: f32,
    /// Where the manubrium ends along the chains, 0 to 1.
    pub stalk: f32,
    /// A blade's width, m.
    pub arm_width: f32,
    /// Ruffle depth as a fraction of the blade's width.
    pub frill: f32,
    /// Ruffle waves along an arm.
    pub waves: f32,
}

impl OralStyle {
    /// The species' manubrium and arms.
    pub fn of(species: &Species) -> Self {
        let stalk = stalk_fraction(species);
        let arm = (1.0 - stalk) * (species.manubrium_length + species.oral_arm_length);
        Self {
            manubrium: species.manubrium_length > 0.0,
            manubrium_radius: species.manubrium_radius,
            stalk,
            arm_width: species.oral_arm_width,
            frill: species.oral_arm_frill,
            // No more waves than the tube's rings draw softly (eight to a wave at the
            // species' own resolution: fewer are zigzags).
            waves: (arm / (2.0 * species.oral_arm_width.max(1e-6)))
                .round()
                .clamp(1.0, (species.mesh_rings / 8).max(1) as f32),
        }
    }

    /// Whether tube `t` is the manubrium.
    pub fn is_manubrium(&self, t: usize) -> bool {
        self.manubrium && t == 0
    }

    /// The arm's index and angle around the axis of tube `t` (not the manubrium).
    pub fn arm_angle(&self, t: usize, layout: &TentacleLayout) -> (usize, f32) {
        let a = t - self.manubrium as usize;
        let arms = layout.count - self.manubrium as usize;
        (a, TAU * a as f32 / arms.max(1) as f32)
    }

    /// Half-width (radial) and half-thickness of tube `t`'s section at fraction `f` along it.
    pub fn section(&self, manubrium: bool, f: f32) -> (f32, f32) {
        if manubrium {
            let r = self.manubrium_radius * (1.0 + 0.5 * f * f);
            return (r, r);
        }
        let grow = smoothstep(0.25, f);
        let half = 0.5 * self.arm_width * (0.4 + 0.6 * grow) * (1.0 - 0.6 * f * f);
        (half, 0.3 * half)
    }

    /// How far the blade's edge at `e = cos φ` is pushed across it at fraction `f`: curled
    /// to one side by [`ARM_CURL`] and ruffled in waves along the arm, both by the frill.
    pub fn ruffle(&self, arm: usize, f: f32, half_width: f32, e: f32) -> f32 {
        let waves = 2.0 * (TAU * self.waves * f + 1.7 * arm as f32).sin();
        self.frill * half_width * e * e * (ARM_CURL + waves)
    }

    /// The tube's thickness at fraction `f` relative to its reference (the manubrium's
    /// radius; an arm's blade at full width), which the tissue material's opacity is
    /// painted for.
    pub fn thickness(&self, manubrium: bool, f: f32) -> f32 {
        let reference = match manubrium {
            true => self.manubrium_radius,
            false => 0.15 * self.arm_width,
        };
        relative_thickness(self.section(manubrium, f).1, reference)
    }
}

/// How far an arm's blade curls: its edges fold to one side by this share of its
/// half-width per unit of frill, so a blade's section is a shallow C, as the oral arms of
/// *Aurelia* fold along their length.
pub const ARM_CURL: f32 = 0.8;

/// `3x² − 2x³` of `x / edge`, clamped: 0 at 0, 1 from `edge` on.
fn smoothstep(edge: f32, x: f32) -> f32 {
    let t = (x / edge).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Ring `m`'s fraction along a tube, 0 at the root, 1 at the tip.
pub fn fraction(layout: &TentacleLayout, m: usize) -> f32 {
    m as f32 / (layout.points - 1) as f32
}

/// Discs along the manubrium, and again along the arms: half the tubes' rings (the slice's
/// chains have 16 points; the rings between discs are interpolated, so the packed shape
/// carries half as many).
pub fn disc_count(layout: &TentacleLayout) -> usize {
    ((layout.points - 1) / 2 + 1).max(2)
}

/// The discs the tubes sweep: [`disc_count`] along the manubrium, then as many along the
/// arms, from the two oral chains (an empty chain stands at `apex`).
pub fn chain_discs(
    layout: &TentacleLayout,
    style: &OralStyle,
    chains: [&[Vec2]; 2],
    apex: Vec2,
    out: &mut Vec<Disc>,
) {
    let chains = chains.map(|c| {
        if c.is_empty() {
            std::slice::from_ref(&apex)
        } else {
            c
        }
    });
    out.clear();
    let n = disc_count(layout);
    for (from, to) in [(0.0, style.stalk), (style.stalk, 1.0)] {
        let mut radial = Vec2::X;
        for k in 0..n {
            let along = from + (to - from) * (k as f32 / (n - 1) as f32);
            let at = |c: &[Vec2]| catmull_rom(c, along * (c.len() - 1) as f32);
            let disc = Disc::through(at(chains[0]), at(chains[1]), radial);
            radial = disc.radial;
            out.push(disc);
        }
    }
}

/// Centre of tube `t`'s ring `m` from the discs of [`chain_discs`].
pub fn centre(
    discs: &[Disc],
    layout: &TentacleLayout,
    style: &OralStyle,
    t: usize,
    m: usize,
) -> Vec3 {
    let (n, f) = (disc_count(layout), fraction(layout, m));
    if style.is_manubrium(t) {
        // On the axis: the discs' centres, between the two around ring m.
        return along(&discs[..n], f, (0.0, 0.0));
    }
    let (sin, cos) = style.arm_angle(t, layout).1.sin_cos();
    along(&discs[n..2 * n], f, (cos, sin))
}

/// Position and normal of a section vertex: `e = cos φ`, `o = sin φ` around the tube whose
/// ring centre is `c`, tangent `t` and radial `n` (already across the tangent).
#[allow(clippy::too_many_arguments)]
pub fn section_vertex(
    style: &OralStyle,
    manubrium: bool,
    arm: usize,
    f: f32,
    c: Vec3,
    t: Vec3,
    n: Vec3,
    (e, o): (f32, f32),
) -> (Vec3, Vec3) {
    let b = t.cross(n);
    let (half, thin) = style.section(manubrium, f);
    let ruffle = if manubrium {
        0.0
    } else {
        style.ruffle(arm, f, half, e)
    };
    let position = c + half * e * n + (thin * o + ruffle) * b;
    let normal = (thin * e * n + half * o * b).normalize_or(n);
    (position, normal)
}

/// Where the slice draws each oral tube's guide (`sim::guides`): `GUIDE_NODES` points
/// from the tube's root to its tip, straight along the two oral chains (`apex` standing
/// in for an empty one), relative to `origin` (the bell's centroid), tube by tube in
/// `layout`'s order. The manubrium's guide runs down the axis from the apex to the mouth;
/// an arm's from the mouth, at the arm's angle, to its tip.
pub fn guide_reference(
    layout: &TentacleLayout,
    style: &OralStyle,
    chains: [&[Vec2]; 2],
    apex: Vec2,
    origin: Vec2,
    out: &mut Vec<Vec3>,
) {
    let chains = chains.map(|c| {
        if c.is_empty() {
            std::slice::from_ref(&apex)
        } else {
            c
        }
    });
    let origin = Vec3::new(origin.x, origin.y, 0.0);
    let span = |from: f32, to: f32| {
        let mut radial = Vec2::X;
        let mut discs = [Disc::through(apex, apex, radial); GUIDE_NODES];
        for (m, disc) in discs.iter_mut().enumerate() {
            let f = from + (to - from) * (m as f32 / (GUIDE_NODES - 1) as f32);
            let at = |c: &[Vec2]| linear(c, f * (c.len() - 1) as f32);
            *disc = Disc::through(at(chains[0]), at(chains[1]), radial);
            radial = disc.radial;
        }
        discs
    };
    let (stalk, arms) = (span(0.0, style.stalk), span(style.stalk, 1.0));
    out.clear();
    for t in 0..layout.count {
        if style.is_manubrium(t) {
            out.extend(stalk.iter().map(|d| d.centre - origin));
        } else {
            let (sin, cos) = style.arm_angle(t, layout).1.sin_cos();
            out.extend(arms.iter().map(|d| d.point((cos, sin)) - origin));
        }
    }
}

/// Per-frame scratch.
#[derive(Clone, Debug, Default)]
pub struct OralScratch {
    discs: Vec<Disc>,
    centre: Vec<Vec3>,
}

/// Writes the tubes' positions and normals in place, tube `t` starting at vertex
/// `first + t · per-tube`, each moved by its own guide's offset in `trail` (none if it
/// is not one guide per tube). `outward` is the aperture's disc: its radial directions
/// orient the blades.
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_surface(
    layout: &TentacleLayout,
    first: usize,
    style: &OralStyle,
    chains: [&[Vec2]; 2],
    trail: &Trail,
    apex: Vec2,
    outward: &Disc,
    buf: &mut SurfaceBuffers,
    s: &mut OralScratch,
) {
    let l = layout;
    chain_discs(l, style, chains, apex, &mut s.discs);
    let trail = match trail.guides() == l.count {
        true => *trail,
        false => Trail::NONE,
    };
    for t in 0..l.count {
        let manubrium = style.is_manubrium(t);
        let (arm, sigma) = if manubrium {
            (0, 0.0)
        } else {
            style.arm_angle(t, l)
        };
        let (sin, cos) = sigma.sin_cos();
        let radial = outward.direction((cos, sin));
        s.centre.clear();
        s.centre.extend(
            (0..l.points)
                .map(|m| centre(&s.discs, l, style, t, m) + trail.along(t, fraction(l, m))),
        );
        for m in 0..l.points {
            let tm = tangent(&s.centre, m);
            let n = across(radial, tm);
            let f = fraction(l, m);
            for i in 0..=l.sides {
                let (o, e) = (TAU * (i % l.sides) as f32 / l.sides as f32).sin_cos();
                let (p, normal) =
                    section_vertex(style, manubrium, arm, f, s.centre[m], tm, n, (e, o));
                let v = first + l.ring(t, m, i);
                buf.positions[v] = p.to_array();
                buf.normals[v] = normal.to_array();
                buf.tissue[v] = [style.thickness(manubrium, f), 0.0];
            }
        }
        let last = l.points - 1;
        let (root, tip) = (tangent(&s.centre, 0), tangent(&s.centre, last));
        let thin = |f| style.section(manubrium, f).1;
        buf.positions[first + l.root(t)] = (s.centre[0] - thin(0.0) * root).to_array();
        buf.normals[first + l.root(t)] = (-root).to_array();
        buf.positions[first + l.tip(t)] = (s.centre[last] + thin(1.0) * tip).to_array();
        buf.normals[first + l.tip(t)] = tip.to_array();
        buf.tissue[first + l.root(t)] = [style.thickness(manubrium, 0.0), 0.0];
        buf.tissue[first + l.tip(t)] = [style.thickness(manubrium, 1.0), 0.0];
    }
}
