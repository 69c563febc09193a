//! A symmetric positive-definite banded matrix with an in-place Cholesky solve.
//!
//! The body's implicit stiffness couples each point only to its chain neighbours and, by
//! the muscles, to its opposite point. Numbered from the apex outwards, alternating sides,
//! every coupling lands within a few rows of the diagonal, so an exact banded solve costs
//! O(n·b²) and never stalls the way conjugate gradients does on stiff hinges.

/// Entries of `k·g gᵀ` over three points of two unknowns each, lower triangle: three
/// points' 2×2 blocks of three, and three pairs' blocks of four.
const STAMP_ENTRIES: usize = 21;

/// Where one coupling's entries lie in a [`BandedSpd`]'s storage ([`BandedSpd::stamp`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stamp {
    points: usize,
    places: [usize; STAMP_ENTRIES],
}

/// A symmetric positive-definite banded matrix, factored in place by Cholesky.
#[derive(Clone)]
pub(crate) struct BandedSpd {
    n: usize,
    /// Half-bandwidth: entries with `|row - col| > band` are zero.
    band: usize,
    /// Lower band, row-major: `lower[row * (band + 1) + (row - col)]`.
    lower: Vec<f64>,
    /// The reciprocals of the factor's diagonal: each row's entries and the substitutions
    /// multiply by them, where a division in every entry's dependency chain was most of
    /// the factorisation's time.
    inverse: Vec<f64>,
}

impl BandedSpd {
    /// An `n`×`n` zero matrix with `band` diagonals above the main one.
    pub(crate) fn new(n: usize, band: usize) -> Self {
        Self {
            n,
            band,
            lower: vec![0.0; n * (band + 1)],
            inverse: vec![0.0; n],
        }
    }

    /// Sets the matrix to `diagonal` times the identity.
    pub(crate) fn clear_to_diagonal(&mut self, diagonal: f64) {
        self.lower.iter_mut().for_each(|x| *x = 0.0);
        for row in 0..self.n {
            self.lower[row * (self.band + 1)] = diagonal;
        }
    }

    /// Half-bandwidth: entries with `|row - col|` past it are zero.
    pub(crate) fn band(&self) -> usize {
        self.band
    }

    /// The entry at `(row, col)`, which must lie within the band.
    #[inline]
    pub(crate) fn get(&self, row: usize, col: usize) -> f64 {
        let (r, c) = if row >= col { (row, col) } else { (col, row) };
        debug_assert!(r - c <= self.band, "entry outside the band");
        self.lower[r * (self.band + 1) + (r - c)]
    }

    /// Adds `value` at `(row, col)` of the symmetric matrix (give each off-diagonal pair
    /// once, either way round).
    pub(crate) fn add(&mut self, row: usize, col: usize, value: f64) {
        let (r, c) = if row >= col { (row, col) } else { (col, row) };
        debug_assert!(r - c <= self.band, "entry outside the band");
        self.lower[r * (self.band + 1) + (r - c)] += value;
    }

    /// Where `k·g gᵀ` lands in the lower band for a coupling of a few points whose first
    /// unknowns are `firsts` (two unknowns each, distinct points): worked out once for a
    /// coupling whose points never change, so adding it is a load per entry.
    pub(crate) fn stamp(&self, firsts: &[usize]) -> Stamp {
        assert!(firsts.len() <= 3, "a stamp couples at most three points");
        let w = self.band + 1;
        let mut stamp = Stamp {
            points: firsts.len(),
            places: [0; STAMP_ENTRIES],
        };
        let mut entry = 0;
        let mut place = |r: usize, c: usize| {
            let (r, c) = if r >= c { (r, c) } else { (c, r) };
            assert!(r - c <= self.band && r < self.n, "entry outside the band");
            stamp.places[entry] = r * w + (r - c);
            entry += 1;
        };
        for (p, &op) in firsts.iter().enumerate() {
            // The point's own 2×2 block is symmetric: its lower triangle.
            place(op, op);
            place(op + 1, op);
            place(op + 1, op + 1);
            for &oq in &firsts[..p] {
                for a in 0..2 {
                    for b in 0..2 {
                        place(op + a, oq + b);
                    }
                }
            }
        }
        stamp
    }

    /// Adds `k·g gᵀ` for a gradient over the points `stamp` was made for, `[x, y]` each,
    /// each entry `k·(gₐ·g_b)` (the product in `f32`, as the gradients are) added once.
    pub(crate) fn add_stamped(&mut self, k: f64, stamp: &Stamp, g: &[[f32; 2]]) {
        debug_assert_eq!(g.len(), stamp.points, "a gradient for the stamp's points");
        // Block by block in the stamp's order, unrolled: most of the body's couplings are
        // one or two points, their entries a handful of loads and adds.
        let own = |a: [f32; 2]| [a[0] * a[0], a[1] * a[0], a[1] * a[1]];
        let cross = |p: [f32; 2], q: [f32; 2]| [p[0] * q[0], p[0] * q[1], p[1] * q[0], p[1] * q[1]];
        let at = &stamp.places;
        if let [a, ..] = *g {
            self.add_at(k, at, own(a));
        }
        if let [a, b, ..] = *g {
            self.add_at(k, &at[3..], own(b));
            self.add_at(k, &at[6..], cross(b, a));
        }
        if let [a, b, c] = *g {
            self.add_at(k, &at[10..], own(c));
            self.add_at(k, &at[13..], cross(c, a));
            self.add_at(k, &at[17..], cross(c, b));
        }
    }

    /// Adds `k` times each of `values` at the first of `places`.
    #[inline(always)]
    fn add_at<const E: usize>(&mut self, k: f64, places: &[usize], values: [f32; E]) {
        let places: &[usize; E] = places[..E].try_into().expect("E entries");
        for (&at, value) in places.iter().zip(values) {
            self.lower[at] += k * value as f64;
        }
    }

    /// Factorises in place (Cholesky, `A = L·Lᵀ`) and solves `A x = rhs`, overwriting
    /// `rhs` with `x`. Returns false if the matrix was not positive definite.
    pub(crate) fn factor_and_solve(&mut self, rhs: &mut [f64]) -> bool {
        // The body's chains, solved on their half, couple each point to the next two
        // (hinges): five diagonals, which the compiler unrolls when it knows them.
        match self.band {
            5 => self.factor_and_solve_within(5, rhs),
            band => self.factor_and_solve_within(band, rhs),
        }
    }

    /// [`Self::factor_and_solve`] for a half-bandwidth `b`, the matrix's own. Past the
    /// first `b` rows every row reaches `b` entries left of its diagonal, a count the
    /// compiler can unroll when `b` is a constant; the first rows reach fewer.
    #[inline(always)]
    fn factor_and_solve_within(&mut self, b: usize, rhs: &mut [f64]) -> bool {
        debug_assert_eq!(b, self.band);
        let n = self.n;
        for i in 0..n {
            let whole = if i >= b {
                self.factor_row(i, b, b)
            } else {
                self.factor_row(i, i, b)
            };
            if !whole {
                return false;
            }
        }
        // Forward: L y = rhs.
        for i in 0..n {
            if i >= b {
                self.forward_row(i, b, b, rhs);
            } else {
                self.forward_row(i, i, b, rhs);
            }
        }
        // Backward: Lᵀ x = y.
        for i in (0..n).rev() {
            if i + b < n {
                self.backward_row(i, b, b, rhs);
            } else {
                self.backward_row(i, n - 1 - i, b, rhs);
            }
        }
        true
    }

    /// Row `i` of the factor, whose entries reach `reach` columns left of its diagonal.
    /// Returns false where its pivot is not positive.
    #[inline(always)]
    fn factor_row(&mut self, i: usize, reach: usize, b: usize) -> bool {
        let w = b + 1;
        // Row i's entries run from column `first`; every column j of it shares that start
        // with row j (j − b ≤ i − b), so each sum runs over k in first..j.
        let first = i - reach;
        let (done, rest) = self.lower.split_at_mut(i * w);
        let row_i = &mut rest[..w];
        for terms in 0..reach {
            // Σ over k ascending of L[i][k]·L[j][k]: both rows are stored from the
            // diagonal down, so `t` counts down as k counts up.
            let j = first + terms;
            let row_j = &done[j * w..][..w];
            let (ik, jk) = (&row_i[i - j + 1..][..terms], &row_j[1..][..terms]);
            let mut sum = row_i[i - j];
            for t in (0..terms).rev() {
                sum -= ik[t] * jk[t];
            }
            row_i[i - j] = sum * self.inverse[j];
        }
        let mut sum = row_i[0];
        for &l in row_i[1..=reach].iter().rev() {
            sum -= l * l;
        }
        if sum <= 0.0 || !sum.is_finite() {
            return false;
        }
        row_i[0] = sum.sqrt();
        self.inverse[i] = 1.0 / row_i[0];
        true
    }

    /// Row `i` of the forward substitution, over the `reach` unknowns before it.
    #[inline(always)]
    fn forward_row(&self, i: usize, reach: usize, b: usize, rhs: &mut [f64]) {
        let row = &self.lower[i * (b + 1)..][..b + 1];
        let sum = (i - reach..i).fold(rhs[i], |sum, k| sum - row[i - k] * rhs[k]);
        rhs[i] = sum * self.inverse[i];
    }

    /// Row `i` of the backward substitution, over the `reach` unknowns after it.
    #[inline(always)]
    fn backward_row(&self, i: usize, reach: usize, b: usize, rhs: &mut [f64]) {
        let w = b + 1;
        let sum = (i + 1..i + 1 + reach)
            .fold(rhs[i], |sum, k| sum - self.lower[k * w + (k - i)] * rhs[k]);
        rhs[i] = sum * self.inverse[i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_banded_system() {
        let n = 12;
        let band = 3;
        let mut dense = vec![vec![0.0f64; n]; n];
        let mut m = BandedSpd::new(n, band);
        m.clear_to_diagonal(4.0);
        for i in 0..n {
            dense[i][i] = 4.0;
            for d in 1..=band {
                if i + d < n {
                    let v = 0.3 / d as f64;
                    m.add(i + d, i, v);
                    dense[i + d][i] = v;
                    dense[i][i + d] = v;
                }
            }
        }
        let x_true: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin()).collect();
        let mut rhs: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| dense[i][j] * x_true[j]).sum())
            .collect();
        assert!(m.factor_and_solve(&mut rhs));
        for (a, b) in rhs.iter().zip(&x_true) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn refuses_an_indefinite_matrix() {
        let mut m = BandedSpd::new(3, 1);
        m.clear_to_diagonal(1.0);
        m.add(1, 0, 2.0);
        assert!(!m.factor_and_solve(&mut [1.0, 1.0, 1.0]));
    }

    /// A stamped outer product is `k·g gᵀ` entry by entry, wherever its points lie in the
    /// band and in whatever order they come, and adds on top of what is there.
    #[test]
    fn a_stamp_adds_the_outer_product() {
        let (n, band) = (10, 5);
        let entry = |m: &BandedSpd, r: usize, c: usize| {
            let (r, c) = if r >= c { (r, c) } else { (c, r) };
            if r - c > band {
                0.0
            } else {
                m.lower[r * (band + 1) + (r - c)]
            }
        };
        for firsts in [vec![4], vec![6, 4], vec![2, 0, 4], vec![8, 4, 6]] {
            let g: Vec<[f32; 2]> = (0..firsts.len())
                .map(|p| [0.3 + p as f32, -1.7 + 0.5 * p as f32])
                .collect();
            let mut m = BandedSpd::new(n, band);
            m.clear_to_diagonal(2.0);
            let stamp = m.stamp(&firsts);
            m.add_stamped(1.5, &stamp, &g);
            m.add_stamped(1.5, &stamp, &g);
            let mut dense = vec![vec![0.0f64; n]; n];
            for (p, &op) in firsts.iter().enumerate() {
                for (q, &oq) in firsts.iter().enumerate() {
                    for a in 0..2 {
                        for b in 0..2 {
                            dense[op + a][oq + b] += 3.0 * (g[p][a] * g[q][b]) as f64;
                        }
                    }
                }
            }
            for (r, row) in dense.iter().enumerate() {
                for (c, &want) in row.iter().enumerate() {
                    let want = want + if r == c { 2.0 } else { 0.0 };
                    let got = entry(&m, r, c);
                    assert!(
                        (got - want).abs() < 1e-9,
                        "{firsts:?} ({r}, {c}): {got} vs {want}"
                    );
                }
            }
        }
    }
}
