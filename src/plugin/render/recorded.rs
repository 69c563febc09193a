//! The far tier's recorded cycles, packed once each.
//!
//! Every far jellyfish of a species plays the same recorded cycle, and a frame shows one
//! of its steps (the nearest, not a blend: [`shown_step`]). So the first time a far
//! jellyfish shows a step of a cycle, every step of it is packed
//! (`shape::packed::pack_frame`, a few milliseconds once, shared by every thread that
//! wants the cycle: [`Packing`]) and the template upload sends them once, together; every
//! far jellyfish then sends only its seed, noise time and trails
//! (`shape::packed::pack_instance`, 64 bytes), and reads its step's frame there.

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
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, OnceLock, RwLock, Weak};

/// Each recorded cycle's steps as packed frames, by cycle and resolution.
#[derive(Resource, Default)]
pub(crate) struct RecordedFrames {
    cycles: RwLock<HashMap<Key, Arc<PackedCycle>>>,
    /// The cycles being packed this frame.
    packing: Mutex<HashMap<Key, Arc<Packing>>>,
}

/// A cycle (its address) at a resolution.
type Key = (usize, Resolution);

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
        // Packed by every thread that asks for it meanwhile, a step at a time.
        let packing = {
            let mut packing = self.packing.lock().ok()?;
            let entry = packing
                .entry(key)
                .or_insert_with(|| Arc::new(Packing::new(cache, species, res)));
            if !same(&entry.species, species) {
                *entry = Arc::new(Packing::new(cache, species, res));
            }
            entry.clone()
        };
        packing.help();
        let mut cycles = self.cycles.write().ok()?;
        // Finished by another thread, or a species edited without a new recording (its
        // looks): its own entry.
        if let Some(cycle) = cycles.get(&key).filter(|c| current(c)) {
            return Some(cycle.clone());
        }
        let cycle = Arc::new(packing.finish()?);
        cycles.insert(key, cycle.clone());
        Some(cycle)
    }

    /// Forgets the cycles no jellyfish plays any more: their recording gone, or held by
    /// nothing but this (no far jellyfish, nor the upload, draws from them); and the
    /// last frame's packings, finished or failed (a failed one is tried again).
    pub(crate) fn prune(&self) {
        if let Ok(mut cycles) = self.cycles.write() {
            cycles.retain(|_, c| c.cache.strong_count() > 0 && Arc::strong_count(c) > 1);
        }
        if let Ok(mut packing) = self.packing.lock() {
            packing.clear();
        }
    }
}

/// A cycle being packed: its steps handed out one at a time to every thread that asks for
/// it, so that the frame a cycle is first shown in (a new recording's, or a species'
/// edited looks) packs it on every thread, instead of one packing it all while the
/// others wait for it. Each step is packed alone, the same bits as one after another.
struct Packing {
    cache: Arc<CycleCache>,
    species: Arc<Species>,
    res: Resolution,
    /// The next step to hand out, and how many are packed.
    next: AtomicU32,
    done: AtomicU32,
    /// Each step's frame; `None` where it could not be packed.
    steps: Vec<OnceLock<Option<Vec<f32>>>>,
}

impl Packing {
    fn new(cache: &Arc<CycleCache>, species: &Arc<Species>, res: Resolution) -> Self {
        let steps = (0..cache.steps_per_cycle()).map(|_| OnceLock::new());
        Self {
            cache: cache.clone(),
            species: species.clone(),
            res,
            next: AtomicU32::new(0),
            done: AtomicU32::new(0),
            steps: steps.collect(),
        }
    }

    /// Packs steps until none is left to take, then waits for those others took (each a
    /// few tens of microseconds).
    fn help(&self) {
        let count = self.steps.len() as u32;
        let (mut packer, mut step) = (ShapePacker::default(), Snapshot::default());
        loop {
            let index = self.next.fetch_add(1, Ordering::Relaxed);
            if index >= count {
                break;
            }
            step.copy_frame(&self.cache, index, 0.0, 0.0);
            let view = step.view(self.cache.rest_bell());
            let mut frame = Vec::new();
            let packed =
                packed::pack_frame(&mut packer, &view, &self.species, self.res, &mut frame);
            let _ = self.steps[index as usize].set(packed.ok().map(|()| frame));
            self.done.fetch_add(1, Ordering::Release);
        }
        while self.done.load(Ordering::Acquire) < count {
            std::thread::yield_now();
        }
    }

    /// The packed cycle, once every step is: `None` where a step could not be packed.
    fn finish(&self) -> Option<PackedCycle> {
        let (mut frames, mut starts) = (Vec::new(), Vec::with_capacity(self.steps.len()));
        for step in &self.steps {
            starts.push(frames.len() as u32);
            frames.extend_from_slice(step.get()?.as_ref()?);
        }
        Some(PackedCycle {
            cache: Arc::downgrade(&self.cache),
            species: self.species.clone(),
            res: self.res,
            frames,
            starts,
        })
    }
}

impl PackedCycle {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A cycle asked for by several threads at once is packed by all of them, and is the
    /// cycle packed step after step by one, bit for bit; asked for again, it is the same
    /// cycle, and for an edited species' looks it is packed again.
    #[test]
    fn a_cycle_packed_side_by_side_is_the_one_packed_in_turn() {
        let species = Arc::new(Species {
            grid_resolution: 40,
            ..Species::default()
        });
        let cache = Arc::new(CycleCache::record(&species).unwrap());
        let res = Resolution::scaled(&species, 1.0);
        let (mut packer, mut step, mut frames) =
            (ShapePacker::default(), Snapshot::default(), Vec::new());
        let mut starts = Vec::new();
        for index in 0..cache.steps_per_cycle() {
            step.copy_frame(&cache, index, 0.0, 0.0);
            starts.push(frames.len() as u32);
            let view = step.view(cache.rest_bell());
            packed::pack_frame(&mut packer, &view, &species, res, &mut frames).unwrap();
        }
        let recorded = RecordedFrames::default();
        let cycles: Vec<Arc<PackedCycle>> = std::thread::scope(|scope| {
            let asks: Vec<_> = (0..4)
                .map(|_| scope.spawn(|| recorded.cycle(&cache, &species, res).unwrap()))
                .collect();
            asks.into_iter().map(|a| a.join().unwrap()).collect()
        });
        for cycle in &cycles {
            assert!(Arc::ptr_eq(cycle, &cycles[0]), "one cycle for every thread");
            assert_eq!(cycle.starts, starts);
            assert_eq!(cycle.frames.len(), frames.len());
            let same_bits = cycle
                .frames
                .iter()
                .zip(&frames)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same_bits, "the frames packed in turn");
        }
        recorded.prune();
        let again = recorded.cycle(&cache, &species, res).unwrap();
        assert!(Arc::ptr_eq(&again, &cycles[0]), "kept while held");
        let looks = Arc::new(Species {
            tentacle_length: species.tentacle_length * 1.5,
            ..(*species).clone()
        });
        let edited = recorded.cycle(&cache, &looks, res).unwrap();
        assert!(
            !Arc::ptr_eq(&edited, &again),
            "packed again for other looks"
        );
        assert!(edited.plays(&cache, &looks, res) && !again.plays(&cache, &looks, res));
    }
}
