//! `cdca`: the continuous–discontinuous cellular automaton method (CDCA) for
//! crack initiation and growth in brittle rock under compression–shear.
//!
//! Headless: no UI and no file system. Scenes come in as `&str` (JSON) and
//! reports go out as serialisable structs.
//!
//! The pipeline of one solve reads like the method: [`model::Model`] (mesh,
//! material, supports) → [`xfem::Xfem`] (enrichment, quadrature, face
//! points) → assembly and a solver ([`direct`]) with frictional contact →
//! [`sif`] → criterion → growth.

pub mod assembly;
pub mod automaton;
pub mod boundary;
pub mod cells;
pub mod contact;
pub mod contact_loop;
pub mod cracks;
pub mod criterion;
pub mod direct;
pub mod dofs;
pub mod element_op;
pub mod enrichment;
pub mod error;
pub mod field;
pub mod geometry;
pub mod growth;
pub mod loads;
pub mod material;
pub mod mesh;
pub mod model;
pub mod multigrid;
pub mod pcg;
pub mod quadrature;
pub mod relaxation;
pub mod report;
pub mod scene;
pub mod sif;
mod simulation;
pub mod solver;
pub mod solvers;
pub mod subdivision;
pub mod tips;
mod validate;
pub mod xfem;

pub use error::{SceneError, SolveError};
pub use scene::Scene;
pub use simulation::{
    ContactPointView, ContactState, CriterionCurve, RelaxStatus, ResidualSample, Simulation,
};
