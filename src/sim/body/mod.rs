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

mod depth;
mod elements;
mod half;
mod implicit;
mod kept;
mod network;
mod outline;
mod relaxation;
mod rest_shape;
mod tentacle;

pub(crate) use depth::Depth;
pub(crate) use elements::{Hinge, HoopBend, Muscle, Spring};
pub use outline::{Outline, cavity, contains, outward_normals};
pub(crate) use outline::{polygon_area, signed_area};
pub(crate) use rest_shape::{mesoglea_thickness, rest_outline};
pub(crate) use tentacle::cylinder_filament;

use crate::sim::response::Response;
use crate::species::Species;
#[cfg(test)]
use elements::constraints;
use elements::{Constraint, for_each_constraint};
use glam::Vec2;
use half::Weights;
use implicit::Solver;
use network::{
    Tentacles, circumferential_muscles, hang_tentacles, hoop_bending, mesoglea_hinges, ring_hoops,
    subumbrellar_springs,
};
use std::ops::Range;
use tentacle::TentacleDrag;

/// What one side's fringe pulls its margin with over a step, N per unit depth, and the
/// share the margin's water takes directly (the rest loads the bell).
#[derive(Clone, Copy, Debug)]
struct Pull {
    force: Vec2,
    direct: f32,
}

impl Pull {
    const NONE: Pull = Pull {
        force: Vec2::ZERO,
        direct: 1.0,
    };

    /// What the margin's water gets: all of the pull while it can take it.
    fn on_margins_water(self) -> Vec2 {
        self.direct * self.force
    }

    /// The rest, a load on the bell: none while the margin's water takes it all.
    fn on_bell(self) -> Option<Vec2> {
        (self.direct < 1.0).then(|| -(1.0 - self.direct) * self.force)
    }
}

/// The most a fringe point's drag may change from one step to the next, either way. The
/// drag is taken at the last step's slip, and a cylinder's drag grows with its speed: a
/// thin tentacle that slips far one step drags hard the next and hardly slips, then
/// slips far again, and the swing grows until the slice blows up (*Sarsia* made 62 mm
/// by its lengths alone, its 0.3 mm tentacles 97 mm long, slipped 0.5 m in a step and was
/// restarted twice in fourteen strokes). Bounded, the swing dies out. 16 leaves every
/// shipped species' first ten strokes as they were to the bit (it first binds later in
/// *Sarsia*'s, and not in 100 of the rowers' at any size, grid or rate tried); at 100
/// the swing still grows.
const DRAG_CHANGE: f32 = 16.0;

/// What one implicit solve reads: the predicted positions, the step, the water a point
/// drags along over it, and the water's response where the bell is solved against it.
#[derive(Clone, Copy)]
struct Solve<'a> {
    predicted: &'a [Vec2],
    dt: f32,
    mass_over_dt2: &'a [f32],
    water: Option<&'a Response>,
}

/// The bell and tentacles as a spring-mass system: points, Hookean springs, angular
/// springs (hinges) and muscle springs, per metre of slice depth.
#[derive(Clone)]
pub struct Body {
    /// Every point, m: the bell's subumbrella, then the tentacles.
    pub(crate) points: Vec<Vec2>,
    /// Indices of the subumbrellar points (left margin, apex, right margin).
    pub(crate) bell: Range<usize>,
    /// Indices of the left and right tentacle points, margin outwards (margin excluded).
    pub(crate) tentacles: [Range<usize>; 2],
    /// Mesoglea and tentacle springs.
    pub(crate) springs: Vec<Spring>,
    /// Angular springs: the wall's bending stiffness.
    pub(crate) hinges: Vec<Hinge>,
    /// The hoop bending of an r–z bell's rings (none in the plane).
    pub(crate) hoop_bends: Vec<HoopBend>,
    /// Muscle springs across the bell, driven by the contraction function.
    pub(crate) muscles: Vec<Muscle>,
    /// The mesoglea's Kelvin–Voigt time τ (viscosity over modulus), s: every element
    /// resists its rate of strain with τ times its stiffness.
    pub(crate) damping_time: f32,
    /// Each tentacle point's drag per unit of slip velocity, per unit depth, N·s/m²
    /// (set each step from the point's last slip).
    pub(crate) tentacle_drag: Vec<f32>,
    /// Per unit of what depth every element is (a metre of a plane, a radian of rings).
    pub(crate) depth: Depth,
    /// Of a mirror-symmetric body (a body of revolution, or a planar one held
    /// symmetric), each point past the axis's partner before it, whose mirror image it is
    /// (`None` before the axis and on it; empty for a planar body free to tilt).
    mirror_partners: Vec<Option<usize>>,
    /// How often the solve on the half counts each element (`half`), from
    /// `mirror_partners`.
    weights: Weights,
    drag_model: TentacleDrag,
    bell_solver: Solver,
    tentacle_solver: Solver,
    scratch: Vec<Vec2>,
    /// The elements at the predicted positions, the bell's and the tentacles', kept
    /// between steps so that a step allocates nothing.
    split: Split,
}

/// The partner of each point past the axis (the right half of the subumbrella and the
/// right tentacle), as [`Body::symmetrise`] pairs them.
fn mirror_partners(
    bell_len: usize,
    tentacles: &[Range<usize>; 2],
    count: usize,
) -> Vec<Option<usize>> {
    let mut partners = vec![None; count];
    for i in 0..bell_len / 2 {
        partners[bell_len - 1 - i] = Some(i);
    }
    let [left, right] = tentacles.clone();
    for (i, j) in left.zip(right) {
        partners[j] = Some(i);
    }
    partners
}

/// A step's elements, sorted by what they join: the bell alone, or a tentacle.
#[derive(Clone, Default)]
struct Split {
    bell: Vec<Constraint>,
    tentacles: Vec<Constraint>,
}

impl Body {
    /// Builds the rest configuration with the aperture centre at `origin`, for fluid cells
    /// of size `h`: the paper's Fig. 4, part by part (see `network`).
    ///
    /// Points sit about half a kernel cell apart (half a cell where the kernel spans its own
    /// three cells, as immersed boundaries need). A kernel stretched to the bell's
    /// `boundary_width` cannot see finer detail, so on a finer grid the bell keeps the
    /// points it had: refining the grid refines the water around one body instead of
    /// adding wrinkles the water cannot hold straight (they crossed the outline at 2·G).
    ///
    /// In the axisymmetric geometry the axis is the vertical through `origin`, every point
    /// a ring about it, and the muscle a hoop of each ring. Either is mirror-symmetric
    /// about it and solved on its half (see [`Body::set_mirror_symmetric`]).
    ///
    /// The last few bodies built are kept (`kept`): the same three give a copy of one.
    pub(crate) fn new(species: &Species, origin: Vec2, h: f32) -> Self {
        kept::body(species, origin, h)
    }

    /// [`Body::new`], built part by part.
    fn build(species: &Species, origin: Vec2, h: f32) -> Self {
        let outline = rest_outline(species, h * species.kernel_stretch_at(h));
        let bell_len = outline.len();
        let spacing = (outline[1] - outline[0]).length();
        let depth = Depth::new(species, origin.x, h);
        let mut points: Vec<Vec2> = outline.iter().map(|p| *p + origin).collect();
        let mut springs = subumbrellar_springs(species, &points, depth);
        let mut hinges = mesoglea_hinges(species, &points, spacing, depth);
        let hoop_bends = hoop_bending(species, &points, spacing, depth);
        let muscles = if depth.rings() {
            ring_hoops(species, &points, spacing, &mut springs)
        } else {
            circumferential_muscles(species, &points, spacing)
        };
        let Tentacles {
            ranges: tentacles,
            segment: seg_len,
        } = hang_tentacles(
            species,
            bell_len,
            spacing,
            &mut points,
            &mut springs,
            &mut hinges,
            depth,
        );

        let mirror_partners = mirror_partners(bell_len, &tentacles, points.len());
        let [bell_solver, tentacle_solver] =
            Solver::pair(points.len(), &(0..bell_len), &tentacles, &mirror_partners);
        let scratch = vec![Vec2::ZERO; points.len()];
        let drag_model = TentacleDrag::new(species, seg_len, depth);
        let mut body = Self {
            points,
            bell: 0..bell_len,
            tentacles,
            springs,
            hinges,
            hoop_bends,
            muscles,
            damping_time: species.mesoglea_damping_time(),
            tentacle_drag: vec![drag_model.at(0.0); scratch.len()],
            depth,
            weights: Weights::default(),
            mirror_partners,
            drag_model,
            scratch,
            bell_solver,
            tentacle_solver,
            split: Split::default(),
        };
        body.weights = Weights::of(&body);
        body
    }

    /// Whether `other` has the same points, laid out alike (its positions fit this body).
    pub(crate) fn same_layout(&self, other: &Body) -> bool {
        self.points.len() == other.points.len()
            && self.bell == other.bell
            && self.tentacles == other.tentacles
    }

    /// Each point's partner across the axis, whose mirror image it is: the points past
    /// the axis of a mirror-symmetric body (empty for a planar body free to tilt).
    pub(crate) fn mirror_partners(&self) -> &[Option<usize>] {
        &self.mirror_partners
    }

    /// Holds a planar body mirror-symmetric, solved on its half with the points past the
    /// axis its mirror images (`true`, as built), or lets it tilt, every point solved
    /// (`false`). A body of revolution is always symmetric.
    pub(crate) fn set_mirror_symmetric(&mut self, on: bool) {
        if self.depth.rings() || on != self.mirror_partners.is_empty() {
            return;
        }
        self.mirror_partners = if on {
            mirror_partners(self.bell.len(), &self.tentacles, self.points.len())
        } else {
            Vec::new()
        };
        self.weights = Weights::of(self);
        [self.bell_solver, self.tentacle_solver] = Solver::pair(
            self.points.len(),
            &self.bell,
            &self.tentacles,
            &self.mirror_partners,
        );
    }

    /// The subumbrella's points, left margin to right margin.
    pub(crate) fn bell_points(&self) -> &[Vec2] {
        &self.points[self.bell.clone()]
    }

    /// Index of the apex within [`Self::bell_points`].
    pub(crate) fn apex_index(&self) -> usize {
        self.bell.len() / 2
    }

    /// Centroid of the subumbrellar points.
    pub(crate) fn bell_centroid(&self) -> Vec2 {
        let bell = self.bell_points();
        bell.iter().sum::<Vec2>() / bell.len() as f32
    }

    /// Unit vector from the aperture centre to the apex.
    pub(crate) fn axis(&self) -> Vec2 {
        let bell = self.bell_points();
        let aperture = 0.5 * (bell[0] + bell[bell.len() - 1]);
        (bell[self.apex_index()] - aperture).normalize_or(Vec2::Y)
    }

    /// Area enclosed by the subumbrella and the aperture chord, m² per metre of depth.
    pub(crate) fn bell_area(&self) -> f32 {
        polygon_area(self.bell_points())
    }

    /// Elastic forces at the current positions, N per metre of depth (explicit; the
    /// tests' reference for the implicit forces).
    #[cfg(test)]
    pub(crate) fn forces(&self, out: &mut [Vec2]) {
        out.iter_mut().for_each(|f| *f = Vec2::ZERO);
        for c in constraints(self, &self.points, &Weights::default()) {
            c.add_force(out);
        }
    }

    /// Forces on the water at the positions the points will reach, and the tentacles'
    /// slip through it.
    ///
    /// The bell is an immersed boundary: it solves `(m/dt² + K) δ = F(X̃)` and gives the
    /// water `F* = m/dt²·δ`, where `X̃` are the predicted positions, `K` the Gauss–Newton
    /// stiffness and `m` the fluid mass a point drags along. Its forces sum to zero, no net
    /// force and no net torque, like the springs themselves. Given the `water`'s response
    /// over the step, it solves `(W + K·G) f = F(X̃)` for the forces instead (`G` that
    /// response; `mass_over_dt2` then only weighs the fringe's pull against the margin's
    /// water).
    ///
    /// Tentacles are thin cylinders, not the walls an immersed boundary would make of them
    /// in a slice (as sheets they were sucked into the bell and stopped it): each point
    /// slips through the water against slender-body drag `ξ` ([`Body::tentacle_drag`]),
    /// overdamped, `(ξ/dt + K) δ = F`. The water gets the drag back (`ξ/dt·δ`, in
    /// `forces`), the bell's margins get the tentacles' pull, so the whole body's forces
    /// still sum to zero; `slip` is `δ` on tentacle points (zero on the bell's).
    pub(crate) fn implicit_forces(
        &mut self,
        water: Option<&Response>,
        predicted: &[Vec2],
        dt: f32,
        mass_over_dt2: &[f32],
        forces: &mut [Vec2],
        slip: &mut [Vec2],
    ) {
        let mut split = std::mem::take(&mut self.split);
        let solve = Solve {
            predicted,
            dt,
            mass_over_dt2,
            water,
        };
        self.implicit_forces_split(&mut split, solve, forces, slip);
        self.split = split;
    }

    /// The bell's solved points, in its solver's order.
    pub(crate) fn bell_solved(&self) -> &[usize] {
        self.bell_solver.sequence()
    }

    /// An empty water response over the bell's solved points, in its solver's order.
    pub(crate) fn water_response(&self) -> Response {
        self.bell_solver.response()
    }

    /// [`Self::implicit_forces`] with the elements sorted into `split`'s buffers, which
    /// are kept from step to step.
    fn implicit_forces_split(
        &mut self,
        split: &mut Split,
        solve: Solve,
        forces: &mut [Vec2],
        slip: &mut [Vec2],
    ) {
        let Solve {
            predicted,
            dt,
            mass_over_dt2,
            water,
        } = solve;
        let bell_len = self.bell.end;
        let damping = self.damping_time / dt;
        let Split { bell, tentacles } = split;
        bell.clear();
        tentacles.clear();
        // The strains before the step are read only for the viscosity. Of a body held
        // symmetric, the elements past the axis are left out and their mirror images
        // count twice (`half`): the solve is on the half.
        let before = (damping > 0.0).then_some(&self.points[..]);
        for_each_constraint(self, predicted, before, &self.weights, |c| {
            if c.idx[..c.count].iter().all(|&i| i < bell_len) {
                bell.push(c);
            } else {
                tentacles.push(c);
            }
        });
        // The tentacles move with the bell held where it is predicted to be.
        for c in tentacles.iter_mut() {
            for k in 0..c.count {
                if c.idx[k] < bell_len {
                    c.grad[k] = Vec2::ZERO;
                }
            }
        }
        if self.bell_solver.rhs.is_empty() {
            self.bell_solver.prepare(bell);
            self.tentacle_solver.prepare(tentacles);
        }
        slip.iter_mut().for_each(|s| *s = Vec2::ZERO);
        // The fringe first, the bell held where it is predicted to be. What drags the
        // tentacles along pulls back on the margin they hang from: on the margin's water
        // as far as that water can take it in a step, the rest a load on the bell, which
        // its implicit solve spreads over the water the bell drags. All of it on the
        // margin's water overshot wherever the fringe drags more in a step than that water
        // weighs (a small bell's dense fringe beaten slowly), and the slice blew up.
        let margins = [self.bell.start, self.bell.end - 1];
        let fringe = !tentacles.is_empty();
        let pulls = if fringe {
            self.drag_the_fringe(tentacles, dt, mass_over_dt2, damping, slip)
        } else {
            [Pull::NONE; 2]
        };
        let mut loads = [(0, Vec2::ZERO); 2];
        let mut count = 0;
        for (side, pull) in pulls.iter().enumerate() {
            if let Some(load) = pull.on_bell() {
                loads[count] = (margins[side], load);
                count += 1;
            }
        }
        self.bell_solver.solve_each(
            bell,
            |i| mass_over_dt2[i],
            water,
            damping,
            &loads[..count],
            forces,
        );
        if !fringe {
            return;
        }
        for (side, range) in self.tentacles.clone().into_iter().enumerate() {
            forces[range.clone()].copy_from_slice(&self.scratch[range]);
            forces[margins[side]] -= pulls[side].on_margins_water();
        }
    }

    /// Solves the tentacles' slip through the water against their drag, the bell held
    /// where it is predicted to be, into `scratch` (the forces their water gets) and
    /// `slip`; updates each point's drag for the next step; and gives each side's pull on
    /// its margin.
    fn drag_the_fringe(
        &mut self,
        tentacles: &[Constraint],
        dt: f32,
        mass_over_dt2: &[f32],
        damping: f32,
        slip: &mut [Vec2],
    ) -> [Pull; 2] {
        let drag = &self.tentacle_drag;
        // In r–z the fringe's drag per radian is the same at any radius while the water a
        // point can push shrinks with its ring: no point slips against more drag than the
        // water it drags along could take in one step (it then moves with the water, as a
        // tentacle in syrup does), or the margin and its fringe ring against each other.
        let rings = self.depth.rings();
        let diagonal = |drag: f32, i: usize| {
            let d = drag / dt;
            if rings { d.min(mass_over_dt2[i]) } else { d }
        };
        self.tentacle_solver.solve_each(
            tentacles,
            |i| diagonal(drag[i], i),
            None,
            damping,
            &[],
            &mut self.scratch,
        );
        let margins = [self.bell.start, self.bell.end - 1];
        // What each side's fringe drags in a step against what its margin's water weighs.
        let direct = [0, 1].map(|side| {
            let dragged: f32 = self.tentacles[side]
                .clone()
                .map(|i| diagonal(drag[i], i))
                .sum();
            let direct = (mass_over_dt2[margins[side]] / dragged).min(1.0);
            if direct.is_nan() { 1.0 } else { direct }
        });
        let mut pulls = [Pull::NONE; 2];
        for (side, range) in self.tentacles.clone().into_iter().enumerate() {
            let mut pull = Vec2::ZERO;
            for i in range.clone() {
                let f = self.scratch[i];
                slip[i] = if rings {
                    f / diagonal(self.tentacle_drag[i], i)
                } else {
                    f * dt / self.tentacle_drag[i]
                };
                pull += f;
                // Next step's drag at this step's relative speed, across or along the
                // tentacle.
                let before = if i == range.start {
                    margins[side]
                } else {
                    i - 1
                };
                let after = if i + 1 < range.end { i + 1 } else { i };
                let tangent = (self.points[after] - self.points[before]).normalize_or_zero();
                let direction = slip[i].normalize_or_zero();
                let along = direction.dot(tangent).powi(2);
                let speed = slip[i].length() / dt;
                let last = self.tentacle_drag[i];
                self.tentacle_drag[i] = self
                    .drag_model
                    .at_angle(speed, along)
                    .clamp(last / DRAG_CHANGE, DRAG_CHANGE * last);
            }
            pulls[side] = Pull {
                force: pull,
                direct: direct[side],
            };
        }
        pulls
    }

    /// Averages the body with its mirror image about the vertical line `x = centre`.
    pub(crate) fn symmetrise(&mut self, centre: f32) {
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
    pub(crate) fn is_finite(&self) -> bool {
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
                let stretch = (p[m.b] - p[m.a]).length() - m.rest;
                (p[m.a], p[m.b], m.stiffness_at(stretch) * stretch)
            }))
    }
}

#[cfg(test)]
mod fringe_tests;
#[cfg(test)]
mod tests;
