//! The bell's canals and gonads as two small textures per species (`shape::pattern`): the
//! colour and opacity its material takes, and where it glows brighter. Made with the
//! species' first material and remade in place when the species is edited; CPU meshes and
//! templates sample the same images through the umbrella's UVs.

use crate::shape::pattern::{self, HEIGHT, WIDTH};
use crate::species::Species;
use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageSampler, ImageSamplerDescriptor};
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};

/// Glow of the plain bell in the glow texture; canals and gonads glow up to 1, so the
/// material's emission is the species' glow divided by this.
pub const PLAIN_GLOW: f32 = 0.5;

/// The pattern images made for each species.
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct BellPatterns {
    /// Per species, its two images.
    pub by_species: HashMap<AssetId<Species>, PatternImages>,
}

/// One species' pattern.
#[derive(Clone, Debug, Reflect)]
pub struct PatternImages {
    /// Linear RGBA: the bell's colour and opacity, canals and gonads painted in.
    pub color: Handle<Image>,
    /// Grey: how much of the species' glow each texel emits.
    pub glow: Handle<Image>,
}

impl BellPatterns {
    /// The species' images, made on first use.
    pub(crate) fn get_or_make(
        &mut self,
        id: AssetId<Species>,
        species: &Species,
        images: &mut Assets<Image>,
    ) -> PatternImages {
        self.by_species
            .entry(id)
            .or_insert_with(|| {
                let [color, glow] = pattern_images(species);
                PatternImages {
                    color: images.add(color),
                    glow: images.add(glow),
                }
            })
            .clone()
    }

    /// Repaints a species' images in place after an edit.
    pub(crate) fn repaint(
        &self,
        id: AssetId<Species>,
        species: &Species,
        images: &mut Assets<Image>,
    ) {
        let Some(p) = self.by_species.get(&id) else {
            return;
        };
        let [color, glow] = pattern_images(species);
        for (handle, image) in [(&p.color, color), (&p.glow, glow)] {
            if let Some(mut slot) = images.get_mut(handle) {
                *slot = image;
            }
        }
    }
}

pub(super) fn repaint_edited(
    mut events: MessageReader<AssetEvent<Species>>,
    species: Res<Assets<Species>>,
    mut patterns: ResMut<BellPatterns>,
    mut images: ResMut<Assets<Image>>,
) {
    for event in events.read() {
        match event {
            AssetEvent::Modified { id } => {
                if let Some(s) = species.get(*id)
                    && s.validate().is_ok()
                {
                    patterns.repaint(*id, s, &mut images);
                }
            }
            AssetEvent::Removed { id } | AssetEvent::Unused { id } => {
                patterns.by_species.remove(id);
            }
            _ => {}
        }
    }
}

/// The colour and glow images of a species' pattern.
pub(crate) fn pattern_images(species: &Species) -> [Image; 2] {
    let bell = Vec4::from_array(species.bell_color);
    let canal = bell.lerp(Vec4::ONE, 0.35).with_w((bell.w * 1.5).min(1.0));
    let gonad = Vec4::from_array(species.gonad_color);
    let texels = pattern::texels(species);
    let mut color = Vec::with_capacity(texels.len() * 4);
    let mut glow = Vec::with_capacity(texels.len() * 4);
    let byte = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    for m in &texels {
        let c = bell.lerp(canal, m.canal).lerp(gonad, m.gonad);
        color.extend(c.to_array().map(byte));
        let g = byte(glow_grey(m));
        glow.extend([g, g, g, 255]);
    }
    [color, glow].map(|data| bell_image((WIDTH, HEIGHT), data, RenderAssetUsages::RENDER_WORLD))
}

/// How much of the species' glow a texel with these marks emits (the glow image's grey).
pub(super) fn glow_grey(m: &pattern::Marks) -> f32 {
    PLAIN_GLOW + 0.3 * m.canal + 0.5 * m.gonad
}

/// An RGBA8 image over the bell's UVs, `(width, height)` texels of `data`.
pub(super) fn bell_image(
    (width, height): (usize, usize),
    data: Vec<u8>,
    usage: RenderAssetUsages,
) -> Image {
    let mut image = Image::new(
        Extent3d {
            width: width as u32,
            height: height as u32,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8Unorm,
        usage,
    );
    // Around the bell the pattern wraps; from apex to apex it does not.
    let mut sampler = ImageSamplerDescriptor::linear();
    sampler.address_mode_u = ImageAddressMode::Repeat;
    image.sampler = ImageSampler::Descriptor(sampler);
    image
}
