//! Uniform Catmull-Rom spline through a polyline, evaluated at a fractional index.
//!
//! Uniform (index) parametrisation divides by nothing, so coincident points (a collapsed
//! bell, a zero-length tentacle) still give finite values; and resampled pairs stay matched
//! by index, as the simulation pairs its points.

use glam::Vec2;

/// The cubic through `points` at fractional index `u`, clamped to `0..=len-1`.
///
/// Interpolating: at whole `u` it returns that point. The ends are extended by reflection so
/// the curve keeps its end tangents. Empty input gives zero; non-finite `u` reads as 0.
pub fn catmull_rom(points: &[Vec2], u: f32) -> Vec2 {
    let n = points.len();
    match n {
        0 => return Vec2::ZERO,
        1 => return points[0],
        _ => {}
    }
    let u = if u.is_finite() {
        u.clamp(0.0, (n - 1) as f32)
    } else {
        0.0
    };
    // `u` is finite and not negative: truncating is flooring, without `floorf`'s call.
    let i = (u as usize).min(n - 2);
    let t = u - i as f32;
    let (p1, p2) = (points[i], points[i + 1]);
    let p0 = if i > 0 { points[i - 1] } else { 2.0 * p1 - p2 };
    let p3 = if i + 2 < n {
        points[i + 2]
    } else {
        2.0 * p2 - p1
    };
    let (t2, t3) = (t * t, t * t * t);
    0.5 * (2.0 * p1
        + (p2 - p0) * t
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
        + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_its_points_and_between_them_smoothly() {
        let pts: Vec<Vec2> = (0..6)
            .map(|i| Vec2::new(i as f32, (i as f32 * 0.7).sin()))
            .collect();
        for (i, p) in pts.iter().enumerate() {
            assert!(catmull_rom(&pts, i as f32).distance(*p) < 1e-6);
        }
        // A straight evenly spaced line is reproduced exactly, ends included.
        let line: Vec<Vec2> = (0..4)
            .map(|i| Vec2::new(i as f32, 2.0 * i as f32))
            .collect();
        for k in 0..=30 {
            let u = k as f32 * 0.1;
            assert!(catmull_rom(&line, u).distance(Vec2::new(u, 2.0 * u)) < 1e-5);
        }
    }

    #[test]
    fn degenerate_input_stays_finite() {
        assert_eq!(catmull_rom(&[], 0.5), Vec2::ZERO);
        assert_eq!(catmull_rom(&[Vec2::ONE], 3.0), Vec2::ONE);
        let same = [Vec2::new(1.0, 2.0); 5];
        assert_eq!(catmull_rom(&same, 2.3), Vec2::new(1.0, 2.0));
        assert!(catmull_rom(&same, f32::NAN).is_finite());
    }
}
