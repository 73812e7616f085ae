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
            self.factor = Some(Factor::new(x, blocks)?);
        }
        let Some(factor) = &self.factor else {
            unreachable!("factor was just set")
        };
        *u = factor.solve(f)?;
        let residual = relative_residual(x, blocks, f, u);
        Ok(LinearInfo {
            iterations: 1,
            residual,
            converged: true,
            history: vec![residual],
        })
    }
}

/// `‖f − K u‖ / ‖f‖` (or ‖K u‖ when f = 0).
pub fn relative_residual(x: &Xfem, blocks: &[ElementBlock], f: &[f64], u: &[f64]) -> f64 {
    let mut ku = vec![0.0; f.len()];
    crate::discretisation::assembly::apply(x, blocks, u, &mut ku);
    let r: f64 = f
        .iter()
        .zip(&ku)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt();
    let nf = f.iter().map(|a| a * a).sum::<f64>().sqrt();
    if nf > 0.0 { r / nf } else { r }
}
