//! The linear solvers of one operator `(K + K_contact) u = f` (SPEC §6),
//! behind one resumable trait so that the contact iteration runs any of
//! them in slices of any size: [`LinearSolver::start`] sets a solve up (at
//! most one factorisation, set of cells or hierarchy),
//! [`LinearSolver::run`] advances it by a few iterations, and the blocking
//! [`LinearSolver::solve`] is a loop over the two.

use nalgebra::DMatrix;
use web_time::Instant;

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::scene::DIRECT_TOLERANCE;
use crate::solvers::direct::{FACTOR_SLICE_FLOPS, Factor, Partial};
use crate::solvers::forward::SparseColumn;
use crate::solvers::relaxation::{RelaxStatus, ResidualSample};

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

/// A resumable solver of the assembled-or-not operator. `Send`, so that a
/// [`Simulation`](crate::Simulation) can be moved to another thread (the
/// workbench grows natively on a thread of its own).
pub trait LinearSolver: Send {
    /// Name as in the scene's `solver.kind`.
    fn name(&self) -> &'static str;

    /// Starts a solve of `(K + blocks) u = f` from `u0` (a warm start for
    /// iterative solvers; zero when its length does not match).
    /// `matrix_changed` is false when only `f` changed since the last solve
    /// on the same discretisation: the setup (factorisation, cells,
    /// hierarchy) is then kept.
    fn start(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u0: &[f64],
        matrix_changed: bool,
    ) -> Result<(), SolveError>;

    /// Runs at most `max_iterations` more iterations of the started solve.
    /// It has `finished` when it converged or reached the solver's
    /// iteration cap (`solver.max_iterations`; then `converged: false`,
    /// which is not an error: the last iterate stays in [`u`](Self::u)).
    fn run(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        max_iterations: usize,
    ) -> Result<RelaxStatus, SolveError>;

    /// The current iterate (the solution once finished and converged).
    fn u(&self) -> &[f64];

    /// The started solve so far.
    fn info(&self) -> LinearInfo;

    /// The started solve has a factorisation to make first: it runs in the
    /// next [`run`](Self::run) calls, a slice of about
    /// [`FACTOR_SLICE_FLOPS`] each (the workbench gives each a frame slice
    /// of its own), before the solve.
    fn factorising(&self) -> bool {
        false
    }

    /// Factorises the next slice of the started solve's factorisation
    /// (about [`FACTOR_SLICE_FLOPS`]) without solving: whether it is now
    /// complete (at once for a solver that makes none).
    fn factorise_next(&mut self) -> Result<bool, SolveError> {
        Ok(true)
    }

    /// Progress samples of the started solve with their times, s (setup
    /// included).
    fn samples(&self) -> &[ResidualSample];

    /// `aᵀ K⁻¹ b` for every `a` of `rows` and `b` of `cols` (sparse, by
    /// DOF), `K` the matrix of the started solve, column-major
    /// `rows.len() × cols.len()`: how a force along `b` moves the
    /// displacement along `a`, without a solve of the whole system. `None`
    /// for a solver that keeps no factor.
    fn coupling(&self, _rows: &[SparseColumn], _cols: &[SparseColumn]) -> Option<DMatrix<f64>> {
        None
    }

    /// `K⁻¹ b`, `K` the matrix of the started solve, for a solver that
    /// keeps a factor of it (once factorised); `None` for one that does
    /// not. The contact iteration's Newton step
    /// ([`newton`](crate::contact::newton)) solves with it.
    fn solve_again(&self, _b: &[f64]) -> Option<Vec<f64>> {
        None
    }

    /// [`solve_again`](Self::solve_again) for a sparse `b` (by DOF), on
    /// the DOFs `dofs` alone (by DOF; the others zero or partial): the
    /// part of the factor `b` and `dofs` reach (all of it for a small,
    /// simplicial factor).
    fn solve_on(&self, _b: &SparseColumn, _dofs: &[usize]) -> Option<Vec<f64>> {
        None
    }

    /// Whether the solver keeps a factor of its matrix, so that
    /// [`solve_again`](Self::solve_again) answers once it is factorised:
    /// the contact iteration then takes Newton steps.
    fn keeps_factor(&self) -> bool {
        false
    }

    /// The started solve's solution on the rows that the DOFs `dofs`
    /// need, without the rest of the system and without a residual check,
    /// when its right-hand side differs from `load` on `dofs` alone:
    /// the whole solve's to round-off on `dofs`, with every other DOF
    /// keeping its value in `elsewhere`. For a contact iteration that only
    /// needs the faces' gaps to see whether a state changes. `None` for a
    /// solver that keeps no factor, and while the factor is not complete.
    fn solve_reaching(
        &mut self,
        _load: &[f64],
        _dofs: &[usize],
        _elsewhere: &[f64],
    ) -> Option<Vec<f64>> {
        None
    }

    /// Hands over the current factor (a direct solver's), for
    /// [`adopt_factor`](Self::adopt_factor) by the solver of a simulation
    /// built from this one's discretisation.
    fn hand_over_factor(&mut self) -> Option<Factor> {
        None
    }

    /// Takes a factor of another simulation's matrix as storage for the
    /// next factorisation, which on the same pattern redoes only the part
    /// whose values changed (dropped by solvers that keep no factor).
    fn adopt_factor(&mut self, _factor: Factor) {}

    /// The whole solve at once: [`start`](Self::start), then
    /// [`run`](Self::run) until it has finished; `u` is the starting guess
    /// and the result.
    fn solve(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u: &mut Vec<f64>,
        matrix_changed: bool,
    ) -> Result<LinearInfo, SolveError> {
        self.start(x, blocks, f, u, matrix_changed)?;
        while !self.run(x, blocks, usize::MAX)?.finished {}
        u.clear();
        u.extend_from_slice(self.u());
        Ok(self.info())
    }
}

/// Factors a [`DirectSolver`] keeps: the current one and the one before.
/// The contact iteration of a critical-control trial often returns to the
/// contact states the previous trial's matrix was built with (in a 40-step
/// growth run of a two-flaw specimen, 38 of 148 factorisations were of a
/// matrix the solver had factorised just before the current one).
const KEPT_FACTORS: usize = 2;

/// Iterative refinement steps (`u += K⁻¹ (f − K u)`) a direct solve may
/// take to meet [`DIRECT_TOLERANCE`].
pub const MAX_REFINEMENTS: usize = 3;

/// The true relative residual a solve through a low-rank correction must
/// reach, by refinement, or the matrix is factorised after all: 1e-12, or
/// [`CORRECTED_SLACK`] times the residual its factor's own matrix was
/// solved to if that is larger (the round-off floor grows with the mesh:
/// 2.5–9e-13 at 100 × 100, 1.4e-12 at 300 × 300; a corrected solve
/// reaches the same floor). So a correction gives the solution a
/// factorisation would, to well below the tolerances that read it.
pub const CORRECTED_TOLERANCE: f64 = 1e-12;

/// See [`CORRECTED_TOLERANCE`].
pub const CORRECTED_SLACK: f64 = 10.0;

/// Sparse Cholesky, refactorised only when the matrix changed (the
/// symbolic factorisation is the discretisation's, computed once), and not
/// even then when it is the matrix of a kept factor or differs from one by
/// contact blocks of rank at most
/// [`MAX_RANK`](crate::solvers::low_rank::MAX_RANK) (a few points changed
/// state: solved through a low-rank correction of that factor, checked
/// against [`CORRECTED_TOLERANCE`], and factorised after all where the
/// correction misses it). One
/// [`run`](LinearSolver::run) is the triangular solves and, while the true
/// relative residual ‖f − K u‖/‖f‖ is above [`DIRECT_TOLERANCE`] and falls,
/// up to [`MAX_REFINEMENTS`] steps of iterative refinement; the solve has
/// converged when the residual meets that tolerance (a singular matrix,
/// such as a piece held by its crack faces alone, may still factorise
/// with tiny pivots, and its "solution" is then no solution).
#[derive(Default)]
pub struct DirectSolver {
    /// The last factors, the current one first.
    factors: Vec<Factor>,
    /// A factor handed over from another simulation
    /// ([`LinearSolver::adopt_factor`]): storage for the next new factor,
    /// and, on the same pattern, a refactorisation of its changed part
    /// only ([`Factor::reassemble`]). It never solves: its matrix is not
    /// this simulation's.
    adopted: Option<Factor>,
    f: Vec<f64>,
    u: Vec<f64>,
    status: RelaxStatus,
    samples: Vec<ResidualSample>,
    /// Setup time of the started solve, s.
    setup_seconds: f64,
    /// The started solve taken on the faces' rows
    /// ([`solve_reaching`](LinearSolver::solve_reaching)), which the whole
    /// solve completes.
    partial: Option<Partial>,
}

impl DirectSolver {
    /// The rank of the low-rank correction the current solve goes
    /// through (`None`: a factorised matrix, or nothing started).
    pub fn correction_rank(&self) -> Option<usize> {
        self.factors.first().and_then(Factor::correction_rank)
    }

    /// Makes a kept factor on `x` solve `K` plus `blocks` through a
    /// low-rank correction (the one needing the lowest rank, at most
    /// [`MAX_RANK`](crate::solvers::low_rank::MAX_RANK)); its index.
    fn corrected(&mut self, x: &Xfem, blocks: &[ElementBlock]) -> Option<usize> {
        let (i, terms) = self
            .factors
            .iter()
            .enumerate()
            .filter_map(|(i, k)| k.difference(x, blocks).map(|t| (i, t)))
            .min_by_key(|(_, t)| t.rank())?;
        self.factors[i].correct(x, terms, blocks).then_some(i)
    }

    /// Assembles `K` plus `blocks` as the current factor, in the oldest
    /// kept factor's storage when all are kept (dropped if this fails); its
    /// factorisation is left to [`factorise_slice`](Self::factorise_slice).
    fn reassemble(&mut self, x: &Xfem, blocks: &[ElementBlock]) -> Result<(), SolveError> {
        let oldest = (self.factors.len() >= KEPT_FACTORS)
            .then(|| self.factors.pop())
            .flatten();
        let factor = if let Some(old) = oldest.or_else(|| self.adopted.take()) {
            old.reassemble(x, blocks)?
        } else {
            let pattern = x.pattern()?;
            let updates = self
                .factors
                .iter()
                .find(|f| f.is_on(pattern))
                .and_then(|f| f.updates().cloned());
            Factor::assembled(x, blocks, updates)?
        };
        self.factors.insert(0, factor);
        Ok(())
    }

    /// Factorises `K` plus `blocks` as the current factor, all at once.
    fn refactor(&mut self, x: &Xfem, blocks: &[ElementBlock]) -> Result<(), SolveError> {
        self.reassemble(x, blocks)?;
        while !self.factorise_slice(f64::INFINITY)? {}
        Ok(())
    }

    /// Factorises about `flops` more of the current factor: whether it is
    /// complete.
    fn factorise_slice(&mut self, flops: f64) -> Result<bool, SolveError> {
        match self.factors.first_mut() {
            Some(factor) => factor.factorise_slice(flops).inspect_err(|_| {
                self.factors.remove(0);
            }),
            None => Ok(true),
        }
    }

    /// The residual a solve through the current factor's correction must
    /// reach ([`CORRECTED_TOLERANCE`]).
    fn corrected_tolerance(&self) -> f64 {
        let floor = self.factors.first().map_or(0.0, Factor::floor);
        CORRECTED_TOLERANCE.max(CORRECTED_SLACK * floor)
    }

    /// The current factor's solution of `f`, refined while the true
    /// relative residual is above its tolerance ([`DIRECT_TOLERANCE`], or
    /// [`corrected_tolerance`](Self::corrected_tolerance) through a
    /// correction) and falls: the solution, its residual and the
    /// refinements taken.
    fn refined(&mut self) -> Result<(Vec<f64>, f64, usize), SolveError> {
        let partial = self.partial.take();
        let factor = self
            .factors
            .first()
            .expect("a direct solve is started before it runs");
        let tolerance = if factor.correction_rank().is_some() {
            self.corrected_tolerance()
        } else {
            DIRECT_TOLERANCE
        };
        let mut u = match partial {
            Some(p) => factor.complete(p)?,
            None => factor.solve(&self.f)?,
        };
        let mut residual = factor.relative_residual(&self.f, &u);
        let mut refinements = 0;
        while residual > tolerance && refinements < MAX_REFINEMENTS {
            let mut r = vec![0.0; u.len()];
            factor.residual(&self.f, &u, &mut r);
            let du = factor.solve(&r)?;
            let refined: Vec<f64> = u.iter().zip(&du).map(|(a, b)| a + b).collect();
            let after = factor.relative_residual(&self.f, &refined);
            refinements += 1;
            if after >= residual || after.is_nan() {
                break;
            }
            u = refined;
            residual = after;
        }
        Ok((u, residual, refinements))
    }
}

impl LinearSolver for DirectSolver {
    fn name(&self) -> &'static str {
        "direct"
    }

    fn hand_over_factor(&mut self) -> Option<Factor> {
        self.factors.truncate(1);
        self.factors.pop()
    }

    fn adopt_factor(&mut self, factor: Factor) {
        self.adopted = Some(factor);
    }

    fn start(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        f: &[f64],
        u0: &[f64],
        matrix_changed: bool,
    ) -> Result<(), SolveError> {
        let clock = Instant::now();
        if matrix_changed || self.factors.is_empty() {
            let pattern = x.pattern()?;
            if let Some(i) = self
                .factors
                .iter_mut()
                .position(|k| k.select(pattern, blocks))
            {
                self.factors[..=i].rotate_right(1);
            } else if let Some(i) = self.corrected(x, blocks) {
                self.factors[..=i].rotate_right(1);
            } else {
                self.reassemble(x, blocks)?;
            }
        }
        self.f.clear();
        self.f.extend_from_slice(f);
        self.u.clear();
        self.u.extend_from_slice(u0);
        self.status = RelaxStatus::default();
        self.samples.clear();
        self.partial = None;
        self.setup_seconds = clock.elapsed().as_secs_f64();
        Ok(())
    }

    fn run(
        &mut self,
        x: &Xfem,
        blocks: &[ElementBlock],
        max_iterations: usize,
    ) -> Result<RelaxStatus, SolveError> {
        if self.status.finished || max_iterations == 0 {
            return Ok(self.status);
        }
        let clock = Instant::now();
        if !self.factorise_slice(FACTOR_SLICE_FLOPS)? {
            // the factorisation goes on in the next call
            self.setup_seconds += clock.elapsed().as_secs_f64();
            return Ok(self.status);
        }
        let mut solved = self.refined();
        let tolerance = self.corrected_tolerance();
        let missed = match &solved {
            Ok((_, residual, _)) => residual.is_nan() || *residual > tolerance,
            Err(_) => true,
        };
        if missed && self.correction_rank().is_some() {
            // the correction lost too much to round-off (or the corrected
            // matrix is singular): factorise
            self.refactor(x, blocks)?;
            solved = self.refined();
        }
        let (u, residual, refinements) = solved?;
        if self.correction_rank().is_none() {
            self.factors[0].set_floor(residual);
        }
        self.u = u;
        self.status = RelaxStatus {
            iterations: 1 + refinements,
            residual,
            converged: residual <= DIRECT_TOLERANCE,
            finished: true,
        };
        self.samples.push(ResidualSample {
            iteration: 1,
            seconds: self.setup_seconds + clock.elapsed().as_secs_f64(),
            residual,
        });
        Ok(self.status)
    }

    fn u(&self) -> &[f64] {
        &self.u
    }

    fn info(&self) -> LinearInfo {
        LinearInfo {
            iterations: self.status.iterations,
            residual: self.status.residual,
            converged: self.status.converged,
            history: self.samples.iter().map(|s| s.residual).collect(),
        }
    }

    fn factorising(&self) -> bool {
        self.factors.first().is_some_and(|f| !f.is_factorised())
    }

    fn coupling(&self, rows: &[SparseColumn], cols: &[SparseColumn]) -> Option<DMatrix<f64>> {
        self.factors.first().map(|f| f.coupling(rows, cols))
    }

    fn keeps_factor(&self) -> bool {
        true
    }

    fn factorise_next(&mut self) -> Result<bool, SolveError> {
        let clock = Instant::now();
        let done = self.factorise_slice(FACTOR_SLICE_FLOPS);
        self.setup_seconds += clock.elapsed().as_secs_f64();
        done
    }

    fn solve_on(&self, b: &SparseColumn, dofs: &[usize]) -> Option<Vec<f64>> {
        let factor = self.factors.first().filter(|f| f.is_factorised())?;
        factor.solve_on(b, dofs).or_else(|| {
            // a simplicial factor (a small system) solves whole
            let mut dense = vec![0.0; self.f.len()];
            for &(d, v) in b {
                dense[d] += v;
            }
            factor.solve(&dense).ok()
        })
    }

    fn solve_again(&self, b: &[f64]) -> Option<Vec<f64>> {
        let factor = self.factors.first().filter(|f| f.is_factorised())?;
        factor.solve(b).ok()
    }

    fn solve_reaching(
        &mut self,
        load: &[f64],
        dofs: &[usize],
        elsewhere: &[f64],
    ) -> Option<Vec<f64>> {
        let factor = self.factors.first_mut().filter(|f| f.is_factorised())?;
        let partial = factor.solve_reaching(&self.f, load, dofs)?;
        let mut u = elsewhere.to_vec();
        factor.reached_rows(&partial, &mut u);
        if u.iter().any(|v| !v.is_finite()) {
            return None;
        }
        // the whole solve, if it follows, completes this one
        self.partial = Some(partial);
        Some(u)
    }

    fn samples(&self) -> &[ResidualSample] {
        &self.samples
    }
}
