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
        let (lo, hi) = self.whole.iter().chain(&self.cavity).fold(
            (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        // The meridian's radius is never negative: the box spans the wider side.
        self.bounds = (Vec2::new(0.0, lo.y), Vec2::new(hi.x.max(-lo.x), hi.y));
        self.clearance = 1e-3 * bell[0].distance(bell[n - 1]);
    }

    /// Whether the body-frame point `p` lies inside the bell, wall or cavity.
    pub fn contains(&self, p: Vec3) -> bool {
        self.near(meridian(p)) && inside(&self.whole, meridian(p))
    }

    /// Whether a meridian point lies within the bell's bounding box.
    fn near(&self, q: Vec2) -> bool {
        let (lo, hi) = self.bounds;
        q.cmpge(lo).all() && q.cmple(hi).all()
    }

    /// Where a node the slice draws at `reference` may be drawn instead of `p`: outside
    /// the bell, or where the slice itself draws it inside the wall (its fringe keeps out
    /// of the cavity only), outside the cavity; put back just outside the nearest point
    /// of the outline, at the same angle around the axis.
    pub fn keep_out(&self, p: Vec3, reference: Vec3) -> Vec3 {
        let outline = if self.contains(reference) {
            &self.cavity
        } else {
            &self.whole
        };
        if !(self.near(meridian(p)) && inside(outline, meridian(p))) {
            return p;
        }
        let placed = nearest_outside(outline, meridian(p), self.clearance);
        let around = Vec2::new(p.x, p.z).normalize_or(Vec2::X);
        let r = placed.x.abs();
        Vec3::new(r * around.x, placed.y, r * around.y)
    }
}

fn inside(outline: &[Vec2], q: Vec2) -> bool {
    outline.len() >= 3 && contains(outline, q)
}

/// The point of the closed `outline` nearest `q`, moved `clearance` further out.
fn nearest_outside(outline: &[Vec2], q: Vec2, clearance: f32) -> Vec2 {
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
    best.1 + (best.1 - q).normalize_or_zero() * clearance
}

/// A body-frame point in the meridian: its distance from the axis and its height.
fn meridian(p: Vec3) -> Vec2 {
    Vec2::new(Vec2::new(p.x, p.z).length(), p.y)
}
