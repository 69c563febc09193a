//! Immersed-boundary coupling (paper section 3.2, after Peskin).
//!
//! Points read the fluid velocity through a kernel (see [`kernel`](super::kernel)) and give
//! their forces back to the same faces with the same weights: the two operations are exact
//! adjoints, so spreading conserves the total force. The points do not move between
//! reading the water, spreading their forces and reading it again after the fluid step,
//! so a step finds their stencils once.

use super::fluid::{Component, Fluid};
use super::kernel::{Stencil, span};
use super::response::Response;
use glam::Vec2;
use std::ops::Range;

/// The stencils of a set of points on the grid, per velocity component.
#[derive(Clone, Default)]
pub(crate) struct Coupling {
    u: Vec<Stencil>,
    v: Vec<Stencil>,
    /// The points read as their partner's mirror image (an axisymmetric slice's points
    /// past the axis), ascending.
    mirrored: Vec<Mirrored>,
    /// The rows of faces the stencils reach, both components': where the forces land.
    rows: std::ops::Range<usize>,
}

/// A point past the axis of an axisymmetric slice, read through its partner's stencils.
#[derive(Clone, Copy)]
struct Mirrored {
    point: usize,
    partner: usize,
    /// Its stencils reach the solved half, so its force is spread there.
    near: bool,
}

impl Coupling {
    /// Finds the stencils of `points` on `fluid`'s grid. `partners[i]`, where given, is the
    /// point `i` is the mirror image of: a mirror-symmetric slice's water is mirrored
    /// about its axis, so such a point reads its partner's velocity mirrored and spreads
    /// through its partner's stencils mirrored; only where those reach the solved half
    /// (near the axis), since the projection overwrites the rest (`docs/numerics.md`).
    pub(crate) fn locate(&mut self, fluid: &Fluid, points: &[Vec2], partners: &[Option<usize>]) {
        // In place: a stencil built and then moved was read back before its own stores
        // had landed (a store-forwarding stall per copy).
        self.u.resize(points.len(), Stencil::default());
        self.v.resize(points.len(), Stencil::default());
        self.mirrored.clear();
        let partner = |i: usize| partners.get(i).copied().flatten();
        for (i, ((p, u), v)) in points.iter().zip(&mut self.u).zip(&mut self.v).enumerate() {
            if let Some(partner) = partner(i) {
                let near = !fluid.beyond_the_solved_half(*p);
                self.mirrored.push(Mirrored {
                    point: i,
                    partner,
                    near,
                });
                continue;
            }
            fluid.locate(Component::U, *p, u);
            fluid.locate(Component::V, *p, v);
        }
        // A mirrored point spreads through its partner's stencils: the same rows.
        let mut rows = 0..0;
        for stencils in [&self.u, &self.v] {
            for stencil in stencils {
                rows = span(rows, stencil.rows());
            }
        }
        self.rows = rows;
    }

    /// How many points the last [`Self::locate`] read as their partners' mirrors, and how
    /// many of them spread near the axis.
    #[cfg(test)]
    pub(crate) fn mirrored(&self) -> (usize, usize) {
        let near = self.mirrored.iter().filter(|m| m.near).count();
        (self.mirrored.len(), near)
    }

    /// Fluid velocity at each located point.
    pub(crate) fn interpolate(&self, fluid: &Fluid, out: &mut [Vec2]) {
        let mut skip = self.mirrored.iter().map(|m| m.point).peekable();
        for (i, ((o, su), sv)) in out.iter_mut().zip(&self.u).zip(&self.v).enumerate() {
            if skip.next_if_eq(&i).is_some() {
                continue;
            }
            *o = Vec2::new(su.sample(&fluid.u), sv.sample(&fluid.v));
        }
        // The water is mirrored about the axis: `u` odd, `v` even.
        for m in &self.mirrored {
            out[m.point] = Vec2::new(-out[m.partner].x, out[m.partner].y);
        }
    }

    /// Adds each located point's force (N per unit of the slice's depth: a metre of a
    /// planar slice, a radian of an axisymmetric one's rings) to the fluid's force
    /// density, over each face's volume per unit depth.
    pub(crate) fn spread(&self, fluid: &mut Fluid, forces: &[Vec2]) {
        let n = fluid.n;
        fluid.force_in_rows(self.rows.clone());
        let (scale_u, scale_v) = (&fluid.spread_u, &fluid.spread_v);
        let (force_u, force_v) = (&mut fluid.force_u, &mut fluid.force_v);
        let mut skip = self.mirrored.iter().map(|m| m.point).peekable();
        for (i, ((f, su), sv)) in forces.iter().zip(&self.u).zip(&self.v).enumerate() {
            if skip.next_if_eq(&i).is_some() {
                continue;
            }
            su.spread(f.x, scale_u, force_u);
            sv.spread(f.y, scale_v, force_v);
        }
        let (mirror_u, mirror_v) = (
            |a| Component::U.mirrored_column(a, n),
            |a| Component::V.mirrored_column(a, n),
        );
        for m in self.mirrored.iter().filter(|m| m.near) {
            let f = forces[m.point];
            self.u[m.partner].spread_mirrored(f.x, scale_u, force_u, mirror_u);
            self.v[m.partner].spread_mirrored(f.y, scale_v, force_v, mirror_v);
        }
    }

    /// Writes over `water` how far each of its points moves in a step of `dt` for a unit
    /// force on each (and on its mirror image, where it has one): what one samples of the
    /// other's spread, `dt²/ρ` times their stencils' overlap. The whole grid is counted,
    /// as if the half past the axis were stepped too: the water there is the mirror of the
    /// solved half, and so is every force, so the overlaps are the same.
    pub(crate) fn respond(&self, fluid: &Fluid, dt: f32, water: &mut Response) {
        water.clear();
        let (n, per_force) = (fluid.n, dt * dt / fluid.rho);
        let components = [
            (&self.u, &fluid.spread_u, Component::U, -1.0),
            (&self.v, &fluid.spread_v, Component::V, 1.0),
        ];
        let meet = |x: Range<usize>, y: Range<usize>| x.start < y.end && y.start < x.end;
        for p in 0..water.len() {
            let a = water.points()[p];
            for q in p..(p + water.reach() + 1).min(water.len()) {
                let b = water.points()[q];
                let meets = |s: &[Stencil]| {
                    meet(s[a].rows(), s[b].rows()) && meet(s[a].columns(), s[b].columns())
                };
                if !meets(&self.u) && !meets(&self.v) {
                    continue;
                }
                for (c, &(stencils, scale, component, image)) in components.iter().enumerate() {
                    let (sa, sb) = (&stencils[a], &stencils[b]);
                    let straight = sa.overlap(sb, scale);
                    if straight == 0.0 {
                        // Stencils that do not meet meet no mirror image either: an
                        // image past the axis is further from a solved point than it.
                        continue;
                    }
                    // What `of` samples of `by`'s mirror image, where that reaches it.
                    let mirrored = |of: &Stencil, by: &Stencil| {
                        let columns = by.columns();
                        let reflected = [columns.start, columns.end - 1]
                            .map(|col| component.mirrored_column(col, n));
                        if let [Some(far), Some(near)] = reflected
                            && !meet(near..far + 1, of.columns())
                        {
                            return 0.0;
                        }
                        image
                            * of.overlap_mirrored(by, scale, |col| {
                                component.mirrored_column(col, n)
                            })
                    };
                    let mut a_of_b = straight;
                    if water.imaged(q) {
                        a_of_b += mirrored(sa, sb);
                    }
                    water.add(c, p, q, per_force * a_of_b);
                    if q != p {
                        let mut b_of_a = straight;
                        if water.imaged(p) {
                            b_of_a += mirrored(sb, sa);
                        }
                        water.add(c, q, p, per_force * b_of_a);
                    }
                }
            }
        }
    }
}
