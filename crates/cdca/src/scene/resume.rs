//! Where a growth run saved mid-way stands (`growth.resume`): what the next
//! growth step starts from besides the cracks, so that a scene saved at any
//! moment of a run and opened again grows the same next step, to the last
//! digit, as the run that went on.
//!
//! Every step starts from the scene: displacement zero, the contact states
//! below (the committed slip history of load control, the initial guess of
//! the contact iteration under critical control), and, under critical
//! control, its first λ_cr trial at the last step's load factor.

use serde::{Deserialize, Serialize};

use crate::error::SceneError;

/// State of a growth run between two steps. Written by the solver into
/// the simulated scene after every step; absent in a scene not yet grown.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Resume {
    /// Growth steps done (the next one is `steps + 1`).
    pub steps: usize,
    /// Load factor λ of the last step (critical control: λ_cr, where the
    /// next step's search starts).
    pub load_factor: f64,
    /// Load control: the load increment (1-based) the run is at, and the
    /// growths done at it.
    #[serde(default = "first_increment")]
    pub increment: usize,
    #[serde(default)]
    pub growths_here: usize,
    /// One entry per crack-face point of the saved cracks' discretisation,
    /// in its order: `[state, g_T^s, g_N, g_T, p_N, p_T]` with state 0 open,
    /// 1 stick, 2 slip; gaps in m, tractions in Pa.
    #[serde(default)]
    pub faces: Vec<[f64; 6]>,
    /// Per crack, the segments grown at its two ends, as scenes saved by
    /// version 0.1 wrote them. Read and ignored: the criterion no longer
    /// depends on which tips grew (one rule at every tip), so nothing
    /// needs it; never written.
    #[serde(default, skip_serializing)]
    pub grown: Vec<[usize; 2]>,
}

fn first_increment() -> usize {
    1
}

impl Resume {
    /// Checks the values (the face count is checked against the
    /// discretisation when a simulation is built).
    pub(crate) fn validate(&self) -> Result<(), SceneError> {
        let lambda = self.load_factor;
        if !lambda.is_finite() || lambda < 0.0 {
            return Err(SceneError::invalid(
                "growth.resume.load_factor",
                lambda,
                "must be a finite number ≥ 0",
            ));
        }
        if self.increment == 0 {
            return Err(SceneError::invalid(
                "growth.resume.increment",
                0,
                "must be at least 1",
            ));
        }
        for (i, f) in self.faces.iter().enumerate() {
            let field = format!("growth.resume.faces[{i}]");
            if let Some(v) = f.iter().find(|v| !v.is_finite()) {
                return Err(SceneError::invalid(field, v, "must be finite"));
            }
            if ![0.0, 1.0, 2.0].contains(&f[0]) {
                return Err(SceneError::invalid(
                    format!("{field}[0]"),
                    f[0],
                    "must be 0 (open), 1 (stick) or 2 (slip)",
                ));
            }
        }
        Ok(())
    }
}
