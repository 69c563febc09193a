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
    Jellyfish, JellyfishDiagnostics, JellyfishPlugin, JellyfishSettings, JellyfishSystems,
    SpeciesRejected,
};
pub use sim::{SliceSim, SliceView};
pub use species::{Species, SpeciesError};

/// What a game needs: `use bevy_jellyfish::prelude::*;`.
pub mod prelude {
    #[cfg(feature = "editor")]
    pub use crate::JellyfishEditorPlugin;
    #[cfg(feature = "bevy")]
    pub use crate::plugin::{
        AmbientWater, DetailLevels, Jellyfish, JellyfishDiagnostics, JellyfishGeometry,
        JellyfishPlugin, JellyfishSettings, JellyfishSlice, JellyfishStarted, JellyfishSystems,
        Pose, Resting, SliceRecovered, SpeciesRejected, Steering, StrokeStarted, SurfaceMode,
        SwimMotion, TankWater, Tier,
    };
    pub use crate::species::{Species, SpeciesError};
}

/// The README's code examples, compiled and run as doctests (they include a Bevy app).
#[cfg(all(doctest, feature = "bevy"))]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
