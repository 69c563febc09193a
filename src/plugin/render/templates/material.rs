//! The template material: the jellyfish's `StandardMaterial` with a vertex shader that
//! shapes the template from the shape buffers.

use bevy::pbr::{ExtendedMaterial, MaterialExtension};
use bevy::prelude::*;
use bevy::render::render_resource::AsBindGroup;
use bevy::render::storage::ShaderBuffer;
use bevy::shader::ShaderRef;

/// The jellyfish look of [`bell_material`](crate::plugin::render::bell_material) on a
/// template mesh.
pub type SurfaceMaterial = ExtendedMaterial<StandardMaterial, SurfaceExtension>;

/// The shape buffers, bound for the vertex stage (bindings 100 and 101).
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct SurfaceExtension {
    /// `u32` per slot: where its packed shape starts in `shapes`.
    #[storage(100, read_only, visibility(vertex))]
    pub offsets: Handle<ShaderBuffer>,
    /// Every jellyfish's packed shape, `f32`.
    #[storage(101, read_only, visibility(vertex))]
    pub shapes: Handle<ShaderBuffer>,
}

const SHADER: &str = "embedded://bevy_jellyfish/plugin/render/templates/surface.wgsl";

impl MaterialExtension for SurfaceExtension {
    fn vertex_shader() -> ShaderRef {
        SHADER.into()
    }

    fn prepass_vertex_shader() -> ShaderRef {
        SHADER.into()
    }

    fn deferred_vertex_shader() -> ShaderRef {
        SHADER.into()
    }
}
