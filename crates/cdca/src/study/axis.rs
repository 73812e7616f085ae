//! One axis of a study, checked: the field it sets and its values; a
//! point: one value of every axis.

use serde_json::Value;

use super::error::StudyError;
use super::file::{AxisSpec, Combine};
use super::flaws::Layout;
use super::random::SplitMix64;

/// Points a study may have (a grid's product of its axes' counts).
pub const MAX_POINTS: usize = 1_000_000;

/// One point of a study: its number (1-based, in the study's order) and
/// one input per axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub id: usize,
    pub inputs: Vec<Input>,
}

/// One input value of a point.
#[derive(Clone, Debug, PartialEq)]
pub enum Input {
    Number(f64),
    /// Any other JSON value (a layout's name, a list of cracks).
    Json(Value),
}

impl Input {
    fn of(value: &Value) -> Self {
        match value.as_f64() {
            Some(x) if value.is_number() => Self::Number(x),
            _ => Self::Json(value.clone()),
        }
    }

    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Self::Number(x) => Some(*x),
            Self::Json(_) => None,
        }
    }

    /// The value as JSON (a number as the number).
    pub fn to_json(&self) -> Value {
        match self {
            Self::Number(x) => crate::scene::json_number(*x),
            Self::Json(v) => v.clone(),
        }
    }

    /// As a CSV cell: a number in Rust's shortest round-trip form, a text
    /// as it is, other JSON compact (quoted where it must be).
    pub fn csv(&self) -> String {
        match self {
            Self::Number(x) => x.to_string(),
            Self::Json(Value::String(s)) => crate::csv::field(s),
            Self::Json(v) => crate::csv::field(&v.to_string()),
        }
    }
}

/// What an axis sets.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// A scene field, by its dotted path.
    Scene(String),
    /// One of the flaws generator's inputs.
    Flaws(FlawsInput),
}

/// The flaws generator's inputs an axis can vary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FlawsInput {
    Layout,
    Length,
    AngleDeg,
    Friction,
    BridgeOverFlaw,
}

impl FlawsInput {
    const ALL: [(&'static str, Self); 5] = [
        ("layout", Self::Layout),
        ("length", Self::Length),
        ("angle_deg", Self::AngleDeg),
        ("friction", Self::Friction),
        ("bridge_over_flaw", Self::BridgeOverFlaw),
    ];
}

/// Where an axis's values come from.
#[derive(Clone, Debug, PartialEq)]
enum Source {
    List(Vec<Input>),
    /// One uniform draw in [from, to) per point of a joint random sample.
    Random {
        from: f64,
        to: f64,
    },
}

/// A checked axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The field as the file names it (the CSV column's name).
    pub field: String,
    pub target: Target,
    source: Source,
}

impl Axis {
    /// Checks axis `k` of a study combined by `combine`, drawing a random
    /// axis's values (grid and zip) from `rng`. `rng` is `None` when the
    /// file has no seed.
    pub(crate) fn new(
        spec: &AxisSpec,
        k: usize,
        combine: Combine,
        rng: Option<&mut SplitMix64>,
    ) -> Result<Self, StudyError> {
        let at = |what: &str| format!("axes[{k}]{what}");
        let target = match spec.field.strip_prefix("flaws.") {
            Some(name) => {
                let input = FlawsInput::ALL
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map(|(_, i)| *i)
                    .ok_or_else(|| {
                        let names: Vec<&str> = FlawsInput::ALL.iter().map(|(n, _)| *n).collect();
                        StudyError::field(
                            at(".field"),
                            format!(
                                "`{}`: the flaws generator has no input `{name}` (it has {})",
                                spec.field,
                                names.join(", ")
                            ),
                        )
                    })?;
                Target::Flaws(input)
            }
            None => Target::Scene(spec.field.clone()),
        };
        let source = match (&spec.values, spec.range, spec.random) {
            (Some(values), None, None) => {
                if values.is_empty() {
                    return Err(StudyError::field(at(".values"), "an empty list of values"));
                }
                Source::List(values.iter().map(Input::of).collect())
            }
            (None, Some(r), None) => {
                if r.count == 0 {
                    return Err(StudyError::field(
                        at(".range.count"),
                        "0: an empty range (count must be at least 1)",
                    ));
                }
                finite(&at(".range"), r.from, r.to)?;
                let n = r.count;
                // rounded to 15 significant digits, which a decimal range
                // needs no more of: 1e-4 to 3e-4 in 3 gives 2e-4, not
                // 1.9999999999999998e-4; the ends are `from` and `to`
                let step = |i: usize| match i {
                    0 => r.from,
                    i if i + 1 == n => r.to,
                    i => {
                        let x = r.from + (r.to - r.from) * (i as f64 / (n - 1) as f64);
                        format!("{x:.14e}").parse().unwrap_or(x)
                    }
                };
                Source::List((0..n).map(|i| Input::Number(step(i))).collect())
            }
            (None, None, Some(r)) => {
                finite(&at(".random"), r.from, r.to)?;
                if r.to < r.from {
                    return Err(StudyError::field(
                        at(".random"),
                        format!("from {} above to {}: an empty range", r.from, r.to),
                    ));
                }
                let rng = rng.ok_or_else(|| {
                    StudyError::field("seed", "a random axis needs the file's `seed`")
                })?;
                match (combine, r.count) {
                    (Combine::Random, None) => Source::Random {
                        from: r.from,
                        to: r.to,
                    },
                    (Combine::Random, Some(_)) => {
                        return Err(StudyError::field(
                            at(".random.count"),
                            "not used in a joint random sample (its points are the file's `count`)",
                        ));
                    }
                    (_, None | Some(0)) => {
                        return Err(StudyError::field(
                            at(".random.count"),
                            "missing or 0: a random axis of a grid or zip needs a count of at least 1",
                        ));
                    }
                    (_, Some(n)) => Source::List(
                        (0..n)
                            .map(|_| Input::Number(rng.uniform(r.from, r.to)))
                            .collect(),
                    ),
                }
            }
            _ => {
                return Err(StudyError::field(
                    at(""),
                    format!(
                        "axis `{}` needs exactly one of `values`, `range` and `random`",
                        spec.field
                    ),
                ));
            }
        };
        let axis = Self {
            field: spec.field.clone(),
            target,
            source,
        };
        axis.check_values(k)?;
        Ok(axis)
    }

    /// Values of the flaws generator's inputs are of their kind: a
    /// layout's name, or a number.
    fn check_values(&self, k: usize) -> Result<(), StudyError> {
        let Target::Flaws(input) = self.target else {
            return Ok(());
        };
        let Source::List(values) = &self.source else {
            return if input == FlawsInput::Layout {
                Err(StudyError::field(
                    format!("axes[{k}].random"),
                    "a layout is named, not drawn as a number",
                ))
            } else {
                Ok(())
            };
        };
        for (j, v) in values.iter().enumerate() {
            let ok = match (input, v) {
                (FlawsInput::Layout, Input::Json(Value::String(name))) => {
                    Layout::from_name(name).is_some()
                }
                (FlawsInput::Layout, _) | (_, Input::Json(_)) => false,
                (_, Input::Number(_)) => true,
            };
            if !ok {
                let names: Vec<&str> = Layout::ALL.iter().map(|l| l.name()).collect();
                let want = if input == FlawsInput::Layout {
                    format!("one of {}", names.join(", "))
                } else {
                    "a number".to_owned()
                };
                return Err(StudyError::field(
                    format!("axes[{k}].values[{j}]"),
                    format!("{}: must be {want}", v.to_json()),
                ));
            }
        }
        Ok(())
    }

    /// Values of a listed, ranged or (grid, zip) random axis; `None` for a
    /// random axis of a joint random sample.
    pub fn values(&self) -> Option<&[Input]> {
        match &self.source {
            Source::List(v) => Some(v),
            Source::Random { .. } => None,
        }
    }

    /// Whether every value is a number (the axis of a plot).
    pub fn is_numeric(&self) -> bool {
        match &self.source {
            Source::List(v) => v.iter().all(|x| matches!(x, Input::Number(_))),
            Source::Random { .. } => true,
        }
    }

    /// One value drawn for a point of a joint random sample.
    pub(crate) fn draw(&self, rng: &mut SplitMix64) -> Input {
        match &self.source {
            Source::List(v) => v[rng.index(v.len())].clone(),
            Source::Random { from, to } => Input::Number(rng.uniform(*from, *to)),
        }
    }
}

fn finite(field: &str, from: f64, to: f64) -> Result<(), StudyError> {
    if from.is_finite() && to.is_finite() {
        Ok(())
    } else {
        Err(StudyError::field(
            field,
            "`from` and `to` must be finite numbers",
        ))
    }
}
