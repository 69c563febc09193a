//! Puts each jellyfish on its drawing path: the shared template meshes and a slot, or its
//! own CPU meshes; moves it when the path or its resolution changes.

use super::material::SurfaceMaterial;
use super::upload::SurfaceSlots;
use crate::plugin::render::looks::SpeciesMaterials;
use crate::plugin::render::meshes::{JellyfishMeshes, SurfacePath};
use crate::plugin::render::parts::{glow_layer, tentacle_layer};
use crate::plugin::render::rebuild::new_mesh;
use crate::plugin::render::resolutions::Resolutions;
use crate::plugin::settings::JellyfishSettings;
use crate::plugin::slice::JellyfishSlice;
use crate::shape::{JellyMesh, Resolution, SliceOutline, build_at};
use bevy::asset::RenderAssetUsages;
use bevy::mesh::MeshTag;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::utils::Parallel;

/// The template meshes, one pair per resolution, shared by every species drawn at it.
#[derive(Resource, Default)]
pub(crate) struct Templates {
    by_resolution: HashMap<Resolution, TemplateMeshes>,
}

#[derive(Clone)]
struct TemplateMeshes {
    umbrella: Handle<Mesh>,
    /// None for a resolution without tentacles.
    tentacles: Option<Handle<Mesh>>,
}

impl Templates {
    /// Makes the meshes for `res` unless they exist; returns whether it made them.
    fn make(&mut self, res: Resolution, slice: &JellyfishSlice, meshes: &mut Assets<Mesh>) -> bool {
        if self.by_resolution.contains_key(&res) {
            return false;
        }
        self.get(res, slice, meshes);
        true
    }

    /// The meshes for `res`, made the first time from the species' rest shape (the
    /// shader ignores the template's positions and normals; they make a sensible rest
    /// mesh for tools that read it).
    fn get(
        &mut self,
        res: Resolution,
        slice: &JellyfishSlice,
        meshes: &mut Assets<Mesh>,
    ) -> TemplateMeshes {
        self.by_resolution
            .entry(res)
            .or_insert_with(|| {
                let rest = SliceOutline::rest(&slice.species, 25, 12);
                let mut mesh = JellyMesh::new();
                build_at(&mut mesh, &rest.view(), &slice.species, res, 0, 0.0)
                    .expect("a species' rest outline always meshes");
                let usage = RenderAssetUsages::default();
                TemplateMeshes {
                    umbrella: meshes.add(new_mesh(&mut mesh.umbrella, usage)),
                    tentacles: (mesh.tentacles.vertex_count() > 0)
                        .then(|| meshes.add(new_mesh(&mut mesh.tentacles, usage))),
                }
            })
            .clone()
    }
}

/// The tag of a jellyfish's part: its slot, and 0 for the umbrella, 1 for the tentacles.
fn tag(slot: u32, part: u32) -> MeshTag {
    MeshTag(slot << 1 | part)
}

/// Runs before the meshes are built each frame.
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub(crate) fn set_up(
    mut commands: Commands,
    path: Option<Res<SurfacePath>>,
    settings: Res<JellyfishSettings>,
    mut jellyfish: Query<(
        Entity,
        &JellyfishSlice,
        &mut JellyfishMeshes,
        Option<&MeshMaterial3d<StandardMaterial>>,
    )>,
    mut templates: ResMut<Templates>,
    mut slots: ResMut<SurfaceSlots>,
    mut removed: RemovedComponents<JellyfishMeshes>,
    own: Option<Res<SpeciesMaterials<StandardMaterial>>>,
    mut assets: ResMut<Assets<Mesh>>,
    mut moving: Local<Parallel<Vec<Entity>>>,
) {
    for entity in removed.read() {
        slots.give_back(entity);
    }
    let global = path.map_or(SurfacePath::CpuMeshes, |p| *p);
    let own = own.as_deref();
    // A material of the game's own is a StandardMaterial: it needs real meshes.
    let wanted_path = |material: Option<&MeshMaterial3d<StandardMaterial>>| {
        if material.is_some_and(|m| !is_ours(own, &m.0)) {
            SurfacePath::CpuMeshes
        } else {
            global
        }
    };
    // Most frames no jellyfish changes path or resolution: those that do are looked for
    // side by side (ten thousand, a resolution worked out for each, were a serial stretch
    // of the frame), then moved in entity order.
    // Boxed: `for_each_init` hands a batch's state through every item by value, and the
    // resolution memo was copied in and out for each of ten thousand jellyfish.
    jellyfish.par_iter().for_each_init(
        || Box::new((moving.borrow_local_mut(), Resolutions::default())),
        |state, (entity, slice, meshes, material)| {
            let (list, resolutions) = &mut **state;
            if !slice.started() {
                return;
            }
            let wanted = wanted_path(material);
            if meshes.path != Some(wanted)
                || wanted == SurfacePath::Templates
                    && meshes.written.as_ref() != Some(resolutions.of(&slice.species, &settings))
            {
                list.push(entity);
            }
        },
    );
    let mut stale = Vec::new();
    moving.drain_into(&mut stale);
    stale.sort_unstable();
    let mut stale = jellyfish.iter_many_mut(&stale);
    while let Some((entity, slice, mut meshes, material)) = stale.fetch_next() {
        let wanted = wanted_path(material);
        if meshes.path != Some(wanted) {
            tear_down(
                &mut commands,
                entity,
                &mut meshes,
                &mut slots,
                material,
                own,
            );
            meshes.path = Some(wanted);
        }
        if wanted != SurfacePath::Templates {
            continue;
        }
        let res = settings.resolution(&slice.species);
        if meshes.written == Some(res) {
            continue;
        }
        // A template made this frame is drawn from the next: an entity given a mesh the
        // renderer has not prepared yet was drawn by the first of several cameras only.
        if templates.make(res, slice, &mut assets) {
            continue;
        }
        meshes.written = Some(res);
        let slot = slots.take(entity);
        meshes.slot = Some(slot);
        meshes.block.clear();
        meshes.shared = None;
        let template = templates.get(res, slice, &mut assets);
        commands
            .entity(entity)
            .insert((Mesh3d(template.umbrella.clone()), tag(slot, 0)));
        let glow = (Mesh3d(template.umbrella.clone()), tag(slot, 0));
        match meshes.glow_entity {
            Some(child) => {
                commands.entity(child).insert(glow);
            }
            None => {
                let child = commands
                    .spawn((glow_layer(entity, glow.0, meshes.bounds), glow.1))
                    .id();
                meshes.glow_entity = Some(child);
            }
        }
        meshes.umbrella = Some(template.umbrella);
        meshes.tentacles = template.tentacles.clone();
        match (template.tentacles, meshes.tentacle_entity) {
            (Some(mesh), Some(child)) => {
                commands
                    .entity(child)
                    .insert((Mesh3d(mesh), tag(slot, 1), Visibility::Inherited));
            }
            (Some(mesh), None) => {
                let child = commands
                    .spawn((
                        tentacle_layer(entity, Mesh3d(mesh), meshes.bounds),
                        tag(slot, 1),
                    ))
                    .id();
                meshes.tentacle_entity = Some(child);
            }
            (None, Some(child)) => {
                commands.entity(child).insert(Visibility::Hidden);
            }
            (None, None) => {}
        }
    }
}

/// Undoes either path's set-up, keeping a material of the game's own.
fn tear_down(
    commands: &mut Commands,
    entity: Entity,
    meshes: &mut JellyfishMeshes,
    slots: &mut SurfaceSlots,
    material: Option<&MeshMaterial3d<StandardMaterial>>,
    own: Option<&SpeciesMaterials<StandardMaterial>>,
) {
    if meshes.path.is_none() {
        return;
    }
    let mut e = commands.entity(entity);
    e.remove::<(Mesh3d, MeshTag, MeshMaterial3d<SurfaceMaterial>)>();
    if material.is_some_and(|m| is_ours(own, &m.0)) {
        e.remove::<MeshMaterial3d<StandardMaterial>>();
    }
    for child in [meshes.tentacle_entity.take(), meshes.glow_entity.take()]
        .into_iter()
        .flatten()
    {
        commands.entity(child).despawn();
    }
    slots.give_back(entity);
    *meshes = JellyfishMeshes {
        blended: std::mem::take(&mut meshes.blended),
        bounds: meshes.bounds,
        ..default()
    };
}

/// Whether our material plugin made `material` (none is ours without it).
fn is_ours(
    own: Option<&SpeciesMaterials<StandardMaterial>>,
    material: &Handle<StandardMaterial>,
) -> bool {
    own.is_some_and(|o| o.is_ours(material))
}
