//! The unstructured noise at the mesh's fixed samples, blended in time between knots.
//!
//! Every vertex keeps its latitude and longitude from frame to frame, and the noise's time
//! coordinate crawls (paper: 0.01·t, a 6000th of a noise cell per frame at 60 Hz). So the
//! field is evaluated at knots [`KNOT`] noise units apart in time and blended linearly
//! between them: exact at the knots, off by KNOT²/8 of the field's curvature between (under
//! 1e-3 of its ±1 range, tested), and one evaluation per sample every KNOT/f_t seconds
//! (2.5 s) instead of every frame, where it made up most of a frame's cost. Knots are offset per seed
//! so that a school does not refresh in one frame. Values depend only on seed, species and
//! time, never on the frames before.

use super::variation::Variation;

/// Knot spacing in noise units of time.
pub const KNOT: f64 = 0.025;

/// Noise values at a fixed list of samples, cached between frames.
#[derive(Clone, Debug, Default)]
pub struct NoiseField {
    /// Latitude coordinate (may exceed 1 on tentacles) and `(cos σ, sin σ)` per sample.
    samples: Vec<(f32, (f32, f32))>,
    key: Option<NoiseKey>,
    knot: Option<i64>,
    early: Vec<f32>,
    late: Vec<f32>,
    /// QP at each sample for the current time, in about [-1, 1].
    pub values: Vec<f32>,
}

/// What the cached knots depend on besides time: the individual and the spatial frequencies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoiseKey {
    /// The individual's seed.
    pub seed: u32,
    /// The latitudinal frequency, as bits so that the key compares exactly.
    pub lat_frequency_bits: u32,
    /// The longitudinal frequency's bits.
    pub lon_frequency_bits: u32,
}

impl NoiseField {
    /// Replaces the sample list (on a resolution change); drops the cached knots.
    pub fn set_samples(&mut self, samples: impl Iterator<Item = (f32, (f32, f32))>) {
        self.samples.clear();
        self.samples.extend(samples);
        self.knot = None;
        let n = self.samples.len();
        for v in [&mut self.early, &mut self.late, &mut self.values] {
            v.clear();
            v.resize(n, 0.0);
        }
    }

    /// Brings `values` to the variation's time. A zero amplitude skips the evaluation.
    pub fn update(&mut self, variation: &Variation, key: NoiseKey) {
        if variation.unstructured_amplitude() == 0.0 {
            self.values.iter_mut().for_each(|v| *v = 0.0);
            self.knot = None;
            return;
        }
        if self.key != Some(key) {
            self.key = Some(key);
            self.knot = None;
        }
        let phase = seed_phase(key.seed);
        let x = variation.time_coordinate() / KNOT + phase;
        let knot = x.floor();
        let w = (x - knot) as f32;
        let knot = knot as i64;
        let at = |k: i64, out: &mut Vec<f32>, samples: &[(f32, (f32, f32))]| {
            let tau = (k as f64 - phase) * KNOT;
            for (o, &(lat, cs)) in out.iter_mut().zip(samples) {
                *o = variation.noise_at(lat, cs, tau);
            }
        };
        match self.knot {
            Some(k) if k == knot => {}
            Some(k) if k + 1 == knot => {
                std::mem::swap(&mut self.early, &mut self.late);
                at(knot + 1, &mut self.late, &self.samples);
            }
            _ => {
                at(knot, &mut self.early, &self.samples);
                at(knot + 1, &mut self.late, &self.samples);
            }
        }
        self.knot = Some(knot);
        for ((v, a), b) in self.values.iter_mut().zip(&self.early).zip(&self.late) {
            *v = a + (b - a) * w;
        }
    }
}

/// A per-seed offset of the knots in [0, 1) knot spacings (Fibonacci hashing).
fn seed_phase(seed: u32) -> f64 {
    (seed.wrapping_mul(0x9E37_79B9) >> 8) as f64 / (1u32 << 24) as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::species::Species;

    fn field_at(time: f32, seed: u32, history: &[f32]) -> Vec<f32> {
        let sp = Species::aurelia();
        let key = NoiseKey {
            seed,
            lat_frequency_bits: 0,
            lon_frequency_bits: 0,
        };
        let mut f = NoiseField::default();
        f.set_samples((0..40).map(|i| {
            let (s, c) = (i as f32 * 0.4).sin_cos();
            (i as f32 / 30.0, (c, s))
        }));
        for &t in history.iter().chain([&time]) {
            f.update(&Variation::new(&sp, seed, t), key);
        }
        f.values.clone()
    }

    #[test]
    fn values_follow_the_exact_field_and_not_the_history() {
        let sp = Species::aurelia();
        let (seed, time) = (11, 123.4);
        let exact = Variation::new(&sp, seed, time);
        let cached = field_at(time, seed, &[]);
        for (i, v) in cached.iter().enumerate() {
            let (s, c) = (i as f32 * 0.4).sin_cos();
            let e = exact.noise(i as f32 / 30.0, (c, s));
            assert!((v - e).abs() < 1e-3, "sample {i}: {v} vs {e}");
        }
        // Same result whether reached directly, step by step, or after going back in time.
        let steps: Vec<f32> = (0..200).map(|i| 100.0 + i as f32 * 0.25).collect();
        assert_eq!(field_at(time, seed, &steps), cached);
        assert_eq!(field_at(time, seed, &[500.0, 0.0]), cached);
        assert_ne!(field_at(time, seed + 1, &[]), cached);
    }
}
