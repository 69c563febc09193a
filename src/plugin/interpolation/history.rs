//! The steps a frame blends between, and the fade that hides a change of tier.

use super::snapshot::Snapshot;
use crate::plugin::swimming::Pose;
use crate::sim::SliceSim;
use crate::sim::clock::FixedClock;
use bevy::prelude::*;

/// The last few fixed steps of a jellyfish, oldest first: enough to bracket any time a
/// frame shows. Whoever steps the slice records each step and says which time the frame
/// shows ([`Self::show`]); the frame's systems only read.
#[derive(Component, Default)]
pub(crate) struct SliceHistory {
    /// The states in a ring of slots, each written in place by the step it records (so a
    /// step moves no snapshot and allocates nothing): the oldest at `first`, `len` of them.
    slots: Vec<Snapshot>,
    first: usize,
    len: usize,
    /// The slice time the frame shows, s (see `JellyfishSlice::display_time`).
    shown: f64,
    /// What the frame shows at `shown`, found when it was set, while the stepping had the
    /// states in cache (ten thousand far histories do not fit in one): the frame's
    /// systems then read only the states they draw. `None` once the states change.
    shown_at: Option<Shown>,
    /// A shape difference left by a change of tier, faded out over the next steps.
    carry: Option<Box<Carry>>,
}

/// The states around the shown time (`state` indices) and how far between them, and the
/// pose blended there.
#[derive(Clone, Copy)]
struct Shown {
    states: (usize, usize, f32),
    pose: Pose,
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
        // `ceil`, clamped to 0..=64, without the call into libm it is on the baseline
        // x86-64 target (every step of every jellyfish records).
        let steps = frame / clock.step();
        let whole = steps as usize;
        3 + whole
            .saturating_add(usize::from((whole as f64) < steps))
            .min(64)
    }

    /// Forgets the past: the slice's present state only (a new or rebuilt slice).
    pub fn restart(&mut self, sim: &SliceSim, pose: Pose) {
        self.begin(sim.clock(), pose, |s| s.capture(sim));
    }

    /// Forgets the past, fade included, and records one state (`fill` writes it).
    fn begin(&mut self, clock: &FixedClock, pose: Pose, fill: impl FnOnce(&mut Snapshot)) {
        (self.first, self.len) = (0, 0);
        self.carry = None;
        self.record(clock, 0.0, pose, fill);
    }

    /// The `k`th stored state, oldest first.
    fn state(&self, k: usize) -> &Snapshot {
        &self.slots[(self.first + k) % self.slots.len()]
    }

    /// Every stored state, oldest first.
    fn states_mut(&mut self) -> impl Iterator<Item = &mut Snapshot> {
        let (tail, head) = self.slots.split_at_mut(self.first);
        head.iter_mut().chain(tail).take(self.len)
    }

    /// The slot after the newest state, the oldest dropped to keep at most `capacity`
    /// states with it (a slot added where the ring is full).
    fn next_slot(&mut self, capacity: usize) -> usize {
        while self.len >= capacity.max(1) {
            self.first = (self.first + 1) % self.slots.len();
            self.len -= 1;
        }
        if self.len == self.slots.len() {
            // Full: a new slot between the newest and the oldest.
            self.slots.insert(self.first, Snapshot::default());
            if self.len > 0 {
                self.first += 1;
            }
        }
        (self.first + self.len) % self.slots.len()
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
        let slot = self.next_slot(Self::capacity(clock, frame));
        self.shown_at = None;
        let snapshot = &mut self.slots[slot];
        fill(snapshot);
        snapshot.pose = pose;
        if let Some(carry) = &mut self.carry {
            let weight = carry.left as f32 / carry.steps.max(1) as f32;
            snapshot.add(&carry.shape, weight);
            carry.left = carry.left.saturating_sub(1);
            if carry.left == 0 {
                self.carry = None;
            }
        }
        self.len += 1;
    }

    /// Asks the processor now for the slots the next `steps` records will write: ten
    /// thousand far jellyfish's histories do not fit in a cache, and a far step's own work
    /// before its record (its travel and its guides) is about as long as the wait for
    /// memory. Changes nothing else.
    pub fn prefetch(&self, steps: usize) {
        #[cfg(target_arch = "x86_64")]
        for k in 0..steps.min(self.slots.len()) {
            let slot = &self.slots[(self.first + self.len + k) % self.slots.len()];
            let at = std::ptr::from_ref(slot).cast::<i8>();
            // A step writes its slot's first two lines (`Snapshot`'s layout).
            for line in [at, at.wrapping_add(64)] {
                // SAFETY: a prefetch reads nothing into the program and cannot fault.
                unsafe {
                    std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(line)
                };
            }
        }
    }

    /// A change of tier: the new tier's present shape is `now`, at time `time`. The
    /// stored steps are moved to the new clock's time, and the difference between the
    /// newest stored shape and `now` fades out over `steps` steps, so nothing jumps.
    pub fn change_tier(&mut self, now: &Snapshot, time: f64, steps: u32) {
        let Some(newest) = self.newest() else {
            return;
        };
        let shift = time - newest.time;
        let mut shape = newest.clone();
        shape.add(now, -1.0);
        self.shown_at = None;
        for s in self.states_mut() {
            s.time += shift;
        }
        self.carry = Some(Box::new(Carry {
            shape,
            left: steps,
            steps,
        }));
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
        self.len.checked_sub(1).map(|k| self.state(k))
    }

    /// The two states around time `t` and how far between them it is, in [0, 1]; held at
    /// the ends if `t` is outside the history. Searched from the newest, where a frame's
    /// time lies: ten thousand far jellyfish's histories do not fit in a cache, and this
    /// reads no state the frame does not show.
    pub fn bracket(&self, t: f64) -> Option<(&Snapshot, &Snapshot, f32)> {
        let (a, b, f) = self.search(t)?;
        Some((self.state(a), self.state(b), f))
    }

    /// [`Self::bracket`] as the states' indices, oldest first.
    fn search(&self, t: f64) -> Option<(usize, usize, f32)> {
        let newest = self.len.checked_sub(1)?;
        if t > self.state(newest).time || t.is_nan() {
            return Some((newest, newest, 0.0));
        }
        // The first state at or after `t` (the times ascend), and the one before it.
        let mut i = newest;
        while i > 0 && self.state(i - 1).time >= t {
            i -= 1;
        }
        if i == 0 {
            return Some((0, 0, 0.0));
        }
        let (a, b) = (self.state(i - 1), self.state(i));
        let span = (b.time - a.time).max(1e-12);
        Some((i - 1, i, ((t - a.time) / span) as f32))
    }

    /// Sets the slice time the frame shows, s, and finds what it shows there.
    pub fn show(&mut self, time: f64) {
        self.shown = time;
        self.shown_at = self.search(time).map(|states| {
            let (a, b, f) = states;
            let pose = self.state(a).pose.blend(&self.state(b).pose, f);
            Shown { states, pose }
        });
    }

    /// The two states around the time the frame shows, and how far between them it is.
    pub fn shown(&self) -> Option<(&Snapshot, &Snapshot, f32)> {
        match self.shown_at {
            Some(Shown {
                states: (a, b, f), ..
            }) => Some((self.state(a), self.state(b), f)),
            None => self.bracket(self.shown),
        }
    }

    /// The pose the frame shows, blended between the steps around it.
    pub fn shown_pose(&self) -> Option<Pose> {
        match self.shown_at {
            Some(shown) => Some(shown.pose),
            None => self.shown().map(|(a, b, f)| a.pose.blend(&b.pose, f)),
        }
    }

    /// Moves every stored pose as `edit` moves `from` (a game moved or turned the
    /// jellyfish): what the frames show continues from where it was put.
    pub fn move_poses(&mut self, from: Pose, to: Pose) {
        self.shown_at = None;
        for s in self.states_mut() {
            s.pose = s.pose.moved(from, to);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A history of steps of 0.1 s recorded at times 0.1, 0.2, … (swim = time), for a
    /// frame of `frame` seconds.
    fn recorded(steps: u32, frame: f64) -> (SliceHistory, FixedClock) {
        let clock = FixedClock::new(1.0, 10);
        let mut history = SliceHistory::default();
        for k in 1..=steps {
            let time = f64::from(k) / 10.0;
            history.record(&clock, frame, Pose::default(), |s| {
                s.time = time;
                s.swim = time as f32;
            });
        }
        (history, clock)
    }

    fn times(history: &SliceHistory) -> Vec<f64> {
        (0..history.len).map(|k| history.state(k).time).collect()
    }

    /// The states kept for a frame are three and the frame's steps rounded up, at most 64
    /// of them: as `f64::ceil` clamped would count them, for frames of whole and partial
    /// steps, none, negative, huge and not a number.
    #[test]
    fn a_frame_keeps_its_steps_rounded_up() {
        let clock = FixedClock::new(1.0, 10);
        let step = clock.step();
        let mut frames: Vec<f64> = (0..800).map(|k| f64::from(k) * step / 8.0).collect();
        frames.extend([
            -0.3,
            0.0,
            -0.0,
            6.4,
            6.4000001,
            1e300,
            f64::INFINITY,
            f64::NAN,
        ]);
        frames.extend((1..70).map(|k| f64::from(k) * step));
        for frame in frames {
            let ceiled = 3 + (frame / step).ceil().clamp(0.0, 64.0) as usize;
            assert_eq!(SliceHistory::capacity(&clock, frame), ceiled, "{frame}");
        }
    }

    #[test]
    fn the_ring_keeps_the_newest_steps_in_order_and_brackets_between_them() {
        // Three steps kept (a frame of no length), after the ring has gone round twice.
        let (history, _) = recorded(8, 0.0);
        assert_eq!(times(&history), [0.6, 0.7, 0.8]);
        assert_eq!(history.slots.len(), 3, "a step allocates nothing once full");
        let (a, b, t) = history.bracket(0.75).unwrap();
        assert_eq!((a.time, b.time), (0.7, 0.8));
        assert!((t - 0.5).abs() < 1e-5, "{t}");
        // On a step, and at both ends (held there).
        let (a, b, t) = history.bracket(0.7).unwrap();
        assert_eq!((a.time, b.time, t), (0.6, 0.7, 1.0));
        let (a, b, _) = history.bracket(0.1).unwrap();
        assert_eq!((a.time, b.time), (0.6, 0.6));
        let (a, b, _) = history.bracket(2.0).unwrap();
        assert_eq!((a.time, b.time), (0.8, 0.8));
        assert_eq!(history.newest().map(|s| s.time), Some(0.8));
    }

    /// What `show` found (the states around the shown time and the pose blended there) is
    /// what a search finds, and a step recorded, a change of tier or a move after it is
    /// seen: the frame never shows old states.
    #[test]
    fn what_is_shown_is_found_from_the_states_as_they_are() {
        let at = |x: f32| Pose {
            position: Vec3::new(x, 0.0, 0.0),
            ..Pose::default()
        };
        let clock = FixedClock::new(1.0, 10);
        let mut history = SliceHistory::default();
        for k in 1..=8 {
            history.record(&clock, 0.2, at(k as f32), |s| s.time = f64::from(k) / 10.0);
        }
        let same = |h: &SliceHistory, t: f64| {
            let ((a, b, f), (c, d, g)) = (h.shown().unwrap(), h.bracket(t).unwrap());
            assert!(std::ptr::eq(a, c) && std::ptr::eq(b, d) && f == g, "at {t}");
            assert_eq!(h.shown_pose(), Some(c.pose.blend(&d.pose, g)), "at {t}");
        };
        for t in [0.0, 0.55, 0.6, 0.65, 0.8, 0.81, 2.0] {
            history.show(t);
            same(&history, t);
        }
        // Past the newest step, which a step recorded then replaces.
        history.show(0.95);
        history.record(&clock, 0.2, at(100.0), |s| s.time = 0.9);
        same(&history, 0.95);
        assert_eq!(history.shown_pose(), Some(at(100.0)));
        history.show(0.85);
        let before = history.shown_pose().unwrap();
        history.move_poses(at(0.0), at(10.0));
        same(&history, 0.85);
        let moved = history.shown_pose().unwrap();
        assert!((moved.position.x - before.position.x - 10.0).abs() < 1e-4);
        let mut now = Snapshot::default();
        now.time = 5.0;
        history.change_tier(&now, 5.0, 2);
        same(&history, 0.85);
        let oldest = history.shown().map(|(a, ..)| a.time).unwrap();
        assert!((oldest - 4.6).abs() < 1e-9, "{oldest}");
    }

    #[test]
    fn a_longer_frame_keeps_more_steps_and_a_shorter_one_fewer() {
        let (mut history, clock) = recorded(5, 0.0);
        // A frame of three steps keeps six: the ring grows between the newest and oldest.
        for k in 6..=12 {
            let time = f64::from(k) / 10.0;
            history.record(&clock, 0.3, Pose::default(), |s| s.time = time);
            let newest_first = times(&history);
            assert!(
                newest_first.windows(2).all(|w| w[0] < w[1]),
                "{newest_first:?}"
            );
        }
        assert_eq!(times(&history).len(), 6);
        assert_eq!(times(&history).last(), Some(&1.2));
        history.record(&clock, 0.0, Pose::default(), |s| s.time = 1.3);
        assert_eq!(times(&history), [1.1, 1.2, 1.3]);
    }

    #[test]
    fn a_change_of_tier_moves_every_step_to_the_new_clock_and_a_restart_forgets() {
        let (mut history, clock) = recorded(7, 0.0);
        let mut now = Snapshot::default();
        now.time = 5.0;
        history.change_tier(&now, 5.0, 2);
        assert!(history.fading());
        let shifted = times(&history);
        assert!((shifted[2] - 5.0).abs() < 1e-12 && (shifted[0] - 4.8).abs() < 1e-12);
        history.restart_at(&clock, &now, Pose::default());
        assert!(!history.fading());
        assert_eq!(times(&history), [5.0]);
    }
}
