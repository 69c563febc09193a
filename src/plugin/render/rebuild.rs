//! Surfaces rebuilt every frame from the slice, blended between fixed steps: CPU meshes
//! written into the same mesh assets in place, or packed shapes for the templates;
//! skipped for jellyfish no camera sees (see [`culling`](super::culling)).

use super::culling::{active_frusta, seen, slice_bounds};
use super::meshes::{CPU_MESH_TAG, FarInstance, JellyfishMeshes, SurfacePath};
use super::parts::{glow_layer, tentacle_layer};
use super::recorded::{RecordedFrames, drawn_view, shown_step};
use super::resolutions::Resolutions;
use crate::plugin::interpolation::{SliceHistory, Snapshot};
use crate::plugin::settings::JellyfishSettings;
use crate::plugin::slice::{JellyfishSlice, LiveSlice, ONE_AT_A_TIME, SMALL_BATCHES, Tier};
use crate::plugin::timings::{BatchClock, JellyfishTimings, Spent};
use crate::shape::mesh::Resolution;
use crate::shape::{self, SurfaceBuffers, packed};
use crate::sim::guides::Trail;
use crate::species::Species;
use bevy::asset::RenderAssetUsages;
use bevy::camera::primitives::{Aabb, Frustum};
use bevy::camera::visibility::NoAutoAabb;
use bevy::mesh::{Indices, MeshTag, PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;
use bevy::utils::Parallel;
use std::sync::Arc;
use std::time::Instant;

/// The CPU-heavy half, in parallel: blend the steps around the frame's time (a far
/// jellyfish shows the nearer recorded step), bound them, and build the surfaces (CPU
/// meshes) or pack the shapes (templates) of the jellyfish a camera sees.
pub(super) fn build_buffers(
    mut live: Query<Shaped, With<LiveSlice>>,
    mut rest: Query<Shaped, Without<LiveSlice>>,
    cameras: Query<(&Camera, &Frustum)>,
    settings: Res<JellyfishSettings>,
    timings: Res<JellyfishTimings>,
    recorded: Res<RecordedFrames>,
) {
    let frusta = active_frusta(&cameras);
    recorded.prune();
    let (frusta, recorded, settings) = (&frusta[..], &*recorded, &*settings);
    // Boxed: `for_each_init` hands a batch's state through every item by value.
    let batch = || {
        let clock = BatchClock::new(&timings, Spent::Meshing);
        Box::new((clock, Resolutions::default()))
    };
    let shape = |state: &mut Box<(BatchClock, Resolutions)>,
                 (slice, history, mut meshes, transform): ShapedItem| {
        let (clock, resolutions) = &mut **state;
        if slice.started() {
            clock.time(slice.tier() as usize, || {
                let at = (transform, frusta);
                let res = resolutions.of(&slice.species, settings);
                shape_one(slice, history, &mut meshes, at, recorded, res)
            });
        }
    };
    // Live slices first, as the stepping takes them (`LiveSlice`).
    live.par_iter_mut()
        .batching_strategy(ONE_AT_A_TIME)
        .for_each_init(batch, shape);
    rest.par_iter_mut()
        .batching_strategy(SMALL_BATCHES)
        .for_each_init(batch, shape);
}

/// One jellyfish as the meshing sees it.
type Shaped = (
    &'static JellyfishSlice,
    &'static SliceHistory,
    &'static mut JellyfishMeshes,
    &'static GlobalTransform,
);

/// The meshing query's item.
type ShapedItem<'w, 's> = bevy::ecs::query::QueryItem<'w, 's, Shaped>;

/// One jellyfish's surface: blended (or its recorded step, if far), bounded, and built or
/// packed if a camera sees it.
fn shape_one(
    slice: &JellyfishSlice,
    history: &SliceHistory,
    meshes: &mut JellyfishMeshes,
    (transform, frusta): (&GlobalTransform, &[Frustum]),
    recorded: &RecordedFrames,
    res: &Resolution,
) {
    let Some((a, b, t)) = history.shown() else {
        return;
    };
    let JellyfishMeshes {
        blended,
        packer,
        block,
        shared,
        instance,
        instance_trail,
        buffers,
        trails,
        ..
    } = meshes;
    // A far jellyfish shows its recorded step as it is: read in place, not copied.
    let step = (slice.tier() == Tier::Far).then(|| shown_step(a, b, t));
    let shown = match step {
        Some(step) => step,
        None => {
            blended.blend(a, b, t);
            &*blended
        }
    };
    let bounds = slice_bounds(shown, &slice.species);
    meshes.bounds = Some(bounds);
    meshes.seen = seen(frusta, &bounds, &transform.affine());
    let templates = meshes.path == Some(SurfacePath::Templates);
    // A template's slot is shaped once even unseen: it must never show another's.
    if !(meshes.seen || templates && block.is_empty()) {
        return;
    }
    let view = drawn_view(shown, step.is_some(), &slice.rest_bell, res, trails);
    let (seed, time) = (slice.seed, shown.time as f32);
    let step = step.and_then(|s| s.recorded.as_ref());
    // The cycle it drew from last frame, if still the one: `None` keeps it held.
    let recorded_step = step.filter(|_| templates).and_then(|(cache, index)| {
        if let Some((held, _)) = shared.as_ref()
            && held.plays(cache, &slice.species, *res)
        {
            return held.start(*index).map(|_| (None, *index));
        }
        let cycle = recorded.cycle(cache, &slice.species, *res)?;
        cycle.start(*index).map(|_| (Some(cycle), *index))
    });
    let built = if let Some((cycle, index)) = recorded_step {
        pack_far(
            shown,
            &slice.species,
            res,
            (seed, time),
            view.trail,
            (block, instance, instance_trail),
        );
        match (cycle, shared.as_mut()) {
            (Some(cycle), _) => *shared = Some((cycle, index)),
            (None, Some(held)) => held.1 = index,
            (None, None) => {}
        }
        Ok(())
    } else if templates {
        let mut packed = std::mem::take(block);
        packed.clear();
        let result = packer.pack(&view, &slice.species, *res, seed, time, &mut packed);
        // On an error the last frame stays, its shared step with it.
        if result.is_ok() || block.is_empty() {
            *block = packed;
            *shared = None;
            *instance_trail = None;
        }
        result
    } else {
        shape::build_at(buffers, &view, &slice.species, *res, seed, time)
            .map(|()| meshes.dirty = true)
    };
    if let Err(e) = built {
        warn_once!("jellyfish mesh not rebuilt, keeping the last frame: {e}");
    }
}

/// A far jellyfish's instance: its own words and the thinned `trail` of the step it
/// shows, in `instance` (packed in `block` first). Where that is the shared trail the
/// instance already carries, at the same guides, the trail's half floats are kept and only
/// the words written (the same bits: the packing is a function of the trail alone).
fn pack_far(
    shown: &Snapshot,
    species: &Species,
    res: &Resolution,
    (seed, time): (u32, f32),
    trail: Trail,
    (block, instance, instance_trail): (&mut Vec<f32>, &mut FarInstance, &mut HeldTrail),
) {
    let guides = packed::far_guides(res);
    // The trail drawn is the shared one itself (not thinned again from it).
    let shared = shown.shared_trail().filter(|s| {
        std::ptr::eq(s.as_ptr(), trail.offsets.as_ptr()) && s.len() == trail.offsets.len()
    });
    let carried = instance_trail
        .as_ref()
        .zip(shared)
        .is_some_and(|((held, at), s)| Arc::ptr_eq(held, s) && *at == guides);
    if carried && instance.words().len() == packed::instance_len(res) {
        packed::write_instance_words(species, seed, time, instance.words_mut());
        debug_assert!(
            {
                let mut fresh = Vec::new();
                packed::pack_instance(species, res, seed, time, trail, &mut fresh);
                let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                bits(&fresh) == bits(instance.words())
            },
            "a kept trail is the trail packed afresh"
        );
        return;
    }
    block.clear();
    packed::pack_instance(species, res, seed, time, trail, block);
    instance.set(block);
    *instance_trail = shared.map(|s| (s.clone(), guides));
}

/// The shared trail a far instance carries, and the guides it was packed for.
type HeldTrail = Option<(Arc<[Vec3]>, usize)>;

/// The mostly serial half: copy the buffers into the mesh assets (creating them the first
/// time). An empty surface (a species without tentacles) is hidden, never handed to Bevy.
/// Every jellyfish's bounds are copied side by side first: ten thousand of them were a
/// serial stretch of the frame (its parts take them in [`place_parts`](super::parts)).
pub(super) fn write_meshes(
    mut commands: Commands,
    mut jellyfish: Query<(Entity, &mut JellyfishMeshes, Option<&mut Aabb>)>,
    mut assets: ResMut<Assets<Mesh>>,
    timings: Res<JellyfishTimings>,
    mut unbounded: Local<Parallel<Vec<(Entity, Aabb)>>>,
) {
    let start = Instant::now();
    // Bounds follow the slice every frame, seen or not, so Bevy culls with them.
    jellyfish
        .par_iter_mut()
        .for_each(|(entity, meshes, aabb)| match (meshes.bounds, aabb) {
            (Some(bounds), Some(mut aabb)) => *aabb = bounds,
            (Some(bounds), None) => unbounded.borrow_local_mut().push((entity, bounds)),
            (None, _) => {}
        });
    for (entity, bounds) in unbounded.drain() {
        commands.entity(entity).insert((bounds, NoAutoAabb));
    }
    for (entity, mut meshes, _) in &mut jellyfish {
        if !meshes.dirty {
            continue;
        }
        let meshes = &mut *meshes;
        meshes.dirty = false;
        let topology = meshes.written != meshes.buffers.resolution();
        meshes.written = meshes.buffers.resolution();
        let umbrella = &mut meshes.buffers.umbrella;
        match &meshes.umbrella {
            Some(handle) => {
                if let Some(mut mesh) = assets.get_mut(handle) {
                    timings.add_mesh_bytes(write(&mut mesh, umbrella, topology));
                }
            }
            None if umbrella.vertex_count() > 0 => {
                timings.add_mesh_bytes(bytes(umbrella));
                let handle = assets.add(new_mesh(umbrella, RenderAssetUsages::default()));
                let tag = MeshTag(CPU_MESH_TAG);
                commands
                    .entity(entity)
                    .insert((Mesh3d(handle.clone()), tag.clone()));
                let glow = commands
                    .spawn((
                        glow_layer(entity, Mesh3d(handle.clone()), meshes.bounds),
                        tag,
                    ))
                    .id();
                meshes.glow_entity = Some(glow);
                meshes.umbrella = Some(handle);
            }
            None => {}
        }
        let tentacles = &mut meshes.buffers.tentacles;
        let visible = tentacles.vertex_count() > 0;
        match (&meshes.tentacles, meshes.tentacle_entity) {
            (Some(handle), Some(child)) => {
                if visible && let Some(mut mesh) = assets.get_mut(handle) {
                    timings.add_mesh_bytes(write(&mut mesh, tentacles, topology));
                }
                let visibility = if visible {
                    Visibility::Inherited
                } else {
                    Visibility::Hidden
                };
                if topology {
                    commands.entity(child).insert(visibility);
                }
            }
            _ if visible => {
                timings.add_mesh_bytes(bytes(tentacles));
                let handle = assets.add(new_mesh(tentacles, RenderAssetUsages::default()));
                let child = commands
                    .spawn((
                        tentacle_layer(entity, Mesh3d(handle.clone()), meshes.bounds),
                        MeshTag(CPU_MESH_TAG),
                    ))
                    .id();
                meshes.tentacles = Some(handle);
                meshes.tentacle_entity = Some(child);
            }
            _ => {}
        }
    }
    timings.add_meshing(start.elapsed());
}

pub(crate) fn new_mesh(b: &mut SurfaceBuffers, usage: RenderAssetUsages) -> Mesh {
    let mut mesh = Mesh::new(PrimitiveTopology::TriangleList, usage);
    write(&mut mesh, b, true);
    mesh
}

/// Hands the new positions, normals and tissue (the second UV channel, which the tissue
/// material reads) to the mesh by swapping buffers (the build overwrites every vertex each
/// frame, so what comes back is as good as empty); the whole topology is copied only when
/// it changed. Returns the bytes written.
fn write(mesh: &mut Mesh, b: &mut SurfaceBuffers, topology: bool) -> usize {
    let written = bytes(b);
    let in_place = !topology
        && swap(mesh, Mesh::ATTRIBUTE_POSITION, &mut b.positions)
        && swap(mesh, Mesh::ATTRIBUTE_NORMAL, &mut b.normals)
        && swap(mesh, Mesh::ATTRIBUTE_UV_1, &mut b.tissue);
    if !in_place {
        mesh.insert_attribute(Mesh::ATTRIBUTE_POSITION, b.positions.clone());
        mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals.clone());
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, b.uvs.clone());
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_1, b.tissue.clone());
        mesh.insert_indices(Indices::U32(b.indices.clone()));
    }
    written
}

/// Bytes a changed mesh costs the renderer: Bevy 0.19 re-extracts and re-uploads a
/// modified mesh whole (positions, normals, both texture coordinates, indices), however
/// little of it changed.
fn bytes(b: &SurfaceBuffers) -> usize {
    b.vertex_count() * (2 * std::mem::size_of::<[f32; 3]>() + 2 * 8) + b.indices.len() * 4
}

/// Swaps `values` with the mesh's `attribute` where it has their type and length.
fn swap<T>(mesh: &mut Mesh, attribute: bevy::mesh::MeshVertexAttribute, values: &mut Vec<T>) -> bool
where
    T: Attribute,
{
    match mesh.try_attribute_mut(attribute) {
        Ok(v) => T::swap(v, values),
        _ => false,
    }
}

/// A vertex attribute's element type, as `VertexAttributeValues` holds it.
trait Attribute: Sized {
    fn swap(held: &mut VertexAttributeValues, values: &mut Vec<Self>) -> bool;
}

impl Attribute for [f32; 3] {
    fn swap(held: &mut VertexAttributeValues, values: &mut Vec<Self>) -> bool {
        match held {
            VertexAttributeValues::Float32x3(v) if v.len() == values.len() => {
                std::mem::swap(v, values);
                true
            }
            _ => false,
        }
    }
}

impl Attribute for [f32; 2] {
    fn swap(held: &mut VertexAttributeValues, values: &mut Vec<Self>) -> bool {
        match held {
            VertexAttributeValues::Float32x2(v) if v.len() == values.len() => {
                std::mem::swap(v, values);
                true
            }
            _ => false,
        }
    }
}
