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

use super::{Factors, shared};
use rustdct::{DctPlanner, TransformType2And3};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

type Across = Arc<dyn TransformType2And3<f32>>;

/// One transform plan per size, shared by every slice.
fn plan(n: usize) -> Across {
    static PLANS: OnceLock<Mutex<HashMap<usize, Across>>> = OnceLock::new();
    shared(PLANS.get_or_init(Default::default), n, || {
        DctPlanner::new().plan_dct2(n)
    })
}

/// The exact pressure solve: a cosine transform across the channel diagonalises the
/// free-slip Poisson problem, leaving one tridiagonal solve per mode along it.
#[derive(Clone)]
pub(crate) struct PoissonSolver {
    n: usize,
    across: Across,
    /// Elimination factors, shared by every slice of the same grid (115 KB at grid 60).
    factors: Arc<Factors>,
    /// The modes' values along the channel, `f64`.
    modes: Vec<f64>,
    scratch: Vec<f32>,
}

/// The factors for `n` cells of size `h`, computed once per grid: the channel's (φ = 0 on
/// the open wake face at the bottom) or, `closed`, a closed box's (test set-ups only: see
/// `fluid::Walls`), ∂φ/∂n = 0 on all four sides. A closed box's constant mode (k = 0,
/// constant along each row) is singular and is pinned ([`Factors::pin_last`]): the
/// pressure is defined up to a constant, which its gradient does not see.
fn factors(n: usize, h: f32, closed: bool) -> Arc<Factors> {
    type Shared = Mutex<HashMap<(usize, u32, bool), Arc<Factors>>>;
    static FACTORS: OnceLock<Shared> = OnceLock::new();
    shared(
        FACTORS.get_or_init(Default::default),
        (n, h.to_bits(), closed),
        || {
            let (pi, h) = (std::f64::consts::PI, h as f64);
            let off = 1.0 / (h * h);
            // The cosine modes' eigenvalues across the channel.
            let lambda: Vec<f64> = (0..n)
                .map(|k| (2.0 * (pi * k as f64 / n as f64).cos() - 2.0) * off)
                .collect();
            // Bottom: ghost cell −φ (p = 0 on the face), or φ when closed; top: ghost
            // cell φ (∂p/∂y = 0).
            let diagonal: Vec<f64> = (0..n)
                .map(|j| {
                    if j == 0 && !closed {
                        -3.0 * off
                    } else if j == 0 || j == n - 1 {
                        -off
                    } else {
                        -2.0 * off
                    }
                })
                .collect();
            let off = vec![off; n];
            let mut factors = Factors::new(&off, &diagonal, &off, &lambda);
            if closed {
                factors.pin_last(0);
            }
            Arc::new(factors)
        },
    )
}

impl PoissonSolver {
    /// A solver for a closed `n × n` box of cells of size `h`: Neumann on all four sides
    /// (see `factors`), so [`PoissonSolver::solve`] returns the pressure up to a
    /// constant (its row means' mode pinned to zero on the top row). For the test set-ups
    /// of `fluid::Walls` only.
    pub(crate) fn closed(n: usize, h: f32) -> Self {
        Self {
            factors: factors(n, h, true),
            ..Self::new(n, h)
        }
    }

    /// A solver for an `n × n` grid of cells of size `h`.
    pub(crate) fn new(n: usize, h: f32) -> Self {
        let across = plan(n);
        let scratch = vec![0.0; across.get_scratch_len()];
        Self {
            n,
            across,
            factors: factors(n, h, false),
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
        // DCT-III after DCT-II multiplies by n/2: undone on the way in.
        self.factors.solve(field, 2.0 / n as f64, &mut self.modes);
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

    /// The 5-point Laplacian: Neumann at the side walls and the top (mirror ghost cells);
    /// at the bottom the ghost cell is `bottom` times its neighbour: −1 for the channel's
    /// open end (odd, φ = 0 on the face), +1 for the closed box's wall.
    fn laplacian(phi: &[f32], n: usize, h: f32, bottom: f64) -> Vec<f32> {
        let at = |i: usize, j: usize| phi[j * n + i] as f64;
        let h = h as f64;
        let mut out = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let c = at(i, j);
                let left = if i > 0 { at(i - 1, j) } else { c };
                let right = if i + 1 < n { at(i + 1, j) } else { c };
                let below = if j > 0 { at(i, j - 1) } else { bottom * c };
                let above = if j + 1 < n { at(i, j + 1) } else { c };
                out[j * n + i] = ((left + right + below + above - 4.0 * c) / (h * h)) as f32;
            }
        }
        out
    }

    #[test]
    fn inverts_the_closed_box_laplacian() {
        // Pure Neumann: the solution is defined up to a constant, so both are compared
        // with their means removed. The right-hand side (a Laplacian) sums to zero, as a
        // closed box's divergence does.
        for n in [16, 50, 60, 64, 100] {
            let h = 0.004;
            let exact: Vec<f32> = (0..n * n)
                .map(|k| {
                    let (i, j) = ((k % n) as f32, (k / n) as f32);
                    let (x, y) = ((i + 0.5) / n as f32, (j + 0.5) / n as f32);
                    (std::f32::consts::PI * x).cos() * (std::f32::consts::PI * y).cos()
                        + 0.7 * (std::f32::consts::PI * y).cos()
                        + 0.3 * (7.0 * x).sin() * (5.0 * y * y).sin()
                        + 0.01 * (((k * 7919) % 101) as f32 / 101.0 - 0.5)
                })
                .collect();
            let mut phi = laplacian(&exact, n, h, 1.0);
            PoissonSolver::closed(n, h).solve(&mut phi);
            let mean = |f: &[f32]| f.iter().map(|&x| x as f64).sum::<f64>() / f.len() as f64;
            let (m_phi, m_exact) = (mean(&phi), mean(&exact));
            let scale = exact.iter().fold(0.0f32, |m, r| m.max(r.abs()));
            let err = phi.iter().zip(&exact).fold(0.0f64, |m, (a, b)| {
                m.max(((*a as f64 - m_phi) - (*b as f64 - m_exact)).abs())
            });
            let rel = err / scale as f64;
            assert!(rel < 1e-5, "n={n}: relative error {rel}");
            assert!(phi.iter().all(|x| x.is_finite()), "n={n}: not finite");
        }
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
            let mut phi = laplacian(&exact, n, h, -1.0);
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
