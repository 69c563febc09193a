//! Guide chains: the fringe in the 3D water that the slice cannot see.
//!
//! The slice simulates the water in its own plane, in a frame that swims with the bell and
//! never turns; its tentacle chains are what a fringe does in that water, and they keep
//! driving the swimming. What the slice cannot see is carried by a few *guide chains*
//! around the margin, as offsets from where the slice draws their tentacle (the
//! *reference*): the water's velocity relative to the body that differs from the slice's
//! (a current that is not the one carrying the bell, a game dragging the jellyfish through
//! the water) and the body's turns, which leave the fringe where the water holds it.
//!
//! Each guide is a towed filament pinned at its root (follow-the-leader kinematics of a
//! slender body whose drag dominates its inertia): every node moves with the water
//! relative to it — the stream the swimming tows past the fringe, speed `W` along the
//! reference from root to tip, plus the unseen water `w` — and the chain is then pulled
//! back to its length from the root, which is the tension. In a uniform relative stream
//! the chain comes to lie along it, where its drag balances its tension; with `w = 0` it
//! stays on the reference. The drag per length across the tentacle (`c_n`, the slice's own
//! law at the tentacle's Reynolds number) sets the filament's response time
//! `τ = m/c_n` (its mass with the water it carries; its inertia in a turn) and, with its
//! bending stiffness `EI`, how fast a kink of the guide's spacing `Δs` straightens,
//! `EI/(c_n·Δs⁴)`. The drawn chain keeps its reference's segment lengths (inextensible)
//! and stays out of the bell ([`Solid`]).

mod solid;
mod trail;
mod water;

pub use solid::Solid;
pub use trail::{THIN_NODES, Trail, along, between};
pub use water::read_along;

use crate::species::Species;
use glam::{Quat, Vec3};

/// Nodes per guide, the root included: enough for a smooth curve of the offset, whose
/// steady state is straight and whose lag after a turn is one bend.
pub const GUIDE_NODES: usize = 7;

/// A jump of the body farther than this many tentacle lengths in one move is a teleport,
/// not a drag through the water: the fringe starts again where the slice draws it.
const TELEPORT_LENGTHS: f32 = 4.0;

/// Where a guide hangs, and so what of the bell its nodes stay out of.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Hanging {
    /// From the margin, outside the bell: out of the mesoglea and the cavity (the fringe).
    #[default]
    Outside,
    /// From the subumbrellar apex, in the cavity and below it, never through the
    /// mesoglea (the manubrium and the oral arms). As the slice models these parts, they
    /// have no inertia of their own and bend back towards where the slice draws them
    /// over `relaxation` seconds (`sim::oral_arms`: 0.08 s for the manubrium, 0.6 s
    /// for an arm).
    Within {
        /// How long the part takes to bend back, s.
        relaxation: f32,
    },
}

impl Hanging {
    /// The manubrium, from the subumbrellar apex: bent back as the slice bends it.
    pub const MANUBRIUM: Self = Self::Within {
        relaxation: crate::sim::oral_arms::MANUBRIUM_RELAXATION,
    };
    /// An oral arm, from the mouth: bent back as the slice bends it.
    pub const ORAL_ARM: Self = Self::Within {
        relaxation: crate::sim::oral_arms::ARM_RELAXATION,
    };
}

/// The guide chains of one jellyfish: offsets from the reference, body frame (the slice's
/// 3D frame: metres, y the bell's axis, origin at the bell's centroid).
#[derive(Clone, Debug, Default)]
pub struct GuideChains {
    guides: usize,
    hanging: Hanging,
    /// `guides × GUIDE_NODES` offsets from the reference, m; each guide's root is zero.
    offsets: Vec<Vec3>,
    /// Their rate of change, m/s.
    velocity: Vec<Vec3>,
    /// The reference of the last step (where the slice drew each guide), m.
    reference: Vec<Vec3>,
    /// Each of its segments' length, m, at the node that ends it (a root's is 0): a far
    /// jellyfish trails from one reference a whole cycle long.
    lengths: Vec<f32>,
}

/// What one step of the guides needs besides their state.
#[derive(Clone, Copy, Debug)]
pub struct GuideStep<'a> {
    /// The step, s.
    pub dt: f32,
    /// Where the slice draws each guide's tentacle after the step: `guides × GUIDE_NODES`
    /// points, root first, body frame, m.
    pub reference: &'a [Vec3],
    /// The water's velocity relative to the body that the slice does not see, at each
    /// node, body frame, m/s.
    pub water: &'a [Vec3],
    /// How fast the swimming tows the water past the fringe from root to tip, m/s (≥ 0).
    pub towing: f32,
    /// The tentacle's drag and inertia.
    pub filament: Filament,
    /// The bell as a solid the nodes must stay out of.
    pub solid: &'a Solid,
}

/// A tentacle as a filament in the water: what its drag, inertia and stiffness are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Filament {
    /// Mass per length with the water it carries sideways (ρ_t + ρ)·π·a², kg/m.
    pub mass_per_length: f32,
    /// Drag per length across the tentacle, per unit of relative speed, N·s/m².
    pub normal_drag: f32,
    /// Bending stiffness E·π·a⁴/4, N·m².
    pub bending: f32,
}

impl Filament {
    /// A tentacle of `species` at relative speed `speed` (m/s): the drag across it by the
    /// slice's own law (slender-body Stokes drag, White's cylinder drag as it speeds up),
    /// its mass with the water it carries and the bending of a cylinder of mesoglea.
    pub fn of(species: &Species, speed: f32) -> Self {
        let (radius, length) = (species.tentacle_radius, species.tentacle_length);
        crate::sim::body::cylinder_filament(species, radius, length, speed)
    }

    /// The manubrium: a tube of mesoglea of the species' radius, far stiffer than a
    /// tentacle (bending goes as the radius to the fourth). Carried by the water as the
    /// slice carries it: no inertia of its own ([`Hanging::Within`]).
    pub fn manubrium(species: &Species, speed: f32) -> Self {
        let (radius, length) = (species.manubrium_radius, species.manubrium_length);
        Self {
            mass_per_length: 0.0,
            ..crate::sim::body::cylinder_filament(species, radius, length, speed)
        }
    }

    /// An oral arm: a blade `w` wide and about `0.3·w` thick (as the surface draws it),
    /// dragged broadside as a cylinder of its half-width, bending across its thin side,
    /// `E·w·t³/12`: limp. Carried by the water as the slice carries it: no inertia of its
    /// own ([`Hanging::Within`]).
    pub fn oral_arm(species: &Species, speed: f32) -> Self {
        let w = species.oral_arm_width.max(1e-6);
        let blade =
            crate::sim::body::cylinder_filament(species, 0.5 * w, species.oral_arm_length, speed);
        let t = 0.3 * w;
        Self {
            mass_per_length: 0.0,
            bending: species.elastic_modulus * w * t * t * t / 12.0,
            ..blade
        }
    }

    /// The time the tentacle takes to catch up with the water around it, s.
    pub fn response_time(&self) -> f32 {
        self.mass_per_length / self.normal_drag.max(1e-12)
    }
}

impl GuideChains {
    /// `guides` chains of the fringe hanging where the slice draws them.
    pub fn new(guides: usize) -> Self {
        Self::hanging(guides, Hanging::Outside)
    }

    /// `guides` chains hanging where the slice draws them, `hanging` as they do.
    pub fn hanging(guides: usize, hanging: Hanging) -> Self {
        let n = guides * GUIDE_NODES;
        Self {
            guides,
            hanging,
            offsets: vec![Vec3::ZERO; n],
            velocity: vec![Vec3::ZERO; n],
            reference: Vec::new(),
            lengths: Vec::new(),
        }
    }

    /// Guides around the margin.
    pub fn guides(&self) -> usize {
        self.guides
    }

    /// Offsets from the reference, `guides × GUIDE_NODES`, guide by guide, root first.
    pub fn offsets(&self) -> &[Vec3] {
        &self.offsets
    }

    /// The angle of guide `g` around the axis (σ, from +x through +z).
    pub fn angle(g: usize, guides: usize) -> f32 {
        std::f32::consts::TAU * g as f32 / guides.max(1) as f32
    }

    /// Back where the slice draws them, at rest.
    pub fn reset(&mut self) {
        self.offsets.fill(Vec3::ZERO);
        self.velocity.fill(Vec3::ZERO);
    }

    /// The body turned by `turn` (the new frame's axes in the old frame's terms): nodes
    /// stay where the water holds them, so their body-frame positions turn back.
    pub fn turn_frame(&mut self, turn: Quat) {
        if turn == Quat::IDENTITY || self.reference.len() != self.offsets.len() {
            return;
        }
        let back = turn.inverse();
        for ((d, v), q) in self
            .offsets
            .iter_mut()
            .zip(&mut self.velocity)
            .zip(&self.reference)
        {
            *d = back * (*q + *d) - *q;
            *v = back * *v;
        }
        self.zero_roots();
    }

    /// The body was moved by something other than the water and its own swimming (a game
    /// placing it): `to_body` maps a point of the old body frame into the new one. The
    /// nodes stay in the water, the chains pulled after their roots and kept out of the
    /// bell; a jump of more than a few `length`s starts them afresh.
    pub fn move_frame(&mut self, to_body: impl Fn(Vec3) -> Vec3, length: f32, solid: &Solid) {
        if self.reference.len() != self.offsets.len() {
            return;
        }
        let jump = to_body(Vec3::ZERO).length();
        let near = jump <= TELEPORT_LENGTHS * length; // false for NaN too
        if !near {
            self.reset();
            return;
        }
        let origin = to_body(Vec3::ZERO);
        for ((d, v), q) in self
            .offsets
            .iter_mut()
            .zip(&mut self.velocity)
            .zip(&self.reference)
        {
            *d = to_body(*q + *d) - *q;
            *v = to_body(*v) - origin;
        }
        for g in 0..self.guides {
            let range = g * GUIDE_NODES..(g + 1) * GUIDE_NODES;
            let reference = &self.reference[range.clone()];
            let lengths = segment_lengths(reference);
            inextensible(
                reference,
                &lengths,
                &mut self.offsets[range],
                solid,
                self.hanging,
            );
        }
    }

    /// One step: each node carried by the water relative to it (with the filament's lag
    /// `τ`), its kinks relaxed by bending, the chain pulled back to its length from the
    /// root and kept out of the bell. A step with the wrong number of points is skipped.
    pub fn step(&mut self, s: &GuideStep) {
        let n = self.offsets.len();
        let positive = s.dt > 0.0; // false for NaN too
        if s.reference.len() != n || s.water.len() != n || !positive {
            return;
        }
        let (dt, towing) = (s.dt, s.towing.max(0.0));
        let tau = s.filament.response_time();
        for g in 0..self.guides {
            let range = g * GUIDE_NODES..(g + 1) * GUIDE_NODES;
            let reference = &s.reference[range.clone()];
            let water = &s.water[range.clone()];
            let offsets = &mut self.offsets[range.clone()];
            let velocity = &mut self.velocity[range];
            let before: [Vec3; GUIDE_NODES] = (&*offsets).try_into().unwrap_or_default();
            for m in 1..GUIDE_NODES {
                let along = (reference[m] - reference[m - 1]).normalize_or(Vec3::NEG_Y);
                let stream = water[m] + towing * along;
                velocity[m] = (tau * velocity[m] + dt * stream) / (tau + dt);
                offsets[m] += dt * velocity[m];
            }
            if let Hanging::Within { relaxation } = self.hanging {
                let keep = relaxation.max(0.0) / (relaxation.max(0.0) + dt);
                offsets.iter_mut().for_each(|d| *d *= keep);
            }
            let lengths = segment_lengths(reference);
            let spacing = lengths[1..].iter().sum::<f32>() / (GUIDE_NODES - 1) as f32;
            let rate = s.filament.bending / (s.filament.normal_drag.max(1e-12) * spacing.powi(4));
            straighten(offsets, (rate * dt).min(0.25));
            inextensible(reference, &lengths, offsets, s.solid, self.hanging);
            for m in 1..GUIDE_NODES {
                velocity[m] = (offsets[m] - before[m]) / dt;
            }
        }
        self.reference.clear();
        self.reference.extend_from_slice(s.reference);
        self.lengths.clear();
        if !self.offsets.iter().all(|d| d.is_finite()) {
            self.reset();
        }
    }

    /// The steady trailing in a relative stream that does not change: `water[g]` along
    /// guide `g`, towed at `towing` (what a far jellyfish, which replays its cycle, shows).
    pub fn steady(&mut self, reference: &[Vec3], water: &[Vec3], towing: f32, solid: &Solid) {
        if reference.len() != self.offsets.len() || water.len() != self.guides {
            return;
        }
        // Below a tenth of a millimetre a second the fringe is simply carried off.
        let towing = towing.max(1e-4);
        // The segments' lengths, worked out again only when the reference has changed.
        if self.lengths.len() != reference.len() || self.reference != reference {
            self.reference.clear();
            self.reference.extend_from_slice(reference);
            self.lengths.clear();
            let each = reference.chunks_exact(GUIDE_NODES).map(segment_lengths);
            self.lengths.extend(each.flatten());
        }
        for (g, water) in water.iter().enumerate() {
            let range = g * GUIDE_NODES..(g + 1) * GUIDE_NODES;
            let reference = &reference[range.clone()];
            let lengths = &self.lengths[range.clone()];
            let step = lengths[1..].iter().sum::<f32>() / (GUIDE_NODES - 1) as f32;
            let offsets = &mut self.offsets[range.clone()];
            // Bent back over a relaxation time, a part hanging within the bell is moved
            // no further than the water takes it in that time.
            let most = match self.hanging {
                Hanging::Within { relaxation } => relaxation.max(0.0),
                Hanging::Outside => f32::INFINITY,
            };
            for (m, d) in offsets.iter_mut().enumerate() {
                *d = *water * (m as f32 * step / towing).min(most);
            }
            inextensible(reference, lengths, offsets, solid, self.hanging);
            self.velocity[range].fill(Vec3::ZERO);
        }
        if !self.offsets.iter().all(|d| d.is_finite()) {
            self.reset();
        }
    }

    fn zero_roots(&mut self) {
        for g in 0..self.guides {
            self.offsets[g * GUIDE_NODES] = Vec3::ZERO;
            self.velocity[g * GUIDE_NODES] = Vec3::ZERO;
        }
    }
}

/// The length of each segment of one guide's reference, at the node that ends it (the
/// root's 0).
fn segment_lengths(reference: &[Vec3]) -> [f32; GUIDE_NODES] {
    let mut lengths = [0.0; GUIDE_NODES];
    for (l, w) in lengths[1..].iter_mut().zip(reference.windows(2)) {
        *l = w[0].distance(w[1]);
    }
    lengths
}

/// Bending: each interior offset moves `share` of the way to its neighbours' mean, so a
/// kink the water put into the guide (not the reference's own curve) straightens.
fn straighten(offsets: &mut [Vec3], share: f32) {
    if share <= 0.0 {
        return;
    }
    let before: [Vec3; GUIDE_NODES] = (&*offsets).try_into().unwrap_or_default();
    for m in 1..GUIDE_NODES - 1 {
        let mean = 0.5 * (before[m - 1] + before[m + 1]);
        offsets[m] += share * (mean - before[m]);
    }
}

/// Keeps each segment of the drawn chain (reference + offset) at its reference's length,
/// walking from the root, and every node out of the bell ([`Solid::keep_out`]: where the
/// slice itself draws a node in the wall, only out of the cavity; the guides carry what
/// the slice cannot see, not a second opinion on what it can), or for guides hanging
/// within it, from passing through its wall ([`Solid::keep_within`]).
/// `lengths` are the reference's segments' ([`segment_lengths`]).
fn inextensible(
    reference: &[Vec3],
    lengths: &[f32],
    offsets: &mut [Vec3],
    solid: &Solid,
    hanging: Hanging,
) {
    offsets[0] = Vec3::ZERO;
    let mut previous = reference[0];
    // A root on the subumbrella (the manubrium's, at the apex) is on the cavity's edge:
    // the chain starts on the side its reference hangs into.
    let first = reference[0].lerp(reference[1.min(reference.len() - 1)], 0.5);
    let mut in_cavity = matches!(hanging, Hanging::Within { .. }) && solid.in_cavity_at(first);
    for m in 1..reference.len() {
        let length = lengths[m];
        let drawn = reference[m] + offsets[m];
        let along = (drawn - previous)
            .try_normalize()
            .unwrap_or_else(|| (reference[m] - reference[m - 1]).normalize_or(Vec3::NEG_Y));
        let p = previous + along * length;
        let placed = match hanging {
            Hanging::Outside => solid.keep_out(p, reference[m]),
            Hanging::Within { .. } => {
                let (placed, inside) =
                    solid.keep_within((previous, in_cavity), p, reference[m - 1], reference[m]);
                in_cavity = inside;
                placed
            }
        };
        offsets[m] = placed - reference[m];
        previous = placed;
    }
}

#[cfg(test)]
mod tests;
