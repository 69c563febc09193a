//! The guides as the surface reads them: an offset at any angle around the margin and any
//! fraction of a tentacle's length, bilinear between the guides and their nodes.

use super::GUIDE_NODES;
use glam::Vec3;
use std::f32::consts::TAU;

/// The guide chains' offsets from where the slice draws the fringe, `guides ×
/// GUIDE_NODES` (body frame, m); empty where the fringe follows the slice alone.
#[derive(Clone, Copy, Debug, Default)]
pub struct Trail<'a> {
    /// Guide by guide, root first.
    pub offsets: &'a [Vec3],
}

impl Trail<'_> {
    /// No guides: the fringe as the slice draws it.
    pub const NONE: Trail<'static> = Trail { offsets: &[] };

    /// Guides around the margin.
    pub fn guides(&self) -> usize {
        self.offsets.len() / GUIDE_NODES
    }

    /// The offset of a tentacle at angle `sigma` around the axis, `fraction` of the way
    /// from its root (0) to the tip of its chain (1). The packed shape's
    /// `trail_offset` and the vertex shader's are this function.
    pub fn at(&self, sigma: f32, fraction: f32) -> Vec3 {
        between(self.guides(), sigma, fraction, |g, m| {
            self.offsets[g * GUIDE_NODES + m]
        })
    }

    /// The offset of guide `g`'s own tube (an oral tube is its own guide), `fraction` of
    /// the way from its root to its tip; zero for a guide it does not have.
    pub fn along(&self, g: usize, fraction: f32) -> Vec3 {
        match self.offsets.get(g * GUIDE_NODES..(g + 1) * GUIDE_NODES) {
            Some(nodes) => along(fraction, |m| nodes[m]),
            None => Vec3::ZERO,
        }
    }
}

/// Linear between one guide's nodes (`node(m)`) at `fraction` of the way down: what
/// [`Trail::along`] and the packed shape's CPU mirror both read.
pub fn along(fraction: f32, node: impl Fn(usize) -> Vec3) -> Vec3 {
    let along = fraction.clamp(0.0, 1.0) * (GUIDE_NODES - 1) as f32;
    let m = (along as usize).min(GUIDE_NODES - 2);
    let v = along - m as f32;
    node(m) + (node(m + 1) - node(m)) * v
}

/// Bilinear between `guides` guides' nodes (`node(g, m)`) at angle `sigma` and `fraction`
/// of the way down: what [`Trail::at`] and the packed shape's CPU mirror both read.
pub fn between(
    guides: usize,
    sigma: f32,
    fraction: f32,
    node: impl Fn(usize, usize) -> Vec3,
) -> Vec3 {
    if guides == 0 {
        return Vec3::ZERO;
    }
    let around = (sigma / TAU).rem_euclid(1.0) * guides as f32;
    let g = (around as usize).min(guides - 1);
    let (w, next) = (around - g as f32, (g + 1) % guides);
    let on = |g: usize| along(fraction, |m| node(g, m));
    on(g) + (on(next) - on(g)) * w
}
