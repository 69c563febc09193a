//! The co-moving frame: the fluid box follows the bell continuously along the channel.
//!
//! The box moves at the bell's low-pass-filtered swim speed plus a gentle pull back to the
//! bell's home position, so the bell stays where the box has room for its wake and the
//! water streams past it as it would past a swimmer. Changing the frame's speed is a
//! Galilean change of frame ([`Fluid::change_frame`](crate::sim::fluid::Fluid::change_frame)):
//! the world's water is untouched, unlike whole-cell recentring, which jolted the flow each
//! time the bell crossed a cell.

/// How the frame follows the bell; both times are in contraction periods.
#[derive(Clone, Debug)]
pub(super) struct ComovingFrame {
    /// World position of the box along the channel (y), m.
    pub(super) position: f64,
    /// Velocity of the box along the channel, m/s.
    pub(super) velocity: f32,
    /// Low-passed world velocity of the bell, m/s.
    filtered: f32,
    /// Filter time constant, s.
    smoothing: f32,
    /// Time over which an offset from home is taken back, s.
    return_time: f32,
}

/// The filter's time constant, in contraction periods: long enough that the frame's speed
/// hardly ripples within a stroke (the bell surges and recoils every cycle).
const SMOOTHING_PERIODS: f32 = 1.0;
/// How quickly the frame takes back the bell's drift from home, in periods.
const RETURN_PERIODS: f32 = 2.0;

impl ComovingFrame {
    /// A frame at rest, following a bell with stroke period `period` seconds.
    pub(super) fn new(period: f32) -> Self {
        Self {
            position: 0.0,
            velocity: 0.0,
            filtered: 0.0,
            smoothing: SMOOTHING_PERIODS * period,
            return_time: RETURN_PERIODS * period,
        }
    }

    /// Moves the box through a step of `dt` seconds in which the bell's centroid moved by
    /// `moved` m along the channel within the box, ending `from_home` m ahead of its home.
    /// Returns the change of the frame's velocity for the next step.
    pub(super) fn follow(&mut self, dt: f32, moved: f32, from_home: f32) -> f32 {
        self.position += (self.velocity * dt) as f64;
        let bell = self.velocity + moved / dt;
        self.filtered += (dt / self.smoothing).min(1.0) * (bell - self.filtered);
        let next = self.filtered + from_home / self.return_time;
        let change = next - self.velocity;
        self.velocity = next;
        change
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bell swimming at a steady `speed` in the world, seen from the frame.
    fn chase(speed: f32, steps: usize) -> (ComovingFrame, f32) {
        let (dt, mut frame, mut offset) = (0.02, ComovingFrame::new(1.0), 0.0f32);
        for _ in 0..steps {
            let moved = (speed - frame.velocity) * dt;
            offset += moved;
            frame.follow(dt, moved, offset);
        }
        (frame, offset)
    }

    #[test]
    fn the_frame_catches_up_with_a_steady_swimmer() {
        let (frame, offset) = chase(0.01, 2000);
        assert!((frame.velocity - 0.01).abs() < 1e-5, "{}", frame.velocity);
        assert!(offset.abs() < 1e-4, "the bell returns home: {offset}");
        // The box moved as far as the bell did, less the offset.
        assert!((frame.position as f32 - 0.01 * 40.0).abs() < 2e-3);
    }
}
