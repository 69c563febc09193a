//! The slice of a [`ShowSlice`] jellyfish, drawn in its plane through the bell: the
//! water's velocity, particles the water carries and the body's springs by tension.

use super::{JellyfishGizmos, ShowSlice};
use crate::plugin::slice::JellyfishSlice;
use crate::sim::SliceSim;
use bevy::prelude::*;

/// Trace particles per jellyfish.
const PARTICLES: usize = 400;
/// Arrows across the slice's box, per side.
const LATTICE: usize = 24;

/// Particles carried by a [`ShowSlice`] jellyfish's water, in the slice's world
/// coordinates (its box plus the box's offset), m; reseeded near the bell as they leave.
#[derive(Component, Clone, Debug, Default)]
pub struct TraceParticles {
    particles: Vec<Vec2>,
    seed: u32,
}

impl TraceParticles {
    /// A uniform number in [0, 1) from a linear congruential sequence: the same overlay
    /// every run.
    fn next(&mut self) -> f32 {
        self.seed = self
            .seed
            .wrapping_mul(1_664_525)
            .wrapping_add(1_013_904_223);
        (self.seed >> 8) as f32 / (1 << 24) as f32
    }
}

/// Draws the slices of every jellyfish marked [`ShowSlice`].
pub(super) fn draw_slices(
    mut gizmos: Gizmos<JellyfishGizmos>,
    time: Res<Time>,
    mut jellyfish: Query<(&JellyfishSlice, &GlobalTransform, &mut TraceParticles), With<ShowSlice>>,
) {
    let config = gizmos.config_ext.clone();
    for (slice, global, mut particles) in &mut jellyfish {
        let Some(sim) = slice.sim() else {
            continue;
        };
        let world = |p: Vec2| global.transform_point(slice.to_local(p));
        if config.flow {
            draw_flow(&mut gizmos, sim, &world);
        }
        if config.particles {
            draw_particles(&mut gizmos, &mut particles, sim, time.delta_secs(), &world);
        }
        if config.springs {
            draw_springs(&mut gizmos, sim, &world);
        }
    }
}

/// Velocity arrows on a coarse lattice over the box, the fastest one lattice step long.
fn draw_flow(gizmos: &mut Gizmos<JellyfishGizmos>, sim: &SliceSim, world: &impl Fn(Vec2) -> Vec3) {
    let fluid = sim.fluid();
    let every = (fluid.n / LATTICE).max(1);
    let lattice = || {
        (every / 2..fluid.n).step_by(every).flat_map(move |j| {
            (every / 2..fluid.n)
                .step_by(every)
                .map(move |i| (Vec2::new(i as f32, j as f32) + 0.5) * fluid.h)
        })
    };
    let fastest = lattice()
        .map(|p| fluid.velocity_at(p).length())
        .filter(|v| v.is_finite())
        .fold(1e-6f32, f32::max);
    let scale = every as f32 * fluid.h / fastest;
    for p in lattice() {
        let v = fluid.velocity_at(p) * scale;
        if v.is_finite() && v.length() > 0.05 * fluid.h {
            gizmos.arrow(world(p), world(p + v), Color::srgba(0.5, 0.9, 1.0, 0.7));
        }
    }
}

/// Passive particles carried by the water, reseeded around the bell where they leave it.
fn draw_particles(
    gizmos: &mut Gizmos<JellyfishGizmos>,
    trace: &mut TraceParticles,
    sim: &SliceSim,
    dt: f32,
    world: &impl Fn(Vec2) -> Vec3,
) {
    let fluid = sim.fluid();
    let (size, offset) = (fluid.size(), sim.offset());
    let centre = sim.bell_centroid_world();
    let spread = 1.5 * sim.species().diameter;
    while trace.particles.len() < PARTICLES {
        let (a, b) = (trace.next(), trace.next());
        let p = centre + (Vec2::new(a, b) * 2.0 - 1.0) * spread;
        trace.particles.push(p);
    }
    trace.particles.retain_mut(|p| {
        let d = *p - offset;
        if !(0.0..size).contains(&d.x) || !(0.0..size).contains(&d.y) {
            return false;
        }
        *p += fluid.tracer_velocity(d) * dt;
        p.is_finite() && (*p - centre).length() < 4.0 * spread
    });
    for p in &trace.particles {
        let at = world(*p - offset);
        gizmos.line(at, at + Vec3::Y * 0.01, Color::srgb(1.0, 0.9, 0.4));
    }
}

/// Every spring of the body, coloured by its tension relative to the largest (on a
/// compressed scale: the muscles are far stiffer than the mesoglea).
fn draw_springs(
    gizmos: &mut Gizmos<JellyfishGizmos>,
    sim: &SliceSim,
    world: &impl Fn(Vec2) -> Vec3,
) {
    let body = sim.body();
    let max = body
        .tensions()
        .map(|(_, _, t)| t.abs())
        .filter(|t| t.is_finite())
        .fold(1e-9f32, f32::max);
    for (a, b, t) in body.tensions() {
        let s = (t / max).clamp(-1.0, 1.0);
        let s = s.signum() * s.abs().powf(0.3);
        let color = if s >= 0.0 {
            Color::srgb(1.0, 1.0 - s, 1.0 - s)
        } else {
            Color::srgb(1.0 + s, 1.0 + s, 1.0)
        };
        gizmos.line(world(a), world(b), color);
    }
}
