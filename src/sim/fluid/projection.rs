//! Incompressibility: the pressure that removes the divergent part of the velocity,
//! solved exactly (see `sim::pressure`), with the open wake end at zero pressure.

use super::Fluid;
use crate::sim::pressure::PoissonSolver;

impl Fluid {
    /// Removes the divergent part of the velocity with an exact Poisson solve.
    pub(crate) fn project(&mut self) {
        if let Some(mut half) = self.take_half() {
            self.project_half(&mut half);
            return self.put_half(half);
        }
        let (n, h) = (self.n, self.h);
        // φ = div u per cell (as `divergence` computes it), row by row.
        for j in 0..n {
            let u = &self.u[j * (n + 1)..][..n + 1];
            let (v0, v1) = (&self.v[j * n..][..n], &self.v[(j + 1) * n..][..n]);
            let phi = &mut self.phi[j * n..][..n];
            for (i, p) in phi.iter_mut().enumerate() {
                *p = ((u[i + 1] - u[i]) + (v1[i] - v0[i])) / h;
            }
        }
        self.poisson
            .get_or_insert_with(|| PoissonSolver::new(n, h))
            .solve(&mut self.phi);
        for j in 0..n {
            let phi = &self.phi[j * n..][..n];
            let u = &mut self.u[j * (n + 1)..][..n + 1];
            for i in 1..n {
                u[i] -= (phi[i] - phi[i - 1]) / h;
            }
        }
        for j in 1..n {
            let (below, here) = (&self.phi[(j - 1) * n..][..n], &self.phi[j * n..][..n]);
            let v = &mut self.v[j * n..][..n];
            for ((v, p1), p0) in v.iter_mut().zip(here).zip(below) {
                *v -= (p1 - p0) / h;
            }
        }
        // A closed box (a test set-up) has no open end: ∂φ/∂y = 0 there too.
        if self.walls.is_closed() {
            return;
        }
        // The open wake end: φ = 0 on the boundary face, so the ghost cell beyond is −φ.
        // The inflow face at the top keeps the stream (∂φ/∂y = 0 there).
        for (v, p) in self.v[..n].iter_mut().zip(&self.phi[..n]) {
            *v -= 2.0 * p / h;
        }
    }

    /// Discrete divergence of cell `(i, j)`, 1/s (r-weighted in an axisymmetric slice).
    pub(crate) fn divergence(&self, i: usize, j: usize) -> f32 {
        if let Some(rings) = self.half() {
            return self.ring_divergence(rings, i, j);
        }
        let n = self.n;
        let du = self.u[j * (n + 1) + i + 1] - self.u[j * (n + 1) + i];
        let dv = self.v[(j + 1) * n + i] - self.v[j * n + i];
        (du + dv) / self.h
    }

    /// max |div u| after the last projection, 1/s (a mirror-symmetric slice: over its
    /// solved half, the mirrored one being its copy). Measured on demand, so the step does
    /// not pay for a diagnostic.
    pub(crate) fn divergence_max(&self) -> f32 {
        if let Some(rings) = self.half() {
            return self.ring_divergence_max(rings);
        }
        let n = self.n;
        (0..n * n)
            .map(|c| self.divergence(c % n, c / n).abs())
            .fold(0.0, f32::max)
    }
}
