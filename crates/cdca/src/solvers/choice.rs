//! Choice of the linear solver from the scene (`solver.kind`, SPEC §6 and
//! §10): `direct` (sparse Cholesky), `automaton` (the paper's cell sweeps),
//! `cg` (conjugate gradients preconditioned with the automaton's symmetric
//! sweep) and `multigrid` (CG with a V-cycle whose smoother is that sweep).
//!
//! The iterative solvers run a [`Relaxation`], warm-started from the `u`
//! they are given; they keep their setup (cells, hierarchy) while the
//! matrix is unchanged.

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::scene::{SolverKind, SolverSpec};
use crate::solvers::linear::{DirectSolver, LinearInfo, LinearSolver};
use crate::solvers::relaxation::{RelaxStatus, Relaxation, ResidualSample};

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

/// An iterative solver behind the [`LinearSolver`] trait: a
/// [`Relaxation`] capped at `solver.max_iterations` per solve, kept (cells,
/// hierarchy) while the matrix is unchanged.
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

    fn relaxation(&self) -> &Relaxation {
        self.relaxation
            .as_ref()
            .expect("an iterative solve is started before it runs")
    }
}

impl LinearSolver for IterativeSolver {
    fn name(&self) -> &'static str {
        kind_name(self.kind)
    }

    fn start(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u0: &[f64],
        matrix_changed: bool,
    ) -> Result<(), SolveError> {
        let n = x.n_free();
        let zero;
        let u0 = if u0.len() == n {
            u0
        } else {
            zero = vec![0.0; n];
            &zero
        };
        match &mut self.relaxation {
            Some(r) if !matrix_changed && r.operator().n == n => r.reset(f, u0),
            slot => {
                *slot = Some(Relaxation::new(self.kind, &self.spec, x, blocks, f, u0)?);
                Ok(())
            }
        }
    }

    fn run(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        max_iterations: usize,
    ) -> Result<RelaxStatus, SolveError> {
        let cap = self.spec.max_iterations.max(1);
        let relaxation = self
            .relaxation
            .as_mut()
            .expect("an iterative solve is started before it runs");
        let left = cap.saturating_sub(relaxation.status().iterations);
        let status = relaxation.run(x, blocks, max_iterations.min(left), &mut |_| {})?;
        // capped or not, the last iterate stays and the status says so
        Ok(RelaxStatus {
            finished: status.converged || status.iterations >= cap,
            ..status
        })
    }

    fn u(&self) -> &[f64] {
        self.relaxation().u()
    }

    fn info(&self) -> LinearInfo {
        let r = self.relaxation();
        let status = r.status();
        LinearInfo {
            iterations: status.iterations,
            residual: status.residual,
            converged: status.converged,
            history: r.history().iter().map(|s| s.residual).collect(),
        }
    }

    fn samples(&self) -> &[ResidualSample] {
        self.relaxation().history()
    }
}
