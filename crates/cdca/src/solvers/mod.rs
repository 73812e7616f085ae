//! The linear solvers of one operator `(K + K_contact) u = f` (SPEC §6):
//! the sparse direct solver (the reference), the paper's cellular automaton
//! (block Gauss–Seidel/SOR cell sweeps, no global matrix), and the
//! matrix-free accelerations built from the same cell updates (SSOR-CG and
//! multigrid-CG); a resumable [`Relaxation`] for the app and the benchmark.
//!
//! Uses the discretisation; contact enters only as element blocks
//! ([`ElementBlock`](crate::discretisation::assembly::ElementBlock)), so the
//! solvers know nothing of contact laws or fracture.

pub mod automaton;
pub mod cells;
pub mod choice;
pub mod direct;
pub mod element_op;
pub mod forward;
pub mod linear;
pub mod low_rank;
pub mod multigrid;
pub mod pcg;
pub mod relaxation;
pub mod supernodal;

pub use choice::{kind_name, make_solver};
pub use linear::{DirectSolver, LinearInfo, LinearSolver};
pub use relaxation::{RelaxStatus, Relaxation, ResidualSample};
