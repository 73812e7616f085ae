//! Geometric multigrid on the structured mesh, used as a V-cycle
//! preconditioner inside CG: the grid hierarchy (cracks' Heaviside
//! enrichment kept on coarse grids), Galerkin coarse operators built
//! element by element, the crack block solved exactly, and the automaton's
//! sweeps as the smoother.
//!
//! Uses the discretisation and the automaton's cells; used by
//! [`relaxation`](crate::solvers::relaxation).

mod coarsen;
mod crack_block;
mod galerkin;
mod grid;
mod vcycle;

pub use vcycle::{MultigridParams, Vcycle};
