//! A hand-made slice: a half-ellipse bell, at rest or contracted, with two hanging
//! tentacles. For tests, benches and examples that need a slice without running the
//! simulation.

use crate::sim::SliceView;
use crate::sim::guides::Trail;
use crate::sim::oral_arms::OralArms;
use crate::species::Species;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// An owned slice in the layout of [`SliceView`].
#[derive(Clone, Debug, PartialEq)]
pub struct SliceOutline {
    /// The bell's points now, metres, apex on the axis.
    pub bell: Vec<Vec2>,
    /// The same points at rest, which contraction is measured against.
    pub rest_bell: Vec<Vec2>,
    /// The two tentacle chains of the slice, margin first.
    pub tentacles: [Vec<Vec2>; 2],
    /// The manubrium's and oral arms' chains, hanging at rest from the apex.
    pub oral_arms: [Vec<Vec2>; 2],
    /// The fringe's guide offsets ([`Trail`]); none unless a test sets them.
    pub trail: Vec<Vec3>,
    /// The oral tubes' guide offsets; none unless a test sets them.
    pub oral_trail: Vec<Vec3>,
}

impl SliceOutline {
    /// The bell at rest: a half-ellipse the species' diameter wide and height tall, margin
    /// at y = 0, apex at y = height. `bell_points` is rounded up to an odd count of at
    /// least 3; `tentacle_points` may be 0 (no chains).
    pub fn rest(species: &Species, bell_points: usize, tentacle_points: usize) -> Self {
        Self::contracted(species, bell_points, tentacle_points, 0.0)
    }

    /// The bell with each opposite pair pulled towards the axis, more towards the margin:
    /// at `amount` 1 the margin pair spans `contraction_ratio` (0.56) of its rest span and
    /// the bell has grown a third taller, as a contracted bell does.
    pub fn contracted(
        species: &Species,
        bell_points: usize,
        tentacle_points: usize,
        amount: f32,
    ) -> Self {
        let n = bell_points.max(3) | 1;
        let mid = (n - 1) / 2;
        let (a, b) = (0.5 * species.diameter, species.height);
        let pull = amount * (1.0 - species.contraction_ratio);
        let point = |i: usize, amount: f32, pull: f32| {
            let theta = PI * (1.0 - i as f32 / (n - 1) as f32);
            let s = i.abs_diff(mid) as f32 / mid as f32;
            let x = a * theta.cos() * (1.0 - pull * s * s);
            let y = b - (b - b * theta.sin()) * (1.0 + amount / 3.0);
            Vec2::new(x, y)
        };
        let bell: Vec<Vec2> = (0..n).map(|i| point(i, amount, pull)).collect();
        let rest_bell = (0..n).map(|i| point(i, 0.0, 0.0)).collect();
        let chain = |root: Vec2, outward: f32| -> Vec<Vec2> {
            let len = species.tentacle_length;
            (0..tentacle_points)
                .map(|m| {
                    let f = m as f32 / (tentacle_points.max(2) - 1) as f32;
                    let sway = outward * (0.15 - 0.3 * amount) * len * f * f;
                    root + Vec2::new(sway, -len * f)
                })
                .collect()
        };
        let tentacles = [chain(bell[0], -1.0), chain(bell[n - 1], 1.0)];
        let oral_arms = OralArms::new(species, bell[mid], Vec2::Y).chains;
        Self {
            bell,
            rest_bell,
            tentacles,
            oral_arms,
            trail: Vec::new(),
            oral_trail: Vec::new(),
        }
    }

    /// Borrows the slice as the renderer reads it.
    pub fn view(&self) -> SliceView<'_> {
        SliceView {
            bell: &self.bell,
            rest_bell: &self.rest_bell,
            tentacles: [&self.tentacles[0], &self.tentacles[1]],
            oral_arms: [&self.oral_arms[0], &self.oral_arms[1]],
            trail: Trail::new(&self.trail),
            oral_trail: Trail::new(&self.oral_trail),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rest_outline_is_the_species_half_ellipse() {
        let sp = Species::aurelia();
        let o = SliceOutline::rest(&sp, 24, 10);
        assert_eq!(o.bell.len(), 25);
        assert_eq!(o.bell, o.rest_bell);
        assert!((o.bell[12] - Vec2::new(0.0, sp.height)).length() < 1e-7);
        assert!((o.bell[24].x - 0.5 * sp.diameter).abs() < 1e-7);
        assert_eq!(o.tentacles[1][0], o.bell[24]);
        assert!((o.tentacles[0][9].y + sp.tentacle_length).abs() < 1e-7);
    }

    #[test]
    fn contracted_outline_closes_the_margin_to_the_ratio() {
        let sp = Species::aurelia();
        let o = SliceOutline::contracted(&sp, 25, 0, 1.0);
        let span = o.bell[0].distance(o.bell[24]);
        assert!((span / sp.diameter - sp.contraction_ratio).abs() < 1e-5);
        assert!(o.tentacles.iter().all(Vec::is_empty));
    }
}
