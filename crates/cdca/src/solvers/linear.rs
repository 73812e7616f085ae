//! The linear solvers of one operator `(K + K_contact) u = f` (SPEC §6),
//! behind one trait so that the contact iteration and the app can use any.

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::solvers::direct::Factor;

/// What one linear solve did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinearInfo {
    /// Sweeps or iterations (1 for a direct solve).
    pub iterations: usize,
    /// Final relative residual ‖f − K u‖/‖f‖.
    pub residual: f64,
    pub converged: bool,
    /// Relative residual after each iteration.
    pub history: Vec<f64>,
}

/// A solver of the assembled-or-not operator.
pub trait LinearSolver {
    /// Name as in the scene's `solver.kind`.
    fn name(&self) -> &'static str;
    /// Solves `(K + blocks) u = f`, starting from `u` (a warm start for
    /// iterative solvers). `matrix_changed` is false when only `f` changed
    /// since the last call on the same discretisation. An iterative solve
    /// that stops at its iteration cap is not an error: it leaves the last
    /// iterate in `u` and says `converged: false` with its residual.
    fn solve(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u: &mut Vec<f64>,
        matrix_changed: bool,
    ) -> Result<LinearInfo, SolveError>;
}

/// Sparse Cholesky, refactorised only when the matrix changed (the
/// symbolic factorisation is the discretisation's, computed once).
#[derive(Default)]
pub struct DirectSolver {
    factor: Option<Factor>,
}

impl LinearSolver for DirectSolver {
    fn name(&self) -> &'static str {
        "direct"
    }

    fn solve(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u: &mut Vec<f64>,
        matrix_changed: bool,
    ) -> Result<LinearInfo, SolveError> {
        if matrix_changed || self.factor.is_none() {
            // in the last factor's storage (dropped if this fails)
            self.factor = Some(match self.factor.take() {
                Some(old) => old.refactor(x, blocks)?,
                None => Factor::new(x, blocks)?,
            });
        }
        let Some(factor) = &self.factor else {
            unreachable!("factor was just set")
        };
        *u = factor.solve(f)?;
        let residual = factor.relative_residual(f, u);
        Ok(LinearInfo {
            iterations: 1,
            residual,
            converged: true,
            history: vec![residual],
        })
    }
}
