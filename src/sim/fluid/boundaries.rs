//! The channel's boundaries: free-slip side walls, still water (the stream) entering at
//! the top, and the open bottom where the wake leaves through an absorbing layer.

use super::Fluid;

impl Fluid {
    /// Sets up an absorbing layer `width` cells deep at the bottom (wake) end whose damping
    /// rises smoothly to `rate` (1/s) at the boundary: vortices shed long ago fade into the
    /// stream before they reach the open end, where a zero-pressure boundary would
    /// reflect part of them.
    pub(crate) fn set_sponge(&mut self, width: usize, rate: f32) {
        let w = width as f32;
        let ramp = |d: f32| {
            if w <= 0.0 || d >= w {
                0.0
            } else {
                let s = 1.0 - d / w;
                rate * s * s
            }
        };
        let n = self.n;
        for j in 0..n {
            let r = ramp(j as f32 + 0.5);
            self.sponge_u[j * (n + 1)..][..n + 1].fill(r);
        }
        for j in 0..=n {
            let r = ramp(j as f32);
            self.sponge_v[j * n..][..n].fill(r);
        }
    }

    /// Relaxes the velocity in the absorbing layer towards the stream (implicit Euler:
    /// stable for any rate and step). Only the rows within the layer: elsewhere there is
    /// nothing to relax, and a planar slice's `n` columns or a mirror-symmetric slice's
    /// solved half (the projection mirrors the rest).
    pub(crate) fn absorb(&mut self, dt: f32) {
        let n = self.n;
        let columns = self.half().map_or(n, |r| r.solved);
        let stream = self.stream;
        for (u, rate) in self
            .u
            .chunks_exact_mut(n + 1)
            .zip(self.sponge_u.chunks_exact(n + 1))
        {
            if rate[0] > 0.0 {
                let damp = 1.0 / (1.0 + rate[0] * dt);
                u[..(columns + 1).min(n + 1)]
                    .iter_mut()
                    .for_each(|u| *u *= damp);
            }
        }
        for (v, rate) in self
            .v
            .chunks_exact_mut(n)
            .zip(self.sponge_v.chunks_exact(n))
        {
            if rate[0] > 0.0 {
                let damp = 1.0 / (1.0 + rate[0] * dt);
                v[..columns]
                    .iter_mut()
                    .for_each(|v| *v = stream + (*v - stream) * damp);
            }
        }
    }

    /// Zero normal velocity on the side walls; still water (the stream) entering at the
    /// top. The bottom, where the wake leaves, is open.
    pub(super) fn enforce_walls(&mut self) {
        if self.walls.is_closed() {
            return self.enforce_box_walls();
        }
        let n = self.n;
        for j in 0..n {
            self.u[j * (n + 1)] = 0.0;
            self.u[j * (n + 1) + n] = 0.0;
        }
        let stream = self.stream;
        self.v[n * n..].fill(stream);
    }
}
