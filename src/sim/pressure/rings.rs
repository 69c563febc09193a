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
//!
//! A planar slice held mirror-symmetric is solved the same way on its half
//! ([`Across::MirroredPlane`]): the plane's operator across, from the axis (the mirror:
//! the column past it is the one before it) to the free-slip wall.

use super::{Factors, shared};
use rustdct::{DctPlanner, TransformType4};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// A DST-IV of one length, shared by every slice of it: for an even length, one complex
/// FFT of half the length between two twiddles (half of what a general DST-IV through
/// two type-3 transforms costs); for an odd one, rustdct's.
#[derive(Clone)]
enum Along {
    Even {
        fft: Arc<dyn Fft<f32>>,
        /// `e^{−iπ(4j + 1)/4n}`, applied before the FFT, and `e^{−iπj/n}` after it.
        before: Arc<[Complex<f32>]>,
        after: Arc<[Complex<f32>]>,
    },
    Odd(Arc<dyn TransformType4<f32>>),
}

/// Work space of one row's transform.
#[derive(Clone)]
struct Scratch {
    complex: Vec<Complex<f32>>,
    real: Vec<f32>,
}

impl Along {
    fn plan(n: usize) -> Self {
        static PLANS: OnceLock<Mutex<HashMap<usize, Arc<Along>>>> = OnceLock::new();
        let plan = shared(PLANS.get_or_init(Default::default), n, || {
            if n % 2 == 1 {
                return Arc::new(Along::Odd(DctPlanner::new().plan_dst4(n)));
            }
            let half = n / 2;
            let turn = |angle: f64| {
                let (sin, cos) = angle.sin_cos();
                Complex::new(cos as f32, sin as f32)
            };
            let pi = std::f64::consts::PI;
            Arc::new(Along::Even {
                fft: FftPlanner::new().plan_fft_forward(half),
                before: (0..half)
                    .map(|j| turn(-pi * (4 * j + 1) as f64 / (4 * n) as f64))
                    .collect(),
                after: (0..half).map(|j| turn(-pi * j as f64 / n as f64)).collect(),
            })
        });
        (*plan).clone()
    }

    /// Scratch space one row's transform needs.
    fn scratch(&self) -> Scratch {
        match self {
            Along::Even { fft, before, .. } => Scratch {
                complex: vec![Complex::default(); before.len() + fft.get_inplace_scratch_len()],
                real: Vec::new(),
            },
            Along::Odd(dst) => Scratch {
                complex: Vec::new(),
                // The row, then the transform's own work space.
                real: vec![0.0; dst.len() + dst.get_scratch_len()],
            },
        }
    }

    /// `row[k] ← Σ_j row[j]·sin(π(j + ½)(k + ½)/n)`.
    #[cfg(test)]
    fn transform(&self, row: &mut [f32], scratch: &mut Scratch) {
        let n = row.len();
        self.load(n, scratch, |j| row[j]);
        self.store(n, scratch, |j, x| row[j] = x);
    }

    /// The first half of [`Self::transform`] of the `n` values `read` gives: they are
    /// read, all of them, before [`Self::store`] writes any, so the two may be different
    /// layouts (a column of one field in, a row of another out) with no copy between.
    fn load(&self, n: usize, scratch: &mut Scratch, read: impl Fn(usize) -> f32) {
        match self {
            Along::Even { fft, before, .. } => {
                // The DCT-IV of the row reversed, through one FFT of n/2 (the even and
                // odd samples as the real and imaginary parts), its odd outputs negated:
                // the DST-IV.
                let half = before.len();
                let (buffer, scratch) = scratch.complex.split_at_mut(half);
                for (j, (b, w)) in buffer.iter_mut().zip(before.iter()).enumerate() {
                    *b = Complex::new(read(n - 1 - 2 * j), read(2 * j)) * w;
                }
                fft.process_with_scratch(buffer, scratch);
            }
            Along::Odd(dst) => {
                let (row, work) = scratch.real.split_at_mut(n);
                for (j, x) in row.iter_mut().enumerate() {
                    *x = read(j);
                }
                dst.process_dst4_with_scratch(row, work);
            }
        }
    }

    /// The second half of [`Self::transform`]: `write(k, value)` for each of the `n`.
    fn store(&self, n: usize, scratch: &Scratch, mut write: impl FnMut(usize, f32)) {
        match self {
            Along::Even { after, .. } => {
                for (j, (b, w)) in scratch.complex.iter().zip(after.iter()).enumerate() {
                    let u = b * w;
                    write(2 * j, u.re);
                    write(n - 1 - 2 * j, u.im);
                }
            }
            Along::Odd(_) => {
                for (j, x) in scratch.real[..n].iter().enumerate() {
                    write(j, *x);
                }
            }
        }
    }
}

/// The operator across the solved half, from the axis to the wall.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Across {
    /// The r-weighted one of an axisymmetric slice ([`radial_operator`]).
    Rings,
    /// The plane's, mirrored at the axis ([`mirrored_plane_operator`]).
    MirroredPlane,
}

/// The exact pressure solve on `rings × n` cells of a mirror-symmetric slice: `rings`
/// columns across (the axis first), `n` along the axis.
#[derive(Clone)]
pub(crate) struct RingPoissonSolver {
    n: usize,
    along: Along,
    factors: Arc<Factors>,
    modes: Vec<f64>,
    scratch: Scratch,
    /// Every ring's half-length transform at once (`rings × n/2`, ring by ring): an even
    /// length's whole batch goes through the FFT in one call, and its twiddles run along
    /// the rows the projection holds, not down their columns.
    batch: Vec<Complex<f32>>,
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

/// Coefficients of the plane's operator across `columns` cells of size `h` from the axis
/// to the wall, as [`radial_operator`] gives them: the cell on the axis has its mirror
/// image on both sides (the column past the axis is the one before it), the wall's cell
/// no flux through the wall.
pub(crate) fn mirrored_plane_operator(columns: usize, h: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let off = 1.0 / (h * h);
    let (mut lower, mut diagonal, mut upper) =
        (vec![0.0; columns], vec![0.0; columns], vec![0.0; columns]);
    for k in 0..columns {
        let wall = k + 1 == columns;
        if k == 0 {
            upper[0] = if wall { 0.0 } else { 2.0 * off };
        } else {
            lower[k] = off;
            upper[k] = if wall { 0.0 } else { off };
        }
        diagonal[k] = -(lower[k] + upper[k]);
    }
    (lower, diagonal, upper)
}

fn factors(across: Across, rings: usize, n: usize, h: f32) -> Arc<Factors> {
    type Shared = Mutex<HashMap<(Across, usize, usize, u32), Arc<Factors>>>;
    static FACTORS: OnceLock<Shared> = OnceLock::new();
    shared(
        FACTORS.get_or_init(Default::default),
        (across, rings, n, h.to_bits()),
        || {
            let (pi, h) = (std::f64::consts::PI, h as f64);
            // Each system in the order the transform leaves its modes (`mode_at`).
            let lambda: Vec<f64> = (0..n)
                .map(|p| mode_at(n, p) as f64)
                .map(|m| (2.0 * (pi * (m + 0.5) / n as f64).cos() - 2.0) / (h * h))
                .collect();
            // Eliminated from the outer wall in to the axis: the fluid's column order.
            let (lower, mut diagonal, upper) = match across {
                Across::Rings => radial_operator(rings, h),
                Across::MirroredPlane => mirrored_plane_operator(rings, h),
            };
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
        Self::across(Across::Rings, rings, n, h)
    }

    /// A solver for `columns` cells across (the `across` operator) and `n` along the axis.
    pub(crate) fn across(across: Across, columns: usize, n: usize, h: f32) -> Self {
        let along = Along::plan(n);
        let scratch = along.scratch();
        let batch = match along {
            Along::Even { .. } => vec![Complex::default(); columns * (n / 2)],
            Along::Odd(_) => Vec::new(),
        };
        Self {
            n,
            along,
            factors: factors(across, columns, n, h),
            modes: vec![0.0; columns * n],
            scratch,
            batch,
        }
    }

    /// Heap bytes of this solver's own (unshared) buffers.
    pub(crate) fn bytes(&self) -> usize {
        self.modes.len() * 8
            + (self.scratch.complex.len() + self.batch.len()) * 8
            + self.scratch.real.len() * 4
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
    #[cfg(test)]
    pub(crate) fn solve_reversed(&mut self, field: &mut [f32]) {
        let n = self.n;
        debug_assert_eq!(field.len(), self.modes.len());
        let mut natural = vec![0.0; n];
        for row in field.chunks_exact_mut(n) {
            self.along.transform(row, &mut self.scratch);
            natural.copy_from_slice(row);
            for (p, x) in row.iter_mut().enumerate() {
                *x = natural[mode_at(n, p)];
            }
        }
        // DST-IV is its own inverse up to n/2: undone on the way in.
        self.factors.solve(field, 2.0 / n as f64, &mut self.modes);
        for (row, modes) in field.chunks_exact_mut(n).zip(self.modes.chunks_exact(n)) {
            for (p, m) in modes.iter().enumerate() {
                row[mode_at(n, p)] = *m as f32;
            }
            self.along.transform(row, &mut self.scratch);
        }
    }

    /// [`Self::solve_reversed`] of a field held the other way round, as the projection
    /// builds it: `across` has one row per cell along the axis, each a value per ring in
    /// the fluid's order (the outer wall first). Each ring's column is transformed
    /// straight into its row of `work` (`rings × n`, its modes in [`mode_at`]'s order)
    /// and back, so the field is never turned: the same arithmetic, the same bits. An
    /// even length's twiddles run along the rows of `across`, every ring at once, and
    /// its FFTs go through in one batch.
    pub(crate) fn solve_across(&mut self, across: &mut [f32], work: &mut [f32]) {
        let solver = self;
        eight_wide!(
            RingPoissonSolver::solve_across_passes,
            (solver: &mut RingPoissonSolver, across: &mut [f32], work: &mut [f32])
        )
    }

    /// [`Self::solve_across`]'s passes, inlined into each of its callers' codegen.
    #[inline(always)]
    fn solve_across_passes(&mut self, across: &mut [f32], work: &mut [f32]) {
        let n = self.n;
        let rings = across.len() / n;
        debug_assert_eq!(work.len(), self.modes.len());
        let Along::Even { fft, before, after } = &self.along else {
            return self.solve_across_one_by_one(across, work);
        };
        let half = n / 2;
        let scratch = &mut self.scratch.complex[half..];
        // In: the twiddles before the FFT along each pair of rows of `across` (every ring
        // at once), each ring's values into its row of the batch.
        for (j, w) in before.iter().enumerate() {
            let reversed = &across[(n - 1 - 2 * j) * rings..][..rings];
            let even = &across[2 * j * rings..][..rings];
            for (k, (a, b)) in reversed.iter().zip(even).enumerate() {
                self.batch[k * half + j] = Complex::new(*a, *b) * w;
            }
        }
        fft.process_with_scratch(&mut self.batch, scratch);
        // Modes n − 1 − 2j and 2j side by side (`mode_at`).
        for (row, ring) in work.chunks_exact_mut(n).zip(self.batch.chunks_exact(half)) {
            for (pair, (b, w)) in row.chunks_exact_mut(2).zip(ring.iter().zip(after.iter())) {
                let u = b * w;
                pair[0] = u.im;
                pair[1] = u.re;
            }
        }
        // DST-IV is its own inverse up to n/2: undone on the way in.
        self.factors.solve(work, 2.0 / n as f64, &mut self.modes);
        // Out: each ring's modes through the FFT, then the twiddles after it along the
        // rows of `across`.
        for (ring, modes) in self
            .batch
            .chunks_exact_mut(half)
            .zip(self.modes.chunks_exact(n))
        {
            for (b, (pair, w)) in ring
                .iter_mut()
                .zip(modes.chunks_exact(2).zip(before.iter()))
            {
                *b = Complex::new(pair[0] as f32, pair[1] as f32) * w;
            }
        }
        fft.process_with_scratch(&mut self.batch, scratch);
        for (j, w) in after.iter().enumerate() {
            let (even, reversed) = two_rows(across, rings, 2 * j, n - 1 - 2 * j);
            for (k, (re, im)) in even.iter_mut().zip(reversed).enumerate() {
                let u = self.batch[k * half + j] * w;
                *re = u.re;
                *im = u.im;
            }
        }
    }

    /// [`Self::solve_across`] one ring's column at a time (odd lengths).
    fn solve_across_one_by_one(&mut self, across: &mut [f32], work: &mut [f32]) {
        let n = self.n;
        let rings = across.len() / n;
        for (k, row) in work.chunks_exact_mut(n).enumerate() {
            self.along
                .load(n, &mut self.scratch, |j| across[j * rings + k]);
            self.along.store(n, &self.scratch, |j, x| row[j] = x);
        }
        self.factors.solve(work, 2.0 / n as f64, &mut self.modes);
        for (k, modes) in self.modes.chunks_exact(n).enumerate() {
            self.along.load(n, &mut self.scratch, |j| modes[j] as f32);
            self.along
                .store(n, &self.scratch, |j, x| across[j * rings + k] = x);
        }
    }
}

/// Which mode of the transform along the axis the solve holds at position `p` of a row of
/// `n`: the even-length transform leaves modes `n − 1 − 2j` and `2j` as the two halves of
/// its `j`-th complex output, so they are kept side by side (the elimination is the same
/// for any order of the modes); an odd length's in order.
fn mode_at(n: usize, p: usize) -> usize {
    match (n % 2, p % 2) {
        (1, _) => p,
        (_, 0) => n - 1 - p,
        _ => p - 1,
    }
}

/// Rows `a` and `b` (different, either order) of rows `len` long.
fn two_rows(field: &mut [f32], len: usize, a: usize, b: usize) -> (&mut [f32], &mut [f32]) {
    if a < b {
        let (low, high) = field.split_at_mut(b * len);
        (&mut low[a * len..][..len], &mut high[..len])
    } else {
        let (low, high) = field.split_at_mut(a * len);
        (&mut high[..len], &mut low[b * len..][..len])
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
    fn the_half_length_fft_is_the_dst_iv() {
        for n in [2, 16, 60, 62, 100, 192] {
            let row: Vec<f32> = (0..n).map(|j| ((j * 37 % 11) as f32 - 5.0) * 0.1).collect();
            let mut fast = row.clone();
            let along = Along::plan(n);
            assert!(matches!(along, Along::Even { .. }));
            along.transform(&mut fast, &mut along.scratch());
            let mut reference = row.clone();
            let dst = DctPlanner::new().plan_dst4(n);
            dst.process_dst4(&mut reference);
            let scale = reference.iter().fold(0.0f32, |m, x| m.max(x.abs()));
            let err = fast
                .iter()
                .zip(&reference)
                .fold(0.0f32, |m, (a, b)| m.max((a - b).abs()));
            assert!(err < 1e-5 * scale, "n = {n}: {err} of {scale}");
        }
    }

    /// The projection's solve of a field held along the axis is the solve of the same
    /// field turned, bit for bit (even lengths through the half-length FFT, odd through
    /// rustdct's).
    #[test]
    fn solving_across_is_solving_the_field_turned() {
        for (rings, n) in [(9, 16), (31, 60), (32, 63)] {
            let rhs: Vec<f32> = (0..rings * n)
                .map(|q| ((q * 7919 % 211) as f32 / 211.0 - 0.5) * 3.0)
                .collect();
            // `rows`: ring-major, as `solve_reversed` takes it; `across`: axis-major.
            let mut rows = rhs.clone();
            let mut across = vec![0.0; rings * n];
            for k in 0..rings {
                for j in 0..n {
                    across[j * rings + k] = rhs[k * n + j];
                }
            }
            let mut solver = RingPoissonSolver::new(rings, n, 0.003);
            solver.solve_reversed(&mut rows);
            let mut work = vec![0.0; rings * n];
            solver.solve_across(&mut across, &mut work);
            for k in 0..rings {
                for j in 0..n {
                    assert_eq!(
                        across[j * rings + k].to_bits(),
                        rows[k * n + j].to_bits(),
                        "{rings}×{n}: ring {k}, cell {j}"
                    );
                }
            }
        }
    }

    /// A planar field that is mirror-symmetric about the middle column of an odd grid,
    /// solved on its half, is the channel's solve of the whole field.
    #[test]
    fn the_mirrored_half_is_the_whole_planar_solve() {
        for n in [15, 61, 101] {
            let (c, h) = (n / 2, 0.004);
            let rhs: Vec<f32> = (0..n * n)
                .map(|q| {
                    let (i, j) = ((q % n) as f32, (q / n) as f32);
                    let x = (i - c as f32).abs() / n as f32;
                    let y = (j + 0.5) / n as f32;
                    (3.0 * x * x).cos() * (2.0 * y).sin() + 0.2 * (9.0 * x).sin() * y
                        - 0.5 * (7.0 * x * y).cos()
                })
                .collect();
            let mut whole = rhs.clone();
            crate::sim::pressure::PoissonSolver::new(n, h).solve(&mut whole);
            // One row per column from the axis out, each along the channel.
            let mut half: Vec<f32> = (0..(c + 1) * n)
                .map(|q| rhs[(q % n) * n + c - q / n])
                .collect();
            RingPoissonSolver::across(Across::MirroredPlane, c + 1, n, h).solve(&mut half);
            let scale = whole.iter().fold(0.0f32, |m, x| m.max(x.abs()));
            let err = half.iter().enumerate().fold(0.0f32, |m, (q, x)| {
                m.max((x - whole[(q % n) * n + c - q / n]).abs())
            });
            assert!(err < 1e-5 * scale, "n = {n}: {err} of {scale}");
        }
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
