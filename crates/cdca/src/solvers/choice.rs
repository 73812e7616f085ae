//! Choice of the linear solver from the scene (`solver.kind`, SPEC §6 and
//! §10): `direct` (sparse Cholesky), `automaton` (the paper's cell sweeps),
//! `cg` (conjugate gradients preconditioned with the automaton's symmetric
//! sweep) and `multigrid` (CG with a V-cycle whose smoother is that sweep).
//!
//! The iterative solvers run a [`Relaxation`] to completion, warm-started
//! from the `u` they are given; they keep their setup (cells, hierarchy)
//! while the matrix is unchanged.

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::scene::{SolverKind, SolverSpec};
use crate::solvers::linear::{DirectSolver, LinearInfo, LinearSolver};
use crate::solvers::relaxation::Relaxation;

/// The solver the scene asks for.
pub fn make_solver(spec: &SolverSpec) -> Box<dyn LinearSolver> {
    match spec.kind {
        SolverKind::Direct => Box::new(DirectSolver::default()),
        kind => Box::new(IterativeSolver::new(kind, spec.clone())),
    }
}

/// Name of a solver kind, as in the scene file.
pub fn kind_name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Direct => "direct",
        SolverKind::Automaton => "automaton",
        SolverKind::Cg => "cg",
        SolverKind::Multigrid => "multigrid",
    }
}

/// An iterative solver behind the [`LinearSolver`] trait.
pub struct IterativeSolver {
    kind: SolverKind,
    spec: SolverSpec,
    relaxation: Option<Relaxation>,
}

impl IterativeSolver {
    pub fn new(kind: SolverKind, spec: SolverSpec) -> Self {
        Self {
            kind,
            spec,
            relaxation: None,
        }
    }
}

impl LinearSolver for IterativeSolver {
    fn name(&self) -> &'static str {
        kind_name(self.kind)
    }

    fn solve(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u: &mut Vec<f64>,
        matrix_changed: bool,
    ) -> Result<LinearInfo, SolveError> {
        if u.len() != x.n_free() {
            *u = vec![0.0; x.n_free()];
        }
        let relaxation = match &mut self.relaxation {
            Some(r) if !matrix_changed && r.operator().n == x.n_free() => {
                r.reset(f, u)?;
                r
            }
            slot => slot.insert(Relaxation::new(self.kind, &self.spec, x, blocks, f, u)?),
        };
        let status = relaxation.run(x, blocks, self.spec.max_iterations, &mut |_| {})?;
        // capped or not, the caller gets the last iterate and the status
        u.copy_from_slice(relaxation.u());
        Ok(LinearInfo {
            iterations: status.iterations,
            residual: status.residual,
            converged: status.converged,
            history: relaxation.history().iter().map(|s| s.residual).collect(),
        })
    }
}
