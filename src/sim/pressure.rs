//! Direct pressure solve for the slice's channel: free-slip side walls, still water
//! streaming in ahead of the bell, an open wake end behind it.
//!
//! On a MAC grid the cell-centred Laplacian has Neumann boundaries where the normal
//! velocity is given (the side walls, and the inflow at the top, the bow) and a Dirichlet
//! boundary, p = 0, at the bottom, where the wake leaves the box instead of circling back.
//! A cosine transform (DCT-II) across the channel turns it into one tridiagonal system
//! along the channel per cosine mode, solved by elimination (Thomas), in `f64`: the slowest
//! mode, pinned only by the far open end, is ill-conditioned enough that `f32` elimination
//! would leave a visible divergence. Exact to round-off, O(N² log N), no iteration count
//! to tune and no residual divergence left behind; the elimination factors depend only on
//! the grid, so they are computed once.

use rustdct::{DctPlanner, TransformType2And3};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

type Across = Arc<dyn TransformType2And3<f32>>;

/// One transform plan per size, shared by every slice: planning costs more than a solve,
/// and hundreds of jellyfish spawned together need not each plan their own.
fn plan(n: usize) -> Across {
    static PLANS: OnceLock<Mutex<HashMap<usize, Across>>> = OnceLock::new();
    let plans = PLANS.get_or_init(Default::default);
    let mut plans = plans.lock().unwrap_or_else(|e| e.into_inner());
    plans
        .entry(n)
        .or_insert_with(|| DctPlanner::new().plan_dct2(n))
        .clone()
}

/// The exact pressure solve: a cosine transform across the channel diagonalises the
/// free-slip Poisson problem, leaving one tridiagonal solve per mode along it.
#[derive(Clone)]
pub(crate) struct PoissonSolver {
    n: usize,
    across: Across,
    /// `1 / h²`: the tridiagonal systems' off-diagonal.
    off: f64,
    /// Elimination factors, shared by every slice of the same grid.
    factors: Arc<Factors>,
    /// The modes' values along the channel, `f64`.
    modes: Vec<f64>,
    scratch: Vec<f32>,
}

/// Elimination factors per row `j` and cosine mode `k` (row-major, like the field): the
/// reciprocal of the eliminated diagonal, and the eliminated upper diagonal. They depend
/// only on the grid, so slices of one species share them (115 KB at grid 60) and a
/// school's working set stays in cache.
struct Factors {
    inverse_pivot: Vec<f64>,
    upper: Vec<f64>,
}

/// The factors for `n` cells of size `h`, computed once per grid.
fn factors(n: usize, h: f32) -> Arc<Factors> {
    type Shared = Mutex<HashMap<(usize, u32), Arc<Factors>>>;
    static FACTORS: OnceLock<Shared> = OnceLock::new();
    let all = FACTORS.get_or_init(Default::default);
    let mut all = all.lock().unwrap_or_else(|e| e.into_inner());
    all.entry((n, h.to_bits()))
        .or_insert_with(|| Arc::new(Factors::new(n, h)))
        .clone()
}

impl Factors {
    fn new(n: usize, h: f32) -> Self {
        let (pi, h) = (std::f64::consts::PI, h as f64);
        let off = 1.0 / (h * h);
        let (mut inverse_pivot, mut upper) = (vec![0.0; n * n], vec![0.0; n * n]);
        for k in 0..n {
            // The cosine mode's eigenvalue across the channel.
            let lambda = (2.0 * (pi * k as f64 / n as f64).cos() - 2.0) * off;
            for j in 0..n {
                // Bottom: ghost cell −φ (p = 0 on the face); top: ghost cell φ (∂p/∂y = 0).
                let diagonal = lambda
                    + if j == 0 {
                        -3.0 * off
                    } else if j == n - 1 {
                        -off
                    } else {
                        -2.0 * off
                    };
                let eliminated = if j == 0 {
                    diagonal
                } else {
                    diagonal - off * upper[(j - 1) * n + k]
                };
                inverse_pivot[j * n + k] = 1.0 / eliminated;
                upper[j * n + k] = off / eliminated;
            }
        }
        Self {
            inverse_pivot,
            upper,
        }
    }
}

impl PoissonSolver {
    /// A solver for an `n × n` grid of cells of size `h`.
    pub(crate) fn new(n: usize, h: f32) -> Self {
        let across = plan(n);
        let scratch = vec![0.0; across.get_scratch_len()];
        Self {
            n,
            across,
            off: 1.0 / (h as f64 * h as f64),
            factors: factors(n, h),
            modes: vec![0.0; n * n],
            scratch,
        }
    }

    /// Heap bytes of this solver's own (unshared) buffers.
    pub(crate) fn bytes(&self) -> usize {
        self.modes.len() * 8 + self.scratch.len() * 4
    }

    /// Solves `∇²φ = rhs` in place (row-major, `n × n`, rows along x), with ∂φ/∂n = 0 at
    /// the side walls and the top (inflow) face and φ = 0 on the bottom (wake) face.
    pub(crate) fn solve(&mut self, field: &mut [f32]) {
        let n = self.n;
        debug_assert_eq!(field.len(), n * n);
        for row in field.chunks_exact_mut(n) {
            self.across
                .process_dct2_with_scratch(row, &mut self.scratch);
        }
        // DCT-III after DCT-II multiplies by n/2: undo it on the way in.
        let norm = 2.0 / n as f64;
        // Forward elimination up the channel, all modes of a row at once.
        for j in 0..n {
            let (done, rest) = self.modes.split_at_mut(j * n);
            let here = &mut rest[..n];
            let rhs = &field[j * n..][..n];
            let pivot = &self.factors.inverse_pivot[j * n..][..n];
            if j == 0 {
                for ((m, r), p) in here.iter_mut().zip(rhs).zip(pivot) {
                    *m = norm * *r as f64 * p;
                }
            } else {
                let below = &done[(j - 1) * n..];
                for (((m, r), p), b) in here.iter_mut().zip(rhs).zip(pivot).zip(below) {
                    *m = (norm * *r as f64 - self.off * b) * p;
                }
            }
        }
        // Back substitution down it.
        for j in (0..n - 1).rev() {
            let (lower, upper_rows) = self.modes.split_at_mut((j + 1) * n);
            let (here, above) = (&mut lower[j * n..], &upper_rows[..n]);
            let upper = &self.factors.upper[j * n..][..n];
            for ((m, a), u) in here.iter_mut().zip(above).zip(upper) {
                *m -= u * a;
            }
        }
        for (x, m) in field.iter_mut().zip(&self.modes) {
            *x = *m as f32;
        }
        for row in field.chunks_exact_mut(n) {
            self.across
                .process_dct3_with_scratch(row, &mut self.scratch);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 5-point Laplacian the solver inverts: Neumann at the side walls and the top
    /// (mirror ghost cells), Dirichlet at the bottom (odd ghost cells, φ = 0 on the face).
    fn laplacian(phi: &[f32], n: usize, h: f32) -> Vec<f32> {
        let at = |i: usize, j: usize| phi[j * n + i] as f64;
        let h = h as f64;
        let mut out = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let c = at(i, j);
                let left = if i > 0 { at(i - 1, j) } else { c };
                let right = if i + 1 < n { at(i + 1, j) } else { c };
                let below = if j > 0 { at(i, j - 1) } else { -c };
                let above = if j + 1 < n { at(i, j + 1) } else { c };
                out[j * n + i] = ((left + right + below + above - 4.0 * c) / (h * h)) as f32;
            }
        }
        out
    }

    #[test]
    fn inverts_the_channel_laplacian() {
        for n in [16, 50, 60, 64, 100] {
            let h = 0.004;
            // A pressure with the channel's boundary behaviour and detail at every scale;
            // its Laplacian (in f64) is the right-hand side the solver must invert.
            let exact: Vec<f32> = (0..n * n)
                .map(|k| {
                    let (i, j) = ((k % n) as f32, (k / n) as f32);
                    let (x, y) = ((i + 0.5) / n as f32, (j + 0.5) / n as f32);
                    (std::f32::consts::PI * x).cos() * (0.5 * std::f32::consts::PI * y).sin()
                        + 0.3 * (7.0 * x).sin() * (5.0 * y * y).sin()
                        + 0.01 * (((k * 7919) % 101) as f32 / 101.0 - 0.5)
                })
                .collect();
            let mut phi = laplacian(&exact, n, h);
            PoissonSolver::new(n, h).solve(&mut phi);
            let scale = exact.iter().fold(0.0f32, |m, r| m.max(r.abs()));
            let err = phi
                .iter()
                .zip(&exact)
                .fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
            assert!(err / scale < 1e-5, "n={n}: relative error {}", err / scale);
        }
    }
}
