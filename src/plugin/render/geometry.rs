//! A jellyfish's surfaces in world space, for picking, raycasts and colliders.
//!
//! With template meshes the drawn surface exists only on the GPU, so this builds it on the
//! CPU when asked (about a tenth of a millisecond for a moon jelly), from the same blended
//! state, resolution, seed and time the frame was drawn with; it is the CPU mesh the
//! template path is tested against.

use super::meshes::JellyfishMeshes;
use super::recorded::{DrawnTrails, drawn_view, shown_step};
use crate::plugin::interpolation::SliceHistory;
use crate::plugin::settings::JellyfishSettings;
use crate::plugin::slice::{JellyfishSlice, Tier};
use crate::shape::{JellyMesh, SurfaceBuffers, build_at};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;

/// Reads jellyfish geometry in any system:
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_jellyfish::Jellyfish;
/// use bevy_jellyfish::plugin::JellyfishGeometry;
///
/// fn report(geometry: JellyfishGeometry, jellyfish: Query<Entity, With<Jellyfish>>) {
///     for entity in &jellyfish {
///         if let Some(surfaces) = geometry.surfaces(entity) {
///             let apex = surfaces.umbrella.positions[0];
///             info!("{entity}: apex at {apex:?}");
///         }
///     }
/// }
/// ```
#[derive(SystemParam)]
pub struct JellyfishGeometry<'w, 's> {
    jellyfish: Query<
        'w,
        's,
        (
            &'static JellyfishSlice,
            &'static SliceHistory,
            &'static JellyfishMeshes,
            &'static GlobalTransform,
        ),
    >,
    settings: Res<'w, JellyfishSettings>,
}

/// One jellyfish's surfaces in world coordinates (the layout of
/// [`JellyMesh`]: positions, unit normals, UVs and triangles).
#[derive(Clone, Debug, Default)]
pub struct WorldSurfaces {
    /// The umbrella, world space.
    pub umbrella: SurfaceBuffers,
    /// The tentacles, then the manubrium and the oral arms; empty for a species without any.
    pub tentacles: SurfaceBuffers,
}

impl JellyfishGeometry<'_, '_> {
    /// The surfaces as drawn in the last frame (this frame's, from a system after
    /// [`JellyfishSystems::RebuildMeshes`](crate::plugin::JellyfishSystems)). `None` for an entity
    /// that is not a jellyfish or has not been drawn yet.
    pub fn surfaces(&self, entity: Entity) -> Option<WorldSurfaces> {
        let (slice, history, meshes, transform) = self.jellyfish.get(entity).ok()?;
        if !slice.started() {
            return None;
        }
        meshes.bounds?;
        // A far jellyfish's frame shows its recorded step as it is (see `rebuild`).
        let shown = match slice.tier() {
            Tier::Far => history.shown().map(|(a, b, t)| shown_step(a, b, t))?,
            _ => &meshes.blended,
        };
        let res = self.settings.resolution(&slice.species);
        let far = slice.tier() == Tier::Far;
        let mut trails = DrawnTrails::default();
        let view = drawn_view(shown, far, &slice.rest_bell, &res, &mut trails);
        let mut mesh = JellyMesh::new();
        let time = shown.time as f32;
        build_at(&mut mesh, &view, &slice.species, res, slice.seed, time).ok()?;
        let affine = transform.affine();
        let normal_matrix = affine.matrix3.inverse().transpose();
        for buffers in [&mut mesh.umbrella, &mut mesh.tentacles] {
            for p in &mut buffers.positions {
                *p = affine.transform_point3(Vec3::from_array(*p)).to_array();
            }
            for n in &mut buffers.normals {
                let world = normal_matrix * Vec3A::from_array(*n);
                *n = Vec3::from(world.normalize_or(Vec3A::Y)).to_array();
            }
        }
        Some(WorldSurfaces {
            umbrella: mesh.umbrella,
            tentacles: mesh.tentacles,
        })
    }

    /// A sphere around the whole jellyfish, tentacles included, in world space: centre
    /// and radius. Cheap (from the slice's bounds); `None` as for [`Self::surfaces`].
    pub fn bounding_sphere(&self, entity: Entity) -> Option<(Vec3, f32)> {
        let (_, _, meshes, transform) = self.jellyfish.get(entity).ok()?;
        let bounds = meshes.bounds?;
        let affine = transform.affine();
        let centre = affine.transform_point3a(bounds.center);
        // The largest scale of a rotation-and-scale (what transforms compose to).
        let m = affine.matrix3;
        let scale = m
            .x_axis
            .length()
            .max(m.y_axis.length())
            .max(m.z_axis.length());
        Some((centre.into(), bounds.half_extents.length() * scale))
    }
}
