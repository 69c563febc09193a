//! The shape buffers: every templated jellyfish's packed shape, uploaded once a frame.
//!
//! Two storage buffers: `offsets[slot]` is where slot's block starts in `shapes`. A
//! jellyfish keeps its slot for life (its `MeshTag`), so jellyfish coming and going never
//! re-tag the others. The buffers grow by a quarter when they must, never shrink, and keep
//! their size between frames so Bevy writes them in place; a growth rebinds the materials.

use super::material::SurfaceMaterial;
use crate::plugin::render::meshes::{JellyfishMeshes, SurfacePath};
use crate::plugin::timings::JellyfishTimings;
use bevy::asset::RenderAssetUsages;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::render_resource::BufferUsages;
use bevy::render::storage::ShaderBuffer;
use std::time::Instant;

/// The storage buffers the template materials read.
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(Resource)]
pub struct ShapeBuffers {
    /// `u32` per slot: the start of its block in `shapes`.
    pub offsets: Handle<ShaderBuffer>,
    /// The packed shapes, `f32`.
    pub shapes: Handle<ShaderBuffer>,
    /// Sizes the buffers have now, in elements.
    capacity: (usize, usize),
}

impl ShapeBuffers {
    pub(super) fn new(assets: &mut Assets<ShaderBuffer>) -> Self {
        let capacity = (8, 512);
        Self {
            offsets: assets.add(buffer(vec![0; capacity.0 * 4])),
            shapes: assets.add(buffer(vec![0; capacity.1 * 4])),
            capacity,
        }
    }
}

fn buffer(bytes: Vec<u8>) -> ShaderBuffer {
    let mut b = ShaderBuffer::new(&bytes, RenderAssetUsages::RENDER_WORLD);
    b.buffer_description.usage = BufferUsages::STORAGE | BufferUsages::COPY_DST;
    b.buffer_description.label = Some("jellyfish shapes");
    b
}

/// Which jellyfish owns which slot.
#[derive(Resource, Default)]
pub(crate) struct SurfaceSlots {
    owner: HashMap<Entity, u32>,
    free: Vec<u32>,
    len: u32,
}

impl SurfaceSlots {
    /// The slot of `entity`, taking a free one the first time.
    pub(crate) fn take(&mut self, entity: Entity) -> u32 {
        if let Some(&slot) = self.owner.get(&entity) {
            return slot;
        }
        let slot = self.free.pop().unwrap_or_else(|| {
            self.len += 1;
            self.len - 1
        });
        self.owner.insert(entity, slot);
        slot
    }

    pub(crate) fn give_back(&mut self, entity: Entity) {
        if let Some(slot) = self.owner.remove(&entity) {
            self.free.push(slot);
        }
    }
}

/// Gathers the blocks into the two buffers and hands them to the renderer.
#[allow(clippy::too_many_arguments)]
pub(crate) fn upload(
    jellyfish: Query<&JellyfishMeshes>,
    slots: Res<SurfaceSlots>,
    buffers: Option<ResMut<ShapeBuffers>>,
    assets: Option<ResMut<Assets<ShaderBuffer>>>,
    materials: Option<ResMut<Assets<SurfaceMaterial>>>,
    timings: Res<JellyfishTimings>,
    mut offsets: Local<Vec<u32>>,
) {
    let (Some(mut buffers), Some(mut assets)) = (buffers, assets) else {
        return;
    };
    let start = Instant::now();
    offsets.clear();
    offsets.resize(slots.len as usize, 0);
    // Gathered straight into the bytes handed to the renderer (each frame's go to the
    // render world): one copy of a few megabytes a frame, not two.
    let mut shapes: Vec<u8> = Vec::with_capacity(4 * buffers.capacity.1);
    for meshes in &jellyfish {
        if meshes.path == Some(SurfacePath::Templates)
            && let Some(slot) = meshes.slot
            && !meshes.block.is_empty()
        {
            offsets[slot as usize] = (shapes.len() / 4) as u32;
            extend_words(&mut shapes, &meshes.block);
        }
    }
    if shapes.is_empty() {
        return;
    }
    let grow = |needed: usize, now: usize| {
        if needed > now {
            needed + needed / 4
        } else {
            now
        }
    };
    let capacity = (
        grow(offsets.len(), buffers.capacity.0),
        grow(shapes.len() / 4, buffers.capacity.1),
    );
    let grown = capacity != buffers.capacity;
    buffers.capacity = capacity;
    offsets.resize(capacity.0, 0);
    shapes.resize(4 * capacity.1, 0);
    let mut offset_bytes = Vec::with_capacity(4 * offsets.len());
    extend_words(
        &mut offset_bytes,
        bytemuck::cast_slice::<u32, f32>(&offsets),
    );
    let written = [(&buffers.offsets, offset_bytes), (&buffers.shapes, shapes)];
    let mut total = 0;
    for (handle, data) in written {
        total += data.len();
        if let Some(mut buffer) = assets.get_mut(handle) {
            if grown {
                buffer.buffer_description.size = data.len() as u64;
            }
            buffer.data = Some(data);
        }
    }
    // A grown buffer is a new GPU buffer: rebuild the materials' bind groups.
    if grown && let Some(mut materials) = materials {
        let ids: Vec<_> = materials.ids().collect();
        for id in ids {
            materials.get_mut(id);
        }
    }
    timings.add_mesh_bytes(total);
    timings.add_meshing(start.elapsed());
}

/// Appends `words` as the GPU reads them, little-endian: on such a host, the memory as is.
fn extend_words(bytes: &mut Vec<u8>, words: &[f32]) {
    if cfg!(target_endian = "little") {
        bytes.extend_from_slice(bytemuck::cast_slice(words));
    } else {
        bytes.extend(words.iter().flat_map(|w| w.to_bits().to_le_bytes()));
    }
}
