//! The semi-implicit spring forces: a Gauss–Newton linearisation at the predicted
//! positions, solved exactly with a banded Cholesky factorisation.

use super::elements::Constraint;
use crate::sim::banded::BandedSpd;
use glam::Vec2;
use std::ops::Range;

/// Exact solve of `(m/dt² I + Σ k g gᵀ) δ = F` with a banded Cholesky factorisation, over
/// a subset of the body's points (the others are held where they are).
#[derive(Clone)]
pub(super) struct Solver {
    /// Position of each point in the band ordering; `None` for points held fixed.
    order: Vec<Option<usize>>,
    /// The solved points, in band order.
    sequence: Vec<usize>,
    matrix: BandedSpd,
    /// The right-hand side, then the solution.
    pub(crate) rhs: Vec<f64>,
    forces: Vec<Vec2>,
}

impl Solver {
    /// A solver for the points of `sequence`, numbered in that order (each coupling should
    /// join points a few places apart in it, which keeps the band narrow).
    pub(crate) fn new(body_len: usize, sequence: Vec<usize>) -> Self {
        let mut order = vec![None; body_len];
        for (k, &i) in sequence.iter().enumerate() {
            order[i] = Some(k);
        }
        Self {
            order,
            sequence,
            matrix: BandedSpd::new(0, 0),
            rhs: Vec::new(),
            forces: vec![Vec2::ZERO; body_len],
        }
    }

    /// The bell numbered from the apex outwards, alternating sides: every spring, hinge
    /// and muscle then couples points a few places apart.
    pub(crate) fn bell_order(bell: &Range<usize>) -> Vec<usize> {
        let m = bell.len() / 2;
        let mut out = vec![bell.start + m];
        for d in 1..=m {
            out.push(bell.start + m - d);
            out.push(bell.start + m + d);
        }
        out
    }

    /// The tentacles numbered from the margins outwards, alternating sides.
    pub(crate) fn tentacle_order(tentacles: &[Range<usize>; 2]) -> Vec<usize> {
        let longest = tentacles[0].len().max(tentacles[1].len());
        let mut out = Vec::new();
        for k in 0..longest {
            for side in tentacles {
                if k < side.len() {
                    out.push(side.start + k);
                }
            }
        }
        out
    }

    /// Sizes the band for the couplings the body has.
    pub(crate) fn prepare(&mut self, cons: &[Constraint]) {
        let band = cons
            .iter()
            .map(|c| {
                let pos = c.idx[..c.count].iter().filter_map(|&i| self.order[i]);
                let (lo, hi) = pos.fold((usize::MAX, 0), |(lo, hi), o| (lo.min(o), hi.max(o)));
                hi.saturating_sub(lo)
            })
            .max()
            .unwrap_or(0);
        let dofs = 2 * self.sequence.len();
        self.matrix = BandedSpd::new(dofs, 2 * band + 1);
        self.rhs = vec![0.0; dofs];
    }

    /// Solves for the forces at the predicted positions, `damping = τ/dt` adding the
    /// mesoglea's viscosity (backward Euler: the rate over the step, the stiffness
    /// `k·(1 + τ/dt)`), with a diagonal of its own for each point (`diag(point)`: the
    /// water it drags along, or the tentacles' drag, over the step).
    pub(crate) fn solve_each(
        &mut self,
        cons: &[Constraint],
        diag: impl Fn(usize) -> f32,
        damping: f32,
        out: &mut [Vec2],
    ) {
        // Right-hand side: the explicit forces at the predicted positions.
        self.forces.iter_mut().for_each(|f| *f = Vec2::ZERO);
        for c in cons {
            c.add_damped_force(&mut self.forces, damping);
        }
        for (o, &i) in self.sequence.iter().enumerate() {
            let f = self.forces[i];
            self.rhs[2 * o] = f.x as f64;
            self.rhs[2 * o + 1] = f.y as f64;
        }
        self.matrix.clear_to_diagonal(0.0);
        for (o, &i) in self.sequence.iter().enumerate() {
            let d = diag(i) as f64;
            self.matrix.add(2 * o, 2 * o, d);
            self.matrix.add(2 * o + 1, 2 * o + 1, d);
        }
        for c in cons {
            let k = c.stiffness as f64 * (1.0 + damping as f64);
            for p in 0..c.count {
                for q in 0..=p {
                    let (gp, gq) = (c.grad[p].to_array(), c.grad[q].to_array());
                    let (Some(op), Some(oq)) = (self.order[c.idx[p]], self.order[c.idx[q]]) else {
                        continue;
                    };
                    for (a, ga) in gp.iter().enumerate() {
                        for (b, gb) in gq.iter().enumerate() {
                            // A point's own 2×2 block is symmetric: give each entry once.
                            if p == q && b > a {
                                continue;
                            }
                            self.matrix
                                .add(2 * op + a, 2 * oq + b, k * (ga * gb) as f64);
                        }
                    }
                }
            }
        }
        if !self.matrix.factor_and_solve(&mut self.rhs) {
            // Only non-finite input gets here; the step's health check then recovers.
            for &i in &self.sequence {
                out[i] = Vec2::splat(f32::NAN);
            }
            return;
        }
        out.iter_mut().for_each(|o| *o = Vec2::ZERO);
        for (o, &i) in self.sequence.iter().enumerate() {
            let (x, y) = (self.rhs[2 * o], self.rhs[2 * o + 1]);
            out[i] = diag(i) * Vec2::new(x as f32, y as f32);
        }
    }
}
