//! Samplers of a staggered field at a fractional position: bilinear, bilinear with the
//! range of its corners (for MacCormack's limiter), and limited Catmull–Rom bicubic.

/// Bilinear sample of `field` (`nx × ny`) at `(x, y)`.
#[inline(always)]
pub(super) fn linear_sample(field: &[f32], nx: usize, ny: usize, x: f32, y: f32) -> f32 {
    let [a0, a1, b0, b1, fx, fy] = corners(field, nx, ny, x, y);
    let a = a0 + fx * (a1 - a0);
    let b = b0 + fx * (b1 - b0);
    a + fy * (b - a)
}

/// Catmull–Rom bicubic sample of `field` (`nx × ny`) at `(x, y)`, limited to the range of
/// the four nearest values so that it adds no new extrema (Fedkiw et al. 2001). Its error
/// is fourth order where bilinear's is second: the numerical viscosity that smears a bell
/// ten cells wide falls by an order of magnitude.
#[inline]
pub(super) fn cubic_sample(field: &[f32], nx: usize, ny: usize, x: f32, y: f32) -> f32 {
    let (i, j, fx, fy) = locate(nx, ny, x, y);
    let (wx, wy) = (catmull_rom(fx), catmull_rom(fy));
    let rows = sixteen(field, nx, ny, i, j);
    let mut value = 0.0;
    for (r, w) in rows.iter().zip(&wy) {
        value += w * (wx[0] * r[0] + wx[1] * r[1] + wx[2] * r[2] + wx[3] * r[3]);
    }
    limited(value, rows)
}

/// [`cubic_sample`] at four points at once: the same operations in the same order, lane
/// by lane, so the same bits, laid out so that the arithmetic compiles to four-wide
/// vector instructions.
#[inline]
pub(super) fn cubic_sample4(
    field: &[f32],
    nx: usize,
    ny: usize,
    x: [f32; 4],
    y: [f32; 4],
) -> [f32; 4] {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: SSE2 is in every x86-64 target's baseline, so it is always enabled.
        if let Some(inside) = unsafe { sse2::cubic_sample4(field, nx, ny, x, y) } {
            return inside;
        }
    }
    let (mut fx, mut fy) = ([0.0; 4], [0.0; 4]);
    // values[row][column][lane]
    let mut values = [[[0.0f32; 4]; 4]; 4];
    for (lane, (i, j, tx, ty)) in locate4(nx, ny, x, y).into_iter().enumerate() {
        (fx[lane], fy[lane]) = (tx, ty);
        for (b, row) in sixteen(field, nx, ny, i, j).iter().enumerate() {
            for (a, &v) in row.iter().enumerate() {
                values[b][a][lane] = v;
            }
        }
    }
    // weights[column or row][lane]
    let weights = |t: [f32; 4]| -> [[f32; 4]; 4] {
        let mut w = [[0.0; 4]; 4];
        for lane in 0..4 {
            let [w0, w1, w2, w3] = catmull_rom(t[lane]);
            (w[0][lane], w[1][lane], w[2][lane], w[3][lane]) = (w0, w1, w2, w3);
        }
        w
    };
    let (wx, wy) = (weights(fx), weights(fy));
    let mut value = [0.0f32; 4];
    for (r, w) in values.iter().zip(&wy) {
        for lane in 0..4 {
            value[lane] += w[lane]
                * (wx[0][lane] * r[0][lane]
                    + wx[1][lane] * r[1][lane]
                    + wx[2][lane] * r[2][lane]
                    + wx[3][lane] * r[3][lane]);
        }
    }
    let (a, b) = (&values[1], &values[2]);
    four(|lane| {
        within(
            value[lane],
            [a[1][lane], a[2][lane], b[1][lane], b[2][lane]],
        )
    })
}

/// [`linear_sample`] at four points at once: the same operations in the same order, lane
/// by lane, so the same bits. All but the sixteen loads are four-wide SSE2 instructions
/// on x86-64 (where the plain loop spent most of its time converting and clamping one
/// coordinate at a time); elsewhere, four single samples.
#[inline]
pub(super) fn linear_sample4(
    field: &[f32],
    nx: usize,
    ny: usize,
    x: [f32; 4],
    y: [f32; 4],
) -> [f32; 4] {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: SSE2 is in every x86-64 target's baseline, so it is always enabled.
        unsafe { sse2::linear_sample4(field, nx, ny, x, y) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        std::array::from_fn(|lane| linear_sample(field, nx, ny, x[lane], y[lane]))
    }
}

/// [`locate`] at four points at once: the same cells and fractions, lane by lane.
#[inline]
fn locate4(nx: usize, ny: usize, x: [f32; 4], y: [f32; 4]) -> [(usize, usize, f32, f32); 4] {
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: SSE2 is in every x86-64 target's baseline, so it is always enabled.
        unsafe { sse2::locate4(nx, ny, x, y) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        std::array::from_fn(|lane| locate(nx, ny, x[lane], y[lane]))
    }
}

#[cfg(target_arch = "x86_64")]
mod sse2 {
    use std::arch::x86_64::*;

    /// See [`super::linear_sample4`]; each step is the scalar one's, lane by lane.
    #[target_feature(enable = "sse2")]
    #[inline]
    pub(super) fn linear_sample4(
        field: &[f32],
        nx: usize,
        ny: usize,
        x: [f32; 4],
        y: [f32; 4],
    ) -> [f32; 4] {
        let [i, j, fx, fy] = located(nx, ny, x, y);
        // Whole numbers below 2²⁴: exact in f32.
        let start = _mm_cvttps_epi32(_mm_add_ps(_mm_mul_ps(j, _mm_set1_ps(nx as f32)), i));
        let start = [
            _mm_cvtsi128_si32(start),
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b01_01_01_01>(start)),
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b10_10_10_10>(start)),
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b11_11_11_11>(start)),
        ];
        // corners[corner][lane]: the lower row's two, then the upper row's.
        let mut corners = [[0.0f32; 4]; 4];
        for (lane, k) in start.into_iter().enumerate() {
            let cell = &field[k as u32 as usize..][..nx + 2];
            corners[0][lane] = cell[0];
            corners[1][lane] = cell[1];
            corners[2][lane] = cell[nx];
            corners[3][lane] = cell[nx + 1];
        }
        let (a0, a1) = (vector(corners[0]), vector(corners[1]));
        let (b0, b1) = (vector(corners[2]), vector(corners[3]));
        let a = _mm_add_ps(a0, _mm_mul_ps(fx, _mm_sub_ps(a1, a0)));
        let b = _mm_add_ps(b0, _mm_mul_ps(fx, _mm_sub_ps(b1, b0)));
        lanes(_mm_add_ps(a, _mm_mul_ps(fy, _mm_sub_ps(b, a))))
    }

    /// See [`super::cubic_sample4`]; `None` unless all four points are a cell inside the
    /// field. Each lane's four rows of four load as vectors and transpose in registers
    /// (gathered one value at a time through memory, each vector stalled on its four
    /// stores); the arithmetic is the scalar one's, lane by lane.
    #[target_feature(enable = "sse2")]
    #[inline]
    pub(super) fn cubic_sample4(
        field: &[f32],
        nx: usize,
        ny: usize,
        x: [f32; 4],
        y: [f32; 4],
    ) -> Option<[f32; 4]> {
        let located = locate4(nx, ny, x, y);
        let inside =
            |&(i, j, _, _): &(usize, usize, f32, f32)| i >= 1 && i + 2 < nx && j >= 1 && j + 2 < ny;
        if !located.iter().all(inside) {
            return None;
        }
        // Each lane's sixteen values: four runs of four, one bounds check.
        let blocks = super::four(|lane| {
            let (i, j, _, _) = located[lane];
            &field[(j - 1) * nx + i - 1..][..3 * nx + 4]
        });
        let row = |lane: usize, b: usize| {
            let r = &blocks[lane][b * nx..][..4];
            // SAFETY: `r` holds the four values read.
            unsafe { _mm_loadu_ps(r.as_ptr()) }
        };
        let wx = catmull_rom(vector(super::four(|lane| located[lane].2)));
        let wy = catmull_rom(vector(super::four(|lane| located[lane].3)));
        let mut value = _mm_setzero_ps();
        // middle[row][column][lane]: the four nearest values, for the limiter.
        let mut middle = [[[0.0f32; 4]; 2]; 2];
        for (b, w) in wy.into_iter().enumerate() {
            let [c0, c1, c2, c3] = transpose([row(0, b), row(1, b), row(2, b), row(3, b)]);
            let sum = _mm_add_ps(_mm_mul_ps(wx[0], c0), _mm_mul_ps(wx[1], c1));
            let sum = _mm_add_ps(sum, _mm_mul_ps(wx[2], c2));
            let sum = _mm_add_ps(sum, _mm_mul_ps(wx[3], c3));
            value = _mm_add_ps(value, _mm_mul_ps(w, sum));
            if b == 1 || b == 2 {
                middle[b - 1] = [lanes(c1), lanes(c2)];
            }
        }
        let value = lanes(value);
        let [[below_0, below_1], [above_0, above_1]] = middle;
        Some(super::four(|lane| {
            let nearest = [below_0[lane], below_1[lane], above_0[lane], above_1[lane]];
            super::within(value[lane], nearest)
        }))
    }

    /// `super::catmull_rom` of four fractions: each weight's operations in its order.
    #[target_feature(enable = "sse2")]
    #[inline]
    fn catmull_rom(t: __m128) -> [__m128; 4] {
        let k = _mm_set1_ps;
        let (t2, t3) = (_mm_mul_ps(t, t), _mm_mul_ps(_mm_mul_ps(t, t), t));
        // −a + b is b − a, and (−3)·a is −(3·a), bit for bit.
        let w0 = _mm_sub_ps(_mm_sub_ps(_mm_mul_ps(k(2.0), t2), t3), t);
        let w1 = _mm_add_ps(
            _mm_sub_ps(_mm_mul_ps(k(3.0), t3), _mm_mul_ps(k(5.0), t2)),
            k(2.0),
        );
        let w2 = _mm_add_ps(
            _mm_sub_ps(_mm_mul_ps(k(4.0), t2), _mm_mul_ps(k(3.0), t3)),
            t,
        );
        let w3 = _mm_sub_ps(t3, t2);
        let half = k(0.5);
        [
            _mm_mul_ps(half, w0),
            _mm_mul_ps(half, w1),
            _mm_mul_ps(half, w2),
            _mm_mul_ps(half, w3),
        ]
    }

    /// Rows to columns: `[lane][column]` to `[column][lane]`.
    #[target_feature(enable = "sse2")]
    #[inline]
    fn transpose([r0, r1, r2, r3]: [__m128; 4]) -> [__m128; 4] {
        let (t0, t1) = (_mm_unpacklo_ps(r0, r1), _mm_unpacklo_ps(r2, r3));
        let (t2, t3) = (_mm_unpackhi_ps(r0, r1), _mm_unpackhi_ps(r2, r3));
        [
            _mm_movelh_ps(t0, t1),
            _mm_movehl_ps(t1, t0),
            _mm_movelh_ps(t2, t3),
            _mm_movehl_ps(t3, t2),
        ]
    }

    /// See [`super::locate4`].
    #[target_feature(enable = "sse2")]
    #[inline]
    pub(super) fn locate4(
        nx: usize,
        ny: usize,
        x: [f32; 4],
        y: [f32; 4],
    ) -> [(usize, usize, f32, f32); 4] {
        let [i, j, fx, fy] = located(nx, ny, x, y);
        let [i, j, fx, fy] = [lanes(i), lanes(j), lanes(fx), lanes(fy)];
        super::four(|lane| {
            // Whole numbers from 0 to the last but one: exact conversions.
            let whole = |v: f32| v as u32 as usize;
            (whole(i[lane]), whole(j[lane]), fx[lane], fy[lane])
        })
    }

    /// `locate` of four points: their cells (as floats) and the fractions past them.
    #[target_feature(enable = "sse2")]
    #[inline]
    fn located(nx: usize, ny: usize, x: [f32; 4], y: [f32; 4]) -> [__m128; 4] {
        let (x, y) = (clamp(vector(x), nx), clamp(vector(y), ny));
        let (i, j) = (corner(x, nx), corner(y, ny));
        [i, j, _mm_sub_ps(x, i), _mm_sub_ps(y, j)]
    }

    /// `locate`'s clamp to `[0, top − 1]`: f32::clamp's two comparisons in its order
    /// (`max(a, b)` is `a > b ? a : b`), so NaN passes through.
    #[target_feature(enable = "sse2")]
    #[inline]
    fn clamp(t: __m128, top: usize) -> __m128 {
        let t = _mm_max_ps(_mm_setzero_ps(), t);
        _mm_min_ps(_mm_set1_ps((top - 1) as f32), t)
    }

    /// `locate`'s cell, as a float: the truncation (NaN as 0, as `as i32` takes it), at
    /// most the last but one.
    #[target_feature(enable = "sse2")]
    #[inline]
    fn corner(t: __m128, top: usize) -> __m128 {
        let finite = _mm_and_ps(t, _mm_cmpord_ps(t, t));
        let whole = _mm_cvttps_epi32(_mm_min_ps(finite, _mm_set1_ps((top - 2) as f32)));
        _mm_cvtepi32_ps(whole)
    }

    #[target_feature(enable = "sse2")]
    #[inline]
    fn vector(v: [f32; 4]) -> __m128 {
        _mm_setr_ps(v[0], v[1], v[2], v[3])
    }

    #[target_feature(enable = "sse2")]
    #[inline]
    fn lanes(v: __m128) -> [f32; 4] {
        [
            _mm_cvtss_f32(v),
            _mm_cvtss_f32(_mm_shuffle_ps::<0b01_01_01_01>(v, v)),
            _mm_cvtss_f32(_mm_shuffle_ps::<0b10_10_10_10>(v, v)),
            _mm_cvtss_f32(_mm_shuffle_ps::<0b11_11_11_11>(v, v)),
        ]
    }
}

/// `[f(0), f(1), f(2), f(3)]`, written out: `std::array::from_fn` and `[T; 4]::map` left
/// each lane a call through its closure in the samplers' hot loops (a twentieth of a
/// step's instructions), where these inline into four-wide arithmetic.
#[inline(always)]
pub(super) fn four<T>(f: impl Fn(usize) -> T) -> [T; 4] {
    [f(0), f(1), f(2), f(3)]
}

/// The four by four values around cell `(i, j)` (from `i - 1, j - 1`), clamped to the
/// field at its edges.
#[inline(always)]
fn sixteen(field: &[f32], nx: usize, ny: usize, i: usize, j: usize) -> [[f32; 4]; 4] {
    if i >= 1 && i + 2 < nx && j >= 1 && j + 2 < ny {
        // Inside: four runs of four, one bounds check for the sixteen.
        // Row by row, written out: through a closure each row was a call.
        let block = &field[(j - 1) * nx + i - 1..][..3 * nx + 4];
        let (r0, r1) = (&block[..4], &block[nx..][..4]);
        let (r2, r3) = (&block[2 * nx..][..4], &block[3 * nx..][..4]);
        [
            [r0[0], r0[1], r0[2], r0[3]],
            [r1[0], r1[1], r1[2], r1[3]],
            [r2[0], r2[1], r2[2], r2[3]],
            [r3[0], r3[1], r3[2], r3[3]],
        ]
    } else {
        let cols = four(|d| (i + d).saturating_sub(1).min(nx - 1));
        let row = |b: usize| &field[(j + b).saturating_sub(1).min(ny - 1) * nx..][..nx];
        let (r0, r1, r2, r3) = (row(0), row(1), row(2), row(3));
        let [c0, c1, c2, c3] = cols;
        [
            [r0[c0], r0[c1], r0[c2], r0[c3]],
            [r1[c0], r1[c1], r1[c2], r1[c3]],
            [r2[c0], r2[c1], r2[c2], r2[c3]],
            [r3[c0], r3[c1], r3[c2], r3[c3]],
        ]
    }
}

/// `value` limited to the range of the four nearest of the sixteen: the middle four
/// (`locate` keeps i + 1 and j + 1 inside the field, so none of them is clamped).
#[inline(always)]
fn limited(value: f32, rows: [[f32; 4]; 4]) -> f32 {
    within(value, [rows[1][1], rows[1][2], rows[2][1], rows[2][2]])
}

/// `value` limited to the range of `nearest`, the four values around the point.
#[inline(always)]
pub(super) fn within(value: f32, [a0, a1, b0, b1]: [f32; 4]) -> f32 {
    let lo = least(least(least(a0, a1), b0), b1);
    let hi = greatest(greatest(greatest(a0, a1), b0), b1);
    // Not clamp: NaN must reach the health check, not panic.
    least(greatest(value, lo), hi)
}

/// The lesser of `a` and `b`: `b` where `a` is NaN, and `a` where neither is less (so
/// `a` of a −0 and a +0, which `f32::min` leaves to the platform). One `minps` and a
/// blend, so that eight lanes at once give these bits.
#[inline(always)]
pub(super) fn least(a: f32, b: f32) -> f32 {
    if a.is_nan() || b < a { b } else { a }
}

/// The greater of `a` and `b`, as [`least`]: `b` where `a` is NaN, `a` where neither is
/// greater.
#[inline(always)]
pub(super) fn greatest(a: f32, b: f32) -> f32 {
    if a.is_nan() || b > a { b } else { a }
}

/// The Catmull–Rom weights of the four values around a point a fraction `t` past the
/// second.
#[inline(always)]
fn catmull_rom(t: f32) -> [f32; 4] {
    let (t2, t3) = (t * t, t * t * t);
    [
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    ]
}

/// A grid index as a coordinate (through u32: one instruction, where usize takes a branch).
#[inline(always)]
pub(super) fn cell(i: usize) -> f32 {
    i as u32 as f32
}

/// Writes the sample of `field` at `(x, y)` to `out[k]`, and its corners' range to
/// `bounds[k]` when asked.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn trace(
    field: &[f32],
    nx: usize,
    ny: usize,
    x: f32,
    y: f32,
    k: usize,
    out: &mut [f32],
    bounds: Option<&mut [(f32, f32)]>,
) {
    let [a0, a1, b0, b1, fx, fy] = corners(field, nx, ny, x, y);
    let a = a0 + fx * (a1 - a0);
    let b = b0 + fx * (b1 - b0);
    out[k] = a + fy * (b - a);
    if let Some(bounds) = bounds {
        // Plain comparisons (one instruction each, unlike NaN-aware f32::min); the
        // correction's max-then-min copes with NaN bounds.
        let (lo, hi) = (
            |a: f32, b: f32| if a < b { a } else { b },
            |a: f32, b: f32| if a > b { a } else { b },
        );
        bounds[k] = (lo(lo(a0, a1), lo(b0, b1)), hi(hi(a0, a1), hi(b0, b1)));
    }
}

/// The four values around `(x, y)` (lower row, then upper) and the fractions between them.
/// (Always inlined: left as a call in the advection's sweep, it cost a few percent of the
/// bilinear step's rows' ends.)
#[inline(always)]
fn corners(field: &[f32], nx: usize, ny: usize, x: f32, y: f32) -> [f32; 6] {
    let (i, j, fx, fy) = locate(nx, ny, x, y);
    // One bounds check for all four corners.
    let cell = &field[j * nx + i..][..nx + 2];
    [cell[0], cell[1], cell[nx], cell[nx + 1], fx, fy]
}

/// The lower-left corner and the fractions of a point `(x, y)` (fractional indices) in an
/// `nx × ny` array, clamped to the edges: zero normal gradient, free slip for the
/// tangential component.
#[inline]
fn locate(nx: usize, ny: usize, x: f32, y: f32) -> (usize, usize, f32, f32) {
    let x = x.clamp(0.0, (nx - 1) as f32);
    let y = y.clamp(0.0, (ny - 1) as f32);
    // Non-negative after the clamp, so truncation is floor (and NaN becomes 0); through
    // i32 and u32, the conversions are single instructions.
    let i = (x as i32 as usize).min(nx - 2);
    let j = (y as i32 as usize).min(ny - 2);
    (i, j, x - cell(i), y - cell(j))
}

#[cfg(test)]
mod tests {
    use super::*;

    type Four = fn(&[f32], usize, usize, [f32; 4], [f32; 4]) -> [f32; 4];
    type One = fn(&[f32], usize, usize, f32, f32) -> f32;

    /// Asserts that `four` samples what `one` samples four times, bit for bit: at 2000
    /// points inside, at and past every edge, over a field with a NaN, and at points that
    /// are not finite or are −0 (NaN must reach the health check as NaN). Returns how
    /// many points it compared.
    fn four_at_once_are_four_single_ones(four: Four, one: One) -> usize {
        let (nx, ny) = (9, 7);
        let mut field: Vec<f32> = (0..nx * ny)
            .map(|k| ((k * 7919) % 101) as f32 / 13.0 - 3.5)
            .collect();
        field[20] = f32::NAN;
        let mut state = 12345u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        };
        let mut compared = 0;
        let mut same = |x: [f32; 4], y: [f32; 4]| {
            let at_once = four(&field, nx, ny, x, y);
            for lane in 0..4 {
                let single = one(&field, nx, ny, x[lane], y[lane]);
                assert_eq!(
                    at_once[lane].to_bits(),
                    single.to_bits(),
                    "at ({}, {}): {} against {single}",
                    x[lane],
                    y[lane],
                    at_once[lane]
                );
                compared += 1;
            }
        };
        for _ in 0..500 {
            let x: [f32; 4] = std::array::from_fn(|_| next() * (nx as f32 + 4.0) - 2.0);
            let y: [f32; 4] = std::array::from_fn(|_| next() * (ny as f32 + 4.0) - 2.0);
            same(x, y);
        }
        let odd = [f32::NAN, f32::INFINITY, -f32::INFINITY, -0.0];
        same(odd, [1.5; 4]);
        same([2.5; 4], odd);
        let edges = [(nx - 1) as f32, (nx - 2) as f32, 0.0, 7.999_999];
        same(edges, [(ny - 1) as f32; 4]);
        compared
    }

    /// The limiter's `least` and `greatest` are `f32::min` and `max` (the other where one
    /// is NaN), and keep their first operand at a tie of zeros, whatever the platform does.
    #[test]
    fn least_and_greatest_are_min_and_max_with_ties_fixed() {
        let values = [
            -2.5,
            -0.0,
            0.0,
            1.0,
            f32::INFINITY,
            -f32::INFINITY,
            f32::NAN,
        ];
        for a in values {
            for b in values {
                let (lo, hi) = (least(a, b), greatest(a, b));
                if a == b {
                    assert_eq!((lo.to_bits(), hi.to_bits()), (a.to_bits(), a.to_bits()));
                } else {
                    assert_eq!(lo.to_bits(), a.min(b).to_bits(), "least({a}, {b})");
                    assert_eq!(hi.to_bits(), a.max(b).to_bits(), "greatest({a}, {b})");
                }
            }
        }
        assert_eq!(
            within(-0.0, [0.0; 4]).to_bits(),
            (-0.0f32).to_bits(),
            "a tie keeps the value"
        );
        assert_eq!(within(f32::NAN, [1.0, 2.0, 3.0, 4.0]), 1.0);
    }

    #[test]
    fn four_bilinear_samples_at_once_are_four_single_ones() {
        let compared = four_at_once_are_four_single_ones(linear_sample4, linear_sample);
        assert_eq!(compared, 2012);
    }

    #[test]
    fn four_bicubic_samples_at_once_are_four_single_ones() {
        let compared = four_at_once_are_four_single_ones(cubic_sample4, cubic_sample);
        assert_eq!(compared, 2012);
    }
}
