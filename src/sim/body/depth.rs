//! What one unit of the slice's depth is: a metre of a planar slice, or a radian of the
//! rings an axisymmetric slice is made of.
//!
//! Every element's stiffness, every point's mass and the tentacles' drag are per unit
//! depth. In the plane that unit is the same everywhere; in r–z a point is a ring, and its
//! share of the wall, the water and the fringe grows with its radius, so forces per radian
//! between points at different radii still balance along the axis (action and reaction
//! act on the same element) while the water feels each ring's force over its own
//! circumference.

use crate::species::{SliceGeometry, Species};
use glam::Vec2;

/// Per unit of what depth the body's elements are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Depth {
    /// A metre of an infinitely long bell.
    Planar,
    /// A radian of rings about the vertical line `x = axis`. A ring nearer the axis than
    /// `floor` weighs as if it were at `floor`: the ring on the axis is a point, and
    /// stands for the disc the immersed boundary's kernel smears it over.
    Rings { axis: f32, floor: f32 },
}

impl Depth {
    /// The depth of `species`' slice about the vertical through `axis`, on cells of size
    /// `h`. Rings weigh at least as much as one a quarter of the boundary's width out (the
    /// kernel's reach, a property of the bell): with the grid's h/4 instead, the floppy,
    /// light rings about the apex changed with the grid and a prolate bell's stroke by up
    /// to 40% between neighbouring grids.
    pub(crate) fn new(species: &Species, axis: f32, h: f32) -> Self {
        match species.slice_geometry {
            SliceGeometry::Planar => Depth::Planar,
            SliceGeometry::Axisymmetric => Depth::Rings {
                axis,
                floor: (0.25 * species.boundary_width * species.diameter).max(0.25 * h),
            },
        }
    }

    /// How much of a unit the element at `p` is: 1 in the plane, its ring's radius (m) in
    /// r–z.
    pub(crate) fn at(self, p: Vec2) -> f32 {
        match self {
            Depth::Planar => 1.0,
            Depth::Rings { axis, floor } => (p.x - axis).abs().max(floor),
        }
    }

    /// Whether points are rings.
    pub(crate) fn rings(self) -> bool {
        matches!(self, Depth::Rings { .. })
    }
}
