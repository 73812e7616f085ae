//! A resumable solve with contact in progress: the linear relaxation of the
//! current contact system, and the contact iteration around it.

use crate::contact::iteration::FlipTracker;
use crate::contact::law::FaceState;
use crate::discretisation::assembly::ElementBlock;
use crate::solvers::relaxation::Relaxation;

/// A resumable solve with contact: the linear relaxation of the current
/// contact system, and the contact iteration around it.
pub(super) struct RelaxJob {
    pub(super) relaxation: Relaxation,
    pub(super) blocks: Vec<ElementBlock>,
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
