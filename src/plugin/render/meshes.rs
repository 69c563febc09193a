//! What a jellyfish is drawn with: its meshes (the umbrella on the jellyfish itself, the
//! tentacles and the glow layer on its parts, `PartOf` it) and the path that builds them.

use super::recorded::{DrawnTrails, PackedCycle};
use crate::plugin::interpolation::Snapshot;
use crate::shape::packed::{self, ShapePacker};
use crate::shape::{JellyMesh, Resolution};
use bevy::prelude::*;

/// How this app draws jellyfish surfaces, resolved each frame from
/// [`JellyfishSettings::surfaces`](crate::plugin::JellyfishSettings::surfaces) and what
/// the device can do.
#[derive(Resource, Clone, Copy, Debug, PartialEq, Eq, Reflect)]
pub enum SurfacePath {
    /// Shared template meshes shaped on the GPU.
    Templates,
    /// Each jellyfish's own meshes, rebuilt on the CPU.
    CpuMeshes,
}

/// The jellyfish's meshes and what they are built from each frame.
///
/// The umbrella is the jellyfish entity's own `Mesh3d`; all tentacles are one mesh on a
/// child ([`JellyfishTentacles`]). With CPU meshes these are the jellyfish's own assets,
/// rebuilt every frame (despawning frees them); with templates (see
/// [`SurfaceMode`](crate::plugin::SurfaceMode)) they are shared by every jellyfish of the same
/// resolution and the vertex shader shapes them from the jellyfish's packed shape.
#[derive(Component, Default, Reflect)]
#[reflect(Component, Default)]
pub struct JellyfishMeshes {
    /// The umbrella's mesh, once set up.
    pub umbrella: Option<Handle<Mesh>>,
    /// The tentacles' mesh, once set up.
    pub tentacles: Option<Handle<Mesh>>,
    /// The entity drawing the tentacles, one of its parts ([`PartOf`](super::PartOf)).
    pub tentacle_entity: Option<Entity>,
    /// The entity drawing the umbrella's glow layer ([`JellyfishGlow`]), one of its parts.
    pub glow_entity: Option<Entity>,
    /// How it is drawn, once set up.
    pub(crate) path: Option<SurfacePath>,
    /// CPU meshes: the buffers the assets are rebuilt from.
    #[reflect(ignore)]
    pub(crate) buffers: JellyMesh,
    /// Templates: the packed shape (`shape::packed`) and the slot it is uploaded to.
    pub(crate) block: Vec<f32>,
    /// A far jellyfish's recorded cycle and the step of it shown, packed once for all
    /// that play it: `block` is then only its own words and trails, and the upload points
    /// it at that step's frame.
    #[reflect(ignore)]
    pub(crate) shared: Option<(std::sync::Arc<PackedCycle>, u32)>,
    /// A far jellyfish's instance, what the upload sends while `shared` is set: held here,
    /// not on the heap, so that ten thousand of them are written and read one after
    /// another, each frame.
    #[reflect(ignore)]
    pub(crate) instance: FarInstance,
    /// The thinned trail `instance` carries, and the guides it was packed for: while the
    /// step shown holds the same one, only the instance's own words are written again
    /// (the trail changes a few times a second, the words every frame).
    #[reflect(ignore)]
    pub(crate) instance_trail: Option<(std::sync::Arc<[Vec3]>, usize)>,
    #[reflect(ignore)]
    pub(crate) packer: ShapePacker,
    /// The trails as both paths draw them (`recorded::drawn_view`).
    #[reflect(ignore)]
    pub(crate) trails: DrawnTrails,
    pub(crate) slot: Option<u32>,
    /// The slice the frame shows, blended between the steps around its time (a far
    /// jellyfish's frame reads its recorded step in place instead, see `rebuild`).
    #[reflect(ignore)]
    pub(crate) blended: Snapshot,
    /// The topology the mesh assets were written with.
    #[reflect(ignore)]
    pub(crate) written: Option<Resolution>,
    /// Buffers hold a frame not yet copied to the assets.
    pub(crate) dirty: bool,
    /// The blended slice's bounds in the mesh's frame (see `render::culling`).
    pub(crate) bounds: Option<bevy::camera::primitives::Aabb>,
    /// Whether a camera saw it this frame (meshed) or not (skipped).
    pub(crate) seen: bool,
}

impl JellyfishMeshes {
    /// Whether the last frame meshed it: a camera saw it, or there is no camera.
    pub fn seen(&self) -> bool {
        self.seen
    }

    /// How its surfaces are built, once the plugin has set it up.
    pub fn path(&self) -> Option<SurfacePath> {
        self.path
    }
}

/// A far jellyfish's instance (`packed::pack_instance`: its own words, then its thinned
/// trail), in place.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FarInstance {
    words: [f32; packed::MAX_INSTANCE],
    len: usize,
}

impl FarInstance {
    pub(crate) fn words(&self) -> &[f32] {
        &self.words[..self.len]
    }

    pub(crate) fn words_mut(&mut self) -> &mut [f32] {
        &mut self.words[..self.len]
    }

    /// Holds `words`, an instance as `pack_instance` appends it.
    pub(crate) fn set(&mut self, words: &[f32]) {
        debug_assert!(
            words.len() <= packed::MAX_INSTANCE,
            "{} values",
            words.len()
        );
        self.len = words.len().min(packed::MAX_INSTANCE);
        self.words[..self.len].copy_from_slice(&words[..self.len]);
    }
}

/// The `MeshTag` of a jellyfish part drawn with a CPU mesh: the template material's
/// vertex shader then draws the mesh's own vertices, so both paths wear one material.
pub const CPU_MESH_TAG: u32 = u32::MAX;

const _: () = assert!(CPU_MESH_TAG as usize == crate::shape::packed::layout::CPU_MESH_TAG);

/// Marks the part ([`PartOf`](super::PartOf)) holding a jellyfish's tentacle mesh.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct JellyfishTentacles;

/// Marks the part that draws the umbrella a second time, additively: the glow
/// layer (see [`glow_material`](crate::plugin::render::glow_material)). It shares the umbrella's
/// mesh, so it costs a draw, not a mesh.
#[derive(Component, Clone, Copy, Debug, Default, Reflect)]
#[reflect(Component)]
pub struct JellyfishGlow;
