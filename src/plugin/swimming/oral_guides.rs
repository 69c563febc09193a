//! The manubrium's and the oral arms' guide chains: one per oral tube, hanging within the
//! bell (the manubrium from the subumbrellar apex, the arms from its mouth), carried by the
//! water as the slice carries these parts and bent back to where it draws them.

use super::guide_frame::{GuideFrame, water_along};
use crate::shape::oral::{self, OralStyle};
use crate::shape::tentacles::TentacleLayout;
use crate::sim::guides::{Filament, GUIDE_NODES, GuideChains, GuideStep, Hanging, Solid};
use crate::species::Species;
use bevy::prelude::*;

/// The oral tubes' guides: the manubrium's (stiff, from the apex) and the arms' (limp,
/// from where the slice puts the mouth: the manubrium's own sway, under its radius, is
/// not passed on to them), with the reference the slice draws them at.
#[derive(Clone, Debug, Default)]
pub(super) struct OralGuides {
    stalk: GuideChains,
    arms: GuideChains,
    /// Every tube's reference, in the surface's order (the manubrium first).
    reference: Vec<Vec3>,
    water: Vec<Vec3>,
    /// Every tube's offsets, in the surface's order.
    offsets: Vec<Vec3>,
    /// The species' oral tubes these were made for, and their length, m.
    tubes: usize,
    length: f32,
}

impl OralGuides {
    /// Every tube's offsets from where the slice draws it, in the surface's order.
    pub(super) fn offsets(&self) -> &[Vec3] {
        &self.offsets
    }

    /// Where the slice draws every tube's guide.
    pub(super) fn reference(&self) -> &[Vec3] {
        &self.reference
    }

    /// Oral tubes with a guide.
    pub(super) fn tubes(&self) -> usize {
        self.tubes
    }

    /// The body turned by `turn`: the nodes stay where the water holds them.
    pub(super) fn turn_frame(&mut self, turn: Quat) {
        self.stalk.turn_frame(turn);
        self.arms.turn_frame(turn);
    }

    /// A game moved the jellyfish (`to_body`, as [`GuideChains::move_frame`]).
    pub(super) fn moved(&mut self, to_body: impl Fn(Vec3) -> Vec3, solid: &Solid) {
        self.stalk.move_frame(&to_body, self.length, solid);
        self.arms.move_frame(&to_body, self.length, solid);
        self.gather();
    }

    /// Guides for the species' oral tubes (made afresh when their number or length
    /// changed).
    pub(super) fn fit(&mut self, species: &Species) {
        let tubes = species.oral_guide_count();
        let length = species.manubrium_length + species.oral_arm_length;
        if tubes == self.tubes && length == self.length {
            return;
        }
        let stalk = (tubes > 0 && species.manubrium_length > 0.0) as usize;
        *self = Self {
            stalk: GuideChains::hanging(stalk, Hanging::MANUBRIUM),
            arms: GuideChains::hanging(tubes - stalk, Hanging::ORAL_ARM),
            offsets: vec![Vec3::ZERO; tubes * GUIDE_NODES],
            tubes,
            length,
            ..default()
        };
    }

    /// Nodes of the manubrium's guide (none without one).
    fn stalk_nodes(&self) -> usize {
        self.stalk.guides() * GUIDE_NODES
    }

    /// Where the slice draws every tube's guide now.
    pub(super) fn refresh_shape(&mut self, f: &GuideFrame) {
        if self.tubes == 0 {
            self.reference.clear();
            return;
        }
        let layout = TentacleLayout {
            count: self.tubes,
            sides: oral::ORAL_SIDES,
            points: 2,
        };
        let apex = f.bell[f.bell.len() / 2];
        let style = OralStyle::of(f.species);
        let (chains, reference) = (f.oral_arms, &mut self.reference);
        oral::guide_reference(&layout, &style, chains, apex, f.centroid, reference);
    }

    /// One live step of the manubrium and the arms.
    pub(super) fn step(&mut self, f: &GuideFrame, towing: f32, solid: &Solid) {
        if self.offsets.len() != self.tubes * GUIDE_NODES {
            // Followed again after resting: from where the slice draws them.
            self.reset();
            self.offsets.resize(self.tubes * GUIDE_NODES, Vec3::ZERO);
        }
        if self.tubes == 0 || self.reference.len() != self.offsets.len() {
            return;
        }
        let k = self.stalk_nodes();
        water_along(f, &self.reference, &self.offsets, &mut self.water);
        let (dt, species) = (f.dt, f.species);
        self.stalk.step(&GuideStep {
            dt,
            reference: &self.reference[..k],
            water: &self.water[..k],
            towing,
            filament: Filament::manubrium(species, towing),
            solid,
        });
        self.arms.step(&GuideStep {
            dt,
            reference: &self.reference[k..],
            water: &self.water[k..],
            towing,
            filament: Filament::oral_arm(species, towing),
            solid,
        });
        self.gather();
    }

    fn reset(&mut self) {
        self.stalk.reset();
        self.arms.reset();
        self.offsets.fill(Vec3::ZERO);
    }

    /// Drawn as the slice (or its replayed cycle) draws them, not followed: no offsets
    /// (nothing to record, blend or pack) and no reference.
    pub(super) fn rest(&mut self) {
        if !self.offsets.is_empty() {
            self.reset();
            self.offsets.clear();
            self.reference.clear();
        }
    }

    /// Every tube's offsets in the surface's order.
    pub(super) fn gather(&mut self) {
        let (stalk, arms) = (self.stalk.offsets(), self.arms.offsets());
        if stalk.len() + arms.len() != self.offsets.len() {
            return;
        }
        let (head, tail) = self.offsets.split_at_mut(stalk.len());
        head.copy_from_slice(stalk);
        tail.copy_from_slice(arms);
    }
}
