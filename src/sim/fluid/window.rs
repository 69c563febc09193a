//! Samples eight at a time where every foot lies within a cell of its own face.
//!
//! The fixed step keeps nearly every trace that short (Courant 0.5 at the jet's expected
//! speed, `Species::steps_per_cycle`), so the values around each foot are among the faces
//! of a few rows around its own row, each a column or two before or after its own: three
//! rows and three shifted loads of eight for bilinear, five and five for bicubic. Every
//! value is then chosen lane by lane (or, where all eight feet lie on the same side of
//! their faces, loaded as one shift), where the general samplers gather them one at a
//! time. The cells, the fractions and the arithmetic are `sampling`'s, so the samples are
//! its bits. x86-64 with AVX only (asked at run time): elsewhere, and for any eight of
//! which one foot lies further out, the four-wide samplers.

#[cfg(target_arch = "x86_64")]
pub(super) mod avx {
    use std::arch::x86_64::*;

    /// Whether this processor runs [`trace_row`] (std caches the answer).
    pub(in crate::sim::fluid) fn available() -> bool {
        std::arch::is_x86_feature_detected!("avx")
    }

    /// What carries one row of faces back to their feet: each face's own component, and
    /// the other one averaged from the four faces around it in the rows either side, as
    /// `advection::sweep` reads them.
    #[derive(Clone, Copy)]
    pub(in crate::sim::fluid) enum Carried<'a> {
        /// A row of u faces: its u, and the v rows below and above it (face `i` averages
        /// their columns `i − 1` and `i`).
        U { u: &'a [f32], v: [&'a [f32]; 2] },
        /// A row of v faces: its v, and the u rows below and above it (columns `i` and
        /// `i + 1`).
        V { v: &'a [f32], u: [&'a [f32]; 2] },
    }

    /// Samples `field` (`[nx, ny]`) at the feet of the faces `faces` of row `j`, traced
    /// back `s` cells per unit velocity of `carried`, into `out`: each foot as
    /// `advection::sweep` traces it, each sample as `sampling::linear_sample` (or, with
    /// `CUBIC`, `sampling::cubic_sample`) takes it, one at a time. Eight at a time from a
    /// window of the rows around them where each of the eight lies at most a cell before
    /// its face (on either axis) and less than one after, and the window lies where those
    /// samplers' clamps do not reach; four at a time by the general sampler where not.
    /// The last eight end the row, overlapping the eight before where the count is not a
    /// multiple of eight (those faces get the same values again). At least eight faces.
    /// A row whose window reaches past the field's first or last row takes its window
    /// from `edge`, the rows `j − reach` to `j + reach` each clamped to the field (what the
    /// samplers' clamps read there), for the eights whose feet all lie within the field's
    /// rows (`0 ≤ y < ny − 1`, where the samplers clamp nothing themselves).
    /// Returns how many eights the window took, and how many of those were one shift of
    /// it (every foot on the same side of its face on each axis).
    #[target_feature(enable = "avx")]
    #[allow(clippy::too_many_arguments)]
    pub(in crate::sim::fluid) fn trace_row<const CUBIC: bool>(
        field: &[f32],
        [nx, ny]: [usize; 2],
        j: usize,
        faces: std::ops::Range<usize>,
        carried: Carried,
        s: f32,
        edge: Option<&[f32]>,
        out: &mut [f32],
    ) -> [usize; 2] {
        use crate::sim::fluid::sampling::{cubic_sample4, linear_sample4};
        // Rows and columns the window reaches either side of a face: a foot's cell is its
        // face's or the one before, and bicubic reads one more on each side of it.
        let reach = if CUBIC { 2 } else { 1 };
        // The window's rows (`j − reach` to `j + reach`): the field's own if the samplers'
        // clamps to the field do not reach them (`locate` keeps a cell below the last but
        // one), else `edge`'s, for feet within the field's rows. `rows` holds them from
        // its row `first` on.
        let inside_rows = j >= reach && j + reach < ny;
        // (`advection` hands bicubic rows only: the bilinear loop is built without it.)
        let edge = if CUBIC { edge } else { None };
        let (rows, first, inside_rows, within_rows) = match edge {
            Some(edge) if !inside_rows => {
                assert!(edge.len() >= (2 * reach + 1) * nx);
                (edge, 0, true, true)
            }
            _ => (field, j.saturating_sub(reach), inside_rows, false),
        };
        // Where a foot may lie on the field's rows for `edge`'s window.
        let (lowest, below_last) = (_mm256_setzero_ps(), _mm256_set1_ps((ny - 1) as f32));
        // Every load below lies within these bounds, checked once a row rather than at
        // each of a window's forty loads: the carried rows hold the faces and the four
        // around each (a u face's v columns `i − 1` and `i`, a v face's u columns `i` and
        // `i + 1`), and the field holds its rows.
        match carried {
            Carried::U { u, v } => assert!(
                faces.start >= 1 && faces.end <= u.len() && v.iter().all(|v| faces.end <= v.len())
            ),
            Carried::V { v, u } => {
                assert!(faces.end <= v.len() && u.iter().all(|u| faces.end < u.len()))
            }
        }
        assert!(faces.len() >= 8 && field.len() >= nx * ny);
        // Macros, not closures: the compiler left closures here as calls.
        macro_rules! load {
            // Eight values of `$v` from `$at` on.
            ($v:expr, $at:expr) => {{
                let (v, at): (&[f32], usize) = (&$v, $at);
                debug_assert!(at + 8 <= v.len());
                // SAFETY: within the bounds asserted above (and in debug builds here).
                unsafe { _mm256_loadu_ps(v.as_ptr().add(at)) }
            }};
        }
        // ((a + a′) + b) + b′ of the four faces around each, from column `k` on.
        macro_rules! around {
            ($rows:expr, $k:expr) => {{
                let ([a, b], k) = ($rows, $k);
                let sum = _mm256_add_ps(load!(a, k), load!(a, k + 1));
                _mm256_add_ps(_mm256_add_ps(sum, load!(b, k)), load!(b, k + 1))
            }};
        }
        let (step, quarter) = (_mm256_set1_ps(s), _mm256_set1_ps(s * 0.25));
        let one = _mm256_set1_ps(1.0);
        // Whole numbers below 2²⁴: exact, and so are they plus or minus one.
        let home_y = _mm256_set1_ps(j as u32 as f32);
        let (before_y, after_y) = (_mm256_sub_ps(home_y, one), _mm256_add_ps(home_y, one));
        let lane = _mm256_setr_ps(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0);
        let (mut taken, mut shifts) = (0, 0);
        let mut i = faces.start;
        loop {
            let at = i.min(faces.end - 8);
            let home_x = _mm256_add_ps(_mm256_set1_ps(at as u32 as f32), lane);
            // Each foot: its face less the step times the velocity there.
            let (x, y) = match carried {
                Carried::U { u, v } => (
                    _mm256_sub_ps(home_x, _mm256_mul_ps(step, load!(u, at))),
                    _mm256_sub_ps(home_y, _mm256_mul_ps(quarter, around!(v, at - 1))),
                ),
                Carried::V { v, u } => (
                    _mm256_sub_ps(home_x, _mm256_mul_ps(quarter, around!(u, at))),
                    _mm256_sub_ps(home_y, _mm256_mul_ps(step, load!(v, at))),
                ),
            };
            let (before_x, after_x) = (_mm256_sub_ps(home_x, one), _mm256_add_ps(home_x, one));
            // Within reach on both axes (NaN compares false).
            let mut near = _mm256_and_ps(
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GE_OQ>(x, before_x),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(x, after_x),
                ),
                _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GE_OQ>(y, before_y),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(y, after_y),
                ),
            );
            if within_rows {
                let on_rows = _mm256_and_ps(
                    _mm256_cmp_ps::<_CMP_GE_OQ>(y, lowest),
                    _mm256_cmp_ps::<_CMP_LT_OQ>(y, below_last),
                );
                near = _mm256_and_ps(near, on_rows);
            }
            let out = &mut out[at..][..8];
            // The window's columns, `at − reach` to `at + 7 + reach`, inside the clamps too.
            let inside = inside_rows && at >= reach && at + 8 + reach <= nx;
            if inside && _mm256_movemask_ps(near) == 0xff {
                // A foot before its face lies in the cell before: its cell, and `locate`'s
                // fraction (the foot less its cell's coordinate).
                let left = _mm256_cmp_ps::<_CMP_LT_OQ>(x, home_x);
                let down = _mm256_cmp_ps::<_CMP_LT_OQ>(y, home_y);
                let fx = _mm256_sub_ps(x, _mm256_blendv_ps(home_x, before_x, left));
                let fy = _mm256_sub_ps(y, _mm256_blendv_ps(home_y, before_y, down));
                // The values around each foot's cell, `values[row][column]` from the
                // cell's `reach − 1` before on: `2·reach` rows of `2·reach`.
                let mut values = [[_mm256_setzero_ps(); 4]; 4];
                let (left_lanes, down_lanes) = (_mm256_movemask_ps(left), _mm256_movemask_ps(down));
                if matches!(left_lanes, 0 | 0xff) && matches!(down_lanes, 0 | 0xff) {
                    shifts += 1;
                    // Every foot on the same side of its face on both axes (as in most of
                    // a smooth flow): the eight cells are one window's shift, loaded as
                    // such, what the blends below choose lane by lane.
                    let w = (first + usize::from(down_lanes == 0)) * nx + at - reach
                        + usize::from(left_lanes == 0);
                    for (b, row) in values.iter_mut().enumerate().take(2 * reach) {
                        for (c, value) in row.iter_mut().enumerate().take(2 * reach) {
                            // `inside`: within the window below.
                            *value = load!(rows, w + b * nx + c);
                        }
                    }
                } else {
                    // The window's rows, `j − reach` on: in each, the columns from the
                    // cell's `reach − 1` before on, two shifted loads a column, one
                    // chosen per lane; then the rows likewise. (Loops, not closures:
                    // those were left as calls.)
                    let mut columns = [[_mm256_setzero_ps(); 4]; 5];
                    for (k, row) in columns.iter_mut().enumerate().take(2 * reach + 1) {
                        // `inside`: these rows and columns lie within `rows`.
                        let w = (first + k) * nx + at - reach;
                        let mut shifted = [_mm256_setzero_ps(); 5];
                        for (o, v) in shifted.iter_mut().enumerate().take(2 * reach + 1) {
                            *v = load!(rows, w + o);
                        }
                        for (c, column) in row.iter_mut().enumerate().take(2 * reach) {
                            *column = _mm256_blendv_ps(shifted[c + 1], shifted[c], left);
                        }
                    }
                    for (b, row) in values.iter_mut().enumerate().take(2 * reach) {
                        for (c, value) in row.iter_mut().enumerate().take(2 * reach) {
                            *value = _mm256_blendv_ps(columns[b + 1][c], columns[b][c], down);
                        }
                    }
                }
                let v = if CUBIC {
                    let (wx, wy) = (catmull_rom(fx), catmull_rom(fy));
                    let mut value = _mm256_setzero_ps();
                    for (r, w) in values.iter().zip(wy) {
                        let sum =
                            _mm256_add_ps(_mm256_mul_ps(wx[0], r[0]), _mm256_mul_ps(wx[1], r[1]));
                        let sum = _mm256_add_ps(sum, _mm256_mul_ps(wx[2], r[2]));
                        let sum = _mm256_add_ps(sum, _mm256_mul_ps(wx[3], r[3]));
                        value = _mm256_add_ps(value, _mm256_mul_ps(w, sum));
                    }
                    // Limited to the four nearest values, as the sampler limits one.
                    let [a0, a1] = [values[1][1], values[1][2]];
                    let [b0, b1] = [values[2][1], values[2][2]];
                    let lo = least(least(least(a0, a1), b0), b1);
                    let hi = greatest(greatest(greatest(a0, a1), b0), b1);
                    least(greatest(value, lo), hi)
                } else {
                    // The cell's row and the one after.
                    let [[a0, a1, ..], [b0, b1, ..], ..] = values;
                    let a = _mm256_add_ps(a0, _mm256_mul_ps(fx, _mm256_sub_ps(a1, a0)));
                    let b = _mm256_add_ps(b0, _mm256_mul_ps(fx, _mm256_sub_ps(b1, b0)));
                    _mm256_add_ps(a, _mm256_mul_ps(fy, _mm256_sub_ps(b, a)))
                };
                // SAFETY: `out` holds eight values.
                unsafe { _mm256_storeu_ps(out.as_mut_ptr(), v) };
                taken += 1;
            } else {
                let (xs, ys) = (lanes(x), lanes(y));
                let half = |v: &[f32]| [v[0], v[1], v[2], v[3]];
                let (x0, y0, x1, y1) = (half(&xs), half(&ys), half(&xs[4..]), half(&ys[4..]));
                if CUBIC {
                    out[..4].copy_from_slice(&cubic_sample4(field, nx, ny, x0, y0));
                    out[4..].copy_from_slice(&cubic_sample4(field, nx, ny, x1, y1));
                } else {
                    out[..4].copy_from_slice(&linear_sample4(field, nx, ny, x0, y0));
                    out[4..].copy_from_slice(&linear_sample4(field, nx, ny, x1, y1));
                }
            }
            if at + 8 == faces.end {
                return [taken, shifts];
            }
            i += 8;
        }
    }

    /// `sampling::catmull_rom` of eight fractions: each weight's operations in its order
    /// (−a + b is b − a, and (−3)·a is −(3·a), bit for bit).
    #[target_feature(enable = "avx")]
    #[inline]
    fn catmull_rom(t: __m256) -> [__m256; 4] {
        let k = _mm256_set1_ps;
        let (t2, t3) = (_mm256_mul_ps(t, t), _mm256_mul_ps(_mm256_mul_ps(t, t), t));
        let w0 = _mm256_sub_ps(_mm256_sub_ps(_mm256_mul_ps(k(2.0), t2), t3), t);
        let w1 = _mm256_add_ps(
            _mm256_sub_ps(_mm256_mul_ps(k(3.0), t3), _mm256_mul_ps(k(5.0), t2)),
            k(2.0),
        );
        let w2 = _mm256_add_ps(
            _mm256_sub_ps(_mm256_mul_ps(k(4.0), t2), _mm256_mul_ps(k(3.0), t3)),
            t,
        );
        let w3 = _mm256_sub_ps(t3, t2);
        let half = k(0.5);
        [
            _mm256_mul_ps(half, w0),
            _mm256_mul_ps(half, w1),
            _mm256_mul_ps(half, w2),
            _mm256_mul_ps(half, w3),
        ]
    }

    /// `sampling::least` of eight lanes: `minps` keeps its second operand unless the
    /// first is less (NaN compares false), and `b` replaces a NaN `a`.
    #[target_feature(enable = "avx")]
    #[inline]
    fn least(a: __m256, b: __m256) -> __m256 {
        let nan = _mm256_cmp_ps::<_CMP_UNORD_Q>(a, a);
        _mm256_blendv_ps(_mm256_min_ps(b, a), b, nan)
    }

    /// `sampling::greatest` of eight lanes, as [`least`].
    #[target_feature(enable = "avx")]
    #[inline]
    fn greatest(a: __m256, b: __m256) -> __m256 {
        let nan = _mm256_cmp_ps::<_CMP_UNORD_Q>(a, a);
        _mm256_blendv_ps(_mm256_max_ps(b, a), b, nan)
    }

    /// The eight lanes of `v`.
    #[target_feature(enable = "avx")]
    #[inline]
    fn lanes(v: __m256) -> [f32; 8] {
        let mut out = [0.0f32; 8];
        // SAFETY: `out` holds eight values.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), v) };
        out
    }

    #[cfg(test)]
    mod tests {
        use super::*;
        use crate::sim::fluid::sampling::{cell, cubic_sample, linear_sample};

        /// Every face of a row, u faces and v faces, lands where `advection::sweep` traces
        /// it one at a time and is sampled as the general sampler samples it alone, to the
        /// bit; and the window takes exactly the eights whose feet all lie within a cell
        /// of their faces away from the field's edges. Velocities put feet on the cells'
        /// edges, just inside and just past the reach, at −0, NaN and ±∞, in rows and
        /// runs of faces at and near every edge of a field too small for the window there.
        fn a_row_eight_at_a_time_is_one_at_a_time<const CUBIC: bool>() {
            let n = 22;
            let reach = if CUBIC { 2 } else { 1 };
            let mut state = 2024u32;
            let mut next = || {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                (state >> 8) as f32 / (1 << 24) as f32
            };
            let below_one = 1.0 - f32::EPSILON / 2.0;
            let odd = [
                -1.0, -below_one, -0.5, -0.0, 0.0, 0.25, below_one, 1.0, -1.01,
            ];
            let (mut taken, mut declined, mut ends_taken, mut shifts) = (0, 0, 0, 0);
            for round in 0..1200 {
                let u_faces = round % 2 == 0;
                // The field's columns and rows, and the carried rows' lengths.
                let (nx, ny) = if u_faces { (n + 1, n) } else { (n, n + 1) };
                let (own_len, other_len) = if u_faces { (n + 1, n) } else { (n, n + 1) };
                // Zeros of both signs side by side (the limiter's ties), a NaN now and then.
                let field: Vec<f32> = (0..nx * ny)
                    .map(|k| match ((k + round) * 7919) % 101 {
                        0..=6 => [0.0, -0.0][k % 2],
                        7 if round % 5 == 0 => f32::NAN,
                        r => r as f32 / 13.0 - 3.5,
                    })
                    .collect();
                // Mostly velocities that keep feet within reach, sometimes an edge case.
                // In three rounds of four, each axis's velocities of one sign (the eights
                // the window takes as one shift), and in the fourth of either.
                let signs = [[0.0, 0.0], [1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0]][round % 4];
                let mut speed = |sign: f32| {
                    let r = next();
                    if r < 0.03 {
                        odd[(next() * odd.len() as f32) as usize % odd.len()]
                    } else {
                        let v = (r - 0.03) / 0.97 * 2.0 - 1.0;
                        if sign == 0.0 { v } else { sign * v.abs() }
                    }
                };
                let mut own: Vec<f32> = (0..own_len).map(|_| speed(signs[0])).collect();
                let below: Vec<f32> = (0..other_len).map(|_| speed(signs[1])).collect();
                let above: Vec<f32> = (0..other_len).map(|_| speed(signs[1])).collect();
                let j = (round / 2) % ny;
                let first = usize::from(u_faces) + (round / 7) % 5;
                let end = n - (round / 11) % 5;
                if round % 13 == 0 {
                    own[first + round % 8] = [f32::NAN, f32::INFINITY, -f32::INFINITY][round % 3];
                }
                let s = 1.0;
                let foot = |f: usize| {
                    let (a, b) = (&below, &above);
                    if u_faces {
                        let across = s * 0.25 * (a[f - 1] + a[f] + b[f - 1] + b[f]);
                        (cell(f) - s * own[f], cell(j) - across)
                    } else {
                        let across = s * 0.25 * (a[f] + a[f + 1] + b[f] + b[f + 1]);
                        (cell(f) - across, cell(j) - s * own[f])
                    }
                };
                let carried = if u_faces {
                    Carried::U {
                        u: &own,
                        v: [&below, &above],
                    }
                } else {
                    Carried::V {
                        v: &own,
                        u: [&below, &above],
                    }
                };
                // The rows around `j` clamped to the field, as `advection` hands a row at
                // the field's ends: every other round, those rows take their window from it.
                let clamped: Vec<f32> = (0..2 * reach + 1)
                    .flat_map(|k| {
                        let r = (j + k).saturating_sub(reach).min(ny - 1);
                        field[r * nx..][..nx].to_vec()
                    })
                    .collect();
                let at_an_end = j < reach || j + reach >= ny;
                // (Bicubic rows only: the bilinear loop takes none.)
                let edge = (CUBIC && round % 4 < 2).then_some(&clamped[..]);
                let mut out = vec![f32::NAN; nx];
                let dims = [nx, ny];
                // SAFETY: the caller asked `available()`.
                let [took, shifted] = unsafe {
                    trace_row::<CUBIC>(&field, dims, j, first..end, carried, s, edge, &mut out)
                };
                for (f, sampled) in out.iter().enumerate().take(end).skip(first) {
                    let (x, y) = foot(f);
                    let one = if CUBIC {
                        cubic_sample(&field, nx, ny, x, y)
                    } else {
                        linear_sample(&field, nx, ny, x, y)
                    };
                    assert_eq!(sampled.to_bits(), one.to_bits(), "face {f} of row {j}");
                }
                // The eights it walks, and which of them the window can take: away from
                // the field's first and last rows, or at them from the clamped rows where
                // every foot lies within the field's rows.
                let near = |t: f32, home: usize| t >= home as f32 - 1.0 && t < home as f32 + 1.0;
                let on_rows = |y: f32| y >= 0.0 && y < (ny - 1) as f32;
                let mut expected = 0;
                let mut i = first;
                loop {
                    let at = i.min(end - 8);
                    let columns = at >= reach && at + 8 + reach <= nx;
                    let all = |ok: &dyn Fn(f32, f32, usize) -> bool| {
                        (at..at + 8).all(|f| {
                            let (x, y) = foot(f);
                            ok(x, y, f)
                        })
                    };
                    let all_near = all(&|x, y, f| near(x, f) && near(y, j));
                    let taken_here = match (at_an_end, edge) {
                        (false, _) => columns && all_near,
                        (true, None) => false,
                        (true, Some(_)) => columns && all_near && all(&|_, y, _| on_rows(y)),
                    };
                    if taken_here {
                        expected += 1;
                        ends_taken += usize::from(at_an_end);
                    } else {
                        declined += 1;
                    }
                    if at + 8 == end {
                        break;
                    }
                    i += 8;
                }
                assert_eq!(took, expected, "row {j}, faces {first}..{end}");
                taken += took;
                shifts += shifted;
            }
            assert!(
                taken > 250 && declined > 250 && (ends_taken > 0 || !CUBIC),
                "{taken} taken ({ends_taken} at the field's ends), {declined} declined"
            );
            assert!(
                shifts > 100 && taken - shifts > 100,
                "{shifts} of {taken} taken as one shift, the rest blended lane by lane"
            );
        }

        #[test]
        fn a_row_of_bilinear_samples_eight_at_a_time_is_one_at_a_time() {
            if available() {
                a_row_eight_at_a_time_is_one_at_a_time::<false>();
            }
        }

        #[test]
        fn a_row_of_bicubic_samples_eight_at_a_time_is_one_at_a_time() {
            if available() {
                a_row_eight_at_a_time_is_one_at_a_time::<true>();
            }
        }
    }
}
