//! The far tier's recorded cycles, packed once each.
//!
//! Every far jellyfish of a species plays the same recorded cycle, and a frame shows one
//! of its steps (the nearest, not a blend: [`shown_step`]). So the first time a far
//! jellyfish shows a step of a cycle, every step of it is packed
//! (`shape::packed::pack_frame`, a few milliseconds once) and the template upload sends
//! them once, together; every far jellyfish then sends only its seed, noise time and
//! trails (`shape::packed::pack_instance`, 64 bytes), and reads its step's frame there.

use crate::plugin::interpolation::Snapshot;
use crate::plugin::slice::same;
use crate::shape::mesh::Resolution;
use crate::shape::packed::{self, ShapePacker};
use crate::sim::SliceView;
use crate::sim::cycle::CycleCache;
use crate::sim::guides::{THIN_NODES, Trail};
use crate::species::Species;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use std::sync::{Arc, RwLock, Weak};

/// Each recorded cycle's steps as packed frames, by cycle and resolution.
#[derive(Resource, Default)]
pub(crate) struct RecordedFrames {
    cycles: RwLock<HashMap<(usize, Resolution), Arc<PackedCycle>>>,
}

/// One cycle's steps packed for far jellyfish, for the species they were packed with.
pub(crate) struct PackedCycle {
    /// Keeps the cycle's allocation, so no other cycle takes its address (the key) while
    /// this entry lives; gone when no jellyfish plays it.
    cache: Weak<CycleCache>,
    species: Arc<Species>,
    res: Resolution,
    /// Every step's frame, one after another.
    pub(crate) frames: Vec<f32>,
    /// Where each step's frame starts in `frames`.
    starts: Vec<u32>,
}

impl RecordedFrames {
    /// The steps of `cache` packed for `species` at `res`: all of them the first time.
    /// `None` where a step cannot be packed (the jellyfish then packs its own block).
    pub(crate) fn cycle(
        &self,
        cache: &Arc<CycleCache>,
        species: &Arc<Species>,
        res: Resolution,
    ) -> Option<Arc<PackedCycle>> {
        let key = (Arc::as_ptr(cache) as usize, res);
        let current = |c: &Arc<PackedCycle>| same(&c.species, species);
        let known = self
            .cycles
            .read()
            .ok()?
            .get(&key)
            .filter(|c| current(c))
            .cloned();
        if known.is_some() {
            return known;
        }
        let mut cycles = self.cycles.write().ok()?;
        // Packed by another thread meanwhile, or a species edited without a new
        // recording (its looks): pack again.
        if let Some(cycle) = cycles.get(&key).filter(|c| current(c)) {
            return Some(cycle.clone());
        }
        let cycle = Arc::new(PackedCycle::pack(cache, species, res)?);
        cycles.insert(key, cycle.clone());
        Some(cycle)
    }

    /// Forgets the cycles no jellyfish plays any more: their recording gone, or held by
    /// nothing but this (no far jellyfish, nor the upload, draws from them).
    pub(crate) fn prune(&self) {
        if let Ok(mut cycles) = self.cycles.write() {
            cycles.retain(|_, c| c.cache.strong_count() > 0 && Arc::strong_count(c) > 1);
        }
    }
}

impl PackedCycle {
    fn pack(cache: &Arc<CycleCache>, species: &Arc<Species>, res: Resolution) -> Option<Self> {
        let mut packer = ShapePacker::default();
        let mut step = Snapshot::default();
        let mut frames = Vec::new();
        let mut starts = Vec::new();
        for index in 0..cache.steps_per_cycle() {
            step.copy_frame(cache, index, 0.0, 0.0);
            starts.push(frames.len() as u32);
            let view = step.view(cache.rest_bell());
            packed::pack_frame(&mut packer, &view, species, res, &mut frames).ok()?;
        }
        Some(Self {
            cache: Arc::downgrade(cache),
            species: species.clone(),
            res,
            frames,
            starts,
        })
    }

    /// Whether this is what [`RecordedFrames::cycle`] gives for `cache`, `species` and
    /// `res`: a far jellyfish that drew from it last frame takes it again without the
    /// lock and the reference count that every far jellyfish of the species shares (two
    /// threads contending for their cache line each frame, ten thousand times). Held, it
    /// is still the map's entry: `prune` drops only what no jellyfish holds.
    pub(crate) fn plays(
        &self,
        cache: &Arc<CycleCache>,
        species: &Arc<Species>,
        res: Resolution,
    ) -> bool {
        std::ptr::eq(self.cache.as_ptr(), Arc::as_ptr(cache))
            && self.res == res
            && same(&self.species, species)
    }

    /// Where step `index`'s frame starts in [`Self::frames`].
    pub(crate) fn start(&self, index: u32) -> Option<u32> {
        self.starts.get(index as usize).copied()
    }
}

/// The step a far jellyfish shows of the two around its frame's time, `t` of the way
/// between them: the nearer. A recorded step is shared, a blend of two is not; the frame
/// shows the step's shape at most half a step early or late.
pub(crate) fn shown_step<'a>(a: &'a Snapshot, b: &'a Snapshot, t: f32) -> &'a Snapshot {
    if t < 0.5 { a } else { b }
}

/// Where a drawn view's trails are written: the fringe's (thinned where a far jellyfish
/// shows a recorded step) and the oral tubes'.
#[derive(Debug, Default)]
pub(crate) struct DrawnTrails {
    fringe: Vec<Vec3>,
    oral: Vec<Vec3>,
}

/// What a jellyfish's frame is drawn from, on either path and for picking alike:
/// `shown`'s view with its trails rounded to halves as the templates carry them
/// (`packed::round_to_halves`), so that both paths draw the same surface. Where a far
/// jellyfish shows a recorded step, its fringe's trail is thinned (`Trail::thin_into`)
/// and its oral tubes hang untrailed, as its instance carries them (`pack_instance`).
pub(crate) fn drawn_view<'a>(
    shown: &'a Snapshot,
    far: bool,
    rest_bell: &'a [Vec2],
    res: &Resolution,
    trails: &'a mut DrawnTrails,
) -> SliceView<'a> {
    let mut view = shown.view(rest_bell);
    let DrawnTrails { fringe, oral } = trails;
    if far && shown.recorded.is_some() {
        let guides = packed::far_guides(res);
        // A far step keeps its trail thinned and rounded (`Snapshot::set_thin_trail`).
        if !(shown.thin_trail && view.trail.guides() == guides) {
            view.trail.thin_into(guides, fringe);
            packed::round_to_halves(fringe);
            view.trail = Trail {
                offsets: fringe,
                nodes: THIN_NODES,
            };
        }
        view.oral_trail = Trail::NONE;
        return view;
    }
    view.trail = rounded(view.trail, fringe);
    view.oral_trail = rounded(view.oral_trail, oral);
    view
}

/// `trail` rounded to halves, in `out`.
fn rounded<'a>(trail: Trail, out: &'a mut Vec<Vec3>) -> Trail<'a> {
    out.clear();
    out.extend_from_slice(trail.offsets);
    packed::round_to_halves(out);
    Trail {
        offsets: out,
        nodes: trail.nodes,
    }
}
