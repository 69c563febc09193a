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
    let weights = |t: f32| {
        let (t2, t3) = (t * t, t * t * t);
        [
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ]
    };
    let (wx, wy) = (weights(fx), weights(fy));
    let col = |d: usize| (i + d).saturating_sub(1).min(nx - 1);
    let cols = [col(0), col(1), col(2), col(3)];
    let rows: [&[f32]; 4] =
        std::array::from_fn(|b| &field[(j + b).saturating_sub(1).min(ny - 1) * nx..][..nx]);
    let mut value = 0.0;
    for (r, w) in rows.iter().zip(&wy) {
        value +=
            w * (wx[0] * r[cols[0]] + wx[1] * r[cols[1]] + wx[2] * r[cols[2]] + wx[3] * r[cols[3]]);
    }
    // The four nearest values are the middle of the sixteen (`locate` keeps i + 1 and j + 1
    // inside the field, so neither is clamped).
    let (a, b) = (rows[1], rows[2]);
    let (a0, a1, b0, b1) = (a[cols[1]], a[cols[2]], b[cols[1]], b[cols[2]]);
    let lo = a0.min(a1).min(b0).min(b1);
    let hi = a0.max(a1).max(b0).max(b1);
    // max-then-min, not clamp: NaN must reach the health check, not panic.
    value.max(lo).min(hi)
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
    bounds: Option<&mut Vec<(f32, f32)>>,
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
#[inline]
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
