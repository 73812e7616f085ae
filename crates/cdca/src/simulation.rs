//! The facade used by the CLI and the workbench: one scene, its model, its
//! mutable state and its scratch, and the steps of the method.

use crate::error::SolveError;
use crate::report::{GrowthStepReport, SolveReport, TipReport};
use crate::scene::Scene;

/// State of a crack-face contact point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactState {
    Open,
    Stick,
    Slip,
}

/// A crack-face integration point as the UI shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPointView {
    /// Position, m.
    pub x: f64,
    pub y: f64,
    /// Unit normal pointing into the φ > 0 side.
    pub normal: [f64; 2],
    pub state: ContactState,
    /// Normal traction p_N, Pa (≤ 0 in contact).
    pub p_n: f64,
    /// Tangential traction p_T, Pa.
    pub p_t: f64,
    /// Tangential gap (slip) g_T, m.
    pub slip: f64,
}

/// σ_θθ and τ_rθ on the circle r0 around one tip (SPEC §8), for plots.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CriterionCurve {
    /// Angles in the tip frame, degrees.
    pub theta_deg: Vec<f64>,
    /// σ_θθ(θ, r0), Pa.
    pub sigma_tt: Vec<f64>,
    /// τ_rθ(θ, r0), Pa.
    pub tau_rt: Vec<f64>,
    /// Tensile strength σ_t, Pa.
    pub sigma_t: f64,
    /// r0, m.
    pub r0: f64,
}

/// One sample of an iterative solve's progress.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ResidualSample {
    pub iteration: usize,
    /// Wall time since the relaxation started, s.
    pub seconds: f64,
    /// ‖f − K u‖ / ‖f‖.
    pub residual: f64,
}

/// Progress of a resumable relaxation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RelaxStatus {
    pub iterations: usize,
    pub residual: f64,
    pub converged: bool,
}

/// One scene being simulated: model (immutable), state (cracks, displacement,
/// contact history) and scratch (factorisations, buffers).
pub struct Simulation {
    scene: Scene,
}

// CONTRACT (bodies are being filled in by the core work; signatures are fixed).
impl Simulation {
    /// Validates the scene and builds the discretisation (no solve yet).
    pub fn new(scene: Scene) -> Result<Self, SolveError> {
        scene.validate()?;
        Ok(Self { scene })
    }
    /// The scene as currently simulated (cracks include grown segments).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
    /// Load factor λ in [0, 1] applied to every load.
    pub fn load_factor(&self) -> f64 {
        unimplemented!()
    }
    pub fn set_load_factor(&mut self, _lambda: f64) {
        unimplemented!()
    }
    /// Full solve (with contact) at the current load factor with the scene's
    /// solver; fills SIFs and criterion at every free tip.
    pub fn solve(&mut self) -> Result<SolveReport, SolveError> {
        unimplemented!()
    }
    /// Starts (or restarts) a resumable iterative solve from the current
    /// displacement. For the direct solver this does the whole solve at the
    /// first `relax` call.
    pub fn start_relaxation(&mut self) {
        unimplemented!()
    }
    /// Runs at most `max_iterations` sweeps of the relaxation started by
    /// `start_relaxation`; cheap to call once per frame.
    pub fn relax(&mut self, _max_iterations: usize) -> Result<RelaxStatus, SolveError> {
        unimplemented!()
    }
    /// Residual samples of the current relaxation.
    pub fn residual_history(&self) -> &[ResidualSample] {
        unimplemented!()
    }
    /// One growth step of SPEC §9 (solve, evaluate, extend tips that meet the
    /// criterion, or advance the load factor).
    pub fn grow_step(&mut self) -> Result<GrowthStepReport, SolveError> {
        unimplemented!()
    }
    /// Growth history so far.
    pub fn history(&self) -> &[GrowthStepReport] {
        unimplemented!()
    }
    /// Whether growth has ended (through, unstable, max steps, completed).
    pub fn growth_finished(&self) -> Option<crate::report::Outcome> {
        unimplemented!()
    }
    /// Current crack polylines, m.
    pub fn cracks(&self) -> Vec<Vec<[f64; 2]>> {
        unimplemented!()
    }
    /// SIFs and criterion at every free tip after the last solve.
    pub fn tips(&self) -> &[TipReport] {
        unimplemented!()
    }
    /// σ_xx, σ_yy, τ_xy at a point, Pa (None outside the specimen or before a solve).
    pub fn stress_at(&self, _p: [f64; 2]) -> Option<[f64; 3]> {
        unimplemented!()
    }
    /// Displacement at a point, m.
    pub fn displacement_at(&self, _p: [f64; 2]) -> Option<[f64; 2]> {
        unimplemented!()
    }
    /// Crack-face contact points with their state and tractions.
    pub fn contact_points(&self) -> Vec<ContactPointView> {
        unimplemented!()
    }
    /// σ_θθ and τ_rθ around tip `index` of `tips()`.
    pub fn criterion_curve(&self, _index: usize) -> Option<CriterionCurve> {
        unimplemented!()
    }
}
