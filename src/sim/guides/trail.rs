//! The guides as the surface reads them: an offset at any angle around the margin and any
//! fraction of a tentacle's length, bilinear between the guides and their nodes.

use super::GUIDE_NODES;
use glam::Vec3;
use std::f32::consts::TAU;

/// The guide chains' offsets from where the slice draws the fringe, `guides × nodes`
/// (body frame, m); empty where the fringe follows the slice alone.
#[derive(Clone, Copy, Debug)]
pub struct Trail<'a> {
    /// Guide by guide, root first.
    pub offsets: &'a [Vec3],
    /// Nodes of each guide, its root included: [`GUIDE_NODES`] as the guides are
    /// simulated, [`THIN_NODES`] as a far jellyfish draws them ([`Trail::thin_into`]).
    pub nodes: usize,
}

/// Nodes of each guide of a thinned trail: its root, its middle and its tip.
pub const THIN_NODES: usize = 3;

impl Default for Trail<'_> {
    fn default() -> Self {
        Trail::NONE
    }
}

impl<'a> Trail<'a> {
    /// No guides: the fringe as the slice draws it.
    pub const NONE: Trail<'static> = Trail {
        offsets: &[],
        nodes: GUIDE_NODES,
    };

    /// The guides as simulated: `GUIDE_NODES` nodes each.
    pub fn new(offsets: &'a [Vec3]) -> Self {
        Self {
            offsets,
            nodes: GUIDE_NODES,
        }
    }

    /// Guides around the margin.
    pub fn guides(&self) -> usize {
        self.offsets.len() / self.nodes
    }

    /// The offset of a tentacle at angle `sigma` around the axis, `fraction` of the way
    /// from its root (0) to the tip of its chain (1). The packed shape's
    /// `trail_offset` and the vertex shader's are this function.
    pub fn at(&self, sigma: f32, fraction: f32) -> Vec3 {
        let n = self.nodes;
        between(self.guides(), n, sigma, fraction, |g, m| {
            self.offsets[g * n + m]
        })
    }

    /// The offset of guide `g`'s own tube (an oral tube is its own guide), `fraction` of
    /// the way from its root to its tip; zero for a guide it does not have.
    pub fn along(&self, g: usize, fraction: f32) -> Vec3 {
        let n = self.nodes;
        match self.offsets.get(g * n..(g + 1) * n) {
            Some(nodes) => along(n, fraction, |m| nodes[m]),
            None => Vec3::ZERO,
        }
    }

    /// Writes the trail as a far jellyfish draws it into `out`: at most `guides` guides,
    /// evenly around the margin, each its root, middle and tip ([`THIN_NODES`]) read from
    /// this trail where they lie. Where `guides` divides this trail's guides, and its
    /// nodes' middle is a node, these are its own nodes. Returns the thinned trail.
    pub fn thin_into<'b>(&self, guides: usize, out: &'b mut Vec<Vec3>) -> Trail<'b> {
        out.clear();
        let (all, n) = (self.guides(), self.nodes);
        let guides = guides.min(all);
        for g in 0..guides {
            // Its own nodes where it has them (what `at` reads there, without the search).
            if all.is_multiple_of(guides) && n % 2 == 1 {
                let own = &self.offsets[g * (all / guides) * n..];
                out.extend([Vec3::ZERO, own[n / 2], own[n - 1]]);
            } else {
                let sigma = TAU * g as f32 / guides as f32;
                out.extend([Vec3::ZERO, self.at(sigma, 0.5), self.at(sigma, 1.0)]);
            }
        }
        Trail {
            offsets: out,
            nodes: THIN_NODES,
        }
    }
}

/// Linear between one guide's `nodes` nodes (`node(m)`) at `fraction` of the way down: what
/// [`Trail::along`] and the packed shape's CPU mirror both read.
pub fn along(nodes: usize, fraction: f32, node: impl Fn(usize) -> Vec3) -> Vec3 {
    let along = fraction.clamp(0.0, 1.0) * (nodes - 1) as f32;
    let m = (along as usize).min(nodes - 2);
    let v = along - m as f32;
    node(m) + (node(m + 1) - node(m)) * v
}

/// Bilinear between `guides` guides' `nodes` nodes each (`node(g, m)`) at angle `sigma` and `fraction`
/// of the way down: what [`Trail::at`] and the packed shape's CPU mirror both read.
pub fn between(
    guides: usize,
    nodes: usize,
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
    let on = |g: usize| along(nodes, fraction, |m| node(g, m));
    on(g) + (on(next) - on(g)) * w
}
