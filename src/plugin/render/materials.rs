//! Our materials on every jellyfish: one cache per material type
//! ([`SpeciesMaterials`]), made with a species' first jellyfish, updated in place when the
//! species is edited, and put on each new mesh of the path that wears it.
//!
//! Where the device reads storage buffers in vertex shaders, both surface paths wear
//! [`SurfaceMaterial`] (its vertex shader takes a CPU mesh's vertices as they are, marked
//! by [`CPU_MESH_TAG`]), so both draw the tissue layer; elsewhere (WebGL2) CPU meshes wear
//! plain `StandardMaterial`s. Only where the app renders (the material's assets exist):
//! headless apps and tests run without it. A jellyfish (or a part of one) that has a
//! `MeshMaterial3d<StandardMaterial>` of the game's own keeps it, and is drawn with CPU
//! meshes. Leave [`JellyfishMaterialPlugin`] out to dress every jellyfish yourself (they
//! are then drawn with CPU meshes).
//!
//! [`CPU_MESH_TAG`]: crate::plugin::render::CPU_MESH_TAG

use super::looks::{Look, SpeciesMaterials, looks, scale_step, step_scale, tentacle_look};
use super::meshes::{JellyfishGlow, JellyfishMeshes, JellyfishTentacles, SurfacePath};
use super::parts::PartOf;
use super::patterns::BellPatterns;
use super::templates::{ShapeBuffers, SurfaceExtension, SurfaceMaterial};
use crate::plugin::jellyfish::Jellyfish;
use crate::plugin::schedule::JellyfishSystems;
use crate::species::Species;
use bevy::ecs::system::SystemParam;
use bevy::pbr::{MaterialPlugin, PbrPlugin};
use bevy::prelude::*;
use bevy::render::erased_render_asset::prepare_erased_assets;
use bevy::render::render_asset::prepare_assets;
use bevy::render::storage::GpuShaderBuffer;
use bevy::render::{Render, RenderApp};

/// Makes, updates and assigns our materials: [`SurfaceMaterial`]s (and, without storage
/// buffers in vertex shaders, `StandardMaterial`s on CPU meshes), with each species'
/// canal and gonad pattern.
#[derive(Clone, Copy, Debug, Default)]
pub struct JellyfishMaterialPlugin;

impl Plugin for JellyfishMaterialPlugin {
    fn build(&self, app: &mut App) {
        // Only where the app renders; add the plugins after `DefaultPlugins`.
        if app.is_plugin_added::<PbrPlugin>() {
            bevy::asset::embedded_asset!(app, "tissue.wgsl");
            // One material type of ours for both paths: a third material plugin made
            // template tentacles vanish in Bevy 0.19 (not understood; see the tests).
            app.add_plugins(MaterialPlugin::<SurfaceMaterial>::default());
            if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
                render_app.configure_sets(
                    Render,
                    ShapeBuffersBeforeSurfaceMaterials
                        .after(prepare_assets::<GpuShaderBuffer>)
                        .before(prepare_erased_assets::<MeshMaterial3d<SurfaceMaterial>>),
                );
            }
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
                    // One order: the patterns and the images both paths paint into are
                    // shared, and which path went first was the threads' choice.
                    .chain()
                    .in_set(JellyfishSystems::Materials),
            );
    }
}

/// Orders the shape buffers' preparation before the surface materials' in the render world.
///
/// When the shape buffers grow, each becomes a new GPU buffer and the materials are marked
/// changed so that their bind groups take it. Bevy leaves the two preparations unordered:
/// a material prepared first bound the old buffer, and kept drawing its stale shapes
/// until the next growth (a flaky render test under load). An empty set, so it only
/// orders.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct ShapeBuffersBeforeSurfaceMaterials;

/// A material our jellyfish wear: made from the look of
/// [`bell_material`](super::bell_material) and its siblings, with its tissue layer.
pub(crate) trait JellyfishLook: Material {
    /// Whether a jellyfish drawn on `path` wears it, where the shape buffers exist or not.
    fn wears(path: Option<SurfacePath>, buffers: bool) -> bool;

    /// Whether `standard`, on a part wearing none of ours, is the game's own.
    fn is_games(standard: &Handle<StandardMaterial>, ours: &SpeciesMaterials<Self>) -> bool;

    /// Whether it can be made yet (templates need the shape buffers).
    fn ready(buffers: Option<&ShapeBuffers>) -> bool;

    /// The material with `look`; `None` until it is [`ready`](Self::ready).
    fn dress(look: Look, buffers: Option<&ShapeBuffers>) -> Option<Self>;

    /// Gives an existing material a new look (the species was edited).
    fn restyle(&mut self, look: Look);
}

/// The fallback: CPU meshes where the device has no storage buffers in vertex shaders,
/// without the tissue layer.
impl JellyfishLook for StandardMaterial {
    fn wears(path: Option<SurfacePath>, buffers: bool) -> bool {
        path == Some(SurfacePath::CpuMeshes) && !buffers
    }

    fn is_games(standard: &Handle<StandardMaterial>, ours: &SpeciesMaterials<Self>) -> bool {
        !ours.is_ours(standard)
    }

    fn ready(_: Option<&ShapeBuffers>) -> bool {
        true
    }

    fn dress(look: Look, _: Option<&ShapeBuffers>) -> Option<Self> {
        Some(look.base)
    }

    fn restyle(&mut self, look: Look) {
        *self = look.base;
    }
}

impl JellyfishLook for SurfaceMaterial {
    fn wears(path: Option<SurfacePath>, buffers: bool) -> bool {
        path.is_some() && buffers
    }

    fn is_games(_: &Handle<StandardMaterial>, _: &SpeciesMaterials<Self>) -> bool {
        true
    }

    fn ready(buffers: Option<&ShapeBuffers>) -> bool {
        buffers.is_some()
    }

    fn dress(look: Look, buffers: Option<&ShapeBuffers>) -> Option<Self> {
        let buffers = buffers?;
        Some(SurfaceMaterial {
            base: look.base,
            extension: SurfaceExtension {
                offsets: buffers.offsets.clone(),
                shapes: buffers.shapes.clone(),
                recorded: buffers.recorded.clone(),
                tissue: look.tissue,
            },
        })
    }

    fn restyle(&mut self, look: Look) {
        self.base = look.base;
        self.extension.tissue = look.tissue;
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
                        m.restyle(tentacle_look(s, step_scale(*step)));
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

/// A part's `StandardMaterial`, if it has one (ours on the fallback path, or the game's).
type Standard = Option<&'static MeshMaterial3d<StandardMaterial>>;

/// A jellyfish seen from its parts: what it is, how it is drawn, the material of ours it
/// wears, its `StandardMaterial` if any, and where it is.
type Parent<M> = (
    &'static Jellyfish,
    &'static JellyfishMeshes,
    Option<&'static MeshMaterial3d<M>>,
    Standard,
    &'static GlobalTransform,
);

/// Tentacle entities, with the material of ours they wear, if any, and their
/// `StandardMaterial`.
type Tentacles<M> = (
    Entity,
    &'static PartOf,
    Option<&'static MeshMaterial3d<M>>,
    Standard,
);

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
        let look = tentacle_look(s, step_scale(step));
        let made = self.materials.add(M::dress(look, self.buffers.as_deref())?);
        self.cache.scaled_tentacles.insert(key, made.clone());
        Some(made)
    }
}

/// Puts our materials on the meshes of the path that wears `M`, and takes ours off a part
/// the game has since dressed in its own.
fn assign<M: JellyfishLook>(
    mut commands: Commands,
    redressed: Query<(
        Entity,
        &MeshMaterial3d<M>,
        &MeshMaterial3d<StandardMaterial>,
    )>,
    bells: Query<(Entity, &Jellyfish, &JellyfishMeshes, Standard), Without<MeshMaterial3d<M>>>,
    tentacles: Query<Tentacles<M>, With<JellyfishTentacles>>,
    glows: Query<(Entity, &PartOf, Standard), Undressed<JellyfishGlow, M>>,
    parents: Query<Parent<M>>,
    mut wardrobe: Wardrobe<M>,
) {
    let buffers = wardrobe.buffers.is_some();
    let worn = |m: &JellyfishMeshes| M::wears(m.path, buffers);
    let games = |standard: Option<&MeshMaterial3d<StandardMaterial>>,
                 ours: &SpeciesMaterials<M>| {
        standard.is_some_and(|s| M::is_games(&s.0, ours))
    };
    for (entity, ours, standard) in &redressed {
        if wardrobe.cache.is_ours(&ours.0) && games(Some(standard), &wardrobe.cache) {
            commands.entity(entity).remove::<MeshMaterial3d<M>>();
        }
    }
    for (entity, jelly, meshes, standard) in &bells {
        if meshes.umbrella.is_some()
            && worn(meshes)
            && !games(standard, &wardrobe.cache)
            && let Some([bell, ..]) = wardrobe.get(&jelly.species)
        {
            commands.entity(entity).insert(MeshMaterial3d(bell));
        }
    }
    // Tentacles follow their jellyfish's scale (their sort offset is in world units), so
    // dressed ones are checked too, unless the game dressed them.
    for (entity, part_of, worn_now, standard) in &tentacles {
        if let Ok((jelly, meshes, _, _, at)) = parents.get(part_of.jellyfish())
            && worn(meshes)
            && worn_now.is_none_or(|m| wardrobe.cache.is_ours(&m.0))
            && (worn_now.is_some() || !games(standard, &wardrobe.cache))
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
    for (entity, part_of, standard) in &glows {
        if let Ok((jelly, meshes, bell, bell_standard, _)) = parents.get(part_of.jellyfish())
            && worn(meshes)
            && !games(standard, &wardrobe.cache)
            && !games(bell_standard, &wardrobe.cache)
            && let Some([ours, .., glow]) = wardrobe.get(&jelly.species)
            && bell.is_none_or(|b| b.0 == ours)
        {
            commands.entity(entity).insert(MeshMaterial3d(glow));
        }
    }
}
