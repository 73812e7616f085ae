//! **Studies**: long work that runs many simulations and sets their
//! results side by side, and the plots of those results. Uses `run` (the
//! pacer, the task, the runner's growth solver), `plots` (the figure
//! primitives), `results`, `files` and `style`; nothing above.
//!
//! - this file: a parameter study of one scene field (`Study`);
//! - `file`: a study file's points (`docs/studies.md`);
//! - `map`: the study file's maps;
//! - `race`: Compare solvers, the solver race;
//! - `figures`: the race's and the parameter study's plots.
//!
//! Parameter studies (the *Study* tab): one scene parameter swept over a
//! list of values; for each value a simulation of the modified scene grows
//! until its first step that extends a tip, and the kink angle, mode, load
//! factor and SIFs of that step are recorded. One resumable simulation at a
//! time, advanced inside the frame budget.

pub(crate) mod figures;
pub mod file;
pub(crate) mod map;
pub mod race;

use std::fmt::Write as _;

use cdca::report::{GrownTip, IntactRockReport, NucleatedCrack, Outcome};
use cdca::{Scene, Simulation};
use web_time::Instant;

use crate::run::host::growth_solver;
use crate::run::pacer::Pacer;
use crate::run::task::{Progress, Task};

/// Parameters offered in the Study tab (any numeric scene path works).
pub const SUGGESTED_PATHS: [&str; 6] = [
    "cracks.0.friction",
    "cracks.0.cohesion",
    "boundary.right.normal",
    "boundary.top.normal",
    "criterion.r0",
    "material.poisson",
];

/// The unit a parameter is shown in, and the factor from SI to it, from the
/// last segment of its path.
pub fn param_unit(path: &str) -> (&'static str, f64) {
    let last = path.rsplit('.').next().unwrap_or(path);
    match last {
        "normal" | "shear" | "cohesion" | "young" | "sigma_t" | "kn" | "kt" => ("MPa", 1e-6),
        "k_ic" | "k_iic" => ("MPa·√m", 1e-6),
        "r0" | "width" | "height" | "thickness" | "increment" => ("mm", 1e3),
        "friction_angle_deg" => ("°", 1.0),
        _ => ("–", 1.0),
    }
}

/// What the Study tab is set to run (edited in place by the panel; values
/// in the parameter's display unit).
#[derive(Clone, Debug, PartialEq)]
pub struct StudySetup {
    pub path: String,
    pub from: f64,
    pub to: f64,
    /// Number of values, evenly spaced from `from` to `to`.
    pub count: usize,
}

impl Default for StudySetup {
    fn default() -> Self {
        Self {
            path: SUGGESTED_PATHS[0].to_owned(),
            from: 0.0,
            to: 0.8,
            count: 9,
        }
    }
}

impl StudySetup {
    /// The values in SI units.
    pub fn values(&self) -> Vec<f64> {
        let (_, factor) = param_unit(&self.path);
        let n = self.count.max(1);
        (0..n)
            .map(|i| {
                let t = if n == 1 {
                    0.0
                } else {
                    i as f64 / (n - 1) as f64
                };
                (self.from + t * (self.to - self.from)) / factor
            })
            .collect()
    }
}

/// The first growing step of one value.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyPoint {
    /// The parameter's value, SI.
    pub value: f64,
    /// Load factor of the first step that grew a tip.
    pub load_factor: Option<f64>,
    /// The tips that grew in that step (empty: none grew).
    pub grown: Vec<GrownTip>,
    /// The cracks started in the intact rock in that step: under
    /// `growth.intact_rock` `"nucleate"` the rock can fail before any tip
    /// grows (a long friction-held flaw), and that is the first growth.
    pub nucleated: Vec<NucleatedCrack>,
    /// How growth ended if no tip grew.
    pub outcome: Option<Outcome>,
    /// Growth steps run.
    pub steps: usize,
    /// Why this value could not be simulated.
    pub error: Option<String>,
    /// The rock away from the cracks at that step's load.
    pub intact_rock: Option<IntactRockReport>,
}

impl StudyPoint {
    /// A value whose run ended (`outcome`) or failed (`error`) before any
    /// tip grew.
    fn none_grew(
        value: f64,
        steps: usize,
        outcome: Option<Outcome>,
        error: Option<String>,
    ) -> Self {
        Self {
            value,
            load_factor: None,
            grown: Vec::new(),
            nucleated: Vec::new(),
            outcome,
            steps,
            error,
            intact_rock: None,
        }
    }
}

/// A running or finished parameter study.
pub struct Study {
    pub path: String,
    pub values: Vec<f64>,
    base: Scene,
    accelerate: bool,
    sim: Option<Simulation>,
    /// Sweeps per `advance_growth` call.
    pacer: Pacer,
    pub points: Vec<StudyPoint>,
    cancelled: bool,
}

impl Study {
    /// A study of `path` over `values` (SI) on `base`; `accelerate` as in
    /// growth. The path is checked on the first value.
    pub fn new(
        base: &Scene,
        path: &str,
        values: Vec<f64>,
        accelerate: bool,
    ) -> Result<Self, String> {
        let first = values.first().ok_or("the study needs at least one value")?;
        base.with_param(path, *first).map_err(|e| e.to_string())?;
        Ok(Self {
            path: path.to_owned(),
            values,
            base: base.clone(),
            accelerate,
            sim: None,
            pacer: Pacer::default(),
            points: Vec::new(),
            cancelled: false,
        })
    }

    pub fn finished(&self) -> bool {
        self.cancelled || self.points.len() >= self.values.len()
    }

    pub fn cancelled(&self) -> bool {
        self.cancelled
    }

    /// Stops after the values done so far.
    pub fn cancel(&mut self) {
        self.cancelled = true;
        self.sim = None;
    }

    /// Fraction of the values done.
    pub fn progress(&self) -> f32 {
        self.points.len() as f32 / self.values.len().max(1) as f32
    }

    fn build(&self, value: f64) -> Result<Simulation, String> {
        let accelerate = self.accelerate;
        let scene = self
            .base
            .with_param(&self.path, value)
            .and_then(|s| s.edit(|f| f.solver = growth_solver(&f.solver, accelerate)))
            .map_err(|e| e.to_string())?;
        crate::run::host::interactive_mesh(&scene)?;
        Simulation::new(scene).map_err(|e| e.to_string())
    }

    fn record(&mut self, point: StudyPoint) {
        self.sim = None;
        self.points.push(point);
    }

    /// One row per grown tip (or one row saying none grew): the parameter
    /// in SI units, the load factor, the tip, its mode, kink angle (degrees
    /// from the crack's direction), SIFs (Pa·√m) and the intact rock's
    /// utilisation of its strength at that load. A crack started in the
    /// intact rock is a row of mode `intact_tension` or `intact_shear`
    /// with its direction (degrees from +x) as the angle and no tip or K.
    pub fn to_csv(&self) -> String {
        let mut out = format!(
            "{},load_factor,crack,tip,mode,angle_deg,k1,k2,steps,outcome,error,intact_rock_utilisation\n",
            self.path
        );
        for p in &self.points {
            let outcome = p
                .outcome
                .map(|o| format!("{o:?}").to_lowercase())
                .unwrap_or_default();
            let error = p.error.as_deref().unwrap_or("").replace([',', '\n'], ";");
            let lambda = p.load_factor.map(|l| l.to_string()).unwrap_or_default();
            let rock = p
                .intact_rock
                .map(|r| r.utilisation.to_string())
                .unwrap_or_default();
            for n in &p.nucleated {
                // a crack started in the intact rock: its direction, no tip
                // or K of its own yet
                let _ = writeln!(
                    out,
                    "{},{lambda},{},,intact_{},{},,,{},{outcome},{error},{rock}",
                    p.value,
                    n.crack,
                    n.mode.name(),
                    n.direction_deg,
                    p.steps
                );
            }
            if p.grown.is_empty() && p.nucleated.is_empty() {
                let _ = writeln!(
                    out,
                    "{},{lambda},,,none,,,,{},{outcome},{error},{rock}",
                    p.value, p.steps
                );
            }
            for g in &p.grown {
                let _ = writeln!(
                    out,
                    "{},{lambda},{},{},{},{},{},{},{},{outcome},{error},{rock}",
                    p.value,
                    g.crack,
                    g.tip,
                    g.mode.name(),
                    g.angle_deg,
                    g.k1,
                    g.k2,
                    p.steps
                );
            }
        }
        out
    }
}

impl Task for Study {
    /// Advances the study until about `deadline`: builds the simulation of
    /// the next value, then advances its growth in resumable chunks (sized
    /// by the pacer) until a step grows a tip or the run ends. (Building
    /// one simulation is not split: on the default scene it is a few tens
    /// of ms.)
    fn advance(&mut self, deadline: Instant) -> Result<Progress, String> {
        while !self.finished() {
            let start = Instant::now();
            let value = self.values[self.points.len()];
            if self.sim.is_none() {
                match self.build(value) {
                    Ok(sim) => self.sim = Some(sim),
                    Err(e) => {
                        self.record(StudyPoint::none_grew(value, 0, None, Some(e)));
                        continue;
                    }
                }
            }
            let Some(sim) = self.sim.as_mut() else {
                continue;
            };
            let n = self.pacer.sweeps();
            match sim.advance_growth(n) {
                Err(e) => {
                    let steps = sim.history().len();
                    self.record(StudyPoint::none_grew(
                        value,
                        steps,
                        None,
                        Some(e.to_string()),
                    ));
                }
                Ok(Some(step)) if !(step.grown.is_empty() && step.nucleated.is_empty()) => {
                    let steps = sim.history().len();
                    self.record(StudyPoint {
                        value,
                        load_factor: Some(step.load_factor),
                        grown: step.grown,
                        nucleated: step.nucleated,
                        outcome: None,
                        steps,
                        error: None,
                        intact_rock: step.intact_rock,
                    });
                }
                Ok(_) => {
                    if let Some(outcome) = sim.growth_finished() {
                        let steps = sim.history().len();
                        self.record(StudyPoint::none_grew(value, steps, Some(outcome), None));
                    }
                }
            }
            if !self.pacer.another_fits(start, n, deadline) {
                break;
            }
        }
        Ok(if self.finished() {
            Progress::Finished
        } else {
            Progress::Working
        })
    }
}

/// A scene path as the UI shows it: scene files count cracks from 0
/// (`cracks.0.friction`), the panels from 1 ("Crack 1"), so a crack's path
/// says which panel crack it is: `cracks.0.friction (crack 1)`. Paths are
/// typed and saved as the scene file has them.
pub fn path_label(path: &str) -> String {
    let mut parts = path.split('.');
    match (
        parts.next(),
        parts.next().and_then(|i| i.parse::<usize>().ok()),
    ) {
        (Some("cracks"), Some(i)) => format!("{path} (crack {})", i + 1),
        _ => path.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_evenly_spaced_in_si() {
        let s = StudySetup {
            path: "boundary.right.normal".to_owned(),
            from: -2.0,
            to: -6.0,
            count: 3,
        };
        let v = s.values();
        assert_eq!(v.len(), 3);
        assert!(
            (v[0] + 2e6).abs() < 1e-6 && (v[1] + 4e6).abs() < 1e-6 && (v[2] + 6e6).abs() < 1e-6
        );
    }

    /// The Study tab names a crack's path with the panel's 1-based number.
    #[test]
    fn crack_paths_say_the_panels_crack_number() {
        assert_eq!(
            path_label("cracks.0.friction"),
            "cracks.0.friction (crack 1)"
        );
        assert_eq!(
            path_label("cracks.2.cohesion"),
            "cracks.2.cohesion (crack 3)"
        );
        assert_eq!(path_label("boundary.top.normal"), "boundary.top.normal");
    }

    #[test]
    fn a_bad_path_is_refused_with_a_reason() {
        let scene = cdca::Scene::try_from(crate::files::scenes::default_scene()).expect("valid");
        let err = Study::new(&scene, "cracks.0.nothing", vec![1.0], true)
            .err()
            .unwrap_or_default();
        assert!(err.contains("nothing"), "{err}");
    }
}
