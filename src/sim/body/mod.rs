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

mod elements;
mod implicit;
mod outline;
mod rest_shape;
mod tentacle;

pub use elements::{
    BEND_LIMIT, HINGE_STIFFENING, Hinge, Muscle, REFERENCE_HINGE_LENGTH, STIFFENING, Spring,
    TENTACLE_STRAIN_LIMIT,
};
pub use outline::{CRUMPLED_AREA, Outline, contains, crosses_itself, polygon_area, signed_area};
pub use rest_shape::{mesoglea_thickness, rest_outline};

use crate::species::Species;
use elements::{Constraint, constraints, hinge, spring, wrap_angle};
use glam::Vec2;
use implicit::Solver;
use std::ops::Range;
use tentacle::{TentacleDrag, tentacle_bending};

/// The bell and tentacles as a spring-mass system: points, Hookean springs, angular
/// springs (hinges) and muscle springs, per metre of slice depth.
#[derive(Clone)]
pub struct Body {
    /// Every point, m: the bell's subumbrella, then the tentacles.
    pub points: Vec<Vec2>,
    /// Positions at rest, relative to the same origin as construction.
    pub rest_points: Vec<Vec2>,
    /// Indices of the subumbrellar points (left margin, apex, right margin).
    pub bell: Range<usize>,
    /// Indices of the left and right tentacle points, margin outwards (margin excluded).
    pub tentacles: [Range<usize>; 2],
    /// Mesoglea and tentacle springs.
    pub springs: Vec<Spring>,
    /// Angular springs: the wall's bending stiffness.
    pub hinges: Vec<Hinge>,
    /// Muscle springs across the bell, driven by the contraction function.
    pub muscles: Vec<Muscle>,
    /// The mesoglea's Kelvin–Voigt time τ (viscosity over modulus), s: every element
    /// resists its rate of strain with τ times its stiffness.
    pub damping_time: f32,
    /// Each tentacle point's drag per unit of slip velocity, per metre of depth, N·s/m²
    /// (set each step from the point's last slip).
    pub tentacle_drag: Vec<f32>,
    drag_model: TentacleDrag,
    bell_solver: Solver,
    tentacle_solver: Solver,
    scratch: Vec<Vec2>,
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

        // Muscle springs between opposite points, from the margin to 3/4 of the way up. Each
        // is the circumferential muscle in series with the hoop of mesoglea it lines (the
        // slice has no circumference of its own): the muscle sets the rest length (the
        // contraction function), and the far softer mesoglea sets the stiffness, so the
        // bell's resonance with its water rises with `elastic_modulus` (DeMont & Gosline
        // 1988). Each spring stands for a band of the ring as tall as the point spacing, so
        // the bell's total stiffness does not grow with the number of points (grid).
        let band = species.thickness * (spacing / REFERENCE_HINGE_LENGTH);
        let fibre = species.muscle_modulus * species.muscle_cross_section * band;
        let hoop = species.elastic_modulus * species.hoop_cross_section * band;
        let in_series = fibre * hoop / (fibre + hoop);
        let mut muscles = Vec::new();
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
                stiffness: in_series / relaxed,
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
            // the margin itself; beyond it a tentacle bends as a thin cylinder of mesoglea
            // (see `tentacle_bending`) and trails in the flow. A root stiff over a third of
            // the length swung the tentacles as rods across the bell's axis.
            let margin_hinge =
                species.angular_stiffness * species.margin_thickness_ratio.powi(3) * hinge_scale;
            let tip_hinge = tentacle_bending(species, seg_len.max(1e-6));
            let chain: Vec<usize> = std::iter::once(bell_neighbour[side])
                .chain(std::iter::once(margin))
                .chain(start..points.len())
                .collect();
            for (k, w) in chain.windows(3).enumerate() {
                let stiffness = if k == 0 { margin_hinge } else { tip_hinge };
                hinges.push(hinge(&points, w[0], w[1], w[2], stiffness));
            }
        }

        let rest_points = points.clone();
        let bell_solver = Solver::new(points.len(), Solver::bell_order(&(0..bell_len)));
        let tentacle_solver = Solver::new(points.len(), Solver::tentacle_order(&tentacles));
        let scratch = vec![Vec2::ZERO; points.len()];
        let drag_model = TentacleDrag::new(species, seg_len);
        Self {
            points,
            rest_points,
            bell: 0..bell_len,
            tentacles,
            springs,
            hinges,
            muscles,
            damping_time: species.mesoglea_damping_time(),
            tentacle_drag: vec![drag_model.at(0.0); scratch.len()],
            drag_model,
            scratch,
            bell_solver,
            tentacle_solver,
        }
    }

    /// The subumbrella's points, left margin to right margin.
    pub fn bell_points(&self) -> &[Vec2] {
        &self.points[self.bell.clone()]
    }

    /// Index of the apex within [`Self::bell_points`].
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

    /// Forces on the water at the positions the points will reach, and the tentacles'
    /// slip through it.
    ///
    /// The bell is an immersed boundary: it solves `(m/dt² + K) δ = F(X̃)` and gives the
    /// water `F* = m/dt²·δ`, where `X̃` are the predicted positions, `K` the Gauss–Newton
    /// stiffness and `m` the fluid mass a point drags along. Its forces sum to zero, no net
    /// force and no net torque, like the springs themselves.
    ///
    /// Tentacles are thin cylinders, not the walls an immersed boundary would make of them
    /// in a slice (as sheets they were sucked into the bell and stopped it): each point
    /// slips through the water against slender-body drag `ξ` ([`Body::tentacle_drag`]),
    /// overdamped, `(ξ/dt + K) δ = F`. The water gets the drag back (`ξ/dt·δ`, in
    /// `forces`), the bell's margins get the tentacles' pull, so the whole body's forces
    /// still sum to zero; `slip` is `δ` on tentacle points (zero on the bell's).
    pub fn implicit_forces(
        &mut self,
        predicted: &[Vec2],
        dt: f32,
        mass_over_dt2: f32,
        forces: &mut [Vec2],
        slip: &mut [Vec2],
    ) {
        let bell_len = self.bell.end;
        let damping = self.damping_time / dt;
        let with_rates = |c: &mut Constraint, before: f32| c.change = wrap_angle(c.raw - before);
        let mut all: Vec<Constraint> = constraints(self, predicted).collect();
        if damping > 0.0 {
            for (c, before) in all.iter_mut().zip(constraints(self, &self.points)) {
                with_rates(c, before.raw);
            }
        }
        let (bell, mut tentacles): (Vec<Constraint>, Vec<Constraint>) = all
            .into_iter()
            .partition(|c| c.idx[..c.count].iter().all(|&i| i < bell_len));
        // The tentacles move with the bell held where it is predicted to be.
        for c in &mut tentacles {
            for k in 0..c.count {
                if c.idx[k] < bell_len {
                    c.grad[k] = Vec2::ZERO;
                }
            }
        }
        if self.bell_solver.rhs.is_empty() {
            self.bell_solver.prepare(&bell);
            self.tentacle_solver.prepare(&tentacles);
        }
        self.bell_solver
            .solve(&bell, mass_over_dt2, damping, forces);
        slip.iter_mut().for_each(|s| *s = Vec2::ZERO);
        if tentacles.is_empty() {
            return;
        }
        let drag = &self.tentacle_drag;
        self.tentacle_solver
            .solve_each(&tentacles, |i| drag[i] / dt, damping, &mut self.scratch);
        let margins = [self.bell.start, self.bell.end - 1];
        for (side, range) in self.tentacles.clone().into_iter().enumerate() {
            let mut pull = Vec2::ZERO;
            for i in range {
                let f = self.scratch[i];
                forces[i] = f;
                slip[i] = f * dt / self.tentacle_drag[i];
                pull += f;
                // Next step's drag at this step's relative speed.
                let speed = slip[i].length() / dt;
                self.tentacle_drag[i] = self.drag_model.at(speed);
            }
            // What drags the tentacles along pulls back on the margin they hang from.
            forces[margins[side]] -= pull;
        }
    }

    /// Moves the bell's points by the part of their implicit displacement the fluid cannot
    /// see: `δ = forces · dt²/m`, high-passed along the chain.
    ///
    /// The points move with the interpolated water, and a kernel three cells wide cannot
    /// represent neighbouring points half a cell apart moving oppositely: a zigzag along the
    /// subumbrella spreads no net force, so the water never straightens it, and the
    /// grid-scale unevenness of interpolation feeds it every step until the bell is a saw
    /// blade. Here that part relaxes under the bell's own springs, with the mass the
    /// implicit solve assumed; a smooth displacement's high-pass is of order (spacing/
    /// wavelength)², so everything the water does see is left to the water. Like the
    /// filters of vortex-sheet methods (Krasny 1986), only unresolved modes are touched.
    pub fn relax_unresolved(&mut self, forces: &[Vec2], dt2_over_mass: f32) {
        let n = self.bell.len();
        if n < 3 {
            return;
        }
        let f = &forces[self.bell.clone()];
        // Minus a quarter of the second difference: 1 on the alternating mode, ~0 on smooth
        // ones; one-sided at the margins.
        let high = |i: usize| {
            if i == 0 {
                0.25 * (f[0] - 2.0 * f[1] + f[2])
            } else if i == n - 1 {
                0.25 * (f[n - 1] - 2.0 * f[n - 2] + f[n - 3])
            } else {
                -0.25 * (f[i - 1] - 2.0 * f[i] + f[i + 1])
            }
        };
        let shift: Vec<Vec2> = (0..n).map(|i| dt2_over_mass * high(i)).collect();
        for (p, d) in self.points[self.bell.clone()].iter_mut().zip(shift) {
            *p += d;
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body::new(&Species::aurelia(), Vec2::new(0.2, 0.2), 0.004)
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
    fn implicit_forces_match_explicit_ones_for_tiny_steps_and_soften_for_large() {
        let mut species = Species::aurelia();
        species.tentacle_length = 0.0;
        let mut b = Body::new(&species, Vec2::new(0.2, 0.2), 0.004);
        deformed(&mut b);
        let x = b.points.clone();
        let n = x.len();
        let mut explicit = vec![Vec2::ZERO; n];
        b.forces(&mut explicit);
        let (mut small_dt, mut large_dt, mut slip) = (
            vec![Vec2::ZERO; n],
            vec![Vec2::ZERO; n],
            vec![Vec2::ZERO; n],
        );
        let mass = 1025.0 * 0.004 * 0.004;
        b.implicit_forces(&x, 1e-6, mass / 1e-12, &mut small_dt, &mut slip);
        b.implicit_forces(&x, 0.05, mass / 0.05f32.powi(2), &mut large_dt, &mut slip);
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
    fn tentacles_drag_the_margin_and_the_body_stays_force_free() {
        let mut b = body();
        // Swing the tentacles sideways: their springs and hinges pull.
        let [left, right] = b.tentacles.clone();
        for (k, i) in left.enumerate() {
            b.points[i].x -= 0.0003 * k as f32;
        }
        for (k, i) in right.enumerate() {
            b.points[i].x += 0.0005 * k as f32;
        }
        let x = b.points.clone();
        let n = x.len();
        let (mut forces, mut slip) = (vec![Vec2::ZERO; n], vec![Vec2::ZERO; n]);
        let mass = 1025.0 * 0.004 * 0.004;
        b.implicit_forces(&x, 0.03, mass / 0.03f32.powi(2), &mut forces, &mut slip);
        let scale: f32 = forces.iter().map(|f| f.length()).sum();
        let net: Vec2 = forces.iter().sum();
        assert!(scale > 0.0);
        assert!(net.length() < 1e-4 * scale, "net {net} of {scale}");
        // The tentacle points slip through the water; the bell's do not.
        assert!(
            b.tentacles
                .iter()
                .flat_map(|r| r.clone())
                .any(|i| slip[i] != Vec2::ZERO)
        );
        assert!(slip[b.bell.clone()].iter().all(|s| *s == Vec2::ZERO));
        // The margins feel the tentacles' pull.
        let margins = [b.bell.start, b.bell.end - 1];
        assert!(
            forces[margins[0]].x < 0.0 && forces[margins[1]].x > 0.0,
            "{:?}",
            [forces[margins[0]], forces[margins[1]]]
        );
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
}
