//! The solve in progress ([`Simulation::relax`](super::Simulation::relax)):
//! the outer contact loop around the scene's linear solver, or the
//! automaton with the contact states updated in its sweeps.

use crate::contact::in_sweep::InSweep;
use crate::contact::iteration::ContactSolve;
use crate::contact::status::Reached;

/// The solve in progress: how the contact states are updated.
pub(super) enum Job {
    /// After each linear solve of the scene's solver.
    Outer(Box<ContactSolve>),
    /// At the automaton's cell visits.
    InSweep(Box<InSweep>),
}

impl Job {
    /// Where the solve stands: states, status, residual samples.
    pub(super) fn reached(&self) -> &Reached {
        match self {
            Job::Outer(j) => j.reached(),
            Job::InSweep(j) => j.reached(),
        }
    }

    /// The result.
    pub(super) fn into_reached(self) -> Reached {
        match self {
            Job::Outer(j) => j.into_reached(),
            Job::InSweep(j) => j.into_reached(),
        }
    }
}
