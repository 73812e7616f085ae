//! The paper's solver (SPEC §6): the cellular automaton as block
//! Gauss–Seidel / SOR sweeps on the running residual.
//!
//! Every node is a cell (see [`crate::solvers::cells`]). One iteration is one sweep:
//! each cell in turn solves its own block against the current residual,
//! `Δu_i = ω K_ii⁻¹ r_i`, and passes the change to its neighbours,
//! `r_k −= K_ki Δu_i`. The sweep stops when
//!
//! ```text
//! max |Δu| ≤ tol_u · max |u|   and   ‖r‖ ≤ tol · ‖f‖.
//! ```
//!
//! The running residual drifts from `f − K u` by rounding; it is recomputed
//! element by element every `refresh` sweeps and before convergence is
//! declared. For SPD `K` the sweeps converge for `0 < ω < 2`
//! (Ostrowski–Reich), slowly: about `O(n²)` sweeps on an `n × n` mesh.

use crate::error::SolveError;
use crate::scene::Ordering;
use crate::solvers::cells::Cells;
use crate::solvers::element_op::{ElementOperator, norm};

/// Young's optimal over-relaxation factor for the model problem on an
/// `n × n` grid, `ω = 2 / (1 + sin(π/n))` (n the larger of the mesh's
/// element counts). The automaton's sweeps are block SOR on the Q4 cells,
/// not the 5-point Poisson stencil the formula is exact for, but it is a
/// good factor there too: on the default 60² specimen (ω = 1.90) in-sweep
/// contact converges in 28 k sweeps, against 432 k at ω = 1.
#[must_use]
pub fn sor_omega(n: usize) -> f64 {
    2.0 / (1.0 + (std::f64::consts::PI / n.max(2) as f64).sin())
}

/// Settings of the automaton.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutomatonParams {
    /// Over-relaxation factor ω in (0, 2); 1 is block Gauss–Seidel.
    pub omega: f64,
    /// Relative residual tolerance: `‖r‖ ≤ tolerance ‖f‖`.
    pub tolerance: f64,
    /// Relative change tolerance: `max |Δu| ≤ tolerance_u max |u|`.
    pub tolerance_u: f64,
    /// Sweeps between recomputations of the true residual.
    pub refresh: usize,
}

impl Default for AutomatonParams {
    fn default() -> Self {
        Self {
            omega: 1.0,
            tolerance: 1e-10,
            tolerance_u: 1e-10,
            refresh: 50,
        }
    }
}

/// What one iteration of an iterative method did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Progress {
    /// Relative residual `‖f − K u‖ / ‖f‖` after the iteration.
    pub residual: f64,
    /// Largest displacement change of the iteration, m.
    pub change: f64,
    pub converged: bool,
}

/// The automaton's state between sweeps: the cells and the running
/// residual.
#[derive(Clone, Debug)]
pub struct Automaton {
    pub params: AutomatonParams,
    cells: Cells,
    r: Vec<f64>,
    norm_f: f64,
    since_refresh: usize,
}

impl Automaton {
    /// Cells built by the caller (they depend only on the operator).
    pub fn new(
        params: AutomatonParams,
        cells: Cells,
        op: &ElementOperator,
        f: &[f64],
        u: &[f64],
    ) -> Self {
        let mut a = Self {
            params,
            cells,
            r: vec![0.0; op.n],
            norm_f: 0.0,
            since_refresh: 0,
        };
        a.reset(op, f, u);
        a
    }

    /// Starts again from `u` with right-hand side `f` (same operator).
    pub fn reset(&mut self, op: &ElementOperator, f: &[f64], u: &[f64]) {
        op.residual(f, u, &mut self.r);
        self.norm_f = norm(f);
        self.since_refresh = 0;
    }

    /// Current relative residual (of the running residual).
    pub fn relative_residual(&self) -> f64 {
        relative(norm(&self.r), self.norm_f)
    }

    /// One sweep.
    pub fn step(
        &mut self,
        op: &ElementOperator,
        f: &[f64],
        u: &mut [f64],
    ) -> Result<Progress, SolveError> {
        let p = self.params;
        let backward = false;
        let change = self.cells.sweep(op, p.omega, backward, u, &mut self.r)?;
        self.since_refresh += 1;
        if self.since_refresh >= p.refresh {
            op.residual(f, u, &mut self.r);
            self.since_refresh = 0;
        }
        let scale = u.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let small_change = change <= p.tolerance_u * scale;
        let mut residual = self.relative_residual();
        if !residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: "automaton residual".to_owned(),
            });
        }
        let mut converged = false;
        if small_change && residual <= p.tolerance {
            // confirm with the true residual
            op.residual(f, u, &mut self.r);
            self.since_refresh = 0;
            residual = self.relative_residual();
            converged = residual <= p.tolerance;
        }
        Ok(Progress {
            residual,
            change,
            converged,
        })
    }

    /// Builds the cells of the fine operator of a discretisation.
    pub fn cells_of(
        x: &crate::discretisation::xfem::Xfem,
        op: &ElementOperator,
        ordering: Ordering,
    ) -> Result<Cells, SolveError> {
        Cells::new(op, &x.mesh, &crate::solvers::cells::node_dofs(x), ordering)
    }
}

/// `a / b`, or `a` when `b` is zero.
pub fn relative(a: f64, b: f64) -> f64 {
    if b > 0.0 { a / b } else { a }
}
