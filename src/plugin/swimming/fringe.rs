//! The fringe in the 3D water: each jellyfish's guide chains (`sim::guides`), stepped after
//! each of its slice's steps with the pose that step's travel gave it. The manubrium and
//! each oral arm have a guide of their own, hanging within the bell: the manubrium from
//! the subumbrellar apex, the arms from its mouth.
//!
//! What the guides feel is what the slice cannot: the water's velocity at each node
//! (`AmbientWater`, the tank's included) less the current that carries the bell, the
//! body's turns, and a game's own moves of the jellyfish; the swimming tows them back into
//! line. A far jellyfish, which replays its cycle, shows the steady trailing of the water
//! at its guides, towed at its recorded mean speed.

use super::guide_frame::{GuideFrame, carrying, relative_water, water_along};
use super::oral_guides::OralGuides;
use super::{FAR_REFRESH, Pose};
use crate::shape::packed;
use crate::shape::tentacles::guide_reference;
use crate::sim::cycle::CycleCache;
use crate::sim::guides::{Filament, GUIDE_NODES, GuideChains, GuideStep, Solid, Trail};
use bevy::prelude::*;
use std::sync::{Arc, Weak};

/// A jellyfish's guide chains: where its fringe trails in the water around it. Read only;
/// the plugin steps it with the slice.
#[derive(Component, Clone, Debug, Default)]
pub struct TentacleGuides {
    chains: GuideChains,
    /// Where the slice draws each guide now, body frame (m, about the bell's centroid).
    reference: Vec<Vec3>,
    water: Vec<Vec3>,
    /// The water halfway down each guide (the steady trailing's).
    halfway: Vec<Vec3>,
    solid: Solid,
    /// The manubrium's guide (none, or one) and the oral arms'.
    oral: OralGuides,
    /// Tentacle length the guides were made for, m.
    length: f32,
    /// Steps since a far jellyfish's trailing was last worked out.
    since_refresh: u32,
    /// The fringe's trail as a far jellyfish draws it (`Trail::thin_into`, rounded to
    /// halves), for `thin_guides` guides; `None` once the chains have moved since. A far
    /// jellyfish's trail changes only when its trailing is worked out again, a few times a
    /// second, while every step records it.
    thin: Arc<[Vec3]>,
    thin_guides: Option<usize>,
    /// Where the thinned trail is worked out before it is shared.
    thinning: Vec<Vec3>,
    /// The recorded cycle whose first step `reference` and `solid` were made from, while
    /// far (a far jellyfish's guides hang from it); dangling otherwise.
    hung_from: Weak<CycleCache>,
}

/// A far jellyfish's guides: towed at the recorded stroke's `mean` speed, m/s, and hung
/// where the first step of its `cycle` (the bell at rest) draws them.
pub(crate) struct FarTow<'a> {
    pub mean: f32,
    pub cycle: &'a Arc<CycleCache>,
}

impl TentacleGuides {
    /// Guides around the margin (0: the fringe follows the slice alone).
    pub fn guides(&self) -> usize {
        self.chains.guides()
    }

    /// Where the slice draws each guide's tentacle, `guides × GUIDE_NODES` points root
    /// first, in the jellyfish's local frame (metres, as its mesh).
    pub fn reference(&self) -> &[Vec3] {
        &self.reference
    }

    /// How far the water has moved each guide node from its reference, same frame.
    pub fn offsets(&self) -> &[Vec3] {
        self.chains.offsets()
    }

    /// How far the water has moved each oral tube's guide node from where the slice draws
    /// it, tube by tube in the surface's order (the manubrium first). Empty when the
    /// species has no oral guides, and while the jellyfish is far (its arms hang as its
    /// replayed cycle draws them).
    pub fn oral_offsets(&self) -> &[Vec3] {
        self.oral.offsets()
    }

    /// Where the slice draws each oral tube's guide, as [`Self::reference`].
    pub fn oral_reference(&self) -> &[Vec3] {
        self.oral.reference()
    }

    /// Oral guides: the manubrium (if the species has one and guides) and the arms.
    pub fn oral_guides(&self) -> usize {
        self.oral.tubes()
    }

    /// Oral tube `t`'s guide nodes as drawn, root first, local frame.
    pub fn oral_drawn(&self, t: usize) -> impl Iterator<Item = Vec3> + '_ {
        let range = t * GUIDE_NODES..(t + 1) * GUIDE_NODES;
        let reference = self.oral.reference().get(range.clone()).unwrap_or_default();
        let offsets = self.oral.offsets().get(range).unwrap_or_default();
        reference.iter().zip(offsets).map(|(q, d)| *q + *d)
    }

    /// Guide `g`'s nodes as drawn, root first, local frame.
    pub fn drawn(&self, g: usize) -> impl Iterator<Item = Vec3> + '_ {
        let range = g * GUIDE_NODES..(g + 1) * GUIDE_NODES;
        self.reference[range.clone()]
            .iter()
            .zip(&self.offsets()[range])
            .map(|(q, d)| *q + *d)
    }

    /// The fringe's trail thinned to `guides` guides and rounded to halves, as a far
    /// jellyfish draws it (`Snapshot::set_thin_trail`): worked out again only after the
    /// chains have moved.
    pub(crate) fn thin_trail(&mut self, guides: usize) -> &Arc<[Vec3]> {
        if self.thin_guides != Some(guides) {
            Trail::new(self.chains.offsets()).thin_into(guides, &mut self.thinning);
            packed::round_to_halves(&mut self.thinning);
            self.thin = Arc::from(&self.thinning[..]);
            self.thin_guides = Some(guides);
        }
        &self.thin
    }

    /// Steps the guides by one slice step: live (the filament's dynamics) or, for a
    /// replayed far jellyfish, its steady trailing (`far`; `f` is then its cycle's first
    /// step).
    pub(crate) fn step(&mut self, f: &GuideFrame, far: Option<FarTow>) {
        let guides = f.species.guide_count();
        if guides != self.chains.guides() || f.species.tentacle_length != self.length {
            self.chains = GuideChains::new(guides);
            self.length = f.species.tentacle_length;
            self.thin_guides = None;
            self.hung_from = Weak::new();
        }
        self.oral.fit(f.species);
        if guides == 0 && self.oral.tubes() == 0 {
            self.reference.clear();
            return;
        }
        let towing = (f.surge / f.dt).max(0.0);
        match far {
            None => {
                self.thin_guides = None;
                self.hung_from = Weak::new();
                // The body turned in the step; the water holds the nodes where they were.
                let turn = (f.before.rotation.inverse() * f.after.rotation).normalize();
                self.chains.turn_frame(turn);
                self.oral.turn_frame(turn);
                self.refresh_shape(f);
                self.oral.refresh_shape(f);
                self.read_water(f);
                self.chains.step(&GuideStep {
                    dt: f.dt,
                    reference: &self.reference,
                    water: &self.water,
                    towing,
                    filament: Filament::of(f.species, towing),
                    solid: &self.solid,
                });
                self.oral.step(f, towing, &self.solid);
            }
            Some(far) => self.trail_steadily(f, far),
        }
    }

    /// A far jellyfish's steady trailing in the water halfway down each guide (where the
    /// species hangs it at rest), towed at `mean` m/s: worked out every [`FAR_REFRESH`]
    /// seconds, a whole number of steps (the current changes slowly; the offsets ride on
    /// the replayed shape between, turning with the body), and not at all where the water
    /// there would move a tip by less than a hundredth of a tentacle. The guides hang
    /// from the cycle's first step, so their shape is made once for each cycle.
    fn trail_steadily(&mut self, f: &GuideFrame, FarTow { mean, cycle }: FarTow) {
        // A far jellyfish's oral arms, a few pixels mostly within its bell, hang as the
        // replayed cycle draws them.
        self.oral.rest();
        self.since_refresh += 1;
        let due = self.since_refresh as f32 * f.dt >= FAR_REFRESH;
        if !due && !self.reference.is_empty() {
            return;
        }
        self.since_refresh = 0;
        self.thin_guides = None;
        let s = f.species;
        let guides = self.chains.guides();
        // Where the species hangs each guide's middle at rest, about the bell's centroid.
        let (radius, depth) = (0.5 * s.diameter, 0.4 * s.height + 0.5 * s.tentacle_length);
        let probe = |g: usize| {
            let (sin, cos) = GuideChains::angle(g, guides).sin_cos();
            Vec3::new(radius * cos, -depth, radius * sin)
        };
        let negligible = 0.01 * mean.max(1e-4);
        let carrying = carrying(f);
        self.halfway.clear();
        let halfway = (0..guides).map(|g| relative_water(f, carrying, probe(g)));
        self.halfway.extend(halfway);
        if !std::ptr::eq(self.hung_from.as_ptr(), Arc::as_ptr(cycle)) || self.reference.is_empty() {
            self.refresh_shape(f);
            self.hung_from = Arc::downgrade(cycle);
        }
        if self.halfway.iter().all(|w| w.length() < negligible) {
            self.chains.reset();
            return;
        }
        self.chains
            .steady(&self.reference, &self.halfway, mean, &self.solid);
    }

    /// Where the slice draws the guides now, and the bell as a solid.
    fn refresh_shape(&mut self, f: &GuideFrame) {
        let roots = [f.bell[0], f.bell[f.bell.len() - 1]];
        let guides = self.chains.guides();
        guide_reference(f.tentacles, roots, f.centroid, guides, &mut self.reference);
        self.solid.rebuild(f.bell, f.centroid, f.species);
    }

    /// The water at each node relative to the current carrying the bell ([`water_along`]).
    fn read_water(&mut self, f: &GuideFrame) {
        water_along(f, &self.reference, self.chains.offsets(), &mut self.water);
    }

    /// A game moved the jellyfish from `before` to `after` (poses of the newest step):
    /// the fringe stays in the water and is dragged after it.
    pub(crate) fn moved(&mut self, before: Pose, after: Pose, scale: Vec3) {
        self.thin_guides = None;
        let inverse = after.rotation.inverse();
        let to_body = |y: Vec3| {
            let world = before.position + before.rotation * (scale * y);
            inverse * (world - after.position) / scale
        };
        self.chains.move_frame(to_body, self.length, &self.solid);
        self.oral.moved(to_body, &self.solid);
    }
}
