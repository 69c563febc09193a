//! Stepping the slices in `FixedUpdate`, in parallel over jellyfish.

use super::JellyfishSystems;
use super::components::JellyfishSlice;
use super::diagnostics::JellyfishTimings;
use super::settings::JellyfishSettings;
use bevy::prelude::*;
use std::time::Instant;

pub(super) fn plugin(app: &mut App) {
    app.add_systems(
        FixedUpdate,
        step_slices.in_set(JellyfishSystems::StepSlices),
    );
}

/// Each slice steps once every `ticks_per_step` fixed ticks (its own) by that much
/// time, so its simulated time is exactly the fixed clock's and the result does not depend
/// on the frame rate. Which tick a slice steps on depends on its seed, spreading the cost.
fn step_slices(
    mut jellyfish: Query<&mut JellyfishSlice>,
    time: Res<Time<Fixed>>,
    settings: Res<JellyfishSettings>,
    timings: Res<JellyfishTimings>,
) {
    let tick = time.timestep().as_secs_f32();
    jellyfish.par_iter_mut().for_each(|mut slice| {
        let slice = &mut *slice;
        let Some(sim) = slice.sim.as_mut() else {
            return;
        };
        slice.ticks += 1;
        if slice.ticks < slice.ticks_per_step {
            return;
        }
        let dt = tick * slice.ticks_per_step as f32;
        slice.ticks = 0;
        let start = Instant::now();
        sim.advance(dt);
        std::mem::swap(&mut slice.previous, &mut slice.current);
        slice.current.capture(sim);
        // Between steps, so that a new species or setting never splits one.
        slice.ticks_per_step = settings.ticks_per_step(time.timestep(), &slice.species);
        timings.add_simulation(start.elapsed());
    });
}
