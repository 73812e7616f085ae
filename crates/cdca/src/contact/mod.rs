//! Frictional contact on closed crack faces (SPEC §5): the penalty
//! stick/slip law with Coulomb friction and cohesion per face piece, and
//! the contact iteration around any linear solver: a fixed-point
//! (active-set) loop that solves with the current stick/slip/open states,
//! updates every state by the return mapping and repeats until none
//! changes, with a guard against stick–slip cycling and an explicit status;
//! or, with the automaton, the paper's rule: states updated in the sweep.
//!
//! Uses the discretisation (face points, element blocks) and the solvers'
//! common trait.

pub mod in_sweep;
pub mod iteration;
pub mod law;

pub use law::{ContactState, FaceState};
