//! How much of a jellyfish is simulated ([`Tier`]), and the far tier's stroke: its
//! species' recorded cycle played on its own clock ([`Replay`]). Which tier each
//! jellyfish gets is the levels of detail's choice (`plugin::lod`).

use crate::sim::clock::FixedClock;
use crate::sim::cycle::CycleCache;
use crate::sim::escape::Escape;
use crate::species::Species;
use bevy::prelude::*;
use std::sync::Arc;

/// How much of a jellyfish is simulated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Reflect)]
pub enum Tier {
    /// The species' slice, live.
    #[default]
    Near,
    /// A live slice in a compact box: cheaper, a few percent slower.
    Mid,
    /// The species' recorded stroke cycle, replayed: no fluid.
    Far,
}

/// Marks a jellyfish whose slice is live (near or mid): the stepping and the meshing take
/// these first, one at a time, and the rest after them in small batches, so that cheap
/// work, not a live slice, is what ends each thread's frame. Only the order of work reads
/// it; the levels of detail keep it in step with the tier (without them no jellyfish is
/// marked, and all are taken in small batches).
#[derive(Component, Clone, Copy, Debug, Default)]
pub(crate) struct LiveSlice;

/// The species a tier simulates: the species itself near and far, its
/// [`Species::compact_box`] mid.
pub(crate) fn tier_species(species: &Species, tier: Tier) -> Species {
    if tier == Tier::Mid {
        species.compact_box()
    } else {
        species.clone()
    }
}

/// A far jellyfish's stroke: its species' recorded cycle, played on its own clock.
pub(crate) struct Replay {
    pub cache: Arc<CycleCache>,
    pub clock: FixedClock,
    /// Distance swum, m.
    pub swim: f64,
    /// An edited species whose cycle is being recorded: the old cycle plays until then.
    pub wanted: Option<Species>,
    /// A startle under way: the cycle plays at its quicker rhythm (the recorded stroke
    /// cannot beat deeper).
    pub escape: Option<Escape>,
}

impl Replay {
    /// Sets the time added to `added` seconds and plays the steps that pays for;
    /// `after_step` sees the replay after each. Resting holds the frame where the stroke
    /// stopped and swims nowhere.
    pub fn advance_until(&mut self, added: f64, resting: bool, mut after_step: impl FnMut(&Self)) {
        for _ in 0..self.clock.add_until(added) {
            if resting {
                self.clock.tick_held();
                after_step(self);
                continue;
            }
            // A quicker rhythm plays two recorded steps in some fixed steps, and swims both.
            let species = self.cache.species();
            let quick = self.escape.as_mut().map_or(1, |e| e.step(species));
            if self.escape.as_ref().is_some_and(Escape::done) {
                self.escape = None;
            }
            self.clock.tick();
            self.swim += self.cache.frame(self.index()).surge as f64;
            for _ in 1..quick {
                self.clock.hurry();
                self.swim += self.cache.frame(self.index()).surge as f64;
            }
            after_step(self);
        }
    }

    /// Startles it with a touch of `strength` (see `SliceSim::escape`).
    pub fn escape(&mut self, strength: f32) {
        let species = self.cache.species();
        let Some(fresh) = Escape::new(species, self.clock.steps_per_cycle(), strength) else {
            return;
        };
        match &mut self.escape {
            Some(e) => e.renew(fresh),
            None => self.escape = Some(fresh),
        }
    }

    /// The place in the cycle of the state.
    pub fn index(&self) -> u32 {
        (self.clock.stroke_steps() % self.clock.steps_per_cycle() as u64) as u32
    }
}
