//! The enumerated fields of a species: the gonads' shape, the slice's geometry, how its
//! fringe drags on the water, and three numerical choices kept with the species because
//! its grid resolution is too.
//!
//! Their reflected type paths stay `bevy_jellyfish::species::*`, where they lived before
//! this file split off, so that nothing reflected by path changes.

use serde::{Deserialize, Serialize};

/// The shape of the gonads, drawn through the bell on the subumbrella between the radial
/// canals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
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
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
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
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
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

/// How the bell's implicit solve expects the water to give under its forces over a step:
/// a numerical choice, kept with the species because its calibration was made with one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
pub enum BellCoupling {
    /// Each point alone drags half a cell's water along: cheap, but the water then
    /// carries the points a step before their springs' pull reaches it, and the
    /// subumbrella stretches 11–15% under its own stroke at a species' own step (less
    /// with finer steps). The shipped species are calibrated with it.
    #[default]
    AddedMass,
    /// The water's response as the kernel spreads and reads it: a point moves with the
    /// water its neighbours push too, so the solve finds forces the water can take up.
    /// The wall keeps its length to 2–4% at the species' own step, and the stroke
    /// changes less with the step and the grid (`docs/numerics.md`, "A coupling that sees
    /// the water's response").
    WaterResponse,
}

impl BellCoupling {
    /// Every coupling, for pickers.
    pub const ALL: [BellCoupling; 2] = [BellCoupling::AddedMass, BellCoupling::WaterResponse];
}

/// The geometry of the slice the water and the bell are simulated in.
///
/// Both use the same fixed steps, co-moving open box, kernel and implicit springs; the
/// shape layer reads either as the bell's symmetric half-profile mirrored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
pub enum SliceGeometry {
    /// The paper's slice: a plane through the axis, as if the bell were infinitely long;
    /// its wake is a pair of vortices.
    #[default]
    Planar,
    /// A meridian half-plane of a body of revolution (r–z, no swirl): every point of the
    /// slice is a ring around the axis, the muscle a hoop, the wake a vortex ring.
    Axisymmetric,
}

impl SliceGeometry {
    /// Every geometry, for pickers.
    pub const ALL: [SliceGeometry; 2] = [SliceGeometry::Planar, SliceGeometry::Axisymmetric];
}

/// What a species' contraction function drives in the axisymmetric slice, where every
/// ring has its own hoop of mesoglea. (The planar slice always drives the paper's spring,
/// which stands in for the hoop the plane lacks.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
pub enum MuscleLaw {
    /// A force generator: the function is the muscle's activation, and the muscle pulls
    /// with it (to at most `contraction_ratio` of its length, where its force has fallen
    /// to nothing) and never pushes; the bell's stroke is an outcome of that force against
    /// its hoops, its bending and the water, and it refills on its own recoil. The
    /// animals.
    #[default]
    Force,
    /// A commanded length, the paper's planar spring carried into r–z: the function sets
    /// the muscle's rest length, and the muscle, merged with the hoop it lines, pulls the
    /// bell shut and pushes it open again, so the stroke is the function's at any pulse
    /// rate.
    Length,
}

impl MuscleLaw {
    /// Every law, for pickers.
    pub const ALL: [MuscleLaw; 2] = [MuscleLaw::Force, MuscleLaw::Length];
}

/// How long the muscle takes to contract and to let go when the pulse rate changes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
pub enum MuscleTiming {
    /// The muscle's twitch: it contracts in fixed seconds, the `contraction_duty` of a
    /// cycle at the animal's own pulse rate for its size
    /// ([`Species::natural_pulse_rate`](crate::Species::natural_pulse_rate)), and lets go
    /// as it does at that rate. Beaten slower, the bell rests relaxed between strokes;
    /// beaten faster, the muscle still takes its time to contract and lets go in what is
    /// left of the cycle, so the bell's own recoil limits how fast it can usefully beat.
    /// The animals.
    #[default]
    Twitch,
    /// The paper's: the contraction and the release are those fractions of whatever cycle
    /// the bell beats, so a quicker rate is a quicker twitch.
    Cycle,
}

impl MuscleTiming {
    /// Every timing, for pickers.
    pub const ALL: [MuscleTiming; 2] = [MuscleTiming::Twitch, MuscleTiming::Cycle];
}

/// How a fringe of tentacles drags on the water the slice resolves.
///
/// Across a tentacle both laws take a cylinder's drag. They differ along it, where a
/// trailing fringe meets its water.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
pub enum FringeDrag {
    /// Each tentacle a slender cylinder (resistive-force theory): along it only skin
    /// friction, Stokes drag's tangential half (Cox 1970). A dense fringe slides as a
    /// porous sheet whose skin friction is about as much again, so the law holds for it
    /// too. The animals.
    #[default]
    Filaments,
    /// The paper's tentacles, immersed chains that move with their water: where the
    /// layers a dense fringe drags along span its gaps, it carries its water as a curtain
    /// and drags as much along as across; sparse tentacles slide as filaments. The
    /// curtain's drag is a wall's: at twelve cells per diameter it is the grid's, not the
    /// water's (`docs/numerics.md`).
    Curtain,
}

impl FringeDrag {
    /// Every law, for pickers.
    pub const ALL: [FringeDrag; 2] = [FringeDrag::Filaments, FringeDrag::Curtain];
}

/// Where the bell's resistance to bending comes from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "bevy", derive(bevy::reflect::Reflect))]
#[cfg_attr(feature = "bevy", type_path = "bevy_jellyfish::species")]
pub enum Bending {
    /// The mesoglea's own: a plate of `elastic_modulus` as thick as the wall bends with
    /// E·ϑ³/12, as its stretching follows the same modulus and thickness. A bell resized,
    /// thickened or stiffened keeps a rigidity that fits it; `angular_stiffness` is not
    /// read. The animals.
    #[default]
    Mesoglea,
    /// The paper's angular springs, `angular_stiffness` whatever the mesoglea.
    Springs,
}

impl Bending {
    /// Every source, for pickers.
    pub const ALL: [Bending; 2] = [Bending::Mesoglea, Bending::Springs];
}
