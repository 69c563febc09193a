//! What the tissue material reads at each vertex (`SurfaceBuffers::tissue`): how thick
//! the tissue is there, relative to a reference, and how much of the glow band lies there.
//!
//! The material turns thickness into opacity by Beer–Lambert along the line of sight: a
//! bell's two sheets bound a shell of mesoglea, crossed on a path of thickness / |N·V|, so
//! its rims read milky and its centre clear; a tentacle is a solid tube, crossed on a
//! chord of its radius × |N·V|, so its edges fade. Both paths compute these from the same
//! discs ([`packed`](super::packed) mirrors them), so templates and CPU meshes agree.

use super::discs::Disc;

/// The right-hand (σ = 0) mesoglea thickness of a ring: from its subumbrellar to its
/// exumbrellar point.
pub fn ring_thickness(subumbrella: &Disc, exumbrella: &Disc) -> f32 {
    exumbrella
        .point((1.0, 0.0))
        .distance(subumbrella.point((1.0, 0.0)))
}

/// A ring's thickness relative to the apex's (the species' `bell_color` alpha is one
/// sheet's opacity there, seen straight on); 1 where the apex has no thickness.
pub fn relative_thickness(thickness: f32, apex: f32) -> f32 {
    if apex > 0.0 && thickness.is_finite() {
        thickness / apex
    } else {
        1.0
    }
}

/// How much of the glow band a ring carries at `contraction` (0 at rest, 1 closed):
/// `4c(1 − c)`, brightest where the ring is half-way through closing. The slice's
/// muscles close the bell from the apex down, so the band runs up the bell as it
/// contracts and down it as it relaxes: it follows the contraction the slice simulates.
pub fn band(contraction: f32) -> f32 {
    4.0 * contraction * (1.0 - contraction)
}

/// A tentacle's radius at its tip, as a share of its radius at the root.
pub const TENTACLE_TIP: f32 = 0.3;

/// A tentacle's radius `fraction` of the way from root (0) to tip (1), as a share of the
/// root's: tapering linearly to [`TENTACLE_TIP`].
pub fn taper(fraction: f32) -> f32 {
    1.0 - (1.0 - TENTACLE_TIP) * fraction.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::{JellyMesh, Resolution, SliceOutline, umbrella};
    use crate::species::Species;
    use glam::Vec2;

    #[test]
    fn the_band_lights_half_closed_rings_only() {
        assert_eq!(band(0.0), 0.0);
        assert_eq!(band(1.0), 0.0);
        assert_eq!(band(0.5), 1.0);
        assert!(band(0.25) > 0.7 && band(0.25) < 0.8);
    }

    #[test]
    fn tentacles_taper_from_root_to_tip() {
        assert_eq!(taper(0.0), 1.0);
        assert!((taper(1.0) - TENTACLE_TIP).abs() < 1e-6);
        assert!(taper(0.5) < 1.0 && taper(0.5) > TENTACLE_TIP);
        assert_eq!(taper(2.0), taper(1.0));
    }

    #[test]
    fn thickness_is_measured_between_the_sheets() {
        let sub = Disc::through(Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0), Vec2::X);
        let ex = Disc::through(Vec2::new(-1.2, 0.1), Vec2::new(1.2, 0.1), Vec2::X);
        let t = ring_thickness(&sub, &ex);
        assert!((t - Vec2::new(0.2, 0.1).length()).abs() < 1e-6);
        assert!((relative_thickness(t, 2.0 * t) - 0.5).abs() < 1e-6);
        assert_eq!(relative_thickness(0.3, 0.0), 1.0);
        assert_eq!(relative_thickness(f32::NAN, 1.0), 1.0);
    }

    /// The tissue the material reads: 1 at the apex, thinner towards the margin (the
    /// mesoglea thins); no band at rest, a band where the contracting bell is half-closed;
    /// tentacles taper to their tip.
    #[test]
    fn tissue_follows_the_mesoglea_and_the_contraction() {
        let species = Species::aurelia();
        let res = Resolution::of(&species);
        let (rings, segments) = (res.rings, res.segments);
        let at =
            |mesh: &JellyMesh, k| mesh.umbrella.tissue[umbrella::vertex(rings, segments, 0, k, 3)];
        let rest = JellyMesh::from_slice(
            &SliceOutline::contracted(&species, 31, 12, 0.0).view(),
            &species,
            1,
            0.0,
        )
        .unwrap();
        assert!((at(&rest, 0)[0] - 1.0).abs() < 1e-6);
        assert!(
            at(&rest, rings)[0] < 0.7 * at(&rest, 1)[0],
            "{:?}",
            rest.umbrella.tissue
        );
        assert!(rest.umbrella.tissue.iter().all(|t| t[1] == 0.0));
        let half = JellyMesh::from_slice(
            &SliceOutline::contracted(&species, 31, 12, 0.5).view(),
            &species,
            1,
            0.0,
        )
        .unwrap();
        let most = half
            .umbrella
            .tissue
            .iter()
            .map(|t| t[1])
            .fold(0.0, f32::max);
        assert!(most > 0.9, "band {most}");
        // Subumbrella and exumbrella of a ring agree.
        for k in 0..=rings {
            let (ex, sub) = (
                umbrella::vertex(rings, segments, 0, k, 0),
                umbrella::vertex(rings, segments, 1, k, 0),
            );
            assert_eq!(half.umbrella.tissue[ex], half.umbrella.tissue[sub]);
        }
        let l = res.tentacles;
        let tentacles = &half.tentacles.tissue;
        assert_eq!(tentacles[l.ring(0, 0, 1)][0], 1.0);
        assert!((tentacles[l.ring(0, l.points - 1, 1)][0] - TENTACLE_TIP).abs() < 1e-6);
    }
}
