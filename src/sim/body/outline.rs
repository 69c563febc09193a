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
    if n > SWEPT || !points.iter().all(|p| p.is_finite()) {
        return crosses_itself_pairwise(points);
    }
    // A bell's outline has a few dozen points: its sort buffer on the stack, no bigger
    // than it needs (zeroing the largest one was a tenth of the check).
    if n <= SWEPT_SMALL {
        crosses_itself_swept::<SWEPT_SMALL>(points)
    } else {
        crosses_itself_swept::<SWEPT>(points)
    }
}

/// [`crosses_itself`] for `points.len() ≤ N` finite points, swept along x.
fn crosses_itself_swept<const N: usize>(points: &[Vec2]) -> bool {
    let n = points.len();
    // Sweep along x: the edges by the left end of their boxes, each tested only against
    // those whose box starts before its own ends (a bell's two flanks never meet them).
    // The same pairs pass the box test as in the pairwise check, so the same answer.
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    // Each edge as its box's left end (ordered bits of a finite f32) above its index, so
    // that one integer sort orders them.
    let mut order = [0u64; N];
    let order = &mut order[..n];
    for (i, o) in order.iter_mut().enumerate() {
        let (a, b) = edge(i);
        *o = (u64::from(ordered_bits(a.x.min(b.x))) << 32) | i as u64;
    }
    order.sort_unstable();
    for (s, &i) in order.iter().enumerate() {
        let i = i as u32;
        let (a, b) = edge(i as usize);
        let (lo, hi) = (a.min(b), a.max(b));
        for &j in &order[s + 1..] {
            let j = j as u32;
            let (c, d) = edge(j as usize);
            if c.x.min(d.x) > hi.x {
                break;
            }
            let (i, j) = (i.min(j) as usize, i.max(j) as usize);
            // Neighbours share a corner, the first and the last edge too.
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
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

/// A finite `x`'s bits, ordered as `x` is: the sign bit flipped for positives, every bit
/// for negatives.
fn ordered_bits(x: f32) -> u32 {
    let bits = x.to_bits();
    if bits >> 31 == 0 {
        bits | 1 << 31
    } else {
        !bits
    }
}

/// Outlines of at most this many points are swept (sorted on the stack).
const SWEPT: usize = 512;
/// Outlines of at most this many points (every shipped bell's) sort in a smaller buffer.
const SWEPT_SMALL: usize = 96;

/// [`crosses_itself`] edge pair by edge pair: every pair whose boxes meet.
fn crosses_itself_pairwise(points: &[Vec2]) -> bool {
    let n = points.len();
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

/// The subumbrella's shape as `SliceSim::bell_points` gives it (margin, apex, margin):
/// its depth (apex to the margins' midpoint) over its width at its widest, and the
/// margin's width, m. The measure *Aurelia*'s records use for a saucer and a half-dome.
pub fn cavity(bell: &[Vec2]) -> (f32, f32) {
    let (Some(&left), Some(&right)) = (bell.first(), bell.last()) else {
        return (0.0, 0.0);
    };
    let apex = bell[bell.len() / 2];
    let (least, most) = bell.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| {
        (lo.min(p.x), hi.max(p.x))
    });
    let depth = apex.y - 0.5 * (left.y + right.y);
    (depth / (most - least).max(1e-9), (right - left).length())
}

/// Whether `p` lies inside the closed polygon through `points` (even–odd rule).
pub fn contains(points: &[Vec2], p: Vec2) -> bool {
    let crosses = |a: Vec2, b: Vec2| {
        (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)
    };
    // Each edge from a point to the next, the closing one last (no index wrapped by a
    // division per edge: this runs for every tentacle point, every step).
    let closing = match points {
        [first, .., last] => crosses(*last, *first),
        _ => false,
    };
    points
        .windows(2)
        .fold(closing, |inside, w| inside != crosses(w[0], w[1]))
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

    /// The sweep finds a crossing exactly where the pairwise check does: random walks
    /// that fold back on themselves now and then, and ones that never do.
    #[test]
    fn the_sweep_is_the_pairwise_check() {
        let mut seed = 7u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        let (mut crossed, mut whole) = (0, 0);
        for trial in 0..400 {
            // Both sort buffers: most outlines small, one in seven past the small one.
            let n = if trial % 7 == 0 {
                97 + trial % 90
            } else {
                4 + trial % 60
            };
            let wiggle = [0.05, 0.3, 1.5][trial % 3];
            let points: Vec<Vec2> = (0..n)
                .map(|k| {
                    let t = std::f32::consts::PI * (1.0 - k as f32 / (n - 1) as f32);
                    let jitter = Vec2::new(next() - 0.5, next() - 0.5) * wiggle;
                    Vec2::new(t.cos(), 0.7 * t.sin()) + jitter
                })
                .collect();
            let expected = crosses_itself_pairwise(&points);
            assert_eq!(crosses_itself(&points), expected, "trial {trial}");
            if expected { crossed += 1 } else { whole += 1 }
        }
        assert!(
            crossed > 50 && whole > 50,
            "{crossed} crossed, {whole} whole"
        );
    }

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

    /// The even–odd rule on a bell's slice: a U open at the bottom (the subumbrella's
    /// cavity is outside the mesoglea's band), closed by its last edge back to the first;
    /// points in the band, in the cavity, below and beside it, and the degenerate
    /// polygons.
    #[test]
    fn a_point_is_inside_the_band_not_the_cavity() {
        // Exumbrella from the left margin over the apex to the right margin, then the
        // subumbrella back under it: a band 0.2 thick.
        let mut bell: Vec<Vec2> = (0..=16)
            .map(|k| {
                let a = std::f32::consts::PI * k as f32 / 16.0;
                Vec2::new(-a.cos(), a.sin())
            })
            .collect();
        bell.extend((0..=16).rev().map(|k| {
            let a = std::f32::consts::PI * k as f32 / 16.0;
            Vec2::new(-0.8 * a.cos(), 0.8 * a.sin())
        }));
        for (p, inside) in [
            (Vec2::new(0.0, 0.9), true),
            (Vec2::new(-0.65, 0.65), true),
            (Vec2::new(0.0, 0.5), false),
            (Vec2::new(0.0, -0.3), false),
            (Vec2::new(1.5, 0.2), false),
            (Vec2::new(0.0, 1.2), false),
        ] {
            assert_eq!(contains(&bell, p), inside, "{p}");
            // The same polygon from another first point.
            bell.rotate_left(5);
            assert_eq!(contains(&bell, p), inside, "{p}, rotated");
        }
        assert!(!contains(&[], Vec2::ZERO));
        assert!(!contains(&[Vec2::ZERO], Vec2::ZERO));
        assert!(!contains(&[Vec2::ZERO, Vec2::ONE], Vec2::splat(0.5)));
    }
}
