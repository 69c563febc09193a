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
//! These are `StandardMaterial`s, worn by CPU meshes as they are and by template meshes
//! through [`SurfaceMaterial`](super::SurfaceMaterial), which extends them.

use super::patterns::{PLAIN_GLOW, PatternImages};
use crate::species::Species;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;

/// The materials made for each species, of one material type `M` (`StandardMaterial` for
/// CPU meshes, [`SurfaceMaterial`](super::SurfaceMaterial) for templates): its bell,
/// tentacles and glow layer, in that order.
#[derive(Resource)]
pub struct SpeciesMaterials<M: Material> {
    /// Per species, its `[bell, tentacles, glow]` materials.
    pub by_species: HashMap<AssetId<Species>, [Handle<M>; 3]>,
}

impl<M: Material> Default for SpeciesMaterials<M> {
    fn default() -> Self {
        Self {
            by_species: HashMap::default(),
        }
    }
}

impl<M: Material> SpeciesMaterials<M> {
    /// Whether the plugin made this material (rather than the game).
    pub fn is_ours(&self, material: &Handle<M>) -> bool {
        self.by_species.values().any(|m| m.contains(material))
    }
}

/// The three looks of a species' jellyfish: bell, tentacles, glow layer.
pub(crate) fn looks(species: &Species, pattern: Option<&PatternImages>) -> [StandardMaterial; 3] {
    [
        bell_material(species, pattern),
        tentacle_material(species),
        glow_material(species, pattern),
    ]
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
