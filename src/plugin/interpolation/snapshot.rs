//! One slice step as the frames see it: shapes relative to the bell's centroid, the
//! distance swum, the time and the jellyfish's pose.

use crate::plugin::swimming::Pose;
use crate::sim::cycle::CycleCache;
use crate::sim::guides::Trail;
use crate::sim::{SliceSim, SliceView};
use bevy::math::{Vec2, Vec3};
use std::sync::Arc;

/// One step's slice, relative to the bell's centroid so that the box following the bell
/// never shows.
#[derive(Clone, Debug, Default)]
pub(crate) struct Snapshot {
    pub bell: Vec<Vec2>,
    pub tentacles: [Vec<Vec2>; 2],
    pub oral_arms: [Vec<Vec2>; 2],
    /// The fringe's guide offsets after the step (`TentacleGuides`), body frame.
    pub trail: Vec<Vec3>,
    /// The oral tubes' guide offsets after the step, body frame.
    pub oral_trail: Vec<Vec3>,
    pub centroid: Vec2,
    pub swim: f32,
    /// Slice time of the state, s.
    pub time: f64,
    /// The jellyfish's pose in the world after the step.
    pub pose: Pose,
    /// The recorded cycle and the step of it this shape is, exactly (a far jellyfish's,
    /// not faded into another shape): far jellyfish showing it share its packed shape.
    pub recorded: Option<(Arc<CycleCache>, u32)>,
}

impl Snapshot {
    pub fn capture(&mut self, sim: &SliceSim) {
        let view = sim.view();
        let c = view.bell.iter().sum::<Vec2>() / view.bell.len() as f32;
        self.centroid = c;
        self.bell.clear();
        self.bell.extend(view.bell.iter().map(|p| *p - c));
        let chains = view.tentacles.into_iter().chain(view.oral_arms);
        for (out, chain) in self
            .tentacles
            .iter_mut()
            .chain(&mut self.oral_arms)
            .zip(chains)
        {
            out.clear();
            out.extend(chain.iter().map(|p| *p - c));
        }
        self.swim = sim.swim_distance();
        self.time = sim.clock().time();
        self.recorded = None;
    }

    /// `self = a + t·(b − a)`, point by point; `b` alone where the shapes differ.
    pub fn blend(&mut self, a: &Snapshot, b: &Snapshot, t: f32) {
        let lerp = |out: &mut Vec<Vec2>, a: &[Vec2], b: &[Vec2]| {
            out.clear();
            if a.len() == b.len() {
                out.extend(a.iter().zip(b).map(|(a, b)| a.lerp(*b, t)));
            } else {
                out.extend_from_slice(b);
            }
        };
        lerp(&mut self.bell, &a.bell, &b.bell);
        let lerp3 = |out: &mut Vec<Vec3>, a: &[Vec3], b: &[Vec3]| {
            out.clear();
            // (A far jellyfish's trail changes every few steps only.)
            if a.len() == b.len() && a != b {
                out.extend(a.iter().zip(b).map(|(a, b)| a.lerp(*b, t)));
            } else {
                out.extend_from_slice(b);
            }
        };
        lerp3(&mut self.trail, &a.trail, &b.trail);
        lerp3(&mut self.oral_trail, &a.oral_trail, &b.oral_trail);
        for side in 0..2 {
            lerp(
                &mut self.tentacles[side],
                &a.tentacles[side],
                &b.tentacles[side],
            );
            lerp(
                &mut self.oral_arms[side],
                &a.oral_arms[side],
                &b.oral_arms[side],
            );
        }
        self.centroid = Vec2::ZERO;
        self.recorded = None;
        self.swim = a.swim + t * (b.swim - a.swim);
        self.time = a.time + t as f64 * (b.time - a.time);
        self.pose = a.pose.blend(&b.pose, t);
    }

    /// `self = step`, as [`Self::blend`] of `step` with itself would give it, without the
    /// arithmetic (a far jellyfish shows a recorded step as it is).
    pub fn copy_step(&mut self, step: &Snapshot) {
        self.bell.clone_from(&step.bell);
        self.trail.clone_from(&step.trail);
        self.oral_trail.clone_from(&step.oral_trail);
        for side in 0..2 {
            self.tentacles[side].clone_from(&step.tentacles[side]);
            self.oral_arms[side].clone_from(&step.oral_arms[side]);
        }
        self.centroid = Vec2::ZERO;
        self.recorded = None;
        self.swim = step.swim;
        self.time = step.time;
        self.pose = step.pose;
    }

    /// Step `index` of the recorded `cycle`, at slice time `time` and swim distance
    /// `swim`.
    pub fn copy_frame(&mut self, cycle: &Arc<CycleCache>, index: u32, time: f64, swim: f32) {
        let frame = cycle.frame(index);
        self.recorded = Some((cycle.clone(), index));
        self.bell.clone_from(&frame.bell);
        let chains = frame.tentacles.iter().chain(&frame.oral_arms);
        for (out, chain) in self
            .tentacles
            .iter_mut()
            .chain(&mut self.oral_arms)
            .zip(chains)
        {
            out.clone_from(chain);
        }
        self.centroid = frame.centroid;
        self.swim = swim;
        self.time = time;
    }

    /// The fringe's and the oral tubes' guide offsets after the step.
    pub fn set_trail(&mut self, fringe: &[Vec3], oral: &[Vec3]) {
        self.trail.clear();
        self.trail.extend_from_slice(fringe);
        self.oral_trail.clear();
        self.oral_trail.extend_from_slice(oral);
    }

    /// `self += weight · other`, point by point, where the shapes match.
    pub fn add(&mut self, other: &Snapshot, weight: f32) {
        if weight != 0.0 {
            self.recorded = None;
        }
        let add = |a: &mut Vec<Vec2>, b: &[Vec2]| {
            if a.len() == b.len() {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += weight * *b);
            }
        };
        add(&mut self.bell, &other.bell);
        for side in 0..2 {
            add(&mut self.tentacles[side], &other.tentacles[side]);
            add(&mut self.oral_arms[side], &other.oral_arms[side]);
        }
    }

    pub fn view<'a>(&'a self, rest_bell: &'a [Vec2]) -> SliceView<'a> {
        SliceView {
            bell: &self.bell,
            rest_bell,
            tentacles: [&self.tentacles[0], &self.tentacles[1]],
            oral_arms: [&self.oral_arms[0], &self.oral_arms[1]],
            trail: Trail {
                offsets: &self.trail,
            },
            oral_trail: Trail {
                offsets: &self.oral_trail,
            },
        }
    }
}
