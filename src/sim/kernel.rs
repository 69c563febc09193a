//! The immersed-boundary kernels: how a point reads the velocity of the faces around it and
//! gives its force back to them, with the same weights (so the two are adjoint and the
//! total force is conserved).
//!
//! The paper spreads bilinearly onto the four nearest faces. That is not translation
//! invariant: the same bell half a cell further along feels a differently weighted grid,
//! and its stroke changed by ±15–40% with the offset. Roma, Peskin & Berger's (1999)
//! three-point kernel is built to be invariant (its weights' sum of squares is the same at
//! every offset, bilinear's varies twofold).
//!
//! Its width is a property of the bell, not of the grid: the species' `boundary_width`
//! (three cells at the default ten cells per diameter). A finer grid samples the same
//! stretched kernel with more faces, so refining the grid refines the solution of one
//! continuous problem instead of thinning the bell's hold on the water; with a kernel
//! three cells wide at every grid, the stroke grew by a quarter with each 1.5× refinement.

pub(crate) use crate::species::Kernel;
use std::ops::Range;

/// Most faces a stencil reaches along one axis (a kernel stretched four times).
const MAX_TAPS: usize = 13;

/// Weights along one axis: faces `index[..len]` with weights `weight[..len]`.
#[derive(Clone, Copy, Debug, Default)]
struct Taps {
    /// Face indices: `u32`, so that a stencil (copied once per point and step) is a
    /// third smaller.
    index: [u32; MAX_TAPS],
    weight: [f32; MAX_TAPS],
    len: usize,
}

/// The faces of one component around a point, and their weights (summing to 1): the
/// product of one set of taps across and one along.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Stencil {
    x: Taps,
    y: Taps,
    row: usize,
}

impl Taps {
    /// `Σ w·w'·scale(face)` over the faces both reach: where both run over consecutive
    /// faces (away from the folded ends) by their offset, otherwise face by face.
    #[inline]
    fn overlap(&self, other: &Taps, scale: impl Fn(usize) -> f32) -> f32 {
        let (a, b) = (&self.index[..self.len], &other.index[..other.len]);
        let (Some(&a0), Some(&b0)) = (a.first(), b.first()) else {
            return 0.0;
        };
        let consecutive = |t: &[u32], first: u32| t[t.len() - 1] - first == t.len() as u32 - 1;
        if consecutive(a, a0) && consecutive(b, b0) {
            let (from, to) = (a0.max(b0), (a0 + a.len() as u32).min(b0 + b.len() as u32));
            let mut sum = 0.0;
            for face in from..to {
                let (wa, wb) = (
                    self.weight[(face - a0) as usize],
                    other.weight[(face - b0) as usize],
                );
                sum += wa * wb * scale(face as usize);
            }
            return sum;
        }
        let mut sum = 0.0;
        for (i, &fa) in a.iter().enumerate() {
            for (j, &fb) in b.iter().enumerate() {
                if fa == fb {
                    sum += self.weight[i] * other.weight[j] * scale(fa as usize);
                }
            }
        }
        sum
    }
}

impl Stencil {
    /// Locates a point at fractional face coordinates `(gx, gy)` in an `nx × ny` array of
    /// faces (row-major), the kernel stretched `stretch` times (see the module), in place:
    /// a step locates every point of the body, and a stencil built and then copied was
    /// read back before its own stores had landed.
    pub(crate) fn locate(
        &mut self,
        kernel: Kernel,
        (gx, gy): (f32, f32),
        (nx, ny): (usize, usize),
        stretch: f32,
    ) {
        taps_into(&mut self.x, kernel, gx, nx, stretch);
        taps_into(&mut self.y, kernel, gy, ny, stretch);
        self.row = nx;
    }

    /// The rows of faces the stencil reaches.
    /// A stencil's taps run in order of their faces (folded ends repeat the end face), so
    /// its first and last rows bound them.
    pub(crate) fn rows(&self) -> Range<usize> {
        let rows = &self.y.index[..self.y.len];
        debug_assert!(rows.is_sorted(), "a stencil's rows in order");
        match (rows.first(), rows.last()) {
            (Some(&first), Some(&last)) => first as usize..last as usize + 1,
            _ => 0..0,
        }
    }

    /// The columns of faces the stencil reaches (as [`Self::rows`]).
    pub(crate) fn columns(&self) -> Range<usize> {
        let columns = &self.x.index[..self.x.len];
        match (columns.first(), columns.last()) {
            (Some(&first), Some(&last)) => first as usize..last as usize + 1,
            _ => 0..0,
        }
    }

    /// Scales each tap across by `share(column)` (at most 1) and renormalises them to sum
    /// to 1 again: the same faces, weighted otherwise. Sampling and spreading both read
    /// the taps, so they stay adjoint and the total spread force exact.
    pub(crate) fn reweigh_across(&mut self, share: impl Fn(usize) -> f32) {
        let x = &mut self.x;
        let mut sum = 0.0;
        for (weight, &column) in x.weight[..x.len].iter_mut().zip(&x.index[..x.len]) {
            *weight *= share(column as usize);
            sum += *weight;
        }
        if sum > 0.0 {
            for weight in &mut x.weight[..x.len] {
                *weight /= sum;
            }
        }
    }

    /// `(face index, weight)` pairs.
    #[cfg(test)]
    pub(crate) fn iter(&self) -> impl Iterator<Item = (usize, f32)> + '_ {
        let (x, y, row) = (&self.x, &self.y, self.row);
        (0..y.len).flat_map(move |b| {
            (0..x.len).map(move |a| {
                let face = y.index[b] as usize * row + x.index[a] as usize;
                (face, x.weight[a] * y.weight[b])
            })
        })
    }

    /// The weighted sum of `field` over the stencil's faces, rows in order.
    pub(crate) fn sample(&self, field: &[f32]) -> f32 {
        let (x, y) = (&self.x, &self.y);
        let mut sum = -0.0f32;
        for b in 0..y.len {
            let (start, wy) = (y.index[b] as usize * self.row, y.weight[b]);
            for a in 0..x.len {
                sum += x.weight[a] * wy * field[start + x.index[a] as usize];
            }
        }
        sum
    }

    /// Adds `value` to `field` at the stencil's faces, each share times its weight and
    /// the scale of its column (what varies across the grid only: an axisymmetric slice's
    /// radii); the adjoint of [`Self::sample`].
    pub(crate) fn spread(&self, value: f32, scale: &[f32], field: &mut [f32]) {
        let (x, y) = (&self.x, &self.y);
        for b in 0..y.len {
            let (start, wy) = (y.index[b] as usize * self.row, y.weight[b]);
            for a in 0..x.len {
                let column = x.index[a] as usize;
                field[start + column] += x.weight[a] * wy * value * scale[column];
            }
        }
    }

    /// [`Self::spread`] for the stencil's point mirrored about a vertical axis: each
    /// column `a` becomes `mirror(a)` (dropped where that is off the grid), the weights
    /// the same, so a ring's partner across the axis needs no stencil of its own.
    pub(crate) fn spread_mirrored(
        &self,
        value: f32,
        scale: &[f32],
        field: &mut [f32],
        mirror: impl Fn(usize) -> Option<usize>,
    ) {
        let (x, y) = (&self.x, &self.y);
        for b in 0..y.len {
            let (start, wy) = (y.index[b] as usize * self.row, y.weight[b]);
            for a in 0..x.len {
                if let Some(column) = mirror(x.index[a] as usize) {
                    field[start + column] += x.weight[a] * wy * value * scale[column];
                }
            }
        }
    }

    /// What `self` samples of a unit value spread through `other`: `Σ w·w'·scale` over
    /// the faces both reach. A stencil is one set of taps across times one along, and the
    /// scale varies across only, so the sum is a product of two short ones.
    pub(crate) fn overlap(&self, other: &Stencil, scale: &[f32]) -> f32 {
        let along = self.y.overlap(&other.y, |_| 1.0);
        if along == 0.0 {
            return 0.0;
        }
        along * self.x.overlap(&other.x, |column| scale[column])
    }

    /// [`Self::overlap`] with `other`'s point mirrored: its columns `mirror`ed (dropped
    /// where off the grid), as [`Self::spread_mirrored`] spreads it.
    pub(crate) fn overlap_mirrored(
        &self,
        other: &Stencil,
        scale: &[f32],
        mirror: impl Fn(usize) -> Option<usize>,
    ) -> f32 {
        let along = self.y.overlap(&other.y, |_| 1.0);
        if along == 0.0 {
            return 0.0;
        }
        let (x, ox) = (&self.x, &other.x);
        let mut across = 0.0;
        for oa in 0..ox.len {
            let Some(column) = mirror(ox.index[oa] as usize) else {
                continue;
            };
            for a in 0..x.len {
                if x.index[a] as usize == column {
                    across += x.weight[a] * ox.weight[oa] * scale[column];
                }
            }
        }
        along * across
    }
}

/// The rows of both `a` and `b` and any between (an empty range is no rows).
pub(crate) fn span(a: Range<usize>, b: Range<usize>) -> Range<usize> {
    match (a.is_empty(), b.is_empty()) {
        (true, _) => b,
        (_, true) => a,
        _ => a.start.min(b.start)..a.end.max(b.end),
    }
}

/// How far from a point, in cells, the faces of its stencil can lie: no face further
/// than this along either axis carries weight.
pub(crate) fn reach(kernel: Kernel, stretch: f32) -> f32 {
    match kernel {
        Kernel::Bilinear => 1.0,
        Kernel::Roma3 => 1.5 * clamped_stretch(stretch),
    }
}

/// The stretch a stencil is built with: at most [`MAX_TAPS`] faces along an axis.
fn clamped_stretch(stretch: f32) -> f32 {
    stretch.clamp(1.0, (MAX_TAPS - 1) as f32 / 3.0)
}

/// Roma, Peskin & Berger's three-point kernel at `r` cells (support |r| < 3/2).
#[cfg(any(test, not(target_arch = "x86_64")))]
fn roma(r: f32) -> f32 {
    let r = r.abs();
    if r <= 0.5 {
        (1.0 + (1.0 - 3.0 * r * r).max(0.0).sqrt()) / 3.0
    } else if r < 1.5 {
        (5.0 - 3.0 * r - (1.0 - 3.0 * (1.0 - r) * (1.0 - r)).max(0.0).sqrt()) / 6.0
    } else {
        0.0
    }
}

/// [`roma`] at four points: on x86-64 both pieces four-wide and one chosen per lane (a
/// stencil's divisions and square roots were a tenth of a step one at a time), the same
/// operations in the same order, so the same bits.
#[inline]
fn roma4(r: [f32; 4]) -> [f32; 4] {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: SSE2 is in every x86-64 target's baseline, so it is always enabled.
        unsafe { sse2::roma4(r) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        [roma(r[0]), roma(r[1]), roma(r[2]), roma(r[3])]
    }
}

#[cfg(target_arch = "x86_64")]
mod sse2 {
    use std::arch::x86_64::*;

    /// See [`super::roma4`].
    #[target_feature(enable = "sse2")]
    #[inline]
    pub(super) fn roma4(r: [f32; 4]) -> [f32; 4] {
        let k = _mm_set1_ps;
        let r = _mm_and_ps(
            _mm_setr_ps(r[0], r[1], r[2], r[3]),
            _mm_castsi128_ps(_mm_set1_epi32(0x7fff_ffff)),
        );
        // `f32::max(x, 0.0)`: 0 where x is NaN, as `maxps` gives its second operand.
        let root = |x: __m128| _mm_sqrt_ps(_mm_max_ps(x, k(0.0)));
        let near = _mm_sub_ps(k(1.0), _mm_mul_ps(_mm_mul_ps(k(3.0), r), r));
        let inner = _mm_div_ps(_mm_add_ps(k(1.0), root(near)), k(3.0));
        let rest = _mm_sub_ps(k(1.0), r);
        let far = _mm_sub_ps(k(1.0), _mm_mul_ps(_mm_mul_ps(k(3.0), rest), rest));
        let outer = _mm_div_ps(
            _mm_sub_ps(_mm_sub_ps(k(5.0), _mm_mul_ps(k(3.0), r)), root(far)),
            k(6.0),
        );
        // r ≤ ½: inner; else r < 3/2: outer; else (and NaN) 0.
        let (is_inner, is_outer) = (_mm_cmple_ps(r, k(0.5)), _mm_cmplt_ps(r, k(1.5)));
        let outer = _mm_and_ps(is_outer, outer);
        let w = _mm_or_ps(_mm_and_ps(is_inner, inner), _mm_andnot_ps(is_inner, outer));
        let mut out = [0.0f32; 4];
        // SAFETY: `out` holds four values.
        unsafe { _mm_storeu_ps(out.as_mut_ptr(), w) };
        out
    }
}

/// The floor of a finite `x ≥ 0`, by truncation: a library call on targets without
/// SSE4.1, and the kernel's bounds take two of them per axis and point.
fn floor_non_negative(x: f32) -> f32 {
    x as i32 as f32
}

/// The ceiling of a finite `x` within `i32`'s range, by truncation (a negative `x` already
/// truncates upwards). It gives +0 where `ceil` gives −0, which no weight can tell apart.
fn ceil_in_range(x: f32) -> f32 {
    let t = x as i32 as f32;
    if t < x { t + 1.0 } else { t }
}

/// Weights of `kernel` at fractional face coordinate `g` among `count` faces, the
/// three-point kernel stretched `stretch ≥ 1` times, written over `t`. Faces past either
/// end fold onto the end face, so the weights still sum to 1.
fn taps_into(t: &mut Taps, kernel: Kernel, g: f32, count: usize, stretch: f32) {
    let last = count as f32 - 1.0;
    let g = if g.is_finite() {
        g.clamp(0.0, last)
    } else {
        0.0
    };
    let clamp = |i: f32| i.clamp(0.0, last) as u32;
    t.len = 0;
    match kernel {
        Kernel::Bilinear => {
            let i0 = floor_non_negative(g).min(last - 1.0).max(0.0);
            let f = g - i0;
            t.index[..2].copy_from_slice(&[clamp(i0), clamp(i0 + 1.0)]);
            t.weight[..2].copy_from_slice(&[1.0 - f, f]);
            t.len = 2;
        }
        Kernel::Roma3 => {
            let stretch = clamped_stretch(stretch);
            let reach = reach(kernel, stretch);
            let (first, end) = (ceil_in_range(g - reach), floor_non_negative(g + reach));
            // The faces in reach four at a time, without a branch, so that the divisions
            // and square roots vectorise; those of positive weight kept, in order.
            let mut at = first;
            while at <= end && t.len < MAX_TAPS {
                let faces = [at, at + 1.0, at + 2.0, at + 3.0];
                let r = |k: usize| (faces[k] - g) / stretch;
                let weights = roma4([r(0), r(1), r(2), r(3)]);
                for (&i, &w) in faces.iter().zip(&weights) {
                    if i <= end && w > 0.0 && t.len < MAX_TAPS {
                        t.index[t.len] = clamp(i);
                        t.weight[t.len] = w;
                        t.len += 1;
                    }
                }
                at += 4.0;
            }
            // The sampled kernel sums to 1 and keeps the centre exactly only at whole
            // stretches; a linear tilt `w·(a + b·d)` restores both at any stretch, so a
            // uniform flow is read exactly and a force spreads about its own point.
            let (mut m0, mut m1, mut m2) = (0.0f32, 0.0f32, 0.0f32);
            for k in 0..t.len {
                let d = t.index[k] as f32 - g;
                let w = t.weight[k];
                (m0, m1, m2) = (m0 + w, m1 + w * d, m2 + w * d * d);
            }
            let det = m0 * m2 - m1 * m1;
            let (a, b) = if det > 1e-12 {
                (m2 / det, -m1 / det)
            } else {
                (1.0 / m0, 0.0)
            };
            for k in 0..t.len {
                let d = t.index[k] as f32 - g;
                t.weight[k] *= a + b * d;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn taps(kernel: Kernel, g: f32, count: usize, stretch: f32) -> Taps {
        let mut t = Taps::default();
        taps_into(&mut t, kernel, g, count, stretch);
        t
    }

    fn stencil(kernel: Kernel, gx: f32, gy: f32, nx: usize, ny: usize, stretch: f32) -> Stencil {
        let mut s = Stencil::default();
        s.locate(kernel, (gx, gy), (nx, ny), stretch);
        s
    }

    fn moments(kernel: Kernel, g: f32, stretch: f32) -> (f32, f32, f32) {
        let t = taps(kernel, g, 100, stretch);
        let w = &t.weight[..t.len];
        let sum: f32 = w.iter().sum();
        let first: f32 = (0..t.len).map(|k| w[k] * (t.index[k] as f32 - g)).sum();
        let square: f32 = w.iter().map(|w| w * w).sum::<f32>() * stretch;
        (sum, first, square)
    }

    /// The kernel four points at a time is the kernel one at a time, to the bit: both
    /// pieces, their edges at ½ and 3/2 and just either side, past the support, at ±0,
    /// NaN and ±∞.
    #[test]
    fn the_kernel_four_at_a_time_is_the_kernel_alone() {
        let mut points: Vec<f32> = (0..4000).map(|k| (k as f32 - 2000.0) / 1111.0).collect();
        for edge in [0.5f32, 1.5] {
            for r in [edge, edge.next_down(), edge.next_up()] {
                points.extend([r, -r]);
            }
        }
        points.extend([
            0.0,
            -0.0,
            f32::NAN,
            f32::INFINITY,
            -f32::INFINITY,
            1.0 / 3.0,
        ]);
        for four in points.chunks(4) {
            let r: [f32; 4] = std::array::from_fn(|k| four.get(k).copied().unwrap_or(0.7));
            let at_once = roma4(r);
            for k in 0..4 {
                assert_eq!(at_once[k].to_bits(), roma(r[k]).to_bits(), "at {}", r[k]);
            }
        }
    }

    #[test]
    fn weights_sum_to_one_and_keep_the_centre() {
        for (kernel, stretch) in [
            (Kernel::Bilinear, 1.0),
            (Kernel::Roma3, 1.0),
            (Kernel::Roma3, 1.5),
            (Kernel::Roma3, 2.0),
        ] {
            for k in 0..40 {
                let g = 50.0 + k as f32 / 40.0;
                let (sum, first, _) = moments(kernel, g, stretch);
                assert!(
                    (sum - 1.0).abs() < 1e-6,
                    "{kernel:?}×{stretch} at {g}: sum {sum}"
                );
                assert!(
                    first.abs() < 1e-5,
                    "{kernel:?}×{stretch} at {g}: first moment {first}"
                );
            }
        }
    }

    #[test]
    fn the_three_point_kernel_barely_sees_the_grid() {
        // Σ w² measures how sharply a point couples to the faces; it should not depend on
        // where the point sits in a cell, at the kernel's own width or stretched.
        let spread = |kernel, stretch| {
            let values: Vec<f32> = (0..40)
                .map(|k| moments(kernel, 50.0 + k as f32 / 40.0, stretch).2)
                .collect();
            let max = values.iter().copied().fold(f32::MIN, f32::max);
            let min = values.iter().copied().fold(f32::MAX, f32::min);
            (max - min) / max
        };
        assert!(spread(Kernel::Roma3, 1.0) < 1e-5);
        assert!(spread(Kernel::Roma3, 2.0) < 1e-5);
        for stretch in [1.1, 1.25, 1.5, 2.7] {
            let s = spread(Kernel::Roma3, stretch);
            assert!(s < 0.04, "three-point ×{stretch}: {s}");
        }
        assert!(spread(Kernel::Bilinear, 1.0) > 0.4);
    }

    #[test]
    fn bounds_by_truncation_are_the_library_floor_and_ceiling() {
        // Every quarter and a few ulps either side of each integer, as a kernel's bounds
        // meet them (a point on a face, a whole stretch).
        for k in -40..=400 {
            let x = k as f32 / 4.0;
            for x in [x, x.next_up(), x.next_down()] {
                assert_eq!(ceil_in_range(x), x.ceil(), "ceil {x}");
                if x >= 0.0 {
                    assert_eq!(floor_non_negative(x), x.floor(), "floor {x}");
                }
            }
        }
    }

    #[test]
    fn sampling_and_spreading_are_adjoint() {
        // ⟨spread(f), field⟩ = f·sample(field) for any field: what the body reads from the
        // water is what it gives back, face for face.
        let field: Vec<f32> = (0..40 * 40)
            .map(|i| ((i * 37) % 101) as f32 / 50.0 - 1.0)
            .collect();
        let scale = vec![1.0; 40];
        for (g, stretch) in [(7.3, 1.0), (12.5, 1.2), (20.01, 1.5), (0.2, 2.0)] {
            let s = stencil(Kernel::Roma3, g, g + 3.7, 40, 40, stretch);
            let mut spread = vec![0.0f32; field.len()];
            s.spread(2.5, &scale, &mut spread);
            let inner: f32 = spread.iter().zip(&field).map(|(a, b)| a * b).sum();
            let read = 2.5 * s.sample(&field);
            assert!((inner - read).abs() < 1e-5, "{g}: {inner} against {read}");
        }
    }

    /// The overlap of two stencils is what one samples of a unit value spread through the
    /// other, straight or mirrored, at folded ends, with a scale varying across, and zero
    /// where they do not meet.
    #[test]
    fn an_overlap_is_a_spread_sampled() {
        let n = 30;
        let scale: Vec<f32> = (0..n).map(|c| 1.0 + 0.1 * c as f32).collect();
        let mirror = |c: usize| (21usize).checked_sub(c).filter(|&m| m < n);
        for (a, b, stretch) in [
            ((7.3, 9.1), (8.0, 9.6), 1.0),
            ((10.2, 0.3), (9.6, 1.1), 1.4),
            ((0.2, 12.0), (1.1, 12.4), 1.0),
            ((10.2, 5.0), (11.0, 5.0), 2.0),
            ((3.0, 3.0), (20.0, 20.0), 1.0),
        ] {
            let (sa, sb) = (
                stencil(Kernel::Roma3, a.0, a.1, n, n, stretch),
                stencil(Kernel::Roma3, b.0, b.1, n, n, stretch),
            );
            let mut field = vec![0.0f32; n * n];
            sa.spread(1.0, &scale, &mut field);
            let straight = sb.sample(&field);
            let mut field = vec![0.0f32; n * n];
            sa.spread_mirrored(1.0, &scale, &mut field, mirror);
            let mirrored = sb.sample(&field);
            let (got, got_mirrored) = (
                sb.overlap(&sa, &scale),
                sb.overlap_mirrored(&sa, &scale, mirror),
            );
            assert!(
                (got - straight).abs() < 1e-6,
                "{a:?} {b:?}: {got} vs {straight}"
            );
            assert!(
                (got_mirrored - mirrored).abs() < 1e-6,
                "{a:?} {b:?} mirrored: {got_mirrored} vs {mirrored}"
            );
        }
        let far = stencil(Kernel::Roma3, 3.0, 3.0, n, n, 1.0);
        let other = stencil(Kernel::Roma3, 20.0, 20.0, n, n, 1.0);
        assert_eq!(far.overlap(&other, &scale), 0.0);
    }

    #[test]
    fn no_face_lies_beyond_the_reach() {
        for (kernel, stretch) in [
            (Kernel::Bilinear, 1.0),
            (Kernel::Roma3, 1.0),
            (Kernel::Roma3, 1.43),
            (Kernel::Roma3, 2.0),
            (Kernel::Roma3, 9.0),
        ] {
            for k in 0..97 {
                let g = 40.0 + k as f32 / 32.0;
                let s = stencil(kernel, g, g, 100, 100, stretch);
                let far = s
                    .iter()
                    .map(|(face, _)| (face % 100) as f32 - g)
                    .fold(0.0f32, |m, d| m.max(d.abs()));
                let reach = reach(kernel, stretch);
                assert!(far <= reach, "{kernel:?}×{stretch} at {g}: {far} > {reach}");
            }
        }
    }

    #[test]
    fn ends_fold_back_into_the_array() {
        for stretch in [1.0, 2.5, 10.0] {
            for g in [-3.0, 0.0, 0.2, 98.8, 99.0, 150.0, f32::NAN] {
                let s = stencil(Kernel::Roma3, g, g, 100, 100, stretch);
                let sum: f32 = s.iter().map(|(_, w)| w).sum();
                assert!((sum - 1.0).abs() < 1e-5, "{g}: {sum}");
                assert!(s.iter().all(|(i, _)| i < 100 * 100));
            }
        }
    }
}
