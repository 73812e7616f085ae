//! Direct solver: sparse Cholesky (faer, AMD ordering) of the assembled
//! matrix. The reference for every other solver.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::{Mat, Side};

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{REGULAR, Xfem};
use crate::error::SolveError;

/// A factorised stiffness matrix, reusable for several right-hand sides.
pub struct Factor {
    llt: Llt<usize, f64>,
    n: usize,
}

impl Factor {
    /// Assembles and factorises `K` (bulk plus `extra` blocks) into the
    /// discretisation's stiffness pattern, reusing its symbolic factorisation.
    pub fn new(x: &Xfem, extra: &[ElementBlock]) -> Result<Self, SolveError> {
        let pattern = x.pattern()?;
        let n = x.n_free();
        let mut mat = pattern.matrix().clone();
        let structure = pattern.matrix().symbolic();
        let (col_ptr, row_idx) = (structure.col_ptr(), structure.row_idx());
        let vals = mat.val_mut();
        vals.fill(0.0);
        let mut add = |dofs: &[u32], k: &dyn Fn(usize, usize) -> f64| {
            for (j, &dj) in dofs.iter().enumerate() {
                if dj == FIXED {
                    continue;
                }
                let (a, b) = (col_ptr[dj as usize], col_ptr[dj as usize + 1]);
                let rows = &row_idx[a..b];
                for (i, &di) in dofs.iter().enumerate() {
                    if di == FIXED || di < dj {
                        continue;
                    }
                    let p = rows.binary_search(&(di as usize));
                    assert!(
                        p.is_ok(),
                        "DOF pair ({di}, {dj}) outside the stiffness pattern"
                    );
                    if let Ok(p) = p {
                        vals[a + p] += k(i, j);
                    }
                }
            }
        };
        for e in 0..x.mesh.element_count() {
            if x.slot[e] == REGULAR {
                add(&x.regular_dofs(e), &|i, j| x.k0[(i, j)]);
            }
        }
        for el in &x.enriched {
            add(&el.dofs, &|i, j| el.k[(i, j)]);
        }
        for b in extra {
            add(&x.enriched[b.slot].dofs, &|i, j| b.k[(i, j)]);
        }
        let llt = Llt::try_new_with_symbolic(pattern.symbolic().clone(), mat.as_ref(), Side::Lower)
            .map_err(|e| SolveError::NotPositiveDefinite {
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
