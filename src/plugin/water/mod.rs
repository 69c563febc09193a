//! The water a game puts its jellyfish in: [`AmbientWater`], a velocity at every point and
//! time, in world units per second (the units of the jellyfish's `Transform`).
//!
//! A jellyfish's ground velocity is the water's velocity at its bell plus its own swimming
//! relative to that water (what its slice computes), so a uniform current adds exactly
//! itself; it is turned by half the local vorticity (a small body in a shear spins with
//! the fluid). The slice keeps simulating the water around the bell in the bell's own
//! frame: shear along the axis is not fed into it as inflow.

use crate::sim::trilinear::Trilinear;
use bevy::prelude::*;
use std::sync::Arc;

/// The water every jellyfish swims in: inserts still [`AmbientWater`] unless the app has
/// its own.
#[derive(Clone, Copy, Debug, Default)]
pub struct WaterPlugin;

impl Plugin for WaterPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<AmbientWater>()
            .register_type::<AmbientWater>();
    }
}

/// A velocity field in world units per second.
pub trait WaterField: Send + Sync + 'static {
    /// The water's velocity at `point` (world) at `time` (s of `Time<Virtual>`: the
    /// stepping reads it at the end of each slice step).
    fn velocity(&self, point: Vec3, time: f64) -> Vec3;

    /// The vorticity (curl) at `point`, 1/s: by central differences `spacing` apart, unless
    /// the field knows better.
    fn vorticity(&self, point: Vec3, time: f64, spacing: f32) -> Vec3 {
        let d = spacing.max(1e-6);
        let at = |o: Vec3| self.velocity(point + o, time);
        let (dx, dy, dz) = (Vec3::X * d, Vec3::Y * d, Vec3::Z * d);
        let (vx, vy, vz) = (at(dx) - at(-dx), at(dy) - at(-dy), at(dz) - at(-dz));
        Vec3::new(vy.z - vz.y, vz.x - vx.z, vx.y - vy.x) / (2.0 * d)
    }
}

/// The water every jellyfish swims in: still by default. Insert your own:
///
/// ```
/// use bevy::prelude::*;
/// use bevy_jellyfish::plugin::AmbientWater;
/// let mut app = App::new();
/// // A current of half a unit per second along +x.
/// app.insert_resource(AmbientWater::uniform(Vec3::new(0.5, 0.0, 0.0)));
/// // Or any function of place and time: a gentle swirl about the y axis.
/// app.insert_resource(AmbientWater::from_fn(|p, _t| Vec3::new(-p.z, 0.0, p.x) * 0.1));
/// ```
#[derive(Resource, Clone, Reflect)]
#[reflect(opaque, Resource, Default)]
pub struct AmbientWater(pub Arc<dyn WaterField>);

impl Default for AmbientWater {
    fn default() -> Self {
        Self::still()
    }
}

impl AmbientWater {
    /// No current anywhere.
    pub fn still() -> Self {
        Self::uniform(Vec3::ZERO)
    }

    /// The same current everywhere, world units per second.
    pub fn uniform(velocity: Vec3) -> Self {
        Self(Arc::new(Uniform(velocity)))
    }

    /// A field given by a function of place (world) and time (s).
    pub fn from_fn(f: impl Fn(Vec3, f64) -> Vec3 + Send + Sync + 'static) -> Self {
        Self(Arc::new(FromFn(f)))
    }

    /// Any [`WaterField`] (a sampled grid, a simulation of your own).
    pub fn field(field: impl WaterField) -> Self {
        Self(Arc::new(field))
    }

    /// The water's velocity at `point` (world) at `time` (seconds of virtual time).
    pub fn velocity(&self, point: Vec3, time: f64) -> Vec3 {
        self.0.velocity(point, time)
    }
}

struct Uniform(Vec3);

impl WaterField for Uniform {
    fn velocity(&self, _: Vec3, _: f64) -> Vec3 {
        self.0
    }

    fn vorticity(&self, _: Vec3, _: f64, _: f32) -> Vec3 {
        Vec3::ZERO
    }
}

struct FromFn<F>(F);

impl<F: Fn(Vec3, f64) -> Vec3 + Send + Sync + 'static> WaterField for FromFn<F> {
    fn velocity(&self, point: Vec3, time: f64) -> Vec3 {
        (self.0)(point, time)
    }
}

/// Velocities sampled on a regular grid (cell centres), trilinear between them and held
/// at the edges: for currents baked by a tool or a simulation of the game's own.
#[derive(Clone, Debug, Reflect)]
pub struct SampledWater {
    /// World position of the first sample.
    pub origin: Vec3,
    /// Distance between samples, world units.
    pub spacing: f32,
    /// Samples along x, y, z.
    pub size: UVec3,
    /// `size.x · size.y · size.z` velocities, x fastest, then y, then z.
    pub velocities: Vec<Vec3>,
}

impl SampledWater {
    fn grid(&self) -> Trilinear {
        Trilinear {
            origin: self.origin,
            spacing: self.spacing,
            size: self.size,
        }
    }
}

impl WaterField for SampledWater {
    fn velocity(&self, point: Vec3, _: f64) -> Vec3 {
        self.grid().sample(&self.velocities, point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rigid_rotation_has_twice_its_rate_as_vorticity() {
        let omega = 0.3;
        let water = AmbientWater::from_fn(move |p, _| Vec3::new(-p.z, 0.0, p.x) * omega);
        let w = water.0.vorticity(Vec3::new(1.0, 2.0, 3.0), 0.0, 0.1);
        // u = ω ŷ × r, curl u = 2ω ŷ... with this handedness, −2ω ŷ.
        assert!(
            (w - Vec3::new(0.0, -2.0 * omega, 0.0)).length() < 1e-4,
            "{w}"
        );
        assert_eq!(
            AmbientWater::uniform(Vec3::X)
                .0
                .vorticity(Vec3::ZERO, 0.0, 1.0),
            Vec3::ZERO
        );
    }

    #[test]
    fn a_sampled_grid_interpolates_and_holds_at_its_edges() {
        let grid = SampledWater {
            origin: Vec3::ZERO,
            spacing: 1.0,
            size: UVec3::new(2, 2, 2),
            velocities: (0..8).map(|k| Vec3::splat((k & 1) as f32)).collect(),
        };
        assert_eq!(
            grid.velocity(Vec3::new(0.25, 0.5, 0.5), 0.0),
            Vec3::splat(0.25)
        );
        assert_eq!(grid.velocity(Vec3::new(5.0, 0.0, 0.0), 0.0), Vec3::ONE);
        assert_eq!(grid.velocity(Vec3::NAN, 0.0), Vec3::ZERO);
    }
}
