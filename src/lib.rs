//! Jellyfish animated by physical simulation, after Rudolf & Mould, "An Interactive Fluid
//! Model of Jellyfish for Animation" (2009).
//!
//! Layers, each depending only on those below it:
//! - [`species`]: parameters, presets, validation, RON.
//! - [`sim`]: the 2D slice: fluid grid, spring-mass bell, immersed-boundary coupling,
//!   muscles, and [`SliceSim`] that steps them together.
//! - [`shape`]: slice to 3D surface buffers (umbrella, tentacles, variation).
//! - `plugin` (feature `bevy`): the ECS plugin.
//! - `editor` (feature `editor`): the in-game species editor and stats panel (egui).
//!
//! What follows is the README's usage section (`docs/usage.md`, doc-tested here; a test
//! checks that the README holds it word for word).
#![cfg_attr(feature = "bevy", doc = "")]
#![cfg_attr(feature = "bevy", doc = include_str!("../docs/usage.md"))]
#![warn(missing_docs)]

#[cfg(feature = "editor")]
pub mod editor;
#[cfg(feature = "bevy")]
pub mod plugin;
pub mod shape;
pub mod sim;
pub mod species;

#[cfg(feature = "editor")]
pub use editor::JellyfishEditorPlugin;
#[cfg(feature = "bevy")]
pub use plugin::{
    Jellyfish, JellyfishDiagnostics, JellyfishPlugin, JellyfishPlugins, JellyfishSettings,
    JellyfishSystems, SpeciesRejected,
};
pub use sim::{SliceSim, SliceView};
pub use species::{
    BellCoupling, Bending, GonadShape, MuscleLaw, MuscleTiming, SliceGeometry, Species,
    SpeciesError,
};

/// What a game needs: `use bevy_jellyfish::prelude::*;`.
pub mod prelude {
    #[cfg(feature = "editor")]
    pub use crate::JellyfishEditorPlugin;
    #[cfg(feature = "bevy")]
    pub use crate::plugin::{
        AmbientWater, DetailLevels, Disturbance, Flash, Jellyfish, JellyfishDiagnostics,
        JellyfishGeometry, JellyfishPlugin, JellyfishPlugins, JellyfishSettings, JellyfishSlice,
        JellyfishStarted, JellyfishSystems, Pose, Resting, SliceRecovered, SpeciesRejected,
        Steering, StrokeStarted, SurfaceMode, SwimMotion, TankWater, Tier,
    };
    pub use crate::species::{
        BellCoupling, Bending, GonadShape, MuscleLaw, MuscleTiming, SliceGeometry, Species,
        SpeciesError,
    };
}

#[cfg(test)]
mod tests {
    /// The crate's front page is the README's usage section: `docs/usage.md`, included
    /// above and doc-tested, must stand in the README word for word.
    #[test]
    fn the_readme_holds_the_crate_docs() {
        let readme = include_str!("../README.md");
        let usage = include_str!("../docs/usage.md");
        assert!(usage.contains("## In a Bevy app") && usage.contains("## Use it headless"));
        assert!(
            readme.contains(usage),
            "README.md no longer holds docs/usage.md: edit both together"
        );
    }
}
