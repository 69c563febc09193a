//! [`SliceSim`]: one jellyfish slice, fluid and body stepped together.
//!
//! A coupled step, in the paper's order (section 3.2):
//! 1. muscles set their rest lengths for the end of the step;
//! 2. the body predicts where the water carries it and finds its spring forces there
//!    (semi-implicit, see [`Body::implicit_forces`]);
//! 3. the forces are spread to the grid and the fluid steps (advect, force, diffuse,
//!    project);
//! 4. the points move with the new, divergence-free velocity.
//!
//! The domain follows the bell by whole cells, so a jellyfish swims for ever.

use super::SliceView;
use super::body::Body;
use super::coupling::{interpolate_velocity, spread_forces};
use super::fluid::Fluid;
use super::muscle::MuscleDrive;
use crate::species::{Species, SpeciesError};
use glam::Vec2;

/// The fluid mass a body point drags along in one step, in units of `ρ·h²` (per metre of
/// depth). The semi-implicit forces are stable for any stiffness while this stays below
/// about 4/3 of the true value; bilinear spreading of a point at half-cell spacing gives
/// about 1 for the smooth modes, so 0.5 is safe and still settles a stiff spring within
/// two or three steps.
const ADDED_MASS: f32 = 0.5;
/// Courant number for the step: how many cells the fastest water may cross per step.
/// Advection alone is stable beyond 1, but at 1 (44 ms steps) the semi-implicit bell
/// crumpled and turned inside out within a few strokes; at 0.5 it strokes cleanly.
const COURANT: f32 = 0.5;
/// At least this many steps per contraction cycle, so the muscle drive is resolved.
const MIN_STEPS_PER_CYCLE: f32 = 32.0;
/// Width of the absorbing layer along the walls, in bell diameters (of 10 across).
const SPONGE_DIAMETERS: f32 = 2.0;
/// Damping rate at the wall, per contraction cycle.
const SPONGE_RATE: f32 = 4.0;
/// At most this many substeps per `advance` call, so a huge `dt` cannot hang a frame.
const MAX_SUBSTEPS: usize = 4096;

pub struct SliceSim {
    species: Species,
    fluid: Fluid,
    body: Body,
    drive: MuscleDrive,
    time: f64,
    swim_distance: f64,
    /// World position of the domain's origin: the sum of all recentring shifts.
    offset: Vec2,
    /// Where the bell's centroid is held, in domain coordinates.
    home: Vec2,
    recoveries: u32,
    /// max |u| after the last step (NaN if the water blew up), m/s.
    speed: f32,
    /// Hold the slice mirror-symmetric about its axis (see [`SliceSim::set_mirror_symmetry`]).
    mirror_symmetry: bool,
    steps: u64,
    last_substeps: usize,
    velocity: Vec<Vec2>,
    predicted: Vec<Vec2>,
    forces: Vec<Vec2>,
    tentacle_forces: Vec<Vec2>,
    rest_bell: Vec<Vec2>,
    tentacle_view: [Vec<Vec2>; 2],
}

impl SliceSim {
    /// A slice at rest in still water; the species is validated first.
    pub fn new(species: &Species) -> Result<Self, SpeciesError> {
        species.validate()?;
        let n = species.grid_resolution as usize;
        let h = species.cell_size();
        let mut fluid = Fluid::new(n, h, species.kinematic_viscosity(), species.density);
        fluid.advection = species.advection;
        let sponge_cells = (SPONGE_DIAMETERS * species.diameter / h).round() as usize;
        fluid.set_sponge(sponge_cells, SPONGE_RATE * species.contraction_frequency);
        let size = fluid.size();
        // Aperture a little below the centre: the wake needs more room than the bow.
        let origin = Vec2::new(0.5 * size, 0.5 * size - 0.5 * species.height);
        let body = Body::new(species, origin, h);
        let home = body.bell_centroid();
        let rest_bell = body.bell_points().to_vec();
        let count = body.points.len();
        let mut sim = Self {
            species: species.clone(),
            fluid,
            body,
            drive: MuscleDrive::new(species),
            time: 0.0,
            swim_distance: 0.0,
            offset: Vec2::ZERO,
            home,
            recoveries: 0,
            speed: 0.0,
            mirror_symmetry: true,
            steps: 0,
            last_substeps: 0,
            velocity: vec![Vec2::ZERO; count],
            predicted: vec![Vec2::ZERO; count],
            forces: vec![Vec2::ZERO; count],
            tentacle_forces: vec![Vec2::ZERO; count],
            rest_bell,
            tentacle_view: [Vec::new(), Vec::new()],
        };
        sim.refresh_view();
        Ok(sim)
    }

    /// Advances by `dt` seconds (any value; substeps as stability needs). A `dt` that is
    /// not finite or not positive does nothing.
    pub fn advance(&mut self, dt: f32) {
        if !dt.is_finite() || dt <= 0.0 {
            return;
        }
        // The stable step is re-measured every substep: a stroke can speed the water up
        // within one long frame.
        let mut left = dt;
        let mut substeps = 0;
        while left > 0.0 && substeps < MAX_SUBSTEPS {
            let max = self.max_step();
            // Split what is left evenly rather than leave a sliver for the last step.
            let h = left / (left / max).ceil().max(1.0);
            self.step(h);
            left -= h;
            substeps += 1;
            if left < 1e-6 * dt {
                break;
            }
        }
        self.last_substeps = substeps;
        self.refresh_view();
    }

    /// The largest stable, accurate step for the current flow, s.
    pub fn max_step(&self) -> f32 {
        let speed = self.speed.max(1e-6);
        let cfl = COURANT * self.fluid.h / speed;
        cfl.min(Self::accurate_step(&self.species))
    }

    /// The longest step that resolves the muscle drive (1/32 of a stroke), s. The flow
    /// can ask for shorter ones (the Courant limit), rarely at these speeds.
    pub fn accurate_step(species: &Species) -> f32 {
        species.period() / MIN_STEPS_PER_CYCLE
    }

    /// One coupled step of `dt` seconds.
    fn step(&mut self, dt: f32) {
        let next_time = self.time + dt as f64;
        self.set_muscles(next_time);

        interpolate_velocity(&self.fluid, &self.body.points, &mut self.velocity);
        for ((x, v), p) in self
            .body
            .points
            .iter()
            .zip(&self.velocity)
            .zip(&mut self.predicted)
        {
            *p = *x + dt * *v;
        }
        let mass = ADDED_MASS * self.species.density * self.fluid.h * self.fluid.h;
        self.body.implicit_forces(
            &self.predicted,
            mass / (dt * dt),
            &mut self.forces,
            &mut self.tentacle_forces,
        );
        spread_forces(&mut self.fluid, &self.body.points, &self.forces);

        self.fluid.step(dt);
        self.speed = self.fluid.speed_max();

        let before = self.body.bell_centroid();
        interpolate_velocity(&self.fluid, &self.body.points, &mut self.velocity);
        for (x, v) in self.body.points.iter_mut().zip(&self.velocity) {
            *x += dt * *v;
        }
        // Tentacles are one-way coupled: the flow carries them and their springs move them
        // relative to it, but they give no force back. As two-way immersed boundaries the
        // soft 2D tentacle sheets were sucked into the bell by the refilling flow within a
        // few strokes, and their pull at the margin crumpled the bell.
        for range in self.body.tentacles.clone() {
            for i in range {
                self.body.points[i] += (dt * dt / mass) * self.tentacle_forces[i];
            }
        }
        self.time = next_time;
        self.steps += 1;
        if self.mirror_symmetry {
            self.fluid.symmetrise();
            self.body.symmetrise(0.5 * self.fluid.size());
        }

        if !self.healthy() {
            self.recover();
            return;
        }
        let moved = self.body.bell_centroid() - before;
        self.swim_distance += moved.dot(self.body.axis()) as f64;
        self.recentre();
    }

    fn set_muscles(&mut self, time: f64) {
        let phase = (time * self.species.contraction_frequency as f64).fract() as f32;
        for m in &mut self.body.muscles {
            m.rest = m.relaxed * self.drive.rest_factor(phase, m.level);
        }
    }

    /// Keeps the bell within a cell of home by shifting the fluid and body by whole cells;
    /// the world position (and so `swim_distance`) does not jump.
    fn recentre(&mut self) {
        let h = self.fluid.h;
        let drift = self.body.bell_centroid() - self.home;
        let cells = |d: f32| {
            if d > h {
                1
            } else if d < -h {
                -1
            } else {
                0
            }
        };
        let (dx, dy) = (cells(drift.x), cells(drift.y));
        if dx == 0 && dy == 0 {
            return;
        }
        self.fluid.shift(dx, dy);
        let shift = Vec2::new(dx as f32, dy as f32) * h;
        for p in &mut self.body.points {
            *p -= shift;
        }
        self.offset += shift;
    }

    /// Whether the state is finite and physically plausible.
    fn healthy(&self) -> bool {
        if !self.body.is_finite() || !self.speed.is_finite() {
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
        span_ok && self.speed < speed_limit
    }

    /// Restarts a blown-up slice at rest where the bell was, keeping time and distance.
    fn recover(&mut self) {
        let h = self.fluid.h;
        self.fluid.clear();
        self.speed = 0.0;
        let size = self.fluid.size();
        let origin = Vec2::new(0.5 * size, 0.5 * size - 0.5 * self.species.height);
        self.body = Body::new(&self.species, origin, h);
        self.recoveries += 1;
    }

    fn refresh_view(&mut self) {
        let bell = self.body.bell_points();
        let margins = [bell[0], bell[bell.len() - 1]];
        for ((view, margin), range) in self
            .tentacle_view
            .iter_mut()
            .zip(margins)
            .zip(&self.body.tentacles)
        {
            view.clear();
            view.push(margin);
            view.extend_from_slice(&self.body.points[range.clone()]);
        }
    }

    // --- The headless API of DESIGN.md section 4 ---

    /// Simulated seconds since the start.
    pub fn time(&self) -> f32 {
        self.time as f32
    }

    /// Metres travelled along the bell's axis, apex direction positive, since the start,
    /// through any recentring of the domain.
    pub fn swim_distance(&self) -> f32 {
        self.swim_distance as f32
    }

    /// Subumbrellar points in domain coordinates, m (left margin, apex, right margin).
    pub fn bell_points(&self) -> &[Vec2] {
        self.body.bell_points()
    }

    /// max |div u| after the last projection, 1/s.
    pub fn fluid_divergence_max(&self) -> f32 {
        self.fluid.divergence_max()
    }

    /// max |u| over the grid, m/s.
    pub fn fluid_speed_max(&self) -> f32 {
        self.fluid.speed_max()
    }

    // --- More ---

    pub fn species(&self) -> &Species {
        &self.species
    }

    /// The slice as the renderer needs it: bell, rest bell and tentacles, all in domain
    /// coordinates.
    pub fn view(&self) -> SliceView<'_> {
        SliceView {
            bell: self.body.bell_points(),
            rest_bell: &self.rest_bell,
            tentacles: [&self.tentacle_view[0], &self.tentacle_view[1]],
        }
    }

    /// The fluid grid (for debug overlays and tests).
    pub fn fluid(&self) -> &Fluid {
        &self.fluid
    }

    /// The spring-mass body.
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// World position of the domain origin; world = domain + offset.
    pub fn offset(&self) -> Vec2 {
        self.offset
    }

    /// Centroid of the bell in world coordinates, m.
    pub fn bell_centroid_world(&self) -> Vec2 {
        self.body.bell_centroid() + self.offset
    }

    /// Unit vector from the aperture centre to the apex.
    pub fn axis(&self) -> Vec2 {
        self.body.axis()
    }

    /// Tilt of the axis from +y, rad (positive = counter-clockwise).
    pub fn tilt(&self) -> f32 {
        let a = self.axis();
        (-a.x).atan2(a.y)
    }

    /// Area enclosed by the subumbrella and the aperture chord, m² per metre of depth.
    pub fn bell_area(&self) -> f32 {
        self.body.bell_area()
    }

    /// Contraction cycle phase in [0, 1).
    pub fn phase(&self) -> f32 {
        (self.time * self.species.contraction_frequency as f64).fract() as f32
    }

    /// Completed contraction cycles.
    pub fn cycle(&self) -> u64 {
        (self.time * self.species.contraction_frequency as f64).floor() as u64
    }

    /// Whether the slice is held mirror-symmetric about the vertical through the domain
    /// centre (on by default). The paper models axially symmetric jellyfish; a 2D wake,
    /// unlike a 3D vortex ring, sheds asymmetrically and tips a free slice over within a
    /// few strokes from round-off alone. Turn it off to let the slice tilt (steering).
    pub fn set_mirror_symmetry(&mut self, on: bool) {
        self.mirror_symmetry = on;
    }

    /// Moves the muscle clock to `time` seconds without stepping: individuals spawned
    /// together then beat out of step (a phase offset) at no cost. Meant for a fresh slice;
    /// a negative or non-finite `time` does nothing.
    pub fn set_time(&mut self, time: f32) {
        if time.is_finite() && time >= 0.0 {
            self.time = time as f64;
        }
    }

    /// How often a blown-up state was detected and restarted.
    pub fn recoveries(&self) -> u32 {
        self.recoveries
    }

    /// Coupled steps taken since the start.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Substeps the last `advance` took.
    pub fn last_substeps(&self) -> usize {
        self.last_substeps
    }

    /// Corrupts one body point with NaN, as a blow-up would: for testing recovery.
    #[doc(hidden)]
    pub fn poison_for_tests(&mut self) {
        self.body.points[0] = Vec2::NAN;
    }

    /// Applies new parameters to a living slice. Muscle timing, stiffness and water take
    /// effect at once; a change of geometry or grid rebuilds the slice at rest in place,
    /// keeping time, distance and world position.
    pub fn set_species(&mut self, species: &Species) -> Result<(), SpeciesError> {
        species.validate()?;
        let rebuild = species.grid_resolution != self.species.grid_resolution
            || species.diameter != self.species.diameter
            || species.height != self.species.height
            || species.domain_diameters != self.species.domain_diameters
            || species.tentacle_length != self.species.tentacle_length
            || species.thickness != self.species.thickness;
        if rebuild {
            let mut fresh = SliceSim::new(species)?;
            fresh.time = self.time;
            fresh.swim_distance = self.swim_distance;
            fresh.offset = self.bell_centroid_world() - fresh.body.bell_centroid();
            fresh.recoveries = self.recoveries;
            *self = fresh;
            return Ok(());
        }
        let h = self.fluid.h;
        let mut rebuilt = Body::new(species, Vec2::ZERO, h);
        // Same topology: keep positions, take the new stiffnesses.
        rebuilt.points.clone_from(&self.body.points);
        self.body = rebuilt;
        self.fluid.nu = species.kinematic_viscosity();
        self.fluid.rho = species.density;
        self.fluid.advection = species.advection;
        self.drive = MuscleDrive::new(species);
        self.species = species.clone();
        Ok(())
    }
}
