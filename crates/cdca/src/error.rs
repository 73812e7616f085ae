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
    /// A field has a value outside its valid range. `field` is the dotted
    /// JSON path (`cracks[0].points[1]`) and `value` the value as the file
    /// holds it (SI units), so that an app can name both in its own words
    /// and units; the message shows them as the file does.
    #[error("scene field `{field}` = {value}: {reason}")]
    Invalid {
        field: String,
        value: FieldValue,
        reason: String,
    },
}

/// The value a [`SceneError::Invalid`] names: a number or a point in SI
/// units, a count, or a description (`"60 × 60"`, `"3 entries"`) where
/// the value is not one number.
#[derive(Clone, Debug, PartialEq)]
pub enum FieldValue {
    Number(f64),
    Point([f64; 2]),
    Count(usize),
    Text(String),
}

impl From<f64> for FieldValue {
    fn from(v: f64) -> Self {
        Self::Number(v)
    }
}

impl From<[f64; 2]> for FieldValue {
    fn from(p: [f64; 2]) -> Self {
        Self::Point(p)
    }
}

impl From<usize> for FieldValue {
    fn from(n: usize) -> Self {
        Self::Count(n)
    }
}

impl From<String> for FieldValue {
    fn from(text: String) -> Self {
        Self::Text(text)
    }
}

impl From<&str> for FieldValue {
    fn from(text: &str) -> Self {
        Self::Text(text.to_owned())
    }
}

impl std::fmt::Display for FieldValue {
    /// As the messages show it: a point as `[x, y]`, each number as
    /// written for everyday magnitudes and in exponent form beyond (`1e300`,
    /// not three hundred digits).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Number(v) => write!(f, "{}", Num(*v)),
            Self::Point(p) => write!(f, "[{}, {}]", Num(p[0]), Num(p[1])),
            Self::Count(n) => write!(f, "{n}"),
            Self::Text(text) => f.write_str(text),
        }
    }
}

/// A number as the messages show it (see [`FieldValue`]'s `Display`).
pub(crate) struct Num(pub(crate) f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let m = self.0.abs();
        if m == 0.0 || !m.is_finite() || (1e-4..1e15).contains(&m) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

impl SceneError {
    pub(crate) fn invalid(
        field: impl Into<String>,
        value: impl Into<FieldValue>,
        reason: impl Into<String>,
    ) -> Self {
        Self::Invalid {
            field: field.into(),
            value: value.into(),
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
