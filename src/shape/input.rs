//! What a slice and a species must satisfy before they become a surface.
//!
//! Checked before any buffer is touched, so a refused frame leaves the last good mesh intact.

use crate::sim::SliceView;
use crate::species::Species;
use glam::Vec2;

/// Why a slice could not be turned into a surface.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShapeError {
    /// The bell needs an apex and at least one opposite pair.
    #[error("the bell has {0} points; it needs at least 3")]
    TooFewPoints(usize),
    /// Pairs are `i` and `len - 1 - i` around a middle apex, so the count must be odd.
    #[error("the bell has {0} points; it needs an odd count (pairs around one apex)")]
    EvenPointCount(usize),
    /// `rest_bell` must pair up with `bell` point by point.
    #[error("the rest bell has {rest} points but the bell has {bell}")]
    RestMismatch {
        /// Points of the bell.
        bell: usize,
        /// Points of the rest bell.
        rest: usize,
    },
    /// A point is NaN or infinite (a diverged simulation).
    #[error("{0} holds a non-finite point")]
    NonFinitePoint(&'static str),
    /// A species field the renderer uses is NaN or infinite.
    #[error("species field `{0}` is not finite")]
    NonFiniteSpecies(&'static str),
    /// The time drives the noise, so it must be a number.
    #[error("time {0} is not finite")]
    NonFiniteTime(f32),
}

/// Checks a slice, the species fields the renderer reads, and the time.
pub fn check(view: &SliceView, species: &Species, time: f32) -> Result<(), ShapeError> {
    if !time.is_finite() {
        return Err(ShapeError::NonFiniteTime(time));
    }
    let n = view.bell.len();
    if n < 3 {
        return Err(ShapeError::TooFewPoints(n));
    }
    if n.is_multiple_of(2) {
        return Err(ShapeError::EvenPointCount(n));
    }
    if view.rest_bell.len() != n {
        return Err(ShapeError::RestMismatch {
            bell: n,
            rest: view.rest_bell.len(),
        });
    }
    let finite = |p: &[Vec2]| p.iter().all(|p| p.is_finite());
    for (name, points) in [
        ("bell", view.bell),
        ("rest_bell", view.rest_bell),
        ("tentacles[0]", view.tentacles[0]),
        ("tentacles[1]", view.tentacles[1]),
        ("oral_arms[0]", view.oral_arms[0]),
        ("oral_arms[1]", view.oral_arms[1]),
    ] {
        if !finite(points) {
            return Err(ShapeError::NonFinitePoint(name));
        }
    }
    let mut trails = view.trail.offsets.iter().chain(view.oral_trail.offsets);
    if !trails.all(|d| d.is_finite()) {
        return Err(ShapeError::NonFinitePoint("trail"));
    }
    let s = species;
    for (name, v) in [
        ("thickness", s.thickness),
        ("margin_thickness_ratio", s.margin_thickness_ratio),
        ("contraction_ratio", s.contraction_ratio),
        ("tentacle_radius", s.tentacle_radius),
        ("tentacle_length_spread", s.tentacle_length_spread),
        ("manubrium_radius", s.manubrium_radius),
        ("oral_arm_width", s.oral_arm_width),
        ("oral_arm_frill", s.oral_arm_frill),
        ("structural_scale", s.structural_scale),
        ("structural_frequency", s.structural_frequency),
        ("compression_scale", s.compression_scale),
        ("compression_frequency", s.compression_frequency),
        ("unstructured_scale", s.unstructured_scale),
        ("noise_frequency_lat", s.noise_frequency_lat),
        ("noise_frequency_lon", s.noise_frequency_lon),
        ("noise_frequency_time", s.noise_frequency_time),
    ] {
        if !v.is_finite() {
            return Err(ShapeError::NonFiniteSpecies(name));
        }
    }
    Ok(())
}
