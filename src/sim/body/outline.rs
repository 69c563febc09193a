//! The bell's outline: the subumbrella closed by the aperture chord. A whole bell's
//! outline is a simple polygon with the orientation it has at rest; a crumpled one crosses
//! itself, turns inside out (negative area) or collapses (area under a fifth of rest).

use glam::Vec2;

/// Below this fraction of its rest area an outline counts as crumpled.
pub(crate) const CRUMPLED_AREA: f32 = 0.2;

/// Shoelace area of a closed polygon (unsigned).
pub(crate) fn polygon_area(points: &[Vec2]) -> f32 {
    signed_area(points).abs()
}

/// Signed shoelace area of a closed polygon: positive when the points run clockwise, as
/// the bell's do at rest (left margin, over the apex, to the right margin).
pub(crate) fn signed_area(points: &[Vec2]) -> f32 {
    let n = points.len();
    let twice: f32 = (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum();
    -0.5 * twice
}

/// Whether the closed polygon through `points` crosses itself (edges that touch only at a
/// shared corner do not count).
pub(crate) fn crosses_itself(points: &[Vec2]) -> bool {
    let n = points.len();
    if n < 4 {
        return false;
    }
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    for i in 0..n {
        let (a, b) = edge(i);
        let (lo, hi) = (a.min(b), a.max(b));
        // Skip the neighbours (they share a corner); the first edge's left neighbour is
        // the last edge.
        let last = if i == 0 { n - 1 } else { n };
        for j in i + 2..last {
            let (c, d) = edge(j);
            // Cheap reject on the boxes first.
            if c.max(d).cmplt(lo).any() || c.min(d).cmpgt(hi).any() {
                continue;
            }
            if segments_cross(a, b, c, d) {
                return true;
            }
        }
    }
    false
}

/// Whether `p` lies inside the closed polygon through `points` (even–odd rule).
pub fn contains(points: &[Vec2], p: Vec2) -> bool {
    let n = points.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Unit normals of a left-to-right slice curve, turned away from the bell cavity (+y at an
/// upright apex). Where the curve has no direction (coincident points) the nearest defined
/// normal is reused; a curve with none at all gets +y.
pub fn outward_normals(points: &[Vec2], out: &mut Vec<Vec2>) {
    out.clear();
    let n = points.len();
    out.extend((0..n).map(|i| {
        let tangent = points[(i + 1).min(n - 1)] - points[i.saturating_sub(1)];
        tangent.perp().normalize_or_zero()
    }));
    let Some(first) = out.iter().position(|v| *v != Vec2::ZERO) else {
        out.iter_mut().for_each(|v| *v = Vec2::Y);
        return;
    };
    let mut last = out[first];
    for v in out.iter_mut() {
        if *v == Vec2::ZERO {
            *v = last;
        } else {
            last = *v;
        }
    }
}

/// Proper crossing of segments `ab` and `cd`.
fn segments_cross(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> bool {
    let side = |p: Vec2, q: Vec2, r: Vec2| (q - p).perp_dot(r - p);
    let (d1, d2) = (side(a, b, c), side(a, b, d));
    let (d3, d4) = (side(c, d, a), side(c, d, b));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// What the outline of a bell looks like now, against its rest area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outline {
    /// Signed area over rest area: 1 at rest, negative inside out.
    pub area_ratio: f32,
    /// Whether the outline crosses itself.
    pub crossed: bool,
}

impl Outline {
    /// The outline of a bell whose rest area is `rest_area` (m²).
    pub(crate) fn of(bell: &[Vec2], rest_area: f32) -> Self {
        Self {
            area_ratio: signed_area(bell) / rest_area,
            crossed: crosses_itself(bell),
        }
    }

    /// Crossed, inverted or collapsed.
    pub fn crumpled(&self) -> bool {
        // A NaN area is crumpled too.
        self.crossed || self.area_ratio.is_nan() || self.area_ratio < CRUMPLED_AREA
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dome() -> Vec<Vec2> {
        (0..=20)
            .map(|k| {
                let t = std::f32::consts::PI * (1.0 - k as f32 / 20.0);
                Vec2::new(t.cos(), 0.7 * t.sin())
            })
            .collect()
    }

    #[test]
    fn a_dome_is_whole_and_clockwise() {
        let d = dome();
        let o = Outline::of(&d, signed_area(&d));
        assert!(signed_area(&d) > 0.0);
        assert!(!o.crossed && !o.crumpled());
        assert!((o.area_ratio - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_fold_and_an_inversion_are_crumpled() {
        let rest = signed_area(&dome());
        // The left margin folded across the right half.
        let mut folded = dome();
        folded[0] = Vec2::new(0.8, 0.5);
        folded[1] = Vec2::new(0.9, 0.3);
        assert!(crosses_itself(&folded));
        assert!(Outline::of(&folded, rest).crumpled());
        // Inside out: the apex pushed below the aperture chord.
        let inverted: Vec<Vec2> = dome().iter().map(|p| Vec2::new(p.x, -p.y)).collect();
        let o = Outline::of(&inverted, rest);
        assert!(!o.crossed && o.area_ratio < 0.0 && o.crumpled());
        // Flattened to a sliver.
        let flat: Vec<Vec2> = dome().iter().map(|p| Vec2::new(p.x, 0.1 * p.y)).collect();
        assert!(Outline::of(&flat, rest).crumpled());
    }
}
