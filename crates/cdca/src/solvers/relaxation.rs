//! A resumable solve: run a few sweeps or iterations, report progress,
//! return; call again to continue. This is how the workbench animates the
//! automaton without freezing, and how the benchmark samples error against
//! run time.
//!
//! The clock counts setup (building cells, factorising blocks, the
//! multigrid hierarchy, or the direct factorisation) and iterations, but
//! not the time spent in the progress callback: a caller may measure
//! errors there without charging them to the solver.

use web_time::Instant;

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::scene::{DIRECT_TOLERANCE, SolverKind, SolverSpec};
use crate::solvers::automaton::{Automaton, AutomatonParams, Progress, relative};
use crate::solvers::direct::Factor;
use crate::solvers::element_op::{ElementOperator, norm};
use crate::solvers::multigrid::{MultigridParams, Vcycle};
use crate::solvers::pcg::{Pcg, Ssor};

/// One sample of an iterative solve's progress.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ResidualSample {
    pub iteration: usize,
    /// Wall time since the relaxation started, s.
    pub seconds: f64,
    /// ‖f − K u‖ / ‖f‖.
    pub residual: f64,
}

/// Progress of a resumable relaxation.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RelaxStatus {
    pub iterations: usize,
    /// Relative residual ‖f − K u‖ / ‖f‖.
    pub residual: f64,
    /// Every convergence test passed.
    pub converged: bool,
    /// The solve has ended: converged, or stopped at a cap (then
    /// `converged` is false). A linear relaxation ends when it converges.
    pub finished: bool,
}

/// The method behind a relaxation.
enum Method {
    Direct(Factor),
    Automaton(Automaton),
    Cg(Pcg<Ssor>),
    Multigrid(Box<Pcg<Vcycle>>),
}

/// A resumable solve of `(K + blocks) u = f`.
pub struct Relaxation {
    pub kind: SolverKind,
    op: ElementOperator,
    f: Vec<f64>,
    u: Vec<f64>,
    method: Method,
    status: RelaxStatus,
    change: f64,
    seconds: f64,
    history: Vec<ResidualSample>,
}

impl Relaxation {
    /// Sets up the solver of `kind` (cells, factorisations, hierarchy) and
    /// starts from `u0`. The first history sample (iteration 0) carries the
    /// setup time and the initial residual.
    pub fn new(
        kind: SolverKind,
        spec: &SolverSpec,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u0: &[f64],
    ) -> Result<Self, SolveError> {
        let clock = Instant::now();
        let n = x.n_free();
        assert!(
            f.len() == n && u0.len() == n,
            "vector lengths do not match the DOFs"
        );
        let op = ElementOperator::from_xfem(x, blocks);
        let tol = spec.tolerance;
        let method = match kind {
            SolverKind::Direct => Method::Direct(Factor::new(x, blocks)?),
            SolverKind::Automaton => {
                let params = AutomatonParams {
                    omega: spec.omega,
                    tolerance: tol,
                    tolerance_u: tol,
                    ..AutomatonParams::default()
                };
                let cells = Automaton::cells_of(x, &op, spec.ordering)?;
                Method::Automaton(Automaton::new(params, cells, &op, f, u0))
            }
            SolverKind::Cg => {
                let cells = Automaton::cells_of(x, &op, spec.ordering)?;
                Method::Cg(Pcg::new(tol, Ssor::new(cells, spec.omega, n), &op, f, u0)?)
            }
            SolverKind::Multigrid => {
                let v = Vcycle::new(x, &op, MultigridParams::default())?;
                Method::Multigrid(Box::new(Pcg::new(tol, v, &op, f, u0)?))
            }
        };
        let mut r = Self {
            kind,
            op,
            f: f.to_vec(),
            u: u0.to_vec(),
            method,
            status: RelaxStatus::default(),
            change: 0.0,
            seconds: clock.elapsed().as_secs_f64(),
            history: Vec::new(),
        };
        r.start_history();
        Ok(r)
    }

    /// Starts again from `u0` with a new right-hand side, keeping the
    /// operator's setup (valid while the matrix is unchanged).
    pub fn reset(&mut self, f: &[f64], u0: &[f64]) -> Result<(), SolveError> {
        let clock = Instant::now();
        self.f.copy_from_slice(f);
        self.u.copy_from_slice(u0);
        match &mut self.method {
            Method::Direct(_) => {}
            Method::Automaton(a) => a.reset(&self.op, f, u0),
            Method::Cg(p) => p.reset(&self.op, f, u0)?,
            Method::Multigrid(p) => p.reset(&self.op, f, u0)?,
        }
        self.status = RelaxStatus::default();
        self.seconds = clock.elapsed().as_secs_f64();
        self.history.clear();
        self.start_history();
        Ok(())
    }

    fn start_history(&mut self) {
        let residual = match &self.method {
            Method::Automaton(a) => a.relative_residual(),
            Method::Cg(p) => p.relative_residual(),
            Method::Multigrid(p) => p.relative_residual(),
            Method::Direct(_) => {
                let mut r = vec![0.0; self.op.n];
                self.op.residual(&self.f, &self.u, &mut r);
                relative(norm(&r), norm(&self.f))
            }
        };
        self.status.residual = residual;
        self.history.push(ResidualSample {
            iteration: 0,
            seconds: self.seconds,
            residual,
        });
    }

    /// Runs at most `max_iterations` more sweeps (automaton) or iterations
    /// (CG), calling `callback` after each. Stops early when converged.
    pub fn run(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        max_iterations: usize,
        callback: &mut dyn FnMut(&ResidualSample),
    ) -> Result<RelaxStatus, SolveError> {
        assert_eq!(
            x.n_free(),
            self.op.n,
            "relaxation run on another discretisation"
        );
        debug_assert!(blocks.iter().all(|b| b.slot < x.enriched.len()));
        let mut clock = Instant::now();
        for _ in 0..max_iterations {
            if self.status.finished {
                break;
            }
            let it = self.status.iterations + 1;
            let p = self.step(it)?;
            self.status = RelaxStatus {
                iterations: it,
                residual: p.residual,
                converged: p.converged,
                // a direct solve is done after one, converged or not
                finished: p.converged || matches!(self.method, Method::Direct(_)),
            };
            self.change = p.change;
            self.seconds += clock.elapsed().as_secs_f64();
            let sample = ResidualSample {
                iteration: it,
                seconds: self.seconds,
                residual: p.residual,
            };
            self.history.push(sample);
            callback(&sample);
            clock = Instant::now();
        }
        Ok(self.status)
    }

    fn step(&mut self, it: usize) -> Result<Progress, SolveError> {
        let (op, f, u) = (&self.op, &self.f, &mut self.u);
        match &mut self.method {
            Method::Direct(factor) => {
                *u = factor.solve(f)?;
                let mut r = vec![0.0; op.n];
                op.residual(f, u, &mut r);
                let residual = relative(norm(&r), norm(f));
                Ok(Progress {
                    residual,
                    change: f64::INFINITY,
                    converged: residual <= DIRECT_TOLERANCE,
                })
            }
            Method::Automaton(a) => a.step(op, f, u),
            Method::Cg(p) => p.step(op, f, u, it),
            Method::Multigrid(p) => p.step(op, f, u, it),
        }
    }

    /// The current displacement (free DOFs).
    pub fn u(&self) -> &[f64] {
        &self.u
    }

    /// Progress samples since the start (iteration 0 first).
    pub fn history(&self) -> &[ResidualSample] {
        &self.history
    }

    pub fn status(&self) -> RelaxStatus {
        self.status
    }

    /// Largest displacement change of the last iteration, m.
    pub fn last_change(&self) -> f64 {
        self.change
    }

    /// Solver time so far (setup included, callbacks excluded), s.
    pub fn seconds(&self) -> f64 {
        self.seconds
    }

    /// The operator `K + blocks`, element by element.
    pub fn operator(&self) -> &ElementOperator {
        &self.op
    }
}
