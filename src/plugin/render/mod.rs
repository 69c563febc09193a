//! Drawing jellyfish: each frame's surfaces built from the blended slice, on the CPU as
//! meshes of their own or on the GPU from shared templates ([`SurfacePath`]), bounded and
//! culled from the slice, and dressed in our two-layer material with its tissue layer.

mod culling;
mod flash;
mod geometry;
mod looks;
mod materials;
mod meshes;
mod parts;
mod patterns;
mod rebuild;
mod recorded;
mod resolutions;
mod templates;
mod tissue;

pub use flash::FLASH_SPREAD;
pub use geometry::{JellyfishGeometry, WorldSurfaces};
pub use looks::{
    GLOW_RADIANCE, GLOW_SORT_AHEAD, SpeciesMaterials, TENTACLE_SORT_OFFSET, bell_material,
    glow_material, glow_tissue, tentacle_material, tentacle_material_at,
};
pub use materials::JellyfishMaterialPlugin;
pub use meshes::{CPU_MESH_TAG, JellyfishGlow, JellyfishMeshes, JellyfishTentacles, SurfacePath};
pub use parts::{JellyfishParts, PartOf};
pub use patterns::{BellPatterns, PatternImages};
pub use templates::{ShapeBuffers, SurfaceExtension, SurfaceMaterial};
pub use tissue::Tissue;

use crate::plugin::jellyfish::Jellyfish;
use crate::plugin::schedule::JellyfishSystems;
use bevy::prelude::*;

/// Builds every jellyfish's surfaces each frame, on the path the settings and the device
/// allow, and keeps their bounds; [`JellyfishMaterialPlugin`] dresses them.
#[derive(Clone, Copy, Debug, Default)]
pub struct JellyfishRenderPlugin;

impl Plugin for JellyfishRenderPlugin {
    fn build(&self, app: &mut App) {
        app.register_required_components::<Jellyfish, JellyfishMeshes>()
            .register_type::<JellyfishMeshes>()
            .register_type::<JellyfishTentacles>()
            .register_type::<JellyfishGlow>()
            .init_resource::<recorded::RecordedFrames>()
            .add_systems(
                PostUpdate,
                (
                    templates::set_up,
                    rebuild::build_buffers,
                    rebuild::write_meshes,
                    templates::upload,
                )
                    .chain()
                    .in_set(JellyfishSystems::RebuildMeshes),
            )
            .add_systems(
                PostUpdate,
                (
                    parts::place_parts.in_set(JellyfishSystems::PlaceParts),
                    parts::show_parts.in_set(JellyfishSystems::ShowParts),
                ),
            );
        templates::build(app);
    }
}
