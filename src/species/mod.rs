//! Species: every parameter of a jellyfish kind, in SI units, with validation.
//!
//! The defaults are [`Species::aurelia`], the moon jelly shaped and timed from records of
//! the animal (`docs/physics.md`, section 5); [`Species::paper`] is the paper's Fig. 12
//! model (Rudolf & Mould 2009), read in SI units as `docs/physics.md` explains. Everything else a simulation or a
//! renderer needs lives here too, so that one RON file describes one species.
//!
//! - `presets`: the shipped species, the paper's model, variations and numerics;
//! - `derived`: what follows from the fields (cell size, period, the fixed step...);
//! - `file`: RON text in and out, validated against [`limits`];
//! - `choices`: the enumerated fields (gonad shape, slice geometry, fringe drag, advection,
//!   kernel, bell coupling);
//! - `error`: [`SpeciesError`].

mod choices;
mod cost;
mod derived;
mod error;
mod file;
pub mod limits;
mod presets;
#[cfg(test)]
mod tests;

pub use choices::{
    Advection, BellCoupling, Bending, FringeDrag, GonadShape, Kernel, MuscleLaw, MuscleTiming,
    SliceGeometry,
};
pub use derived::REFERENCE_HINGE_LENGTH;
pub use error::SpeciesError;

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

    // --- Water (`docs/physics.md` section 2: the SI reading of the paper's table) ---
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
    /// The slice's geometry: planar, or a body of revolution (see [`SliceGeometry`]).
    pub slice_geometry: SliceGeometry,
    /// How the water carries its own velocity (see [`Advection`]).
    pub advection: Advection,
    /// How the bell's points read and push the water (see [`Kernel`]).
    pub kernel: Kernel,
    /// What the bell's implicit solve expects of the water over a step (see
    /// [`BellCoupling`]).
    pub bell_coupling: BellCoupling,
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
    /// Where the bell's bending comes from (see [`Bending`]): its mesoglea, or the
    /// paper's angular springs.
    pub bending: Bending,
    /// Bending stiffness of the angular springs per unit depth at the apex thickness, per
    /// 2 mm of hinge, N·m/rad; read with [`Bending::Springs`] only
    /// ([`Species::bending_stiffness`]).
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
    /// the planar slice (no circumference of its own) cannot feel otherwise. Planar only:
    /// in the axisymmetric slice every ring is a hoop of its real cross-section.
    pub hoop_cross_section: f32,

    // --- Muscles (paper section 3.3) ---
    /// Contractions per second, Hz (paper: 0.7).
    pub contraction_frequency: f32,
    /// How the muscle's contraction and release last when the pulse rate is not the
    /// animal's own (see [`MuscleTiming`]).
    pub muscle_timing: MuscleTiming,
    /// The pulse rate the animal beats at when its bell is `natural_diameter` wide, Hz:
    /// with [`MuscleTiming::Twitch`], the rate whose cycle `contraction_duty` and
    /// `relaxation_span` describe in seconds. Smaller medusae pulse faster; at other diameters the
    /// rate is taken to scale as the diameter to the −1/2 (McHenry & Jed 2003 for the
    /// trend; the exponent is ours).
    pub natural_frequency: f32,
    /// The bell diameter `natural_frequency` was measured at, m.
    pub natural_diameter: f32,
    /// Muscle rest length at full contraction as a fraction of rest (paper: 0.56). In the
    /// axisymmetric slice the muscle is a force generator and this is the shortest length
    /// it can pull to (its force falls to nothing there); its ring's hoop of mesoglea
    /// holds the ring somewhat wider.
    pub contraction_ratio: f32,
    /// Fraction of a cycle spent contracting; the rest is re-expansion (with
    /// [`MuscleTiming::Twitch`], of a cycle at the natural pulse rate).
    pub contraction_duty: f32,
    /// Fraction of the time between contractions the muscle takes to relax back to its
    /// rest length (in the axisymmetric slice: to let go), in unison (paper: half). The
    /// bell's own recoil refills it: how long that takes is an outcome. Staggered muscles
    /// nearer the aperture take longer, up to the whole of it.
    pub relaxation_span: f32,
    /// 0: all muscle springs re-expand in unison; 1: springs nearer the aperture
    /// re-expand later and more slowly (the paper's staggered expansion).
    pub expansion_stagger: f32,
    /// Share of the subumbrella, from the margin up towards the apex (as a fraction of its
    /// arc), that the circular swimming muscle lines (paper: 3/4). Where the stomach and
    /// the gonads line the subumbrella there is no swimming muscle.
    pub muscle_extent: f32,
    /// What the contraction function drives in the axisymmetric slice (see
    /// [`MuscleLaw`]): a force generator, or the paper's commanded length.
    pub muscle_law: MuscleLaw,

    // --- Tentacles ---
    /// Tentacles around the 3D aperture.
    pub tentacle_count: u32,
    /// Tentacle length at rest, m.
    pub tentacle_length: f32,
    /// Cross-section of a tentacle spring as a fraction of a bell spring (paper: 1/100).
    pub tentacle_cross_section: f32,
    /// Rendered tentacle radius, m: also the cylinder the water drags on.
    pub tentacle_radius: f32,
    /// How the fringe drags on the water along its tentacles (see [`FringeDrag`]).
    pub fringe_drag: FringeDrag,
    /// How much shorter than the slice's chain a tentacle may be drawn, as a fraction of
    /// it: each tentacle of an individual keeps its own length between `1 − spread` and 1
    /// of the chain, as a living fringe holds some tentacles contracted (0: an even
    /// fringe). Drawn only: the slice's chain, and so the drag, keep `tentacle_length`.
    pub tentacle_length_spread: f32,
    /// Guide chains around the margin that carry the fringe in the 3D water the slice does
    /// not see (a current unlike the one carrying the bell, the body's turns); the drawn
    /// tentacles bend between them; the manubrium and each oral arm then have a guide of
    /// their own. 0: the fringe and the oral arms follow the slice alone. Drawn only: the
    /// slice's chains drive the swimming. At most one per tentacle is used.
    pub tentacle_guides: u32,

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
    /// Strength of the glow band that runs along the bell with the contraction, in the
    /// units and colour of `glow`, where a ring is half-way through closing (0: none).
    pub glow_band: f32,

    // --- Touch: the flash and the escape (`docs/physics.md`, "Touch") ---
    /// Peak strength of a flash when touched, added to `glow` in its units and colour (0:
    /// the animal does not luminesce).
    pub flash: f32,
    /// Time a flash takes to fade to 1/e of its peak, s.
    pub flash_decay: f32,
    /// Time after a flash starts before another can, s.
    pub flash_refractory: f32,
    /// How far from the bell's centre a touch is felt, in bell diameters.
    pub touch_reach: f32,
    /// How far a flash is echoed by neighbours (at most half as bright), in the flasher's
    /// bell diameters (0: no echo).
    pub echo_reach: f32,
    /// How long after a flash its neighbours echo it, s.
    pub echo_delay: f32,
    /// How much deeper an escape's strokes contract, as a fraction of the stroke's own
    /// depth (0: no deeper).
    pub escape_depth: f32,
    /// How much quicker an escape's rhythm is: its pulse rate over the species' own.
    pub escape_rhythm: f32,
    /// Strokes an escape lasts at its rhythm, the last easing back (0: no escape).
    pub escape_strokes: u32,
}

impl Default for Species {
    fn default() -> Self {
        Self::aurelia()
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
