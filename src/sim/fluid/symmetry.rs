//! The mirror about the bell's axis: a slice that is held mirror-symmetric averages its
//! flow with its mirror image, and advection traces only half the faces.

use super::sampling::cell;
use super::{Component, Fluid};

impl Fluid {
    /// The vertical line the slice is mirror-symmetric about, m: the centre of the middle
    /// column of cells. Always a cell centre, for an odd or an even grid: with the axis on
    /// a face line (the box's centre on even grids) the aperture's jet met the grid
    /// differently and the stroke changed by 5% between neighbouring grids.
    pub fn axis(&self) -> f32 {
        (cell(self.n / 2) + 0.5) * self.h
    }

    /// Averages the flow with its mirror image about [`Fluid::axis`]. On even grids the
    /// axis is half a cell off the box's centre: the faces whose mirror is outside the box
    /// or on a wall are left as they are.
    pub(crate) fn symmetrise(&mut self) {
        let n = self.n;
        let c = n / 2;
        for j in 0..n {
            let row = &mut self.u[j * (n + 1)..(j + 1) * (n + 1)];
            for i in 1..=c {
                let m = 2 * c + 1 - i;
                if m < n {
                    let avg = 0.5 * (row[i] - row[m]);
                    row[i] = avg;
                    row[m] = -avg;
                }
            }
        }
        for j in 0..=n {
            let row = &mut self.v[j * n..(j + 1) * n];
            for i in 0..c {
                let m = 2 * c - i;
                if m < n {
                    let avg = 0.5 * (row[i] + row[m]);
                    row[i] = avg;
                    row[m] = avg;
                }
            }
        }
    }
}

impl Component {
    /// The column of this component's faces mirrored about [`Fluid::axis`] on an
    /// `n`-cell grid (the indices of [`Fluid::symmetrise`]), if it is on the grid.
    pub(crate) fn mirrored_column(self, column: usize, n: usize) -> Option<usize> {
        let c = n / 2;
        match self {
            Component::U => (2 * c + 1).checked_sub(column).filter(|&m| m <= n),
            Component::V => (2 * c).checked_sub(column).filter(|&m| m < n),
        }
    }
}

/// Fills the faces past the axis with the mirror images of the traced ones (the indices
/// of [`Fluid::symmetrise`]): `u` changes sign, `v` does not, and a corner range
/// `(lo, hi)` of `u` becomes `(-hi, -lo)`.
pub(super) fn mirror(
    u: &mut [f32],
    v: &mut [f32],
    bounds_u: Option<&mut Vec<(f32, f32)>>,
    bounds_v: Option<&mut Vec<(f32, f32)>>,
    n: usize,
) {
    u.chunks_exact_mut(n + 1).for_each(mirror_u_row);
    v.chunks_exact_mut(n).for_each(mirror_v_row);
    if let Some(bounds) = bounds_u {
        for row in bounds.chunks_exact_mut(n + 1) {
            mirror_u_row_as(row, |(lo, hi)| (-hi, -lo));
        }
    }
    if let Some(bounds) = bounds_v {
        for row in bounds.chunks_exact_mut(n) {
            mirror_v_row_as(row, |t| t);
        }
    }
}

/// One row of `u` faces (`n + 1` of them) past the axis written from the row before it
/// read backwards, as [`mirror`] fills them: face m from face 2c + 1 − m, reversed.
pub(super) fn mirror_u_row(row: &mut [f32]) {
    mirror_u_row_as(row, |t| -t);
}

/// One row of `v` faces (`n` of them) past the axis written from the row before it read
/// backwards, as [`mirror`] fills them: column m from column 2c − m.
pub(super) fn mirror_v_row(row: &mut [f32]) {
    mirror_v_row_as(row, |t| t);
}

/// [`mirror_u_row`] of anything a `u` face carries, each value's mirror image `image`.
fn mirror_u_row_as<T: Copy>(row: &mut [T], image: impl Fn(T) -> T) {
    let n = row.len() - 1;
    let c = n / 2;
    let (traced, past) = row.split_at_mut(c + 1);
    reverse_into(&mut past[..n - 1 - c], traced, image);
}

/// [`mirror_v_row`] of anything a `v` face carries.
fn mirror_v_row_as<T: Copy>(row: &mut [T], image: impl Fn(T) -> T) {
    let n = row.len();
    let c = n / 2;
    let (traced, past) = row.split_at_mut(c + 1);
    reverse_into(past, &traced[..c], image);
}

/// `out[m] = image(from[from.len() − 1 − m])` for each `m` of `out` (no longer than
/// `from`): four at a time, each four read as one block and turned, so that it
/// vectorises (a reversed iterator stepped one value at a time did not).
fn reverse_into<T: Copy>(out: &mut [T], from: &[T], image: impl Fn(T) -> T) {
    let from = &from[from.len() - out.len()..];
    let mut quads = out.chunks_exact_mut(4);
    let mut sources = from.rchunks_exact(4);
    for (o, f) in (&mut quads).zip(&mut sources) {
        let [a, b, c, d] = [f[3], f[2], f[1], f[0]];
        o.copy_from_slice(&[image(a), image(b), image(c), image(d)]);
    }
    for (o, f) in quads
        .into_remainder()
        .iter_mut()
        .zip(sources.remainder().iter().rev())
    {
        *o = image(*f);
    }
}

/// The one column of faces just past the axis, as [`mirror`] would fill it: `u` odd, `v`
/// even about the axis.
pub(super) fn mirror_past_axis(u: &mut [f32], v: &mut [f32], n: usize) {
    let c = n / 2;
    if c + 1 < n && c >= 1 {
        for row in u.chunks_exact_mut(n + 1) {
            row[c + 1] = -row[c];
        }
        for row in v.chunks_exact_mut(n) {
            row[c + 1] = row[c - 1];
        }
    }
}
