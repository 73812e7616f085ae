//! What is wrong with a study file: the field and why.

use thiserror::Error;

/// A study file that cannot be run. The CLI puts the file's path in
/// front of it.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum StudyError {
    /// The JSON does not parse, has a wrong type or an unknown field
    /// (serde's message names the field, with the line and column).
    #[error("study does not parse: {0}")]
    Parse(String),
    /// A field's value cannot be used.
    #[error("study field `{field}`: {reason}")]
    Field { field: String, reason: String },
    /// The scene file the study names could not be read or is not valid.
    #[error("scene file `{path}` of the study: {reason}")]
    Scene { path: String, reason: String },
}

impl StudyError {
    pub(crate) fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Field {
            field: field.into(),
            reason: reason.into(),
        }
    }
}
