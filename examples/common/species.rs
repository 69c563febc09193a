//! The shipped species files: read from `assets/species/` so that an edited file shows in
//! the core examples' numbers, and checked before a windowed example starts so that a
//! missing one is said at once. Shared by the examples (`#[path]`-included).
#![allow(dead_code)] // each example that includes it uses a part

use bevy_jellyfish::Species;
use std::path::PathBuf;

/// `assets/species/*.species.ron`, sorted by name, under `BEVY_ASSET_ROOT` where it is set
/// (as the windowed examples read it: a binary run away from its checkout) and else under
/// this crate.
pub fn species_files() -> Vec<PathBuf> {
    let root = std::env::var_os("BEVY_ASSET_ROOT")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    let dir = root.join("assets/species");
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

/// Where Bevy's asset server will find `species/<name>.species.ron` (`BEVY_ASSET_ROOT`,
/// else `CARGO_MANIFEST_DIR`, else the executable's folder, then `assets/`), or, when the
/// file is not there, a message naming the path and the fix.
pub fn find_species_file(name: &str, example: &str) -> Result<PathBuf, String> {
    let root = std::env::var_os("BEVY_ASSET_ROOT")
        .or_else(|| std::env::var_os("CARGO_MANIFEST_DIR"))
        .map(PathBuf::from)
        .or_else(|| {
            std::env::current_exe()
                .ok()
                .and_then(|exe| exe.parent().map(PathBuf::from))
        })
        .unwrap_or_default();
    let path = root
        .join("assets/species")
        .join(format!("{name}.species.ron"));
    if path.is_file() {
        Ok(path)
    } else {
        Err(format!(
            "no species file at {}: run it from the repository (`cargo run --release \
             --features examples --example {example}`) or set BEVY_ASSET_ROOT to the folder \
             holding assets/",
            path.display()
        ))
    }
}
