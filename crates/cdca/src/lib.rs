//! `cdca`: the continuous–discontinuous cellular automaton method (CDCA) for
//! crack initiation and growth in brittle rock under compression–shear
//! (Yan, Feng, Pan & Li, 2016).
//!
//! Headless: no UI and no file system. Scenes come in as `&str` (JSON) and
//! reports go out as serialisable structs.
//!
//! The modules, bottom to top; each uses only those above it in this list:
//!
//! | module | the method's part |
//! | --- | --- |
//! | [`error`] | typed errors carrying the offending values |
//! | [`scene`] | the scene file and its validation (SPEC §10) |
//! | [`report`] | the report contracts (SPEC §11) |
//! | [`geometry`] | plane geometry, the Q4 mesh, cracks and level sets (§1–2) |
//! | [`discretisation`] | material, supports, loads, enrichment, quadrature, the XFEM discretisation (§3–4) |
//! | [`solvers`] | direct, automaton, CG and multigrid solvers of one operator (§6) |
//! | [`contact`] | the frictional contact law and iteration on closed faces (§5) |
//! | [`fracture`] | SIFs, criteria, tip evaluation, growth geometry (§7–9) |
//! | [`Simulation`] | the facade: the paper's steps on one scene (§9) |
//! | [`race`] | error against run time of any solver, for benchmarks |
//! | [`csv`] | the report tables as CSV, one writer each, for the CLI and the workbench |
//! | [`study`] | studies of many scenes: the study file, its points, one row per growth run |

pub mod contact;
pub mod csv;
pub mod discretisation;
pub mod error;
pub mod fracture;
pub mod geometry;
pub mod race;
pub mod report;
pub mod scene;
mod simulation;
pub mod solvers;
pub mod study;

pub use contact::ContactState;
pub use error::{FieldValue, SceneError, SolveError};
pub use scene::Scene;
pub use simulation::{
    ContactPointView, CriterionCurve, INTEGRATION_CHUNK, Initiation, LAMBDA_TOLERANCE, MAX_TRIALS,
    Simulation, check_cracks, initiation,
};
pub use solvers::{RelaxStatus, ResidualSample};
