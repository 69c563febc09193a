//! The elastic elements of the bell: Hookean springs along the subumbrella and the
//! tentacles, angular springs (hinges) holding its curvature, the hoop bending of an r–z
//! bell's rings, and muscle springs across it.
//! Each is written as scalar constraints `C(x)` with energy `½·k·C²`, the form the
//! implicit solve linearises.

use super::Body;
use super::half::{Weights, counted};
use glam::Vec2;

/// A Hookean spring between two points.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Spring {
    /// One end's point index.
    pub(crate) a: usize,
    /// The other end's.
    pub(crate) b: usize,
    /// Rest length, m.
    pub(crate) rest: f32,
    /// N/m per metre of depth: modulus × cross-section / rest length.
    pub(crate) stiffness: f32,
    /// Strain beyond which the spring stiffens [`STIFFENING`]-fold, if any.
    pub(crate) strain_limit: Option<f32>,
}

/// Tentacle strain at which the tissue stiffens (Megill: mesoglea is linear "except for
/// extremely large stresses, where it becomes more stiff"). Without it the soft tentacle
/// springs (1/100 of the bell's cross-section) let the jet stretch tentacles to several
/// times their length within a few strokes.
pub(crate) const TENTACLE_STRAIN_LIMIT: f32 = 0.1;
/// Hinge bending beyond which the mesoglea stiffens [`HINGE_STIFFENING`]-fold, rad. With
/// plate-bending hinges alone, the wake of the 10-diameter box turned the bell inside out
/// after about a dozen strokes; a gentle knee keeps the stroke soft and the bell upright.
pub(crate) const BEND_LIMIT: f32 = 0.25;
/// Hinge stiffening beyond [`BEND_LIMIT`]; a sharper knee (10×, 100×) made strokes jitter.
pub(crate) const HINGE_STIFFENING: f32 = 3.0;
/// How much stiffer a spring gets beyond its strain limit.
pub(crate) const STIFFENING: f32 = 100.0;

/// An angular spring holding the angle at `b` between `a` and `c`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hinge {
    /// One neighbour's point index.
    pub(crate) a: usize,
    /// The point the angle is at.
    pub(crate) b: usize,
    /// The other neighbour's.
    pub(crate) c: usize,
    /// Signed rest angle from `a - b` to `c - b`, rad.
    pub(crate) rest: f32,
    /// N·m/rad per metre of depth.
    pub(crate) stiffness: f32,
    /// Bending (rad from rest) beyond which the hinge stiffens [`HINGE_STIFFENING`]-fold.
    pub(crate) bend_limit: f32,
    /// The least squared length (m²) either arm is read at: a tenth of the shorter arm
    /// at rest. The angle's gradient is 1/length across an arm, so an arm crushed to
    /// nothing (a fringe's points pushed out of the bell onto one spot) gave the solve a
    /// stiffness its factor could not hold, and the slice a NaN.
    pub(crate) least_arm2: f32,
}

/// The hoop bending of one segment of an axisymmetric bell: a shell of revolution bends
/// around its axis too, by κ_θ = sin ψ / r (ψ the meridian's slope). Its energy per radian,
/// ½·D·Δs·r·(Δκ_θ)², is ½·k·(Δ sin ψ)² with k = D·Δs / r. The hinges hold only the
/// meridian's own curvature, whose stiffness per radian vanishes at the axis; without this
/// the apex of a flat bell folded into a cone (a cone's hoop curvature is unbounded there)
/// and a moon jelly of the recorded 155 mm buckled under its own stroke.
#[derive(Clone, Copy, Debug)]
pub(crate) struct HoopBend {
    /// The segment's first point.
    pub(crate) a: usize,
    /// Its second.
    pub(crate) b: usize,
    /// sin ψ at rest, the segment's slope from a to b.
    pub(crate) rest: f32,
    /// N·m per radian of rings: bending rigidity × segment length / radius.
    pub(crate) stiffness: f32,
}

/// A muscle across the bell, driven by the contraction function.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Muscle {
    /// The point on one side of the bell.
    pub(crate) a: usize,
    /// Its opposite point.
    pub(crate) b: usize,
    /// Rest length when relaxed, m.
    pub(crate) relaxed: f32,
    /// Current rest length, m: the contraction's (a spring's), or the shortest length a
    /// force generator pulls to.
    pub(crate) rest: f32,
    /// N/m per metre of depth (per radian of rings), at full activation.
    pub(crate) stiffness: f32,
    /// 0 nearest the apex, 1 at the margin: where the staggered expansion is slowest.
    pub(crate) level: f32,
    /// How the contraction function drives it.
    pub(crate) drive: Drive,
    /// How strongly it pulls, 0 (let go) to 1 (the full stroke); a spring's is always 1.
    pub(crate) activation: f32,
}

/// How the contraction function drives a muscle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Drive {
    /// The paper's ([`MuscleLaw::Length`](crate::species::MuscleLaw)): the function sets
    /// the spring's rest length, and the spring pulls the bell shut and pushes it open
    /// again, standing in for the hoop elasticity a slice has no other way to feel (paper
    /// section 3.3). `share` is the part of the stiffness the function drives: 1 for a
    /// muscle of its own, less for an r–z ring's muscle merged with the passive hoop it
    /// runs parallel to (one element with the pair's stiffness and rest length, the same
    /// forces exactly).
    RestLength { share: f32 },
    /// A force generator ([`MuscleLaw::Force`](crate::species::MuscleLaw), in the
    /// axisymmetric slice, whose rings have their own hoops): the function sets its
    /// activation; it pulls with activation × stiffness × its stretch beyond the shortest
    /// length it can pull to (`contraction_ratio` of relaxed, where its force has fallen
    /// to nothing), and never pushes. Its length is an outcome of that force against the
    /// hoops, the bending and the water, so a stroke quicker than the bell can follow is
    /// shallower, and a muscle that lets go leaves the bell to refill on its own recoil.
    Activation,
}

impl Muscle {
    /// Drives it as the contraction function asks for `factor` of the relaxed length, of
    /// the species' fully contracted `ratio`. A force generator's activation is how far
    /// into the stroke's depth `factor` is; an escape's deeper stroke (`factor` below the
    /// ratio) pulls harder and to a shorter length.
    pub(crate) fn contract(&mut self, factor: f32, ratio: f32) {
        match self.drive {
            Drive::RestLength { share: 1.0 } => self.rest = self.relaxed * factor,
            Drive::RestLength { share } => {
                self.rest = self.relaxed * (1.0 - share * (1.0 - factor));
            }
            Drive::Activation => {
                self.rest = self.relaxed * ratio.min(factor);
                self.activation = ((1.0 - factor) / (1.0 - ratio).max(1e-6)).max(0.0);
            }
        }
    }

    /// Its stiffness at `stretch` from its rest length: a force generator's only while
    /// stretched, and as strong as its activation.
    pub(crate) fn stiffness_at(&self, stretch: f32) -> f32 {
        match self.drive {
            Drive::RestLength { .. } => self.stiffness,
            Drive::Activation if stretch > 0.0 => self.stiffness * self.activation,
            Drive::Activation => 0.0,
        }
    }
}

pub(super) fn spring(points: &[Vec2], a: usize, b: usize, modulus_times_area: f32) -> Spring {
    let rest = (points[b] - points[a]).length();
    Spring {
        a,
        b,
        rest,
        stiffness: modulus_times_area / rest.max(1e-9),
        strain_limit: None,
    }
}

/// A muscle between the opposite points `a` and `b`, relaxed at their distance, of
/// `modulus_times_area` per unit depth, at `level`, driven as `drive` says (relaxed).
pub(super) fn muscle(
    points: &[Vec2],
    (a, b): (usize, usize),
    modulus_times_area: f32,
    level: f32,
    drive: Drive,
) -> Muscle {
    let relaxed = (points[b] - points[a]).length();
    Muscle {
        a,
        b,
        relaxed,
        rest: relaxed,
        stiffness: modulus_times_area / relaxed.max(1e-9),
        level,
        drive,
        activation: match drive {
            Drive::RestLength { .. } => 1.0,
            Drive::Activation => 0.0,
        },
    }
}

pub(super) fn hinge(points: &[Vec2], a: usize, b: usize, c: usize, stiffness: f32) -> Hinge {
    let (e1, e2) = (points[a] - points[b], points[c] - points[b]);
    let least_arm = 0.1 * e1.length().min(e2.length());
    Hinge {
        a,
        b,
        c,
        rest: signed_angle(e1, e2),
        stiffness,
        bend_limit: BEND_LIMIT,
        least_arm2: (least_arm * least_arm).max(1e-18),
    }
}

pub(super) fn hoop_bend(points: &[Vec2], a: usize, b: usize, stiffness: f32) -> HoopBend {
    HoopBend {
        a,
        b,
        rest: slope_sine(points[b] - points[a]),
        stiffness,
    }
}

/// sin ψ of a segment `d`: its rise over its length.
fn slope_sine(d: Vec2) -> f32 {
    d.y / d.length().max(1e-12)
}

fn signed_angle(e1: Vec2, e2: Vec2) -> f32 {
    e1.perp_dot(e2).atan2(e1.dot(e2))
}

fn wrap_angle(a: f32) -> f32 {
    let two_pi = std::f32::consts::TAU;
    a - two_pi * ((a + std::f32::consts::PI) / two_pi).floor()
}

/// One scalar constraint `C(x)` with energy `½·k·C²`, over up to three points.
#[derive(Clone, Copy)]
pub(super) struct Constraint {
    pub(crate) idx: [usize; 3],
    pub(crate) grad: [Vec2; 3],
    pub(crate) count: usize,
    pub(crate) stiffness: f32,
    /// `C` as the force sees it (past a knee, mapped onto the stiffer slope).
    pub(crate) value: f32,
    /// `C` itself: the strain or bend from rest.
    pub(crate) raw: f32,
    /// How much `raw` changed over the step, for the mesoglea's viscosity.
    pub(crate) change: f32,
}

impl Constraint {
    #[cfg(test)]
    pub(crate) fn add_force(&self, out: &mut [Vec2]) {
        self.add_damped_force(out, 0.0);
    }

    /// Adds the Kelvin–Voigt force `−k·(C + τ·dC/dt)·∇C`, with `damping = τ/dt` and the
    /// rate taken over the step.
    #[inline]
    pub(crate) fn add_damped_force(&self, out: &mut [Vec2], damping: f32) {
        let magnitude = self.stiffness * (self.value + damping * self.change);
        for k in 0..self.count {
            out[self.idx[k]] -= magnitude * self.grad[k];
        }
    }
}

/// Beyond `knee` (either sign), the same force at the knee and a `factor`-fold slope.
fn stiffen_beyond(c: &mut Constraint, knee: f32, factor: f32) {
    let excess = c.value.abs() - knee;
    if excess > 0.0 {
        c.value = c.value.signum() * (excess + knee / factor);
        c.stiffness *= factor;
    }
}

/// A hinge's bend from rest, between its edges `e1` and `e2` from the middle point.
fn hinge_bend(e1: Vec2, e2: Vec2, rest: f32) -> f32 {
    wrap_angle(signed_angle(e1, e2) - rest)
}

/// Every counted element as a constraint at the positions `x`, springs, muscles, hinges
/// and hoop bends in that order, each with its stiffness times its weight (`weights`;
/// [`Weights::default`] counts every element once), handed to `visit`. With `before`,
/// each one's strain or bend from rest there too, the same operations, for the mesoglea's
/// viscosity (`Constraint::change`).
///
/// Plain loops, one list at a time: the chained iterators they replace spent more on
/// asking each list whether it had run out than on the elements.
pub(super) fn for_each_constraint(
    body: &Body,
    x: &[Vec2],
    before: Option<&[Vec2]>,
    weights: &Weights,
    mut visit: impl FnMut(Constraint),
) {
    let weighed = |mut c: Constraint, weight: f32| {
        c.stiffness *= weight;
        c
    };
    // A length's or a slope's change over a step is far below π, where the wrap an
    // angle needs is the identity: only the hinges take it.
    let changed = |mut c: Constraint, raw_before: f32| {
        c.change = c.raw - raw_before;
        c
    };
    let length = |x: &[Vec2], a: usize, b: usize| (x[b] - x[a]).length();
    let stretch = |a: usize, b: usize, rest: f32, stiffness: f32| {
        let d = x[b] - x[a];
        let len = d.length();
        let dir = if len > 1e-12 { d / len } else { Vec2::X };
        Constraint {
            idx: [a, b, b],
            grad: [-dir, dir, Vec2::ZERO],
            count: 2,
            stiffness,
            value: len - rest,
            raw: len - rest,
            change: 0.0,
        }
    };
    for (s, w) in counted(&body.springs, &weights.springs) {
        let mut c = stretch(s.a, s.b, s.rest, s.stiffness);
        if let Some(limit) = s.strain_limit {
            stiffen_beyond(&mut c, limit * s.rest, STIFFENING);
        }
        if let Some(p) = before {
            c = changed(c, length(p, s.a, s.b) - s.rest);
        }
        visit(weighed(c, w));
    }
    // A planar muscle spring pulls and pushes (paper 3.3); an r–z force generator only
    // pulls, as strongly as it is activated (`Drive`).
    for (m, w) in counted(&body.muscles, &weights.muscles) {
        let mut c = stretch(m.a, m.b, m.rest, m.stiffness);
        c.stiffness = m.stiffness_at(c.value);
        if let Some(p) = before {
            c = changed(c, length(p, m.a, m.b) - m.rest);
        }
        visit(weighed(c, w));
    }
    for (h, w) in counted(&body.hinges, &weights.hinges) {
        let e1 = x[h.a] - x[h.b];
        let e2 = x[h.c] - x[h.b];
        let l1 = e1.length_squared().max(h.least_arm2);
        let l2 = e2.length_squared().max(h.least_arm2);
        let ga = -e1.perp() / l1;
        let gc = e2.perp() / l2;
        let bend = hinge_bend(e1, e2, h.rest);
        let mut c = Constraint {
            idx: [h.a, h.b, h.c],
            grad: [ga, -(ga + gc), gc],
            count: 3,
            stiffness: h.stiffness,
            value: bend,
            raw: bend,
            change: 0.0,
        };
        stiffen_beyond(&mut c, h.bend_limit, HINGE_STIFFENING);
        if let Some(p) = before {
            let bent = hinge_bend(p[h.a] - p[h.b], p[h.c] - p[h.b], h.rest);
            c.change = wrap_angle(c.raw - bent);
        }
        visit(weighed(c, w));
    }
    for (h, w) in counted(&body.hoop_bends, &weights.hoop_bends) {
        let d = x[h.b] - x[h.a];
        let len = d.length().max(1e-12);
        // ∂(d.y/|d|)/∂d = d.x·d⊥/|d|³.
        let grad = d.perp() * (d.x / (len * len * len));
        let change = slope_sine(d) - h.rest;
        let mut c = Constraint {
            idx: [h.a, h.b, h.b],
            grad: [-grad, grad, Vec2::ZERO],
            count: 2,
            stiffness: h.stiffness,
            value: change,
            raw: change,
            change: 0.0,
        };
        if let Some(p) = before {
            c = changed(c, slope_sine(p[h.b] - p[h.a]) - h.rest);
        }
        visit(weighed(c, w));
    }
}

/// Every counted element as a constraint at `x` ([`for_each_constraint`], no change).
#[cfg(test)]
pub(super) fn constraints(body: &Body, x: &[Vec2], weights: &Weights) -> Vec<Constraint> {
    let mut all = Vec::new();
    for_each_constraint(body, x, None, weights, |c| all.push(c));
    all
}
