//! Health: a blown-up or crumpled slice is detected and restarted at rest, where the bell
//! was in the world.

use super::SliceSim;
use crate::sim::body::Body;

impl SliceSim {
    /// Whether the state is finite, physically plausible and the bell whole: its outline
    /// (subumbrella closed by the aperture chord) neither crosses itself, nor turns inside
    /// out, nor collapses (see [`Outline`](crate::sim::body::Outline)).
    pub(super) fn healthy(&self) -> bool {
        if !self.body.is_finite() || !self.speed.is_finite() || !self.oral_arms.is_finite() {
            return false;
        }
        let d = self.species.diameter;
        let c = self.body.bell_centroid();
        let span_ok = self
            .body
            .bell_points()
            .iter()
            .all(|p| (*p - c).length() < 3.0 * d);
        // Water in a jellyfish's wake moves at a few diameters per cycle at most.
        let speed_limit = 50.0 * d * self.species.contraction_frequency.max(1.0);
        span_ok && self.speed < speed_limit && !self.outline().crumpled()
    }

    /// Restarts a blown-up slice at rest at home, keeping time and distance, and moves the
    /// box so that the bell stays where it was in the world.
    pub(super) fn recover(&mut self) {
        self.fluid.clear();
        self.speed = 0.0;
        let origin = Self::rest_origin(&self.species, &self.fluid);
        self.body = Body::new(&self.species, origin, self.fluid.h);
        self.body.set_mirror_symmetric(self.mirror_symmetry);
        self.oral_arms = self.hanging_arms(&self.species);
        self.across += self.drift.x;
        self.frame.position += self.drift.y as f64;
        self.drift = glam::Vec2::ZERO;
        self.recoveries += 1;
    }
}
