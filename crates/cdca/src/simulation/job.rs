//! The solve in progress ([`Simulation::relax`](super::Simulation::relax)):
//! the outer contact loop around the scene's linear solver, or the
//! automaton with the contact states updated in its sweeps.

use crate::contact::in_sweep::InSweep;
use crate::contact::iteration::{ContactInfo, ContactSolve};
use crate::contact::law::FaceState;
use crate::solvers::relaxation::ResidualSample;

/// The solve in progress: how the contact states are updated.
pub(super) enum Job {
    /// After each linear solve of the scene's solver.
    Outer(ContactSolve),
    /// At the automaton's cell visits.
    InSweep(InSweep),
}

impl Job {
    /// The contact states as they are now.
    pub(super) fn states(&self) -> &[FaceState] {
        match self {
            Job::Outer(j) => j.states(),
            Job::InSweep(j) => j.states(),
        }
    }

    /// Residual samples so far.
    pub(super) fn history(&self) -> &[ResidualSample] {
        match self {
            Job::Outer(j) => j.history(),
            Job::InSweep(j) => j.history(),
        }
    }

    pub(super) fn into_result(self) -> (Vec<FaceState>, ContactInfo) {
        match self {
            Job::Outer(j) => j.into_result(),
            Job::InSweep(j) => j.into_result(),
        }
    }
}
