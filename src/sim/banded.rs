//! A symmetric positive-definite banded matrix with an in-place Cholesky solve.
//!
//! The body's implicit stiffness couples each point only to its chain neighbours and, by
//! the muscles, to its opposite point. Numbered from the apex outwards, alternating sides,
//! every coupling lands within a few rows of the diagonal, so an exact banded solve costs
//! O(n·b²) and never stalls the way conjugate gradients does on stiff hinges.

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

    /// Adds `value` at `(row, col)` of the symmetric matrix (give each off-diagonal pair
    /// once, either way round).
    pub(crate) fn add(&mut self, row: usize, col: usize, value: f64) {
        let (r, c) = if row >= col { (row, col) } else { (col, row) };
        debug_assert!(r - c <= self.band, "entry outside the band");
        self.lower[r * (self.band + 1) + (r - c)] += value;
    }

    /// Adds `k·g gᵀ` for a gradient `g` over a few points of two unknowns each,
    /// `(first unknown, [x, y])` with distinct points, each entry `k·(gₐ·g_b)` (the product
    /// in `f32`, as the gradients are) added once.
    pub(crate) fn add_outer(&mut self, k: f64, g: &[(usize, [f32; 2])]) {
        let w = self.band + 1;
        let lower = &mut self.lower[..];
        let mut add = |r: usize, c: usize, value: f64| {
            debug_assert!(r >= c && r - c < w, "entry outside the band");
            lower[r * w + (r - c)] += value;
        };
        for (p, &(op, gp)) in g.iter().enumerate() {
            // The point's own 2×2 block is symmetric: its lower triangle.
            add(op, op, k * (gp[0] * gp[0]) as f64);
            add(op + 1, op, k * (gp[1] * gp[0]) as f64);
            add(op + 1, op + 1, k * (gp[1] * gp[1]) as f64);
            for &(oq, gq) in &g[..p] {
                for (a, ga) in gp.iter().enumerate() {
                    for (b, gb) in gq.iter().enumerate() {
                        let (r, c) = (op + a, oq + b);
                        let value = k * (ga * gb) as f64;
                        if r >= c {
                            add(r, c, value)
                        } else {
                            add(c, r, value)
                        }
                    }
                }
            }
        }
    }

    /// Factorises in place (Cholesky, `A = L·Lᵀ`) and solves `A x = rhs`, overwriting
    /// `rhs` with `x`. Returns false if the matrix was not positive definite.
    pub(crate) fn factor_and_solve(&mut self, rhs: &mut [f64]) -> bool {
        let (n, b) = (self.n, self.band);
        let w = b + 1;
        for i in 0..n {
            // Row i's entries run from column `first`; every column j of it shares that
            // start with row j (j − b ≤ i − b), so each sum runs over k in first..j.
            let first = i.saturating_sub(b);
            let (done, rest) = self.lower.split_at_mut(i * w);
            let row_i = &mut rest[..w];
            for j in first..i {
                // Σ over k ascending of L[i][k]·L[j][k]: both rows are stored from the
                // diagonal down, so `t` counts down as k counts up.
                let terms = j - first;
                let row_j = &done[j * w..][..w];
                let (ik, jk) = (&row_i[i - j + 1..][..terms], &row_j[1..][..terms]);
                let mut sum = row_i[i - j];
                for t in (0..terms).rev() {
                    sum -= ik[t] * jk[t];
                }
                row_i[i - j] = sum * self.inverse[j];
            }
            let mut sum = row_i[0];
            for &l in row_i[1..=i - first].iter().rev() {
                sum -= l * l;
            }
            if sum <= 0.0 || !sum.is_finite() {
                return false;
            }
            row_i[0] = sum.sqrt();
            self.inverse[i] = 1.0 / row_i[0];
        }
        // Forward: L y = rhs.
        for i in 0..n {
            let first = i.saturating_sub(b);
            let row = &self.lower[i * w..i * w + w];
            let sum = (first..i).fold(rhs[i], |sum, k| sum - row[i - k] * rhs[k]);
            rhs[i] = sum * self.inverse[i];
        }
        // Backward: Lᵀ x = y.
        for i in (0..n).rev() {
            let last = (i + b + 1).min(n);
            let sum =
                (i + 1..last).fold(rhs[i], |sum, k| sum - self.lower[k * w + (k - i)] * rhs[k]);
            rhs[i] = sum * self.inverse[i];
        }
        true
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
}
