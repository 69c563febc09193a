//! The co-moving box: the fluid's frame follows the bell, by a Galilean change of frame
//! along the axis and whole-cell shifts across it.

use super::Fluid;

impl Fluid {
    /// The frame speeds up by `dv` (m/s, along y): every relative velocity drops by it, the
    /// world's water is untouched (a Galilean change of frame; uniform, so still
    /// divergence-free).
    pub(crate) fn change_frame(&mut self, dv: f32) {
        if dv == 0.0 {
            return;
        }
        self.v.iter_mut().for_each(|v| *v -= dv);
        self.stream -= dv;
    }

    /// Shifts every field across the channel by `dx` whole cells (-1..=1) so that the
    /// content moves by `-dx·h`; still water (the stream) flows in at the opened side.
    pub(crate) fn shift_across(&mut self, dx: i32) {
        let n = self.n;
        shift_field(&mut self.u, &mut self.scratch_u, n + 1, n, dx, 0.0);
        shift_field(&mut self.v, &mut self.scratch_v, n, n + 1, dx, self.stream);
        self.enforce_walls();
        self.project();
    }
}

/// `dst(i, j) = src(i + dx, j)`, `fill` where that falls outside.
fn shift_field(
    field: &mut Vec<f32>,
    scratch: &mut Vec<f32>,
    nx: usize,
    ny: usize,
    dx: i32,
    fill: f32,
) {
    for j in 0..ny {
        for i in 0..nx {
            let si = i as i32 + dx;
            scratch[j * nx + i] = if si >= 0 && (si as usize) < nx {
                field[j * nx + si as usize]
            } else {
                fill
            };
        }
    }
    std::mem::swap(field, scratch);
}
