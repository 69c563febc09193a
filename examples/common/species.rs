//! The shipped species files, read from `assets/species/` so that an edited file shows in
//! the core examples' numbers. Shared by the examples (`#[path]`-included).
#![allow(dead_code)] // each example that includes it uses a part

use bevy_jellyfish::Species;
use std::path::{Path, PathBuf};

/// `assets/species/*.species.ron`, sorted by name.
pub fn species_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/species");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(".species.ron"))
        .collect();
    files.sort();
    files
}

/// Every shipped species, parsed and validated; a bad file panics with its path and reason.
pub fn shipped_species() -> Vec<Species> {
    species_files()
        .iter()
        .map(|f| {
            let text = std::fs::read_to_string(f).expect("readable species file");
            Species::from_ron(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()))
        })
        .collect()
}
