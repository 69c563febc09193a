//! The 2D rendering model (paper 3.4): the slice given its thickness, then resampled into
//! opposite pairs at the rendering resolution.
//!
//! The simulated points are the subumbrella; the exumbrella is found by projecting each
//! point back along its normal by the mesoglea thickness there (thickest at the apex). Both
//! curves, and the rest slice, are then resampled with the same cubic spline parameters, so
//! the pairs of the rendering model stay opposite each other.

pub use crate::sim::body::outward_normals;

use super::spline::catmull_rom;
use crate::sim::body::mesoglea_thickness;
use crate::species::Species;
use glam::Vec2;

/// One opposite pair of the resampled slice; index 0 is the left side, 1 the right.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RingPair {
    /// The inner (subumbrellar) surface's point on each side, metres.
    pub subumbrella: [Vec2; 2],
    /// The outer (exumbrellar) surface's point on each side, metres.
    pub exumbrella: [Vec2; 2],
    /// Unit normals of the mesoglea, pointing away from the bell cavity.
    pub normal: [Vec2; 2],
    /// Latitude d_i: 0 at the apex, 1 at the margin.
    pub latitude: f32,
    /// 0 at rest, 1 when the pair has closed to `contraction_ratio` of its rest span.
    pub contraction: f32,
}

/// The slice with thickness, resampled; buffers are reused between frames.
#[derive(Clone, Debug, Default)]
pub struct Profile {
    normals: Vec<Vec2>,
    exumbrella: Vec<Vec2>,
    /// Pairs from the apex (index 0, a coincident pair) to the margin (index `rings`).
    pub pairs: Vec<RingPair>,
}

impl Profile {
    /// Builds `rings + 1` pairs from a checked slice (odd length, at least 3, `rest_bell`
    /// the same length).
    pub fn build(&mut self, bell: &[Vec2], rest_bell: &[Vec2], species: &Species, rings: usize) {
        outward_normals(bell, &mut self.normals);
        let mid = (bell.len() - 1) / 2;
        self.exumbrella.clear();
        for (i, (p, n)) in bell.iter().zip(&self.normals).enumerate() {
            let s = i.abs_diff(mid) as f32 / mid as f32;
            self.exumbrella
                .push(*p + *n * mesoglea_thickness(species, s));
        }
        self.pairs.clear();
        let mut last_normal = [Vec2::Y; 2];
        for k in 0..=rings {
            let latitude = k as f32 / rings as f32;
            let u = [mid as f32 * (1.0 - latitude), mid as f32 * (1.0 + latitude)];
            let at = |points: &[Vec2]| u.map(|u| catmull_rom(points, u));
            let (subumbrella, rest) = (at(bell), at(rest_bell));
            let raw = at(&self.normals);
            let normal = [0, 1].map(|side| raw[side].normalize_or(last_normal[side]));
            last_normal = normal;
            self.pairs.push(RingPair {
                subumbrella,
                exumbrella: at(&self.exumbrella),
                normal,
                latitude,
                contraction: contraction(
                    subumbrella[0].distance(subumbrella[1]),
                    rest[0].distance(rest[1]),
                    species.contraction_ratio,
                ),
            });
        }
    }

    /// The margin pair (the 3D aperture), where tentacles hang.
    pub fn margin(&self) -> &RingPair {
        self.pairs
            .last()
            .expect("Profile::build makes at least two pairs")
    }

    /// The bell's widest extent across its axis as seen from outside (the exumbrella's),
    /// metres: the diameter a video of the animal measures. At rest it is wider than the
    /// subumbrella's margin by at least the margin's mesoglea on each side.
    pub fn widest(&self) -> f32 {
        self.pairs
            .iter()
            .map(|p| p.exumbrella[0].distance(p.exumbrella[1]))
            .fold(0.0, f32::max)
    }
}

/// How far a pair has closed: `(1 − span/rest_span) / (1 − ratio)`, clamped to [0, 1].
///
/// `ratio` is the species' full contraction (paper: 0.56 of the rest diameter). A pair
/// without a rest span (the apex) never counts as contracted.
pub fn contraction(span: f32, rest_span: f32, ratio: f32) -> f32 {
    if !(rest_span > 0.0 && span.is_finite() && rest_span.is_finite()) {
        return 0.0;
    }
    let full = (1.0 - ratio).max(1e-3);
    ((1.0 - span / rest_span) / full).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::outline::SliceOutline;

    /// The moon jelly's rest slice of 25 points, resampled into `rings` pairs.
    fn rest_profile(rings: usize) -> (Species, SliceOutline, Profile) {
        let sp = Species::aurelia();
        let slice = SliceOutline::rest(&sp, 25, 12);
        let mut profile = Profile::default();
        profile.build(&slice.bell, &slice.rest_bell, &sp, rings);
        (sp, slice, profile)
    }

    #[test]
    fn exumbrella_lies_one_mesoglea_thickness_outside() {
        // With as many rings as original pairs, the pairs are the original points.
        let (sp, slice, profile) = rest_profile(12);
        for (k, pair) in profile.pairs.iter().enumerate() {
            let s = k as f32 / 12.0;
            let t = mesoglea_thickness(&sp, s);
            assert!(pair.subumbrella[0].distance(slice.bell[12 - k]) < 1e-7);
            assert!(pair.subumbrella[1].distance(slice.bell[12 + k]) < 1e-7);
            for side in 0..2 {
                let d = pair.exumbrella[side].distance(pair.subumbrella[side]);
                assert!((d - t).abs() < 1e-6, "pair {k}: {d} vs {t}");
                // Outside: further from the ellipse centre than the subumbrella.
                assert!(pair.exumbrella[side].length() > pair.subumbrella[side].length());
            }
        }
        assert!(profile.pairs[0].exumbrella[0].y > profile.pairs[0].subumbrella[0].y);
    }

    #[test]
    fn the_bell_seen_from_outside_is_wider_than_its_margin() {
        let (sp, _, profile) = rest_profile(12);
        let margin = profile.margin();
        let span = margin.subumbrella[0].distance(margin.subumbrella[1]);
        let outside = margin.exumbrella[0].distance(margin.exumbrella[1]);
        // The outline at the margin stands a wall's thickness out on each side, and the
        // flanks' thicker mesoglea may stand further out still.
        assert!(outside > span + mesoglea_thickness(&sp, 1.0));
        let widest = profile.widest();
        assert!(widest >= outside);
        let spans = profile
            .pairs
            .iter()
            .map(|p| p.exumbrella[0].distance(p.exumbrella[1]));
        assert!(spans.clone().all(|w| w <= widest) && spans.clone().any(|w| w == widest));
        assert_eq!(Profile::default().widest(), 0.0);
    }

    #[test]
    fn resampling_keeps_a_symmetric_slice_symmetric() {
        let (_, _, profile) = rest_profile(37);
        assert_eq!(profile.pairs.len(), 38);
        for pair in &profile.pairs {
            let mirror = |v: Vec2| Vec2::new(-v.x, v.y);
            assert!(pair.subumbrella[0].distance(mirror(pair.subumbrella[1])) < 1e-6);
            assert!(pair.exumbrella[0].distance(mirror(pair.exumbrella[1])) < 1e-6);
            assert!(pair.normal[0].distance(mirror(pair.normal[1])) < 1e-5);
            assert_eq!(pair.contraction, 0.0);
        }
    }

    #[test]
    fn contraction_runs_from_rest_to_the_species_ratio() {
        assert_eq!(contraction(1.0, 1.0, 0.56), 0.0);
        assert!((contraction(0.56, 1.0, 0.56) - 1.0).abs() < 1e-6);
        assert!((contraction(0.78, 1.0, 0.56) - 0.5).abs() < 1e-6);
        assert_eq!(contraction(0.3, 1.0, 0.56), 1.0);
        assert_eq!(contraction(1.4, 1.0, 0.56), 0.0);
        assert_eq!(contraction(0.0, 0.0, 0.56), 0.0);
        assert_eq!(contraction(1.0, 1.0, 1.0), 0.0);

        let sp = Species::aurelia();
        let slice = SliceOutline::contracted(&sp, 25, 12, 1.0);
        let mut profile = Profile::default();
        profile.build(&slice.bell, &slice.rest_bell, &sp, 24);
        let margin = profile.margin().contraction;
        assert!(margin > 0.95, "margin contraction {margin}");
    }

    #[test]
    fn coincident_points_get_a_neighbours_normal() {
        let pts = [
            Vec2::new(-1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 0.0),
        ];
        let mut n = Vec::new();
        outward_normals(&pts, &mut n);
        assert!(n.iter().all(|v| (v.length() - 1.0).abs() < 1e-6));
        outward_normals(&[Vec2::ONE; 3], &mut n);
        assert_eq!(n, vec![Vec2::Y; 3]);
    }
}
