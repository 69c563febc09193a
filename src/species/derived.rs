//! What follows from a species' fields: the fluid box and its cells, the water's
//! kinematic viscosity, the mesoglea's damping, the period and the fixed step.

use super::{Bending, MuscleTiming, Species, limits};

/// The hinge length `angular_stiffness` refers to, m (grid 100: half a 4 mm cell): the
/// bending per radian of a 2 mm stretch of wall.
pub const REFERENCE_HINGE_LENGTH: f32 = 0.002;

impl Species {
    /// Fluid cell size, m.
    pub fn cell_size(&self) -> f32 {
        self.domain_size() / self.grid_resolution as f32
    }

    /// How many times three cells of `h` metres the immersed-boundary kernel spans: the
    /// bell's `boundary_width`, never less than the kernel's own three cells. The body's
    /// points sit half a stretched cell apart, so a grid finer than the band refines the
    /// water around the same body.
    pub fn kernel_stretch_at(&self, h: f32) -> f32 {
        (self.boundary_width * self.diameter / (3.0 * h)).max(1.0)
    }

    /// Side of the square fluid domain, m.
    pub fn domain_size(&self) -> f32 {
        self.domain_diameters * self.diameter
    }

    /// The longest part hanging below the bell at rest, m: the tentacles, or the manubrium
    /// with its oral arms.
    pub fn hanging_length(&self) -> f32 {
        self.tentacle_length
            .max(self.manubrium_length + self.oral_arm_length)
    }

    /// Kinematic viscosity, m²/s.
    pub fn kinematic_viscosity(&self) -> f32 {
        self.viscosity / self.density
    }

    /// The mesoglea's Kelvin–Voigt time τ = η/E, s, from its resilience R over a cycle at
    /// the rate the stroke's timing describes (a [`MuscleTiming::Twitch`]'s natural rate,
    /// where it was measured; with the paper's `Cycle`, the cycle beaten): a linear
    /// viscoelastic solid returns `R = exp(−π·tan δ)` of its energy, and Kelvin–Voigt's
    /// `tan δ = ω·τ`. For the animals a material constant: beaten faster, the bell loses
    /// more of each stroke's energy.
    pub fn mesoglea_damping_time(&self) -> f32 {
        let loss_tangent = -self.mesoglea_resilience.clamp(1e-3, 1.0).ln() / std::f32::consts::PI;
        let rate = self.contraction_frequency * self.cycle_stretch();
        loss_tangent / (std::f32::consts::TAU * rate)
    }

    /// The animal's own pulse rate at this bell's diameter, Hz: `natural_frequency` at
    /// `natural_diameter`, scaled as the diameter to the −1/2.
    pub fn natural_pulse_rate(&self) -> f32 {
        self.natural_frequency * (self.natural_diameter / self.diameter).sqrt()
    }

    /// The same animal grown (or shrunk) to a bell `diameter` wide, m: every length of its
    /// body scaled alike, the plate bending of its mesoglea as the thickness cubed (per
    /// the same 2 mm hinge), and beating at its animal's own rate for that size
    /// ([`Self::natural_pulse_rate`]). Materials, water, shares and the box in diameters
    /// stay as they are. Not validated: a size outside the limits is the caller's to check.
    /// Shrunk far enough, the water's viscosity takes the glide: the shipped species are
    /// drawn back while they refill below about 14.5, 26.4 and 6.3 mm (moon jelly,
    /// *Aequorea*, *Sarsia*; `examples/kinematics.rs`, `docs/physics.md`).
    pub fn resized(&self, diameter: f32) -> Species {
        let scale = diameter / self.diameter;
        let grown = Species {
            diameter,
            height: self.height * scale,
            thickness: self.thickness * scale,
            angular_stiffness: self.angular_stiffness * scale.powi(3),
            tentacle_length: self.tentacle_length * scale,
            tentacle_radius: self.tentacle_radius * scale,
            manubrium_length: self.manubrium_length * scale,
            manubrium_radius: self.manubrium_radius * scale,
            oral_arm_length: self.oral_arm_length * scale,
            oral_arm_width: self.oral_arm_width * scale,
            ..self.clone()
        };
        Species {
            contraction_frequency: grown.natural_pulse_rate(),
            ..grown
        }
    }

    /// The bell's cycle over its animal's natural one, `natural_pulse_rate /
    /// contraction_frequency`: above 1 it beats slower than its own rate. With the paper's
    /// [`MuscleTiming::Cycle`] always 1: its stroke is a share of whatever cycle it beats.
    pub fn cycle_stretch(&self) -> f32 {
        let stretch = self.natural_pulse_rate() / self.contraction_frequency;
        if self.muscle_timing == MuscleTiming::Cycle || !(stretch > 0.0 && stretch.is_finite()) {
            1.0
        } else {
            stretch
        }
    }

    /// The share of the cycle spent contracting at `contraction_frequency`:
    /// `contraction_duty` at the natural rate, and with a [`MuscleTiming::Twitch`] the
    /// same seconds at any other (kept between 2% and 90% of the cycle).
    pub fn contraction_share(&self) -> f32 {
        let stretch = self.cycle_stretch();
        if stretch == 1.0 {
            self.contraction_duty
        } else {
            (self.contraction_duty / stretch).clamp(0.02, 0.9)
        }
    }

    /// The bending the bell's angular springs take at the apex thickness, per
    /// [`REFERENCE_HINGE_LENGTH`] of hinge, N·m/rad: `angular_stiffness` with the paper's
    /// [`Bending::Springs`], or with [`Bending::Mesoglea`] the plate law of its mesoglea,
    /// E·ϑ³/12 (the same number the shipped animals' `angular_stiffness` holds).
    pub fn bending_stiffness(&self) -> f32 {
        match self.bending {
            Bending::Springs => self.angular_stiffness,
            Bending::Mesoglea => {
                let t = self.thickness;
                self.elastic_modulus * t * t * t / 12.0 / REFERENCE_HINGE_LENGTH
            }
        }
    }

    /// Contraction period, s.
    pub fn period(&self) -> f32 {
        1.0 / self.contraction_frequency
    }

    /// The same species in a box two thirds the size, of the same cells and step: a
    /// cheaper live slice (about 0.6 of the cost) whose wake is cut shorter, so it swims a
    /// few percent slower (see `examples/lod.rs`). The species itself where such a box
    /// would be invalid.
    pub fn compact_box(&self) -> Species {
        let least = limits::LIMITS
            .iter()
            .find(|l| l.field == "domain_diameters")
            .map_or(3.0, |l| l.min as f32);
        let domain = (self.domain_diameters * 2.0 / 3.0).max(least);
        let grid_now = self.grid_resolution as f32;
        // The box `grid` cells of this species' size span, in diameters.
        let span = |grid: f32| grid * self.domain_diameters / grid_now;
        let mut grid = (grid_now * domain / self.domain_diameters).round();
        // Whole cells: rounded down past the smallest box, one more.
        if span(grid) < least {
            grid += 1.0;
        }
        let compact = Species {
            domain_diameters: span(grid),
            grid_resolution: grid as u32,
            ..self.clone()
        };
        if compact.validate().is_ok() && compact.steps_per_cycle() == self.steps_per_cycle() {
            compact
        } else {
            self.clone()
        }
    }

    /// Fixed simulation steps per contraction cycle: enough to resolve the muscle drive
    /// (at least 32) and to keep the water a stroke is expected to move under half a cell
    /// per step (Courant 0.5 at four times the margin's mean inward speed: the jet leaves
    /// the aperture faster than the margin closes; measured up to three times).
    pub fn steps_per_cycle(&self) -> u32 {
        const MIN_STEPS_PER_CYCLE: f32 = 32.0;
        const COURANT: f32 = 0.5;
        const JET_SPEED_FACTOR: f32 = 4.0;
        let margin_speed = (1.0 - self.contraction_ratio) * 0.5 * self.diameter
            / (self.contraction_share() * self.period());
        let expected = JET_SPEED_FACTOR * margin_speed;
        let courant = self.period() * expected / (COURANT * self.cell_size());
        let steps = courant.ceil().max(MIN_STEPS_PER_CYCLE);
        if steps.is_finite() {
            steps.min(1e6) as u32
        } else {
            MIN_STEPS_PER_CYCLE as u32
        }
    }

    /// The fixed simulation step, s: a whole fraction of the contraction period.
    pub fn step_length(&self) -> f32 {
        self.period() / self.steps_per_cycle() as f32
    }

    /// Guide chains the fringe is drawn with: `tentacle_guides`, at most one per tentacle,
    /// none without a fringe.
    pub fn guide_count(&self) -> usize {
        let hanging = self.tentacle_length > 0.0; // false for NaN too
        if self.tentacle_count == 0 || !hanging {
            return 0;
        }
        self.tentacle_guides.min(self.tentacle_count) as usize
    }

    /// Guide chains the manubrium and the oral arms are drawn with: one per tube
    /// ([`limits::oral_tubes`]). None, and the hanging parts follow the slice alone, when
    /// the species has no guides (`tentacle_guides: 0`) or when its tubes hang no deeper
    /// than its subumbrella ([`Self::oral_tubes_within_cavity`]).
    pub fn oral_guide_count(&self) -> usize {
        if self.tentacle_guides == 0 || self.oral_tubes_within_cavity() {
            return 0;
        }
        super::limits::oral_tubes(self).min(super::limits::MAX_DRAWN_ORAL_TUBES)
    }

    /// Whether the manubrium and the oral arms, hanging from the subumbrellar apex, reach
    /// no deeper than the subumbrella at rest (`manubrium_length + oral_arm_length ≤
    /// height`; *Aequorea*'s short lips). Within the cavity they hang in the water the
    /// bell carries with it: the currents the slice cannot see, and the body's turns,
    /// hardly reach them there, and what the slice's own water does to them the slice
    /// already draws.
    pub fn oral_tubes_within_cavity(&self) -> bool {
        self.manubrium_length + self.oral_arm_length <= self.height
    }
}
