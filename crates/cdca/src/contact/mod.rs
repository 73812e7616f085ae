//! Frictional contact on closed crack faces (SPEC §5): the penalty
//! stick/slip law with Coulomb friction and cohesion per face piece, and
//! the contact iteration around any linear solver: semismooth Newton steps
//! where the solver keeps a factor (`newton`); otherwise, and where those
//! steps cycle, an active-set loop with the friction limits held fixed (an
//! inner, convex Tresca problem, damped by a line search) inside an outer
//! loop that updates the limits to μ|p_N| + c_c, ending with an explicit
//! status; or, with the automaton, the paper's rule: states updated in the
//! sweep.
//!
//! Uses the discretisation (face points, element blocks) and the solvers'
//! common trait.

pub mod in_sweep;
pub mod iteration;
pub(crate) mod krylov;
pub mod law;
pub mod limit_mix;
pub mod limit_newton;
pub mod newton;
pub mod points;
pub mod status;

pub use law::{ContactState, FaceState};
