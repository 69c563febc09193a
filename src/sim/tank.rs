//! A coarse 3D stable-fluids grid over a box: the water of a whole tank, stirred by pushes
//! and coming slowly to rest.
//!
//! One step, Stam's recipe on cell-centred velocities: apply the pushes gathered since the
//! last step, advect (semi-Lagrangian), let the water come to rest a little, and project
//! (Gauss–Seidel on the pressure, closed free-slip walls). Pushes are applied in the order
//! they came, so the same pushes give the same water; a crowded tank's pushes can be
//! applied in slabs side by side ([`TankFluid::push_slabs`]), to the same bits.

use super::trilinear::Trilinear;
use glam::{UVec3, Vec3};

/// Gauss–Seidel sweeps of the pressure solve: the grid is coarse and the water slow, and
/// what is left of the divergence is damped away within a few steps.
const PRESSURE_SWEEPS: usize = 20;

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
}

/// A push given to the water: within `radius` of `at`, towards `velocity`, smoothly less
/// towards the edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Impulse {
    /// Centre.
    pub at: Vec3,
    /// Reach.
    pub radius: f32,
    /// Velocity given at the centre.
    pub velocity: Vec3,
}

/// What a slab of pushes needs to know of the tank's grid.
#[derive(Clone, Copy, Debug)]
struct Slab {
    min: Vec3,
    cell: f32,
    size: UVec3,
}

impl Slab {
    fn of(tank: &TankFluid) -> Self {
        Self {
            min: tank.min,
            cell: tank.cell,
            size: tank.size,
        }
    }

    fn centre(&self, i: i64, j: i64, k: i64) -> Vec3 {
        self.min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * self.cell
    }
}

/// The tank's pending pushes over one slab of its z-planes ([`TankFluid::push_slabs`]).
#[derive(Debug)]
pub struct PushSlab<'a> {
    tank: Slab,
    /// The slab's first z-plane.
    first: i64,
    /// The slab's cells, x fastest, then y, then z.
    velocity: &'a mut [Vec3],
    pending: &'a [Impulse],
}

impl PushSlab<'_> {
    /// Applies every pending push to the slab's cells, in the order they came.
    pub fn apply(self) {
        let Self {
            tank,
            first,
            velocity,
            pending,
        } = self;
        let s = tank.size.as_i64vec3();
        let last = first + (velocity.len() as i64 / (s.x * s.y)) - 1;
        for imp in pending {
            let reach = (ceil_to_i64(imp.radius / tank.cell) + 1).max(1);
            let c = ((imp.at - tank.min) / tank.cell)
                .to_array()
                .map(floor_to_i32);
            let cells =
                |c: i32, lo: i64, hi: i64| (c as i64 - reach).max(lo)..=(c as i64 + reach).min(hi);
            // Surely outside (a squared distance beyond it): most of the cube around the
            // ball, skipped row by row and then cell by cell before the root. Each skip is
            // exact: such a cell fails `d < 1` too.
            let outside = imp.radius * imp.radius * 1.0001;
            let x = (imp.at.x - tank.min.x) / tank.cell - 0.5;
            for k in cells(c[2], first, last) {
                for j in cells(c[1], 0, s.y - 1) {
                    let off = tank.centre(0, j, k) - imp.at;
                    let across = off.y * off.y + off.z * off.z;
                    if across > outside {
                        continue;
                    }
                    // Cells a cell beyond the ball's chord along this row are outside too.
                    let half = (outside - across).sqrt() / tank.cell + 1.0;
                    let along = cells(c[0], 0, s.x - 1);
                    let first_i = (*along.start()).max(floor_not_below_zero(x - half));
                    let last_i = (*along.end()).min(ceil_to_i64(x + half));
                    let row = (((k - first) * s.y + j) * s.x) as usize;
                    for i in first_i..=last_i {
                        let centre = tank.centre(i, j, k);
                        if centre.distance_squared(imp.at) > outside {
                            continue;
                        }
                        let d = centre.distance(imp.at) / imp.radius;
                        if d < 1.0 {
                            let w = (1.0 - d * d).powi(2);
                            let v = &mut velocity[row + i as usize];
                            *v += (imp.velocity - *v) * w;
                        }
                    }
                }
            }
        }
    }
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
    /// `min + ((i, j, k) + 0.5) · cell`.
    pub fn velocities(&self) -> &[Vec3] {
        &self.velocity
    }

    /// The water's velocity at a point (trilinear; held at the walls).
    pub fn velocity_at(&self, point: Vec3) -> Vec3 {
        self.grid().sample(&self.velocity, point)
    }

    /// Largest speed in the tank.
    pub fn speed_max(&self) -> f32 {
        self.velocity.iter().map(|v| v.length()).fold(0.0, f32::max)
    }

    /// One step of `dt` seconds: pushes, advection, rest, projection.
    pub fn step(&mut self, dt: f32) {
        if dt.is_nan() || dt <= 0.0 {
            return;
        }
        self.push();
        self.step_pushed(dt);
    }

    fn index(&self, i: u32, j: u32, k: u32) -> usize {
        ((k * self.size.y + j) * self.size.x + i) as usize
    }

    fn centre(&self, i: u32, j: u32, k: u32) -> Vec3 {
        self.min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * self.cell
    }

    /// Applies the pending pushes, in the order they came.
    fn push(&mut self) {
        self.push_slabs(1).into_iter().for_each(PushSlab::apply);
        self.pending.clear();
    }

    /// The pending pushes cut into at most `parts` slabs of whole z-planes, to be applied
    /// side by side ([`PushSlab::apply`]) before [`TankFluid::step_pushed`]. A cell lies in
    /// one slab and takes its pushes there in the order they came, so the water is the
    /// same, bit for bit, however many parts it is cut into.
    pub fn push_slabs(&mut self, parts: usize) -> Vec<PushSlab<'_>> {
        let plane = (self.size.x * self.size.y) as usize;
        let planes = self.size.z as usize;
        let per = planes.div_ceil(parts.clamp(1, planes.max(1)));
        let (tank, pending) = (Slab::of(self), &self.pending);
        self.velocity
            .chunks_mut(per * plane)
            .enumerate()
            .map(|(n, velocity)| PushSlab {
                tank,
                first: (n * per) as i64,
                velocity,
                pending,
            })
            .collect()
    }

    /// The rest of a step whose pushes [`TankFluid::push_slabs`] applied: advection,
    /// rest, projection.
    pub fn step_pushed(&mut self, dt: f32) {
        self.pending.clear();
        if dt.is_nan() || dt <= 0.0 {
            return;
        }
        self.advect(dt);
        self.come_to_rest(dt);
        self.walls();
        self.project();
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

    /// Removes the divergent part: solves for the pressure and subtracts its gradient.
    fn project(&mut self) {
        let h = self.cell;
        self.measure_divergence();
        self.pressure.iter_mut().for_each(|p| *p = 0.0);
        relax(&mut self.pressure, &self.divergence, self.size, h * h);
        let (p, v) = (&self.pressure, &mut self.velocity);
        for_each_cell(self.size, |idx, near| {
            let here = p[idx];
            let [l, r, d, u, b, f] = near.map(|n| n.map_or(here, |n| p[n]));
            v[idx] -= Vec3::new(r - l, u - d, f - b) / (2.0 * h);
        });
        self.walls();
    }
}

// Floors and ceilings by truncation, the same integers as `floor`/`ceil` and a cast (each
// a library call on x86-64's baseline, without SSE4.1): two for every row a push crosses.

/// `v.floor() as i32`.
fn floor_to_i32(v: f32) -> i32 {
    let t = v as i32;
    if (t as f32) > v {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// `v.floor().max(0.0) as i64`: truncation is the floor of what is not negative.
fn floor_not_below_zero(v: f32) -> i64 {
    if v > 0.0 { v as i64 } else { 0 }
}

/// `v.ceil() as i64`.
fn ceil_to_i64(v: f32) -> i64 {
    let t = v as i64;
    if (t as f32) < v {
        t.saturating_add(1)
    } else {
        t
    }
}

/// Gauss–Seidel sweeps towards the pressure whose Laplacian is `div` (cells `h2 = h²`
/// apart; Neumann walls). Each cell's update waits on its neighbour's just before it, so
/// one sweep is a chain of dependent divisions; the sweeps run [`SWEEPS_IN_FLIGHT`] at a
/// time instead, each a plane behind the one before and stepped cell by cell with it, so
/// the processor works on several chains at once. Every cell still sees its neighbours as
/// one sweep after another leaves them: the same pressure, bit for bit.
fn relax(p: &mut [f32], div: &[f32], size: UVec3, h2: f32) {
    let [sx, sy, sz] = [size.x, size.y, size.z].map(|n| n as usize);
    let (dy, dz) = (sx, sx * sy);
    let cell = |p: &mut [f32], i: usize, j: usize, k: usize| {
        let idx = (k * sy + j) * sx + i;
        let here = p[idx];
        // Neumann: no pressure gradient through a wall.
        let at = |ok: bool, n: usize| if ok { p[n] } else { here };
        let l = at(i > 0, idx.wrapping_sub(1));
        let r = at(i + 1 < sx, idx + 1);
        let d = at(j > 0, idx.wrapping_sub(dy));
        let u = at(j + 1 < sy, idx + dy);
        let b = at(k > 0, idx.wrapping_sub(dz));
        let f = at(k + 1 < sz, idx + dz);
        p[idx] = (l + r + d + u + b + f - h2 * div[idx]) / 6.0;
    };
    let mut done = 0;
    while done < PRESSURE_SWEEPS {
        let flight = SWEEPS_IN_FLIGHT.min(PRESSURE_SWEEPS - done);
        // Sweep q of the flight is at plane `t - q`: the earlier sweeps lead, and at each
        // cell of a row go first, so a later one reads what they left.
        for t in 0..sz + flight - 1 {
            let planes = (0..flight).filter_map(|q| t.checked_sub(q).filter(|&k| k < sz));
            let (mut ks, mut n) = ([0; SWEEPS_IN_FLIGHT], 0);
            for k in planes {
                ks[n] = k;
                n += 1;
            }
            for j in 0..sy {
                for i in 0..sx {
                    for &k in &ks[..n] {
                        cell(p, i, j, k);
                    }
                }
            }
        }
        done += flight;
    }
}

/// Pressure sweeps [`relax`] runs side by side.
const SWEEPS_IN_FLIGHT: usize = 4;

/// Visits every cell of a grid of `size` in memory order with its index and its six
/// neighbours' (−x, +x, −y, +y, −z, +z; none past a wall). Inside, the neighbours are
/// plain offsets, found without a test per neighbour.
#[inline(always)]
fn for_each_cell(size: UVec3, mut visit: impl FnMut(usize, [Option<usize>; 6])) {
    let [sx, sy, sz] = [size.x, size.y, size.z].map(|n| n as usize);
    let (dy, dz) = (sx, sx * sy);
    for k in 0..sz {
        for j in 0..sy {
            let row = (k * sy + j) * sx;
            let edge = |i: usize| {
                let idx = row + i;
                let step = |ok: bool, n: usize| ok.then_some(n);
                [
                    step(i > 0, idx.wrapping_sub(1)),
                    step(i + 1 < sx, idx + 1),
                    step(j > 0, idx.wrapping_sub(dy)),
                    step(j + 1 < sy, idx + dy),
                    step(k > 0, idx.wrapping_sub(dz)),
                    step(k + 1 < sz, idx + dz),
                ]
            };
            if j == 0 || j + 1 == sy || k == 0 || k + 1 == sz {
                for i in 0..sx {
                    visit(row + i, edge(i));
                }
                continue;
            }
            visit(row, edge(0));
            for idx in row + 1..row + sx - 1 {
                visit(
                    idx,
                    [
                        Some(idx - 1),
                        Some(idx + 1),
                        Some(idx - dy),
                        Some(idx + dy),
                        Some(idx - dz),
                        Some(idx + dz),
                    ],
                );
            }
            visit(row + sx - 1, edge(sx - 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tank() -> TankFluid {
        TankFluid::new(Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 8.0, 4.0), 0.5)
    }

    /// Numbers in [0, 1) from `seed`, the same every run.
    fn uniform(seed: u32) -> impl FnMut() -> f32 {
        let mut state = seed;
        move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        }
    }

    /// The pushes skip what is surely outside each ball, and nothing else: the water is
    /// the same, bit for bit, as from visiting the whole cube around it, for balls of
    /// every size, anywhere (across the walls and outside the tank too).
    #[test]
    fn pushes_reach_exactly_the_cells_in_their_balls() {
        let mut fast = tank();
        let mut every = tank();
        let mut next = uniform(7);
        for _ in 0..300 {
            let at = Vec3::new(
                next() * 10.0 - 5.0,
                next() * 10.0 - 1.0,
                next() * 10.0 - 5.0,
            );
            let radius = 0.05 + 2.5 * next() * next();
            let velocity = Vec3::new(next() - 0.5, next(), next() - 0.5);
            fast.stir(at, radius, velocity);
            every.stir(at, radius, velocity);
        }
        fast.push();
        for imp in std::mem::take(&mut every.pending) {
            let reach = ((imp.radius / every.cell).ceil() as i64 + 1).max(1);
            let c = ((imp.at - every.min) / every.cell).floor().as_ivec3();
            let s = every.size.as_i64vec3();
            for k in c.z as i64 - reach..=c.z as i64 + reach {
                for j in c.y as i64 - reach..=c.y as i64 + reach {
                    for i in c.x as i64 - reach..=c.x as i64 + reach {
                        if i < 0 || j < 0 || k < 0 || i >= s.x || j >= s.y || k >= s.z {
                            continue;
                        }
                        let (i, j, k) = (i as u32, j as u32, k as u32);
                        let d = every.centre(i, j, k).distance(imp.at) / imp.radius;
                        if d < 1.0 {
                            let w = (1.0 - d * d).powi(2);
                            let idx = every.index(i, j, k);
                            let v = &mut every.velocity[idx];
                            *v += (imp.velocity - *v) * w;
                        }
                    }
                }
            }
        }
        let moved = every.velocity.iter().filter(|v| **v != Vec3::ZERO).count();
        assert!(moved > 500, "the pushes reach the water: {moved} cells");
        for (a, b) in fast.velocity.iter().zip(&every.velocity) {
            assert_eq!(
                a.to_array().map(f32::to_bits),
                b.to_array().map(f32::to_bits)
            );
        }
    }

    /// Cut into slabs of z-planes and applied in any order, the pushes give the water
    /// they give in one piece, bit for bit, and a whole step after them is `step`'s.
    #[test]
    fn pushes_in_slabs_are_the_pushes_in_one_piece() {
        let stirred = || {
            let mut t = tank();
            let mut next = uniform(11);
            for _ in 0..400 {
                let at = Vec3::new(next() * 9.0 - 4.5, next() * 9.0 - 0.5, next() * 9.0 - 4.5);
                let velocity = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
                t.stir(at, 0.1 + 2.0 * next(), velocity);
            }
            t
        };
        let bits = |t: &TankFluid| -> Vec<[u32; 3]> {
            t.velocity
                .iter()
                .map(|v| v.to_array().map(f32::to_bits))
                .collect()
        };
        let mut whole = stirred();
        whole.step(1.0 / 64.0);
        let planes = whole.size.z as usize;
        for parts in [1, 2, 3, 5, planes - 1, planes, planes + 7] {
            let mut cut = stirred();
            let mut slabs = cut.push_slabs(parts);
            assert!(
                slabs.len() <= parts,
                "{} slabs for {parts} parts",
                slabs.len()
            );
            // Last first: no slab leans on another.
            slabs.reverse();
            slabs.into_iter().for_each(PushSlab::apply);
            cut.step_pushed(1.0 / 64.0);
            assert!(cut.pending.is_empty());
            assert!(bits(&cut) == bits(&whole), "{parts} parts differ");
        }
        let moved = whole.velocity.iter().filter(|v| **v != Vec3::ZERO).count();
        assert!(
            moved > whole.velocity.len() / 2,
            "the pushes reach the water: {moved}"
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
        t.project();
        let after = divergence_rms(&mut t);
        println!("rms divergence of a stir {before:.3} 1/s, projected {after:.3} 1/s");
        assert!(before > 0.02, "a stir is divergent: {before}");
        assert!(after < 0.4 * before, "projected {after}, before {before}");
    }

    /// The truncating floors and ceilings are the library's, from far below to far
    /// above, at every quarter near zero and an ulp either side, and at the infinities.
    #[test]
    fn truncated_floors_and_ceilings_are_the_librarys() {
        let mut values = vec![f32::INFINITY, f32::NEG_INFINITY, f32::NAN, 0.0, -0.0];
        for q in -400..=400 {
            let v = q as f32 * 0.25;
            values.extend([v, v.next_up(), v.next_down()]);
        }
        for e in [10, 20, 31, 32, 40, 63, 64, 100] {
            let v = 2f32.powi(e);
            values.extend([
                v,
                -v,
                v.next_up(),
                -v.next_up(),
                v.next_down(),
                -v.next_down(),
            ]);
        }
        for v in values {
            assert_eq!(floor_to_i32(v), v.floor() as i32, "floor of {v}");
            assert_eq!(
                floor_not_below_zero(v),
                v.floor().max(0.0) as i64,
                "floor of {v}"
            );
            assert_eq!(ceil_to_i64(v), v.ceil() as i64, "ceil of {v}");
        }
    }

    /// The sweeps in flight leave the pressure one sweep after another leaves it, bit for
    /// bit, on grids thinner than the flight too.
    #[test]
    fn sweeps_in_flight_are_the_sweeps_one_after_another() {
        for size in [
            UVec3::new(19, 12, 14),
            UVec3::new(5, 4, 3),
            UVec3::new(3, 3, 1),
        ] {
            let n = (size.x * size.y * size.z) as usize;
            let div: Vec<f32> = (0..n).map(|c| ((c * 7919) % 23) as f32 - 11.0).collect();
            let h2 = 0.75f32 * 0.75;
            let mut flight = vec![0.0; n];
            relax(&mut flight, &div, size, h2);
            let mut one = vec![0.0f32; n];
            for _ in 0..PRESSURE_SWEEPS {
                for_each_cell(size, |idx, near| {
                    let here = one[idx];
                    let [l, r, d, u, b, f] = near.map(|m| m.map_or(here, |m| one[m]));
                    one[idx] = (l + r + d + u + b + f - h2 * div[idx]) / 6.0;
                });
            }
            assert!(one.iter().any(|p| *p != 0.0));
            let bits = |p: &[f32]| p.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&flight), bits(&one), "grid {size}");
        }
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
