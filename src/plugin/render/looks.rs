//! The jellyfish material, in two layers: a faint alpha-blended body (fresnel rim, light
//! through the mesoglea) and an additive glow layer carrying the canals and gonads.
//!
//! Alpha-blended surfaces are sorted by their meshes' bounding-box centres only, so where
//! two bells overlap the order of the whole meshes decides which is in front; a
//! jellyfish's tentacles sort behind its bell ([`tentacle_material_at`]). Added light does not
//! depend on the order it is drawn in: the bright part of a jellyfish is additive and
//! draws after every body ([`GLOW_SORT_AHEAD`]), and the body is faint enough that drawing
//! it in the wrong order changes a pixel by little (`examples/translucency.rs` measures
//! it). For close-ups, Bevy's order-independent transparency fixes the body too (see the
//! aquarium's `--oit`).
//!
//! These are `StandardMaterial`s, worn by CPU meshes as they are and by template meshes
//! through [`SurfaceMaterial`](super::SurfaceMaterial), which extends them.

use super::patterns::{PLAIN_GLOW, PatternImages};
use super::tissue::Tissue;
use crate::species::Species;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;

/// The materials made for each species, of one material type `M` (`StandardMaterial` for
/// CPU meshes, [`SurfaceMaterial`](super::SurfaceMaterial) for templates): its bell,
/// tentacles and glow layer, in that order.
#[derive(Resource)]
pub struct SpeciesMaterials<M: Material> {
    /// Per species, its `[bell, tentacles, glow]` materials; the tentacles' for jellyfish
    /// drawn at scale 1.
    pub by_species: HashMap<AssetId<Species>, [Handle<M>; 3]>,
    /// The tentacles of jellyfish drawn at other scales, by species and the scale's base-2
    /// logarithm in eighths: their sort offset ([`TENTACLE_SORT_OFFSET`]) is in world units.
    pub scaled_tentacles: HashMap<(AssetId<Species>, i32), Handle<M>>,
}

impl<M: Material> Default for SpeciesMaterials<M> {
    fn default() -> Self {
        Self {
            by_species: HashMap::default(),
            scaled_tentacles: HashMap::default(),
        }
    }
}

impl<M: Material> SpeciesMaterials<M> {
    /// Whether the plugin made this material (rather than the game).
    pub fn is_ours(&self, material: &Handle<M>) -> bool {
        self.by_species.values().any(|m| m.contains(material))
            || self.scaled_tentacles.values().any(|m| m == material)
    }
}

/// One of our materials: its `StandardMaterial` and its tissue layer.
#[derive(Clone, Debug)]
pub(crate) struct Look {
    pub base: StandardMaterial,
    pub tissue: Tissue,
}

/// The three looks of a species' jellyfish: bell, tentacles, glow layer.
pub(crate) fn looks(species: &Species, pattern: Option<&PatternImages>) -> [Look; 3] {
    [
        Look {
            base: bell_material(species, pattern),
            tissue: Tissue::shell(),
        },
        tentacle_look(species, 1.0),
        Look {
            base: glow_material(species, pattern),
            tissue: glow_tissue(species),
        },
    ]
}

/// The tentacles' look at `scale` ([`tentacle_material_at`]): solid tubes.
pub(crate) fn tentacle_look(species: &Species, scale: f32) -> Look {
    Look {
        base: tentacle_material_at(species, scale),
        tissue: Tissue::solid(),
    }
}

/// The glow layer's tissue: its painted light, and the glow band in the glow's colour at
/// the species' `glow_band` (in the units of `glow`).
pub fn glow_tissue(species: &Species) -> Tissue {
    let [r, g, b] = species.glow_color;
    Tissue::glowing(LinearRgba::rgb(r, g, b) * (species.glow_band * GLOW_RADIANCE))
}

/// Radiance (linear, before tonemapping) that one surface of a plain bell adds through
/// its glow layer, per unit of the species' `glow`. Canals and gonads add up to twice it.
pub const GLOW_RADIANCE: f32 = 0.25;

/// The bell's body: alpha-blended and double-sided (the subumbrella shows through), a high
/// reflectance and a clear coat so grazing angles brighten (a fresnel rim), and diffuse
/// transmission so a bell lit from behind brightens. With its `pattern` the colour and
/// opacity come from the canal and gonad image; without, the bell is plain. Its glow is a
/// separate, additive layer ([`glow_material`]).
///
/// The opacity is one sheet's seen straight on where the mesoglea is thickest (the apex);
/// the tissue layer ([`Tissue::SHELL`]) makes it follow the optical path elsewhere.
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

/// The bell's glow layer: unlit and additive. The species' glow colour times `glow` ×
/// [`GLOW_RADIANCE`], brighter along the canals and over the gonads when the `pattern` is
/// given.
///
/// Added light commutes with added light, not with a bell's blend: drawn before a bell,
/// that bell veils it to `1 − alpha` of itself. Its own bell shares its mesh and
/// transform, so sorted by their centres the two tied, and the tie went by the order the
/// renderer met the entities in (a jellyfish moved to another table glowed a third
/// fainter); another bell overlapping it in the view veiled it or not as their centres
/// swapped, a pop of up to 16 of 255 (`examples/translucency.rs`). So every glow layer
/// sorts [`GLOW_SORT_AHEAD`] nearer than it is and draws after every blended body: never
/// veiled, which the per-fragment order (OIT) would do a little where a bell is in front.
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
        depth_bias: GLOW_SORT_AHEAD,
        ..default()
    }
}

/// How much nearer than it is a glow layer counts when blended surfaces are sorted, in
/// world units: farther than a scene's jellyfish lie apart, so every glow layer draws after
/// every blended body. Bevy also hands it to the depth test as a constant bias of as many
/// of the depth buffer's least steps: one to two ten-thousandths of the distance to the
/// camera, nothing a glow shows through an opaque edge.
pub const GLOW_SORT_AHEAD: f32 = 1000.0;

/// How much farther than its centre a jellyfish's tentacles and oral tubes count when
/// blended surfaces are sorted, in bell diameters.
pub const TENTACLE_SORT_OFFSET: f32 = 0.5;

/// Tentacles of a jellyfish drawn at scale 1: thin, so denser than the bell to stay
/// visible, tinted by the species' glow ([`tentacle_material_at`] for other scales).
pub fn tentacle_material(species: &Species) -> StandardMaterial {
    tentacle_material_at(species, 1.0)
}

/// Tentacles of a jellyfish drawn at `scale` (its `GlobalTransform`'s).
///
/// Blended surfaces are drawn far to near by their meshes' centres, and a bell and its
/// tentacles hang on one vertical line, so seen from the side their order was a coin toss,
/// which the two surface paths tossed differently (their meshes' centres differ). The
/// manubrium and oral arms lie inside the bell: drawn first, the bell's walls veil them.
/// So the tentacles sort [`TENTACLE_SORT_OFFSET`] diameters farther than they are (in
/// world units, hence the scale), and draw after their bell only when the camera looks up
/// at them from below.
///
/// Tentacles take half their colour from the glow, and glow faintly themselves (a tenth
/// of the bell's glow layer), so they read as living tissue, never grey tubes; their
/// opacity is the root's, seen through its axis ([`Tissue::SOLID`]).
pub fn tentacle_material_at(species: &Species, scale: f32) -> StandardMaterial {
    let mut m = bell_material(species, None);
    let [r, g, b, a] = species.bell_color;
    let glow = Vec3::from_array(species.glow_color);
    let tint = glow / glow.max_element().max(1e-6);
    let rgb = (Vec3::new(r, g, b) + tint) * 0.5;
    m.base_color = Color::linear_rgba(rgb.x, rgb.y, rgb.z, (a * 1.8).min(1.0));
    let light = glow * (0.1 * species.glow * GLOW_RADIANCE);
    m.emissive = LinearRgba::rgb(light.x, light.y, light.z);
    // Bevy also hands the bias's integer part to the depth test as a constant bias: a few
    // of the depth buffer's least steps, nothing a jellyfish shows.
    m.depth_bias = -TENTACLE_SORT_OFFSET * species.diameter * scale;
    m
}

/// A jellyfish's scale in steps of 2^(1/8) (9 %): how finely tentacle materials follow it.
pub(crate) fn scale_step(scale: f32) -> i32 {
    if scale.is_finite() && scale > 0.0 {
        (scale.log2() * 8.0).round().clamp(-400.0, 400.0) as i32
    } else {
        0
    }
}

/// The scale that [`scale_step`] gives `step` for.
pub(crate) fn step_scale(step: i32) -> f32 {
    (step as f32 / 8.0).exp2()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bell is a shell, the tentacles solid tubes tinted by the glow, and the glow
    /// layer carries the band in the glow's colour at `glow_band` (none at 0).
    #[test]
    fn each_layer_has_its_tissue() {
        let species = Species::aequorea();
        let [bell, tentacles, glow] = looks(&species, None);
        assert_eq!(bell.tissue.kind, Tissue::SHELL);
        assert_eq!(tentacles.tissue.kind, Tissue::SOLID);
        assert_eq!(glow.tissue.kind, Tissue::PAINTED);
        // The glow shares its bell's mesh and centre: it must sort nearer, never tie; and
        // nearer than any other bell of a scene, so none veils it as their centres swap.
        assert!(glow.base.depth_bias >= bell.base.depth_bias + 100.0);
        assert!(tentacles.base.depth_bias < bell.base.depth_bias);
        let [r, g, b] = species.glow_color;
        let band = species.glow_band * GLOW_RADIANCE;
        assert!((glow.tissue.band - Vec4::new(r, g, b, 0.0) * band).length() < 1e-6);
        let rgb = tentacles.base.base_color.to_linear();
        let bell_rgb = bell.base.base_color.to_linear();
        assert!(
            rgb.green - rgb.red > bell_rgb.green - bell_rgb.red,
            "greener than the bell"
        );
        assert!(tentacles.base.emissive.green > 0.0);
        let dark = Species {
            glow_band: 0.0,
            ..species
        };
        assert_eq!(glow_tissue(&dark).band, Vec4::ZERO);
    }
}
