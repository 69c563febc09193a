//! Exact pressure solves for the slice's two geometries.
//!
//! Each boundary condition is uniform along one direction of the box, so a fast
//! transform along it diagonalises the discrete Laplacian, leaving one tridiagonal system
//! per mode across the other direction, solved by elimination (Thomas) in `f64`. Exact to
//! round-off, O(N² log N), no iteration count to tune and no divergence left behind.
//! - `channel`: a planar slice free to tilt (and the closed test box); a cosine transform
//!   across the channel (free-slip walls on both sides), tridiagonal along it (inflow
//!   ahead, open wake end behind);
//! - `rings`: the axisymmetric slice; the r-weighted operator varies across the radius,
//!   so the transform runs along the axis (a quarter-wave sine: open wake end, inflow)
//!   and the tridiagonal systems across the radius, from the axis to the outer wall. A
//!   planar slice held mirror-symmetric is solved the same way on its half.

mod channel;
mod rings;

pub(crate) use channel::PoissonSolver;
pub(crate) use rings::{Across, RingPoissonSolver};

use std::sync::Arc;

/// A tridiagonal system per mode, `lower[r]·x[r−1] + (diagonal[r] + λ[m])·x[r] +
/// upper[r]·x[r+1] = b[r]`, eliminated once: the reciprocal of each eliminated pivot and
/// each eliminated upper diagonal, row-major with the modes contiguous (so one pass
/// eliminates every mode of a row at once). They depend only on the grid, so slices of
/// one species share them and a school's working set stays in cache.
pub(super) struct Factors {
    modes: usize,
    lower: Vec<f64>,
    inverse_pivot: Vec<f64>,
    upper: Vec<f64>,
}

impl Factors {
    pub(super) fn new(lower: &[f64], diagonal: &[f64], upper: &[f64], lambda: &[f64]) -> Self {
        let (rows, modes) = (diagonal.len(), lambda.len());
        let (mut inverse_pivot, mut eliminated_upper) =
            (vec![0.0; rows * modes], vec![0.0; rows * modes]);
        for (k, lambda) in lambda.iter().enumerate() {
            for r in 0..rows {
                let d = lambda + diagonal[r];
                let eliminated = if r == 0 {
                    d
                } else {
                    d - lower[r] * eliminated_upper[(r - 1) * modes + k]
                };
                inverse_pivot[r * modes + k] = 1.0 / eliminated;
                eliminated_upper[r * modes + k] = upper[r] / eliminated;
            }
        }
        Self {
            modes,
            lower: lower.to_vec(),
            inverse_pivot,
            upper: eliminated_upper,
        }
    }

    /// Solves every mode's system for `rhs · norm` (row-major, modes contiguous) into
    /// `out`.
    pub(super) fn solve(&self, rhs: &[f32], norm: f64, out: &mut [f64]) {
        let factors = self;
        eight_wide!(
            Factors::eliminate,
            (factors: &Factors, rhs: &[f32], norm: f64, out: &mut [f64])
        )
    }

    /// [`Self::solve`]'s elimination, inlined into each of its callers' codegen.
    #[inline(always)]
    fn eliminate(&self, rhs: &[f32], norm: f64, out: &mut [f64]) {
        let m = self.modes;
        let rows = out.len() / m;
        // Forward elimination, all modes of a row at once.
        for r in 0..rows {
            let (done, rest) = out.split_at_mut(r * m);
            let here = &mut rest[..m];
            let rhs = &rhs[r * m..][..m];
            let pivot = &self.inverse_pivot[r * m..][..m];
            if r == 0 {
                for ((x, b), p) in here.iter_mut().zip(rhs).zip(pivot) {
                    *x = norm * *b as f64 * p;
                }
            } else {
                let (below, lower) = (&done[(r - 1) * m..], self.lower[r]);
                for (((x, b), p), y) in here.iter_mut().zip(rhs).zip(pivot).zip(below) {
                    *x = (norm * *b as f64 - lower * y) * p;
                }
            }
        }
        // Back substitution.
        for r in (0..rows - 1).rev() {
            let (lower_rows, upper_rows) = out.split_at_mut((r + 1) * m);
            let (here, above) = (&mut lower_rows[r * m..], &upper_rows[..m]);
            let upper = &self.upper[r * m..][..m];
            for ((x, a), u) in here.iter_mut().zip(above).zip(upper) {
                *x -= u * a;
            }
        }
    }

    /// Pins `mode`, whose system is singular (a pure-Neumann operator's constant), by
    /// replacing its last equation with `x = 0`: the last pivot is exactly zero there, so
    /// forward elimination leaves `0·x = Σ b`, which holds whenever the right-hand side is
    /// compatible (zero total divergence in a closed box), and every other row is solved
    /// as before. What is lost is only the free constant of that mode.
    pub(super) fn pin_last(&mut self, mode: usize) {
        let rows = self.inverse_pivot.len() / self.modes;
        self.inverse_pivot[(rows - 1) * self.modes + mode] = 0.0;
    }
}

/// One value per key, built once and shared (plans and factors are costlier than a solve,
/// and hundreds of jellyfish spawned together need not each build their own).
pub(super) fn shared<K: std::hash::Hash + Eq, V: ?Sized>(
    cache: &std::sync::Mutex<std::collections::HashMap<K, Arc<V>>>,
    key: K,
    build: impl FnOnce() -> Arc<V>,
) -> Arc<V> {
    let mut all = cache.lock().unwrap_or_else(|e| e.into_inner());
    all.entry(key).or_insert_with(build).clone()
}
