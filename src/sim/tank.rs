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
        for imp in &pending {
            let reach = ((imp.radius / self.cell).ceil() as i64 + 1).max(1);
            let c = ((imp.at - self.min) / self.cell).floor().as_ivec3();
            for k in c.z as i64 - reach..=c.z as i64 + reach {
                for j in c.y as i64 - reach..=c.y as i64 + reach {
                    for i in c.x as i64 - reach..=c.x as i64 + reach {
                        let s = self.size.as_i64vec3();
                        if i < 0 || j < 0 || k < 0 || i >= s.x || j >= s.y || k >= s.z {
                            continue;
                        }
                        let (i, j, k) = (i as u32, j as u32, k as u32);
                        let d = self.centre(i, j, k).distance(imp.at) / imp.radius;
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
        for k in 0..s.z {
            for j in 0..s.y {
                for i in 0..s.x {
                    let idx = self.index(i, j, k);
                    let v = &mut self.velocity[idx];
                    if i == 0 || i == s.x - 1 {
                        v.x = 0.0;
                    }
                    if j == 0 || j == s.y - 1 {
                        v.y = 0.0;
                    }
                    if k == 0 || k == s.z - 1 {
                        v.z = 0.0;
                    }
                }
            }
        }
    }

    /// The divergence of the velocity at every cell (central differences, no flow through
    /// the walls), into `self.divergence`.
    fn measure_divergence(&mut self) {
        let s = self.size;
        let h = self.cell;
        let at = |v: &[Vec3], i: i64, j: i64, k: i64| -> Vec3 {
            if i < 0 || j < 0 || k < 0 || i >= s.x as i64 || j >= s.y as i64 || k >= s.z as i64 {
                Vec3::ZERO
            } else {
                v[((k as u32 * s.y + j as u32) * s.x + i as u32) as usize]
            }
        };
        for k in 0..s.z as i64 {
            for j in 0..s.y as i64 {
                for i in 0..s.x as i64 {
                    let v = &self.velocity;
                    let div = (at(v, i + 1, j, k).x - at(v, i - 1, j, k).x + at(v, i, j + 1, k).y
                        - at(v, i, j - 1, k).y
                        + at(v, i, j, k + 1).z
                        - at(v, i, j, k - 1).z)
                        / (2.0 * h);
                    let idx = self.index(i as u32, j as u32, k as u32);
                    self.divergence[idx] = div;
                }
            }
        }
    }

    /// Removes the divergent part: solves for the pressure and subtracts its gradient.
    fn project(&mut self) {
        let s = self.size;
        let h = self.cell;
        self.measure_divergence();
        self.pressure.iter_mut().for_each(|p| *p = 0.0);
        let p_at = |p: &[f32], i: i64, j: i64, k: i64, here: f32| -> f32 {
            if i < 0 || j < 0 || k < 0 || i >= s.x as i64 || j >= s.y as i64 || k >= s.z as i64 {
                here // Neumann: no pressure gradient through a wall.
            } else {
                p[((k as u32 * s.y + j as u32) * s.x + i as u32) as usize]
            }
        };
        for _ in 0..PRESSURE_SWEEPS {
            for k in 0..s.z as i64 {
                for j in 0..s.y as i64 {
                    for i in 0..s.x as i64 {
                        let idx = self.index(i as u32, j as u32, k as u32);
                        let here = self.pressure[idx];
                        let p = &self.pressure;
                        let sum = p_at(p, i - 1, j, k, here)
                            + p_at(p, i + 1, j, k, here)
                            + p_at(p, i, j - 1, k, here)
                            + p_at(p, i, j + 1, k, here)
                            + p_at(p, i, j, k - 1, here)
                            + p_at(p, i, j, k + 1, here);
                        self.pressure[idx] = (sum - h * h * self.divergence[idx]) / 6.0;
                    }
                }
            }
        }
        for k in 0..s.z as i64 {
            for j in 0..s.y as i64 {
                for i in 0..s.x as i64 {
                    let idx = self.index(i as u32, j as u32, k as u32);
                    let p = &self.pressure;
                    let here = p[idx];
                    let grad = Vec3::new(
                        p_at(p, i + 1, j, k, here) - p_at(p, i - 1, j, k, here),
                        p_at(p, i, j + 1, k, here) - p_at(p, i, j - 1, k, here),
                        p_at(p, i, j, k + 1, here) - p_at(p, i, j, k - 1, here),
                    ) / (2.0 * h);
                    self.velocity[idx] -= grad;
                }
            }
        }
        self.walls();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tank() -> TankFluid {
        TankFluid::new(Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 8.0, 4.0), 0.5)
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
