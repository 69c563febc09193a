//! Self-advection: the velocity carried along itself, by a semi-Lagrangian trace back
//! from each face (Stam 1999), optionally corrected by MacCormack's forward–backward
//! step or sampled by a limited bicubic (see [`Advection`]).

use super::sampling::{
    cell, cubic_sample, cubic_sample4, four, linear_sample, linear_sample4, trace,
};
use super::symmetry;
#[cfg(target_arch = "x86_64")]
use super::window::{self, avx::Carried};
use super::{Advection, Fluid};
use glam::Vec2;

impl Fluid {
    /// Self-advection by the species' scheme ([`Advection`]), then the walls again.
    pub(crate) fn advect(&mut self, dt: f32) {
        let s = dt / self.h;
        match self.advection {
            Advection::SemiLagrangian => self.advect_once(s, Sample::Linear(None)),
            Advection::Cubic => self.advect_once(s, Sample::Cubic),
            Advection::MacCormack => self.advect_maccormack(s),
        }
        self.enforce_walls();
    }

    /// The velocity a passive tracer at `p` (m) is carried with: each component bilinear
    /// between its four nearest faces, as the advection's own trace reads it (outside the
    /// box, the nearest faces'). A tracer pushes nothing back, so it needs none of the
    /// kernel's adjointness with spreading ([`Fluid::velocity_at`]), which costs a stencil
    /// of up to forty faces a component.
    pub(crate) fn tracer_velocity(&self, p: Vec2) -> Vec2 {
        let n = self.n;
        let (x, y) = (p.x / self.h, p.y / self.h);
        Vec2::new(
            linear_sample(&self.u, n + 1, n, x, y - 0.5),
            linear_sample(&self.v, n, n + 1, x - 0.5, y),
        )
    }

    /// Stam's semi-Lagrangian step: each face takes the value found by tracing the flow
    /// back `s = dt/h` cells per unit velocity, sampled by `sample`.
    fn advect_once(&mut self, s: f32, sample: Sample) {
        let mirror = Mirror::of(self);
        semi_lagrangian(
            [&self.u, &self.v],
            [&self.u, &self.v],
            self.n,
            s,
            [&mut self.scratch_u, &mut self.scratch_v],
            sample,
            mirror,
        );
        std::mem::swap(&mut self.u, &mut self.scratch_u);
        std::mem::swap(&mut self.v, &mut self.scratch_v);
    }

    /// MacCormack's method (Selle et al. 2008): a semi-Lagrangian step forward, one back,
    /// and half the round-trip error corrected, clamped to the values the forward step
    /// interpolated between. Second order where the flow is smooth, plain Stam at extrema,
    /// so it stays unconditionally stable; it keeps the vortices a bell a few cells wide
    /// sheds from being smeared away by numerical viscosity.
    fn advect_maccormack(&mut self, s: f32) {
        let n = self.n;
        // Forward: scratch = A(u); bounds = the corner values it interpolated between.
        semi_lagrangian(
            [&self.u, &self.v],
            [&self.u, &self.v],
            n,
            s,
            [&mut self.scratch_u, &mut self.scratch_v],
            Sample::Linear(Some([&mut self.bounds_u, &mut self.bounds_v])),
            Mirror::whole(self.mirror),
        );
        // Back: back = A⁻¹(A(u)), with the same velocity and the step reversed.
        semi_lagrangian(
            [&self.scratch_u, &self.scratch_v],
            [&self.u, &self.v],
            n,
            -s,
            [&mut self.back_u, &mut self.back_v],
            Sample::Linear(None),
            Mirror::whole(self.mirror),
        );
        for (out, fwd, orig, bounds) in [
            (&mut self.back_u, &self.scratch_u, &self.u, &self.bounds_u),
            (&mut self.back_v, &self.scratch_v, &self.v, &self.bounds_v),
        ] {
            for (((back, fwd), orig), &(lo, hi)) in out.iter_mut().zip(fwd).zip(orig).zip(bounds) {
                // max-then-min, not clamp: clamp panics on NaN bounds, and a blow-up
                // must reach the health check, not abort.
                *back = (fwd + 0.5 * (orig - *back)).max(lo).min(hi);
            }
        }
        std::mem::swap(&mut self.u, &mut self.back_u);
        std::mem::swap(&mut self.v, &mut self.back_v);
    }
}

/// One semi-Lagrangian step of the staggered pair `src` through the velocity `vel`, by
/// `s = dt/h` cells per unit velocity (negative: backwards). Side-wall faces are left as
/// they are: the caller zeroes them. A trace that leaves through an open end reads the
/// boundary face, where the stream enters.
///
/// With a [`Mirror`], the flow is mirror-symmetric about the axis (see
/// [`Fluid::symmetrise`]): only the faces up to the axis are traced, which halves the
/// cost, and the rest are their mirror images.
fn semi_lagrangian(
    src: [&[f32]; 2],
    vel: [&[f32]; 2],
    n: usize,
    s: f32,
    out: [&mut Vec<f32>; 2],
    sample: Sample,
    mirror: Mirror,
) {
    // One loop per sampler, so each inner loop is compiled without the others' branches.
    let traced = if mirror == Mirror::No {
        n
    } else {
        (n / 2 + 1).min(n)
    };
    let [out_u, out_v] = out;
    let (mut bounds_u, mut bounds_v) = (None, None);
    {
        let out = [&mut *out_u, &mut *out_v];
        match sample {
            Sample::Linear(None) => sweep::<LINEAR>(src, vel, n, traced, s, out, None),
            Sample::Linear(Some([bu, bv])) => {
                sweep::<BOUNDED>(src, vel, n, traced, s, out, Some([&mut *bu, &mut *bv]));
                (bounds_u, bounds_v) = (Some(bu), Some(bv));
            }
            Sample::Cubic => sweep::<CUBIC>(src, vel, n, traced, s, out, None),
        }
    }
    match mirror {
        _ if traced == n => {}
        Mirror::No => {}
        Mirror::Whole => symmetry::mirror(out_u, out_v, bounds_u, bounds_v, n),
        Mirror::PastAxis => symmetry::mirror_past_axis(out_u, out_v, n),
    }
}

/// Which faces past the axis a mirror-symmetric step fills in.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mirror {
    /// None: the flow is not held symmetric, every face is traced.
    No,
    /// All of them: the next steps read the whole field.
    Whole,
    /// Only the column just past the axis: a slice solved on its half (see
    /// [`Fluid::half`]) reads no further before its projection mirrors the rest (the
    /// same bits as [`Mirror::Whole`], a pass over half the field fewer).
    PastAxis,
}

impl Mirror {
    /// All faces when `symmetric`, else none.
    fn whole(symmetric: bool) -> Self {
        if symmetric { Mirror::Whole } else { Mirror::No }
    }

    /// What one step of `fluid`'s own advection needs.
    fn of(fluid: &Fluid) -> Self {
        match (fluid.mirror, fluid.half().is_some()) {
            (false, _) => Mirror::No,
            (true, false) => Mirror::Whole,
            (true, true) => Mirror::PastAxis,
        }
    }
}

const LINEAR: u8 = 0;
const BOUNDED: u8 = 1;
const CUBIC: u8 = 2;

/// Traces the faces of columns below `traced` (all of them: `n`).
fn sweep<const MODE: u8>(
    src: [&[f32]; 2],
    vel: [&[f32]; 2],
    n: usize,
    traced: usize,
    s: f32,
    out: [&mut Vec<f32>; 2],
    bounds: Option<[&mut Vec<(f32, f32)>; 2]>,
) {
    let [u, v] = vel;
    let [out_u, out_v] = out;
    let [mut bounds_u, mut bounds_v] = match bounds {
        Some([bu, bv]) => [Some(bu), Some(bv)],
        None => [None, None],
    };
    // Plain bilinear and bicubic take eight feet at a time where they lie near their
    // faces (`window`): the same bits as below.
    #[cfg(target_arch = "x86_64")]
    let avx = window::avx::available();
    // The clamped rows around a row at the field's first or last rows (`trace_windowed`).
    #[cfg(target_arch = "x86_64")]
    let mut edge = Vec::new();
    // u faces, (n + 1) × n: each one's own u, and v averaged from the four faces around it.
    for j in 0..n {
        let row = j * (n + 1);
        let u_row = &u[row..][..n + 1];
        let (v0, v1) = (&v[j * n..][..n], &v[(j + 1) * n..][..n]);
        let foot = |i: usize| {
            let cu = s * u_row[i];
            let cv = s * 0.25 * (v0[i - 1] + v0[i] + v1[i - 1] + v1[i]);
            (cell(i) - cu, cell(j) - cv)
        };
        // The same, four faces at a time.
        let feet = |i: usize| {
            let (w, a, b) = (&u_row[i..][..4], &v0[i - 1..][..5], &v1[i - 1..][..5]);
            let x = four(|k| cell(i + k) - s * w[k]);
            let y = four(|k| cell(j) - s * 0.25 * (a[k] + a[k + 1] + b[k] + b[k + 1]));
            (x, y)
        };
        let faces = 1..traced.min(n);
        let out = &mut out_u[row..][..n + 1];
        #[cfg(target_arch = "x86_64")]
        if MODE != BOUNDED && avx {
            let carried = Carried::U {
                u: u_row,
                v: [v0, v1],
            };
            let dims = [n + 1, n];
            // SAFETY: this processor has AVX (asked above).
            let row = (j, &faces, &mut edge);
            if unsafe { trace_windowed::<MODE>(src[0], dims, row, carried, s, foot, out) } {
                continue;
            }
        }
        let bounds = bounds_u.as_deref_mut().map(|b| &mut b[row..][..n + 1]);
        trace_row::<MODE>(src[0], [n + 1, n], faces, (foot, feet), out, bounds);
    }
    // v faces, n × (n + 1), the open ends included: each one's own v, and u averaged
    // likewise (from the one row there is at the ends).
    for j in 0..=n {
        let row = j * n;
        let v_row = &v[row..][..n];
        let (below, above) = (j.saturating_sub(1), j.min(n - 1));
        let (u0, u1) = (
            &u[below * (n + 1)..][..n + 1],
            &u[above * (n + 1)..][..n + 1],
        );
        let foot = |i: usize| {
            let cv = s * v_row[i];
            let cu = s * 0.25 * (u0[i] + u0[i + 1] + u1[i] + u1[i + 1]);
            (cell(i) - cu, cell(j) - cv)
        };
        let feet = |i: usize| {
            let (w, a, b) = (&v_row[i..][..4], &u0[i..][..5], &u1[i..][..5]);
            let x = four(|k| cell(i + k) - s * 0.25 * (a[k] + a[k + 1] + b[k] + b[k + 1]));
            let y = four(|k| cell(j) - s * w[k]);
            (x, y)
        };
        let out = &mut out_v[row..][..n];
        #[cfg(target_arch = "x86_64")]
        if MODE != BOUNDED && avx {
            let carried = Carried::V {
                v: v_row,
                u: [u0, u1],
            };
            let (dims, faces) = ([n, n + 1], 0..traced);
            // SAFETY: this processor has AVX (asked above).
            let row = (j, &faces, &mut edge);
            if unsafe { trace_windowed::<MODE>(src[1], dims, row, carried, s, foot, out) } {
                continue;
            }
        }
        let bounds = bounds_v.as_deref_mut().map(|b| &mut b[row..][..n]);
        trace_row::<MODE>(src[1], [n, n + 1], 0..traced, (foot, feet), out, bounds);
    }
}

/// Plain bilinear or bicubic with AVX: of the faces `faces` of row `j`, those far enough
/// inside the row for the window go to it eight at a time (`window::avx::trace_row`),
/// the few at its ends one at a time (`foot`); `false`, and nothing done, where fewer
/// than eight are inside. A bicubic row whose window reaches past the field's first or
/// last row hands the window its rows clamped to the field, copied into `edge`.
///
/// # Safety
/// The processor must have AVX (`window::avx::available`).
#[cfg(target_arch = "x86_64")]
#[allow(clippy::too_many_arguments)]
unsafe fn trace_windowed<const MODE: u8>(
    field: &[f32],
    [nx, ny]: [usize; 2],
    (j, faces, edge): (usize, &std::ops::Range<usize>, &mut Vec<f32>),
    carried: Carried,
    s: f32,
    foot: impl Fn(usize) -> (f32, f32),
    out: &mut [f32],
) -> bool {
    // Bicubic reads a column further either side.
    let reach = if MODE == CUBIC { 2 } else { 1 };
    let inside = faces.start.max(reach)..faces.end.min(nx.saturating_sub(reach));
    if inside.len() < 8 {
        return false;
    }
    for i in (faces.start..inside.start).chain(inside.end..faces.end) {
        let (x, y) = foot(i);
        out[i] = match MODE {
            CUBIC => cubic_sample(field, nx, ny, x, y),
            _ => linear_sample(field, nx, ny, x, y),
        };
    }
    // (Bicubic only: bilinear's four-wide fallback costs less than the copy.)
    let edge = (MODE == CUBIC && (j < reach || j + reach >= ny)).then(|| {
        edge.clear();
        for k in 0..2 * reach + 1 {
            let r = (j + k).saturating_sub(reach).min(ny - 1);
            edge.extend_from_slice(&field[r * nx..][..nx]);
        }
        &edge[..]
    });
    let dims = [nx, ny];
    // SAFETY: the caller vouches for AVX.
    unsafe {
        match MODE {
            CUBIC => window::avx::trace_row::<true>(field, dims, j, inside, carried, s, edge, out),
            _ => window::avx::trace_row::<false>(field, dims, j, inside, carried, s, edge, out),
        }
    };
    true
}

/// Samples `field` (`[nx, ny]` columns and rows) at the foot of each face in `faces` of
/// one row, into `out` (and the corners' range into `bounds`, for MacCormack). Bilinear
/// and bicubic take four faces at a time (`feet`), whose arithmetic compiles to four-wide
/// vector instructions: the same bits as one at a time (`foot`), the bicubic a fifth off
/// *Sarsia*'s slice, the bilinear a seventh off the moon jelly's. With AVX, `sweep` hands
/// bilinear and bicubic rows to `trace_windowed` first; this takes what it leaves.
fn trace_row<const MODE: u8>(
    field: &[f32],
    [nx, ny]: [usize; 2],
    faces: std::ops::Range<usize>,
    (foot, feet): (
        impl Fn(usize) -> (f32, f32),
        impl Fn(usize) -> ([f32; 4], [f32; 4]),
    ),
    out: &mut [f32],
    mut bounds: Option<&mut [(f32, f32)]>,
) {
    if MODE != BOUNDED && faces.len() >= 4 {
        // The last four end the row, overlapping the four before where the count is not
        // a multiple of four (those faces get the same value again).
        let mut i = faces.start;
        loop {
            let at = i.min(faces.end - 4);
            let (x, y) = feet(at);
            let four = match MODE {
                CUBIC => cubic_sample4(field, nx, ny, x, y),
                _ => linear_sample4(field, nx, ny, x, y),
            };
            out[at..][..4].copy_from_slice(&four);
            if at + 4 == faces.end {
                return;
            }
            i += 4;
        }
    }
    for i in faces {
        let (x, y) = foot(i);
        match MODE {
            CUBIC => out[i] = cubic_sample(field, nx, ny, x, y),
            LINEAR => out[i] = linear_sample(field, nx, ny, x, y),
            _ => trace(field, nx, ny, x, y, i, out, bounds.as_deref_mut()),
        }
    }
}

/// How a semi-Lagrangian step samples the field at the foot of a trace.
enum Sample<'a> {
    /// Bilinear; with `Some`, also record each sample's corner range (for MacCormack).
    Linear(Option<[&'a mut Vec<(f32, f32)>; 2]>),
    /// Catmull–Rom bicubic, limited to the four nearest values.
    Cubic,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face traced four at a time lands where one traced alone does, to the bit:
    /// its foot by the same arithmetic, sampled by the same bilinear or bicubic weights.
    #[test]
    fn faces_traced_four_at_a_time_are_faces_traced_alone() {
        let n = 13; // odd: rows end in a partial four
        let wave = |k: usize, scale: f32| ((k * 37 % 101) as f32 / 101.0 - 0.5) * scale;
        let u: Vec<f32> = (0..(n + 1) * n).map(|k| wave(k, 3.0)).collect();
        let v: Vec<f32> = (0..n * (n + 1)).map(|k| wave(k + 5, 3.0)).collect();
        let s = 0.7;
        for (sample, cubic) in [(Sample::Linear(None), false), (Sample::Cubic, true)] {
            let (mut out_u, mut out_v) = (vec![0.0; u.len()], vec![0.0; v.len()]);
            semi_lagrangian(
                [&u, &v],
                [&u, &v],
                n,
                s,
                [&mut out_u, &mut out_v],
                sample,
                Mirror::No,
            );
            let alone = |field: &[f32], nx: usize, ny: usize, x: f32, y: f32| {
                if cubic {
                    cubic_sample(field, nx, ny, x, y)
                } else {
                    linear_sample(field, nx, ny, x, y)
                }
            };
            for j in 0..n {
                for i in 1..n {
                    let around = v[j * n + i - 1] + v[j * n + i];
                    let around = around + v[(j + 1) * n + i - 1] + v[(j + 1) * n + i];
                    let x = cell(i) - s * u[j * (n + 1) + i];
                    let y = cell(j) - s * 0.25 * around;
                    let expected = alone(&u, n + 1, n, x, y);
                    assert_eq!(
                        out_u[j * (n + 1) + i].to_bits(),
                        expected.to_bits(),
                        "u {i} {j}"
                    );
                }
            }
            for j in 0..=n {
                let (below, above) = (j.saturating_sub(1), j.min(n - 1));
                for i in 0..n {
                    let around = u[below * (n + 1) + i] + u[below * (n + 1) + i + 1];
                    let around = around + u[above * (n + 1) + i] + u[above * (n + 1) + i + 1];
                    let x = cell(i) - s * 0.25 * around;
                    let y = cell(j) - s * v[j * n + i];
                    let expected = alone(&v, n, n + 1, x, y);
                    assert_eq!(out_v[j * n + i].to_bits(), expected.to_bits(), "v {i} {j}");
                }
            }
        }
    }
}
