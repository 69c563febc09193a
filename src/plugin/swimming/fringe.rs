//! The fringe in the 3D water: each jellyfish's guide chains (`sim::guides`), stepped after
//! each of its slice's steps with the pose that step's travel gave it.
//!
//! What the guides feel is what the slice cannot: the water's velocity at each node
//! (`AmbientWater`, the tank's included) less the current that carries the bell, the
//! body's turns, and a game's own moves of the jellyfish; the swimming tows them back into
//! line. A far jellyfish, which replays its cycle, shows the steady trailing of the water
//! at its guides, towed at its recorded mean speed.

use super::Pose;
use crate::plugin::water::AmbientWater;
use crate::shape::tentacles::guide_reference;
use crate::sim::guides::{Filament, GUIDE_NODES, GuideChains, GuideStep, Solid};
use crate::species::Species;
use bevy::prelude::*;

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
    /// Tentacle length the guides were made for, m.
    length: f32,
    /// Steps since a far jellyfish's trailing was last worked out.
    since_refresh: u32,
}

/// A far jellyfish works out its steady trailing every this many steps.
const FAR_REFRESH: u32 = 4;

/// One slice step as the guides see it.
pub(crate) struct GuideFrame<'a> {
    pub species: &'a Species,
    /// The bell's subumbrella and the two tentacle chains after the step, slice frame.
    pub bell: &'a [Vec2],
    pub tentacles: [&'a [Vec2]; 2],
    /// The bell's centroid in the same frame (the body frame's origin).
    pub centroid: Vec2,
    /// The step, s.
    pub dt: f32,
    /// How far the bell swam along its axis in the step, m.
    pub surge: f32,
    /// The pose before and after the step's travel.
    pub before: Pose,
    pub after: Pose,
    /// World units per metre of slice, per axis.
    pub scale: Vec3,
    pub water: &'a AmbientWater,
    /// World time the water is read at, s.
    pub time: f64,
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

    /// Guide `g`'s nodes as drawn, root first, local frame.
    pub fn drawn(&self, g: usize) -> impl Iterator<Item = Vec3> + '_ {
        let range = g * GUIDE_NODES..(g + 1) * GUIDE_NODES;
        self.reference[range.clone()]
            .iter()
            .zip(&self.offsets()[range])
            .map(|(q, d)| *q + *d)
    }

    /// Steps the guides by one slice step: live (the filament's dynamics) or, for a
    /// replayed far jellyfish towed at `steady` m/s on average, its steady trailing.
    pub(crate) fn step(&mut self, f: &GuideFrame, steady: Option<f32>) {
        let guides = f.species.guide_count();
        if guides != self.chains.guides() || f.species.tentacle_length != self.length {
            self.chains = GuideChains::new(guides);
            self.length = f.species.tentacle_length;
        }
        if guides == 0 {
            self.reference.clear();
            return;
        }
        // The body turned in the step; the water holds the nodes where they were.
        let turn = f.before.rotation.inverse() * f.after.rotation;
        self.chains.turn_frame(turn.normalize());
        let towing = (f.surge / f.dt).max(0.0);
        match steady {
            None => {
                self.refresh_shape(f);
                self.read_water(f, |_| true);
                self.chains.step(&GuideStep {
                    dt: f.dt,
                    reference: &self.reference,
                    water: &self.water,
                    towing,
                    filament: Filament::of(f.species, towing),
                    solid: &self.solid,
                });
            }
            Some(mean) => self.trail_steadily(f, mean),
        }
    }

    /// A far jellyfish's steady trailing in the water halfway down each guide, towed at
    /// `mean` m/s: worked out every [`FAR_REFRESH`] steps (the current changes slowly; the
    /// offsets ride on the replayed shape between), and not at all where the water there
    /// would move a tip by less than a hundredth of a tentacle.
    fn trail_steadily(&mut self, f: &GuideFrame, mean: f32) {
        self.since_refresh += 1;
        if self.since_refresh < FAR_REFRESH && !self.reference.is_empty() {
            return;
        }
        self.since_refresh = 0;
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
        let calm = (0..guides).all(|g| relative_water(f, carrying, probe(g)).length() < negligible);
        if calm {
            self.chains.reset();
            if self.reference.is_empty() {
                self.refresh_shape(f);
            }
            return;
        }
        self.refresh_shape(f);
        self.read_water(f, |m| m == GUIDE_NODES / 2);
        self.halfway.clear();
        let halfway = self.water.chunks(GUIDE_NODES).map(|w| w[GUIDE_NODES / 2]);
        self.halfway.extend(halfway);
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

    /// The water at the nodes `wanted` picks (by index along the guide) relative to the
    /// current carrying the bell, body frame, m/s; zero elsewhere and where the field is
    /// not finite.
    fn read_water(&mut self, f: &GuideFrame, wanted: impl Fn(usize) -> bool) {
        let carrying = carrying(f);
        self.water.clear();
        let offsets = self.chains.offsets();
        for (k, q) in self.reference.iter().enumerate() {
            let local = *q + offsets.get(k).copied().unwrap_or_default();
            self.water.push(match wanted(k % GUIDE_NODES) {
                true => relative_water(f, carrying, local),
                false => Vec3::ZERO,
            });
        }
    }

    /// A game moved the jellyfish from `before` to `after` (poses of the newest step):
    /// the fringe stays in the water and is dragged after it.
    pub(crate) fn moved(&mut self, before: Pose, after: Pose, scale: Vec3) {
        let inverse = after.rotation.inverse();
        let to_body = |y: Vec3| {
            let world = before.position + before.rotation * (scale * y);
            inverse * (world - after.position) / scale
        };
        self.chains.move_frame(to_body, self.length, &self.solid);
    }
}

/// The current carrying the bell, world units per second.
fn carrying(f: &GuideFrame) -> Vec3 {
    finite(f.water.velocity(f.after.position, f.time))
}

/// The water at the body-frame point `local` less the current `carrying` the bell, body
/// frame, m/s (zero where the field is not finite).
fn relative_water(f: &GuideFrame, carrying: Vec3, local: Vec3) -> Vec3 {
    let (pose, scale) = (f.after, f.scale);
    let world = pose.position + pose.rotation * (scale * local);
    let relative = finite(f.water.velocity(world, f.time)) - carrying;
    finite(pose.rotation.inverse() * relative / scale)
}

fn finite(v: Vec3) -> Vec3 {
    if v.is_finite() { v } else { Vec3::ZERO }
}
