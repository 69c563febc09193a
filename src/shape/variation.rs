//! Variation along the surface normal (paper 3.5, Fig. 9): structural lobes, compression
//! ripples and unstructured Perlin noise, the last seeded per individual.
//!
//! Amplitudes are the species' scales times `thickness` (paper: α_str = 0.375·ϑ,
//! α_unstr = 2.25·ϑ, compression up to (1.51 − 1.36)·ϑ).

use super::perlin::{pcg, perlin4};
use crate::species::Species;
use std::f32::consts::TAU;

/// Latitude below which structural and compression variation fade in. Those depend on σ
/// alone, which is undefined at the apex: unfaded they would tear the apex into a star.
pub const APEX_FADE: f32 = 0.25;

/// The three variations for one individual at one time.
#[derive(Clone, Copy, Debug)]
pub struct Variation {
    seed: u32,
    structural: f32,
    structural_frequency: f32,
    structural_abs: bool,
    compression: f32,
    compression_frequency: f32,
    unstructured: f32,
    lat_frequency: f32,
    /// Radius of the circle the longitude is wrapped on in noise space: `f_lon / 2π`, so
    /// one turn spans `f_lon` noise units (the paper's `8·d_j`) and σ = 0 meets σ = 2π.
    lon_radius: f32,
    /// `f_t · t`: the noise field's fourth coordinate.
    time: f64,
    /// The species' `tentacle_length_spread`.
    tentacle_spread: f32,
}

impl Variation {
    /// `seed` picks the individual's noise; `time` in seconds.
    pub fn new(species: &Species, seed: u32, time: f32) -> Self {
        let t = species.thickness;
        Self {
            seed,
            structural: species.structural_scale * t,
            structural_frequency: species.structural_frequency,
            structural_abs: species.structural_abs,
            compression: species.compression_scale * t,
            compression_frequency: species.compression_frequency,
            unstructured: species.unstructured_scale * t,
            lat_frequency: species.noise_frequency_lat,
            lon_radius: species.noise_frequency_lon / TAU,
            time: species.noise_frequency_time as f64 * time as f64,
            tentacle_spread: species.tentacle_length_spread,
        }
    }

    /// How much of the slice's chain tentacle `t` of this individual is drawn, in
    /// `[1 − spread, 1]`: its own for life (a hash of the seed and `t`, not noise in time).
    pub fn tentacle_reach(&self, t: usize) -> f32 {
        tentacle_reach(self.seed, t as u32, self.tentacle_spread)
    }

    /// Structural lobes `α_str·sin(f·σ)` (or `|sin|`), faded in near the apex. A
    /// fractional lobe count leaves a crease at σ = 0.
    pub fn structural(&self, sigma: f32, latitude: f32) -> f32 {
        let s = (self.structural_frequency * sigma).sin();
        let s = if self.structural_abs { s.abs() } else { s };
        self.structural * s * apex_fade(latitude)
    }

    /// Compression ripples, exumbrella only: `sin(f·σ)` mapped to [0, 1], times a factor
    /// rising linearly with the pair's contraction (0 at rest, 1 fully contracted).
    pub fn compression(&self, sigma: f32, latitude: f32, contraction: f32) -> f32 {
        let ripple = 0.5 * (1.0 + (self.compression_frequency * sigma).sin());
        self.compression * contraction * ripple * apex_fade(latitude)
    }

    /// Unstructured noise `α_unstr·d_i·QP(f_lat·d_i, f_lon·d_j, f_t·t)`, σ given as
    /// `(cos σ, sin σ)`. The `d_i` factor attenuates it to zero at the apex.
    pub fn unstructured(&self, latitude: f32, cs: (f32, f32)) -> f32 {
        self.unstructured_with(latitude, self.noise(latitude, cs))
    }

    /// The same, given the noise value `qp` there (from a [`NoiseField`] cache).
    ///
    /// [`NoiseField`]: super::noise_field::NoiseField
    pub fn unstructured_with(&self, latitude: f32, qp: f32) -> f32 {
        self.unstructured * latitude * qp
    }

    /// The noise field alone, QP in about [-1, 1], at latitude coordinate `lat` (may exceed
    /// 1: tentacles continue it below the margin).
    pub fn noise(&self, lat: f32, cs: (f32, f32)) -> f32 {
        self.noise_at(lat, cs, self.time)
    }

    /// The noise field at time coordinate `tau` (noise units, `f_t·t`).
    pub fn noise_at(&self, lat: f32, (cos, sin): (f32, f32), tau: f64) -> f32 {
        perlin4(
            self.seed,
            [
                self.lat_frequency * lat,
                self.lon_radius * cos,
                self.lon_radius * sin,
                tau as f32,
            ],
        )
    }

    /// The noise's time coordinate `f_t·t`.
    pub fn time_coordinate(&self) -> f64 {
        self.time
    }

    /// The unstructured amplitude α_unstr, m.
    pub fn unstructured_amplitude(&self) -> f32 {
        self.unstructured
    }
}

/// `1 − spread·u`, `u` in [0, 1) hashed from `seed` and tentacle `t` (integer arithmetic
/// and an exact conversion, so the vertex shader gets the same number).
pub fn tentacle_reach(seed: u32, t: u32, spread: f32) -> f32 {
    let u = (pcg(seed ^ pcg(t)) >> 8) as f32 / (1u32 << 24) as f32;
    (1.0 - spread * u).clamp(0.0, 1.0)
}

/// 0 at the apex rising smoothly to 1 at latitude [`APEX_FADE`].
pub fn apex_fade(latitude: f32) -> f32 {
    let x = (latitude / APEX_FADE).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn variation(seed: u32, time: f32) -> Variation {
        Variation::new(&Species::aurelia(), seed, time)
    }

    #[test]
    fn structural_and_compression_follow_the_paper() {
        let sp = Species::aurelia();
        let v = variation(1, 0.0);
        let a = sp.structural_scale * sp.thickness;
        let sigma = 0.3;
        let expect = a * (sp.structural_frequency * sigma).sin();
        assert!((v.structural(sigma, 1.0) - expect).abs() < 1e-7);
        assert_eq!(v.structural(sigma, 0.0), 0.0);
        // Compression: zero at rest, (0.15·ϑ)·[0,1] when contracted.
        assert_eq!(v.compression(sigma, 1.0, 0.0), 0.0);
        let peak = TAU / 4.0 / sp.compression_frequency;
        let full = sp.compression_scale * sp.thickness;
        assert!((v.compression(peak, 1.0, 1.0) - full).abs() < 1e-7);
        assert!((v.compression(peak, 1.0, 0.5) - 0.5 * full).abs() < 1e-7);
        assert!(v.compression(-peak, 1.0, 1.0).abs() < 1e-7);
    }

    #[test]
    fn noise_wraps_around_the_axis_and_differs_by_seed() {
        let v = variation(7, 3.0);
        let a = v.noise(0.6, (1.0, 0.0));
        let (s, c) = TAU.sin_cos();
        assert!((a - v.noise(0.6, (c, s))).abs() < 1e-5);
        let w = variation(8, 3.0);
        let differs = (0..20).any(|j| {
            let (s, c) = (j as f32 * 0.3).sin_cos();
            (v.noise(0.6, (c, s)) - w.noise(0.6, (c, s))).abs() > 1e-3
        });
        assert!(differs);
        assert_eq!(v.unstructured(0.0, (c, s)), 0.0);
    }
}
