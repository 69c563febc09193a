//! [`CycleCache`]: one stroke cycle of a species' slice, recorded once and replayed by
//! phase. A jellyfish far from the camera shows the recorded shapes and swims the recorded
//! surge without any fluid; one coming nearer resumes a live slice from the stored state
//! for its phase, so nothing jumps.
//!
//! The slice is symmetric and its only inputs are the species and the stroke, so once the
//! bell has come up to speed (ten to thirty strokes from rest) every stroke is the same
//! one: the replay is the live slice's steady state, not an approximation of it.

use super::SliceSim;
use crate::species::{Species, SpeciesError};
use glam::Vec2;

/// Cycles run from rest before recording, at least: a bell accelerates over many strokes.
pub const MIN_WARM_UP_CYCLES: u32 = 8;
/// Cycles run from rest before recording, at most (a species that never settles).
pub const MAX_WARM_UP_CYCLES: u32 = 60;
/// Recording starts once two successive cycles swim within this fraction of each other.
pub const SETTLED: f32 = 0.002;
/// A full slice state is stored every this many steps; resuming between two costs at most
/// `STATE_STRIDE - 1` steps.
pub const STATE_STRIDE: u32 = 4;

/// One step of the recorded cycle: the shape after the step, relative to the bell's
/// centroid, and how far the step swam.
#[derive(Clone, Debug, Default)]
pub struct CycleFrame {
    /// The bell's points, metres, in the slice's frame.
    pub bell: Vec<Vec2>,
    /// The two tentacle chains.
    pub tentacles: [Vec<Vec2>; 2],
    /// The manubrium's and oral arms' two chains.
    pub oral_arms: [Vec<Vec2>; 2],
    /// The bell's centroid in the slice's domain, m.
    pub centroid: Vec2,
    /// Distance swum along the axis in this step, m.
    pub surge: f32,
    /// How far the shape reaches (`None`: no points), kept so that the thousands of far
    /// jellyfish showing this step do not measure it again each frame.
    pub reach: Option<Reach>,
}

/// How far a slice's shape reaches from its centroid: its widest point from the axis,
/// and its lowest and highest along it, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// The widest point's distance from the axis.
    pub radius: f32,
    /// The lowest point along the axis.
    pub low: f32,
    /// The highest point along the axis.
    pub high: f32,
}

impl Reach {
    /// The reach of `points` (relative to the centroid, x across the axis); `None` for
    /// none.
    pub fn of<'a>(points: impl IntoIterator<Item = &'a Vec2>) -> Option<Self> {
        let (mut radius, mut low, mut high) = (0.0f32, f32::MAX, f32::MIN);
        for p in points {
            radius = radius.max(p.x.abs());
            low = low.min(p.y);
            high = high.max(p.y);
        }
        (low <= high).then_some(Self { radius, low, high })
    }
}

/// A species' stroke cycle: a frame per fixed step, indexed by the step's place in the
/// cycle (`stroke_steps % steps_per_cycle` after it), and full slice states to resume from.
#[derive(Clone)]
pub struct CycleCache {
    species: Species,
    frames: Vec<CycleFrame>,
    /// States after the steps at indices `0, STATE_STRIDE, 2·STATE_STRIDE, …`.
    states: Vec<SliceSim>,
    rest_bell: Vec<Vec2>,
}

impl std::fmt::Debug for CycleCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CycleCache")
            .field("species", &self.species.name)
            .field("steps_per_cycle", &self.frames.len())
            .finish_non_exhaustive()
    }
}

impl CycleCache {
    /// Runs `species` from rest until its stroke has settled ([`SETTLED`]) and records the
    /// next cycle: the cost of 10 to 60 cycles of one live slice (0.1 to 1 s). At once;
    /// [`CycleRecorder`] takes the same steps a few at a time.
    pub fn record(species: &Species) -> Result<Self, SpeciesError> {
        let mut recorder = CycleRecorder::new(species)?;
        loop {
            if let Some(cache) = recorder.advance(u32::MAX) {
                return Ok(cache);
            }
        }
    }

    /// The species it was recorded for.
    pub fn species(&self) -> &Species {
        &self.species
    }

    /// Fixed steps the recording holds per stroke.
    pub fn steps_per_cycle(&self) -> u32 {
        self.frames.len() as u32
    }

    /// A slice's place in the cycle: the index of the frame that shows its state.
    pub fn index_of(sim: &SliceSim) -> u32 {
        let clock = sim.clock();
        (clock.stroke_steps() % clock.steps_per_cycle() as u64) as u32
    }

    /// The frame at `index` (wrapped into the cycle).
    pub fn frame(&self, index: u32) -> &CycleFrame {
        &self.frames[(index % self.steps_per_cycle()) as usize]
    }

    /// The bell at rest, as the live slice's view has it.
    pub fn rest_bell(&self) -> &[Vec2] {
        &self.rest_bell
    }

    /// Distance swum in one cycle, m.
    pub fn swim_per_cycle(&self) -> f32 {
        self.frames.iter().map(|f| f.surge).sum()
    }

    /// A live slice in the recorded state at `index`: the stored state at or before it,
    /// stepped on to it. Its clock is the recording's; the caller sets its own.
    pub fn resume(&self, index: u32) -> SliceSim {
        let index = index % self.steps_per_cycle();
        let mut sim = self.states[(index / STATE_STRIDE) as usize].clone();
        for _ in 0..index % STATE_STRIDE {
            sim.step_once();
        }
        sim
    }

    /// Heap bytes held, roughly: the stored states dominate.
    pub fn bytes(&self) -> usize {
        let frame = |f: &CycleFrame| {
            (f.bell.len()
                + f.tentacles
                    .iter()
                    .chain(&f.oral_arms)
                    .map(Vec::len)
                    .sum::<usize>())
                * 8
                + 64
        };
        self.frames.iter().map(frame).sum::<usize>()
            + self.states.iter().map(SliceSim::bytes).sum::<usize>()
    }
}

/// [`CycleCache::record`] a few steps at a time: a species recorded over many frames, a
/// bounded number of steps in each, instead of all at once. The same steps in the same
/// order, so the same cycle, bit for bit; and a count of steps, not a time, so it ends on
/// the same frame in every run.
pub struct CycleRecorder {
    species: Species,
    sim: SliceSim,
    per_cycle: u32,
    stage: Stage,
}

/// Where a recording is.
enum Stage {
    /// Running from rest: `step` steps into warm-up cycle `cycle` (from 1), which began at
    /// swim distance `start`; the cycle before swam `last`.
    WarmUp {
        cycle: u32,
        step: u32,
        start: f32,
        last: f32,
    },
    /// One contiguous pass, from the state at index 0 (whole cycles of warm-up end there)
    /// to the step that wraps back to it: every frame and state comes from the same
    /// cycle, so resuming at any index shows exactly the recorded frame. The wrapping step
    /// gives frame 0 its surge only.
    Recording {
        step: u32,
        frames: Vec<CycleFrame>,
        states: Vec<Option<SliceSim>>,
    },
    /// Handed over.
    Done,
}

impl CycleRecorder {
    /// A recording of `species` from rest; a species the slice refuses is an error.
    pub fn new(species: &Species) -> Result<Self, SpeciesError> {
        let sim = SliceSim::new(species)?;
        Ok(Self {
            species: species.clone(),
            per_cycle: sim.clock().steps_per_cycle(),
            stage: Stage::WarmUp {
                cycle: 1,
                step: 0,
                start: sim.swim_distance(),
                last: f32::NAN,
            },
            sim,
        })
    }

    /// The species being recorded.
    pub fn species(&self) -> &Species {
        &self.species
    }

    /// Takes at most `steps` more steps; the cycle once it is recorded (then `None`
    /// again).
    pub fn advance(&mut self, steps: u32) -> Option<CycleCache> {
        let (sim, per_cycle) = (&mut self.sim, self.per_cycle);
        let mut left = steps;
        loop {
            match &mut self.stage {
                Stage::WarmUp { step, .. } if *step < per_cycle => {
                    if left == 0 {
                        return None;
                    }
                    sim.step_once();
                    *step += 1;
                    left -= 1;
                }
                Stage::WarmUp {
                    cycle,
                    step,
                    start,
                    last,
                } => {
                    // A whole cycle of warm-up: settled, or another.
                    let swum = sim.swim_distance() - *start;
                    let settled = (swum - *last).abs() <= SETTLED * swum.abs().max(1e-9);
                    if (*cycle >= MIN_WARM_UP_CYCLES && settled) || *cycle == MAX_WARM_UP_CYCLES {
                        debug_assert_eq!(CycleCache::index_of(sim), 0);
                        let mut states = vec![None; per_cycle.div_ceil(STATE_STRIDE) as usize];
                        states[0] = Some(sim.clone());
                        self.stage = Stage::Recording {
                            step: 0,
                            frames: vec![CycleFrame::capture(sim, 0.0); per_cycle as usize],
                            states,
                        };
                    } else {
                        (*cycle, *step, *start, *last) = (*cycle + 1, 0, sim.swim_distance(), swum);
                    }
                }
                Stage::Recording {
                    step,
                    frames,
                    states,
                } if *step < per_cycle => {
                    if left == 0 {
                        return None;
                    }
                    let before = sim.swim_distance();
                    sim.step_once();
                    let (index, surge) = (CycleCache::index_of(sim), sim.swim_distance() - before);
                    if index == 0 {
                        frames[0].surge = surge;
                    } else {
                        frames[index as usize] = CycleFrame::capture(sim, surge);
                        if index % STATE_STRIDE == 0 {
                            states[(index / STATE_STRIDE) as usize] = Some(sim.clone());
                        }
                    }
                    *step += 1;
                    left -= 1;
                }
                Stage::Recording { .. } => {
                    let Stage::Recording { frames, states, .. } =
                        std::mem::replace(&mut self.stage, Stage::Done)
                    else {
                        unreachable!("matched above");
                    };
                    return Some(CycleCache {
                        species: self.species.clone(),
                        frames,
                        states: states.into_iter().flatten().collect(),
                        rest_bell: sim.view().rest_bell.to_vec(),
                    });
                }
                Stage::Done => return None,
            }
        }
    }
}

impl CycleFrame {
    /// The slice's shape now, relative to its bell's centroid.
    pub fn capture(sim: &SliceSim, surge: f32) -> Self {
        let view = sim.view();
        let centroid = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
        let relative = |points: &[Vec2]| points.iter().map(|p| *p - centroid).collect();
        let mut frame = Self {
            bell: relative(view.bell),
            tentacles: [relative(view.tentacles[0]), relative(view.tentacles[1])],
            oral_arms: [relative(view.oral_arms[0]), relative(view.oral_arms[1])],
            centroid,
            surge,
            reach: None,
        };
        let chains = frame.tentacles.iter().chain(&frame.oral_arms).flatten();
        frame.reach = Reach::of(frame.bell.iter().chain(chains));
        frame
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> Species {
        Species {
            grid_resolution: 40,
            ..Species::default()
        }
    }

    #[test]
    fn a_resumed_slice_continues_the_recorded_cycle() {
        let cache = CycleCache::record(&small()).unwrap();
        let n = cache.steps_per_cycle();
        for index in [0, 1, STATE_STRIDE + 2, n - 1] {
            let mut sim = cache.resume(index);
            assert_eq!(CycleCache::index_of(&sim), index % n);
            // Its shape is the recorded one, and the next step is the recorded next step.
            let now = CycleFrame::capture(&sim, 0.0);
            let recorded = cache.frame(index);
            for (a, b) in now.bell.iter().zip(&recorded.bell) {
                assert!(a.distance(*b) < 1e-6, "shape at {index}: {a} vs {b}");
            }
            let before = sim.swim_distance();
            sim.step_once();
            let surge = sim.swim_distance() - before;
            let expected = cache.frame(index + 1).surge;
            // Every frame and state comes from one pass through the cycle.
            assert!(
                (surge - expected).abs() <= 1e-6 * expected.abs().max(1e-6),
                "surge after {index}: {surge} vs {expected}"
            );
        }
    }

    #[test]
    fn the_recorded_cycle_swims_like_the_live_slice() {
        let species = small();
        let cache = CycleCache::record(&species).unwrap();
        // The live slice's next cycles, after the same warm-up.
        let mut sim = cache.resume(0);
        let start = sim.swim_distance();
        for _ in 0..3 * cache.steps_per_cycle() {
            sim.step_once();
        }
        let live = (sim.swim_distance() - start) / 3.0;
        let replay = cache.swim_per_cycle();
        assert!(replay > 0.0, "the cycle swims forwards: {replay}");
        assert!(
            (live - replay).abs() < 0.02 * replay,
            "live {live} m/cycle vs replay {replay}"
        );
    }

    #[test]
    fn recording_a_few_steps_at_a_time_is_the_same_cycle() {
        let species = small();
        let whole = CycleCache::record(&species).unwrap();
        let mut recorder = CycleRecorder::new(&species).unwrap();
        let mut calls = 0;
        let piecewise = loop {
            calls += 1;
            if let Some(cache) = recorder.advance(7) {
                break cache;
            }
        };
        assert!(recorder.advance(7).is_none(), "handed over once");
        // At least the warm-up and the recorded cycle, seven steps a call.
        let n = whole.steps_per_cycle();
        assert!(calls > (MIN_WARM_UP_CYCLES + 1) * n / 7, "{calls} calls");
        assert_eq!(piecewise.steps_per_cycle(), n);
        for index in 0..n {
            let (a, b) = (whole.frame(index), piecewise.frame(index));
            assert_eq!(a.surge.to_bits(), b.surge.to_bits(), "surge at {index}");
            assert!(
                a.bell
                    .iter()
                    .zip(&b.bell)
                    .all(|(p, q)| p.to_array().map(f32::to_bits) == q.to_array().map(f32::to_bits)),
                "bell at {index}"
            );
        }
        let (a, b) = (whole.resume(n - 1), piecewise.resume(n - 1));
        assert_eq!(a.swim_distance().to_bits(), b.swim_distance().to_bits());
    }

    #[test]
    fn a_bad_species_is_refused() {
        let bad = Species {
            diameter: -1.0,
            ..Species::default()
        };
        assert!(CycleCache::record(&bad).is_err());
    }
}
