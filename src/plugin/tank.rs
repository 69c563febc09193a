//! [`TankWater`]: a coarse 3D stable-fluids grid over a box (a tank), stirred by the game
//! and by the jellyfish's own jets, that becomes the [`AmbientWater`] every jellyfish
//! swims in.
//!
//! One step per fixed tick, Stam's recipe on cell-centred velocities: apply the stirs and
//! the jets gathered since the last tick, advect (semi-Lagrangian), let the water slowly
//! come to rest, and project (Gauss–Seidel on the pressure, closed free-slip walls).
//! Everything is summed in a fixed order (jets by entity), so a replay is the same water.

use super::water::{AmbientWater, SampledWater};
use bevy::prelude::*;

/// Gauss–Seidel sweeps of the pressure solve: the grid is coarse and the water slow, and
/// what is left of the divergence is damped away within a few ticks.
const PRESSURE_SWEEPS: usize = 20;

/// The tank's water, as a game adds it: `app.insert_resource(TankWater::new(min, max, cell))`.
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(Resource)]
pub struct TankWater {
    /// The tank's lower corner, world.
    pub min: Vec3,
    /// Cell size, world units.
    pub cell: f32,
    /// Cells along x, y, z.
    pub size: UVec3,
    /// How quickly the water comes back to rest, 1/s.
    pub damping: f32,
    /// How much of a jellyfish's surge speed its jet gives the water behind it (0: the
    /// jellyfish do not stir the water).
    pub jet_strength: f32,
    velocity: Vec<Vec3>,
    scratch: Vec<Vec3>,
    pressure: Vec<f32>,
    divergence: Vec<f32>,
    pending: Vec<Impulse>,
}

/// A push given to the water: within `radius` of `at`, towards `velocity` (world units
/// per second), smoothly less towards the edge.
#[derive(Clone, Copy, Debug, PartialEq, Reflect)]
pub struct Impulse {
    /// Centre, world.
    pub at: Vec3,
    /// Reach, world units.
    pub radius: f32,
    /// Velocity given at the centre, world units per second.
    pub velocity: Vec3,
}

impl TankWater {
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
            jet_strength: 0.5,
            velocity: vec![Vec3::ZERO; count],
            scratch: vec![Vec3::ZERO; count],
            pressure: vec![0.0; count],
            divergence: vec![0.0; count],
            pending: Vec::new(),
        }
    }

    /// Pushes the water at `at` (world) within `radius` towards `velocity`; applied at
    /// the next tick.
    pub fn stir(&mut self, at: Vec3, radius: f32, velocity: Vec3) {
        if at.is_finite() && velocity.is_finite() && radius > 0.0 {
            self.pending.push(Impulse {
                at,
                radius,
                velocity,
            });
        }
    }

    fn index(&self, i: u32, j: u32, k: u32) -> usize {
        ((k * self.size.y + j) * self.size.x + i) as usize
    }

    fn centre(&self, i: u32, j: u32, k: u32) -> Vec3 {
        self.min + (Vec3::new(i as f32, j as f32, k as f32) + 0.5) * self.cell
    }

    /// The water's velocity at a world point (trilinear; held at the walls).
    pub fn velocity_at(&self, point: Vec3) -> Vec3 {
        self.sampled().velocity_of(&self.velocity, point)
    }

    fn sampled(&self) -> Grid {
        Grid {
            origin: self.min + Vec3::splat(0.5 * self.cell),
            cell: self.cell,
            size: self.size,
        }
    }

    /// The water as a field for the jellyfish.
    pub fn snapshot(&self) -> SampledWater {
        SampledWater {
            origin: self.min + Vec3::splat(0.5 * self.cell),
            spacing: self.cell,
            size: self.size,
            velocities: self.velocity.clone(),
        }
    }

    /// Largest speed in the tank, world units per second.
    pub fn speed_max(&self) -> f32 {
        self.velocity.iter().map(|v| v.length()).fold(0.0, f32::max)
    }

    /// One tick: pushes, advection, rest, projection.
    pub fn step(&mut self, dt: f32) {
        if dt.is_nan() || dt <= 0.0 {
            return;
        }
        self.push();
        self.advect(dt);
        let keep = 1.0 / (1.0 + self.damping * dt);
        self.velocity.iter_mut().for_each(|v| *v *= keep);
        self.walls();
        self.project();
    }

    /// Applies the pending impulses, in the order they came.
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
        let grid = self.sampled();
        let s = self.size;
        for k in 0..s.z {
            for j in 0..s.y {
                for i in 0..s.x {
                    let idx = self.index(i, j, k);
                    let back = self.centre(i, j, k) - self.velocity[idx] * dt;
                    self.scratch[idx] = grid.velocity_of(&self.velocity, back);
                }
            }
        }
        std::mem::swap(&mut self.velocity, &mut self.scratch);
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

    fn project(&mut self) {
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
                    self.pressure[idx] = 0.0;
                }
            }
        }
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

/// Trilinear sampling on cell centres, held at the edges.
struct Grid {
    origin: Vec3,
    cell: f32,
    size: UVec3,
}

impl Grid {
    fn velocity_of(&self, field: &[Vec3], point: Vec3) -> Vec3 {
        let s = self.size;
        let g = ((point - self.origin) / self.cell).clamp(Vec3::ZERO, (s - 1).as_vec3());
        let g = if g.is_finite() { g } else { Vec3::ZERO };
        let i0 = g.floor().as_uvec3().min(s - 1);
        let i1 = (i0 + 1).min(s - 1);
        let f = g - i0.as_vec3();
        let at = |i: u32, j: u32, k: u32| field[((k * s.y + j) * s.x + i) as usize];
        let lerp = |a: Vec3, b: Vec3, t: f32| a + (b - a) * t;
        let x00 = lerp(at(i0.x, i0.y, i0.z), at(i1.x, i0.y, i0.z), f.x);
        let x10 = lerp(at(i0.x, i1.y, i0.z), at(i1.x, i1.y, i0.z), f.x);
        let x01 = lerp(at(i0.x, i0.y, i1.z), at(i1.x, i0.y, i1.z), f.x);
        let x11 = lerp(at(i0.x, i1.y, i1.z), at(i1.x, i1.y, i1.z), f.x);
        lerp(lerp(x00, x10, f.y), lerp(x01, x11, f.y), f.z)
    }
}

/// Steps the tank (if the app has one) and hands it to the jellyfish as their water.
pub(super) fn step_tank(
    tank: Option<ResMut<TankWater>>,
    mut ambient: ResMut<AmbientWater>,
    time: Res<Time<Fixed>>,
    timings: Res<super::diagnostics::JellyfishTimings>,
) {
    let Some(mut tank) = tank else {
        return;
    };
    let start = std::time::Instant::now();
    tank.step(time.delta_secs());
    *ambient = AmbientWater::field(tank.snapshot());
    timings.add_water(start.elapsed());
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tank() -> TankWater {
        TankWater::new(Vec3::new(-4.0, 0.0, -4.0), Vec3::new(4.0, 8.0, 4.0), 0.5)
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

    #[test]
    fn the_same_stirs_give_the_same_water() {
        let run = || {
            let mut t = tank();
            for n in 0..20 {
                t.stir(Vec3::new(0.1 * n as f32, 3.0, 0.0), 1.0, Vec3::Y);
                t.step(1.0 / 64.0);
            }
            t.velocity.clone()
        };
        assert_eq!(run(), run());
    }
}
