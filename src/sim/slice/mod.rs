//! [`SliceSim`]: one jellyfish slice, fluid and body stepped together in fixed steps of
//! its own ([`clock`](super::clock)), in a box that follows the bell ([`frame`]), so a
//! jellyfish swims for ever.

mod frame;
mod health;
mod step;

use super::SliceView;
use super::body::{Body, Outline, signed_area};
use super::clock::FixedClock;
use super::coupling::Coupling;
use super::escape::Escape;
use super::fluid::Fluid;
use super::muscle::MuscleDrive;
use super::oral_arms::OralArms;
use super::response::Response;
use crate::species::{SliceGeometry, Species, SpeciesError};
use frame::ComovingFrame;
use glam::Vec2;
/// Depth of the absorbing layer at the wake end, in bell diameters.
const SPONGE_DIAMETERS: f32 = 1.0;
/// Damping rate at the wake end, per contraction cycle.
const SPONGE_RATE: f32 = 4.0;
/// Water ahead of the bell's apex, in bell diameters: the rest of the box is for the wake.
const BOW_DIAMETERS: f32 = 1.5;

/// The coupled 2D slice: fluid, bell, tentacles and muscles, stepped together in fixed
/// steps of its own (the headless API: `docs/usage.md`, "Use it headless").
#[derive(Clone)]
pub struct SliceSim {
    species: Species,
    fluid: Fluid,
    body: Body,
    drive: MuscleDrive,
    clock: FixedClock,
    swim_distance: f64,
    /// The box's motion along the channel.
    frame: ComovingFrame,
    /// World position of the box across the channel: the sum of whole-cell shifts, m.
    across: f32,
    /// Where the bell's centroid is held, in domain coordinates.
    home: Vec2,
    /// The bell's centroid relative to home after the last healthy step.
    drift: Vec2,
    recoveries: u32,
    /// A bound on max |u| after the last step (NaN if the water blew up), m/s.
    speed: f32,
    /// Hold the slice mirror-symmetric about its axis (see [`SliceSim::set_mirror_symmetry`]).
    mirror_symmetry: bool,
    /// The stroke is held (see [`SliceSim::set_resting`]).
    resting: bool,
    /// Coupled substeps taken (a fixed step is one, or two or four when split).
    substeps: u64,
    last_substeps: usize,
    coupling: Coupling,
    /// The water's response to the bell over a step, for its implicit solve.
    water: Response,
    velocity: Vec<Vec2>,
    predicted: Vec<Vec2>,
    forces: Vec<Vec2>,
    /// Each point's dragged water mass over dt², and its reciprocal, for the step.
    mass_over_dt2: Vec<f32>,
    dt2_over_mass: Vec<f32>,
    /// Tentacle points' slip through the water over the last step, m.
    slip: Vec<Vec2>,
    rest_bell: Vec<Vec2>,
    tentacle_view: [Vec<Vec2>; 2],
    /// Carried by the water, never pushing it.
    oral_arms: OralArms,
    /// A startle under way: deeper, quicker strokes ([`SliceSim::escape`]).
    escape: Option<Escape>,
}

impl SliceSim {
    /// A slice at rest in still water; the species is validated first.
    pub fn new(species: &Species) -> Result<Self, SpeciesError> {
        species.validate()?;
        let n = species.grid_resolution as usize;
        let h = species.cell_size();
        let mut fluid = Fluid::new(n, h, species.kinematic_viscosity(), species.density);
        fluid.advection = species.advection;
        fluid.kernel = species.kernel;
        fluid.kernel_stretch = Self::kernel_stretch(species);
        fluid.mirror = true;
        fluid.set_geometry(species.slice_geometry);
        let sponge_cells = (SPONGE_DIAMETERS * species.diameter / h).round() as usize;
        fluid.set_sponge(sponge_cells, SPONGE_RATE * species.contraction_frequency);
        let body = Body::new(species, Self::rest_origin(species, &fluid), h);
        let home = body.bell_centroid();
        let rest_bell = body.bell_points().to_vec();
        let count = body.points.len();
        let oral_arms = OralArms::new(species, body.bell_points()[body.apex_index()], body.axis());
        let mut sim = Self {
            species: species.clone(),
            fluid,
            body,
            drive: MuscleDrive::new(species),
            clock: FixedClock::new(species.period(), Self::steps_per_cycle(species)),
            swim_distance: 0.0,
            frame: ComovingFrame::new(species.period()),
            across: 0.0,
            home,
            drift: Vec2::ZERO,
            recoveries: 0,
            speed: 0.0,
            mirror_symmetry: true,
            resting: false,
            substeps: 0,
            last_substeps: 0,
            coupling: Coupling::default(),
            water: Response::default(),
            velocity: vec![Vec2::ZERO; count],
            predicted: vec![Vec2::ZERO; count],
            forces: vec![Vec2::ZERO; count],
            mass_over_dt2: vec![0.0; count],
            dt2_over_mass: vec![0.0; count],
            slip: vec![Vec2::ZERO; count],
            rest_bell,
            tentacle_view: [Vec::new(), Vec::new()],
            oral_arms,
            escape: None,
        };
        sim.refresh_view();
        Ok(sim)
    }

    /// Adds `dt` seconds to the slice's clock and takes the fixed steps that pays for
    /// ([`Self::step_length`]): any split of the same total time gives the same state. A
    /// `dt` that is not finite or not positive does nothing; one huge `dt` takes at most
    /// [`MAX_STEPS_PER_ADVANCE`](super::clock::MAX_STEPS_PER_ADVANCE) steps.
    pub fn advance(&mut self, dt: f32) {
        self.advance_with(dt, |_| {});
    }

    /// [`Self::advance`], calling `after_step` with the slice after each fixed step (to
    /// keep the states a renderer interpolates between).
    pub fn advance_with(&mut self, dt: f32, after_step: impl FnMut(&Self)) {
        let due = self.clock.add(dt as f64);
        self.take_steps(due, after_step);
    }

    /// [`Self::advance_with`] to a total: the time added since the start becomes `added`
    /// seconds ([`FixedClock::add_until`]), for a caller that keeps an exact total.
    pub fn advance_until_with(&mut self, added: f64, after_step: impl FnMut(&Self)) {
        let due = self.clock.add_until(added);
        self.take_steps(due, after_step);
    }

    fn take_steps(&mut self, due: u64, mut after_step: impl FnMut(&Self)) {
        let before = self.substeps;
        for _ in 0..due {
            self.fixed_step();
            self.refresh_view();
            after_step(self);
        }
        self.last_substeps = (self.substeps - before) as usize;
    }

    /// Exactly one fixed step, whatever time was added (recording a cycle).
    pub(crate) fn step_once(&mut self) {
        self.clock.add(self.clock.step());
        self.fixed_step();
        self.refresh_view();
    }

    /// Puts the slice on another clock (a jellyfish resuming from a recorded cycle keeps
    /// its own time and phase). The clock's step should be this species' step.
    pub fn set_clock(&mut self, clock: FixedClock) {
        self.clock = clock;
    }

    /// Heap bytes held, roughly: the fluid's fields dominate.
    pub fn bytes(&self) -> usize {
        self.fluid.bytes()
            + self.body.points.len() * 6 * std::mem::size_of::<Vec2>()
            + self.oral_arms.bytes()
    }

    /// Fixed steps per contraction cycle for `species` ([`Species::steps_per_cycle`]).
    pub fn steps_per_cycle(species: &Species) -> u32 {
        species.steps_per_cycle()
    }

    /// Where the aperture's centre sits at rest, in domain coordinates: on the axis, with
    /// [`BOW_DIAMETERS`] of water ahead of the apex and the rest of the box for the wake.
    fn rest_origin(species: &Species, fluid: &Fluid) -> Vec2 {
        let size = fluid.size();
        let below_top = BOW_DIAMETERS * species.diameter + species.height;
        Vec2::new(
            fluid.axis(),
            (size - below_top).max(0.5 * size - 0.5 * species.height),
        )
    }

    /// How many times three cells the immersed-boundary kernel spans: the species'
    /// `boundary_width`, never less than three cells.
    pub fn kernel_stretch(species: &Species) -> f32 {
        species.kernel_stretch_at(species.cell_size())
    }

    /// The slice's fixed step for `species`, s: a whole fraction of the contraction period.
    pub fn step_length(species: &Species) -> f32 {
        species.step_length()
    }

    /// Oral arms hanging at rest from the bell where it is now.
    fn hanging_arms(&self, species: &Species) -> OralArms {
        let apex = self.body.bell_points()[self.body.apex_index()];
        OralArms::new(species, apex, self.body.axis())
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

    // --- The headless API (`docs/usage.md`); these keep their meaning ---

    /// Simulated seconds of the state: the end of the last fixed step.
    pub fn time(&self) -> f32 {
        self.clock.time() as f32
    }

    /// The slice's clock: time added, steps taken, and how far past the state it is.
    pub fn clock(&self) -> &FixedClock {
        &self.clock
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

    /// The species it runs with.
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
            oral_arms: [&self.oral_arms.chains[0], &self.oral_arms.chains[1]],
            trail: crate::sim::guides::Trail::NONE,
            oral_trail: crate::sim::guides::Trail::NONE,
        }
    }

    /// The fluid grid, for debug overlays and measurements ([`inspect`](crate::sim::inspect):
    /// not semver-stable).
    pub fn fluid(&self) -> &Fluid {
        &self.fluid
    }

    /// The spring-mass body, for debug overlays and measurements
    /// ([`inspect`](crate::sim::inspect): not semver-stable).
    pub fn body(&self) -> &Body {
        &self.body
    }

    /// World position of the domain origin; world = domain + offset.
    pub fn offset(&self) -> Vec2 {
        Vec2::new(self.across, self.frame.position as f32)
    }

    /// Velocity of the box (the frame the fluid's velocities are relative to), m/s.
    pub fn frame_velocity(&self) -> Vec2 {
        Vec2::Y * self.frame.velocity
    }

    /// Centroid of the bell in world coordinates, m.
    pub fn bell_centroid_world(&self) -> Vec2 {
        self.body.bell_centroid() + self.offset()
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

    /// The bell's outline against its rest shape: whole, crossed or inside out.
    pub fn outline(&self) -> Outline {
        Outline::of(self.body.bell_points(), signed_area(&self.rest_bell))
    }

    /// How much longer the subumbrella is from margin to margin than at rest (0 at its
    /// rest length, 0.1 a tenth longer). The stroke's loads stretch the mesoglea by about
    /// a percent; what more a slice shows is its step's give: the wall's response to its
    /// own forces through the water, which the implicit solve's one assumed mass a point
    /// does not match mode by mode; with the water's one-step response in the solve the
    /// wall holds its length at any step (`docs/numerics.md`, "The meridian through a
    /// stroke, by phase" and "A coupling that sees the water's response").
    pub fn meridian_strain(&self) -> f32 {
        let length =
            |points: &[Vec2]| -> f32 { points.windows(2).map(|w| w[0].distance(w[1])).sum() };
        length(self.body.bell_points()) / length(&self.rest_bell) - 1.0
    }

    /// Contraction cycle phase of the state in [0, 1).
    pub fn phase(&self) -> f32 {
        self.clock.phase()
    }

    /// Completed contraction cycles.
    pub fn cycle(&self) -> u64 {
        self.clock.cycle()
    }

    /// Whether the slice is held mirror-symmetric about the vertical through the domain
    /// centre (on by default). The paper models axially symmetric jellyfish; a 2D wake,
    /// unlike a 3D vortex ring, sheds asymmetrically and tips a free slice over within a
    /// few strokes from round-off alone. Turn it off to let a planar slice tilt; an
    /// axisymmetric slice is a body of revolution and stays symmetric whatever is set.
    pub fn set_mirror_symmetry(&mut self, on: bool) {
        self.mirror_symmetry = on;
        self.body.set_mirror_symmetric(on);
        self.fluid.mirror = on || self.fluid.rings().is_some();
    }

    /// Holds the stroke (`true`) or resumes it: while resting the muscles keep the length
    /// they had and the bell drifts in its water; the stroke's phase does not advance, so
    /// it resumes where it stopped. Time, the water and the bell's flow go on.
    pub fn set_resting(&mut self, resting: bool) {
        self.resting = resting;
    }

    /// Whether the stroke is held.
    pub fn resting(&self) -> bool {
        self.resting
    }

    /// Startles the jellyfish with a touch of `strength` (0 to 1): from its next fixed step
    /// its muscles beat deeper and quicker for the species' `escape_strokes`, then ease
    /// back into its rhythm (`escape_depth`, `escape_rhythm`). A touch during an escape
    /// renews it at the stronger of the two; a species without an escape, or a touch
    /// without strength (or not finite), does nothing.
    pub fn escape(&mut self, strength: f32) {
        let per_cycle = self.clock.steps_per_cycle();
        let Some(fresh) = Escape::new(&self.species, per_cycle, strength) else {
            return;
        };
        match &mut self.escape {
            Some(e) => e.renew(fresh),
            None => self.escape = Some(fresh),
        }
    }

    /// The escape under way, if any.
    pub fn escaping(&self) -> Option<&Escape> {
        self.escape.as_ref()
    }

    /// Carries on an escape begun elsewhere (the jellyfish's replay at another level of
    /// detail), counted in this slice's steps.
    pub fn resume_escape(&mut self, escape: Option<Escape>) {
        self.escape = escape;
    }

    /// Moves the clock to `time` seconds without stepping: individuals spawned together
    /// then beat out of step (a phase offset) at no cost, and take their steps on
    /// different frames. Meant for a fresh slice; a negative or non-finite `time` does
    /// nothing.
    pub fn set_time(&mut self, time: f32) {
        self.clock.start_at(time as f64);
    }

    /// How often a blown-up state was detected and restarted.
    pub fn recoveries(&self) -> u32 {
        self.recoveries
    }

    /// Coupled steps taken since the start (a fixed step split in two counts two).
    pub fn steps(&self) -> u64 {
        self.substeps
    }

    /// Coupled steps the last `advance` took.
    pub fn last_substeps(&self) -> usize {
        self.last_substeps
    }

    /// Corrupts one body point with NaN, as a blow-up would: for testing recovery.
    #[doc(hidden)]
    pub fn poison_for_tests(&mut self) {
        self.body.points[0] = Vec2::NAN;
    }

    /// Folds each margin across the other half of the bell, as a crumpling bell would (and
    /// symmetrically, so the mirror symmetry keeps the fold): for testing that the health
    /// check sees a crossed outline.
    #[doc(hidden)]
    pub fn fold_for_tests(&mut self) {
        let n = self.body.bell.len();
        let p = &mut self.body.points;
        let (apex, left, right) = (p[n / 2], p[0], p[n - 1]);
        let (reach, height) = (0.3 * self.species.diameter, 0.5 * (apex.y + right.y));
        // Out past the other side, half way up: the margins' edges cut across the bell.
        p[0] = Vec2::new(right.x + reach, height);
        p[n - 1] = Vec2::new(left.x - reach, height);
    }

    /// Applies new parameters to a living slice. Muscle timing, stiffness and water take
    /// effect at once; a change of geometry, grid, size, band or of the body's points (a
    /// fringe added or taken away) rebuilds the slice at rest in place, keeping time,
    /// distance and world position.
    pub fn set_species(&mut self, species: &Species) -> Result<(), SpeciesError> {
        species.validate()?;
        self.set_valid_species(species)
    }

    /// [`Self::set_species`] for a species already validated (an edit reaching a hundred
    /// slices is checked once).
    pub(crate) fn set_valid_species(&mut self, species: &Species) -> Result<(), SpeciesError> {
        let reshaped = species.grid_resolution != self.species.grid_resolution
            || species.diameter != self.species.diameter
            || species.height != self.species.height
            || species.domain_diameters != self.species.domain_diameters
            || species.tentacle_length != self.species.tentacle_length
            || species.thickness != self.species.thickness
            || species.slice_geometry != self.species.slice_geometry
            // The band's width sets the points' spacing.
            || Self::kernel_stretch(species) != Self::kernel_stretch(&self.species);
        // Same topology: keep positions, take the new stiffnesses (rings about the live
        // axis). A body laid out otherwise (a fringe added or taken away) starts afresh.
        let origin = match species.slice_geometry {
            SliceGeometry::Planar => Vec2::ZERO,
            SliceGeometry::Axisymmetric => Vec2::X * self.fluid.axis(),
        };
        let kept = (!reshaped)
            .then(|| Body::new(species, origin, self.fluid.h))
            .filter(|body| body.same_layout(&self.body));
        let Some(mut rebuilt) = kept else {
            let mut fresh = SliceSim::new(species)?;
            fresh.clock = self
                .clock
                .retimed(species.period(), Self::steps_per_cycle(species));
            fresh.swim_distance = self.swim_distance;
            let world = self.bell_centroid_world() - fresh.body.bell_centroid();
            fresh.across = world.x;
            fresh.frame.position = world.y as f64;
            fresh.recoveries = self.recoveries;
            fresh.set_mirror_symmetry(self.mirror_symmetry);
            *self = fresh;
            return Ok(());
        };
        rebuilt.points.clone_from(&self.body.points);
        rebuilt.set_mirror_symmetric(self.mirror_symmetry);
        self.body = rebuilt;
        self.fluid.nu = species.kinematic_viscosity();
        self.fluid.rho = species.density;
        self.fluid.advection = species.advection;
        self.fluid.kernel = species.kernel;
        self.fluid.kernel_stretch = Self::kernel_stretch(species);
        self.drive = MuscleDrive::new(species);
        if anatomy_changed(species, &self.species) {
            self.oral_arms = self.hanging_arms(species);
        }
        self.clock = self
            .clock
            .retimed(species.period(), Self::steps_per_cycle(species));
        self.species = species.clone();
        Ok(())
    }
}

/// Whether the manubrium or the arms changed shape (they are then hung afresh).
fn anatomy_changed(a: &Species, b: &Species) -> bool {
    (
        a.manubrium_length,
        a.manubrium_radius,
        a.oral_arm_count,
        a.oral_arm_length,
    ) != (
        b.manubrium_length,
        b.manubrium_radius,
        b.oral_arm_count,
        b.oral_arm_length,
    )
}
