//! A resumable solve with contact in progress: the linear relaxation of the
//! current contact system, and the contact iteration around it.

use crate::contact::iteration::FlipTracker;
use crate::contact::law::{ContactState, FaceState};
use crate::discretisation::assembly::ElementBlock;
use crate::solvers::relaxation::Relaxation;

/// A resumable solve with contact: the linear relaxation of the current
/// contact system, and the contact iteration around it.
pub(super) struct RelaxJob {
    /// `None` until set up (a factorisation, cells or a multigrid
    /// hierarchy) by the next `relax` call: one call sets up at most one.
    pub(super) relaxation: Option<Relaxation>,
    /// Right-hand side of the current contact system.
    pub(super) f: Vec<f64>,
    pub(super) blocks: Vec<ElementBlock>,
    /// Open, stick or slip per point when the job was made: what the
    /// relaxation's matrix is built with.
    pub(super) kinds: Vec<ContactState>,
    /// Contact states of the current contact iteration.
    pub(super) states: Vec<FaceState>,
    pub(super) tracker: FlipTracker,
    pub(super) contact_iterations: usize,
    /// Iterations and seconds of earlier contact iterations (for the
    /// cumulative residual history).
    pub(super) done_iterations: usize,
    pub(super) done_seconds: f64,
    /// Displacement at the start of this contact iteration.
    pub(super) start_u: Vec<f64>,
    /// Samples of `relaxation.history()` already copied to the cumulative
    /// history.
    pub(super) copied: usize,
}

impl RelaxJob {
    /// The relaxation, set up (`relax` sets it up before running it).
    pub(super) fn relaxation(&self) -> &Relaxation {
        self.relaxation
            .as_ref()
            .expect("the relaxation is set up before it runs")
    }

    /// Seconds of this and the earlier contact iterations' relaxations.
    pub(super) fn seconds(&self) -> f64 {
        self.done_seconds + self.relaxation().seconds()
    }
}

/// Open, stick or slip per contact point.
pub(super) fn kinds(states: &[FaceState]) -> Vec<ContactState> {
    states.iter().map(|s| s.state).collect()
}

/// A set-up relaxation kept after its solve ended, with the contact states
/// (open, stick, slip per point) its matrix was built with: the next solve
/// on the same discretisation whose states match restarts it instead of
/// setting up again (the matrix `K + contact blocks` depends on nothing
/// else, not on the load; most λ_cr trials and many contact iterations
/// match).
pub(super) struct KeptRelaxation {
    pub(super) kinds: Vec<ContactState>,
    pub(super) relaxation: Relaxation,
}
