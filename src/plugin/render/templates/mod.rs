//! Template meshes: each jellyfish sends its shape, the GPU builds the surface.
//!
//! A full jellyfish mesh is thousands of vertices rebuilt and re-uploaded every frame; what
//! makes it is a few kilobytes (`shape::packed`). So with [`SurfacePath::Templates`] every
//! jellyfish of a resolution draws the same template mesh, its [`MeshTag`] picks its slot
//! in one storage buffer of packed shapes, and the vertex shader (`surface.wgsl`, also
//! used for the prepass and shadows) places each vertex. CPU meshes remain: they are the
//! reference the shader is tested against, the fallback where a device cannot read storage
//! buffers in vertex shaders (WebGL2), what a custom `StandardMaterial` needs, and what
//! [`JellyfishGeometry`](crate::plugin::JellyfishGeometry) gives for picking and colliders.
//!
//! [`MeshTag`]: bevy::mesh::MeshTag

mod material;
mod packed_layout;
mod setup;
mod upload;

pub use material::{SurfaceExtension, SurfaceMaterial};
pub use upload::ShapeBuffers;

pub(super) use setup::set_up;
pub(super) use upload::upload;

use super::meshes::SurfacePath;
use crate::plugin::schedule::JellyfishSystems;
use crate::plugin::settings::{JellyfishSettings, SurfaceMode};
use bevy::pbr::PbrPlugin;
use bevy::prelude::*;
use bevy::render::render_resource::DownlevelFlags;
use bevy::render::renderer::{RenderAdapter, RenderDevice};
use bevy::render::storage::ShaderBuffer;

/// The shader, the shared meshes and the slots; each frame's path.
pub(super) fn build(app: &mut App) {
    // Only where the app renders; add the plugins after `DefaultPlugins`.
    if app.is_plugin_added::<PbrPlugin>() {
        bevy::asset::embedded_asset!(app, "surface.wgsl");
        packed_layout::add(app);
    }
    app.init_resource::<setup::Templates>()
        .init_resource::<upload::SurfaceSlots>()
        .register_type::<ShapeBuffers>()
        .register_type::<SurfacePath>()
        .add_systems(PreUpdate, resolve_path.in_set(JellyfishSystems::Prepare));
}

/// Whether a device can read the shape buffers in its vertex shaders.
pub(crate) fn device_supports_templates(device: &RenderDevice, adapter: &RenderAdapter) -> bool {
    adapter
        .get_downlevel_capabilities()
        .flags
        .contains(DownlevelFlags::VERTEX_STORAGE)
        && device.limits().max_storage_buffers_per_shader_stage >= 3
}

#[allow(clippy::too_many_arguments)]
fn resolve_path(
    mut commands: Commands,
    settings: Res<JellyfishSettings>,
    current: Option<Res<SurfacePath>>,
    device: Option<Res<RenderDevice>>,
    adapter: Option<Res<RenderAdapter>>,
    materials: Option<Res<Assets<SurfaceMaterial>>>,
    mut buffers: Option<ResMut<Assets<ShaderBuffer>>>,
    shapes: Option<Res<ShapeBuffers>>,
) {
    let supported = match (device, adapter) {
        (Some(d), Some(a)) => Some(device_supports_templates(&d, &a)),
        _ => None,
    };
    let path = match settings.surfaces {
        SurfaceMode::CpuMeshes => SurfacePath::CpuMeshes,
        SurfaceMode::Auto if supported == Some(true) && materials.is_some() => {
            SurfacePath::Templates
        }
        SurfaceMode::Auto => SurfacePath::CpuMeshes,
        SurfaceMode::Templates if supported == Some(false) || buffers.is_none() => {
            warn_once!(
                "jellyfish: template surfaces need storage buffers in vertex shaders (and \
                 Assets<ShaderBuffer>); drawing CPU meshes instead"
            );
            SurfacePath::CpuMeshes
        }
        SurfaceMode::Templates => SurfacePath::Templates,
    };
    // CPU meshes wear the template material too where the device can bind it.
    let bound = supported == Some(true) && materials.is_some();
    if (path == SurfacePath::Templates || bound)
        && shapes.is_none()
        && let Some(buffers) = buffers.as_deref_mut()
    {
        commands.insert_resource(ShapeBuffers::new(buffers));
    }
    if current.as_deref() != Some(&path) {
        commands.insert_resource(path);
    }
}
