//! The bell's unresolved mode: the zigzag along the chain the water cannot see, relaxed
//! under the bell's own springs (`Body::relax_unresolved`), and what that relaxation adds
//! to the water's response in the implicit solve (`Body::add_relaxation`).

use super::Body;
use crate::sim::response::Response;
use glam::Vec2;

/// Minus a quarter of the second difference along a chain of `n ≥ 3` points at point `i`,
/// as `(point, weight)` taps: 1 on the alternating mode, ~0 on smooth ones; one-sided at
/// the margins.
fn high_pass(i: usize, n: usize) -> [(usize, f32); 3] {
    if i == 0 {
        [(0, 0.25), (1, -0.5), (2, 0.25)]
    } else if i == n - 1 {
        [(n - 1, 0.25), (n - 2, -0.5), (n - 3, 0.25)]
    } else {
        [(i - 1, -0.25), (i, 0.5), (i + 1, -0.25)]
    }
}

impl Body {
    /// Moves the bell's points by the part of their implicit displacement the fluid cannot
    /// see: `δ = forces · dt²/m`, high-passed along the chain.
    ///
    /// The points move with the interpolated water, and a kernel three cells wide cannot
    /// represent neighbouring points half a cell apart moving oppositely: a zigzag along the
    /// subumbrella spreads no net force, so the water never straightens it, and the
    /// grid-scale unevenness of interpolation feeds it every step until the bell is a saw
    /// blade. Here that part relaxes under the bell's own springs, with the mass the
    /// implicit solve assumed; a smooth displacement's high-pass is of order (spacing/
    /// wavelength)², so everything the water does see is left to the water. Like the
    /// filters of vortex-sheet methods (Krasny 1986), only unresolved modes are touched.
    pub(crate) fn relax_unresolved(&mut self, forces: &[Vec2], dt2_over_mass: &[f32]) {
        let n = self.bell.len();
        if n < 3 {
            return;
        }
        let f = &forces[self.bell.clone()];
        let high = |i: usize| {
            high_pass(i, n)
                .iter()
                .fold(Vec2::ZERO, |sum, &(k, w)| sum + w * f[k])
        };
        // The shift reads the forces only, so it moves the points as it goes.
        let first = self.bell.start;
        for (i, p) in self.points[self.bell.clone()].iter_mut().enumerate() {
            *p += dt2_over_mass[first + i] * high(i);
        }
    }

    /// Adds to `water` the displacement [`Self::relax_unresolved`] gives each solved bell
    /// point for a unit force on each (and its mirror image): the solve then finds forces
    /// whose whole displacement, the water's and the relaxation's, the springs agree with.
    /// Left out, the rowers' strokes turned irregular (`docs/numerics.md`).
    pub(crate) fn add_relaxation(&self, water: &mut Response, dt2_over_mass: &[f32]) {
        let n = self.bell.len();
        if n < 3 {
            return;
        }
        for p in 0..water.len() {
            let b = water.points()[p];
            let i = b - self.bell.start;
            for (k, w) in high_pass(i, n) {
                let Some((q, mirrored)) = self.bell_solver.place(self.bell.start + k) else {
                    continue;
                };
                let shift = dt2_over_mass[b] * w;
                water.add(0, p, q, if mirrored { -shift } else { shift });
                water.add(1, p, q, shift);
            }
        }
    }
}
