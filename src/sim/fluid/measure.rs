//! What is measured of the water, on demand (the step pays for no diagnostic):
//! divergence, speeds, kinetic energy, finiteness.

use super::Fluid;

impl Fluid {
    /// max |u| over the grid (cell-centred), m/s; NaN if any velocity is NaN.
    pub(crate) fn speed_max(&self) -> f32 {
        let n = self.n;
        let (mut max2, mut nan) = (0.0f32, false);
        for j in 0..n {
            let u = &self.u[j * (n + 1)..][..n + 1];
            let (v0, v1) = (&self.v[j * n..][..n], &self.v[(j + 1) * n..][..n]);
            for (uw, (va, vb)) in u.windows(2).zip(v0.iter().zip(v1)) {
                let (uc, vc) = (0.5 * (uw[0] + uw[1]), 0.5 * (va + vb));
                let s2 = uc * uc + vc * vc;
                max2 = max2.max(s2);
                nan |= s2.is_nan();
            }
        }
        // f32::max skips NaN; a NaN anywhere must come through.
        if nan { f32::NAN } else { max2.sqrt() }
    }

    /// A bound on the speed, m/s: `√(max|u|² + max|v|²)` over the faces, never below
    /// [`Fluid::speed_max`]; two plain reductions (no averaging, no square roots per
    /// cell), cheap enough for the step's Courant check. NaN if any velocity is NaN.
    pub(crate) fn speed_bound(&self) -> f32 {
        let largest = |field: &[f32]| {
            let (mut max, mut nan) = (0.0f32, false);
            for x in field {
                max = max.max(x.abs());
                nan |= x.is_nan();
            }
            if nan { f32::NAN } else { max }
        };
        let (u, v) = (largest(&self.u), largest(&self.v));
        (u * u + v * v).sqrt()
    }

    /// Total kinetic energy per unit depth: J/m in the plane, J per radian of an
    /// axisymmetric slice.
    pub fn kinetic_energy(&self) -> f32 {
        let Some(rings) = self.rings() else {
            let sum: f32 = self.u.iter().chain(&self.v).map(|x| x * x).sum();
            return 0.5 * self.rho * sum * self.h * self.h;
        };
        // Each face weighs its radius; the mirrored grid holds each ring twice.
        let weighted = |field: &[f32], radii: &[f32]| -> f32 {
            field
                .chunks_exact(radii.len())
                .flat_map(|row| row.iter().zip(radii).map(|(x, r)| r * x * x))
                .sum()
        };
        let sum = weighted(&self.u, &rings.face) + weighted(&self.v, &rings.cell);
        0.25 * self.rho * sum * self.h * self.h
    }

    /// Whether every velocity is finite.
    pub fn is_finite(&self) -> bool {
        self.u.iter().chain(&self.v).all(|x| x.is_finite())
    }
}
