//! The spring-mass network of the paper's Fig. 4, part by part: the subumbrellar chain of
//! Hookean springs, the angular springs that give the mesoglea its shape, the
//! circumferential muscle's springs across the bell, and the tentacles hanging from the
//! aperture's margins.

use super::depth::Depth;
use super::elements::{
    Drive, Hinge, HoopBend, Muscle, Spring, TENTACLE_STRAIN_LIMIT, hinge, hoop_bend, muscle, spring,
};
use super::rest_shape::mesoglea_thickness;
use super::tentacle::tentacle_bending;
use crate::species::{MuscleLaw, REFERENCE_HINGE_LENGTH, Species};
use glam::Vec2;
use std::ops::Range;

/// Distance of subumbrellar point `i` from the apex `m` along the chain, as a fraction
/// of the way to the margin (0 at the apex, 1 at either margin).
fn arc_fraction(i: usize, m: usize) -> f32 {
    (i as f32 - m as f32).abs() / m as f32
}

/// The subumbrellar chain: a Hookean spring between neighbouring points, its
/// cross-section the local mesoglea thickness times unit depth (in r–z, the ring's arc
/// per radian at the spring's middle).
pub(super) fn subumbrellar_springs(
    species: &Species,
    subumbrella: &[Vec2],
    depth: Depth,
) -> Vec<Spring> {
    let m = subumbrella.len() / 2;
    (0..subumbrella.len() - 1)
        .map(|i| {
            let s = arc_fraction(i, m) * 0.5 + arc_fraction(i + 1, m) * 0.5;
            let t = mesoglea_thickness(species, s);
            let width = depth.at(0.5 * (subumbrella[i] + subumbrella[i + 1]));
            spring(subumbrella, i, i + 1, species.elastic_modulus * t * width)
        })
        .collect()
}

/// Angular springs along the subumbrella: the mesoglea's bending stiffness. Plate bending
/// stiffness scales with t³; [`Species::bending_stiffness`] is the value at the apex
/// thickness for a 2 mm hinge, rescaled to this `spacing` so the bell's rigidity does not depend on the
/// grid.
pub(super) fn mesoglea_hinges(
    species: &Species,
    subumbrella: &[Vec2],
    spacing: f32,
    depth: Depth,
) -> Vec<Hinge> {
    let m = subumbrella.len() / 2;
    let hinge_scale = REFERENCE_HINGE_LENGTH / spacing;
    (1..subumbrella.len() - 1)
        .map(|i| {
            let t = mesoglea_thickness(species, arc_fraction(i, m)) / species.thickness;
            let width = depth.at(subumbrella[i]);
            hinge(
                subumbrella,
                i - 1,
                i,
                i + 1,
                species.bending_stiffness() * t.powi(3) * hinge_scale * width,
            )
        })
        .collect()
}

/// The hoop bending of an axisymmetric bell's rings, segment by segment (none in the
/// plane, which has no hoop curvature): the rigidity is the hinges' plate law at the
/// segment's thickness, over its ring's radius (floored where the kernel smears the apex).
pub(super) fn hoop_bending(
    species: &Species,
    subumbrella: &[Vec2],
    spacing: f32,
    depth: Depth,
) -> Vec<HoopBend> {
    if !depth.rings() {
        return Vec::new();
    }
    let m = subumbrella.len() / 2;
    (0..subumbrella.len() - 1)
        .map(|i| {
            let s = arc_fraction(i, m) * 0.5 + arc_fraction(i + 1, m) * 0.5;
            let t = mesoglea_thickness(species, s) / species.thickness;
            // E·ϑ³/12 at this thickness: `bending_stiffness` is it per 2 mm of hinge.
            let rigidity = species.bending_stiffness() * t.powi(3) * REFERENCE_HINGE_LENGTH;
            let radius = depth.at(0.5 * (subumbrella[i] + subumbrella[i + 1]));
            hoop_bend(subumbrella, i, i + 1, rigidity * spacing / radius)
        })
        .collect()
}

/// The circumferential muscle: springs between opposite subumbrellar points, from the
/// aperture's margins up the species' `muscle_extent` of the way to the apex (the
/// paper's three quarters).
///
/// Each is the muscle in series with the hoop of mesoglea it lines (the slice has no
/// circumference of its own): the muscle sets the rest length (the contraction function),
/// and the far softer mesoglea sets the stiffness, so the bell's resonance with its water
/// rises with `elastic_modulus` (DeMont & Gosline 1988). Each spring stands for a band of
/// the ring as tall as the point `spacing`, so the bell's total stiffness does not grow
/// with the number of points (grid).
pub(super) fn circumferential_muscles(
    species: &Species,
    subumbrella: &[Vec2],
    spacing: f32,
) -> Vec<Muscle> {
    let bell_len = subumbrella.len();
    let m = bell_len / 2;
    let band = species.thickness * (spacing / REFERENCE_HINGE_LENGTH);
    let fibre = species.muscle_modulus * species.muscle_cross_section * band;
    let hoop = species.elastic_modulus * species.hoop_cross_section * band;
    let in_series = fibre * hoop / (fibre + hoop);
    let mut muscles = Vec::new();
    let unlined = 1.0 - species.muscle_extent;
    for i in 0..m {
        let level = 1.0 - i as f32 / m as f32;
        if level < unlined {
            break;
        }
        let j = bell_len - 1 - i;
        let drive = Drive::RestLength { share: 1.0 };
        muscles.push(muscle(subumbrella, (i, j), in_series, level, drive));
    }
    muscles
}

/// The rings of an axisymmetric bell: each subumbrellar point and its mirror are one ring,
/// and the element between them measures the ring's diameter, so its strain is the ring's
/// hoop strain and its force on each point is the ring's hoop tension per radian (N): a
/// hoop of the ring itself, not a spring across the water.
///
/// The ring's cross-section is real: the local mesoglea thickness times the band of the
/// meridian one point stands for (`spacing`). Every ring is a hoop of mesoglea
/// (`elastic_modulus` times that cross-section, at its rest radius), which resists the
/// bell's being squeezed and pushes it open again; the rings of the muscle band (from the
/// margin `muscle_extent` of the way up, as in the plane) also carry the muscle around the same
/// circumference, in parallel (`muscle_modulus × muscle_cross_section` of the ring), as
/// the species' `muscle_law` says: a force generator the contraction function activates
/// ([`Drive::Activation`]), which pulls and never pushes, so the bell refills on its
/// hoops' and its bending's recoil; or the paper's spring whose rest length the function
/// sets, merged with the hoop into one element, which pushes the bell open again as fast
/// as it pulled it shut. `hoop_cross_section`, the planar slice's stand-in for this
/// circumference, has no part here. (The muscle in series with its hoop, as the plane
/// has it, let the strong real hoop pull a prolate bell past its commanded contraction
/// until its margin folded in: Sarsia crumpled after 16 strokes.)
/// Returns the muscles; the hoops without one join `springs`.
pub(super) fn ring_hoops(
    species: &Species,
    subumbrella: &[Vec2],
    spacing: f32,
    springs: &mut Vec<Spring>,
) -> Vec<Muscle> {
    let bell_len = subumbrella.len();
    let m = bell_len / 2;
    let mut muscles = Vec::new();
    let unlined = 1.0 - species.muscle_extent;
    for i in 0..m {
        let j = bell_len - 1 - i;
        let ring = mesoglea_thickness(species, arc_fraction(i, m)) * spacing;
        let hoop = species.elastic_modulus * ring;
        let level = 1.0 - i as f32 / m as f32;
        let fibre = species.muscle_modulus * species.muscle_cross_section * ring;
        match species.muscle_law {
            _ if level < unlined => springs.push(spring(subumbrella, i, j, hoop)),
            MuscleLaw::Force => {
                springs.push(spring(subumbrella, i, j, hoop));
                muscles.push(muscle(subumbrella, (i, j), fibre, level, Drive::Activation));
            }
            MuscleLaw::Length => {
                // The muscle and the hoop in parallel, as one element.
                let share = fibre / (fibre + hoop).max(f32::MIN_POSITIVE);
                let drive = Drive::RestLength { share };
                muscles.push(muscle(subumbrella, (i, j), fibre + hoop, level, drive));
            }
        }
    }
    muscles
}

/// The tentacles hanging from the aperture's two margins.
pub(super) struct Tentacles {
    /// Indices of the left and right tentacle points, margin outwards (margin excluded).
    pub(crate) ranges: [Range<usize>; 2],
    /// Length of one tentacle segment, m (0 without tentacles).
    pub(crate) segment: f32,
}

/// Hangs a tentacle straight down from each margin of the aperture (the first and last of
/// the `bell_len` subumbrellar points): a chain of springs of the mesoglea's modulus and
/// a fraction of the margin's cross-section, and hinges along it. Appends the points,
/// springs and hinges.
pub(super) fn hang_tentacles(
    species: &Species,
    bell_len: usize,
    spacing: f32,
    points: &mut Vec<Vec2>,
    springs: &mut Vec<Spring>,
    hinges: &mut Vec<Hinge>,
    depth: Depth,
) -> Tentacles {
    let margin_t = mesoglea_thickness(species, 1.0);
    let width = depth.at(points[0]);
    let tentacle_area = margin_t * species.tentacle_cross_section * width;
    // No tentacles, no chains: a chain of no tentacles would slip against no drag at all.
    let segments = if species.tentacle_count == 0 || species.tentacle_length <= 0.0 {
        0
    } else {
        ((species.tentacle_length / spacing).round() as usize).max(2)
    };
    let seg_len = if segments > 0 {
        species.tentacle_length / segments as f32
    } else {
        0.0
    };
    let hinge_scale = REFERENCE_HINGE_LENGTH / spacing;
    let mut tentacles = [0..0, 0..0];
    let bell_neighbour = [1, bell_len - 2];
    for (side, margin) in [(0, 0), (1, bell_len - 1)] {
        let start = points.len();
        let mut prev = margin;
        for k in 1..=segments {
            points.push(points[margin] - Vec2::Y * seg_len * k as f32);
            let idx = points.len() - 1;
            let mut s = spring(points, prev, idx, species.elastic_modulus * tentacle_area);
            s.strain_limit = Some(TENTACLE_STRAIN_LIMIT);
            springs.push(s);
            prev = idx;
        }
        tentacles[side] = start..points.len();
        // Bending: the root, where the tentacle grows from the margin, is as stiff as
        // the margin itself; beyond it a tentacle bends as a thin cylinder of mesoglea
        // (see `tentacle_bending`) and trails in the flow. A root stiff over a third of
        // the length swung the tentacles as rods across the bell's axis.
        let margin_hinge = species.bending_stiffness()
            * species.margin_thickness_ratio.powi(3)
            * hinge_scale
            * width;
        let tip_hinge = tentacle_bending(species, seg_len.max(1e-6), depth);
        let chain: Vec<usize> = std::iter::once(bell_neighbour[side])
            .chain(std::iter::once(margin))
            .chain(start..points.len())
            .collect();
        for (k, w) in chain.windows(3).enumerate() {
            let stiffness = if k == 0 { margin_hinge } else { tip_hinge };
            hinges.push(hinge(points, w[0], w[1], w[2], stiffness));
        }
    }
    Tentacles {
        ranges: tentacles,
        segment: seg_len,
    }
}
