//! Stepping the slices in `FixedUpdate`, in parallel over jellyfish.

use super::JellyfishSystems;
use super::components::JellyfishSlice;
use super::diagnostics::JellyfishTimings;
use bevy::prelude::*;
use std::time::Instant;

pub(super) fn plugin(app: &mut App) {
    app.add_systems(
        FixedUpdate,
        step_slices.in_set(JellyfishSystems::StepSlices),
    );
}

/// Each tick adds its time to every slice's clock; a slice takes the fixed steps of its
/// own length that pays for and records each state for the frames to blend between. The
/// physics sees only the slice's step, never the frame rate or the tick; slices started at
/// different phases step on different ticks, which spreads the cost.
fn step_slices(
    mut jellyfish: Query<&mut JellyfishSlice>,
    time: Res<Time<Fixed>>,
    timings: Res<JellyfishTimings>,
) {
    let tick = time.delta_secs_f64();
    jellyfish.par_iter_mut().for_each(|mut slice| {
        let slice = &mut *slice;
        let Some(sim) = slice.sim.as_mut() else {
            return;
        };
        let start = Instant::now();
        let history = &mut slice.history;
        sim.advance_with(tick as f32, |sim| history.record(sim, tick));
        timings.add_simulation(start.elapsed());
    });
}
