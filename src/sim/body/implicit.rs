//! The semi-implicit spring forces: a Gauss–Newton linearisation at the predicted
//! positions, solved exactly with a banded Cholesky factorisation.

use super::elements::Constraint;
use crate::sim::banded::{BandedSpd, Stamp};
use crate::sim::banded_lu::BandedLu;
use crate::sim::response::Response;
use glam::Vec2;
use std::ops::Range;

/// Exact solve of `(m/dt² I + Σ k g gᵀ) δ = F` with a banded Cholesky factorisation, over
/// a subset of the body's points (the others are held where they are).
///
/// A body of revolution (an r–z slice) is solved on its half: each point past the axis
/// enters as its partner's mirror image (`δ` the same with its radial part reversed), so
/// the system is the full one restricted to mirror-symmetric displacements (Galerkin:
/// `Eᵀ A E δ = Eᵀ F`, `E` the mirror's embedding), half the unknowns in a band the chain's
/// neighbours set instead of the alternating order's.
#[derive(Clone)]
pub(super) struct Solver {
    /// Each point's place in the band ordering; `None` for points held fixed.
    order: Vec<Option<Place>>,
    /// The solved points, in band order.
    sequence: Vec<usize>,
    /// The points that enter as their partner's mirror image, ascending.
    mirrored: Vec<usize>,
    matrix: BandedSpd,
    /// How each element enters the matrix, in the order [`Solver::prepare`] saw them.
    assembly: Vec<Assembly>,
    /// The right-hand side, then the solution.
    pub(crate) rhs: Vec<f64>,
    forces: Vec<Vec2>,
    /// How many of the body's points each solved one stands for (itself and its mirror
    /// image): `W`, the Galerkin restriction's `Eᵀ E`.
    counts: Vec<f64>,
    /// `W + K·G`, where the solve has the water's response `G`.
    coupled: BandedLu,
}

/// Where a point's displacement is in the band ordering.
#[derive(Clone, Copy)]
struct Place {
    at: usize,
    /// The point is its partner's mirror image: its radial (x) part reversed.
    mirrored: bool,
}

/// How one element enters the solve, worked out once: a body's elements and their order
/// never change from step to step, so neither do the unknowns each one couples.
#[derive(Clone, Copy)]
struct Assembly {
    /// For each of its points, the slot among the unknowns it couples that the point's
    /// gradient adds into and whether the point enters mirrored; `None` where it is held.
    points: [Option<(usize, bool)>; 3],
    /// How many distinct points it couples (a point and its mirror image are one).
    slots: usize,
    /// Where its stiffness lands in the band.
    stamp: Stamp,
}

impl Place {
    fn read(self, v: Vec2) -> Vec2 {
        if self.mirrored {
            Vec2::new(-v.x, v.y)
        } else {
            v
        }
    }
}

impl Solver {
    /// A solver for the points of `sequence`, numbered in that order (each coupling should
    /// join points a few places apart in it, which keeps the band narrow), and for each
    /// point `partners` names (`partners[j] = Some(i)`, `i` in `sequence`), as `i`'s
    /// mirror image.
    pub(crate) fn new(body_len: usize, sequence: Vec<usize>, partners: &[Option<usize>]) -> Self {
        let mut order = vec![None; body_len];
        for (at, &i) in sequence.iter().enumerate() {
            order[i] = Some(Place {
                at,
                mirrored: false,
            });
        }
        let mut mirrored = Vec::new();
        for (j, partner) in partners.iter().enumerate() {
            if let Some(Some(place)) = partner.map(|i| order[i])
                && order[j].is_none()
            {
                order[j] = Some(Place {
                    mirrored: true,
                    ..place
                });
                mirrored.push(j);
            }
        }
        let mut counts = vec![1.0; sequence.len()];
        for &j in &mirrored {
            counts[order[j].expect("a mirrored point has a place").at] += 1.0;
        }
        Self {
            order,
            sequence,
            mirrored,
            matrix: BandedSpd::new(0, 0),
            assembly: Vec::new(),
            rhs: Vec::new(),
            forces: vec![Vec2::ZERO; body_len],
            counts,
            coupled: BandedLu::default(),
        }
    }

    /// An empty water response over the solved points, in this solver's order.
    pub(crate) fn response(&self) -> Response {
        let imaged = self.counts.iter().map(|&c| c > 1.0).collect();
        Response::new(self.sequence.clone(), imaged)
    }

    /// The solved points, in band order.
    pub(crate) fn sequence(&self) -> &[usize] {
        &self.sequence
    }

    /// Where point `i` is solved, and whether as its partner's mirror image.
    pub(crate) fn place(&self, i: usize) -> Option<(usize, bool)> {
        self.order[i].map(|p| (p.at, p.mirrored))
    }

    /// The bell's solver and the tentacles', for a body of `count` points, on the half
    /// `partners` leaves (all of it when there are none).
    pub(crate) fn pair(
        count: usize,
        bell: &Range<usize>,
        tentacles: &[Range<usize>; 2],
        partners: &[Option<usize>],
    ) -> [Self; 2] {
        let half = !partners.is_empty();
        [
            Self::new(count, Self::bell_order(bell, half), partners),
            Self::new(count, Self::tentacle_order(tentacles, half), partners),
        ]
    }

    /// The bell numbered from the apex outwards, alternating sides: every spring, hinge
    /// and muscle then couples points a few places apart. Of a body of revolution
    /// (`half`), its half from the left margin to the apex, in the chain's order.
    pub(crate) fn bell_order(bell: &Range<usize>, half: bool) -> Vec<usize> {
        let m = bell.len() / 2;
        if half {
            return (bell.start..=bell.start + m).collect();
        }
        let mut out = vec![bell.start + m];
        for d in 1..=m {
            out.push(bell.start + m - d);
            out.push(bell.start + m + d);
        }
        out
    }

    /// The tentacles numbered from the margins outwards, alternating sides; of a body of
    /// revolution (`half`), the left one's alone.
    pub(crate) fn tentacle_order(tentacles: &[Range<usize>; 2], half: bool) -> Vec<usize> {
        if half {
            return tentacles[0].clone().collect();
        }
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

    /// Sizes the band for the couplings the body has, and works out where each of them
    /// enters it; `cons` must come in the same order at every solve.
    pub(crate) fn prepare(&mut self, cons: &[Constraint]) {
        let band = cons
            .iter()
            .map(|c| {
                let pos = c.idx[..c.count]
                    .iter()
                    .filter_map(|&i| self.order[i].map(|p| p.at));
                let (lo, hi) = pos.fold((usize::MAX, 0), |(lo, hi), o| (lo.min(o), hi.max(o)));
                hi.saturating_sub(lo)
            })
            .max()
            .unwrap_or(0);
        let dofs = 2 * self.sequence.len();
        self.matrix = BandedSpd::new(dofs, 2 * band + 1);
        self.rhs = vec![0.0; dofs];
        self.assembly = cons.iter().map(|c| self.assembly_of(c)).collect();
    }

    /// Which unknowns `c` couples: a point and its mirror image are one, so their
    /// gradients add into one slot.
    fn assembly_of(&self, c: &Constraint) -> Assembly {
        let mut points = [None; 3];
        let mut firsts = [0; 3];
        let mut slots = 0;
        for (p, &i) in c.idx[..c.count].iter().enumerate() {
            let Some(place) = self.order[i] else {
                continue;
            };
            let first = 2 * place.at;
            let slot = match firsts[..slots].iter().position(|&f| f == first) {
                Some(slot) => slot,
                None => {
                    firsts[slots] = first;
                    slots += 1;
                    slots - 1
                }
            };
            points[p] = Some((slot, place.mirrored));
        }
        Assembly {
            points,
            slots,
            stamp: self.matrix.stamp(&firsts[..slots]),
        }
    }

    /// Solves for the forces at the predicted positions, `damping = τ/dt` adding the
    /// mesoglea's viscosity (backward Euler: the rate over the step, the stiffness
    /// `k·(1 + τ/dt)`), with a diagonal of its own for each point (`diag(point)`: the
    /// water it drags along, or the tentacles' drag, over the step). With the water's
    /// `response` the diagonal is replaced by it: `(W + K·G) f = F` (`docs/numerics.md`).
    pub(crate) fn solve_each(
        &mut self,
        cons: &[Constraint],
        diag: impl Fn(usize) -> f32,
        response: Option<&Response>,
        damping: f32,
        loads: &[(usize, Vec2)],
        out: &mut [Vec2],
    ) {
        self.matrix.clear_to_diagonal(0.0);
        // The water each point drags along, unless the water's response stands for it.
        if response.is_none() {
            for (o, &i) in self.sequence.iter().enumerate() {
                let d = diag(i) as f64;
                self.matrix.add(2 * o, 2 * o, d);
                self.matrix.add(2 * o + 1, 2 * o + 1, d);
            }
            for &j in &self.mirrored {
                let place = self.order[j].expect("a mirrored point has a place");
                let (o, d) = (place.at, diag(j) as f64);
                self.matrix.add(2 * o, 2 * o, d);
                self.matrix.add(2 * o + 1, 2 * o + 1, d);
            }
        }
        // Each element once: its explicit force at the predicted positions (the
        // right-hand side) and its stiffness.
        self.forces.iter_mut().for_each(|f| *f = Vec2::ZERO);
        for &(i, load) in loads {
            self.forces[i] += load;
        }
        debug_assert_eq!(cons.len(), self.assembly.len(), "the elements prepared for");
        for (c, assembly) in cons.iter().zip(&self.assembly) {
            c.add_damped_force(&mut self.forces, damping);
            let k = c.stiffness as f64 * (1.0 + damping as f64);
            // The constraint's gradient over the solved displacements: a point and its
            // mirror image are one unknown, so their parts add.
            let mut g = [[0.0f32; 2]; 3];
            for (grad, point) in c.grad.iter().zip(&assembly.points) {
                if let Some((slot, mirrored)) = *point {
                    g[slot][0] += if mirrored { -grad.x } else { grad.x };
                    g[slot][1] += grad.y;
                }
            }
            self.matrix
                .add_stamped(k, &assembly.stamp, &g[..assembly.slots]);
        }
        for (o, &i) in self.sequence.iter().enumerate() {
            let f = self.forces[i];
            self.rhs[2 * o] = f.x as f64;
            self.rhs[2 * o + 1] = f.y as f64;
        }
        for &j in &self.mirrored {
            let place = self.order[j].expect("a mirrored point has a place");
            let f = place.read(self.forces[j]);
            self.rhs[2 * place.at] += f.x as f64;
            self.rhs[2 * place.at + 1] += f.y as f64;
        }
        if let Some(response) = response {
            self.solve_with(response, out);
            return;
        }
        if !self.matrix.factor_and_solve(&mut self.rhs) {
            // Only non-finite input gets here; the step's health check then recovers.
            for &i in self.sequence.iter().chain(&self.mirrored) {
                out[i] = Vec2::splat(f32::NAN);
            }
            return;
        }
        out.iter_mut().for_each(|o| *o = Vec2::ZERO);
        for (o, &i) in self.sequence.iter().enumerate() {
            let (x, y) = (self.rhs[2 * o], self.rhs[2 * o + 1]);
            out[i] = diag(i) * Vec2::new(x as f32, y as f32);
        }
        for &j in &self.mirrored {
            let place = self.order[j].expect("a mirrored point has a place");
            let (x, y) = (self.rhs[2 * place.at], self.rhs[2 * place.at + 1]);
            out[j] = diag(j) * place.read(Vec2::new(x as f32, y as f32));
        }
    }

    /// Solves `(W + K·G) f = F` for the forces themselves, `K` assembled in `matrix`
    /// (no diagonal of its own), `F` in `rhs`, and writes them to `out`, mirror images
    /// included. `G` couples a force's x to displacements' x only, so `(K·G)[r][c]` sums
    /// over `K`'s row `r` at the unknowns of `c`'s component.
    fn solve_with(&mut self, response: &Response, out: &mut [Vec2]) {
        let n = self.sequence.len();
        debug_assert_eq!(response.len(), n, "a response over the solved points");
        let (dofs, kb, gb) = (2 * n, self.matrix.band(), response.band());
        let band = kb + 2 * gb;
        self.coupled.reset(dofs, band, band);
        for r in 0..dofs {
            // Column `col` of row `r` is at `col + band − r`.
            let row = self.coupled.row_mut(r);
            row[band] = self.counts[r / 2];
            // Point by point along `K`'s row: its x and y unknowns' stiffness times `G`'s
            // x and y rows, which lie side by side, so one pass adds both.
            for s in r.saturating_sub(kb) / 2..=((r + kb).min(dofs - 1) / 2) {
                let within = |q: usize| q + kb >= r && q <= r + kb;
                let k = [0, 1].map(|c| {
                    let q = 2 * s + c;
                    if within(q) {
                        self.matrix.get(r, q)
                    } else {
                        0.0
                    }
                });
                let (first, last) = (s.saturating_sub(gb), (s + gb + 1).min(n));
                let g = response.row(s, first..last);
                if within(2 * s) && within(2 * s + 1) {
                    let slots = &mut row[2 * first + band - r..][..2 * (last - first)];
                    for (slot, g) in slots.chunks_exact_mut(2).zip(g.chunks_exact(2)) {
                        slot[0] += k[0] * g[0] as f64;
                        slot[1] += k[1] * g[1] as f64;
                    }
                } else {
                    // At the ends of `K`'s band only one of the two couples.
                    for c in (0..2).filter(|&c| k[c] != 0.0) {
                        for (j, g) in (first..last).zip(g.chunks_exact(2)) {
                            row[2 * j + c + band - r] += k[c] * g[c] as f64;
                        }
                    }
                }
            }
        }
        if !self.coupled.factor_and_solve(&mut self.rhs) {
            // Only non-finite input gets here; the step's health check then recovers.
            for &i in self.sequence.iter().chain(&self.mirrored) {
                out[i] = Vec2::splat(f32::NAN);
            }
            return;
        }
        out.iter_mut().for_each(|o| *o = Vec2::ZERO);
        let force = |o: usize| Vec2::new(self.rhs[2 * o] as f32, self.rhs[2 * o + 1] as f32);
        for (o, &i) in self.sequence.iter().enumerate() {
            out[i] = force(o);
        }
        for &j in &self.mirrored {
            let place = self.order[j].expect("a mirrored point has a place");
            out[j] = place.read(force(place.at));
        }
    }
}
