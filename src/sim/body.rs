//! The bell and tentacles as a spring-mass system (paper section 3.2, Fig. 4).
//!
//! Points on the subumbrellar surface, from the left margin over the apex to the right
//! margin, joined by Hookean springs and held in shape by angular springs; muscle springs
//! span the bell between opposite points; each margin carries a tentacle chain of the same
//! modulus and 1/100 of the cross-section.
//!
//! Forces are semi-implicit: [`Body::implicit_forces`] returns the spring forces at the
//! positions the points are about to reach, found with a Gauss–Newton linearisation and
//! an exact banded solve. That removes the elastic step limit (the paper's safety factor of
//! 0.001) while keeping the forces an exact action–reaction set.

use super::banded::BandedSpd;
use crate::species::Species;
use glam::Vec2;
use std::ops::Range;

/// Mesoglea thickness at arc fraction `s` of the bell (0 at the apex, 1 at the margin), m.
///
/// Thickest at the apex (the paper's ϑ), thinning quadratically towards the margin, as in
/// the paper's Fig. 2 cross-sections.
pub fn mesoglea_thickness(species: &Species, s: f32) -> f32 {
    let s = s.clamp(0.0, 1.0);
    species.thickness * (1.0 - (1.0 - species.margin_thickness_ratio) * s * s)
}

/// A Hookean spring between two points.
#[derive(Clone, Copy, Debug)]
pub struct Spring {
    pub a: usize,
    pub b: usize,
    /// Rest length, m.
    pub rest: f32,
    /// N/m per metre of depth: modulus × cross-section / rest length.
    pub stiffness: f32,
    /// Strain beyond which the spring stiffens [`STIFFENING`]-fold, if any.
    pub strain_limit: Option<f32>,
}

/// Tentacle strain at which the tissue stiffens (Megill: mesoglea is linear "except for
/// extremely large stresses, where it becomes more stiff"). Without it the soft tentacle
/// springs (1/100 of the bell's cross-section) let the jet stretch tentacles to several
/// times their length within a few strokes.
pub const TENTACLE_STRAIN_LIMIT: f32 = 0.1;
/// Hinge bending beyond which the mesoglea stiffens [`HINGE_STIFFENING`]-fold, rad. With
/// plate-bending hinges alone, the wake of the 10-diameter box turned the bell inside out
/// after about a dozen strokes; a gentle knee keeps the stroke soft and the bell upright.
pub const BEND_LIMIT: f32 = 0.25;
/// Hinge stiffening beyond [`BEND_LIMIT`]; a sharper knee (10×, 100×) made strokes jitter.
pub const HINGE_STIFFENING: f32 = 3.0;
/// How much stiffer a spring gets beyond its strain limit.
pub const STIFFENING: f32 = 100.0;

/// An angular spring holding the angle at `b` between `a` and `c`.
#[derive(Clone, Copy, Debug)]
pub struct Hinge {
    pub a: usize,
    pub b: usize,
    pub c: usize,
    /// Signed rest angle from `a - b` to `c - b`, rad.
    pub rest: f32,
    /// N·m/rad per metre of depth.
    pub stiffness: f32,
    /// Bending (rad from rest) beyond which the hinge stiffens [`HINGE_STIFFENING`]-fold.
    pub bend_limit: f32,
}

/// A muscle spring across the bell; its rest length follows the contraction function.
#[derive(Clone, Copy, Debug)]
pub struct Muscle {
    pub a: usize,
    pub b: usize,
    /// Rest length when relaxed, m.
    pub relaxed: f32,
    /// Current rest length, m (set by the muscle drive each step).
    pub rest: f32,
    pub stiffness: f32,
    /// 0 nearest the apex, 1 at the margin: where the staggered expansion is slowest.
    pub level: f32,
}

pub struct Body {
    pub points: Vec<Vec2>,
    /// Positions at rest, relative to the same origin as construction.
    pub rest_points: Vec<Vec2>,
    /// Indices of the subumbrellar points (left margin, apex, right margin).
    pub bell: Range<usize>,
    /// Indices of the left and right tentacle points, margin outwards (margin excluded).
    pub tentacles: [Range<usize>; 2],
    pub springs: Vec<Spring>,
    pub hinges: Vec<Hinge>,
    pub muscles: Vec<Muscle>,
    solver: Solver,
}

impl Body {
    /// Builds the rest configuration with the aperture centre at `origin`, for fluid cells
    /// of size `h` (points sit about half a cell apart, as immersed boundaries need).
    pub fn new(species: &Species, origin: Vec2, h: f32) -> Self {
        let outline = rest_outline(species, h);
        let bell_len = outline.len();
        let m = bell_len / 2;
        let mut points: Vec<Vec2> = outline.iter().map(|p| *p + origin).collect();
        let spacing = (outline[1] - outline[0]).length();
        let mut springs = Vec::new();
        let mut hinges = Vec::new();

        // Subumbrellar chain. Cross-section: local wall thickness times unit depth.
        let arc_fraction = |i: usize| (i as f32 - m as f32).abs() / m as f32;
        for i in 0..bell_len - 1 {
            let t = mesoglea_thickness(species, arc_fraction(i) * 0.5 + arc_fraction(i + 1) * 0.5);
            springs.push(spring(&points, i, i + 1, species.elastic_modulus * t));
        }
        // Angular springs: plate bending stiffness scales with t³; `angular_stiffness` is
        // the value at the apex thickness for a 2 mm hinge, rescaled to this spacing so the
        // bell's rigidity does not depend on the grid.
        let hinge_scale = REFERENCE_HINGE_LENGTH / spacing;
        for i in 1..bell_len - 1 {
            let t = mesoglea_thickness(species, arc_fraction(i)) / species.thickness;
            hinges.push(hinge(
                &points,
                i - 1,
                i,
                i + 1,
                species.angular_stiffness * t.powi(3) * hinge_scale,
            ));
        }

        // Muscle springs between opposite points, from the margin to 3/4 of the way up.
        let mut muscles = Vec::new();
        let muscle_area = species.muscle_cross_section * species.thickness;
        for i in 0..m {
            let level = 1.0 - i as f32 / m as f32;
            if level < 0.25 {
                break;
            }
            let j = bell_len - 1 - i;
            let relaxed = (points[j] - points[i]).length();
            muscles.push(Muscle {
                a: i,
                b: j,
                relaxed,
                rest: relaxed,
                stiffness: species.muscle_modulus * muscle_area / relaxed,
                level,
            });
        }

        // Tentacles hang from the margins: same modulus, a fraction of the cross-section.
        let margin_t = mesoglea_thickness(species, 1.0);
        let tentacle_area = margin_t * species.tentacle_cross_section;
        let segments = ((species.tentacle_length / spacing).round() as usize)
            .max(if species.tentacle_length > 0.0 { 2 } else { 0 });
        let seg_len = if segments > 0 {
            species.tentacle_length / segments as f32
        } else {
            0.0
        };
        let mut tentacles = [0..0, 0..0];
        let bell_neighbour = [1, bell_len - 2];
        for (side, margin) in [(0, 0), (1, bell_len - 1)] {
            let start = points.len();
            let mut prev = margin;
            for k in 1..=segments {
                points.push(points[margin] - Vec2::Y * seg_len * k as f32);
                let idx = points.len() - 1;
                let mut s = spring(&points, prev, idx, species.elastic_modulus * tentacle_area);
                s.strain_limit = Some(TENTACLE_STRAIN_LIMIT);
                springs.push(s);
                prev = idx;
            }
            tentacles[side] = start..points.len();
            // Bending: the root, where the tentacle grows from the margin, is as stiff as
            // the margin itself and holds the tentacle hanging outside the bell; the
            // stiffness tapers geometrically to the tentacle's own (cross-section ratio)
            // over the first third, so the rest trails limply in the flow.
            let margin_hinge =
                species.angular_stiffness * species.margin_thickness_ratio.powi(3) * hinge_scale;
            let tip_hinge =
                species.angular_stiffness * species.tentacle_cross_section * hinge_scale;
            let root = (segments / 3).max(1) as f32;
            let chain: Vec<usize> = std::iter::once(bell_neighbour[side])
                .chain(std::iter::once(margin))
                .chain(start..points.len())
                .collect();
            for (k, w) in chain.windows(3).enumerate() {
                let f = (k as f32 / root).min(1.0);
                let stiffness =
                    margin_hinge.max(tip_hinge) * (tip_hinge / margin_hinge.max(tip_hinge)).powf(f);
                hinges.push(hinge(&points, w[0], w[1], w[2], stiffness));
            }
        }

        let rest_points = points.clone();
        let solver = Solver::new(points.len(), &(0..bell_len), &tentacles);
        Self {
            points,
            rest_points,
            bell: 0..bell_len,
            tentacles,
            springs,
            hinges,
            muscles,
            solver,
        }
    }

    pub fn bell_points(&self) -> &[Vec2] {
        &self.points[self.bell.clone()]
    }

    pub fn apex_index(&self) -> usize {
        self.bell.len() / 2
    }

    /// Centroid of the subumbrellar points.
    pub fn bell_centroid(&self) -> Vec2 {
        let bell = self.bell_points();
        bell.iter().sum::<Vec2>() / bell.len() as f32
    }

    /// Unit vector from the aperture centre to the apex.
    pub fn axis(&self) -> Vec2 {
        let bell = self.bell_points();
        let aperture = 0.5 * (bell[0] + bell[bell.len() - 1]);
        (bell[self.apex_index()] - aperture).normalize_or(Vec2::Y)
    }

    /// Area enclosed by the subumbrella and the aperture chord, m² per metre of depth.
    pub fn bell_area(&self) -> f32 {
        polygon_area(self.bell_points())
    }

    /// Elastic forces at the current positions, N per metre of depth (explicit).
    pub fn forces(&self, out: &mut [Vec2]) {
        out.iter_mut().for_each(|f| *f = Vec2::ZERO);
        for c in constraints(self, &self.points) {
            c.add_force(out);
        }
    }

    /// Forces at the positions the points will reach: solves
    /// `(m/dt² + K) δ = F(X̃)` and returns `F* = m/dt²·δ`, where `X̃` are the predicted
    /// positions, `K` the Gauss–Newton stiffness and `m` the fluid mass a point drags along.
    ///
    /// The bell's forces (`bell_out`, zero on tentacle points) sum to zero, no net force
    /// and no net torque, like the springs themselves. Tentacles are solved after it with
    /// the bell held fixed (`tentacle_out`, zero on bell points): they hang from the margin
    /// but do not pull on it (see [`SliceSim`](super::SliceSim) on one-way tentacles).
    pub fn implicit_forces(
        &mut self,
        predicted: &[Vec2],
        mass_over_dt2: f32,
        bell_out: &mut [Vec2],
        tentacle_out: &mut [Vec2],
    ) {
        let bell_len = self.bell.end;
        let (bell, mut tentacles): (Vec<Constraint>, Vec<Constraint>) =
            constraints(self, predicted)
                .partition(|c| c.idx[..c.count].iter().all(|&i| i < bell_len));
        for c in &mut tentacles {
            for k in 0..c.count {
                if c.idx[k] < bell_len {
                    c.grad[k] = Vec2::ZERO;
                }
            }
        }
        if self.solver.rhs.is_empty() {
            let all: Vec<Constraint> = bell.iter().chain(&tentacles).copied().collect();
            self.solver.prepare(&all);
        }
        self.solver.solve(&bell, mass_over_dt2, bell_out);
        self.solver.solve(&tentacles, mass_over_dt2, tentacle_out);
    }

    /// Averages the body with its mirror image about the vertical line `x = centre`.
    pub fn symmetrise(&mut self, centre: f32) {
        let mirror = |p: Vec2| Vec2::new(2.0 * centre - p.x, p.y);
        let len = self.bell.len();
        for i in 0..len / 2 {
            let j = len - 1 - i;
            let a = 0.5 * (self.points[i] + mirror(self.points[j]));
            self.points[i] = a;
            self.points[j] = mirror(a);
        }
        self.points[len / 2].x = centre;
        let [l, r] = self.tentacles.clone();
        for (i, j) in l.zip(r) {
            let a = 0.5 * (self.points[i] + mirror(self.points[j]));
            self.points[i] = a;
            self.points[j] = mirror(a);
        }
    }

    /// Whether every point is finite.
    pub fn is_finite(&self) -> bool {
        self.points.iter().all(|p| p.is_finite())
    }

    /// Sum of spring tensions per spring, N per metre of depth (positive = stretched), for
    /// debug overlays: the springs in order, then the muscles.
    pub fn tensions(&self) -> impl Iterator<Item = (Vec2, Vec2, f32)> + '_ {
        let p = &self.points;
        self.springs
            .iter()
            .map(move |s| {
                (
                    p[s.a],
                    p[s.b],
                    s.stiffness * ((p[s.b] - p[s.a]).length() - s.rest),
                )
            })
            .chain(self.muscles.iter().map(move |m| {
                let len = (p[m.b] - p[m.a]).length();
                (p[m.a], p[m.b], m.stiffness * (len - m.rest))
            }))
    }
}

/// Hinge length the default `angular_stiffness` refers to, m (grid 100: half a 4 mm cell).
pub const REFERENCE_HINGE_LENGTH: f32 = 0.002;

fn spring(points: &[Vec2], a: usize, b: usize, modulus_times_area: f32) -> Spring {
    let rest = (points[b] - points[a]).length();
    Spring {
        a,
        b,
        rest,
        stiffness: modulus_times_area / rest.max(1e-9),
        strain_limit: None,
    }
}

fn hinge(points: &[Vec2], a: usize, b: usize, c: usize, stiffness: f32) -> Hinge {
    Hinge {
        a,
        b,
        c,
        rest: signed_angle(points[a] - points[b], points[c] - points[b]),
        stiffness,
        bend_limit: BEND_LIMIT,
    }
}

fn signed_angle(e1: Vec2, e2: Vec2) -> f32 {
    e1.perp_dot(e2).atan2(e1.dot(e2))
}

fn wrap_angle(a: f32) -> f32 {
    let two_pi = std::f32::consts::TAU;
    a - two_pi * ((a + std::f32::consts::PI) / two_pi).floor()
}

/// Shoelace area of a closed polygon.
pub fn polygon_area(points: &[Vec2]) -> f32 {
    let n = points.len();
    let twice: f32 = (0..n)
        .map(|i| points[i].perp_dot(points[(i + 1) % n]))
        .sum();
    0.5 * twice.abs()
}

/// The rest subumbrella: a half-ellipse of the species' diameter and height, aperture
/// centre at the origin, apex at +y, points at equal arc length about `h/2` apart.
pub fn rest_outline(species: &Species, h: f32) -> Vec<Vec2> {
    let a = 0.5 * species.diameter;
    let b = species.height;
    // Dense polyline from the left margin (θ = π) over the apex to the right margin.
    const DENSE: usize = 2000;
    let dense: Vec<Vec2> = (0..=DENSE)
        .map(|k| {
            let theta = std::f32::consts::PI * (1.0 - k as f32 / DENSE as f32);
            Vec2::new(a * theta.cos(), b * theta.sin())
        })
        .collect();
    let mut cumulative = vec![0.0f32; dense.len()];
    for k in 1..dense.len() {
        cumulative[k] = cumulative[k - 1] + (dense[k] - dense[k - 1]).length();
    }
    let total = cumulative[DENSE];
    // An even number of segments keeps a point on the apex.
    let half = ((total / (0.5 * h)) / 2.0).round().max(6.0) as usize;
    let segments = 2 * half;
    let mut out = Vec::with_capacity(segments + 1);
    let mut k = 0;
    for s in 0..=segments {
        let target = total * s as f32 / segments as f32;
        while k + 1 < DENSE && cumulative[k + 1] < target {
            k += 1;
        }
        let span = (cumulative[k + 1] - cumulative[k]).max(1e-12);
        let f = ((target - cumulative[k]) / span).clamp(0.0, 1.0);
        out.push(dense[k].lerp(dense[k + 1], f));
    }
    // Exact symmetry: mirror the left half onto the right.
    for i in 0..half {
        let p = out[i];
        out[segments - i] = Vec2::new(-p.x, p.y);
    }
    out[half].x = 0.0;
    out
}

/// One scalar constraint `C(x)` with energy `½·k·C²`, over up to three points.
#[derive(Clone, Copy)]
struct Constraint {
    idx: [usize; 3],
    grad: [Vec2; 3],
    count: usize,
    stiffness: f32,
    value: f32,
}

impl Constraint {
    fn add_force(&self, out: &mut [Vec2]) {
        for k in 0..self.count {
            out[self.idx[k]] -= self.stiffness * self.value * self.grad[k];
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

fn constraints<'a>(body: &'a Body, x: &'a [Vec2]) -> impl Iterator<Item = Constraint> + 'a {
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
        }
    };
    let springs = body.springs.iter().map(move |s| {
        let mut c = stretch(s.a, s.b, s.rest, s.stiffness);
        if let Some(limit) = s.strain_limit {
            stiffen_beyond(&mut c, limit * s.rest, STIFFENING);
        }
        c
    });
    // A muscle spring stands for the circumferential muscle and the ring of mesoglea it
    // lines: it pulls while contracted and pushes the bell back open like the hoop
    // elasticity of the 3D umbrella, which a slice has no other way to feel (paper 3.3:
    // the rest lengths of these springs drive both contraction and re-expansion).
    let muscles = body
        .muscles
        .iter()
        .map(move |m| stretch(m.a, m.b, m.rest, m.stiffness));
    let hinges = body.hinges.iter().map(move |h| {
        let e1 = x[h.a] - x[h.b];
        let e2 = x[h.c] - x[h.b];
        let l1 = e1.length_squared().max(1e-18);
        let l2 = e2.length_squared().max(1e-18);
        let ga = -e1.perp() / l1;
        let gc = e2.perp() / l2;
        let mut c = Constraint {
            idx: [h.a, h.b, h.c],
            grad: [ga, -(ga + gc), gc],
            count: 3,
            stiffness: h.stiffness,
            value: wrap_angle(signed_angle(e1, e2) - h.rest),
        };
        stiffen_beyond(&mut c, h.bend_limit, HINGE_STIFFENING);
        c
    });
    springs.chain(muscles).chain(hinges)
}

/// Exact solve of `(m/dt² I + Σ k g gᵀ) δ = F` with a banded Cholesky factorisation.
struct Solver {
    /// Position of each point in the band ordering.
    order: Vec<usize>,
    matrix: BandedSpd,
    rhs: Vec<f64>,
    forces: Vec<Vec2>,
}

impl Solver {
    /// Numbers the bell from the apex outwards, alternating sides, then the tentacles
    /// from the margins outwards, alternating sides: every spring, hinge and muscle then
    /// couples points a few places apart.
    fn new(body_len: usize, bell: &Range<usize>, tentacles: &[Range<usize>; 2]) -> Self {
        let mut order = vec![0; body_len];
        let m = bell.len() / 2;
        order[bell.start + m] = 0;
        for d in 1..=m {
            order[bell.start + m - d] = 2 * d - 1;
            order[bell.start + m + d] = 2 * d;
        }
        let base = bell.len();
        let longest = tentacles[0].len().max(tentacles[1].len());
        let mut next = base;
        for k in 0..longest {
            for side in tentacles {
                if k < side.len() {
                    order[side.start + k] = next;
                    next += 1;
                }
            }
        }
        Self {
            order,
            matrix: BandedSpd::new(0, 0),
            rhs: Vec::new(),
            forces: vec![Vec2::ZERO; body_len],
        }
    }

    /// Sizes the band for the couplings the body has.
    fn prepare(&mut self, cons: &[Constraint]) {
        let band = cons
            .iter()
            .map(|c| {
                let pos = &c.idx[..c.count];
                let lo = pos.iter().map(|&i| self.order[i]).min().unwrap_or(0);
                let hi = pos.iter().map(|&i| self.order[i]).max().unwrap_or(0);
                hi - lo
            })
            .max()
            .unwrap_or(0);
        let dofs = 2 * self.order.len();
        self.matrix = BandedSpd::new(dofs, 2 * band + 1);
        self.rhs = vec![0.0; dofs];
    }

    fn solve(&mut self, cons: &[Constraint], diag: f32, out: &mut [Vec2]) {
        // Right-hand side: the explicit forces at the predicted positions.
        self.forces.iter_mut().for_each(|f| *f = Vec2::ZERO);
        for c in cons {
            c.add_force(&mut self.forces);
        }
        for (i, f) in self.forces.iter().enumerate() {
            self.rhs[2 * self.order[i]] = f.x as f64;
            self.rhs[2 * self.order[i] + 1] = f.y as f64;
        }
        self.matrix.clear_to_diagonal(diag as f64);
        for c in cons {
            let k = c.stiffness as f64;
            for p in 0..c.count {
                for q in 0..=p {
                    let (gp, gq) = (c.grad[p].to_array(), c.grad[q].to_array());
                    let (op, oq) = (self.order[c.idx[p]], self.order[c.idx[q]]);
                    for (a, ga) in gp.iter().enumerate() {
                        for (b, gb) in gq.iter().enumerate() {
                            // A point's own 2×2 block is symmetric: give each entry once.
                            if p == q && b > a {
                                continue;
                            }
                            self.matrix
                                .add(2 * op + a, 2 * oq + b, k * (ga * gb) as f64);
                        }
                    }
                }
            }
        }
        if !self.matrix.factor_and_solve(&mut self.rhs) {
            // Only non-finite input gets here; the step's health check then recovers.
            out.iter_mut().for_each(|o| *o = Vec2::splat(f32::NAN));
            return;
        }
        for (i, o) in out.iter_mut().enumerate() {
            let (x, y) = (self.rhs[2 * self.order[i]], self.rhs[2 * self.order[i] + 1]);
            *o = diag * Vec2::new(x as f32, y as f32);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body::new(&Species::aurelia(), Vec2::new(0.2, 0.2), 0.004)
    }

    #[test]
    fn rest_outline_is_symmetric_with_apex_on_axis() {
        let s = Species::aurelia();
        let o = rest_outline(&s, 0.004);
        assert_eq!(o.len() % 2, 1);
        let m = o.len() / 2;
        assert!((o[m] - Vec2::new(0.0, s.height)).length() < 1e-5);
        assert!((o[0] - Vec2::new(-0.02, 0.0)).length() < 1e-5);
        for i in 0..m {
            let mirrored = Vec2::new(-o[i].x, o[i].y);
            assert!((o[o.len() - 1 - i] - mirrored).length() < 1e-6);
        }
        // About half a cell apart.
        let spacing = (o[1] - o[0]).length();
        assert!(spacing > 0.0015 && spacing < 0.0025, "{spacing}");
    }

    #[test]
    fn rest_shape_feels_no_force() {
        let b = body();
        let mut f = vec![Vec2::ZERO; b.points.len()];
        b.forces(&mut f);
        let max = f.iter().fold(0.0f32, |m, v| m.max(v.length()));
        assert!(max < 1e-4, "{max}");
    }

    fn deformed(b: &mut Body) {
        for (i, p) in b.points.iter_mut().enumerate() {
            *p += Vec2::new((i as f32 * 1.3).sin(), (i as f32 * 0.7).cos()) * 0.001;
        }
        for m in &mut b.muscles {
            m.rest = 0.6 * m.relaxed;
        }
    }

    #[test]
    fn internal_forces_sum_to_zero() {
        let mut b = body();
        deformed(&mut b);
        let mut f = vec![Vec2::ZERO; b.points.len()];
        b.forces(&mut f);
        let scale: f32 = f.iter().map(|v| v.length()).sum();
        let net: Vec2 = f.iter().sum();
        let torque: f32 = b.points.iter().zip(&f).map(|(p, f)| p.perp_dot(*f)).sum();
        assert!(scale > 1.0, "the deformation loads the springs");
        assert!(net.length() < 1e-5 * scale, "net {net}, scale {scale}");
        assert!(torque.abs() < 1e-5 * scale, "torque {torque}");
    }

    #[test]
    fn implicit_forces_sum_to_zero_and_soften_with_larger_steps() {
        // Without tentacles: they are solved separately and do not pull on the bell.
        let mut species = Species::aurelia();
        species.tentacle_length = 0.0;
        let mut b = Body::new(&species, Vec2::new(0.2, 0.2), 0.004);
        deformed(&mut b);
        let x = b.points.clone();
        let n = x.len();
        let mut explicit = vec![Vec2::ZERO; n];
        b.forces(&mut explicit);
        let mut small_dt = vec![Vec2::ZERO; n];
        let mut large_dt = vec![Vec2::ZERO; n];
        let mass = 1025.0 * 0.004 * 0.004;
        let mut tentacle = vec![Vec2::ZERO; n];
        b.implicit_forces(&x, mass / 1e-12, &mut small_dt, &mut tentacle);
        for (s, t) in small_dt.iter_mut().zip(&tentacle) {
            *s += *t;
        }
        b.implicit_forces(&x, mass / 0.05f32.powi(2), &mut large_dt, &mut tentacle);
        let norm = |f: &[Vec2]| f.iter().map(|v| v.length_squared()).sum::<f32>().sqrt();
        // Tiny step: implicit equals explicit. Large step: the stiff modes are damped.
        let diff: f32 = explicit
            .iter()
            .zip(&small_dt)
            .map(|(a, b)| (*a - *b).length_squared())
            .sum::<f32>()
            .sqrt();
        assert!(diff < 1e-3 * norm(&explicit), "{diff}");
        assert!(norm(&large_dt) < norm(&explicit));
        let net: Vec2 = large_dt.iter().sum();
        assert!(net.length() < 1e-4 * norm(&large_dt), "net {net}");
    }

    #[test]
    fn relaxed_muscles_hold_the_rest_shape() {
        let mut b = body();
        let rest = b.points.clone();
        for m in &mut b.muscles {
            m.rest = 0.56 * m.relaxed;
        }
        let mut f = vec![Vec2::ZERO; b.points.len()];
        b.forces(&mut f);
        // Contracted rest lengths pull opposite margins together...
        let (l, r) = (b.muscles[0].a, b.muscles[0].b);
        assert!(f[l].x > 0.0 && f[r].x < 0.0);
        // ...and relaxed ones leave the rest shape alone.
        for m in &mut b.muscles {
            m.rest = m.relaxed;
        }
        b.forces(&mut f);
        assert!(f.iter().all(|v| v.length() < 1e-4));
        assert_eq!(b.points, rest);
    }

    #[test]
    fn thickness_is_largest_at_the_apex() {
        let s = Species::aurelia();
        assert_eq!(mesoglea_thickness(&s, 0.0), s.thickness);
        assert!(mesoglea_thickness(&s, 1.0) < mesoglea_thickness(&s, 0.5));
        assert!(
            (mesoglea_thickness(&s, 1.0) - s.thickness * s.margin_thickness_ratio).abs() < 1e-7
        );
    }
}
