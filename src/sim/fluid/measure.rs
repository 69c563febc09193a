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
        let (u, v) = (largest_magnitude(&self.u), largest_magnitude(&self.v));
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

/// max |x| over `field`, NaN if any `x` is NaN.
///
/// On x86_64 four SSE2 maxima of four lanes each (`maxps` on the magnitudes, a running
/// "unordered" mask for NaN): the magnitudes are non-negative, so their float order is
/// their bit order and the result is [`largest_magnitude_bits`]' to the bit, at half its
/// cost (SSE2 has no unsigned integer maximum: that one takes five instructions a vector).
/// With AVX, the same eight lanes at a time.
fn largest_magnitude(field: &[f32]) -> f32 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: this processor has AVX (asked above).
        return unsafe { avx::largest_magnitude(field) };
    }
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: SSE2 is in every x86-64 target's baseline, so it is always enabled.
        unsafe { sse2::largest_magnitude(field) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        largest_magnitude_bits(field)
    }
}

/// max |x| over `field`, NaN if any `x` is NaN: on the bit patterns with the sign
/// cleared, which order as the magnitudes do (every NaN above infinity), so the reduction
/// is a plain integer maximum that vectorises, where `f32::max` (which skips NaN) does not.
fn largest_magnitude_bits(field: &[f32]) -> f32 {
    const LANES: usize = 8;
    let magnitude = |x: &f32| x.to_bits() & 0x7fff_ffff;
    let mut lanes = [0u32; LANES];
    let chunks = field.chunks_exact(LANES);
    let rest = chunks.remainder().iter().map(magnitude).max().unwrap_or(0);
    for chunk in chunks {
        for (lane, x) in lanes.iter_mut().zip(chunk) {
            *lane = (*lane).max(magnitude(x));
        }
    }
    let bits = lanes.into_iter().fold(rest, u32::max);
    if bits > f32::INFINITY.to_bits() {
        f32::NAN
    } else {
        f32::from_bits(bits)
    }
}

#[cfg(target_arch = "x86_64")]
mod sse2 {
    use std::arch::x86_64::*;

    /// See [`super::largest_magnitude`].
    #[target_feature(enable = "sse2")]
    pub(super) fn largest_magnitude(field: &[f32]) -> f32 {
        let sign = _mm_castsi128_ps(_mm_set1_epi32(0x7fff_ffff));
        // Four running maxima, so that each waits only on its own last `maxps`.
        let mut most = [_mm_setzero_ps(); 4];
        let mut unordered = _mm_setzero_ps();
        let mut blocks = field.chunks_exact(16);
        for block in &mut blocks {
            for (k, most) in most.iter_mut().enumerate() {
                // SAFETY: `block` holds sixteen values, four at each `k`.
                let x = _mm_and_ps(unsafe { _mm_loadu_ps(block[4 * k..].as_ptr()) }, sign);
                unordered = _mm_or_ps(unordered, _mm_cmpunord_ps(x, x));
                *most = _mm_max_ps(*most, x);
            }
        }
        let most = _mm_max_ps(_mm_max_ps(most[0], most[1]), _mm_max_ps(most[2], most[3]));
        let mut lanes = [0.0f32; 4];
        // SAFETY: `lanes` holds four values.
        unsafe { _mm_storeu_ps(lanes.as_mut_ptr(), most) };
        // The last few (under sixteen) by the bit-pattern reduction.
        let rest = super::largest_magnitude_bits(blocks.remainder());
        if _mm_movemask_ps(unordered) != 0 || rest.is_nan() {
            return f32::NAN;
        }
        lanes.into_iter().fold(rest, f32::max)
    }
}

#[cfg(target_arch = "x86_64")]
mod avx {
    use std::arch::x86_64::*;

    /// [`super::sse2::largest_magnitude`], eight lanes wide.
    #[target_feature(enable = "avx")]
    pub(super) fn largest_magnitude(field: &[f32]) -> f32 {
        let sign = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fff_ffff));
        let mut most = [_mm256_setzero_ps(); 4];
        let mut unordered = _mm256_setzero_ps();
        let mut blocks = field.chunks_exact(32);
        for block in &mut blocks {
            for (k, most) in most.iter_mut().enumerate() {
                // SAFETY: `block` holds thirty-two values, eight at each `k`.
                let x = _mm256_and_ps(unsafe { _mm256_loadu_ps(block[8 * k..].as_ptr()) }, sign);
                unordered = _mm256_or_ps(unordered, _mm256_cmp_ps::<_CMP_UNORD_Q>(x, x));
                *most = _mm256_max_ps(*most, x);
            }
        }
        let most = _mm256_max_ps(
            _mm256_max_ps(most[0], most[1]),
            _mm256_max_ps(most[2], most[3]),
        );
        let mut lanes = [0.0f32; 8];
        // SAFETY: `lanes` holds eight values.
        unsafe { _mm256_storeu_ps(lanes.as_mut_ptr(), most) };
        let rest = super::largest_magnitude_bits(blocks.remainder());
        if _mm256_movemask_ps(unordered) != 0 || rest.is_nan() {
            return f32::NAN;
        }
        lanes.into_iter().fold(rest, f32::max)
    }
}

#[cfg(test)]
mod tests {
    use super::{largest_magnitude, largest_magnitude_bits};

    #[test]
    fn the_largest_magnitude_is_exact_and_sees_nan_and_infinity() {
        // Every length up to three blocks and a remainder (of sixteen, and of AVX's
        // thirty-two), with the largest anywhere.
        for len in 0..101 {
            for at in 0..len {
                let mut field: Vec<f32> =
                    (0..len).map(|k| ((k * 29) % 17) as f32 * -0.03).collect();
                field[at] = -7.5;
                assert_eq!(largest_magnitude(&field).to_bits(), 7.5f32.to_bits());
                assert_eq!(largest_magnitude_bits(&field).to_bits(), 7.5f32.to_bits());
                // SAFETY: SSE2 is in every x86-64 target's baseline.
                #[cfg(target_arch = "x86_64")]
                assert_eq!(
                    unsafe { super::sse2::largest_magnitude(&field) }.to_bits(),
                    7.5f32.to_bits()
                );
                field[at] = f32::NAN;
                assert!(largest_magnitude(&field).is_nan(), "{len} {at}");
                #[cfg(target_arch = "x86_64")]
                assert!(unsafe { super::sse2::largest_magnitude(&field) }.is_nan());
            }
        }
        let mut field: Vec<f32> = (0..203)
            .map(|k| ((k * 37) % 101) as f32 * 0.013 - 0.6)
            .collect();
        let plain = field.iter().fold(0.0f32, |m, x| m.max(x.abs()));
        assert_eq!(largest_magnitude(&field).to_bits(), plain.to_bits());
        assert_eq!(largest_magnitude(&[]), 0.0);
        assert_eq!(largest_magnitude(&[-0.0, 0.0]).to_bits(), 0.0f32.to_bits());
        field[201] = -f32::INFINITY;
        assert_eq!(largest_magnitude(&field), f32::INFINITY);
        field[3] = -f32::NAN;
        assert!(largest_magnitude(&field).is_nan());
    }
}
