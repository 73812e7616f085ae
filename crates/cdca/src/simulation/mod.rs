//! The facade used by the CLI and the workbench: one scene, its model, its
//! state and its scratch, and the steps of the method as the paper lists
//! them:
//!
//! 1. classify the cracks and discretise ([`Simulation::new`], and after
//!    growth a local rebuild);
//! 2. relax the cells (or solve directly) at the current load, with the
//!    contact states updated by the return mapping until they settle
//!    ([`Simulation::solve`] in one call, [`Simulation::relax`] a few sweeps
//!    at a time);
//! 3. evaluate every free tip: SIFs by the interaction integral and the
//!    criterion's decision ([`Simulation::tips`]);
//! 4. grow the tips that meet the criterion, or raise the load
//!    ([`Simulation::grow_step`], resumable as
//!    [`Simulation::advance_growth`]).
//!
//! The top of the crate: uses every part below it.

mod critical;
mod grow;
mod initiation;
mod intact;
mod job;
mod relax;
mod run;
mod search;
mod solve;
mod state;
mod views;

pub use grow::INTEGRATION_CHUNK;
pub use initiation::{Initiation, initiation};
pub use search::{LAMBDA_TOLERANCE, MAX_TRIALS};
pub use state::{Simulation, check_cracks};
pub use views::{ContactPointView, CriterionCurve};
