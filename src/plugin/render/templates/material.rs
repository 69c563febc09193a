//! The template material: the jellyfish's `StandardMaterial` with a vertex shader that
//! shapes the template from the shape buffers, and the tissue layer's fragment shader.

use crate::plugin::render::tissue::{TISSUE_SHADER, Tissue};
use bevy::pbr::{ExtendedMaterial, MaterialExtension};
use bevy::prelude::*;
use bevy::render::render_resource::AsBindGroup;
use bevy::render::storage::ShaderBuffer;
use bevy::shader::ShaderRef;

/// The jellyfish look of [`bell_material`](crate::plugin::render::bell_material) with the
/// tissue layer, on template meshes and (where the device binds it) CPU meshes.
pub type SurfaceMaterial = ExtendedMaterial<StandardMaterial, SurfaceExtension>;

/// The shape buffers, bound for the vertex stage (bindings 100, 101 and 103), and the
/// tissue layer's uniform (binding 102). CPU meshes wear it too (tagged
/// [`CPU_MESH_TAG`](crate::plugin::render::CPU_MESH_TAG)).
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct SurfaceExtension {
    /// `u32` per slot: where its packed shape starts in `shapes`.
    #[storage(100, read_only, visibility(vertex))]
    pub offsets: Handle<ShaderBuffer>,
    /// Every jellyfish's packed shape, `f32`: a near one's block, a far one's own words
    /// and trails.
    #[storage(101, read_only, visibility(vertex))]
    pub shapes: Handle<ShaderBuffer>,
    /// The recorded steps far jellyfish show, `f32`: each frame written once.
    #[storage(103, read_only, visibility(vertex))]
    pub recorded: Handle<ShaderBuffer>,
    /// How the opacity follows the path, and the band.
    #[uniform(102)]
    pub tissue: Tissue,
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

    fn fragment_shader() -> ShaderRef {
        TISSUE_SHADER.into()
    }
}
