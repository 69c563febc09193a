//! Viscosity: explicit Laplacian sweeps of the velocity, sub-stepped where one sweep
//! would be unstable.

use super::{Fluid, RINGS_SWEEP_LIMIT, Walls};

/// Most explicit diffusion sweeps in one step (see [`Fluid::diffuse`]).
pub(crate) const MAX_DIFFUSION_SWEEPS: usize = 32;

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
        if let Some(mut rings) = self.rings.take() {
            // The same cap on the viscosity as the plane's, in sweeps half as long.
            let most = MAX_DIFFUSION_SWEEPS * 2;
            let substeps = ((alpha / RINGS_SWEEP_LIMIT).ceil() as usize).clamp(1, most);
            let a = (alpha / substeps as f32).min(RINGS_SWEEP_LIMIT);
            for _ in 0..substeps {
                self.ring_viscosity_sweep(&mut rings, a);
            }
            self.rings = Some(rings);
            return;
        }
        let substeps = ((alpha / 0.2).ceil() as usize).clamp(1, MAX_DIFFUSION_SWEEPS);
        let a = (alpha / substeps as f32).min(0.2);
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
