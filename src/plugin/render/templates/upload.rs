//! The shape buffers: every templated jellyfish's packed shape, uploaded once a frame.
//!
//! Two storage buffers: `offsets[slot]` is where slot's block starts in `shapes`. A
//! jellyfish keeps its slot for life (its `MeshTag`), so jellyfish coming and going never
//! re-tag the others. Far jellyfish showing the same recorded step share its rings and
//! discs, written once; each block's `H_BODY` and `H_TRAILS` say where its rings and trails
//! start in `shapes`. The buffers grow by a quarter when they must, shrink when less than
//! half used (far jellyfish need far less than near ones), and otherwise keep their size
//! between frames so Bevy writes them in place; a new size rebinds the materials.

use super::material::SurfaceMaterial;
use crate::plugin::render::meshes::{JellyfishMeshes, SurfacePath};
use crate::plugin::timings::JellyfishTimings;
use crate::shape::packed::{
    self,
    layout::{H_BODY, H_TRAILS, HEADER},
};
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
    mut bodies: Local<HashMap<usize, u32>>,
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
    bodies.clear();
    for meshes in &jellyfish {
        if meshes.path == Some(SurfacePath::Templates)
            && let Some(slot) = meshes.slot
            && !meshes.block.is_empty()
        {
            // A far jellyfish's recorded step: its rings and discs once for all.
            let body = meshes.shared.as_ref().map(|frame| {
                *bodies.entry(frame.as_ptr() as usize).or_insert_with(|| {
                    let at = (shapes.len() / 4) as u32;
                    extend_words(&mut shapes, packed::body(frame));
                    at
                })
            });
            let start = (shapes.len() / 4) as u32;
            offsets[slot as usize] = start;
            extend_words(&mut shapes, &meshes.block);
            // Where its rings and trails start, from the buffer's start.
            let word = |at: usize| meshes.block[at].to_bits();
            let (rings, trails) = match body {
                Some(body) => (body, start + HEADER as u32),
                None => (start + word(H_BODY), start + word(H_TRAILS)),
            };
            set_word(&mut shapes, start as usize + H_BODY, rings);
            set_word(&mut shapes, start as usize + H_TRAILS, trails);
        }
    }
    if shapes.is_empty() {
        return;
    }
    // Room for a quarter more than needed; kept while it is at least half used.
    let grow = |needed: usize, now: usize| {
        if needed > now || 2 * needed < now {
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
    // A resized buffer is a new GPU buffer: rebuild the materials' bind groups.
    if grown && let Some(mut materials) = materials {
        let ids: Vec<_> = materials.ids().collect();
        for id in ids {
            materials.get_mut(id);
        }
    }
    timings.add_mesh_bytes(total);
    timings.add_meshing(start.elapsed());
}

/// Sets word `at` of `bytes` to `value`, as the GPU reads it.
fn set_word(bytes: &mut [u8], at: usize, value: u32) {
    bytes[4 * at..4 * at + 4].copy_from_slice(&value.to_le_bytes());
}

/// Appends `words` as the GPU reads them, little-endian: on such a host, the memory as is.
fn extend_words(bytes: &mut Vec<u8>, words: &[f32]) {
    if cfg!(target_endian = "little") {
        bytes.extend_from_slice(bytemuck::cast_slice(words));
    } else {
        bytes.extend(words.iter().flat_map(|w| w.to_bits().to_le_bytes()));
    }
}
