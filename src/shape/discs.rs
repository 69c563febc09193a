//! 3D extrapolation (paper 3.5): each opposite pair becomes a disc about its own axis.
//!
//! The axis runs through the pair's midpoint, orthogonal to the segment between the two
//! points, in the slice plane; the disc is the circle the pair sweeps about it. Each pair has
//! its own axis, so an asymmetric slice gives an asymmetric bell. The slice plane is the 3D
//! x-y plane (y the bell axis); the angle σ turns from the right point (σ = 0) through +z to
//! the left point (σ = π).

use glam::{Vec2, Vec3};

/// The circle swept by one opposite pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disc {
    /// The disc's centre on the axis, metres.
    pub centre: Vec3,
    /// Its radius, metres.
    pub radius: f32,
    /// Unit direction from the centre to the right point, in the slice plane.
    pub radial: Vec2,
}

impl Disc {
    /// The disc through `left` and `right`. A coincident pair (the apex) has radius 0 and
    /// borrows `fallback` as its radial direction, so the frame never has a NaN.
    pub fn through(left: Vec2, right: Vec2, fallback: Vec2) -> Self {
        let half = 0.5 * (right - left);
        let radius = half.length();
        let radial = if radius > 0.0 {
            (half / radius).normalize_or(fallback)
        } else {
            fallback
        };
        let c = 0.5 * (left + right);
        Self {
            centre: Vec3::new(c.x, c.y, 0.0),
            radius,
            radial,
        }
    }

    /// The disc's axis, in the slice plane: +y for an upright level pair.
    pub fn axis(&self) -> Vec3 {
        let a = self.radial.perp();
        Vec3::new(a.x, a.y, 0.0)
    }

    /// Unit direction from the centre towards angle σ, given as `(cos σ, sin σ)`.
    pub fn direction(&self, (cos, sin): (f32, f32)) -> Vec3 {
        Vec3::new(self.radial.x * cos, self.radial.y * cos, sin)
    }

    /// The point at angle σ, given as `(cos σ, sin σ)`.
    pub fn point(&self, cs: (f32, f32)) -> Vec3 {
        self.centre + self.radius * self.direction(cs)
    }

    /// The slice normals `[left, right]` swept to angle σ: each side's normal split into a
    /// radial and an axial part, blended from the right (σ = 0) to the left (σ = π). A
    /// symmetric pair gives the rotated normal exactly.
    pub fn normal(&self, normals: [Vec2; 2], cs: (f32, f32)) -> Vec3 {
        let a = self.radial.perp();
        let (right_radial, right_axial) = (normals[1].dot(self.radial), normals[1].dot(a));
        let (left_radial, left_axial) = (-normals[0].dot(self.radial), normals[0].dot(a));
        let w = 0.5 * (1.0 - cs.0);
        let radial = right_radial + (left_radial - right_radial) * w;
        let axial = right_axial + (left_axial - right_axial) * w;
        (radial * self.direction(cs) + axial * self.axis()).normalize_or(self.axis())
    }
}

/// `(cos σ, sin σ)` for `count` angles evenly around the circle, from σ = 0.
pub fn angles(count: usize, out: &mut Vec<(f32, f32)>) {
    out.clear();
    out.extend((0..count).map(|j| {
        let (s, c) = (std::f32::consts::TAU * j as f32 / count as f32).sin_cos();
        (c, s)
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disc_passes_through_both_points_about_its_own_axis() {
        // A tilted pair: the axis is orthogonal to the segment, not the slice's y.
        let (l, r) = (Vec2::new(-1.0, 0.5), Vec2::new(2.0, 1.5));
        let d = Disc::through(l, r, Vec2::X);
        assert!(d.point((1.0, 0.0)).distance(Vec3::new(r.x, r.y, 0.0)) < 1e-6);
        assert!(d.point((-1.0, 0.0)).distance(Vec3::new(l.x, l.y, 0.0)) < 1e-6);
        let seg = Vec3::new(r.x - l.x, r.y - l.y, 0.0);
        assert!(d.axis().dot(seg).abs() < 1e-6);
        let mut cs = Vec::new();
        angles(12, &mut cs);
        for &a in &cs {
            let p = d.point(a);
            assert!((p.distance(d.centre) - d.radius).abs() < 1e-5);
            assert!((p - d.centre).dot(d.axis()).abs() < 1e-6);
        }
    }

    #[test]
    fn coincident_pair_is_a_finite_point() {
        let p = Vec2::new(0.3, 0.7);
        let d = Disc::through(p, p, Vec2::X);
        assert_eq!(d.radius, 0.0);
        assert_eq!(d.point((0.0, 1.0)), Vec3::new(0.3, 0.7, 0.0));
        let n = d.normal([Vec2::ZERO, Vec2::ZERO], (0.0, 1.0));
        assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn swept_normal_is_each_sides_own_normal_in_the_slice_plane() {
        let d = Disc::through(Vec2::new(-1.0, 0.2), Vec2::new(1.5, -0.1), Vec2::X);
        let (left, right) = (Vec2::new(-0.3, 0.9).normalize(), Vec2::new(0.8, 0.6));
        let lift = |v: Vec2| Vec3::new(v.x, v.y, 0.0);
        assert!(d.normal([left, right], (1.0, 0.0)).distance(lift(right)) < 1e-6);
        assert!(d.normal([left, right], (-1.0, 0.0)).distance(lift(left)) < 1e-6);
    }

    #[test]
    fn symmetric_normals_sweep_as_a_rotation() {
        let d = Disc::through(Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0), Vec2::X);
        let n = Vec2::new(0.6, 0.8);
        let normals = [Vec2::new(-n.x, n.y), n];
        let mut cs = Vec::new();
        angles(8, &mut cs);
        for &(c, s) in &cs {
            let expect = Vec3::new(0.6 * c, 0.8, 0.6 * s);
            assert!(d.normal(normals, (c, s)).distance(expect) < 1e-6);
        }
    }
}
