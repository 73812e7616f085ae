//! `cdca`: the continuous–discontinuous cellular automaton method (CDCA) for
//! crack initiation and growth in brittle rock under compression–shear.
//!
//! Headless: no UI and no file system. Scenes come in as `&str` (JSON) and
//! reports go out as serialisable structs.

pub mod error;
pub mod report;
pub mod scene;
mod simulation;
mod validate;

pub use error::{SceneError, SolveError};
pub use scene::Scene;
pub use simulation::{
    ContactPointView, ContactState, CriterionCurve, RelaxStatus, ResidualSample, Simulation,
};
