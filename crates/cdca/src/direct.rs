//! Direct solver: sparse Cholesky (faer, AMD ordering) of the assembled
//! matrix. The reference for every other solver.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::{Mat, Side};

use crate::assembly::{ElementBlock, assemble_lower};
use crate::error::SolveError;
use crate::xfem::Xfem;

/// A factorised stiffness matrix, reusable for several right-hand sides.
pub struct Factor {
    llt: Llt<usize, f64>,
    n: usize,
}

impl Factor {
    /// Assembles and factorises `K` (bulk plus `extra` blocks).
    pub fn new(x: &Xfem, extra: &[ElementBlock]) -> Result<Self, SolveError> {
        let n = x.n_free();
        let k = assemble_lower(x, extra).map_err(|detail| SolveError::NotPositiveDefinite { dofs: n, detail })?;
        let llt = k.sp_cholesky(Side::Lower).map_err(|e| SolveError::NotPositiveDefinite {
            dofs: n,
            detail: format!("{e:?} (a mechanism: check supports, or a singular enrichment)"),
        })?;
        Ok(Self { llt, n })
    }

    /// Solves `K u = f`.
    pub fn solve(&self, f: &[f64]) -> Result<Vec<f64>, SolveError> {
        let mut rhs = Mat::<f64>::from_fn(self.n, 1, |i, _| f[i]);
        self.llt.solve_in_place(rhs.as_mut());
        let u: Vec<f64> = (0..self.n).map(|i| rhs[(i, 0)]).collect();
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite {
                place: format!("direct solution, DOF {i}"),
            });
        }
        Ok(u)
    }
}
