//! The shape buffers: every templated jellyfish's packed shape.
//!
//! Three storage buffers. `offsets[slot]` is where slot's words start in `shapes`. A
//! jellyfish keeps its slot for life (its `MeshTag`), so jellyfish coming and going never
//! re-tag the others. `shapes`, written every frame, holds a near jellyfish's whole block
//! and a far one's own words and trails (`shape::packed::pack_instance`, 16 values).
//! `recorded` holds the frames of every step of the recorded cycles far jellyfish play,
//! uploaded only when a cycle is new (a species' first far jellyfish, or after an edit
//! records its stroke again); each block's `H_FRAME` says where its frame starts, and in
//! which buffer. The buffers grow by a quarter when they must, shrink when less than half
//! used, and otherwise keep their size between frames so Bevy writes them in place; a new
//! size rebinds the materials.

use super::material::SurfaceMaterial;
use crate::plugin::render::meshes::{JellyfishMeshes, SurfacePath};
use crate::plugin::render::recorded::PackedCycle;
use crate::plugin::timings::JellyfishTimings;
use crate::shape::packed::layout::{H_FRAME, RECORDED_FRAME};
use bevy::asset::RenderAssetUsages;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::render_resource::BufferUsages;
use bevy::render::storage::ShaderBuffer;
use std::sync::Arc;
use std::time::Instant;

/// The storage buffers the template materials read.
#[derive(Resource, Clone, Debug, Reflect)]
#[reflect(Resource)]
pub struct ShapeBuffers {
    /// `u32` per slot: the start of its block in `shapes`.
    pub offsets: Handle<ShaderBuffer>,
    /// The packed shapes, `f32`.
    pub shapes: Handle<ShaderBuffer>,
    /// The recorded steps' frames, `f32`.
    pub recorded: Handle<ShaderBuffer>,
    /// Sizes the buffers have now, in elements.
    capacity: [usize; 3],
}

impl ShapeBuffers {
    pub(super) fn new(assets: &mut Assets<ShaderBuffer>) -> Self {
        let capacity = [8, 512, 512];
        Self {
            offsets: assets.add(buffer(vec![0; capacity[0] * 4])),
            shapes: assets.add(buffer(vec![0; capacity[1] * 4])),
            recorded: assets.add(buffer(vec![0; capacity[2] * 4])),
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

/// The recorded buffer's contents: each recorded cycle far jellyfish play, its steps'
/// frames written together once.
#[derive(Default)]
pub(crate) struct RecordedLayout {
    /// Each cycle by address, held so that no other cycle takes its address: where its
    /// frames start in `words`, and the last frame that drew from it.
    base: HashMap<usize, (Arc<PackedCycle>, u32, u64)>,
    words: Vec<f32>,
    /// Whether `words` changed since it was last uploaded.
    changed: bool,
    /// Frames counted.
    frame: u64,
}

/// Frames a cycle stays in the recorded buffer without a far jellyfish playing it.
const UNPLAYED_FRAMES: u64 = 60;

impl RecordedLayout {
    /// Where step `index` of `cycle` starts, the cycle written the first time.
    fn start(&mut self, cycle: &Arc<PackedCycle>, index: u32) -> u32 {
        let key = Arc::as_ptr(cycle) as usize;
        let frame = self.frame;
        let base = match self.base.get_mut(&key) {
            Some((_, base, used)) => {
                *used = frame;
                *base
            }
            None => {
                let base = self.words.len() as u32;
                self.words.extend_from_slice(&cycle.frames);
                self.base.insert(key, (cycle.clone(), base, frame));
                self.changed = true;
                base
            }
        };
        base + cycle.start(index).unwrap_or(0)
    }

    /// A new frame; starts again, empty, once a cycle has gone unplayed for
    /// [`UNPLAYED_FRAMES`] (a species edited and recorded again, another resolution, no
    /// far jellyfish of it any more): the cycles still played are written again.
    fn next_frame(&mut self) {
        self.frame += 1;
        let frame = self.frame;
        if self
            .base
            .values()
            .any(|(.., used)| frame - used > UNPLAYED_FRAMES)
        {
            *self = Self {
                frame,
                ..Self::default()
            };
        }
    }
}

/// Gathers the blocks into the buffers and hands them to the renderer.
#[allow(clippy::too_many_arguments)]
pub(crate) fn upload(
    jellyfish: Query<&JellyfishMeshes>,
    slots: Res<SurfaceSlots>,
    buffers: Option<ResMut<ShapeBuffers>>,
    assets: Option<ResMut<Assets<ShaderBuffer>>>,
    materials: Option<ResMut<Assets<SurfaceMaterial>>>,
    timings: Res<JellyfishTimings>,
    mut offsets: Local<Vec<u32>>,
    mut recorded: Local<RecordedLayout>,
) {
    let (Some(mut buffers), Some(mut assets)) = (buffers, assets) else {
        return;
    };
    let start = Instant::now();
    offsets.clear();
    offsets.resize(slots.len as usize, 0);
    // Gathered straight into the bytes handed to the renderer (each frame's go to the
    // render world): one copy a frame, not two.
    let mut shapes: Vec<u8> = Vec::with_capacity(4 * buffers.capacity[1]);
    recorded.next_frame();
    for meshes in &jellyfish {
        if meshes.path == Some(SurfacePath::Templates)
            && let Some(slot) = meshes.slot
            && !meshes.block.is_empty()
        {
            let start = (shapes.len() / 4) as u32;
            offsets[slot as usize] = start;
            // A far jellyfish sends its instance, its frame its recorded step's in the
            // recorded buffer.
            let frame = match &meshes.shared {
                Some((cycle, index)) => {
                    extend_words(&mut shapes, meshes.instance.words());
                    RECORDED_FRAME as u32 | recorded.start(cycle, *index)
                }
                None => {
                    extend_words(&mut shapes, &meshes.block);
                    start
                }
            };
            set_word(&mut shapes, start as usize + H_FRAME, frame);
        }
    }
    if shapes.is_empty() {
        return;
    }
    // Room for a quarter more than needed; kept while it is at least half used. Never
    // empty: a buffer bound is at least a value long.
    let grow = |needed: usize, now: usize| {
        let needed = needed.max(64);
        if needed > now || 2 * needed < now {
            needed + needed / 4
        } else {
            now
        }
    };
    let needed = [offsets.len(), shapes.len() / 4, recorded.words.len()];
    let capacity = [0, 1, 2].map(|i| grow(needed[i], buffers.capacity[i]));
    let grown = [0, 1, 2].map(|i| capacity[i] != buffers.capacity[i]);
    buffers.capacity = capacity;
    offsets.resize(capacity[0], 0);
    shapes.resize(4 * capacity[1], 0);
    let mut offset_bytes = Vec::with_capacity(4 * offsets.len());
    extend_words(
        &mut offset_bytes,
        bytemuck::cast_slice::<u32, f32>(&offsets),
    );
    let mut written = vec![
        (&buffers.offsets, offset_bytes, grown[0]),
        (&buffers.shapes, shapes, grown[1]),
    ];
    // The recorded frames only when one is new (or the buffer moved).
    if recorded.changed || grown[2] {
        recorded.changed = false;
        let mut bytes = Vec::with_capacity(4 * capacity[2]);
        extend_words(&mut bytes, &recorded.words);
        bytes.resize(4 * capacity[2], 0);
        written.push((&buffers.recorded, bytes, grown[2]));
    }
    let mut total = 0;
    for (handle, data, grown) in written {
        total += data.len();
        if let Some(mut buffer) = assets.get_mut(handle) {
            if grown {
                buffer.buffer_description.size = data.len() as u64;
            }
            buffer.data = Some(data);
        }
    }
    // A resized buffer is a new GPU buffer: rebuild the materials' bind groups. Only a
    // mutable borrow marks an asset modified (`get_mut` alone does not).
    if grown.contains(&true)
        && let Some(mut materials) = materials
    {
        let ids: Vec<_> = materials.ids().collect();
        for id in ids {
            if let Some(material) = materials.get_mut(id) {
                material.into_inner();
            }
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
