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

/// Factors a [`DirectSolver`] keeps: the current one and the one before.
/// The contact iteration of a critical-control trial often returns to the
/// contact states the previous trial's matrix was built with (in a 40-step
/// growth run of a two-flaw specimen, 38 of 148 factorisations were of a
/// matrix the solver had factorised just before the current one).
const KEPT_FACTORS: usize = 2;

/// Sparse Cholesky, refactorised only when the matrix changed (the
/// symbolic factorisation is the discretisation's, computed once), and not
/// even then when it is the matrix of a kept factor.
#[derive(Default)]
pub struct DirectSolver {
    /// The last factors, the current one first.
    factors: Vec<Factor>,
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
        if matrix_changed || self.factors.is_empty() {
            let pattern = x.pattern()?;
            if let Some(i) = self.factors.iter().position(|k| k.is_of(pattern, blocks)) {
                self.factors[..=i].rotate_right(1);
            } else {
                // in the oldest one's storage (dropped if this fails)
                let oldest = (self.factors.len() >= KEPT_FACTORS)
                    .then(|| self.factors.pop())
                    .flatten();
                let factor = match oldest {
                    Some(old) => old.refactor(x, blocks)?,
                    None => Factor::new(x, blocks)?,
                };
                self.factors.insert(0, factor);
            }
        }
        let factor = &self.factors[0];
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
