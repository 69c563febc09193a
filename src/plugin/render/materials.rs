//! Our materials on every jellyfish: one cache per material type
//! ([`SpeciesMaterials`]), made with a species' first jellyfish, updated in place when the
//! species is edited, and put on each new mesh of the path that wears it.
//!
//! Only where the app renders (the material's assets exist): headless apps and tests run
//! without it. A jellyfish that already has a `MeshMaterial3d<StandardMaterial>` keeps its
//! own, and is drawn with CPU meshes. Leave [`JellyfishMaterialPlugin`] out to dress every
//! jellyfish yourself (they are then drawn with CPU meshes).

use super::looks::{SpeciesMaterials, looks, scale_step, step_scale, tentacle_material_at};
use super::meshes::{JellyfishGlow, JellyfishMeshes, JellyfishTentacles, SurfacePath};
use super::patterns::BellPatterns;
use super::templates::{ShapeBuffers, SurfaceExtension, SurfaceMaterial};
use crate::plugin::jellyfish::Jellyfish;
use crate::plugin::schedule::JellyfishSystems;
use crate::species::Species;
use bevy::ecs::system::SystemParam;
use bevy::pbr::{MaterialPlugin, PbrPlugin};
use bevy::prelude::*;

/// Makes, updates and assigns our materials: `StandardMaterial`s on CPU meshes and
/// [`SurfaceMaterial`]s on templates, with each species' canal and gonad pattern.
#[derive(Clone, Copy, Debug, Default)]
pub struct JellyfishMaterialPlugin;

impl Plugin for JellyfishMaterialPlugin {
    fn build(&self, app: &mut App) {
        // Only where the app renders; add the plugins after `DefaultPlugins`.
        if app.is_plugin_added::<PbrPlugin>() {
            app.add_plugins(MaterialPlugin::<SurfaceMaterial>::default());
        }
        app.init_resource::<BellPatterns>()
            .register_type::<BellPatterns>()
            .init_resource::<SpeciesMaterials<StandardMaterial>>()
            .init_resource::<SpeciesMaterials<SurfaceMaterial>>()
            .add_systems(
                PostUpdate,
                (
                    super::patterns::repaint_edited.run_if(resource_exists::<Assets<Image>>),
                    (
                        update::<StandardMaterial>,
                        assign::<StandardMaterial>,
                        super::flash::flash::<StandardMaterial>,
                    )
                        .chain()
                        .run_if(resource_exists::<Assets<StandardMaterial>>),
                    (
                        update::<SurfaceMaterial>,
                        assign::<SurfaceMaterial>,
                        super::flash::flash::<SurfaceMaterial>,
                    )
                        .chain()
                        .run_if(resource_exists::<Assets<SurfaceMaterial>>),
                )
                    .in_set(JellyfishSystems::Materials),
            );
    }
}

/// A material our jellyfish wear: made from the `StandardMaterial` look of
/// [`bell_material`](super::bell_material) and its siblings.
pub(crate) trait JellyfishLook: Material {
    /// The surfaces that wear it.
    const PATH: SurfacePath;

    /// Whether it can be made yet (templates need the shape buffers).
    fn ready(buffers: Option<&ShapeBuffers>) -> bool;

    /// The material with `look`; `None` until it is [`ready`](Self::ready).
    fn dress(look: StandardMaterial, buffers: Option<&ShapeBuffers>) -> Option<Self>;

    /// Gives an existing material a new look (the species was edited).
    fn restyle(&mut self, look: StandardMaterial);
}

impl JellyfishLook for StandardMaterial {
    const PATH: SurfacePath = SurfacePath::CpuMeshes;

    fn ready(_: Option<&ShapeBuffers>) -> bool {
        true
    }

    fn dress(look: StandardMaterial, _: Option<&ShapeBuffers>) -> Option<Self> {
        Some(look)
    }

    fn restyle(&mut self, look: StandardMaterial) {
        *self = look;
    }
}

impl JellyfishLook for SurfaceMaterial {
    const PATH: SurfacePath = SurfacePath::Templates;

    fn ready(buffers: Option<&ShapeBuffers>) -> bool {
        buffers.is_some()
    }

    fn dress(look: StandardMaterial, buffers: Option<&ShapeBuffers>) -> Option<Self> {
        let buffers = buffers?;
        Some(SurfaceMaterial {
            base: look,
            extension: SurfaceExtension {
                offsets: buffers.offsets.clone(),
                shapes: buffers.shapes.clone(),
            },
        })
    }

    fn restyle(&mut self, look: StandardMaterial) {
        self.base = look;
    }
}

/// Edited species restyle their materials in place; removed ones are forgotten.
fn update<M: JellyfishLook>(
    mut events: MessageReader<AssetEvent<Species>>,
    species: Res<Assets<Species>>,
    mut cache: ResMut<SpeciesMaterials<M>>,
    mut materials: ResMut<Assets<M>>,
    patterns: Res<BellPatterns>,
) {
    for event in events.read() {
        match event {
            AssetEvent::Modified { id } => {
                let (Some(s), Some(handles)) = (species.get(*id), cache.by_species.get(id)) else {
                    continue;
                };
                if s.validate().is_err() {
                    continue;
                }
                for (handle, look) in handles.iter().zip(looks(s, patterns.by_species.get(id))) {
                    if let Some(mut m) = materials.get_mut(handle) {
                        m.restyle(look);
                    }
                }
                for ((_, step), handle) in cache.scaled_tentacles.iter().filter(|e| e.0.0 == *id) {
                    if let Some(mut m) = materials.get_mut(handle) {
                        m.restyle(tentacle_material_at(s, step_scale(*step)));
                    }
                }
            }
            AssetEvent::Removed { id } | AssetEvent::Unused { id } => {
                cache.by_species.remove(id);
                cache
                    .scaled_tentacles
                    .retain(|(species, _), _| species != id);
            }
            _ => {}
        }
    }
}

/// Entities with `T` that have no `M` yet.
type Undressed<T, M> = (With<T>, Without<MeshMaterial3d<M>>);

/// Tentacle entities, with the material they wear, if any.
type Tentacles<M> = (Entity, &'static ChildOf, Option<&'static MeshMaterial3d<M>>);

/// What a species' materials are made from: its parameters, its painted patterns, the
/// shape buffers (templates) and the asset stores they go into.
#[derive(SystemParam)]
pub(super) struct Wardrobe<'w, M: JellyfishLook> {
    pub(super) species: Res<'w, Assets<Species>>,
    cache: ResMut<'w, SpeciesMaterials<M>>,
    pub(super) materials: ResMut<'w, Assets<M>>,
    patterns: ResMut<'w, BellPatterns>,
    pub(super) images: Option<ResMut<'w, Assets<Image>>>,
    pub(super) buffers: Option<Res<'w, ShapeBuffers>>,
}

impl<M: JellyfishLook> Wardrobe<'_, M> {
    /// The species' `[bell, tentacles, glow]` materials, made the first time.
    pub(super) fn get(&mut self, handle: &Handle<Species>) -> Option<[Handle<M>; 3]> {
        let s = self.species.get(handle)?;
        if let Some(made) = self.cache.by_species.get(&handle.id()) {
            return Some(made.clone());
        }
        let buffers = self.buffers.as_deref();
        // Nothing is made (not even the pattern) until the material can be.
        if !M::ready(buffers) {
            return None;
        }
        let pattern = self
            .images
            .as_deref_mut()
            .map(|images| self.patterns.get_or_make(handle.id(), s, images));
        let made = looks(s, pattern.as_ref())
            .map(|look| M::dress(look, buffers).map(|m| self.materials.add(m)));
        let [Some(bell), Some(tentacles), Some(glow)] = made else {
            return None;
        };
        let made = [bell, tentacles, glow];
        self.cache.by_species.insert(handle.id(), made.clone());
        Some(made)
    }

    /// The species' tentacle material for a jellyfish drawn at scale step `step`.
    fn tentacles(&mut self, handle: &Handle<Species>, step: i32) -> Option<Handle<M>> {
        let [_, tentacles, _] = self.get(handle)?;
        if step == 0 {
            return Some(tentacles);
        }
        let key = (handle.id(), step);
        if let Some(made) = self.cache.scaled_tentacles.get(&key) {
            return Some(made.clone());
        }
        let s = self.species.get(handle)?;
        let look = tentacle_material_at(s, step_scale(step));
        let made = self.materials.add(M::dress(look, self.buffers.as_deref())?);
        self.cache.scaled_tentacles.insert(key, made.clone());
        Some(made)
    }
}

/// Puts our materials on the meshes of the path that wears `M`.
fn assign<M: JellyfishLook>(
    mut commands: Commands,
    bells: Query<(Entity, &Jellyfish, &JellyfishMeshes), Without<MeshMaterial3d<M>>>,
    tentacles: Query<Tentacles<M>, With<JellyfishTentacles>>,
    glows: Query<(Entity, &ChildOf), Undressed<JellyfishGlow, M>>,
    parents: Query<(
        &Jellyfish,
        &JellyfishMeshes,
        Option<&MeshMaterial3d<M>>,
        &GlobalTransform,
    )>,
    mut wardrobe: Wardrobe<M>,
) {
    let worn = |m: &JellyfishMeshes| m.path == Some(M::PATH);
    for (entity, jelly, meshes) in &bells {
        if meshes.umbrella.is_some()
            && worn(meshes)
            && let Some([bell, ..]) = wardrobe.get(&jelly.species)
        {
            commands.entity(entity).insert(MeshMaterial3d(bell));
        }
    }
    // Tentacles follow their jellyfish's scale (their sort offset is in world units), so
    // dressed ones are checked too, unless the game dressed them.
    for (entity, child_of, worn_now) in &tentacles {
        if let Ok((jelly, meshes, _, at)) = parents.get(child_of.parent())
            && worn(meshes)
            && worn_now.is_none_or(|m| wardrobe.cache.is_ours(&m.0))
            && let Some(wanted) = wardrobe.tentacles(
                &jelly.species,
                scale_step(at.affine().matrix3.y_axis.length()),
            )
            && worn_now.is_none_or(|m| m.0 != wanted)
        {
            commands.entity(entity).insert(MeshMaterial3d(wanted));
        }
    }
    // A bell in a material of the game's own keeps it alone: no glow of ours over it.
    for (entity, child_of) in &glows {
        if let Ok((jelly, meshes, bell, _)) = parents.get(child_of.parent())
            && worn(meshes)
            && let Some([ours, .., glow]) = wardrobe.get(&jelly.species)
            && bell.is_none_or(|b| b.0 == ours)
        {
            commands.entity(entity).insert(MeshMaterial3d(glow));
        }
    }
}
