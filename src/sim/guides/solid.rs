//! The bell as a solid a guide's nodes stay out of: the mesoglea and the cavity it
//! closes, in the meridian (a body of revolution about the axis, as the surface sweeps it).

use crate::sim::body::{contains, mesoglea_thickness, outward_normals};
use crate::species::Species;
use glam::{Vec2, Vec3};

/// The bell's two outlines in the meridian: its cavity (the subumbrella closed by the
/// aperture chord, what the slice keeps its own fringe out of) and the whole bell (the
/// exumbrella from margin to margin, closed through the aperture).
#[derive(Clone, Debug, Default)]
pub struct Solid {
    cavity: Vec<Vec2>,
    whole: Vec<Vec2>,
    normals: Vec<Vec2>,
    /// The whole bell's bounding box in the meridian: most nodes hang below it.
    bounds: (Vec2, Vec2),
    /// The cavity's, the same way.
    cavity_bounds: (Vec2, Vec2),
    /// The subumbrella from the apex to the right margin where it only ever descends
    /// (else empty): a meridian point is in the cavity where it lies left of it.
    descent: Vec<Vec2>,
    /// How far outside an outline a node is put back: a thousandth of the span.
    clearance: f32,
}

impl Solid {
    /// The solid of the slice's subumbrella `bell` (left margin over the apex to the right
    /// margin), with the species' wall thickness, relative to `origin`.
    pub fn rebuild(&mut self, bell: &[Vec2], origin: Vec2, species: &Species) {
        self.cavity.clear();
        self.whole.clear();
        let n = bell.len();
        if n < 3 {
            return;
        }
        outward_normals(bell, &mut self.normals);
        let mid = (n - 1) / 2;
        for (i, (p, normal)) in bell.iter().zip(&self.normals).enumerate() {
            let s = i.abs_diff(mid) as f32 / mid.max(1) as f32;
            self.whole
                .push(*p + *normal * mesoglea_thickness(species, s) - origin);
            self.cavity.push(*p - origin);
        }
        self.whole.push(bell[n - 1] - origin);
        self.whole.push(bell[0] - origin);
        self.bounds = meridian_bounds(self.whole.iter().chain(&self.cavity));
        self.cavity_bounds = meridian_bounds(&self.cavity);
        let right = &self.cavity[mid..];
        self.descent.clear();
        if right.windows(2).all(|w| w[1].y < w[0].y && w[1].x >= 0.0) {
            self.descent.extend_from_slice(right);
        }
        self.clearance = 1e-3 * bell[0].distance(bell[n - 1]);
    }

    /// Whether the body-frame point `p` lies inside the bell, wall or cavity.
    pub fn contains(&self, p: Vec3) -> bool {
        self.near(meridian(p)) && inside(&self.whole, meridian(p))
    }

    /// Whether a meridian point lies within the bell's bounding box.
    fn near(&self, q: Vec2) -> bool {
        within(self.bounds, q)
    }

    /// Whether a meridian point lies in the cavity (its box first: most nodes hang below;
    /// then, where the subumbrella only descends, the one stretch of it at the point's
    /// height, the even-odd rule's crossing on that side).
    fn in_cavity(&self, q: Vec2) -> bool {
        if !within(self.cavity_bounds, q) {
            return false;
        }
        if self.descent.len() < 2 {
            return inside(&self.cavity, q);
        }
        let d = &self.descent;
        let k = d.partition_point(|p| p.y > q.y);
        if k == 0 || k == d.len() {
            return false;
        }
        let (a, b) = (d[k - 1], d[k]);
        q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x)
    }

    /// Where a node the slice draws at `reference` may be drawn instead of `p`: outside
    /// the bell, or where the slice itself draws it inside the wall (its fringe keeps out
    /// of the cavity only), outside the cavity; put back just outside the nearest point
    /// of the outline, at the same angle around the axis.
    pub fn keep_out(&self, p: Vec3, reference: Vec3) -> Vec3 {
        // Most nodes hang below the bell's box: nothing to keep them out of.
        if !self.near(meridian(p)) {
            return p;
        }
        let outline = if self.contains(reference) {
            &self.cavity
        } else {
            &self.whole
        };
        if !inside(outline, meridian(p)) {
            return p;
        }
        // Where the outline folds back on itself (a contracted margin), just past the
        // nearest edge can be inside again: step out edge by edge, and where that does not
        // leave the fold, draw the node where the slice draws it.
        let mut placed = meridian(p);
        for _ in 0..4 {
            placed = nearest_outside(outline, placed, self.clearance);
            if !inside(outline, placed) {
                return on_meridian(p, placed);
            }
        }
        if inside(outline, meridian(reference)) {
            on_meridian(p, placed)
        } else {
            reference
        }
    }

    /// Where a node of a part hanging within the bell (the manubrium, an oral arm) may
    /// be drawn instead of `p`, the node before it drawn at `previous`: never in the
    /// mesoglea, and never through the subumbrella out of the cavity or into it, so
    /// in the cavity, or out of it through the aperture (a segment that does not leave or
    /// enter the cavity may cut a fold of the wall, as the straight chord of a curved
    /// tube does). A node that would be is put back on its predecessor's side: just
    /// inside the cavity, or just outside the bell, at the same angle around the axis.
    /// Where the slice itself draws the segment (`reference`, from `reference_previous`;
    /// within the clearance) it is left, through the subumbrella or not: its oral chains
    /// are carried by its water alone. `previous` comes with whether it is in the cavity
    /// ([`Self::in_cavity_at`]), and so does the node placed: a chain is walked from its
    /// root.
    pub fn keep_within(
        &self,
        (previous, in_a): (Vec3, bool),
        p: Vec3,
        reference_previous: Vec3,
        reference: Vec3,
    ) -> (Vec3, bool) {
        let (a, b) = (meridian(previous), meridian(p));
        let in_b = self.in_cavity(b);
        let drawn_as_the_slice = previous.distance_squared(reference_previous)
            <= self.clearance * self.clearance
            && p.distance_squared(reference) <= self.clearance * self.clearance;
        if drawn_as_the_slice || (!self.near(a) && !self.near(b)) {
            return (p, in_b);
        }
        let (ra, rb) = (meridian(reference_previous), meridian(reference));
        let walled = !in_b && self.near(b) && inside(&self.whole, b) && !self.in_wall(rb);
        let crossing = in_a != in_b
            && self.through_subumbrella(a, b)
            && !(self.in_cavity(ra) != self.in_cavity(rb) && self.through_subumbrella(ra, rb));
        if !(walled || crossing) {
            return (p, in_b);
        }
        let placed = if in_a {
            let c = nearest_on(&self.cavity, b);
            let inward = match in_b {
                true => b - c,
                false => c - b,
            };
            c + inward.normalize_or_zero() * self.clearance
        } else if inside(&self.whole, b) {
            nearest_outside(&self.whole, b, self.clearance)
        } else {
            b
        };
        (on_meridian(p, placed), in_a)
    }

    /// Whether the body-frame point `p` lies in the cavity.
    pub fn in_cavity_at(&self, p: Vec3) -> bool {
        self.in_cavity(meridian(p))
    }

    /// Whether a meridian point lies in the mesoglea: in the bell, not in its cavity.
    fn in_wall(&self, q: Vec2) -> bool {
        self.near(q) && inside(&self.whole, q) && !self.in_cavity(q)
    }

    /// Whether the meridian segment `a`–`b` passes through the subumbrella (the cavity's
    /// outline less the aperture chord), on either side of the axis; a segment that
    /// starts on it (the manubrium's root at the apex) does not.
    fn through_subumbrella(&self, a: Vec2, b: Vec2) -> bool {
        let mirror = |p: Vec2| Vec2::new(-p.x, p.y);
        [(a, b), (mirror(a), mirror(b))].into_iter().any(|(a, b)| {
            self.cavity
                .windows(2)
                .any(|w| segments_cross(a, b, w[0], w[1]))
        })
    }
}

/// Whether segment `a`–`b` crosses segment `p`–`q` past its own start.
fn segments_cross(a: Vec2, b: Vec2, p: Vec2, q: Vec2) -> bool {
    let (ab, pq) = (b - a, q - p);
    let d = ab.perp_dot(pq);
    if d.abs() < 1e-18 {
        return false;
    }
    let t = (p - a).perp_dot(pq) / d;
    let u = (p - a).perp_dot(ab) / d;
    t > 1e-3 && t <= 1.0 && (0.0..=1.0).contains(&u)
}

/// The body-frame point at the meridian point `placed` (its radius and height), at the
/// angle around the axis of `p`.
fn on_meridian(p: Vec3, placed: Vec2) -> Vec3 {
    let around = Vec2::new(p.x, p.z).normalize_or(Vec2::X);
    let r = placed.x.abs();
    Vec3::new(r * around.x, placed.y, r * around.y)
}

/// The box in the meridian (radius, height) of points on both sides of the axis: the
/// radius is never negative, and spans the wider side.
fn meridian_bounds<'a>(points: impl IntoIterator<Item = &'a Vec2>) -> (Vec2, Vec2) {
    let (lo, hi) = points.into_iter().fold(
        (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (Vec2::new(0.0, lo.y), Vec2::new(hi.x.max(-lo.x), hi.y))
}

fn within((lo, hi): (Vec2, Vec2), q: Vec2) -> bool {
    q.cmpge(lo).all() && q.cmple(hi).all()
}

fn inside(outline: &[Vec2], q: Vec2) -> bool {
    outline.len() >= 3 && contains(outline, q)
}

/// The point of the closed `outline` nearest `q`, moved `clearance` further out.
fn nearest_outside(outline: &[Vec2], q: Vec2, clearance: f32) -> Vec2 {
    let c = nearest_on(outline, q);
    c + (c - q).normalize_or_zero() * clearance
}

/// The point of the closed `outline` nearest `q`.
fn nearest_on(outline: &[Vec2], q: Vec2) -> Vec2 {
    let n = outline.len();
    let mut best = (f32::MAX, q);
    for k in 0..n {
        let (a, b) = (outline[k], outline[(k + 1) % n]);
        let ab = b - a;
        let t = ((q - a).dot(ab) / ab.length_squared().max(1e-18)).clamp(0.0, 1.0);
        let c = a + t * ab;
        let d = c.distance_squared(q);
        if d < best.0 {
            best = (d, c);
        }
    }
    best.1
}

/// A body-frame point in the meridian: its distance from the axis and its height.
fn meridian(p: Vec3) -> Vec2 {
    Vec2::new(Vec2::new(p.x, p.z).length(), p.y)
}
