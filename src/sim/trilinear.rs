//! Trilinear sampling of a vector field stored at the nodes of a regular 3D grid.

use glam::{UVec3, Vec3};

/// A regular grid of nodes: `size` along x, y, z, `spacing` apart from `origin`.
/// Fields on it are stored x fastest, then y, then z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trilinear {
    /// World position of the first node.
    pub origin: Vec3,
    /// Distance between nodes.
    pub spacing: f32,
    /// Nodes along x, y, z.
    pub size: UVec3,
}

impl Trilinear {
    /// Where node (i, j, k) is stored.
    pub fn index(&self, i: u32, j: u32, k: u32) -> usize {
        ((k * self.size.y + j) * self.size.x + i) as usize
    }

    /// `field` at `point`, trilinear between the nodes around it and held at the grid's
    /// edges; zero for a non-finite point's missing neighbours, an empty grid or a field
    /// too short for it.
    pub fn sample(&self, field: &[Vec3], point: Vec3) -> Vec3 {
        let s = self.size;
        if s.min_element() == 0 || field.len() < (s.x * s.y * s.z) as usize {
            return Vec3::ZERO;
        }
        let g =
            ((point - self.origin) / self.spacing.max(1e-9)).clamp(Vec3::ZERO, (s - 1).as_vec3());
        let g = if g.is_finite() { g } else { Vec3::ZERO };
        // Finite and not negative: truncation is the floor (a library call each, on
        // x86-64 without SSE4.1, for every sample of every jellyfish).
        let i0 = g.as_uvec3().min(s - 1);
        let i1 = (i0 + 1).min(s - 1);
        let f = g - i0.as_vec3();
        let at = |i: u32, j: u32, k: u32| field[self.index(i, j, k)];
        let lerp = |a: Vec3, b: Vec3, t: f32| a + (b - a) * t;
        let x00 = lerp(at(i0.x, i0.y, i0.z), at(i1.x, i0.y, i0.z), f.x);
        let x10 = lerp(at(i0.x, i1.y, i0.z), at(i1.x, i1.y, i0.z), f.x);
        let x01 = lerp(at(i0.x, i0.y, i1.z), at(i1.x, i0.y, i1.z), f.x);
        let x11 = lerp(at(i0.x, i1.y, i1.z), at(i1.x, i1.y, i1.z), f.x);
        lerp(lerp(x00, x10, f.y), lerp(x01, x11, f.y), f.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_between_nodes_and_holds_at_the_edges() {
        let grid = Trilinear {
            origin: Vec3::ZERO,
            spacing: 1.0,
            size: UVec3::new(2, 2, 2),
        };
        let field: Vec<Vec3> = (0..8).map(|k| Vec3::splat((k & 1) as f32)).collect();
        assert_eq!(
            grid.sample(&field, Vec3::new(0.25, 0.5, 0.5)),
            Vec3::splat(0.25)
        );
        assert_eq!(grid.sample(&field, Vec3::new(5.0, 0.0, 0.0)), Vec3::ONE);
        assert_eq!(grid.sample(&field, Vec3::NAN), Vec3::ZERO);
        assert_eq!(grid.sample(&field[..7], Vec3::ZERO), Vec3::ZERO);
    }

    #[test]
    fn a_linear_field_is_reproduced_exactly_inside() {
        let grid = Trilinear {
            origin: Vec3::new(-1.0, 2.0, 0.5),
            spacing: 0.5,
            size: UVec3::new(4, 3, 5),
        };
        let linear = |p: Vec3| Vec3::new(p.x + 2.0 * p.y, -p.z, 3.0 * p.x - p.y + p.z);
        let mut field = vec![Vec3::ZERO; 60];
        for k in 0..5 {
            for j in 0..3 {
                for i in 0..4 {
                    let p = grid.origin + Vec3::new(i as f32, j as f32, k as f32) * 0.5;
                    field[grid.index(i, j, k)] = linear(p);
                }
            }
        }
        let p = Vec3::new(-0.3, 2.7, 1.9);
        assert!((grid.sample(&field, p) - linear(p)).length() < 1e-5);
    }
}
