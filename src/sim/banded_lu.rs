//! A general banded matrix with an in-place LU solve, no pivoting.
//!
//! The bell's forces with the water's response in the solve, `(W + K·G) f = F`, are not
//! symmetric: `K` the bell's stiffness and `G` the water's reply are, their product is not.
//! Its eigenvalues are those of `W + G^½·K·G^½`, real and positive, and its diagonal is
//! most of it, so elimination in order needs no pivoting; a zero or non-finite pivot is
//! reported instead.

/// A square banded matrix: entries with `col < row − lower` or `col > row + upper` are zero.
#[derive(Clone, Default)]
pub(crate) struct BandedLu {
    n: usize,
    lower: usize,
    upper: usize,
    /// Row-major: `entries[row * width + (col + lower − row)]`.
    entries: Vec<f64>,
}

impl BandedLu {
    /// Zeroes the matrix and sizes it `n`×`n` with `lower` and `upper` diagonals either
    /// side of the main one, keeping its storage.
    pub(crate) fn reset(&mut self, n: usize, lower: usize, upper: usize) {
        self.n = n;
        self.lower = lower;
        self.upper = upper;
        self.entries.clear();
        self.entries.resize(n * (lower + upper + 1), 0.0);
    }

    fn width(&self) -> usize {
        self.lower + self.upper + 1
    }

    /// Adds `value` at `(row, col)`, which must lie in the band.
    #[cfg(test)]
    pub(crate) fn add(&mut self, row: usize, col: usize, value: f64) {
        debug_assert!(
            col + self.lower >= row && col <= row + self.upper,
            "outside the band"
        );
        let w = self.width();
        self.entries[row * w + col + self.lower - row] += value;
    }

    /// Row `row`'s stored entries and the column of its first: column `c` is at
    /// `c + lower − row`.
    #[inline]
    pub(crate) fn row_mut(&mut self, row: usize) -> &mut [f64] {
        let w = self.width();
        &mut self.entries[row * w..][..w]
    }

    /// Factorises in place (`A = L·U`, `L` unit lower) and solves `A x = rhs`, overwriting
    /// `rhs` with `x`. Returns false at a zero or non-finite pivot.
    pub(crate) fn factor_and_solve(&mut self, rhs: &mut [f64]) -> bool {
        let mut pivots_ok = true;
        eliminate_dispatch(self, rhs, &mut pivots_ok);
        if !pivots_ok {
            return false;
        }
        let (n, kl, ku, w) = (self.n, self.lower, self.upper, self.width());
        for r in (0..n).rev() {
            let row = &self.entries[r * w..][..w];
            let last = (n - 1).min(r + ku);
            let sum = (r + 1..=last).fold(rhs[r], |s, c| s - row[c + kl - r] * rhs[c]);
            rhs[r] = sum / row[kl];
        }
        true
    }
}

/// [`eliminate`] four lanes wide where the processor has AVX (the same operations in the
/// same order, so the same bits).
fn eliminate_dispatch(lu: &mut BandedLu, rhs: &mut [f64], ok: &mut bool) {
    eight_wide!(eliminate, (lu: &mut BandedLu, rhs: &mut [f64], ok: &mut bool))
}

/// Gaussian elimination in order, `rhs` carried along; `ok` cleared at a zero or
/// non-finite pivot (the matrix is then left part-way).
#[inline(always)]
fn eliminate(lu: &mut BandedLu, rhs: &mut [f64], ok: &mut bool) {
    let (n, kl, ku, w) = (lu.n, lu.lower, lu.upper, lu.width());
    let a = &mut lu.entries;
    for k in 0..n {
        let pivot = a[k * w + kl];
        if pivot == 0.0 || !pivot.is_finite() {
            *ok = false;
            return;
        }
        let inverse = 1.0 / pivot;
        let span = (n - 1).min(k + ku) - k;
        let (head, tail) = a.split_at_mut((k + 1) * w);
        // Row k's entries from column k + 1 on, subtracted from each row below.
        let pivot_row = &head[k * w + kl + 1..][..span];
        let rhs_k = rhs[k];
        for below in 1..=(n - 1 - k).min(kl) {
            // Row k + below: its column k at `kl − below`, the next ones after it.
            let row = &mut tail[(below - 1) * w + kl - below..][..=span];
            let l = row[0] * inverse;
            if l == 0.0 {
                continue;
            }
            for (x, &p) in row[1..].iter_mut().zip(pivot_row) {
                *x -= l * p;
            }
            rhs[k + below] -= l * rhs_k;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric banded system, lower and upper bands of different widths, solved
    /// to round-off against the solution it was made from.
    #[test]
    fn solves_a_non_symmetric_banded_system() {
        let (n, kl, ku) = (17, 3, 5);
        let entry = |r: usize, c: usize| -> f64 {
            if r == c {
                6.0 + (r % 3) as f64
            } else if c + kl >= r && c <= r + ku {
                ((r * 7 + c * 3) % 11) as f64 / 11.0 - 0.4
            } else {
                0.0
            }
        };
        let mut m = BandedLu::default();
        m.reset(n, kl, ku);
        for r in 0..n {
            for c in 0..n {
                if entry(r, c) != 0.0 {
                    m.add(r, c, entry(r, c));
                }
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.9).cos()).collect();
        let mut rhs: Vec<f64> = (0..n)
            .map(|r| (0..n).map(|c| entry(r, c) * x[c]).sum())
            .collect();
        assert!(m.factor_and_solve(&mut rhs));
        for (got, want) in rhs.iter().zip(&x) {
            assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        }
    }

    #[test]
    fn reports_a_zero_pivot() {
        let mut m = BandedLu::default();
        m.reset(2, 1, 1);
        m.add(0, 1, 1.0);
        m.add(1, 0, 1.0);
        assert!(!m.factor_and_solve(&mut [1.0, 1.0]));
    }
}
