//! The jellyfish material, in two layers: a faint alpha-blended body (fresnel rim, light
//! through the mesoglea) and an additive glow layer carrying the canals and gonads.
//!
//! Alpha-blended surfaces are sorted by their meshes' bounding-box centres only, so where
//! two bells overlap the order of the whole meshes decides which is in front. Added light does not
//! depend on the order it is drawn in: the bright part of a jellyfish is additive and
//! needs no sorting, and the body is faint enough that drawing it in the wrong order
//! changes a pixel by little (`examples/translucency.rs` measures it). For close-ups,
//! Bevy's order-independent transparency fixes the body too (see the aquarium's `--oit`).
//!
//! Only where the app renders (`Assets<StandardMaterial>` exists): headless apps and tests
//! run without it. One set of materials per species, updated in place when it is edited.
//! These are for CPU meshes; template meshes wear the same look through
//! [`SurfaceMaterial`](super::SurfaceMaterial). A jellyfish that already has a
//! `MeshMaterial3d<StandardMaterial>` keeps its own, and is drawn with CPU meshes.

use super::JellyfishSystems;
use super::components::{Jellyfish, JellyfishGlow, JellyfishMeshes, JellyfishTentacles};
use super::pattern::{BellPatterns, PLAIN_GLOW, PatternImages};
use super::surface::SurfacePath;
use crate::species::Species;
use bevy::ecs::system::SystemParam;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;

/// The materials made for each species.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct JellyfishMaterials {
    /// Per species, its two materials.
    pub by_species: HashMap<AssetId<Species>, SpeciesMaterials>,
}

/// The materials of one species' jellyfish (CPU meshes).
#[derive(Clone, Debug, Reflect)]
pub struct SpeciesMaterials {
    /// The umbrella's.
    pub bell: Handle<StandardMaterial>,
    /// The tentacles'.
    pub tentacles: Handle<StandardMaterial>,
    /// The umbrella's glow layer ([`JellyfishGlow`]).
    pub glow: Handle<StandardMaterial>,
}

impl JellyfishMaterials {
    /// Whether the plugin made this material (rather than the game).
    pub fn is_ours(&self, material: &Handle<StandardMaterial>) -> bool {
        self.by_species
            .values()
            .any(|m| [&m.bell, &m.tentacles, &m.glow].contains(&material))
    }
}

pub(super) fn plugin(app: &mut App) {
    app.init_resource::<JellyfishMaterials>()
        .register_type::<JellyfishMaterials>()
        .add_systems(
            PostUpdate,
            (update_materials, assign_materials)
                .chain()
                .after(JellyfishSystems::RebuildMeshes)
                .run_if(resource_exists::<Assets<StandardMaterial>>),
        );
}

/// Radiance (linear, before tonemapping) that one surface of a plain bell adds through
/// its glow layer, per unit of the species' `glow`. Canals and gonads add up to twice it.
pub const GLOW_RADIANCE: f32 = 0.25;

/// The bell's body: alpha-blended and double-sided (the subumbrella shows through), a high
/// reflectance and a clear coat so grazing angles brighten (a fresnel rim), and diffuse
/// transmission so a bell lit from behind brightens. With its `pattern` the colour and
/// opacity come from the canal and gonad image; without, the bell is plain. Its glow is a
/// separate, additive layer ([`glow_material`]).
pub fn bell_material(species: &Species, pattern: Option<&PatternImages>) -> StandardMaterial {
    let [r, g, b, a] = species.bell_color;
    let base_color = match pattern {
        Some(_) => Color::WHITE,
        None => Color::linear_rgba(r, g, b, a),
    };
    StandardMaterial {
        base_color,
        base_color_texture: pattern.map(|p| p.color.clone()),
        alpha_mode: AlphaMode::Blend,
        double_sided: true,
        cull_mode: None,
        perceptual_roughness: 0.3,
        reflectance: 0.8,
        clearcoat: 1.0,
        clearcoat_perceptual_roughness: 0.15,
        diffuse_transmission: 0.5,
        ..default()
    }
}

/// The bell's glow layer: unlit and additive, so it is the same whatever order it is drawn
/// in. The species' glow colour times `glow` × [`GLOW_RADIANCE`], brighter along the
/// canals and over the gonads when the `pattern` is given.
pub fn glow_material(species: &Species, pattern: Option<&PatternImages>) -> StandardMaterial {
    let [r, g, b] = species.glow_color;
    let mut radiance = LinearRgba::rgb(r, g, b) * (species.glow * GLOW_RADIANCE);
    if pattern.is_some() {
        radiance *= 1.0 / PLAIN_GLOW;
    }
    StandardMaterial {
        base_color: radiance.into(),
        base_color_texture: pattern.map(|p| p.glow.clone()),
        unlit: true,
        alpha_mode: AlphaMode::Add,
        double_sided: true,
        cull_mode: None,
        fog_enabled: true,
        ..default()
    }
}

/// Tentacles: thin, so denser than the bell to stay visible.
pub fn tentacle_material(species: &Species) -> StandardMaterial {
    let mut m = bell_material(species, None);
    m.base_color
        .set_alpha((species.bell_color[3] * 1.8).min(1.0));
    m
}

fn update_materials(
    mut events: MessageReader<AssetEvent<Species>>,
    species: Res<Assets<Species>>,
    mut cache: ResMut<JellyfishMaterials>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    patterns: Res<BellPatterns>,
) {
    for event in events.read() {
        match event {
            AssetEvent::Modified { id } => {
                let (Some(s), Some(m)) = (species.get(*id), cache.by_species.get(id)) else {
                    continue;
                };
                if s.validate().is_err() {
                    continue;
                }
                if let Some(mut bell) = materials.get_mut(&m.bell) {
                    *bell = bell_material(s, patterns.by_species.get(id));
                }
                if let Some(mut tentacles) = materials.get_mut(&m.tentacles) {
                    *tentacles = tentacle_material(s);
                }
                if let Some(mut glow) = materials.get_mut(&m.glow) {
                    *glow = glow_material(s, patterns.by_species.get(id));
                }
            }
            AssetEvent::Removed { id } | AssetEvent::Unused { id } => {
                cache.by_species.remove(id);
            }
            _ => {}
        }
    }
}

/// Entities with `T` that have no material yet.
type WithoutMaterial<T> = (With<T>, Without<MeshMaterial3d<StandardMaterial>>);

/// What a species' materials are made from: its parameters, its painted patterns, and the
/// asset stores they go into.
#[derive(SystemParam)]
struct MaterialSources<'w> {
    species: Res<'w, Assets<Species>>,
    cache: ResMut<'w, JellyfishMaterials>,
    materials: ResMut<'w, Assets<StandardMaterial>>,
    patterns: ResMut<'w, BellPatterns>,
    images: Option<ResMut<'w, Assets<Image>>>,
}

fn assign_materials(
    mut commands: Commands,
    bells: Query<(Entity, &Jellyfish, &JellyfishMeshes), Without<MeshMaterial3d<StandardMaterial>>>,
    tentacles: Query<(Entity, &ChildOf), WithoutMaterial<JellyfishTentacles>>,
    glows: Query<(Entity, &ChildOf), WithoutMaterial<JellyfishGlow>>,
    parents: Query<(
        &Jellyfish,
        &JellyfishMeshes,
        Option<&MeshMaterial3d<StandardMaterial>>,
    )>,
    mut sources: MaterialSources,
) {
    let MaterialSources {
        species,
        cache,
        materials,
        patterns,
        images,
    } = &mut sources;
    let mut get = |handle: &Handle<Species>| -> Option<SpeciesMaterials> {
        let s = species.get(handle)?;
        Some(
            cache
                .by_species
                .entry(handle.id())
                .or_insert_with(|| {
                    let pattern = images
                        .as_deref_mut()
                        .map(|images| patterns.get_or_make(handle.id(), s, images));
                    SpeciesMaterials {
                        bell: materials.add(bell_material(s, pattern.as_ref())),
                        tentacles: materials.add(tentacle_material(s)),
                        glow: materials.add(glow_material(s, pattern.as_ref())),
                    }
                })
                .clone(),
        )
    };
    let cpu = |m: &JellyfishMeshes| m.path == Some(SurfacePath::CpuMeshes);
    for (entity, jelly, meshes) in &bells {
        if meshes.umbrella.is_some()
            && cpu(meshes)
            && let Some(m) = get(&jelly.species)
        {
            commands.entity(entity).insert(MeshMaterial3d(m.bell));
        }
    }
    for (entity, child_of) in &tentacles {
        if let Ok((jelly, meshes, _)) = parents.get(child_of.parent())
            && cpu(meshes)
            && let Some(m) = get(&jelly.species)
        {
            commands.entity(entity).insert(MeshMaterial3d(m.tentacles));
        }
    }
    // A bell in a material of the game's own keeps it alone: no glow of ours over it.
    for (entity, child_of) in &glows {
        if let Ok((jelly, meshes, bell)) = parents.get(child_of.parent())
            && cpu(meshes)
            && let Some(m) = get(&jelly.species)
            && bell.is_none_or(|b| b.0 == m.bell)
        {
            commands.entity(entity).insert(MeshMaterial3d(m.glow));
        }
    }
}
