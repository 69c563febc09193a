//! Direct pressure solve for the axisymmetric slice (r–z, no swirl).
//!
//! The r-weighted Laplacian `(1/r)∂/∂r(r ∂φ/∂r) + ∂²φ/∂z²` on the MAC grid, finite
//! volumes of rings: the cell on the axis is a disc of radius h/2, the others annuli of
//! width h. Its boundary conditions are uniform along the axis (φ = 0 on the open wake
//! face, ∂φ/∂z = 0 at the inflow), so a quarter-wave sine transform along z (DST-IV, whose
//! modes `sin(π(m + ½)(j + ½)/n)` meet exactly those two conditions) diagonalises it,
//! leaving one tridiagonal system across the radius per mode: from the axis (no flux
//! through r = 0) to the free-slip outer wall (no flux through it). Every mode's
//! eigenvalue is negative, so every system is regular (no pinned constant).

use super::{Factors, shared};
use rustdct::{DctPlanner, TransformType4};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

type Along = Arc<dyn TransformType4<f32>>;

fn plan(n: usize) -> Along {
    static PLANS: OnceLock<Mutex<HashMap<usize, Along>>> = OnceLock::new();
    shared(PLANS.get_or_init(Default::default), n, || {
        DctPlanner::new().plan_dst4(n)
    })
}

/// The exact r–z pressure solve on `rings × n` cells: `rings` across the radius (the
/// axis cell first), `n` along the axis.
#[derive(Clone)]
pub(crate) struct RingPoissonSolver {
    n: usize,
    along: Along,
    factors: Arc<Factors>,
    modes: Vec<f64>,
    scratch: Vec<f32>,
}

/// Coefficients of the radial operator for `rings` cells of size `h`, `(lower, diagonal,
/// upper)` per ring, as [`Factors`] takes them.
pub(crate) fn radial_operator(rings: usize, h: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let off = 1.0 / (h * h);
    let (mut lower, mut diagonal, mut upper) =
        (vec![0.0; rings], vec![0.0; rings], vec![0.0; rings]);
    for k in 0..rings {
        if k == 0 {
            // The disc on the axis: flux through its rim r = h/2 over its area π(h/2)².
            upper[0] = 4.0 * off;
        } else {
            let r = k as f64;
            lower[k] = (r - 0.5) / r * off;
            // The outermost ring's outer face is the wall: no flux.
            upper[k] = if k + 1 < rings {
                (r + 0.5) / r * off
            } else {
                0.0
            };
        }
        diagonal[k] = -(lower[k] + upper[k]);
    }
    (lower, diagonal, upper)
}

fn factors(rings: usize, n: usize, h: f32) -> Arc<Factors> {
    type Shared = Mutex<HashMap<(usize, usize, u32), Arc<Factors>>>;
    static FACTORS: OnceLock<Shared> = OnceLock::new();
    shared(
        FACTORS.get_or_init(Default::default),
        (rings, n, h.to_bits()),
        || {
            let (pi, h) = (std::f64::consts::PI, h as f64);
            let lambda: Vec<f64> = (0..n)
                .map(|m| (2.0 * (pi * (m as f64 + 0.5) / n as f64).cos() - 2.0) / (h * h))
                .collect();
            // Eliminated from the outer wall in to the axis: the fluid's column order.
            let (lower, mut diagonal, upper) = radial_operator(rings, h);
            let (mut inward_lower, mut inward_upper) = (upper, lower);
            for v in [&mut inward_lower, &mut inward_upper, &mut diagonal] {
                v.reverse();
            }
            Arc::new(Factors::new(
                &inward_lower,
                &diagonal,
                &inward_upper,
                &lambda,
            ))
        },
    )
}

impl RingPoissonSolver {
    /// A solver for `rings` cells across the radius and `n` along the axis, of size `h`.
    pub(crate) fn new(rings: usize, n: usize, h: f32) -> Self {
        let along = plan(n);
        let scratch = vec![0.0; along.get_scratch_len()];
        Self {
            n,
            along,
            factors: factors(rings, n, h),
            modes: vec![0.0; rings * n],
            scratch,
        }
    }

    /// Heap bytes of this solver's own (unshared) buffers.
    pub(crate) fn bytes(&self) -> usize {
        self.modes.len() * 8 + self.scratch.len() * 4
    }

    /// Solves the r-weighted `∇²φ = rhs` in place; `field` holds one row per ring (the
    /// axis first), each `n` cells along the axis from the wake end up.
    #[cfg(test)]
    pub(crate) fn solve(&mut self, field: &mut [f32]) {
        let n = self.n;
        let rings = field.len() / n;
        // The same rows, the outer wall first.
        for k in 0..rings / 2 {
            let (a, b) = field.split_at_mut((rings - 1 - k) * n);
            a[k * n..][..n].swap_with_slice(&mut b[..n]);
        }
        self.solve_reversed(field);
        for k in 0..rings / 2 {
            let (a, b) = field.split_at_mut((rings - 1 - k) * n);
            a[k * n..][..n].swap_with_slice(&mut b[..n]);
        }
    }

    /// [`Self::solve`] with the rings' rows in the fluid's order: the outer wall first, the
    /// axis last.
    pub(crate) fn solve_reversed(&mut self, field: &mut [f32]) {
        let n = self.n;
        debug_assert_eq!(field.len(), self.modes.len());
        for row in field.chunks_exact_mut(n) {
            self.along.process_dst4_with_scratch(row, &mut self.scratch);
        }
        // DST-IV is its own inverse up to n/2: undone on the way in.
        self.factors.solve(field, 2.0 / n as f64, &mut self.modes);
        for (x, m) in field.iter_mut().zip(&self.modes) {
            *x = *m as f32;
        }
        for row in field.chunks_exact_mut(n) {
            self.along.process_dst4_with_scratch(row, &mut self.scratch);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The operator the solver inverts, applied directly: rings across, `n` along, with
    /// the wake face at φ = 0 (odd ghost) and the inflow face at ∂φ/∂z = 0 (even ghost).
    fn laplacian(phi: &[f32], rings: usize, n: usize, h: f32) -> Vec<f32> {
        let (lower, diagonal, upper) = radial_operator(rings, h as f64);
        let at = |k: usize, j: usize| phi[k * n + j] as f64;
        let mut out = vec![0.0; rings * n];
        let off = 1.0 / (h as f64 * h as f64);
        for k in 0..rings {
            for j in 0..n {
                let c = at(k, j);
                let radial = diagonal[k] * c
                    + if k > 0 { lower[k] * at(k - 1, j) } else { 0.0 }
                    + if k + 1 < rings {
                        upper[k] * at(k + 1, j)
                    } else {
                        0.0
                    };
                let below = if j > 0 { at(k, j - 1) } else { -c };
                let above = if j + 1 < n { at(k, j + 1) } else { c };
                out[k * n + j] = (radial + (below + above - 2.0 * c) * off) as f32;
            }
        }
        out
    }

    #[test]
    fn inverts_the_ring_laplacian() {
        for (rings, n) in [(9, 16), (31, 60), (32, 63), (51, 100)] {
            let h = 0.004;
            let exact: Vec<f32> = (0..rings * n)
                .map(|q| {
                    let (k, j) = ((q / n) as f32, (q % n) as f32);
                    let (r, z) = (k / rings as f32, (j + 0.5) / n as f32);
                    (2.0 * r * r).cos() * (0.5 * std::f32::consts::PI * z).sin()
                        + 0.3 * (7.0 * r).sin() * (5.0 * z * z).sin()
                        + 0.01 * (((q * 7919) % 101) as f32 / 101.0 - 0.5)
                })
                .collect();
            let mut phi = laplacian(&exact, rings, n, h);
            RingPoissonSolver::new(rings, n, h).solve(&mut phi);
            let scale = exact.iter().fold(0.0f32, |m, r| m.max(r.abs()));
            let err = phi
                .iter()
                .zip(&exact)
                .fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
            assert!(
                err / scale < 1e-5,
                "{rings}×{n}: relative error {}",
                err / scale
            );
        }
    }
}
