//! A flash, drawn: while a jellyfish flashes ([`Flash`]) its glow layer wears a material
//! of its own whose image is the species' glow pattern plus the flash, which spreads round
//! the margin from the side that was touched and lights the margin most (where
//! *Aequorea*'s photocytes are). Both surface paths share the umbrella's UVs, so they
//! draw the same flash. Few flash at once; the rest keep sharing their species' material.

use super::looks::{GLOW_RADIANCE, Look, glow_material, glow_tissue};
use super::materials::{JellyfishLook, Wardrobe};
use super::meshes::JellyfishMeshes;
use super::patterns::{PLAIN_GLOW, bell_image, glow_grey};
use crate::plugin::jellyfish::Jellyfish;
use crate::plugin::touch::Flash;
use crate::shape::pattern;
use crate::species::Species;
use bevy::asset::RenderAssetUsages;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use std::f32::consts::{PI, TAU};

/// The flash image's size: half the glow pattern's each way.
const WIDTH: usize = pattern::WIDTH / 2;
const HEIGHT: usize = pattern::HEIGHT / 2;

/// How long the flash takes to spread from the touched side to the far side, s.
pub const FLASH_SPREAD: f32 = 0.4;

/// The share of a flash's light that leaves the whole bell rather than the margin.
const BELL_SHARE: f32 = 0.25;

/// A flashing jellyfish's glow layer: its own material and image while it flashes.
#[derive(Component)]
pub(super) struct FlashGlow<M: Material> {
    material: Handle<M>,
    image: Handle<Image>,
}

/// Each species' glow pattern at the flash image's size, grey (what the pattern's glow
/// image holds, `PLAIN_GLOW` where it is plain).
#[derive(Default)]
pub(super) struct GlowGreys(HashMap<AssetId<Species>, Vec<f32>>);

impl GlowGreys {
    fn of(&mut self, id: AssetId<Species>, species: &Species) -> &[f32] {
        self.0.entry(id).or_insert_with(|| {
            let texels = pattern::texels(species);
            (0..HEIGHT * WIDTH)
                .map(|i| {
                    let (row, col) = (2 * (i / WIDTH), 2 * (i % WIDTH));
                    let m = &texels[row * pattern::WIDTH + col];
                    glow_grey(m)
                })
                .collect()
        })
    }
}

/// How much of a flash of brightness 1 lights the bell at UV `(u, v)`, `age` seconds in,
/// touched from the side at angle `touched` round the axis: the margin (v = ½) most, the
/// rest of the bell a quarter as much, lit where the wave round the margin has reached.
pub fn flash_share(u: f32, v: f32, age: f32, touched: f32) -> f32 {
    let margin = (-((v - 0.5) / 0.06).powi(2)).exp();
    let across = (TAU * u - touched + PI).rem_euclid(TAU) - PI;
    let front = PI * (age / FLASH_SPREAD).clamp(0.0, 1.0) + 0.3;
    let x = ((front - across.abs()) / 0.3).clamp(0.0, 1.0);
    let reached = x * x * (3.0 - 2.0 * x);
    reached * (BELL_SHARE + (1.0 - BELL_SHARE) * margin)
}

/// Puts on, redraws and takes off each flashing jellyfish's own glow.
pub(super) fn flash<M: JellyfishLook>(
    mut commands: Commands,
    jellyfish: Query<(&Jellyfish, &JellyfishMeshes, &Flash), Changed<Flash>>,
    glows: Query<Option<&FlashGlow<M>>, With<MeshMaterial3d<M>>>,
    mut wardrobe: Wardrobe<M>,
    mut greys: Local<GlowGreys>,
    mut edits: MessageReader<AssetEvent<Species>>,
    time: Res<Time<Virtual>>,
) {
    // An edited species may have other canals and gonads.
    for edit in edits.read() {
        if let AssetEvent::Modified { id } | AssetEvent::Removed { id } = edit {
            greys.0.remove(id);
        }
    }
    let now = time.elapsed_secs_f64();
    for (jelly, meshes, flash) in &jellyfish {
        let worn = M::wears(meshes.path, wardrobe.buffers.is_some());
        let Some(glow) = meshes.glow_entity.filter(|_| worn) else {
            continue;
        };
        // Only a glow layer already dressed in ours (not one the game took over).
        let Ok(own) = glows.get(glow) else {
            continue;
        };
        if flash.brightness <= 0.0 {
            if own.is_some()
                && let Some([.., shared]) = wardrobe.get(&jelly.species)
            {
                commands
                    .entity(glow)
                    .insert(MeshMaterial3d(shared))
                    .remove::<FlashGlow<M>>();
            }
            continue;
        }
        let Some(species) = wardrobe.species.get(&jelly.species).cloned() else {
            continue;
        };
        let Some(images) = wardrobe.images.as_deref_mut() else {
            continue;
        };
        let grey = greys.of(jelly.species.id(), &species);
        let age = flash.started.map_or(0.0, |t| (now - t) as f32);
        let touched = flash.origin.z.atan2(flash.origin.x);
        let (data, most) = flash_image(grey, species.glow, flash.brightness, age, touched);
        match own {
            Some(own) => {
                if let Some(mut image) = images.get_mut(&own.image) {
                    image.data = Some(data);
                }
                if let Some(mut m) = wardrobe.materials.get_mut(&own.material) {
                    m.restyle(flash_look(&species, most, own.image.clone()));
                }
            }
            None => {
                let usage = RenderAssetUsages::RENDER_WORLD | RenderAssetUsages::MAIN_WORLD;
                let image = images.add(bell_image((WIDTH, HEIGHT), data, usage));
                let look = flash_look(&species, most, image.clone());
                let Some(made) = M::dress(look, wardrobe.buffers.as_deref()) else {
                    continue;
                };
                let material = wardrobe.materials.add(made);
                commands.entity(glow).insert((
                    MeshMaterial3d(material.clone()),
                    FlashGlow { material, image },
                ));
            }
        }
    }
}

/// The flash image's bytes (grey, the glow pattern plus the flash, scaled to fit a byte)
/// and the glow strength its white stands for.
fn flash_image(grey: &[f32], glow: f32, brightness: f32, age: f32, touched: f32) -> (Vec<u8>, f32) {
    // In the pattern's units: its plain grey is `glow`, a flash of 1 adds one `PLAIN_GLOW`.
    let most = glow * (PLAIN_GLOW + 0.8) + brightness * PLAIN_GLOW;
    let mut data = Vec::with_capacity(WIDTH * HEIGHT * 4);
    for (i, g) in grey.iter().enumerate() {
        let (u, v) = (
            ((i % WIDTH) as f32 + 0.5) / WIDTH as f32,
            ((i / WIDTH) as f32 + 0.5) / HEIGHT as f32,
        );
        let lit = glow * g + brightness * PLAIN_GLOW * flash_share(u, v, age, touched);
        let byte = (lit / most.max(1e-6) * 255.0).round().clamp(0.0, 255.0) as u8;
        data.extend([byte, byte, byte, 255]);
    }
    (data, most)
}

/// The glow layer's look with `image`, whose white is `most` of the pattern's units.
fn flash_look(species: &Species, most: f32, image: Handle<Image>) -> Look {
    let [r, g, b] = species.glow_color;
    let radiance = LinearRgba::rgb(r, g, b) * (most * GLOW_RADIANCE / PLAIN_GLOW);
    Look {
        base: StandardMaterial {
            base_color: radiance.into(),
            base_color_texture: Some(image),
            ..glow_material(species, None)
        },
        tissue: glow_tissue(species),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_flash_spreads_round_the_margin_from_the_touched_side() {
        let touched = 0.0;
        // At first only the touched side's margin; the far side once the wave arrives.
        assert!(flash_share(0.0, 0.5, 0.0, touched) > 0.9);
        assert_eq!(flash_share(0.5, 0.5, 0.0, touched), 0.0);
        assert!(flash_share(0.5, 0.5, FLASH_SPREAD, touched) > 0.9);
        // The margin more than the apex.
        assert!(flash_share(0.0, 0.5, 1.0, touched) > 3.0 * flash_share(0.0, 0.05, 1.0, touched));
        // Touched from the other side, the other side lights first.
        assert!(flash_share(0.5, 0.5, 0.0, PI) > 0.9);
    }
}
