//! The study file (JSON) as serde types, any values: [`Study`](super::Study)
//! checks them. Unknown fields are errors, as in scene files.
//!
//! ```json
//! {
//!   "name": "coplanar and stepped pairs over angle and bridge",
//!   "scene": "../scenes/specimen_two_flaws_stepped.json",
//!   "set": { "mesh.nx": 60, "mesh.ny": 60 },
//!   "flaws": { "length": 0.003, "friction": 0.5 },
//!   "axes": [
//!     { "field": "flaws.layout", "values": ["coplanar", "stepped"] },
//!     { "field": "flaws.angle_deg", "range": { "from": 30, "to": 60, "count": 4 } },
//!     { "field": "flaws.bridge_over_flaw", "random": { "from": 0.5, "to": 1.5, "count": 4 } }
//!   ],
//!   "combine": "grid",
//!   "seed": 7,
//!   "run": "grow"
//! }
//! ```

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::error::StudyError;
use super::flaws::Layout;

/// A study file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    #[serde(default)]
    pub name: String,
    #[serde(default)]
    pub description: String,
    /// The base scene: a scene file's path, relative to the study file, or
    /// the scene itself (an object).
    pub scene: Value,
    /// Fields of the base scene set for every point, by dotted path
    /// (`"mesh.nx": 60`, `"solver.kind": "cg"`).
    #[serde(default)]
    pub set: BTreeMap<String, Value>,
    /// The flaws generator's values for every point (an axis `flaws.NAME`
    /// varies one). With it, or with an axis on it, the generator draws
    /// each point's cracks.
    #[serde(default)]
    pub flaws: Option<FlawsSpec>,
    /// What varies, in order: the first axis varies slowest in a grid.
    pub axes: Vec<AxisSpec>,
    /// How the axes' values make points.
    #[serde(default)]
    pub combine: Combine,
    /// Points of a joint random sample (`combine: "random"` only).
    #[serde(default)]
    pub count: Option<usize>,
    /// Seed of every random draw of the study (needed by random axes and
    /// the random sample).
    #[serde(default)]
    pub seed: Option<u64>,
    /// What each point runs.
    #[serde(default)]
    pub run: RunKind,
}

impl StudyFile {
    pub fn from_json(text: &str) -> Result<Self, StudyError> {
        serde_json::from_str(text).map_err(|e| StudyError::Parse(e.to_string()))
    }

    /// The path of the base scene's file, when the study names one.
    pub fn scene_path(&self) -> Option<&str> {
        self.scene.as_str()
    }
}

/// One axis: a field and its values, given in exactly one of three ways.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisSpec {
    /// A scene field's dotted path (`cracks.0.friction`,
    /// `boundary.top.normal`, `cracks`), or one of the flaws generator's
    /// inputs (`flaws.layout`, `flaws.length`, `flaws.angle_deg`,
    /// `flaws.friction`, `flaws.bridge_over_flaw`).
    pub field: String,
    /// The values listed: numbers, or any JSON the field takes (a layout's
    /// name, a solver's kind, a list of cracks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<Value>>,
    /// Evenly spaced numbers, ends included.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub range: Option<RangeSpec>,
    /// Uniform random numbers in [from, to), drawn with the file's seed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub random: Option<RandomSpec>,
}

/// `count` numbers from `from` to `to`, ends included (`from` alone when
/// `count` is 1), evenly spaced and rounded to 15 significant digits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RangeSpec {
    pub from: f64,
    pub to: f64,
    pub count: usize,
}

/// Uniform random numbers in [from, to): `count` of them in a grid or a
/// zip; in a joint random sample one per point (no `count`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RandomSpec {
    pub from: f64,
    pub to: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<usize>,
}

/// How axes combine into points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Combine {
    /// Every combination, the first axis varying slowest.
    #[default]
    Grid,
    /// The k-th values of every axis together (axes of equal length).
    Zip,
    /// `count` points, each axis's value drawn at random (a listed or
    /// ranged axis: one of its values, each as likely).
    Random,
}

/// What each point runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunKind {
    /// Growth to its end, as `cdca grow`.
    #[default]
    Grow,
    /// The first growth step only: the point's scene with
    /// `growth.max_steps = 1`, grown as `cdca grow`.
    FirstStep,
}

/// The flaws generator's inputs for every point (see
/// [`Flaws`](super::Flaws)); an input left out takes the bundled pairs'
/// value.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlawsSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layout: Option<Layout>,
    /// Each flaw's length, m (3 mm).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// The flaws' angle to the horizontal, degrees (45).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
    /// Face friction μ (0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
    /// The bridge between the facing ends over the flaw length (1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bridge_over_flaw: Option<f64>,
    /// Where the flaws' centre is off the specimen's, in element sizes
    /// (`[0, 0]`; the flaw range's single flaw sits off the grid at
    /// `[0.37, 0.21]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset_elements: Option<[f64; 2]>,
}
