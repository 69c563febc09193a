//! Species: every parameter of a jellyfish kind, in SI units, with validation.
//!
//! The defaults of [`Species::aurelia`] are the paper's Fig. 12 (Rudolf & Mould 2009),
//! read in SI units as DESIGN.md section 3 explains. Everything else a simulation or a
//! renderer needs lives here too, so that one RON file describes one species.

pub mod limits;

use serde::{Deserialize, Serialize};
use std::fmt;

/// A jellyfish species: physical, muscular and visual parameters.
///
/// Lengths in metres, moduli in pascals, frequencies in hertz. Parameters quoted from the
/// paper say so; the rest are choices of ours, each explained where it is used.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[serde(default, deny_unknown_fields)]
pub struct Species {
    /// Display name.
    pub name: String,

    // --- Water (DESIGN.md section 3: the SI reading of the paper's table) ---
    /// Fluid cells per side of the square slice domain (paper: 100 over 10 diameters; the
    /// default 60 over 6 keeps its ten cells per diameter).
    pub grid_resolution: u32,
    /// Dynamic viscosity of the water, Pa·s (sea water: 1.304e-3).
    pub viscosity: f32,
    /// Density of the water, kg/m³ (sea water: 1025).
    pub density: f32,
    /// Side of the square fluid domain in bell diameters (paper: 10; default 6: the box
    /// follows the bell and the wake leaves through its open end).
    pub domain_diameters: f32,
    /// How the water carries its own velocity (see [`Advection`]).
    pub advection: Advection,
    /// How the bell's points read and push the water (see [`Kernel`]).
    pub kernel: Kernel,
    /// Width of the band over which the bell's points meet the water, in bell diameters:
    /// the immersed boundary's regularisation. 0.3 is three cells at ten cells per
    /// diameter (Roma et al.'s kernel at the paper's resolution); finer grids resolve the
    /// same band, coarser ones widen it to three cells.
    pub boundary_width: f32,

    // --- Bell geometry (paper Fig. 12) ---
    /// Bell diameter at rest, m (paper: 40 mm).
    pub diameter: f32,
    /// Bell height from aperture to apex at rest, m (paper: 28 mm).
    pub height: f32,
    /// Mesoglea thickness at the apex, m (paper: ϑ = 4 mm).
    pub thickness: f32,
    /// Mesoglea thickness at the margin as a fraction of `thickness`.
    pub margin_thickness_ratio: f32,

    // --- Elasticity ---
    /// Hookean modulus of the bell mesoglea, Pa (paper: λ = 1186 Pa).
    pub elastic_modulus: f32,
    /// Bending stiffness of the angular springs per unit depth, N·m/rad.
    pub angular_stiffness: f32,
    /// Fraction of the strain energy the mesoglea gives back over a stroke cycle (the
    /// rest is lost to its viscosity); DeMont & Gosline (1988) measured 58%.
    pub mesoglea_resilience: f32,
    /// Modulus of the muscle fibres, Pa (paper, after Megill: 400 kPa).
    pub muscle_modulus: f32,
    /// Cross-section of the circumferential muscle as a fraction of the wall's (a thin
    /// sheet lining the subumbrella: 1/100).
    pub muscle_cross_section: f32,
    /// Cross-section of the hoop of mesoglea the muscle pulls through, as a fraction of
    /// the wall's: with `elastic_modulus`, the bell's stiffness against contraction, which
    /// the slice (no circumference of its own) cannot feel otherwise.
    pub hoop_cross_section: f32,

    // --- Muscles (paper section 3.3) ---
    /// Contractions per second, Hz (paper: 0.7).
    pub contraction_frequency: f32,
    /// Muscle rest length at full contraction as a fraction of rest (paper: 0.56).
    pub contraction_ratio: f32,
    /// Fraction of a cycle spent contracting; the rest is re-expansion.
    pub contraction_duty: f32,
    /// 0: all muscle springs re-expand in unison; 1: springs nearer the aperture
    /// re-expand later and more slowly (the paper's staggered expansion).
    pub expansion_stagger: f32,

    // --- Tentacles ---
    /// Tentacles around the 3D aperture.
    pub tentacle_count: u32,
    /// Tentacle length at rest, m.
    pub tentacle_length: f32,
    /// Cross-section of a tentacle spring as a fraction of a bell spring (paper: 1/100).
    pub tentacle_cross_section: f32,
    /// Rendered tentacle radius, m.
    pub tentacle_radius: f32,
    /// How much shorter than the slice's chain a tentacle may be drawn, as a fraction of
    /// it: each tentacle of an individual keeps its own length between `1 − spread` and 1
    /// of the chain, as a living fringe holds some tentacles contracted (0: an even
    /// fringe). Drawn only: the slice's chain, and so the drag, keep `tentacle_length`.
    pub tentacle_length_spread: f32,

    // --- Anatomy (drawn; carried by the slice's water, never pushing it) ---
    /// Length of the manubrium, the stalk carrying the mouth from the subumbrellar apex, m
    /// (0: none).
    pub manubrium_length: f32,
    /// Radius of the manubrium, m.
    pub manubrium_radius: f32,
    /// Oral arms hanging from the manubrium (Aurelia: 4).
    pub oral_arm_count: u32,
    /// Length of an oral arm below the manubrium, m (0: none).
    pub oral_arm_length: f32,
    /// Width of an oral arm's blade, m.
    pub oral_arm_width: f32,
    /// Frilliness of the arms' margins: the ruffle's depth as a fraction of the blade's
    /// width (0: smooth blades).
    pub oral_arm_frill: f32,
    /// Gonads seen through the bell (Aurelia: 4; 0: none).
    pub gonad_count: u32,
    /// The gonads' shape (see [`GonadShape`]).
    pub gonad_shape: GonadShape,
    /// Gonad size as a fraction of the subumbrella's span from apex to margin.
    pub gonad_size: f32,
    /// Gonad colour, linear RGBA (alpha is its opacity through the bell).
    pub gonad_color: [f32; 4],
    /// Radial canals from the stomach to the ring canal along the margin (0: none).
    pub radial_canal_count: u32,
    /// Width of the radial and ring canals as a fraction of the subumbrella's span.
    pub canal_width: f32,

    // --- Surface variation (paper section 3.5, Fig. 9) ---
    /// Structural variation amplitude as a fraction of `thickness` (paper: 0.375).
    pub structural_scale: f32,
    /// Lobes around the bell for the structural variation.
    pub structural_frequency: f32,
    /// Use `|sin(f·σ)|` instead of `sin(f·σ)` for the structural variation.
    pub structural_abs: bool,
    /// Compression ripple amplitude at full contraction as a fraction of `thickness`
    /// (paper: 1.51 − 1.36 = 0.15).
    pub compression_scale: f32,
    /// Ripples around the bell for the compression variation (paper Fig. 3: 8).
    pub compression_frequency: f32,
    /// Unstructured (Perlin) variation amplitude as a fraction of `thickness` (paper: 2.25).
    pub unstructured_scale: f32,
    /// Noise frequency along the latitude (apex to margin) (paper: 2).
    pub noise_frequency_lat: f32,
    /// Noise frequency along the longitude (around the axis) (paper: 8).
    pub noise_frequency_lon: f32,
    /// Noise frequency in time, 1/s (paper: 0.01).
    pub noise_frequency_time: f32,

    // --- Rendering resolution ---
    /// Rings of the umbrella mesh from apex to margin, per surface.
    pub mesh_rings: u32,
    /// Segments around the axis.
    pub mesh_segments: u32,
    /// Sides of a tentacle tube.
    pub tentacle_sides: u32,

    // --- Looks ---
    /// Bell colour, linear RGBA (alpha is the translucency).
    pub bell_color: [f32; 4],
    /// Colour of the light the bell's glow layer adds, linear RGB.
    pub glow_color: [f32; 3],
    /// Glow strength: the plain bell's glow layer adds `glow_color × glow × 0.25` of
    /// radiance per surface (before tonemapping), canals and gonads twice that.
    pub glow: f32,
}

impl Default for Species {
    fn default() -> Self {
        Self::aurelia()
    }
}

impl Species {
    /// The moon jelly of the paper's Fig. 12, in SI units, simulated in a compact box that
    /// follows the bell (see [`Species::with_paper_numerics`] for the paper's own box).
    pub fn aurelia() -> Self {
        Self {
            name: "Aurelia".into(),
            grid_resolution: 60,
            viscosity: 1.304e-3,
            density: 1025.0,
            domain_diameters: 6.0,
            advection: Advection::SemiLagrangian,
            kernel: Kernel::Roma3,
            boundary_width: 0.3,
            diameter: 0.040,
            height: 0.028,
            thickness: 0.004,
            margin_thickness_ratio: 0.3,
            elastic_modulus: 1186.0,
            // Plate bending of the apex wall, E·ϑ³/12 per 2 mm hinge (DESIGN.md section 3).
            angular_stiffness: 1186.0 * 0.004 * 0.004 * 0.004 / 12.0 / 0.002,
            mesoglea_resilience: 1.0,
            muscle_modulus: 400.0e3,
            muscle_cross_section: 0.01,
            // Calibrated: puts the bell's resonance with its water near the paper's 0.7 Hz
            // (the distance swum in 20 s peaks between 0.7 and 1 Hz).
            hoop_cross_section: 0.0101,
            contraction_frequency: 0.7,
            contraction_ratio: 0.56,
            contraction_duty: 0.35,
            expansion_stagger: 1.0,
            // A moon jelly's fringe: hundreds of short, fine marginal tentacles. Their drag
            // slows the bell by about a tenth (Miles & Battista 2019: tentacles reduce
            // forward speed; measured here 9%, `tests/slice.rs`).
            tentacle_count: 200,
            tentacle_length: 0.015,
            tentacle_cross_section: 0.01,
            tentacle_radius: 0.00015,
            tentacle_length_spread: 0.35,
            // Four frilly oral arms from a short manubrium, four horseshoe gonads between
            // them and sixteen radial canals: how a moon jelly is recognised.
            manubrium_length: 0.003,
            manubrium_radius: 0.0015,
            oral_arm_count: 4,
            oral_arm_length: 0.03,
            oral_arm_width: 0.003,
            oral_arm_frill: 0.5,
            gonad_count: 4,
            gonad_shape: GonadShape::Horseshoe,
            gonad_size: 0.3,
            gonad_color: [0.85, 0.45, 0.95, 0.9],
            radial_canal_count: 16,
            canal_width: 0.008,
            // A smooth, taut bell, as in photographs of living medusae: gentle lobes, faint
            // ripples as it contracts, a hint of irregularity. The paper's Fig. 12 values,
            // several times larger, crumple the dome: `with_paper_variations`.
            structural_scale: 0.06,
            structural_frequency: 8.0,
            structural_abs: false,
            compression_scale: 0.08,
            compression_frequency: 8.0,
            unstructured_scale: 0.3,
            noise_frequency_lat: 2.0,
            noise_frequency_lon: 8.0,
            noise_frequency_time: 0.01,
            mesh_rings: 24,
            mesh_segments: 48,
            // Hair-thin tubes: three sides read as round at any size they are seen at,
            // and keep two hundred of them under 11,000 vertices.
            tentacle_sides: 3,
            bell_color: [0.75, 0.85, 1.0, 0.35],
            glow_color: [0.35, 0.55, 1.0],
            glow: 0.6,
        }
    }

    /// The crystal jelly (`assets/species/aequorea.species.ron`): a wide, flat disc with a hundred
    /// long fine tentacles, slow strokes, green glow.
    pub fn aequorea() -> Self {
        Self {
            name: "Aequorea".into(),
            diameter: 0.06,
            height: 0.02,
            thickness: 0.005,
            margin_thickness_ratio: 0.25,
            contraction_frequency: 0.6,
            contraction_ratio: 0.56,
            tentacle_count: 100,
            tentacle_length: 0.045,
            tentacle_radius: 0.00025,
            // Some of a crystal jelly's long tentacles hang full length, others curled up.
            tentacle_length_spread: 0.6,
            tentacle_sides: 4,
            // A short, wide stomach fringed with lips, gonads along its many radial canals.
            manubrium_length: 0.003,
            manubrium_radius: 0.004,
            oral_arm_count: 12,
            oral_arm_length: 0.004,
            oral_arm_width: 0.0015,
            oral_arm_frill: 0.8,
            gonad_count: 60,
            gonad_shape: GonadShape::Radial,
            gonad_size: 0.45,
            gonad_color: [0.85, 1.0, 0.9, 0.45],
            radial_canal_count: 60,
            canal_width: 0.006,
            structural_scale: 0.05,
            structural_frequency: 16.0,
            structural_abs: true,
            compression_frequency: 12.0,
            unstructured_scale: 0.2,
            bell_color: [0.8, 0.95, 0.9, 0.25],
            glow_color: [0.3, 1.0, 0.45],
            glow: 0.5,
            ..Self::aurelia()
        }
    }

    /// A small hydromedusa (`assets/species/sarsia.species.ron`): a tall bell with four long
    /// tentacles, quick strokes.
    pub fn sarsia() -> Self {
        Self {
            name: "Sarsia".into(),
            diameter: 0.016,
            height: 0.022,
            thickness: 0.0025,
            margin_thickness_ratio: 0.4,
            contraction_frequency: 1.4,
            contraction_ratio: 0.5,
            contraction_duty: 0.3,
            tentacle_count: 4,
            tentacle_length: 0.025,
            tentacle_radius: 0.0003,
            tentacle_length_spread: 0.15,
            tentacle_sides: 6,
            // A long tubular manubrium hanging out of the bell, four radial canals.
            manubrium_length: 0.02,
            manubrium_radius: 0.0008,
            oral_arm_count: 0,
            oral_arm_length: 0.0,
            gonad_count: 0,
            radial_canal_count: 4,
            canal_width: 0.025,
            structural_scale: 0.04,
            structural_frequency: 4.0,
            unstructured_scale: 0.15,
            bell_color: [0.95, 0.8, 0.85, 0.3],
            glow_color: [1.0, 0.35, 0.5],
            glow: 0.5,
            ..Self::aurelia()
        }
    }

    /// Every shipped species, as in `assets/species/`.
    pub fn presets() -> [Species; 3] {
        [Self::aurelia(), Self::aequorea(), Self::sarsia()]
    }

    /// The paper's surface variation (its Fig. 9 and 12): structural lobes 0.375, compression
    /// ripples 0.15 and Perlin noise 2.25 of the thickness, eight lobes and ripples. Only the
    /// shape changes, not the slice. The shipped species are smoother.
    pub fn with_paper_variations(mut self) -> Self {
        self.structural_scale = 0.375;
        self.structural_frequency = 8.0;
        self.structural_abs = false;
        self.compression_scale = 0.15;
        self.compression_frequency = 8.0;
        self.unstructured_scale = 2.25;
        self.noise_frequency_lat = 2.0;
        self.noise_frequency_lon = 8.0;
        self.noise_frequency_time = 0.01;
        self
    }

    /// The paper's numerics (its Fig. 12 and section 3.2): grid 100 over a box ten
    /// diameters wide, bilinear spreading, semi-Lagrangian advection. The physics is the
    /// same; [`Species::aurelia`] keeps the resolution (ten cells per diameter) in a
    /// six-diameter box that follows the bell, with a kernel that does not see the grid.
    pub fn with_paper_numerics(mut self) -> Self {
        self.grid_resolution = 100;
        self.domain_diameters = 10.0;
        self.kernel = Kernel::Bilinear;
        self.advection = Advection::SemiLagrangian;
        self
    }

    /// Fluid cell size, m.
    pub fn cell_size(&self) -> f32 {
        self.domain_size() / self.grid_resolution as f32
    }

    /// Side of the square fluid domain, m.
    pub fn domain_size(&self) -> f32 {
        self.domain_diameters * self.diameter
    }

    /// Kinematic viscosity, m²/s.
    pub fn kinematic_viscosity(&self) -> f32 {
        self.viscosity / self.density
    }

    /// The mesoglea's Kelvin–Voigt time τ = η/E, s, from its resilience R at the stroke
    /// frequency: a linear viscoelastic solid returns `R = exp(−π·tan δ)` of its energy,
    /// and Kelvin–Voigt's `tan δ = ω·τ`.
    pub fn mesoglea_damping_time(&self) -> f32 {
        let loss_tangent = -self.mesoglea_resilience.clamp(1e-3, 1.0).ln() / std::f32::consts::PI;
        loss_tangent / (std::f32::consts::TAU * self.contraction_frequency)
    }

    /// Contraction period, s.
    pub fn period(&self) -> f32 {
        1.0 / self.contraction_frequency
    }

    /// Parses a species from RON text, then validates it.
    pub fn from_ron(text: &str) -> Result<Self, SpeciesError> {
        let species: Species =
            ron::from_str(text).map_err(|e| SpeciesError::Parse(e.to_string()))?;
        species.validate()?;
        Ok(species)
    }

    /// Writes the species as pretty RON.
    pub fn to_ron(&self) -> Result<String, SpeciesError> {
        ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default())
            .map_err(|e| SpeciesError::Parse(e.to_string()))
    }

    /// Checks every parameter against [`limits::LIMITS`] and the limits that join fields
    /// (proportions, the mesh's vertex budget, the slice's cost); the error names the
    /// first bad field, its allowed range and why.
    pub fn validate(&self) -> Result<(), SpeciesError> {
        limits::validate(self)
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
        let grid = (self.grid_resolution as f32 * domain / self.domain_diameters).round();
        let compact = Species {
            domain_diameters: grid * self.domain_diameters / self.grid_resolution as f32,
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
            / (self.contraction_duty * self.period());
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
}

/// The shape of the gonads, drawn through the bell on the subumbrella between the radial
/// canals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
pub enum GonadShape {
    /// A horseshoe opening towards the centre (Aurelia's four-leaf clover).
    #[default]
    Horseshoe,
    /// An oval.
    Oval,
    /// A strip along each radial canal (Aequorea).
    Radial,
}

impl GonadShape {
    /// Every shape, for pickers.
    pub const ALL: [GonadShape; 3] = [GonadShape::Horseshoe, GonadShape::Oval, GonadShape::Radial];
}

/// The fluid's advection scheme: a numerical choice, kept with the species because the
/// grid resolution is too.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
pub enum Advection {
    /// Stam's semi-Lagrangian step: the cheapest and the most regular. Its numerical
    /// viscosity grows with the cell size: at grid 100 the default bell swims about a
    /// quarter of a diameter per stroke, at grid 64 a twentieth, and at grid 50 not at all.
    #[default]
    SemiLagrangian,
    /// MacCormack's forward–backward correction (Selle et al. 2008), clamped: about twice
    /// the cost of a fluid step, far less numerical viscosity, so coarse grids swim too
    /// (grid 64: about 0.3 diameters per stroke), at the price of a less regular stroke.
    MacCormack,
    /// Stam's step with Catmull–Rom bicubic sampling limited to the four nearest values
    /// (Fedkiw et al. 2001): as stable and regular as the plain step, with far less
    /// numerical viscosity, so the stroke converges at ten cells per diameter.
    Cubic,
}

impl Advection {
    /// Every scheme, for pickers.
    pub const ALL: [Advection; 3] = [
        Advection::SemiLagrangian,
        Advection::MacCormack,
        Advection::Cubic,
    ];
}

/// The immersed-boundary kernel: how a point reads the faces around it and spreads its
/// force back onto them (the same weights both ways; see `sim::kernel`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
pub enum Kernel {
    /// Roma, Peskin & Berger's three-point kernel (1999): nearly translation invariant, so
    /// the stroke does not depend on where the bell sits in a cell.
    #[default]
    Roma3,
    /// The paper's bilinear weights on the four nearest faces: sharpest, but the stroke
    /// changes with the bell's offset to the cells.
    Bilinear,
}

impl Kernel {
    /// Every kernel, for pickers.
    pub const ALL: [Kernel; 2] = [Kernel::Roma3, Kernel::Bilinear];
}

/// Why a species (or a simulation built from one) was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpeciesError {
    /// A parameter is out of range; `field` is its name in [`Species`].
    #[error("species field `{field}`: {reason}")]
    Invalid {
        /// The field's name in [`Species`].
        field: &'static str,
        /// Why it is refused, with the allowed range.
        reason: String,
    },
    /// The RON text could not be read.
    #[error("species file: {0}")]
    Parse(String),
}

impl SpeciesError {
    /// An error naming `field` and why it is refused.
    pub fn invalid(field: &'static str, reason: impl Into<String>) -> Self {
        Self::Invalid {
            field,
            reason: reason.into(),
        }
    }

    /// The offending field, if the error is about one.
    pub fn field(&self) -> Option<&'static str> {
        match self {
            Self::Invalid { field, .. } => Some(field),
            Self::Parse(_) => None,
        }
    }
}

impl fmt::Display for Species {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({:.0} mm bell, {} Hz)",
            self.name,
            self.diameter * 1000.0,
            self.contraction_frequency
        )
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn each_preset_is_its_shipped_file() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/species");
        for preset in Species::presets() {
            let file = dir.join(format!("{}.species.ron", preset.name.to_lowercase()));
            let text = std::fs::read_to_string(&file).expect("shipped species file");
            assert_eq!(
                Species::from_ron(&text).unwrap(),
                preset,
                "{}",
                file.display()
            );
            preset.validate().unwrap();
        }
    }

    #[test]
    fn an_unknown_field_is_an_error_naming_it_and_where() {
        let error = Species::from_ron("(\n    name: \"X\",\n    diamter: 0.05,\n)").unwrap_err();
        let text = error.to_string();
        assert!(text.contains("diamter"), "{text}");
        assert!(text.contains("3:"), "names the line: {text}");
    }

    use super::*;

    #[test]
    fn aurelia_is_valid_and_matches_the_paper() {
        let s = Species::aurelia();
        s.validate().unwrap();
        assert_eq!(s.contraction_frequency, 0.7);
        assert_eq!(s.diameter, 0.040);
        assert_eq!(s.height, 0.028);
        assert_eq!(s.thickness, 0.004);
        assert_eq!(s.elastic_modulus, 1186.0);
        assert_eq!(s.contraction_ratio, 0.56);
        assert_eq!(s.tentacle_cross_section, 0.01);
        // The compact co-moving box keeps the paper's resolution, ten cells per diameter.
        assert_eq!((s.grid_resolution, s.domain_diameters), (60, 6.0));
        assert!((s.cell_size() - 0.004).abs() < 1e-7);
        // The paper's own numerics stay one call away.
        let paper = Species::aurelia().with_paper_numerics();
        paper.validate().unwrap();
        assert_eq!((paper.grid_resolution, paper.domain_diameters), (100, 10.0));
        assert_eq!(paper.kernel, Kernel::Bilinear);
        assert!((paper.cell_size() - 0.004).abs() < 1e-7);
    }

    #[test]
    fn ron_round_trip() {
        let mut s = Species::aurelia();
        s.name = "Test".into();
        s.expansion_stagger = 0.25;
        let text = s.to_ron().unwrap();
        assert_eq!(Species::from_ron(&text).unwrap(), s);
    }

    #[test]
    fn missing_fields_take_defaults() {
        let s = Species::from_ron("(name: \"Short\", contraction_frequency: 0.5)").unwrap();
        assert_eq!(s.contraction_frequency, 0.5);
        assert_eq!(s.diameter, Species::aurelia().diameter);
    }

    fn field_of(s: &Species) -> &'static str {
        s.validate().unwrap_err().field().unwrap()
    }

    #[test]
    fn every_bad_value_names_its_field() {
        type Mutation = Box<dyn Fn(&mut Species)>;
        let cases: Vec<(&str, Mutation)> = vec![
            ("grid_resolution", Box::new(|s| s.grid_resolution = 8)),
            ("grid_resolution", Box::new(|s| s.grid_resolution = 1024)),
            ("viscosity", Box::new(|s| s.viscosity = -1.0)),
            ("density", Box::new(|s| s.density = 0.0)),
            ("diameter", Box::new(|s| s.diameter = f32::NAN)),
            ("diameter", Box::new(|s| s.diameter = -0.04)),
            ("height", Box::new(|s| s.height = 0.0)),
            ("height", Box::new(|s| s.height = f32::INFINITY)),
            ("thickness", Box::new(|s| s.thickness = 0.0)),
            ("thickness", Box::new(|s| s.thickness = 0.03)),
            ("elastic_modulus", Box::new(|s| s.elastic_modulus = -5.0)),
            (
                "angular_stiffness",
                Box::new(|s| s.angular_stiffness = -1.0),
            ),
            ("muscle_modulus", Box::new(|s| s.muscle_modulus = 0.0)),
            (
                "contraction_frequency",
                Box::new(|s| s.contraction_frequency = 0.0),
            ),
            (
                "contraction_frequency",
                Box::new(|s| s.contraction_frequency = -1.0),
            ),
            ("contraction_ratio", Box::new(|s| s.contraction_ratio = 1.5)),
            ("expansion_stagger", Box::new(|s| s.expansion_stagger = 2.0)),
            ("tentacle_length", Box::new(|s| s.tentacle_length = -0.01)),
            ("mesh_segments", Box::new(|s| s.mesh_segments = 2)),
            ("bell_color[3]", Box::new(|s| s.bell_color[3] = 2.0)),
        ];
        for (field, mutate) in cases {
            let mut s = Species::aurelia();
            mutate(&mut s);
            assert_eq!(field_of(&s), field, "{:?}", s.validate());
            let msg = s.validate().unwrap_err().to_string();
            assert!(msg.contains(field), "message `{msg}` names `{field}`");
        }
    }

    #[test]
    fn bad_ron_is_an_error_not_a_panic() {
        assert!(matches!(
            Species::from_ron("(diameter: \"wide\")"),
            Err(SpeciesError::Parse(_))
        ));
        let err = Species::from_ron("(diameter: -1.0)").unwrap_err();
        assert_eq!(err.field(), Some("diameter"));
    }
}
