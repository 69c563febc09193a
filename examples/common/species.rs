//! The shipped species files: read from `assets/species/` so that an edited file shows in
//! the core examples' numbers, and checked before a windowed example starts so that a
//! missing one is said at once; and the `--set field=value` overrides the core examples
//! take. Shared by the examples and the test binaries (`#[path]`-included).
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

/// The `--set field=value` pairs among `args` (values in RON); a `--set` without a
/// `field=value` after it ends the program with an error saying so.
pub fn overrides(args: &[String]) -> Vec<(String, String)> {
    args.iter()
        .enumerate()
        .filter(|(_, a)| *a == "--set")
        .map(|(i, _)| {
            let pair = args.get(i + 1).and_then(|a| a.split_once('='));
            let Some((k, v)) = pair else {
                refuse("--set needs field=value after it (e.g. --set grid_resolution=90)")
            };
            (k.to_string(), v.to_string())
        })
        .collect()
}

/// `species` with `overrides` applied through its RON text. A field the species does not
/// have, or a value it rejects, ends the program with the species' own error naming it,
/// never a silent default.
pub fn with_overrides(species: Species, overrides: &[(String, String)]) -> Species {
    if overrides.is_empty() {
        return species;
    }
    // One line a field: below the top level nothing is pretty-printed, so a colour's
    // tuple stays on its field's line and only the species' own fields start a line.
    let pretty = ron::ser::PrettyConfig::default().depth_limit(1);
    let text = ron::ser::to_string_pretty(&species, pretty).expect("a species writes as RON");
    if let Some((k, _)) = overrides
        .iter()
        .find(|(k, _)| !text.lines().any(|line| field(line) == k))
    {
        refuse(&format!("--set: a species has no field `{k}`"));
    }
    let lines: Vec<String> = text
        .lines()
        .map(
            |line| match overrides.iter().find(|(k, _)| k == field(line)) {
                Some((k, v)) => format!("    {k}: {v},"),
                None => line.to_string(),
            },
        )
        .collect();
    Species::from_ron(&lines.join("\n")).unwrap_or_else(|e| refuse(&format!("--set: {e}")))
}

/// The field a line of a species' RON text sets: a line at the first indent, `name:`
/// ("" for the brackets).
fn field(line: &str) -> &str {
    line.strip_prefix("    ")
        .filter(|rest| !rest.starts_with(' '))
        .and_then(|rest| rest.split_once(':'))
        .map_or("", |(name, _)| name)
}

/// Ends the program on bad input with `message` and exit status 2, as a command-line tool
/// does, instead of a panic's backtrace.
pub fn refuse(message: &str) -> ! {
    eprintln!("{message}");
    std::process::exit(2)
}
