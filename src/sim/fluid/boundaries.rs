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

    /// Relaxes the velocity in the absorbing layer towards the stream.
    pub(crate) fn absorb(&mut self, dt: f32) {
        if let Some(solved) = self.rings().map(|r| r.solved) {
            return self.absorb_half(dt, solved);
        }
        // Implicit Euler: stable for any rate and step.
        for (u, s) in self.u.iter_mut().zip(&self.sponge_u) {
            *u /= 1.0 + s * dt;
        }
        let stream = self.stream;
        for (v, s) in self.v.iter_mut().zip(&self.sponge_v) {
            *v = stream + (*v - stream) / (1.0 + s * dt);
        }
    }

    /// [`Fluid::absorb`] over the solved half of an axisymmetric slice (`columns` from
    /// the left wall, and the `u` face past the axis), rows within the layer only.
    fn absorb_half(&mut self, dt: f32, columns: usize) {
        let (n, stream) = (self.n, self.stream);
        for j in 0..n {
            let rate = self.sponge_u[j * (n + 1)];
            if rate > 0.0 {
                let damp = 1.0 / (1.0 + rate * dt);
                self.u[j * (n + 1)..][..columns + 1]
                    .iter_mut()
                    .for_each(|u| *u *= damp);
            }
        }
        for j in 0..=n {
            let rate = self.sponge_v[j * n];
            if rate > 0.0 {
                let damp = 1.0 / (1.0 + rate * dt);
                self.v[j * n..][..columns]
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
