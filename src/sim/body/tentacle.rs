//! The tentacles as thin cylinders in the water: slender-body drag, and contact with the
//! bell they hang from.

use super::Body;
use super::depth::Depth;
use super::outline::contains;
use crate::species::{FringeDrag, Species};

/// Euler's constant γ, of the thick layer's skin friction ([`TentacleDrag::along_one`]).
const EULER_GAMMA: f32 = 0.577_215_7;

/// The drag on one point of the slice's tentacle curtain, per metre of depth.
///
/// One tentacle is a cylinder of radius `a` across the flow: `½·ρ·U²·2a·C_d` per length,
/// with White's (1991) `C_d = 1 + 10·Re^(−2/3)` for a cylinder at `Re = U·2a/ν` (a
/// tentacle at a centimetre per second is at Re ≈ 6), and never less than slender-body
/// Stokes drag `4πμ/(ln(L/a) + 1/2)` (Lighthill 1976) as the flow stops. The slice stands
/// for the bell's whole circumference, so the curtain has `count / (π·D)` tentacles per
/// metre of depth; a point carries one segment. In r–z the fringe is a ring of
/// tentacles, `count / 2π` of them per radian.
#[derive(Clone, Copy, Debug)]
pub(super) struct TentacleDrag {
    radius: f32,
    density: f32,
    kinematic_viscosity: f32,
    /// Slender-body Stokes drag per length of one tentacle, N·s/m².
    stokes: f32,
    /// Tentacle length per metre of depth that one point carries: segment × count / (π·D).
    length_per_point: f32,
    /// One tentacle's length, m.
    length: f32,
    /// The water between neighbouring tentacles at the margin, m: π·D/count − 2a.
    gap: f32,
    /// The species' law along a tentacle.
    law: FringeDrag,
}

impl TentacleDrag {
    /// A tentacle of the species, hanging straight, in segments of `segment` metres.
    pub(crate) fn new(species: &Species, segment: f32, depth: Depth) -> Self {
        let per_depth = tentacles_per_depth(species, depth);
        let (radius, length) = (species.tentacle_radius, species.tentacle_length);
        let gap = std::f32::consts::PI * species.diameter / species.tentacle_count.max(1) as f32
            - 2.0 * radius;
        Self {
            gap: gap.max(0.0),
            law: species.fringe_drag,
            ..Self::cylinder(species, radius, length, per_depth * segment)
        }
    }

    /// A cylinder of `radius` and `length` (m) in the species' water, carrying
    /// `length_per_point` of it per point.
    fn cylinder(species: &Species, radius: f32, length: f32, length_per_point: f32) -> Self {
        let a = radius.max(1e-6);
        let length = length.max(2.0 * a);
        Self {
            radius: a,
            density: species.density,
            kinematic_viscosity: species.kinematic_viscosity(),
            stokes: 4.0 * std::f32::consts::PI * species.viscosity / ((length / a).ln() + 0.5),
            length_per_point,
            length,
            gap: 0.0,
            law: FringeDrag::Filaments,
        }
    }

    /// Force per unit of slip velocity at relative speed `speed` (m/s), N·s/m² per metre
    /// of depth.
    pub(crate) fn at(&self, speed: f32) -> f32 {
        (self.per_length(speed) * self.length_per_point).max(1e-9)
    }

    /// [`TentacleDrag::at`] for a slip at `speed` (m/s) whose direction makes an angle θ
    /// with the tentacle, `along` = cos²θ (resistive-force theory: the slip's two
    /// components resisted apart, Gray & Hancock 1955). Across a tentacle the cylinder's
    /// drag; along it a cylinder has no form drag, only skin friction: never less than
    /// slender-body Stokes drag's tangential half (Cox 1970; Lighthill 1976).
    ///
    /// [`FringeDrag::Filaments`]: where the viscous layers the tentacles drag along their
    /// length (`√(ν·L/U)` thick, Glauert & Lighthill 1955) span the gaps between them, the
    /// fringe slides as one porous sheet, whose skin friction (Blasius, `1.328/√Re_L` on
    /// each face) per tentacle's share is about that tangential half (unit test); where
    /// they are apart, each tentacle drags its own layer, thinner than its length
    /// ([`TentacleDrag::along_one`]); between, in proportion to the share of the gap the
    /// layers span. [`FringeDrag::Curtain`], the paper's immersed chains, lets a dense
    /// fringe drag as much along as across: it moves with its water, and the grid, not the
    /// water, then sets its drag.
    pub(crate) fn at_angle(&self, speed: f32, along: f32) -> f32 {
        let across = self.per_length(speed);
        let isolated = (0.5 * self.stokes).min(across);
        // How many times the gap between neighbours the layer each drags is thick.
        let layer = (self.kinematic_viscosity * self.length / speed.max(1e-9)).sqrt();
        let spans = layer / self.gap.max(1e-9);
        let tangential = match self.law {
            FringeDrag::Filaments if spans >= 1.0 || spans.is_nan() => isolated,
            FringeDrag::Filaments => {
                spans * isolated + (1.0 - spans) * self.along_one(speed).min(across)
            }
            FringeDrag::Curtain if spans >= 1.0 || spans.is_nan() => return self.at(speed),
            FringeDrag::Curtain => spans * across + (1.0 - spans) * isolated,
        };
        let along = along.clamp(0.0, 1.0);
        (((1.0 - along) * across + along * tangential) * self.length_per_point).max(1e-9)
    }

    /// The drag along one tentacle on its own, per unit of slip velocity per length, at
    /// relative speed `speed` (m/s), N·s/m². Slipping along its length, a cylinder drags a
    /// layer that grows from its root, `√(4·ν·x/U)` thick at `x`; much thicker than the
    /// cylinder, the flow in it is logarithmic and the skin friction `4πμ / (ln ξ − γ)` a
    /// metre, `ξ = 4·ν·x/(U·a²)` (Glauert & Lighthill 1955), read halfway down. Stokes
    /// drag's tangential half is the limit as the layer reaches the whole length, and the
    /// least it can be; the log is held at 2 or more (ξ above 13), where the asymptote
    /// holds. At *Sarsia*'s slip, 3 cm/s along 25 mm, it is about four times Stokes'.
    pub(crate) fn along_one(&self, speed: f32) -> f32 {
        let a = self.radius;
        let xi = 2.0 * self.kinematic_viscosity * self.length / (speed.max(1e-9) * a * a);
        let log = (xi.ln() - EULER_GAMMA).max(2.0);
        let mu = self.density * self.kinematic_viscosity;
        (4.0 * std::f32::consts::PI * mu / log).max(0.5 * self.stokes)
    }

    /// Force per unit of slip velocity per length of one tentacle at relative speed
    /// `speed` (m/s), N·s/m².
    pub(crate) fn per_length(&self, speed: f32) -> f32 {
        let d = 2.0 * self.radius;
        let re = (speed * d / self.kinematic_viscosity).max(1e-6);
        let drag_coefficient = 1.0 + 10.0 * re.powf(-2.0 / 3.0);
        let inertial = 0.5 * self.density * speed * d * drag_coefficient;
        self.stokes.max(inertial)
    }
}

/// A cylinder of mesoglea `radius` thick and `length` long in the species' water, as a
/// filament at relative speed `speed` (m/s): the drag across it by the slice's own law
/// for its tentacles, its mass with the water it carries (it is about as dense as sea
/// water, and a cylinder carries its own volume of water sideways) and its bending
/// stiffness `E·π·a⁴/4`. A tentacle is one; the guides also draw the manubrium and the
/// oral arms with it.
pub(crate) fn cylinder_filament(
    species: &Species,
    radius: f32,
    length: f32,
    speed: f32,
) -> crate::sim::guides::Filament {
    let a = radius.max(1e-6);
    let drag = TentacleDrag::cylinder(species, radius, length, 0.0);
    let area = std::f32::consts::PI * a * a;
    crate::sim::guides::Filament {
        mass_per_length: 2.0 * species.density * area,
        normal_drag: drag.per_length(speed.abs()),
        bending: species.elastic_modulus * area * a * a / 4.0,
    }
}

/// Tentacles per unit depth: `count / (π·D)` per metre of a planar slice (the slice
/// stands for the whole circumference), `count / 2π` per radian of a ring.
fn tentacles_per_depth(species: &Species, depth: Depth) -> f32 {
    let count = species.tentacle_count as f32;
    if depth.rings() {
        count / std::f32::consts::TAU
    } else {
        count / (std::f32::consts::PI * species.diameter)
    }
}

/// Bending stiffness per hinge of the tentacle curtain, per unit depth, N·m/rad: one
/// tentacle's `E·π·a⁴/4` (a cylinder of the bell's mesoglea), times the tentacles per unit
/// depth, over one segment. Far softer than the bell's wall: the tentacles trail in the
/// flow instead of swinging as rods.
pub(super) fn tentacle_bending(species: &Species, segment: f32, depth: Depth) -> f32 {
    let a = species.tentacle_radius;
    let one = species.elastic_modulus * std::f32::consts::PI * a.powi(4) / 4.0;
    one * tentacles_per_depth(species, depth) / segment
}

impl Body {
    /// Puts back outside the bell any tentacle point the refilling flow carried into it:
    /// onto the nearest point of the outline (the subumbrella closed by the aperture
    /// chord). Tentacles hang from the margin and cannot pass through the mesoglea.
    pub(crate) fn keep_tentacles_outside(&mut self) {
        let n = self.bell.len();
        // No point above the bell's highest nor below its lowest can be inside it (no
        // edge spans its height): most of a trailing fringe, tested without its edges.
        let (low, high) = self.points[self.bell.clone()]
            .iter()
            .fold((f32::MAX, f32::MIN), |(lo, hi), q| {
                (lo.min(q.y), hi.max(q.y))
            });
        for range in self.tentacles.clone() {
            for i in range {
                let p = self.points[i];
                let bell = &self.points[self.bell.clone()];
                if p.y < low || p.y >= high || !contains(bell, p) {
                    continue;
                }
                let mut best = (f32::MAX, p);
                for k in 0..n {
                    let (a, b) = (bell[k], bell[(k + 1) % n]);
                    let ab = b - a;
                    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-18)).clamp(0.0, 1.0);
                    let q = a + t * ab;
                    let d = (p - q).length_squared();
                    if d < best.0 {
                        best = (d, q);
                    }
                }
                // Just outside, not on the edge, so the next step starts outside.
                let out = (best.1 - p).normalize_or_zero();
                self.points[i] = best.1 + out * 1e-3 * (bell[0] - bell[n - 1]).length();
            }
        }
    }
}
