//! The editor's working copy of one species. Edits go to a draft; a draft that validates
//! replaces the asset, so every jellyfish of the species takes it the next frame, and one
//! that does not stays in the panel with its error. No egui here: this is what tests drive.

use crate::species::{Species, SpeciesError};
use bevy::platform::collections::{HashMap, HashSet};
use bevy::prelude::*;
use std::path::Path;

/// The species editor's state: which species is open, its draft, and each species as
/// first loaded (its preset).
#[derive(Resource, Default, Reflect)]
#[reflect(Resource, Default)]
pub struct SpeciesEditor {
    /// Whether the editor window is shown.
    pub open: bool,
    selected: Option<AssetId<Species>>,
    draft: Species,
    #[reflect(ignore)]
    error: Option<SpeciesError>,
    /// The outcome of the last save or reset, for the panel.
    status: Option<String>,
    presets: HashMap<AssetId<Species>, Species>,
}

impl SpeciesEditor {
    /// The species open for editing, if any.
    pub fn selected(&self) -> Option<AssetId<Species>> {
        self.selected
    }

    /// Opens `id` for editing, with its current value as the draft.
    pub fn select(&mut self, id: AssetId<Species>, assets: &Assets<Species>) {
        self.selected = Some(id);
        self.error = None;
        self.status = None;
        if let Some(species) = assets.get(id) {
            self.draft = species.clone();
        }
    }

    /// The edited copy of the open species, applied when it validates.
    pub fn draft(&self) -> &Species {
        &self.draft
    }

    /// The draft, to edit; call [`Self::apply`] afterwards.
    pub fn draft_mut(&mut self) -> &mut Species {
        &mut self.draft
    }

    /// Why the draft was not applied, if it was not.
    pub fn error(&self) -> Option<&SpeciesError> {
        self.error.as_ref()
    }

    /// What the last save or reset did, for the panel.
    pub fn status(&self) -> Option<&str> {
        self.status.as_deref()
    }

    /// Remembers `species` as the preset of `id`, unless one is already known.
    pub fn remember_preset(&mut self, id: AssetId<Species>, species: &Species) {
        self.presets.entry(id).or_insert_with(|| species.clone());
    }

    /// Validates the draft and, if it is valid and differs, writes it into the asset.
    /// An invalid draft leaves the asset as it was and is reported by [`Self::error`].
    pub fn apply(&mut self, assets: &mut Assets<Species>) -> Result<(), SpeciesError> {
        let Some(id) = self.selected else {
            return Ok(());
        };
        if let Err(e) = self.draft.validate() {
            self.error = Some(e.clone());
            return Err(e);
        }
        self.error = None;
        if let Some(mut species) = assets.get_mut(id)
            && *species != self.draft
        {
            *species = self.draft.clone();
        }
        Ok(())
    }

    /// Grows or shrinks the whole animal to a bell `diameter` wide, m
    /// ([`Species::resized`]: every length of its body scaled, beating at its own rate for
    /// the size), and applies it; a size outside the limits is shown as the draft's error.
    pub fn resize(
        &mut self,
        diameter: f32,
        assets: &mut Assets<Species>,
    ) -> Result<(), SpeciesError> {
        self.draft = self.draft.resized(diameter);
        self.status = Some(format!(
            "the whole animal at {:.1} mm, beating at {:.2} Hz",
            1000.0 * diameter,
            self.draft.contraction_frequency
        ));
        self.apply(assets)
    }

    /// Puts the selected species back to its preset (as first loaded), draft and asset.
    pub fn reset(&mut self, assets: &mut Assets<Species>) {
        let Some(preset) = self.selected.and_then(|id| self.presets.get(&id)) else {
            return;
        };
        self.draft = preset.clone();
        self.status = Some("reset to preset".into());
        // A preset was valid when it loaded.
        let _ = self.apply(assets);
    }

    /// Follows changes made elsewhere (a file reload, a script) while the draft is valid;
    /// an invalid draft is kept so the user can fix it.
    pub fn follow(&mut self, assets: &Assets<Species>) {
        if self.error.is_some() {
            return;
        }
        if let Some(species) = self.selected.and_then(|id| assets.get(id))
            && *species != self.draft
        {
            self.draft = species.clone();
        }
    }

    /// Writes the draft to `path` (see [`write_species_file`]); an invalid draft is not
    /// saved.
    pub fn save(&mut self, path: &Path) -> Result<(), SaveError> {
        let result = match self.draft.validate() {
            Err(e) => Err(SaveError::Invalid(e)),
            Ok(()) => write_species_file(path, &self.draft),
        };
        self.status = Some(match &result {
            Ok(()) => format!("saved {}", path.display()),
            Err(e) => format!("not saved: {e}"),
        });
        result
    }
}

/// Why a species was not saved.
#[derive(Debug, thiserror::Error)]
pub enum SaveError {
    /// The draft does not validate.
    #[error("{0}")]
    Invalid(SpeciesError),
    /// The species could not be written as RON.
    #[error("{0}")]
    Species(#[from] SpeciesError),
    /// The file could not be written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
}

/// Writes `species` as RON to `path` in the shipped files' style: the fields that differ
/// from the moon jelly's (`Species::aurelia`, what a missing field means), keeping the
/// comment lines that head an existing file (they describe the species).
pub fn write_species_file(path: &Path, species: &Species) -> Result<(), SaveError> {
    let io = |source| SaveError::Io {
        path: path.display().to_string(),
        source,
    };
    let header: String = match std::fs::read_to_string(path) {
        Ok(old) => old
            .lines()
            .take_while(|l| l.trim_start().starts_with("//"))
            .map(|l| format!("{l}\n"))
            .collect(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
        Err(e) => return Err(io(e)),
    };
    let text = format!("{header}{}\n", differences_from_default(species)?);
    std::fs::write(path, text).map_err(io)
}

/// Pretty RON of `species` without the field lines equal to the default's. Pretty RON
/// writes this flat struct one field per line; should that ever not hold, the result would
/// not read back equal, and every field is written instead.
fn differences_from_default(species: &Species) -> Result<String, SpeciesError> {
    let full = species.to_ron()?;
    let default = Species::default().to_ron()?;
    let unchanged: HashSet<&str> = default.lines().collect();
    let kept: Vec<&str> = full
        .lines()
        .filter(|l| {
            let field = l.contains(':');
            !field || l.trim_start().starts_with("name:") || !unchanged.contains(l)
        })
        .collect();
    let short = kept.join("\n");
    Ok(match Species::from_ron(&short) {
        Ok(read) if read == *species => short,
        _ => full,
    })
}
