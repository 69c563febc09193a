//! The bell's inner anatomy as a pattern on its surface: the radial canals, the ring canal
//! along the margin and the gonads, on the subumbrella in the umbrella's UVs (u = σ/2π
//! around the axis; v from 0 at the exumbrellar apex over 0.5 at the margin to 1 at the
//! subumbrellar apex, see `umbrella::write_topology`). Painted in the surface's own
//! coordinates, it follows the bell as it contracts, on CPU meshes and templates alike.
//!
//! Distances are measured on the subumbrella laid flat: a point at latitude ℓ (0 at the
//! apex, 1 at the margin) and angle σ sits at `ℓ·(cos σ, sin σ)` in the unit disc; widths
//! and sizes are fractions of that disc's radius (the span from apex to margin).

use crate::species::{GonadShape, Species};
use glam::Vec2;
use std::f32::consts::TAU;

/// Texels around the axis.
pub const WIDTH: usize = 512;
/// Texels from the exumbrellar apex to the subumbrellar apex.
pub const HEIGHT: usize = 256;
/// Where the radial canals leave the stomach, as a latitude.
const STOMACH: f32 = 0.12;
/// The ring canal's latitude.
const RING_CANAL: f32 = 0.965;
/// A texel's size on the flattened subumbrella, for antialiased edges.
const TEXEL: f32 = 2.0 / HEIGHT as f32;

/// How strongly each texel belongs to a canal and to a gonad, 0 to 1.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Marks {
    /// Radial or ring canal.
    pub canal: f32,
    /// Gonad.
    pub gonad: f32,
}

/// The pattern at UV `(u, v)`: nothing on the exumbrella (the subumbrella's pattern shows
/// through it).
pub fn marks_at(species: &Species, u: f32, v: f32) -> Marks {
    if v < 0.5 {
        return Marks::default();
    }
    let latitude = (2.0 * (1.0 - v)).clamp(0.0, 1.0);
    let sigma = TAU * u;
    Marks {
        canal: canal(species, latitude, sigma),
        gonad: gonad(species, latitude, sigma),
    }
}

/// 1 inside a shape whose signed distance is `d`, 0 outside, over a texel between.
fn coverage(d: f32) -> f32 {
    (0.5 - d / TEXEL).clamp(0.0, 1.0)
}

/// Angle from `sigma` to the nearest of `count` directions starting at `offset` (in
/// units of the spacing), and that direction's index.
fn nearest(sigma: f32, count: u32, offset: f32) -> (f32, usize) {
    let spacing = TAU / count as f32;
    let k = (sigma / spacing - offset).round();
    let delta = sigma - (k + offset) * spacing;
    (delta, k.rem_euclid(count as f32) as usize)
}

fn canal(s: &Species, latitude: f32, sigma: f32) -> f32 {
    if s.canal_width <= 0.0 {
        return 0.0;
    }
    let half = 0.5 * s.canal_width;
    let ring = coverage((latitude - RING_CANAL).abs() - half);
    if s.radial_canal_count == 0 || !(STOMACH..=RING_CANAL).contains(&latitude) {
        return ring;
    }
    let (delta, _) = nearest(sigma, s.radial_canal_count, 0.0);
    let radial = coverage(latitude * delta.abs() - half);
    radial.max(ring)
}

fn gonad(s: &Species, latitude: f32, sigma: f32) -> f32 {
    if s.gonad_count == 0 || s.gonad_size <= 0.0 {
        return 0.0;
    }
    let size = s.gonad_size;
    match s.gonad_shape {
        GonadShape::Radial => {
            // A strip along each radial canal, from near the stomach outwards.
            let (delta, _) = nearest(sigma, s.gonad_count, 0.0);
            let (from, to) = (0.3, (0.3 + size).min(0.9));
            let across = latitude * delta.abs() - 1.5 * s.canal_width.max(TEXEL);
            let along = (latitude - 0.5 * (from + to)).abs() - 0.5 * (to - from);
            coverage(across.max(along))
        }
        GonadShape::Horseshoe | GonadShape::Oval => {
            // Between the canals' main directions, half a spacing round.
            let p = latitude * Vec2::new(sigma.cos(), sigma.sin());
            let (_, g) = nearest(sigma, s.gonad_count, 0.5);
            let angle = TAU * (g as f32 + 0.5) / s.gonad_count as f32;
            let outward = Vec2::new(angle.cos(), angle.sin());
            let centre = (STOMACH + 0.9 * size) * outward;
            let radius = 0.5 * size;
            let d = p - centre;
            if s.gonad_shape == GonadShape::Oval {
                let (radial, tangential) = (d.dot(outward), d.perp_dot(outward));
                let r = Vec2::new(radial / radius, tangential / (0.6 * radius)).length();
                return coverage((r - 1.0) * 0.6 * radius);
            }
            // A band round the centre, open towards the stomach.
            let band = (d.length() - 0.7 * radius).abs() - 0.18 * radius;
            let opening = (-d.normalize_or_zero()).dot(outward) - 0.6;
            coverage(band.max(opening * radius))
        }
    }
}

/// The pattern's texels, row by row from v = 0: how much of a canal and of a gonad each
/// shows, as bytes (0–255), for a texture the renderer colours with the species' colours.
pub fn texels(species: &Species) -> Vec<Marks> {
    let mut out = Vec::with_capacity(WIDTH * HEIGHT);
    for row in 0..HEIGHT {
        let v = (row as f32 + 0.5) / HEIGHT as f32;
        for column in 0..WIDTH {
            let u = (column as f32 + 0.5) / WIDTH as f32;
            out.push(marks_at(species, u, v));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs of marked texels around the ring at latitude `latitude`.
    fn runs(species: &Species, latitude: f32, mark: fn(Marks) -> f32) -> usize {
        let v = 1.0 - 0.5 * latitude;
        let marked: Vec<bool> = (0..2048)
            .map(|i| mark(marks_at(species, (i as f32 + 0.5) / 2048.0, v)) > 0.5)
            .collect();
        (0..marked.len())
            .filter(|&i| marked[i] && !marked[(i + marked.len() - 1) % marked.len()])
            .count()
    }

    #[test]
    fn each_species_shows_its_canals_and_gonads() {
        let [aurelia, aequorea, sarsia] = Species::presets();
        assert_eq!(runs(&aurelia, 0.8, |m| m.canal), 16);
        assert_eq!(runs(&aequorea, 0.8, |m| m.canal), 60);
        assert_eq!(runs(&sarsia, 0.8, |m| m.canal), 4);
        // The ring canal runs all the way round.
        let ring = (0..64)
            .all(|i| marks_at(&aurelia, i as f32 / 64.0, 1.0 - 0.5 * RING_CANAL).canal > 0.9);
        assert!(ring);
        // Four horseshoes: a ring through their middles crosses each twice (both arms).
        let middle = STOMACH + 0.9 * aurelia.gonad_size;
        assert_eq!(runs(&aurelia, middle, |m| m.gonad), 8);
        // Nearer the stomach the horseshoes are open: no gonad on their inner side.
        let inner = middle - 0.7 * 0.5 * aurelia.gonad_size;
        assert_eq!(runs(&aurelia, inner, |m| m.gonad), 0);
        assert_eq!(runs(&aequorea, 0.5, |m| m.gonad), 60);
        assert_eq!(runs(&sarsia, 0.5, |m| m.gonad), 0);
    }

    #[test]
    fn the_exumbrella_is_plain() {
        let s = Species::aurelia();
        for row in 0..HEIGHT / 2 {
            let v = (row as f32 + 0.5) / HEIGHT as f32;
            for i in 0..32 {
                assert_eq!(marks_at(&s, i as f32 / 32.0, v), Marks::default());
            }
        }
        assert_eq!(texels(&s).len(), WIDTH * HEIGHT);
    }
}
