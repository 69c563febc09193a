//! The coupled step, in the paper's order (section 3.2):
//! 1. muscles set their rest lengths for the end of the step;
//! 2. the body predicts where the water carries it and finds its spring forces there
//!    (semi-implicit, see [`Body::implicit_forces`](crate::sim::body::Body::implicit_forces));
//! 3. the forces are spread to the grid and the fluid steps (advect, force, diffuse,
//!    project);
//! 4. the points move with the new, divergence-free velocity;
//! 5. the frame follows the bell.

use super::SliceSim;
use crate::species::BellCoupling;
use glam::Vec2;

/// The fluid mass a body point drags along in one step, in units of `ρ·h²` (per metre of
/// depth). The semi-implicit forces are stable for any stiffness while this stays below
/// about 4/3 of the true value; spreading a point at half-cell spacing gives about 1 for
/// the smooth modes, so 0.5 is safe and still settles a stiff spring within two or three
/// steps. Along the wall the water is two to four times more, but no one mass fits
/// every mode: a tangential block twice as heavy takes a third of the meridian's give,
/// four times as heavy rings (`docs/numerics.md`, "The meridian through a stroke, by
/// phase"). A species with `BellCoupling::WaterResponse` solves against the water's
/// response instead; this mass then weighs only the fringe and the relaxation.
pub(super) const ADDED_MASS: f32 = 0.5;
/// A fixed step is split in two (then four …) when the measured flow would cross more
/// cells than this in it; the split depends only on the state, so it is the same every run.
const COURANT_SPLIT: f32 = 1.0;

impl SliceSim {
    /// One fixed step, split in 2ᵏ equal substeps if the water is faster than expected.
    pub(super) fn fixed_step(&mut self) {
        let dt = self.clock.step() as f32;
        let crossing = self.speed * dt / self.fluid.h;
        let mut split = 1u32;
        while (split as f32) * COURANT_SPLIT < crossing && split < 64 {
            split *= 2;
        }
        let per_cycle = self.clock.steps_per_cycle() as u64;
        let first = (self.clock.stroke_steps() % per_cycle) * split as u64;
        let n = per_cycle * split as u64;
        // An escape beats deeper, and quicker: some steps move the phase on by two.
        let (depth, stroke_steps) = match &mut self.escape {
            Some(e) if !self.resting => (e.depth(&self.species), e.step(&self.species) as u64),
            _ => (1.0, 1),
        };
        if self.escape.as_ref().is_some_and(|e| e.done()) {
            self.escape = None;
        }
        for s in 1..=split as u64 {
            // Resting holds the muscles where the stroke stopped.
            let phase = if self.resting {
                first as f32 / n as f32
            } else {
                ((first + s * stroke_steps) % n) as f32 / n as f32
            };
            self.step(dt / split as f32, phase, depth);
        }
        if self.resting {
            self.clock.tick_held();
        } else {
            self.clock.tick();
            (1..stroke_steps).for_each(|_| self.clock.hurry());
        }
    }

    /// One coupled step of `dt` seconds, ending at muscle phase `phase`, the stroke
    /// `depth` times its own depth.
    fn step(&mut self, dt: f32, phase: f32, depth: f32) {
        self.set_muscles(phase, depth);
        self.substeps += 1;
        self.coupling
            .locate(&self.fluid, &self.body.points, self.body.mirror_partners());
        self.coupling.interpolate(&self.fluid, &mut self.velocity);
        for ((x, v), p) in self
            .body
            .points
            .iter()
            .zip(&self.velocity)
            .zip(&mut self.predicted)
        {
            *p = *x + dt * *v;
        }
        // The water a point drags along: per metre of a plane, per radian of its ring.
        let mass = ADDED_MASS * self.species.density * self.fluid.h * self.fluid.h;
        let depth = self.body.depth;
        for ((m, inverse), p) in self
            .mass_over_dt2
            .iter_mut()
            .zip(&mut self.dt2_over_mass)
            .zip(&self.body.points)
        {
            let mass = mass * depth.at(*p);
            *m = mass / (dt * dt);
            *inverse = dt * dt / mass;
        }
        let water = match self.species.bell_coupling {
            BellCoupling::AddedMass => None,
            BellCoupling::WaterResponse => {
                if self.water.points() != self.body.bell_solved() {
                    self.water = self.body.water_response();
                }
                self.coupling.respond(&self.fluid, dt, &mut self.water);
                self.body
                    .add_relaxation(&mut self.water, &self.dt2_over_mass);
                Some(&self.water)
            }
        };
        self.body.implicit_forces(
            water,
            &self.predicted,
            dt,
            &self.mass_over_dt2,
            &mut self.forces,
            &mut self.slip,
        );
        self.coupling.spread(&mut self.fluid, &self.forces);

        self.fluid.step(dt);
        self.speed = self.fluid.speed_bound();

        let before = self.body.bell_centroid();
        self.coupling.interpolate(&self.fluid, &mut self.velocity);
        for ((x, v), slip) in self
            .body
            .points
            .iter_mut()
            .zip(&self.velocity)
            .zip(&self.slip)
        {
            *x += dt * *v + *slip;
        }
        self.body
            .relax_unresolved(&self.forces, &self.dt2_over_mass);
        if self.mirror_symmetry || depth.rings() {
            self.body.symmetrise(self.fluid.axis());
        }
        self.body.keep_tentacles_outside();
        let bell = self.body.bell_points();
        let mirror = (self.mirror_symmetry || depth.rings()).then(|| self.fluid.axis());
        self.oral_arms.step(
            &self.fluid,
            bell[bell.len() / 2],
            self.body.axis(),
            dt,
            mirror,
        );

        if !self.healthy() {
            self.recover();
            return;
        }
        let moved = self.body.bell_centroid() - before;
        let world = moved + Vec2::Y * self.frame.velocity * dt;
        self.swim_distance += world.dot(self.body.axis()) as f64;
        self.follow(dt, moved.y);
    }

    fn set_muscles(&mut self, phase: f32, depth: f32) {
        for m in &mut self.body.muscles {
            let factor = self.drive.rest_factor(phase, m.level);
            // Exactly the species' stroke outside an escape (1 − (1 − f) rounds).
            let factor = if depth == 1.0 {
                factor
            } else {
                1.0 - (1.0 - factor) * depth
            };
            m.contract(factor, self.drive.ratio);
        }
    }

    /// The frame follows the bell along the channel; across it (only a slice that is not
    /// mirror-symmetric drifts sideways) the box shifts by whole cells when the bell is more
    /// than a cell off the axis.
    fn follow(&mut self, dt: f32, moved_along: f32) {
        let from_home = self.body.bell_centroid() - self.home;
        self.drift = from_home;
        let change = self.frame.follow(dt, moved_along, from_home.y);
        self.fluid.change_frame(change);
        let h = self.fluid.h;
        let dx = if from_home.x > h {
            1
        } else if from_home.x < -h {
            -1
        } else {
            0
        };
        if dx != 0 {
            self.fluid.shift_across(dx);
            let shift = Vec2::X * dx as f32 * h;
            self.body.points.iter_mut().for_each(|p| *p -= shift);
            self.oral_arms.shift(-shift);
            self.across += shift.x;
        }
    }
}
