//! The tissue layer of our materials: a fragment shader (`tissue.wgsl`) on top of
//! `StandardMaterial` that makes the opacity follow the optical path through the tissue
//! (Beer–Lambert) and adds the glow band to the glow layer. Both surface paths wear it in
//! [`SurfaceMaterial`](super::SurfaceMaterial), whose extension carries the [`Tissue`]
//! uniform. Each vertex's thickness and band come from the shape
//! ([`shape::tissue`](crate::shape::tissue)) in the mesh's second UV channel, which
//! templates fill in their vertex shader.

use bevy::prelude::*;
use bevy::render::render_resource::ShaderType;

/// How a material's painted opacity follows the optical path, and what band it adds.
#[derive(ShaderType, Clone, Copy, Debug, Default, PartialEq, Reflect)]
pub struct Tissue {
    /// [`Tissue::SHELL`], [`Tissue::SOLID`] or [`Tissue::PAINTED`].
    pub kind: u32,
    /// The glow band's radiance where a vertex carries all of it, linear RGB (w unused).
    pub band: Vec4,
}

impl Tissue {
    /// A sheet bounding a shell of mesoglea (the bell): crossed on thickness / |N·V|, so
    /// rims read milky and the centre clear.
    pub const SHELL: u32 = 0;
    /// The surface of a solid tube (tentacles, manubrium, oral arms): crossed on a chord
    /// of thickness × |N·V|, so its edges fade.
    pub const SOLID: u32 = 1;
    /// Opacity as painted (the additive glow layer).
    pub const PAINTED: u32 = 2;

    /// A material whose opacity follows the path through a shell.
    pub const fn shell() -> Self {
        Self {
            kind: Self::SHELL,
            band: Vec4::ZERO,
        }
    }

    /// A material whose opacity follows the chord through a solid tube.
    pub const fn solid() -> Self {
        Self {
            kind: Self::SOLID,
            band: Vec4::ZERO,
        }
    }

    /// A painted layer that adds `band` (linear RGB radiance) where the band lies.
    pub fn glowing(band: LinearRgba) -> Self {
        Self {
            kind: Self::PAINTED,
            band: Vec4::new(band.red, band.green, band.blue, 0.0),
        }
    }
}

/// The tissue layer's fragment shader.
pub(super) const TISSUE_SHADER: &str = "embedded://bevy_jellyfish/plugin/render/tissue.wgsl";
