//! Four-dimensional gradient (Perlin) noise that the CPU and the GPU evaluate alike.
//!
//! The surface's unstructured variation is evaluated here on the CPU and, for template
//! meshes, by the vertex shader (`surface.wgsl` mirrors this file line for line). So the
//! lattice gradients come from an integer hash of the corner and the individual's seed,
//! not from a permutation table, and everything is `f32` and wrapping `u32` arithmetic,
//! which WGSL has too. Gradients are the 32 edge midpoints of the 4D hypercube (one
//! component 0, three ±1), blended with the quintic fade: values lie in about [-1, 1] and
//! are clamped there, and the noise is 0 at every lattice point.

/// Noise at `p` for the individual `seed`.
pub fn perlin4(seed: u32, p: [f32; 4]) -> f32 {
    let cell = p.map(|x| x.floor());
    let corner = cell.map(|c| c as i32);
    let d = [0, 1, 2, 3].map(|i| p[i] - cell[i]);
    let f = d.map(fade);
    let mut sum = 0.0;
    // Corners in binary order, bit i set = +1 along axis i; multilinear blend of the
    // gradient ramps with the fade weights.
    for c in 0..16 {
        let mut lattice = corner;
        let mut offset = d;
        let mut weight = 1.0;
        for i in 0..4 {
            if (c >> i) & 1 == 1 {
                lattice[i] += 1;
                offset[i] -= 1.0;
                weight *= f[i];
            } else {
                weight *= 1.0 - f[i];
            }
        }
        sum += weight * gradient(hash(seed, lattice), offset);
    }
    sum.clamp(-1.0, 1.0)
}

/// Quintic fade `6t⁵ − 15t⁴ + 10t³`: zero first and second derivatives at 0 and 1.
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The dot product of the corner's gradient with `d`: bits 3–4 of `h` pick the zero
/// component, bits 0–2 the signs of the other three.
fn gradient(h: u32, d: [f32; 4]) -> f32 {
    let zero = ((h >> 3) & 3) as usize;
    let mut sum = 0.0;
    let mut sign_bit = 0;
    for (i, &x) in d.iter().enumerate() {
        if i == zero {
            continue;
        }
        let negative = (h >> sign_bit) & 1 == 1;
        sum += if negative { -x } else { x };
        sign_bit += 1;
    }
    sum
}

/// A hash of the lattice corner and the seed (PCG output permutation applied per
/// coordinate).
fn hash(seed: u32, corner: [i32; 4]) -> u32 {
    let mut h = pcg(seed ^ 0x9E37_79B9);
    for c in corner {
        h = pcg(h ^ c as u32);
    }
    h
}

/// One step of PCG-RXS-M-XS (O'Neill 2014), as a 32-bit integer hash.
pub(crate) fn pcg(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scattered point in [-5, 5)⁴.
    fn sample(i: u32) -> [f32; 4] {
        [0, 1, 2, 3].map(|k| (pcg(i * 4 + k) % 10_000) as f32 * 1e-3 - 5.0)
    }

    #[test]
    fn zero_at_lattice_points_and_bounded() {
        for x in -3..3 {
            for w in -2..2 {
                let p = [x as f32, 1.0, -2.0, w as f32];
                assert_eq!(perlin4(7, p), 0.0);
            }
        }
        let values: Vec<f32> = (0..4000).map(|i| perlin4(3, sample(i))).collect();
        assert!(values.iter().all(|v| v.abs() <= 1.0));
        let mean = values.iter().sum::<f32>() / values.len() as f32;
        let rms = (values.iter().map(|v| v * v).sum::<f32>() / values.len() as f32).sqrt();
        assert!(mean.abs() < 0.03, "mean {mean}");
        // Perlin noise in 4D with these gradients: an rms of about a third of the range.
        assert!((0.2..0.5).contains(&rms), "rms {rms}");
    }

    #[test]
    fn continuous_and_smooth() {
        // A step of 1e-3 changes the value by at most the gradient bound (√3 per unit
        // along one axis, times the fade's slope of at most 1.875) times the step.
        for i in 0..500 {
            let p = sample(i + 9000);
            for axis in 0..4 {
                let mut q = p;
                q[axis] += 1e-3;
                let change = (perlin4(9, q) - perlin4(9, p)).abs();
                assert!(change < 6e-3, "jump {change} at {p:?} along {axis}");
            }
        }
    }

    #[test]
    fn seeds_give_different_fields() {
        let p = [0.3, 1.7, -0.4, 2.2];
        let differ = (0..50).filter(|&s| (perlin4(s, p) - perlin4(s + 1, p)).abs() > 1e-3);
        assert!(differ.count() > 40);
    }

    #[test]
    fn the_slope_at_a_lattice_point_is_an_edge_midpoint_of_the_hypercube() {
        // The fade is flat at the corners, so at a lattice point the noise rises along the
        // corner's own gradient: one component 0, three ±1 (central differences).
        let delta = 1e-3;
        for seed in 0..20 {
            let corner = [2.0, -1.0, 0.0, 3.0 + seed as f32];
            let slope = [0, 1, 2, 3].map(|axis| {
                let (mut up, mut down) = (corner, corner);
                up[axis] += delta;
                down[axis] -= delta;
                (perlin4(seed, up) - perlin4(seed, down)) / (2.0 * delta)
            });
            let zeros = slope.iter().filter(|g| g.abs() < 1e-3).count();
            let units = slope
                .iter()
                .filter(|g| (g.abs() - 1.0).abs() < 1e-3)
                .count();
            assert_eq!((zeros, units), (1, 3), "seed {seed}: slope {slope:?}");
        }
    }
}
