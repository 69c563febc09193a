//! Viscosity: explicit Laplacian sweeps of the velocity, sub-stepped where one sweep
//! would be unstable.

use super::{Fluid, RINGS_SWEEP_LIMIT, Walls};

/// Most explicit diffusion sweeps in one step (see [`Fluid::diffuse`]).
pub(crate) const MAX_DIFFUSION_SWEEPS: usize = 32;
/// Largest `ν·dt/h²` of one explicit sweep of the plane's Laplacian (stable below 1/4).
const PLANE_SWEEP_LIMIT: f32 = 0.2;

impl Fluid {
    /// Viscosity, explicit, sub-stepped where `ν·dt/h²` would be unstable. For sea water at
    /// these scales `ν·dt/h²` is about 1e-3, so this is one cheap sweep. At most
    /// [`MAX_DIFFUSION_SWEEPS`] sweeps: beyond, the viscosity is capped at what they
    /// resolve (`32 · 0.2 · h²/dt`; Re ≈ 0.3 for the default species, where nothing swims
    /// anyway), so a species as viscous as honey costs a bounded step instead of hanging.
    pub(crate) fn diffuse(&mut self, dt: f32) {
        if let Walls::ClosedBox { no_slip: true, lid } = self.walls {
            return self.diffuse_no_slip(dt, lid);
        }
        let alpha = self.nu * dt / (self.h * self.h);
        if alpha.is_nan() || alpha <= 0.0 {
            return;
        }
        if let Some(mut half) = self.take_half() {
            // Rings: the same cap on the viscosity as the plane's, in sweeps half as long.
            let (limit, most) = if half.axisymmetric() {
                (RINGS_SWEEP_LIMIT, MAX_DIFFUSION_SWEEPS * 2)
            } else {
                (PLANE_SWEEP_LIMIT, MAX_DIFFUSION_SWEEPS)
            };
            let substeps = ((alpha / limit).ceil() as usize).clamp(1, most);
            let a = (alpha / substeps as f32).min(limit);
            for _ in 0..substeps {
                self.ring_viscosity_sweep(&mut half, a);
            }
            return self.put_half(half);
        }
        let substeps = ((alpha / PLANE_SWEEP_LIMIT).ceil() as usize).clamp(1, MAX_DIFFUSION_SWEEPS);
        let a = (alpha / substeps as f32).min(PLANE_SWEEP_LIMIT);
        let n = self.n;
        for _ in 0..substeps {
            laplacian_step(&self.u, &mut self.scratch_u, n + 1, n, a);
            laplacian_step(&self.v, &mut self.scratch_v, n, n + 1, a);
            std::mem::swap(&mut self.u, &mut self.scratch_u);
            std::mem::swap(&mut self.v, &mut self.scratch_v);
            self.enforce_walls();
        }
    }
}

/// One explicit diffusion sweep `dst = src + a·∇²src` with zero-gradient edges.
fn laplacian_step(src: &[f32], dst: &mut [f32], nx: usize, ny: usize, a: f32) {
    for j in 0..ny {
        let (jm, jp) = (j.saturating_sub(1), (j + 1).min(ny - 1));
        let (below, here, above) = (
            &src[jm * nx..][..nx],
            &src[j * nx..][..nx],
            &src[jp * nx..][..nx],
        );
        let out = &mut dst[j * nx..][..nx];
        let update = |c: f32, left: f32, right: f32, i: usize| {
            c + a * (left + right + below[i] + above[i] - 4.0 * c)
        };
        out[0] = update(here[0], here[0], here[1], 0);
        // The interior over slices of one length (no index checks), so that it vectorises;
        // each value's arithmetic as `update`'s.
        let sides = here[..nx - 2].iter().zip(&here[2..]);
        let centre = here[1..nx - 1]
            .iter()
            .zip(&below[1..nx - 1])
            .zip(&above[1..nx - 1]);
        for (o, ((left, right), ((c, b), t))) in out[1..nx - 1].iter_mut().zip(sides.zip(centre)) {
            *o = c + a * (left + right + b + t - 4.0 * c);
        }
        out[nx - 1] = update(here[nx - 1], here[nx - 2], here[nx - 1], nx - 1);
    }
}
