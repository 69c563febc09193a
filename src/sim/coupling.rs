//! Immersed-boundary coupling (paper section 3.2, after Peskin).
//!
//! Points read the fluid velocity by bilinear interpolation and give their forces back to
//! the four nearest faces of each velocity component with the same weights, instead of
//! Peskin's wide kernel: sharper on the coarse grids we use, and the two operations are
//! exact adjoints, so spreading conserves the total force.

use super::fluid::Fluid;
use glam::Vec2;

/// Fluid velocity at each point.
pub fn interpolate_velocity(fluid: &Fluid, points: &[Vec2], out: &mut [Vec2]) {
    for (o, p) in out.iter_mut().zip(points) {
        *o = fluid.velocity_at(*p);
    }
}

/// Adds each point force (N per metre of depth) to the fluid's force density.
pub fn spread_forces(fluid: &mut Fluid, points: &[Vec2], forces: &[Vec2]) {
    for (p, f) in points.iter().zip(forces) {
        fluid.spread_force(*p, *f);
    }
}
