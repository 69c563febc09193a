//! What the test binaries share: the shipped species files and, with Bevy, a headless app.
#![allow(dead_code)] // each test binary that includes it uses a part

#[cfg(feature = "bevy")]
pub mod app;

// The shipped species files, read as the core examples read them (one loader for both).
#[path = "../../examples/common/species.rs"]
mod files;
#[allow(unused_imports)] // each binary uses one or both
pub use files::{shipped_species, species_files};
