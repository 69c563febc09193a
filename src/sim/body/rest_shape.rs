//! The bell at rest: its subumbrellar outline and the mesoglea's thickness along it.

use crate::species::Species;
use glam::Vec2;
use std::sync::{Arc, Mutex};

/// Mesoglea thickness at arc fraction `s` of the bell (0 at the apex, 1 at the margin), m.
///
/// Thickest at the apex (the paper's ϑ), thinning quadratically towards the margin, as in
/// the paper's Fig. 2 cross-sections.
pub(crate) fn mesoglea_thickness(species: &Species, s: f32) -> f32 {
    let s = s.clamp(0.0, 1.0);
    species.thickness * (1.0 - (1.0 - species.margin_thickness_ratio) * s * s)
}

/// The rest subumbrella: a half-ellipse of the species' diameter and height, aperture
/// centre at the origin, apex at +y, points at equal arc length about `h/2` apart.
///
/// The last few outlines are kept ([`Outlines`]): an edit of a species rebuilds the body
/// of each of its live slices, and jellyfish moving between tiers build new ones, mostly
/// with an outline already made.
pub(crate) fn rest_outline(species: &Species, h: f32) -> Vec<Vec2> {
    let key = [species.diameter, species.height, h].map(f32::to_bits);
    if let Some(known) = OUTLINES.find(key) {
        return known.to_vec();
    }
    let made = make_rest_outline(species.diameter, species.height, h);
    OUTLINES.keep(key, &made);
    made
}

/// The outlines made last, by the bits of the diameter, height and spacing they were made
/// for (all they depend on), newest first: the same points, bit for bit, without the two
/// thousand sines and cosines of making them (half of rebuilding a body).
struct Outlines(Mutex<Vec<Kept>>);

/// An outline, by the bits of its diameter, height and spacing.
type Kept = ([u32; 3], Arc<[Vec2]>);

/// A few species, a few grids each.
const OUTLINES_KEPT: usize = 16;

static OUTLINES: Outlines = Outlines(Mutex::new(Vec::new()));

impl Outlines {
    fn find(&self, key: [u32; 3]) -> Option<Arc<[Vec2]>> {
        let kept = self.0.lock().ok()?;
        kept.iter().find(|(k, _)| *k == key).map(|(_, o)| o.clone())
    }

    fn keep(&self, key: [u32; 3], outline: &[Vec2]) {
        if let Ok(mut kept) = self.0.lock() {
            kept.retain(|(k, _)| *k != key);
            kept.insert(0, (key, Arc::from(outline)));
            kept.truncate(OUTLINES_KEPT);
        }
    }
}

/// [`rest_outline`] for a bell of `diameter` and `height`, points about `h/2` apart.
fn make_rest_outline(diameter: f32, height: f32, h: f32) -> Vec<Vec2> {
    let a = 0.5 * diameter;
    let b = height;
    // Dense polyline from the left margin (θ = π) over the apex to the right margin.
    const DENSE: usize = 2000;
    let dense: Vec<Vec2> = (0..=DENSE)
        .map(|k| {
            let theta = std::f32::consts::PI * (1.0 - k as f32 / DENSE as f32);
            Vec2::new(a * theta.cos(), b * theta.sin())
        })
        .collect();
    let mut cumulative = vec![0.0f32; dense.len()];
    for k in 1..dense.len() {
        cumulative[k] = cumulative[k - 1] + (dense[k] - dense[k - 1]).length();
    }
    let total = cumulative[DENSE];
    // An even number of segments keeps a point on the apex.
    let half = ((total / (0.5 * h)) / 2.0).round().max(6.0) as usize;
    let segments = 2 * half;
    let mut out = Vec::with_capacity(segments + 1);
    let mut k = 0;
    for s in 0..=segments {
        let target = total * s as f32 / segments as f32;
        while k + 1 < DENSE && cumulative[k + 1] < target {
            k += 1;
        }
        let span = (cumulative[k + 1] - cumulative[k]).max(1e-12);
        let f = ((target - cumulative[k]) / span).clamp(0.0, 1.0);
        out.push(dense[k].lerp(dense[k + 1], f));
    }
    // Exact symmetry: mirror the left half onto the right.
    for i in 0..half {
        let p = out[i];
        out[segments - i] = Vec2::new(-p.x, p.y);
    }
    out[half].x = 0.0;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rest_outline_is_symmetric_with_apex_on_axis() {
        let s = Species::aurelia();
        let o = rest_outline(&s, 0.004);
        assert_eq!(o.len() % 2, 1);
        let m = o.len() / 2;
        assert!((o[m] - Vec2::new(0.0, s.height)).length() < 1e-5);
        assert!((o[0] - Vec2::new(-0.02, 0.0)).length() < 1e-5);
        for i in 0..m {
            let mirrored = Vec2::new(-o[i].x, o[i].y);
            assert!((o[o.len() - 1 - i] - mirrored).length() < 1e-6);
        }
        // About half a cell apart.
        let spacing = (o[1] - o[0]).length();
        assert!(spacing > 0.0015 && spacing < 0.0025, "{spacing}");
    }

    /// A kept outline is the one made afresh, bit for bit, for every species and spacing
    /// asked for (more than are kept, so some are made again).
    #[test]
    fn a_kept_outline_is_the_one_made() {
        let species = [Species::aurelia(), Species::aequorea(), Species::sarsia()];
        for round in 0..2 {
            for s in &species {
                for k in 0..8 {
                    let h = 0.0005 * (1.0 + k as f32);
                    let made = make_rest_outline(s.diameter, s.height, h);
                    assert_eq!(rest_outline(s, h), made, "round {round}, h {h}");
                }
            }
        }
    }

    #[test]
    fn thickness_is_largest_at_the_apex() {
        let s = Species::aurelia();
        assert_eq!(mesoglea_thickness(&s, 0.0), s.thickness);
        assert!(mesoglea_thickness(&s, 1.0) < mesoglea_thickness(&s, 0.5));
        assert!(
            (mesoglea_thickness(&s, 1.0) - s.thickness * s.margin_thickness_ratio).abs() < 1e-7
        );
    }
}
