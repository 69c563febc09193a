//! Steering a school: each member heads along a slow wander of its own, bent back from
//! the walls of its school's box and away from close neighbours of any school. Decided in
//! fixed ticks, so a replay steers the same; the plugin turns a jellyfish only while it
//! strokes.
//!
//! A member decides its heading every [`STEER_EVERY`] ticks, the school's members in turn
//! by their number: at Bevy's 64 Hz fixed rate that is 4 times a second, still more often
//! than the second a stroke takes (and a jellyfish turns only while it strokes). At 16
//! times a second finding the neighbours was a fifth of the CPU of 10,002 jellyfish
//! (`docs/benchmarks.md`). The schools steer on every other tick ([`STEER_TICKS`]), an
//! eighth of the members each time (at 1002 jellyfish, about 60 within reach of each):
//! gathering, sorting and filing every member's place is paid half as often (at 10,002,
//! 0.55 ms of one thread each time), and a frame that takes two fixed ticks steers once,
//! as the tank's water, which steps on every other tick too, steps once.

use super::grid::Neighbours;
use super::{JellyfishSchool, MemberOf, Swimmer};
use crate::plugin::swimming::{Steering, SteeringTarget, SwimMotion};
use bevy::prelude::*;

/// The walls push from this many reaches away.
const WALL_REACH: f32 = 3.0;
/// Neighbours push from this factor of the two reaches apart.
const NEIGHBOUR_REACH: f32 = 1.3;
/// How much more the walls and neighbours count than the wander.
const PUSH: f32 = 3.0;
/// A member is pushed by at most this many neighbours, the nearest: a crowd's members
/// heed the few around them (starlings their six or seven nearest, Ballerini et al. 2008),
/// and a member of an overfull box does not pay for the hundreds within its reach.
const NEAREST: usize = 7;
/// A member decides its heading in one fixed tick of this many.
pub(super) const STEER_EVERY: u32 = 16;
/// The schools steer in one fixed tick of this many (a divisor of [`STEER_EVERY`]).
const STEER_TICKS: u32 = 2;

/// Sets every member's heading.
pub(super) fn steer_schools(
    time: Res<Time<Fixed>>,
    schools: Query<(&JellyfishSchool, &Transform)>,
    mut members: Query<(&MemberOf, &Swimmer, &SwimMotion, &mut Steering)>,
    mut tick: Local<u32>,
    mut grid: Local<Neighbours>,
) {
    let t = time.elapsed_secs();
    let this = *tick;
    *tick = tick.wrapping_add(1);
    if !this.is_multiple_of(STEER_TICKS) {
        return;
    }
    // The members whose turn it is: each decides once in STEER_EVERY ticks.
    let turns = STEER_EVERY / STEER_TICKS;
    let turn = (this / STEER_TICKS) % turns;
    // Where they are in the simulation (not where the last frame drew them), in one order
    // every run.
    let mut all: Vec<(Vec3, f32)> = members
        .iter()
        .map(|(_, s, motion, _)| (motion.pose.position, s.radius))
        .collect();
    super::sort_by_position(&mut all);
    let widest = all.iter().fold(0.0f32, |r, (_, rq)| r.max(*rq));
    grid.refill(&all, cube(&all, NEIGHBOUR_REACH * widest));
    let grid = &*grid;
    // Each member's heading reads only `all` and the grid, so the members decide side by
    // side: the same headings, however many threads share them.
    members.par_iter_mut().for_each_init(
        Vec::new,
        |nearest, (of, swimmer, motion, mut steering)| {
            if swimmer.number % turns != turn {
                return;
            }
            let Ok((school, frame)) = schools.get(of.0) else {
                return;
            };
            let p = motion.pose.position;
            let w = swimmer.wander;
            let wander = frame.rotation
                * Vec3::new(
                    0.6 * (0.11 * t + w.x).sin(),
                    1.0 + 0.5 * (0.07 * t + w.y).sin(),
                    0.6 * (0.09 * t + w.z).cos(),
                );
            let mut push = walls(p, school, frame, swimmer.radius);
            // The nearest within reach, summed in the order of `all`: the same sum, to the
            // bit, as a pass over everyone sorted by distance.
            let range = NEIGHBOUR_REACH * (swimmer.radius + widest);
            let within = |i: usize| {
                let (q, rq) = all[i];
                let d = p.distance(q);
                (d > 1e-6 && d < NEIGHBOUR_REACH * (swimmer.radius + rq)).then_some(d)
            };
            grid.nearest(p, range, NEAREST, within, nearest);
            nearest.sort_unstable_by_key(|&(_, i)| i);
            for &(_, i) in nearest.iter() {
                push += pushes(p, swimmer.radius, all[i]).unwrap_or_default();
            }
            let desired = (wander.normalize_or(Vec3::Y) + PUSH * push).normalize_or(Vec3::Y);
            steering.target = SteeringTarget::Heading(desired);
        },
    );
}

/// The grid's cube for `points` whose neighbours reach up to `range`: about eight members
/// to a cube where they crowd (so a search for the nearest reads a few cubes), never
/// finer than a quarter of the range nor wider than it (to within a tenth of an octave).
fn cube(points: &[(Vec3, f32)], range: f32) -> f32 {
    let (lo, hi) = points.iter().fold(
        (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
        |(lo, hi), (p, _)| (lo.min(*p), hi.max(*p)),
    );
    let volume = (hi - lo).max(Vec3::splat(range)).element_product();
    let crowded = 2.0 * (volume / points.len().max(1) as f32).cbrt();
    let side = crowded.clamp(0.25 * range, range.max(1e-6));
    // On steps of a fifth of an octave: a school's box drifts a little every tick, and a
    // grid whose cubes keep their size keeps its lists (`Neighbours::refill`). The grid
    // finds the same members with cubes of any size.
    let step = (5.0 * side.log2()).round() / 5.0;
    if step.is_finite() { step.exp2() } else { side }
}

/// The push on a member at `p` of `radius` from a neighbour at `q` of `rq`, if it is
/// within reach (and not the member itself): one at contact, none at the reach.
fn pushes(p: Vec3, radius: f32, (q, rq): (Vec3, f32)) -> Option<Vec3> {
    let d = p - q;
    let reach = NEIGHBOUR_REACH * (radius + rq);
    let len = d.length();
    (len > 1e-6 && len < reach).then(|| d / len * (1.0 - len / reach))
}

/// The push back from the box's walls at `p`, world: zero until [`WALL_REACH`] reaches
/// from a wall, one at a reach from it, more beyond (outside the box).
fn walls(p: Vec3, school: &JellyfishSchool, frame: &Transform, radius: f32) -> Vec3 {
    let local = frame.rotation.inverse() * (p - frame.translation);
    let margin = (WALL_REACH * radius).max(1e-6);
    let near = |d: f32| ((margin - d) / (margin - radius).max(1e-6)).clamp(0.0, 2.0);
    let h = school.half_extents;
    let push = Vec3::new(
        near(h.x + local.x) - near(h.x - local.x),
        near(h.y + local.y) - near(h.y - local.y),
        near(h.z + local.z) - near(h.z - local.z),
    );
    frame.rotation * push
}
