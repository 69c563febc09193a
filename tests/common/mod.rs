//! What the test binaries share: the shipped species files and, with Bevy, a headless app.
#![allow(dead_code)] // each test binary that includes it uses a part

#[cfg(feature = "bevy")]
pub mod app;

use bevy_jellyfish::Species;
use std::path::{Path, PathBuf};

/// `assets/species/*.species.ron`, sorted by name.
pub fn species_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/species");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".species.ron"))
        .collect();
    files.sort();
    files
}

/// Every shipped species file, parsed and validated, in file-name order.
pub fn shipped_species() -> Vec<Species> {
    species_files()
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            Species::from_ron(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()))
        })
        .collect()
}
