//! A coarse 3D stable-fluids grid over a box: the water of a whole tank, stirred by pushes
//! and coming slowly to rest.
//!
//! One step, Stam's recipe on cell-centred velocities: apply the pushes gathered since the
//! last step, advect (semi-Lagrangian), let the water come to rest a little, and project
//! (Gauss–Seidel on the pressure, closed free-slip walls). Pushes are applied in the order
//! they came, so the same pushes give the same water; a crowded tank's pushes can be
//! applied in slabs side by side ([`TankFluid::push_slabs`], `pushes`), to the same bits; the
//! pressure's sweeps are in `relax`. A caller that steps the water every few frames can
//! split a step's work over two calls ([`TankFluid::begin_step`],
//! [`TankFluid::advance_pushed`], [`TankFluid::finish_step`]), to the same bits, the water
//! before it seen from outside until it is done.

mod pushes;
mod relax;

pub use pushes::PushSlab;

use super::trilinear::Trilinear;
use glam::{UVec3, Vec3};
use pushes::Impulse;
use relax::{PRESSURE_SWEEPS, SWEEPS_IN_FLIGHT, for_each_cell, relax_sweeps};

/// Of a step split over two calls, the pressure's sweeps taken in the first: with the
/// pushes and the advection there, about half a quiet step's work in each (the aquarium's
/// tank with 18 jellyfish: 0.21 and 0.16 ms; with ten thousand, whose jets' pushes are
/// most of the first, 0.6 and 0.18). Whole flights, so the split changes no bit.
const FIRST_SWEEPS: usize = 8;
const _: () =
    assert!(FIRST_SWEEPS.is_multiple_of(SWEEPS_IN_FLIGHT) && FIRST_SWEEPS <= PRESSURE_SWEEPS);

/// The tank's water: velocities at cell centres of a box.
#[derive(Clone, Debug, Default)]
pub struct TankFluid {
    /// The tank's lower corner.
    pub min: Vec3,
    /// Cell size.
    pub cell: f32,
    /// Cells along x, y, z.
    pub size: UVec3,
    /// How quickly the water comes back to rest, 1/s.
    pub damping: f32,
    velocity: Vec<Vec3>,
    scratch: Vec<Vec3>,
    pressure: Vec<f32>,
    divergence: Vec<f32>,
    pending: Vec<Impulse>,
    /// Where a step split over two calls stands ([`TankFluid::begin_step`]).
    split: Split,
    /// The water before the step in flight: what is seen from outside until it is done.
    before: Vec<Vec3>,
}

/// How far a step split over two calls has come.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Split {
    /// None in flight: the water is as it stands.
    #[default]
    Idle,
    /// Begun: the pushes are being applied; nothing else is done yet.
    Pushing,
    /// Advected and part relaxed: the pressure's last sweeps are left.
    Relaxing,
    /// Begun with a step of no length: only the pushes were applied.
    Pushed,
}

impl TankFluid {
    /// Still water filling the box from `min` to `max` in cells of about `cell`.
    pub fn new(min: Vec3, max: Vec3, cell: f32) -> Self {
        let cell = cell.max(1e-3);
        let size = ((max - min) / cell).ceil().max(Vec3::splat(3.0)).as_uvec3();
        let count = (size.x * size.y * size.z) as usize;
        Self {
            min,
            cell,
            size,
            damping: 0.15,
            velocity: vec![Vec3::ZERO; count],
            scratch: vec![Vec3::ZERO; count],
            pressure: vec![0.0; count],
            divergence: vec![0.0; count],
            pending: Vec::new(),
            split: Split::Idle,
            before: Vec::new(),
        }
    }

    /// Pushes the water at `at` within `radius` towards `velocity`; applied at the next
    /// step. A non-finite or empty push is ignored.
    pub fn stir(&mut self, at: Vec3, radius: f32, velocity: Vec3) {
        if at.is_finite() && velocity.is_finite() && radius > 0.0 {
            self.pending.push(Impulse {
                at,
                radius,
                velocity,
            });
        }
    }

    /// The cell centres as a sampling grid.
    pub(crate) fn grid(&self) -> Trilinear {
        Trilinear {
            origin: self.min + Vec3::splat(0.5 * self.cell),
            spacing: self.cell,
            size: self.size,
        }
    }

    /// The velocity of every cell, x fastest, then y, then z; cell (i, j, k) is centred at
    /// `min + ((i, j, k) + 0.5) · cell`. While a split step is in flight, the water before
    /// it.
    pub fn velocities(&self) -> &[Vec3] {
        if self.split == Split::Idle {
            &self.velocity
        } else {
            &self.before
        }
    }

    /// The water's velocity at a point (trilinear; held at the walls).
    pub fn velocity_at(&self, point: Vec3) -> Vec3 {
        self.grid().sample(self.velocities(), point)
    }

    /// Largest speed in the tank.
    pub fn speed_max(&self) -> f32 {
        self.velocities()
            .iter()
            .map(|v| v.length())
            .fold(0.0, f32::max)
    }

    /// Whether a step split over two calls is in flight ([`TankFluid::begin_step`]).
    pub fn step_in_flight(&self) -> bool {
        self.split != Split::Idle
    }

    /// Begins a step to be split over two calls: the water as it stands is what is seen
    /// from outside until [`TankFluid::finish_step`], and the pending pushes are cut into
    /// slabs to apply ([`TankFluid::push_slabs`]) before [`TankFluid::advance_pushed`]. A
    /// step still in flight is finished first.
    pub fn begin_step(&mut self, parts: usize) -> Vec<PushSlab<'_>> {
        self.finish_step();
        self.before.clone_from(&self.velocity);
        self.split = Split::Pushing;
        self.push_slabs(parts)
    }

    /// The first part of a step begun ([`TankFluid::begin_step`]) whose pushes were
    /// applied: advection, rest, and the pressure's first sweeps. Outside a split step,
    /// the whole step ([`TankFluid::step_pushed`]).
    pub fn advance_pushed(&mut self, dt: f32) {
        if self.split != Split::Pushing {
            self.step_pushed(dt);
            return;
        }
        self.pending.clear();
        if dt.is_nan() || dt <= 0.0 {
            self.split = Split::Pushed;
            return;
        }
        self.advect(dt);
        self.come_to_rest(dt);
        self.walls();
        self.begin_projection();
        self.split = Split::Relaxing;
    }

    /// The rest of a split step: the pressure's last sweeps and its gradient taken out.
    /// The stepped water is then what is seen from outside. Nothing when none is in
    /// flight.
    pub fn finish_step(&mut self) {
        if self.split == Split::Relaxing {
            self.finish_projection();
        }
        self.split = Split::Idle;
    }

    /// One step of `dt` seconds: pushes, advection, rest, projection.
    pub fn step(&mut self, dt: f32) {
        if dt.is_nan() || dt <= 0.0 {
            return;
        }
        self.finish_step();
        self.push();
        self.step_pushed(dt);
    }

    fn index(&self, i: u32, j: u32, k: u32) -> usize {
        ((k * self.size.y + j) * self.size.x + i) as usize
    }

    fn centre(&self, i: u32, j: u32, k: u32) -> Vec3 {
        self.min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * self.cell
    }

    /// The rest of a step whose pushes [`TankFluid::push_slabs`] applied: advection,
    /// rest, projection. (A split step in flight is finished first.)
    pub fn step_pushed(&mut self, dt: f32) {
        self.finish_step();
        self.pending.clear();
        if dt.is_nan() || dt <= 0.0 {
            return;
        }
        self.advect(dt);
        self.come_to_rest(dt);
        self.walls();
        self.begin_projection();
        self.finish_projection();
    }

    fn advect(&mut self, dt: f32) {
        let grid = self.grid();
        let s = self.size;
        for k in 0..s.z {
            for j in 0..s.y {
                for i in 0..s.x {
                    let idx = self.index(i, j, k);
                    let back = self.centre(i, j, k) - self.velocity[idx] * dt;
                    self.scratch[idx] = grid.sample(&self.velocity, back);
                }
            }
        }
        std::mem::swap(&mut self.velocity, &mut self.scratch);
    }

    /// The water slows by `1 / (1 + damping·dt)`: implicit, so never past rest.
    fn come_to_rest(&mut self, dt: f32) {
        let keep = 1.0 / (1.0 + self.damping * dt);
        self.velocity.iter_mut().for_each(|v| *v *= keep);
    }

    /// Closed, free-slip walls: no velocity through them.
    fn walls(&mut self) {
        let s = self.size;
        let [sx, sy, sz] = [s.x, s.y, s.z].map(|n| n as usize);
        for k in 0..sz {
            for j in 0..sy {
                let row = &mut self.velocity[(k * sy + j) * sx..][..sx];
                row[0].x = 0.0;
                row[sx - 1].x = 0.0;
                if j == 0 || j == sy - 1 {
                    row.iter_mut().for_each(|v| v.y = 0.0);
                }
                if k == 0 || k == sz - 1 {
                    row.iter_mut().for_each(|v| v.z = 0.0);
                }
            }
        }
    }

    /// The divergence of the velocity at every cell (central differences, no flow through
    /// the walls), into `self.divergence`.
    fn measure_divergence(&mut self) {
        let h = self.cell;
        let v = &self.velocity;
        for_each_cell(self.size, |idx, [l, r, d, u, b, f]| {
            let at = |n: Option<usize>| n.map_or(Vec3::ZERO, |n| v[n]);
            self.divergence[idx] =
                (at(r).x - at(l).x + at(u).y - at(d).y + at(f).z - at(b).z) / (2.0 * h);
        });
    }

    /// The projection's first part: the divergence, and the pressure's first sweeps.
    fn begin_projection(&mut self) {
        let h = self.cell;
        self.measure_divergence();
        self.pressure.iter_mut().for_each(|p| *p = 0.0);
        relax_sweeps(
            &mut self.pressure,
            &self.divergence,
            self.size,
            h * h,
            FIRST_SWEEPS,
        );
    }

    /// The projection's rest: the pressure's last sweeps, and its gradient subtracted.
    /// With [`TankFluid::begin_projection`], the divergent part removed.
    fn finish_projection(&mut self) {
        let h = self.cell;
        let rest = PRESSURE_SWEEPS - FIRST_SWEEPS;
        relax_sweeps(&mut self.pressure, &self.divergence, self.size, h * h, rest);
        let (p, v) = (&self.pressure, &mut self.velocity);
        for_each_cell(self.size, |idx, near| {
            let here = p[idx];
            let [l, r, d, u, b, f] = near.map(|n| n.map_or(here, |n| p[n]));
            v[idx] -= Vec3::new(r - l, u - d, f - b) / (2.0 * h);
        });
        self.walls();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(super) fn tank() -> TankFluid {
        TankFluid::new(Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 8.0, 4.0), 0.5)
    }

    /// Numbers in [0, 1) from `seed`, the same every run.
    pub(super) fn uniform(seed: u32) -> impl FnMut() -> f32 {
        let mut state = seed;
        move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        }
    }

    /// A step split over two calls is the step taken at once, to the bit, and until it is
    /// done the water seen from outside is the water before it.
    #[test]
    fn a_step_split_in_two_is_the_step_at_once() {
        let stirred = || {
            let mut t = tank();
            t.stir(Vec3::new(0.5, 3.0, -0.5), 1.5, Vec3::new(1.0, 0.5, 0.0));
            t.step(1.0 / 32.0);
            t.stir(Vec3::new(-1.5, 5.0, 1.0), 1.0, Vec3::new(0.0, -0.8, 0.6));
            t
        };
        let bits = |v: &[Vec3]| {
            v.iter()
                .map(|v| v.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        let (mut whole, mut split) = (stirred(), stirred());
        whole.step(1.0 / 32.0);
        let before = bits(split.velocities());
        split.begin_step(3).into_iter().for_each(PushSlab::apply);
        assert!(split.step_in_flight());
        assert_eq!(bits(split.velocities()), before, "pushed, seen as before");
        split.advance_pushed(1.0 / 32.0);
        assert_eq!(
            bits(split.velocities()),
            before,
            "half stepped, seen as before"
        );
        assert_eq!(
            split.velocity_at(Vec3::new(0.5, 3.0, -0.5)),
            stirred().velocity_at(Vec3::new(0.5, 3.0, -0.5))
        );
        split.finish_step();
        assert!(!split.step_in_flight());
        assert_eq!(
            bits(split.velocities()),
            bits(whole.velocities()),
            "finished"
        );
        assert_ne!(bits(split.velocities()), before);
        // Begun again and left in flight, a whole step finishes it first.
        split.stir(Vec3::new(1.0, 2.0, 1.0), 1.0, Vec3::X);
        whole.stir(Vec3::new(1.0, 2.0, 1.0), 1.0, Vec3::X);
        split.begin_step(2).into_iter().for_each(PushSlab::apply);
        split.advance_pushed(1.0 / 32.0);
        split.step(1.0 / 32.0);
        whole.step(1.0 / 32.0);
        whole.step(1.0 / 32.0);
        assert_eq!(
            bits(split.velocities()),
            bits(whole.velocities()),
            "in flight, then whole"
        );
    }

    #[test]
    fn a_stir_moves_the_water_near_it_and_fades() {
        let mut t = tank();
        let at = Vec3::new(0.0, 4.0, 0.0);
        t.stir(at, 1.0, Vec3::new(1.0, 0.0, 0.0));
        t.step(1.0 / 64.0);
        let near = t.velocity_at(at).x;
        let far = t.velocity_at(Vec3::new(0.0, 4.0, 3.5)).length();
        assert!(near > 0.3, "{near}");
        assert!(far < 0.1 * near, "far {far}, near {near}");
        for _ in 0..64 * 30 {
            t.step(1.0 / 64.0);
        }
        assert!(t.speed_max() < 0.05 * near, "the water comes to rest");
    }

    /// A coarse tank's water barely depends on its step: stirred alike and stepped at 64
    /// and at 32 steps a second, it is the same water a second and two seconds on to
    /// within a few hundredths of its speed (the plugin steps every other fixed tick).
    #[test]
    fn the_water_barely_depends_on_the_step() {
        let stirred = || {
            let mut t = tank();
            t.stir(Vec3::new(0.5, 3.0, -0.5), 1.5, Vec3::new(1.0, 0.5, 0.0));
            t.stir(Vec3::new(-1.5, 5.0, 1.0), 1.0, Vec3::new(0.0, -0.8, 0.6));
            t
        };
        let (mut fine, mut coarse) = (stirred(), stirred());
        for seconds in 1..=2 {
            for _ in 0..64 {
                fine.step(1.0 / 64.0);
            }
            for _ in 0..32 {
                coarse.step(1.0 / 32.0);
            }
            let rms = |t: &TankFluid| {
                let sum: f32 = t.velocity.iter().map(|v| v.length_squared()).sum();
                (sum / t.velocity.len() as f32).sqrt()
            };
            let apart: f32 = fine
                .velocity
                .iter()
                .zip(&coarse.velocity)
                .map(|(a, b)| a.distance_squared(*b))
                .sum();
            let apart = (apart / fine.velocity.len() as f32).sqrt();
            let speed = rms(&fine);
            println!(
                "after {seconds} s: rms speed {speed:.4}, at half the steps {:.4}, apart {apart:.5} ({:.1}%)",
                rms(&coarse),
                100.0 * apart / speed
            );
            assert!(speed > 0.01, "the water still moves: {speed}");
            assert!(apart < 0.05 * speed, "apart {apart}, speed {speed}");
        }
    }

    #[test]
    fn the_walls_hold_the_water_in() {
        let mut t = tank();
        t.stir(Vec3::new(3.8, 4.0, 0.0), 1.5, Vec3::new(2.0, 0.0, 0.0));
        for _ in 0..10 {
            t.step(1.0 / 64.0);
        }
        let s = t.size;
        for k in 0..s.z {
            for j in 0..s.y {
                assert_eq!(t.velocity[t.index(s.x - 1, j, k)].x, 0.0);
            }
        }
    }

    /// Root-mean-square divergence over the tank, 1/s.
    fn divergence_rms(t: &mut TankFluid) -> f32 {
        t.measure_divergence();
        let sum: f32 = t.divergence.iter().map(|d| d * d).sum();
        (sum / t.divergence.len() as f32).sqrt()
    }

    #[test]
    fn projection_takes_out_most_of_a_stirs_divergence() {
        let mut t = tank();
        t.stir(Vec3::new(0.5, 3.0, -0.5), 1.5, Vec3::new(1.0, 0.5, 0.0));
        t.push();
        t.walls();
        let before = divergence_rms(&mut t);
        t.begin_projection();
        t.finish_projection();
        let after = divergence_rms(&mut t);
        println!("rms divergence of a stir {before:.3} 1/s, projected {after:.3} 1/s");
        assert!(before > 0.02, "a stir is divergent: {before}");
        assert!(after < 0.4 * before, "projected {after}, before {before}");
    }

    #[test]
    fn a_stir_mirrored_across_the_tank_gives_the_mirrored_water() {
        let run = |sign: f32| {
            let mut t = tank();
            t.stir(
                Vec3::new(sign * 1.2, 3.0, 0.7),
                1.5,
                Vec3::new(sign, 0.4, 0.2),
            );
            for _ in 0..20 {
                t.step(1.0 / 64.0);
            }
            t
        };
        let (a, b) = (run(1.0), run(-1.0));
        for p in [Vec3::new(1.0, 3.0, 0.5), Vec3::new(2.5, 4.0, -1.0)] {
            let (va, vb) = (
                a.velocity_at(p),
                b.velocity_at(p * Vec3::new(-1.0, 1.0, 1.0)),
            );
            let mirrored = vb * Vec3::new(-1.0, 1.0, 1.0);
            assert!(
                (va - mirrored).length() < 1e-3 * (1.0 + va.length()),
                "{va} against mirrored {mirrored}"
            );
        }
    }
}
