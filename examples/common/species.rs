//! The shipped species files: read from `assets/species/` so that an edited file shows in
//! the core examples' numbers, and checked before a windowed example starts so that a
//! missing one is said at once; and the `--set field=value` overrides the core examples
//! take. Shared by the examples (`#[path]`-included).
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

/// The value after the option `name` among `args`, if any.
pub fn value<'a>(args: &'a [String], name: &str) -> Option<&'a String> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
}

/// The `--set field=value` pairs among `args` (values in RON).
pub fn overrides(args: &[String]) -> Vec<(String, String)> {
    args.windows(2)
        .filter(|w| w[0] == "--set")
        .filter_map(|w| {
            w[1].split_once('=')
                .map(|(k, v)| (k.to_string(), v.to_string()))
        })
        .collect()
}

/// `species` with `overrides` applied through its RON text; a bad field or value panics
/// with the species' own error naming it.
pub fn with_overrides(species: Species, overrides: &[(String, String)]) -> Species {
    if overrides.is_empty() {
        return species;
    }
    let text = species.to_ron().expect("a species writes as RON");
    let lines: Vec<String> = text
        .lines()
        .map(|line| {
            let key = line.trim_start().split(':').next().unwrap_or("");
            match overrides.iter().find(|(k, _)| k == key) {
                Some((k, v)) => format!("    {k}: {v},"),
                None => line.to_string(),
            }
        })
        .collect();
    Species::from_ron(&lines.join("\n")).unwrap_or_else(|e| panic!("--set: {e}"))
}
