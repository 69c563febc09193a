//! The slice's fixed-step clock: the caller's `dt` only says how much time to add; the
//! slice moves in steps of its own length, so the physics never sees the frame rate.
//!
//! Time is counted in whole steps from zero, and the step is a whole fraction of the
//! contraction period, so every cycle samples the muscle drive at the same phases. The
//! time added is summed in `f64`: splits that are exact in binary (1/64 s × 512, or
//! 1/128 + 3/128 + 1/16 s …) sum exactly, take the same steps and give bit-identical states.

/// Counts added time and the fixed steps it pays for.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedClock {
    /// Step length, s.
    step: f64,
    /// Steps per contraction cycle (the step is `period / steps_per_cycle`).
    steps_per_cycle: u32,
    /// Time added so far, s (from zero, including the start offset).
    added: f64,
    /// Steps taken since time zero (the start offset counts as steps already taken).
    taken: u64,
    /// Of those, steps taken with the stroke held (resting): the muscle drive's phase
    /// counts only the others, so a rest resumes the stroke where it stopped.
    held: u64,
    /// Stroke steps counted beyond the steps taken: a hurried rhythm (an escape) moves the
    /// muscle drive's phase on faster than time.
    hurried: u64,
}

/// The most steps one `advance` may take; time beyond it is dropped, so a huge `dt` (a
/// debugger pause, a hitch) costs at most this many steps instead of hanging the caller.
pub const MAX_STEPS_PER_ADVANCE: u64 = 1024;

impl FixedClock {
    /// A clock at time zero for a drive of `period` seconds split into `steps_per_cycle`.
    pub fn new(period: f32, steps_per_cycle: u32) -> Self {
        let steps_per_cycle = steps_per_cycle.max(1);
        Self {
            step: period as f64 / steps_per_cycle as f64,
            steps_per_cycle,
            added: 0.0,
            taken: 0,
            held: 0,
            hurried: 0,
        }
    }

    /// Step length, s.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// Fixed steps per stroke cycle.
    pub fn steps_per_cycle(&self) -> u32 {
        self.steps_per_cycle
    }

    /// Simulated time of the state: the last step's end, s.
    pub fn time(&self) -> f64 {
        self.taken as f64 * self.step
    }

    /// Time added so far, s: at least [`Self::time`], less than a step ahead of it.
    pub fn added(&self) -> f64 {
        self.added
    }

    /// How far the added time is past the state, as a fraction of a step in `[0, 1)`.
    pub fn overstep_fraction(&self) -> f32 {
        (((self.added - self.time()) / self.step) as f32).clamp(0.0, 1.0)
    }

    /// Steps taken since time zero.
    pub fn steps(&self) -> u64 {
        self.taken
    }

    /// Steps the muscle drive has counted: all but the held ones, and the hurried ones.
    pub fn stroke_steps(&self) -> u64 {
        self.taken - self.held + self.hurried
    }

    /// Phase of the contraction cycle at the state, in `[0, 1)`: exact, in whole steps.
    pub fn phase(&self) -> f32 {
        (self.stroke_steps() % self.steps_per_cycle as u64) as f32 / self.steps_per_cycle as f32
    }

    /// Completed contraction cycles.
    pub fn cycle(&self) -> u64 {
        self.stroke_steps() / self.steps_per_cycle as u64
    }

    /// Starts the clock at `time` s: the state begins at the last step boundary at or
    /// before it, and the remainder is already added, so clocks started at different
    /// times step on different frames.
    pub fn start_at(&mut self, time: f64) {
        if time.is_finite() && time >= 0.0 {
            self.taken = steps_in(time, self.step) as u64;
            self.added = time;
        }
    }

    /// The same cycle, phase and overstep with a new period and step (a species edit):
    /// the muscle drive carries on where it was instead of jumping.
    pub fn retimed(&self, period: f32, steps_per_cycle: u32) -> Self {
        let mut c = Self::new(period, steps_per_cycle);
        if c.step == self.step && c.steps_per_cycle == self.steps_per_cycle {
            return self.clone();
        }
        let phase = self.phase() as f64;
        let n = c.steps_per_cycle as f64;
        // Held (resting) time carries over as held time of the new step.
        c.held = (self.held as f64 * self.step / c.step).round() as u64;
        // So are hurried steps (as hurried ones of the new step).
        c.hurried = (self.hurried as f64 * self.step / c.step).round() as u64;
        let stroke = self.cycle() * c.steps_per_cycle as u64 + (phase * n).round() as u64;
        c.hurried = c.hurried.min(stroke);
        c.taken = c.held + stroke - c.hurried;
        c.added = c.time() + self.overstep_fraction() as f64 * c.step;
        c
    }

    /// Adds `dt` seconds; returns how many steps are now due (at most
    /// [`MAX_STEPS_PER_ADVANCE`]). A `dt` that is not finite or not positive adds nothing.
    pub fn add(&mut self, dt: f64) -> u64 {
        if !dt.is_finite() || dt <= 0.0 {
            return 0;
        }
        self.added += dt;
        let due = self.steps_due();
        if due > MAX_STEPS_PER_ADVANCE {
            self.added = (self.taken + MAX_STEPS_PER_ADVANCE) as f64 * self.step;
            return MAX_STEPS_PER_ADVANCE;
        }
        due
    }

    /// Sets the time added so far to `added` s (if later than now): a caller that keeps
    /// its own total (an exact count of nanoseconds) adds no rounding of its own, so any
    /// split of the same total ends at the same time. Returns the steps now due, as
    /// [`Self::add`].
    pub fn add_until(&mut self, added: f64) -> u64 {
        if !added.is_finite() || added <= self.added {
            return 0;
        }
        self.added = added;
        let due = self.steps_due();
        if due > MAX_STEPS_PER_ADVANCE {
            self.added = (self.taken + MAX_STEPS_PER_ADVANCE) as f64 * self.step;
            return MAX_STEPS_PER_ADVANCE;
        }
        due
    }

    /// Steps the added time pays for that are not taken yet.
    pub fn steps_due(&self) -> u64 {
        self.steps_due_at(self.added)
    }

    /// Steps `added` s of added time would pay for that are not taken yet: what a later
    /// [`Self::add_until`] will take (before its cap), without taking them.
    pub fn steps_due_at(&self, added: f64) -> u64 {
        let target = steps_in(added, self.step);
        if target.is_finite() && target > self.taken as f64 {
            target as u64 - self.taken
        } else {
            0
        }
    }

    /// Marks one step as taken.
    pub fn tick(&mut self) {
        self.taken += 1;
    }

    /// Marks one step as taken with the stroke held: time passes, the phase does not.
    pub fn tick_held(&mut self) {
        self.taken += 1;
        self.held += 1;
    }

    /// Counts one stroke step more without time passing: the phase moves on a step.
    pub fn hurry(&mut self) {
        self.hurried += 1;
    }
}

/// Whole steps of `step` in `time`. A time a rounding error short of a whole number of
/// steps counts as reaching it: 0.25 s + 0.05 s is 3 steps of 0.1 s, not 2.
fn steps_in(time: f64, step: f64) -> f64 {
    (time / step + 1e-9).floor()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_splits_take_the_same_steps() {
        let splits: [&[f64]; 3] = [
            &[1.0 / 32.0; 256],
            &[1.0 / 64.0; 512],
            &[1.0 / 128.0, 3.0 / 128.0, 1.0 / 16.0, 1.0 / 32.0],
        ];
        let taken = |parts: &[f64], repeat: usize| {
            let mut c = FixedClock::new(1.0 / 0.7, 40);
            let mut total = 0;
            for _ in 0..repeat {
                for &dt in parts {
                    total += c.add(dt);
                    (0..c.steps_due()).for_each(|_| c.tick());
                }
            }
            (total, c.steps(), c.added())
        };
        let a = taken(splits[0], 1);
        assert_eq!(a, taken(splits[1], 1));
        assert_eq!(a, taken(splits[2], 64));
        // 8 s of 40 steps per 1/0.7 s cycle: 224, less one if the f32 period rounds up.
        assert!((223..=224).contains(&a.1), "{}", a.1);
    }

    #[test]
    fn phase_is_exact_in_whole_steps() {
        let mut c = FixedClock::new(2.0, 40);
        for k in 0..200u64 {
            assert_eq!(c.phase(), (k % 40) as f32 / 40.0);
            assert_eq!(c.cycle(), k / 40);
            c.tick();
        }
    }

    #[test]
    fn a_start_offset_shifts_which_frames_step() {
        let mut a = FixedClock::new(1.0, 10);
        let mut b = FixedClock::new(1.0, 10);
        b.start_at(0.25);
        assert_eq!(b.steps(), 2);
        assert!((b.overstep_fraction() - 0.5).abs() < 1e-6);
        assert_eq!(a.add(0.05), 0);
        assert_eq!(b.add(0.05), 1);
    }

    #[test]
    fn meaningless_or_huge_time_is_bounded() {
        let mut c = FixedClock::new(1.0, 10);
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(c.add(dt), 0);
        }
        assert_eq!(c.add(1e12), MAX_STEPS_PER_ADVANCE);
        (0..MAX_STEPS_PER_ADVANCE).for_each(|_| c.tick());
        assert_eq!(c.steps_due(), 0);
        assert_eq!(c.add(0.05), 0);
    }
}
