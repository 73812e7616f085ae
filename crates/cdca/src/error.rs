//! Typed errors of the library. Every variant carries the offending values.

use thiserror::Error;

/// A scene that cannot be used: it names the field and the value.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SceneError {
    /// The JSON does not parse or has a wrong type or an unknown field.
    #[error("scene does not parse: {0}")]
    Parse(String),
    /// The scene could not be written as JSON.
    #[error("scene cannot be written as JSON: {0}")]
    Write(String),
    /// A field has a value outside its valid range.
    #[error("scene field `{field}` = {value}: {reason}")]
    Invalid {
        field: String,
        value: String,
        reason: String,
    },
}

impl SceneError {
    // the value is usually a temporary (a number or a formatted string)
    #[allow(clippy::needless_pass_by_value)]
    pub(crate) fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        reason: impl Into<String>,
    ) -> Self {
        Self::Invalid {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}

/// A solve that could not produce a trustworthy answer.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SolveError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The assembled matrix is not positive definite (a mechanism, or a
    /// singular enrichment).
    #[error("stiffness matrix is not positive definite ({dofs} DOFs): {detail}")]
    NotPositiveDefinite { dofs: usize, detail: String },
    /// A non-finite number appeared; `place` says where.
    #[error("non-finite value in {place}")]
    NonFinite { place: String },
}
