//! The template material: the jellyfish's `StandardMaterial` with a vertex shader that
//! shapes the template from the shape buffers. One set (bell, tentacles, glow) per species.

use super::SurfacePath;
use super::upload::ShapeBuffers;
use crate::plugin::JellyfishSystems;
use crate::plugin::components::{Jellyfish, JellyfishGlow, JellyfishMeshes, JellyfishTentacles};
use crate::plugin::material::{bell_material, glow_material, tentacle_material};
use crate::plugin::pattern::BellPatterns;
use crate::species::Species;
use bevy::pbr::{ExtendedMaterial, MaterialExtension};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::render_resource::AsBindGroup;
use bevy::render::storage::ShaderBuffer;
use bevy::shader::ShaderRef;

/// The jellyfish look of [`bell_material`] on a template mesh.
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

const SHADER: &str = "embedded://bevy_jellyfish/plugin/surface/surface.wgsl";

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

/// The template materials made for each species: `[bell, tentacles, glow]`.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct SurfaceMaterials {
    /// Per species, its bell, tentacle and glow materials.
    pub by_species: HashMap<AssetId<Species>, [Handle<SurfaceMaterial>; 3]>,
}

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<SurfaceMaterials>()
        .register_type::<SurfaceMaterials>()
        .add_systems(
            PostUpdate,
            (update, assign)
                .chain()
                .after(JellyfishSystems::RebuildMeshes)
                .run_if(resource_exists::<Assets<SurfaceMaterial>>),
        );
}

fn surface(base: StandardMaterial, buffers: &ShapeBuffers) -> SurfaceMaterial {
    SurfaceMaterial {
        base,
        extension: SurfaceExtension {
            offsets: buffers.offsets.clone(),
            shapes: buffers.shapes.clone(),
        },
    }
}

fn update(
    mut events: MessageReader<AssetEvent<Species>>,
    species: Res<Assets<Species>>,
    mut cache: ResMut<SurfaceMaterials>,
    mut materials: ResMut<Assets<SurfaceMaterial>>,
    patterns: Res<BellPatterns>,
) {
    for event in events.read() {
        match event {
            AssetEvent::Modified { id } => {
                let (Some(s), Some(pair)) = (species.get(*id), cache.by_species.get(id)) else {
                    continue;
                };
                if s.validate().is_err() {
                    continue;
                }
                let pattern = patterns.by_species.get(id);
                let bases = [
                    bell_material(s, pattern),
                    tentacle_material(s),
                    glow_material(s, pattern),
                ];
                for (handle, base) in pair.iter().zip(bases) {
                    if let Some(mut m) = materials.get_mut(handle) {
                        m.base = base;
                    }
                }
            }
            AssetEvent::Removed { id } | AssetEvent::Unused { id } => {
                cache.by_species.remove(id);
            }
            _ => {}
        }
    }
}

/// Entities with `T` that have no template material yet.
type Unassigned<T> = (With<T>, Without<MeshMaterial3d<SurfaceMaterial>>);

#[allow(clippy::too_many_arguments)]
fn assign(
    mut commands: Commands,
    bells: Query<(Entity, &Jellyfish, &JellyfishMeshes), Without<MeshMaterial3d<SurfaceMaterial>>>,
    tentacles: Query<(Entity, &ChildOf), Unassigned<JellyfishTentacles>>,
    glows: Query<(Entity, &ChildOf), Unassigned<JellyfishGlow>>,
    parents: Query<(&Jellyfish, &JellyfishMeshes)>,
    species: Res<Assets<Species>>,
    buffers: Option<Res<ShapeBuffers>>,
    mut cache: ResMut<SurfaceMaterials>,
    mut materials: ResMut<Assets<SurfaceMaterial>>,
    mut patterns: ResMut<BellPatterns>,
    mut images: Option<ResMut<Assets<Image>>>,
) {
    let Some(buffers) = buffers else {
        return;
    };
    let mut get = |jelly: &Jellyfish, meshes: &JellyfishMeshes| {
        if meshes.path != Some(SurfacePath::Templates) {
            return None;
        }
        let s = species.get(&jelly.species)?;
        Some(
            cache
                .by_species
                .entry(jelly.species.id())
                .or_insert_with(|| {
                    let pattern = images
                        .as_deref_mut()
                        .map(|images| patterns.get_or_make(jelly.species.id(), s, images));
                    let pattern = pattern.as_ref();
                    [
                        bell_material(s, pattern),
                        tentacle_material(s),
                        glow_material(s, pattern),
                    ]
                    .map(|base| materials.add(surface(base, &buffers)))
                })
                .clone(),
        )
    };
    for (entity, jelly, meshes) in &bells {
        if meshes.umbrella.is_some()
            && let Some([bell, ..]) = get(jelly, meshes)
        {
            commands.entity(entity).insert(MeshMaterial3d(bell));
        }
    }
    for (entity, child_of) in &tentacles {
        if let Ok((jelly, meshes)) = parents.get(child_of.parent())
            && let Some([_, tentacles, _]) = get(jelly, meshes)
        {
            commands.entity(entity).insert(MeshMaterial3d(tentacles));
        }
    }
    for (entity, child_of) in &glows {
        if let Ok((jelly, meshes)) = parents.get(child_of.parent())
            && let Some([.., glow]) = get(jelly, meshes)
        {
            commands.entity(entity).insert(MeshMaterial3d(glow));
        }
    }
}
