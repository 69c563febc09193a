//! Where the immersed boundary meets the grid: points read the velocity of the faces
//! around them and spread their forces back onto the same faces with the same weights,
//! which makes interpolation and spreading adjoint and spreading exactly force-conserving.

use super::symmetry::mirror_past_axis;
use super::{Component, Fluid};
use crate::sim::kernel::{Stencil, reach, span};
use glam::Vec2;

impl Fluid {
    /// Adds the accumulated force density, then clears it: only the rows it was spread
    /// to ([`Fluid::force_rows`]), the rest being zero. A slice solved on its half adds
    /// it there, then mirrors the faces just past the axis (which its viscosity and
    /// divergence read); the projection mirrors the rest.
    pub(crate) fn apply_force(&mut self, dt: f32) {
        let scale = dt / self.rho;
        let (n, rows) = (self.n, std::mem::take(&mut self.force_rows));
        let solved = self.half().map(|r| r.solved);
        for (field, force, row, count) in [
            (&mut self.u, &mut self.force_u, n + 1, n),
            (&mut self.v, &mut self.force_v, n, n + 1),
        ] {
            let faces = rows.start.min(count) * row..rows.end.min(count) * row;
            let (field, force) = (&mut field[faces.clone()], &mut force[faces]);
            let columns = solved.unwrap_or(row);
            for (u, f) in field.chunks_exact_mut(row).zip(force.chunks_exact_mut(row)) {
                for (u, f) in u[..columns].iter_mut().zip(&f[..columns]) {
                    *u += scale * *f;
                }
                f.fill(0.0);
            }
        }
        if solved.is_some() {
            mirror_past_axis(&mut self.u, &mut self.v, n);
        }
        self.enforce_walls();
    }

    /// Widens the rows that may hold force to `rows` as well.
    pub(crate) fn force_in_rows(&mut self, rows: std::ops::Range<usize>) {
        self.force_rows = span(std::mem::take(&mut self.force_rows), rows);
    }

    /// Velocity at a point, per component under the fluid's kernel.
    pub fn velocity_at(&self, p: Vec2) -> Vec2 {
        Vec2::new(
            self.sample_component(Component::U, p),
            self.sample_component(Component::V, p),
        )
    }

    /// Sample of one component under the fluid's kernel. Outside the box, the nearest
    /// faces' values. Inlined: its stencil, returned by value, is large.
    #[inline]
    pub(crate) fn sample_component(&self, c: Component, p: Vec2) -> f32 {
        let field = match c {
            Component::U => &self.u,
            Component::V => &self.v,
        };
        self.stencil(c, p).sample(field)
    }

    /// The faces of component `c` around `p` and their weights under the fluid's
    /// [`Kernel`] (summing to 1). Interpolation and force spreading both use this, which
    /// makes them adjoint.
    pub(crate) fn stencil(&self, c: Component, p: Vec2) -> Stencil {
        let mut s = Stencil::default();
        self.locate(c, p, &mut s);
        s
    }

    /// Where `p` lies among the faces of component `c`, in face spacings, and how many
    /// faces there are across and along.
    pub(crate) fn in_faces(&self, c: Component, p: Vec2) -> ((f32, f32), (usize, usize)) {
        let n = self.n;
        match c {
            Component::U => ((p.x / self.h, p.y / self.h - 0.5), (n + 1, n)),
            Component::V => ((p.x / self.h - 0.5, p.y / self.h), (n, n + 1)),
        }
    }

    /// Whether a point of a slice solved on its half ([`Fluid::half`]) lies so far past
    /// the axis that no face of its stencils is in the solved half: what it spreads there
    /// is dropped (the projection mirrors the solved half over it), and what it reads is
    /// the mirror image of what its partner before the axis reads. Always false for a
    /// planar slice free to tilt.
    pub(crate) fn beyond_the_solved_half(&self, p: Vec2) -> bool {
        let Some(solved) = self.half().map(|r| r.solved) else {
            return false;
        };
        // The first `u` face of its stencil past the last one applied (`solved`), with a
        // face to spare; `v`'s stencil starts half a cell further out.
        p.x / self.h - reach(self.kernel, self.kernel_stretch) > solved as f32 + 1.0
    }

    /// [`Self::stencil`], written over `out`.
    pub(crate) fn locate(&self, c: Component, p: Vec2, out: &mut Stencil) {
        let (at, faces) = self.in_faces(c, p);
        out.locate(self.kernel, at, faces, self.kernel_stretch);
        if let Some(rings) = self.rings() {
            let reach = reach(self.kernel, self.kernel_stretch) * self.h;
            if rings.within_reach_of_axis(p.x, reach) {
                rings.weigh_by_volume_near_axis(c, out, reach);
            }
        }
    }
}
