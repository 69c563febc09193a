//! Why a species was refused: the field and its allowed range, or the file's syntax.

/// Why a species (or a simulation built from one) was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpeciesError {
    /// A parameter is out of range; `field` is its name in [`Species`](super::Species).
    #[error("species field `{field}`: {reason}")]
    Invalid {
        /// The field's name in [`Species`](super::Species).
        field: &'static str,
        /// Why it is refused, with the allowed range.
        reason: String,
    },
    /// The RON text could not be read.
    #[error("species file: {0}")]
    Parse(String),
}

impl SpeciesError {
    /// An error naming `field` and why it is refused.
    pub fn invalid(field: &'static str, reason: impl Into<String>) -> Self {
        Self::Invalid {
            field,
            reason: reason.into(),
        }
    }

    /// The offending field, if the error is about one.
    pub fn field(&self) -> Option<&'static str> {
        match self {
            Self::Invalid { field, .. } => Some(field),
            Self::Parse(_) => None,
        }
    }
}
