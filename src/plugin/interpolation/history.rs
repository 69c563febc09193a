//! The steps a frame blends between, and the fade that hides a change of tier.

use super::snapshot::Snapshot;
use crate::plugin::swimming::Pose;
use crate::sim::SliceSim;
use crate::sim::clock::FixedClock;
use bevy::prelude::*;
use std::collections::VecDeque;

/// The last few fixed steps of a jellyfish, oldest first: enough to bracket any time a
/// frame shows. Whoever steps the slice records each step and says which time the frame
/// shows ([`Self::show`]); the frame's systems only read.
#[derive(Component, Default)]
pub(crate) struct SliceHistory {
    states: VecDeque<Snapshot>,
    /// Each state's time, in the same order: a frame's bracket reads these few numbers,
    /// not a cache line of every stored state (ten thousand far jellyfish's histories do
    /// not fit in a cache).
    times: VecDeque<f64>,
    /// The slice time the frame shows, s (see `JellyfishSlice::display_time`).
    shown: f64,
    /// Recycled snapshots, so a step allocates nothing.
    spare: Vec<Snapshot>,
    /// A shape difference left by a change of tier, faded out over the next steps.
    carry: Option<Carry>,
}

/// What the shape was minus what the new tier shows, at the change; added back to the
/// recorded shapes with a weight falling from 1 to 0 over `steps`.
#[derive(Default)]
struct Carry {
    shape: Snapshot,
    left: u32,
    steps: u32,
}

impl SliceHistory {
    /// Keeps this many states: the bracket for a lag of one step, when one frame can hold
    /// several steps.
    fn capacity(clock: &FixedClock, frame: f64) -> usize {
        3 + (frame / clock.step()).ceil().clamp(0.0, 64.0) as usize
    }

    /// Forgets the past: the slice's present state only (a new or rebuilt slice).
    pub fn restart(&mut self, sim: &SliceSim, pose: Pose) {
        self.begin(sim.clock(), pose, |s| s.capture(sim));
    }

    /// Forgets the past, fade included, and records one state (`fill` writes it).
    fn begin(&mut self, clock: &FixedClock, pose: Pose, fill: impl FnOnce(&mut Snapshot)) {
        self.spare.extend(self.states.drain(..));
        self.times.clear();
        self.carry = None;
        self.record(clock, 0.0, pose, fill);
    }

    /// Records the state after a step (`fill` writes the shape, time and swim distance)
    /// and the jellyfish's pose, dropping what a frame of `frame` seconds can no longer
    /// show.
    pub fn record(
        &mut self,
        clock: &FixedClock,
        frame: f64,
        pose: Pose,
        fill: impl FnOnce(&mut Snapshot),
    ) {
        let mut snapshot = self.spare.pop().unwrap_or_default();
        fill(&mut snapshot);
        snapshot.pose = pose;
        if let Some(carry) = &mut self.carry {
            let weight = carry.left as f32 / carry.steps.max(1) as f32;
            snapshot.add(&carry.shape, weight);
            carry.left = carry.left.saturating_sub(1);
            if carry.left == 0 {
                self.carry = None;
            }
        }
        self.times.push_back(snapshot.time);
        self.states.push_back(snapshot);
        while self.states.len() > Self::capacity(clock, frame) {
            if let Some(old) = self.states.pop_front() {
                self.times.pop_front();
                self.spare.push(old);
            }
        }
    }

    /// A change of tier: the new tier's present shape is `now`, at time `time`. The
    /// stored steps are moved to the new clock's time, and the difference between the
    /// newest stored shape and `now` fades out over `steps` steps, so nothing jumps.
    pub fn change_tier(&mut self, now: &Snapshot, time: f64, steps: u32) {
        let Some(newest) = self.states.back() else {
            return;
        };
        let shift = time - newest.time;
        let mut shape = newest.clone();
        shape.add(now, -1.0);
        for (s, time) in self.states.iter_mut().zip(&mut self.times) {
            s.time += shift;
            *time = s.time;
        }
        self.carry = Some(Carry {
            shape,
            left: steps,
            steps,
        });
    }

    /// Starts over at `now`, the new tier's present shape, at `pose`, with nothing to
    /// fade: a jellyfish that changes tier before any frame has shown it.
    pub fn restart_at(&mut self, clock: &FixedClock, now: &Snapshot, pose: Pose) {
        self.begin(clock, pose, |s| s.clone_from(now));
    }

    /// Whether the next steps fade from the last tier's shape (`change_tier`): they become
    /// shapes of their own, not their recorded steps.
    pub fn fading(&self) -> bool {
        self.carry.is_some()
    }

    /// The newest recorded step: none before the jellyfish starts.
    pub fn newest(&self) -> Option<&Snapshot> {
        self.states.back()
    }

    /// The two states around time `t` and how far between them it is, in [0, 1]; held at
    /// the ends if `t` is outside the history.
    pub fn bracket(&self, t: f64) -> Option<(&Snapshot, &Snapshot, f32)> {
        if t <= *self.times.front()? {
            let s = self.states.front()?;
            return Some((s, s, 0.0));
        }
        // The first state at or after `t`, and the one before it.
        match self.times.iter().position(|&time| t <= time) {
            Some(i) => {
                let (a, b) = (self.times[i - 1], self.times[i]);
                let span = (b - a).max(1e-12);
                Some((
                    &self.states[i - 1],
                    &self.states[i],
                    ((t - a) / span) as f32,
                ))
            }
            None => {
                let s = self.states.back()?;
                Some((s, s, 0.0))
            }
        }
    }

    /// Sets the slice time the frame shows, s.
    pub fn show(&mut self, time: f64) {
        self.shown = time;
    }

    /// The two states around the time the frame shows, and how far between them it is.
    pub fn shown(&self) -> Option<(&Snapshot, &Snapshot, f32)> {
        self.bracket(self.shown)
    }

    /// The pose the frame shows, blended between the steps around it.
    pub fn shown_pose(&self) -> Option<Pose> {
        self.shown().map(|(a, b, f)| a.pose.blend(&b.pose, f))
    }

    /// Moves every stored pose as `edit` moves `from` (a game moved or turned the
    /// jellyfish): what the frames show continues from where it was put.
    pub fn move_poses(&mut self, from: Pose, to: Pose) {
        for s in &mut self.states {
            s.pose = s.pose.moved(from, to);
        }
    }
}
