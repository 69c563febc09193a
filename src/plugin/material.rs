//! The jellyfish material: translucent, with a fresnel rim and the species' glow.
//!
//! Only where the app renders (`Assets<StandardMaterial>` exists): headless apps and tests
//! run without it. One material pair per species, updated in place when it is edited.
//! These are for CPU meshes; template meshes wear the same look through
//! [`SurfaceMaterial`](super::SurfaceMaterial). A jellyfish that already has a
//! `MeshMaterial3d<StandardMaterial>` keeps its own, and is drawn with CPU meshes.

use super::JellyfishSystems;
use super::components::{Jellyfish, JellyfishMeshes, JellyfishTentacles};
use super::pattern::{BellPatterns, PLAIN_GLOW, PatternImages};
use super::surface::SurfacePath;
use crate::species::Species;
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
}

impl JellyfishMaterials {
    /// Whether the plugin made this material (rather than the game).
    pub fn is_ours(&self, material: &Handle<StandardMaterial>) -> bool {
        self.by_species
            .values()
            .any(|m| m.bell == *material || m.tentacles == *material)
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

/// The bell: alpha-blended and double-sided (the subumbrella shows through), a high
/// reflectance and a clear coat so grazing angles brighten (a fresnel rim), and the
/// species' glow as emission. With its `pattern` the colour, opacity and glow come from
/// the canal and gonad images; without, the bell is plain.
pub fn bell_material(species: &Species, pattern: Option<&PatternImages>) -> StandardMaterial {
    let [r, g, b, a] = species.bell_color;
    let [er, eg, eb] = species.glow_color;
    let glow = LinearRgba::rgb(er, eg, eb) * species.glow;
    let (base_color, emissive) = match pattern {
        Some(_) => (Color::WHITE, glow * (1.0 / PLAIN_GLOW)),
        None => (Color::linear_rgba(r, g, b, a), glow),
    };
    StandardMaterial {
        base_color,
        base_color_texture: pattern.map(|p| p.color.clone()),
        emissive,
        emissive_texture: pattern.map(|p| p.glow.clone()),
        alpha_mode: AlphaMode::Blend,
        double_sided: true,
        cull_mode: None,
        perceptual_roughness: 0.3,
        reflectance: 0.8,
        clearcoat: 1.0,
        clearcoat_perceptual_roughness: 0.15,
        ..default()
    }
}

/// Tentacles: thin, so denser and brighter than the bell to stay visible.
pub fn tentacle_material(species: &Species) -> StandardMaterial {
    let mut m = bell_material(species, None);
    m.base_color
        .set_alpha((species.bell_color[3] * 1.8).min(1.0));
    m.emissive *= 1.5;
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

fn assign_materials(
    mut commands: Commands,
    bells: Query<(Entity, &Jellyfish, &JellyfishMeshes), Without<MeshMaterial3d<StandardMaterial>>>,
    tentacles: Query<(Entity, &ChildOf), WithoutMaterial<JellyfishTentacles>>,
    parents: Query<(&Jellyfish, &JellyfishMeshes)>,
    species: Res<Assets<Species>>,
    mut cache: ResMut<JellyfishMaterials>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut patterns: ResMut<BellPatterns>,
    mut images: Option<ResMut<Assets<Image>>>,
) {
    let mut get = |handle: &Handle<Species>| -> Option<SpeciesMaterials> {
        let s = species.get(handle)?;
        Some(
            cache
                .by_species
                .entry(handle.id())
                .or_insert_with(|| SpeciesMaterials {
                    bell: materials.add(bell_material(
                        s,
                        images
                            .as_deref_mut()
                            .map(|images| patterns.get_or_make(handle.id(), s, images))
                            .as_ref(),
                    )),
                    tentacles: materials.add(tentacle_material(s)),
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
        if let Ok((jelly, meshes)) = parents.get(child_of.parent())
            && cpu(meshes)
            && let Some(m) = get(&jelly.species)
        {
            commands.entity(entity).insert(MeshMaterial3d(m.tentacles));
        }
    }
}
