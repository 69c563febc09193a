//! A coarse 3D stable-fluids grid over a box: the water of a whole tank, stirred by pushes
//! and coming slowly to rest.
//!
//! One step, Stam's recipe on cell-centred velocities: apply the pushes gathered since the
//! last step, advect (semi-Lagrangian), let the water come to rest a little, and project
//! (Gauss–Seidel on the pressure, closed free-slip walls). Pushes are applied in the order
//! they came, so the same pushes give the same water.

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
        self.advect(dt);
        self.come_to_rest(dt);
        self.walls();
        self.project();
    }

    fn index(&self, i: u32, j: u32, k: u32) -> usize {
        ((k * self.size.y + j) * self.size.x + i) as usize
    }

    fn centre(&self, i: u32, j: u32, k: u32) -> Vec3 {
        self.min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * self.cell
    }

    /// Applies the pending pushes, in the order they came.
    fn push(&mut self) {
        let pending = std::mem::take(&mut self.pending);
        let s = self.size.as_i64vec3();
        for imp in &pending {
            let reach = ((imp.radius / self.cell).ceil() as i64 + 1).max(1);
            let c = ((imp.at - self.min) / self.cell).floor().as_ivec3();
            let cells = |c: i32, n: i64| (c as i64 - reach).max(0)..=(c as i64 + reach).min(n - 1);
            // Surely outside (a squared distance beyond it): most of the cube around the
            // ball, skipped row by row and then cell by cell before the root. Each skip is
            // exact: such a cell fails `d < 1` too.
            let outside = imp.radius * imp.radius * 1.0001;
            let x = (imp.at.x - self.min.x) / self.cell - 0.5;
            for k in cells(c.z, s.z) {
                for j in cells(c.y, s.y) {
                    let off = self.centre(0, j as u32, k as u32) - imp.at;
                    let across = off.y * off.y + off.z * off.z;
                    if across > outside {
                        continue;
                    }
                    // Cells a cell beyond the ball's chord along this row are outside too.
                    let half = (outside - across).sqrt() / self.cell + 1.0;
                    let along = cells(c.x, s.x);
                    let first = (*along.start()).max((x - half).floor().max(0.0) as i64);
                    let last = (*along.end()).min((x + half).ceil() as i64);
                    for i in first..=last {
                        let (i, j, k) = (i as u32, j as u32, k as u32);
                        let centre = self.centre(i, j, k);
                        if centre.distance_squared(imp.at) > outside {
                            continue;
                        }
                        let d = centre.distance(imp.at) / imp.radius;
                        if d < 1.0 {
                            let w = (1.0 - d * d).powi(2);
                            let idx = self.index(i, j, k);
                            let v = &mut self.velocity[idx];
                            *v += (imp.velocity - *v) * w;
                        }
                    }
                }
            }
        }
        self.pending = pending;
        self.pending.clear();
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
        for _ in 0..PRESSURE_SWEEPS {
            let (p, div) = (&mut self.pressure, &self.divergence);
            for_each_cell(self.size, |idx, near| {
                let here = p[idx];
                // Neumann: no pressure gradient through a wall.
                let [l, r, d, u, b, f] = near.map(|n| n.map_or(here, |n| p[n]));
                p[idx] = (l + r + d + u + b + f - h * h * div[idx]) / 6.0;
            });
        }
        let (p, v) = (&self.pressure, &mut self.velocity);
        for_each_cell(self.size, |idx, near| {
            let here = p[idx];
            let [l, r, d, u, b, f] = near.map(|n| n.map_or(here, |n| p[n]));
            v[idx] -= Vec3::new(r - l, u - d, f - b) / (2.0 * h);
        });
        self.walls();
    }
}

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

    /// The pushes skip what is surely outside each ball, and nothing else: the water is
    /// the same, bit for bit, as from visiting the whole cube around it, for balls of
    /// every size, anywhere (across the walls and outside the tank too).
    #[test]
    fn pushes_reach_exactly_the_cells_in_their_balls() {
        let mut fast = tank();
        let mut every = tank();
        let mut state = 7u32;
        let mut next = || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1 << 24) as f32
        };
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
