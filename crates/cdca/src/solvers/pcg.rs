//! Preconditioned conjugate gradients, matrix-free (SPEC §6).
//!
//! The operator is applied element by element ([`ElementOperator::apply`]);
//! the preconditioner is the automaton's symmetric sweep ([`Ssor`]: a
//! forward then a backward cell sweep from zero, i.e. block symmetric
//! SOR) or a multigrid V-cycle built on it ([`crate::solvers::multigrid::Vcycle`]).
//! Both are symmetric positive definite for `0 < ω < 2`, so CG applies.
//!
//! ```text
//! r = f − K u,  z = M⁻¹ r,  p = z
//! repeat:  α = rᵀz / pᵀKp,  u += α p,  r −= α K p,
//!          z = M⁻¹ r,  β = rᵀz_new / rᵀz_old,  p = z + β p
//! ```
//!
//! Stops when `‖r‖ ≤ tolerance ‖f‖`, confirmed with the true residual (if
//! the recursive residual has drifted, CG restarts from the true one).

use crate::error::SolveError;
use crate::solvers::automaton::{Progress, relative};
use crate::solvers::cells::Cells;
use crate::solvers::element_op::{ElementOperator, dot, norm};

/// A symmetric positive definite approximation `M` of `K`: `z = M⁻¹ r`.
pub trait Preconditioner {
    fn precondition(
        &mut self,
        op: &ElementOperator,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<(), SolveError>;
}

/// The automaton's symmetric sweep as a preconditioner.
#[derive(Clone, Debug)]
pub struct Ssor {
    cells: Cells,
    omega: f64,
    s: Vec<f64>,
}

impl Ssor {
    pub fn new(cells: Cells, omega: f64, n: usize) -> Self {
        Self {
            cells,
            omega,
            s: vec![0.0; n],
        }
    }
}

impl Preconditioner for Ssor {
    fn precondition(
        &mut self,
        op: &ElementOperator,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<(), SolveError> {
        z.fill(0.0);
        self.s.copy_from_slice(r);
        self.cells.sweep(op, self.omega, false, z, &mut self.s)?;
        self.cells.sweep(op, self.omega, true, z, &mut self.s)?;
        Ok(())
    }
}

/// State of a preconditioned CG iteration between steps.
#[derive(Clone, Debug)]
pub struct Pcg<P> {
    pub tolerance: f64,
    pub pre: P,
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
    rz: f64,
    norm_f: f64,
}

impl<P: Preconditioner> Pcg<P> {
    pub fn new(
        tolerance: f64,
        pre: P,
        op: &ElementOperator,
        f: &[f64],
        u: &[f64],
    ) -> Result<Self, SolveError> {
        let n = op.n;
        let mut s = Self {
            tolerance,
            pre,
            r: vec![0.0; n],
            z: vec![0.0; n],
            p: vec![0.0; n],
            q: vec![0.0; n],
            rz: 0.0,
            norm_f: 0.0,
        };
        s.reset(op, f, u)?;
        Ok(s)
    }

    /// Starts again from `u` with right-hand side `f` (same operator).
    pub fn reset(&mut self, op: &ElementOperator, f: &[f64], u: &[f64]) -> Result<(), SolveError> {
        self.norm_f = norm(f);
        op.residual(f, u, &mut self.r);
        self.restart(op)
    }

    /// `z = M⁻¹ r`, `p = z` from the current residual.
    fn restart(&mut self, op: &ElementOperator) -> Result<(), SolveError> {
        self.pre.precondition(op, &self.r, &mut self.z)?;
        self.p.copy_from_slice(&self.z);
        self.rz = dot(&self.r, &self.z);
        Ok(())
    }

    pub fn relative_residual(&self) -> f64 {
        relative(norm(&self.r), self.norm_f)
    }

    /// One CG iteration.
    pub fn step(
        &mut self,
        op: &ElementOperator,
        f: &[f64],
        u: &mut [f64],
        iteration: usize,
    ) -> Result<Progress, SolveError> {
        let residual = self.relative_residual();
        if residual <= self.tolerance || self.rz == 0.0 {
            // nothing left to do (e.g. a zero right-hand side)
            return Ok(Progress {
                residual,
                change: 0.0,
                converged: true,
            });
        }
        op.apply(&self.p, &mut self.q);
        let pq = dot(&self.p, &self.q);
        if !pq.is_finite() || !self.rz.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("conjugate gradients, iteration {iteration}"),
            });
        }
        if pq <= 0.0 {
            return Err(SolveError::NotPositiveDefinite {
                dofs: op.n,
                detail: format!("p^T K p = {pq:.3e} at CG iteration {iteration}"),
            });
        }
        let alpha = self.rz / pq;
        let mut change: f64 = 0.0;
        for ((ui, pi), (ri, qi)) in u
            .iter_mut()
            .zip(&self.p)
            .zip(self.r.iter_mut().zip(&self.q))
        {
            *ui += alpha * pi;
            *ri -= alpha * qi;
            change = change.max((alpha * pi).abs());
        }
        let mut residual = self.relative_residual();
        if !residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("conjugate gradients residual, iteration {iteration}"),
            });
        }
        if residual <= self.tolerance {
            op.residual(f, u, &mut self.r);
            residual = self.relative_residual();
            if residual <= self.tolerance {
                return Ok(Progress {
                    residual,
                    change,
                    converged: true,
                });
            }
            self.restart(op)?; // the recursive residual drifted
            return Ok(Progress {
                residual,
                change,
                converged: false,
            });
        }
        self.pre.precondition(op, &self.r, &mut self.z)?;
        let rz = dot(&self.r, &self.z);
        let beta = rz / self.rz;
        self.rz = rz;
        for (pi, zi) in self.p.iter_mut().zip(&self.z) {
            *pi = zi + beta * *pi;
        }
        Ok(Progress {
            residual,
            change,
            converged: false,
        })
    }
}
