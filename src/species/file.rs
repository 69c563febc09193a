//! A species file: RON text in and out, every value validated on the way in.

use super::{Species, SpeciesError, limits};

impl Species {
    /// Parses a species from RON text, then validates it.
    pub fn from_ron(text: &str) -> Result<Self, SpeciesError> {
        let species: Species =
            ron::from_str(text).map_err(|e| SpeciesError::Parse(e.to_string()))?;
        species.validate()?;
        Ok(species)
    }

    /// Writes the species as pretty RON.
    pub fn to_ron(&self) -> Result<String, SpeciesError> {
        ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default())
            .map_err(|e| SpeciesError::Parse(e.to_string()))
    }

    /// Checks every parameter against [`limits::LIMITS`] and the limits that join fields
    /// (proportions, the mesh's vertex budget, the slice's cost); the error names the
    /// first bad field, its allowed range and why.
    pub fn validate(&self) -> Result<(), SpeciesError> {
        limits::validate(self)
    }
}
