//! Direct solver: sparse Cholesky (faer, AMD ordering) of the assembled
//! matrix. The reference for every other solver.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use crate::assembly::ElementBlock;
use crate::dofs::FIXED;
use crate::error::SolveError;
use crate::xfem::{REGULAR, Xfem};

/// The sparsity pattern (lower triangle) of one discretisation's stiffness
/// and its symbolic Cholesky factorisation (AMD ordering, elimination
/// tree), computed once and reused for every numeric factorisation on that
/// discretisation: contact blocks live on enriched elements, whose DOFs are
/// already coupled, so they never change the pattern.
#[derive(Clone, Debug)]
pub struct Pattern {
    mat: SparseColMat<usize, f64>,
    symbolic: SymbolicLlt<usize>,
}

impl Pattern {
    pub fn new(x: &Xfem) -> Result<Self, SolveError> {
        let n = x.n_free();
        let mut trip: Vec<Triplet<usize, usize, f64>> =
            Vec::with_capacity(x.mesh.element_count() * 36);
        let mut push = |dofs: &[u32]| {
            for &dj in dofs.iter().filter(|&&d| d != FIXED) {
                for &di in dofs.iter().filter(|&&d| d != FIXED && d >= dj) {
                    trip.push(Triplet::new(di as usize, dj as usize, 0.0));
                }
            }
        };
        for e in 0..x.mesh.element_count() {
            if x.slot[e] == REGULAR {
                push(&x.regular_dofs(e));
            }
        }
        for el in &x.enriched {
            push(&el.dofs);
        }
        let not_pd = |detail: String| SolveError::NotPositiveDefinite { dofs: n, detail };
        let mat = SparseColMat::try_new_from_triplets(n, n, &trip)
            .map_err(|e| not_pd(format!("{e:?}")))?;
        let symbolic = SymbolicLlt::try_new(mat.symbolic(), Side::Lower)
            .map_err(|e| not_pd(format!("{e:?}")))?;
        Ok(Self { mat, symbolic })
    }

    /// Scatters the element matrices into the pattern and factorises.
    pub fn factor(&self, x: &Xfem, extra: &[ElementBlock]) -> Result<Factor, SolveError> {
        let n = x.n_free();
        let mut mat = self.mat.clone();
        let pattern = self.mat.symbolic();
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
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
        let llt = Llt::try_new_with_symbolic(self.symbolic.clone(), mat.as_ref(), Side::Lower)
            .map_err(|e| SolveError::NotPositiveDefinite {
                dofs: n,
                detail: format!("{e:?} (a mechanism: check supports, or a singular enrichment)"),
            })?;
        Ok(Factor { llt, n })
    }
}

/// A factorised stiffness matrix, reusable for several right-hand sides.
pub struct Factor {
    llt: Llt<usize, f64>,
    n: usize,
}

impl Factor {
    /// Assembles and factorises `K` (bulk plus `extra` blocks), with the
    /// discretisation's cached symbolic factorisation.
    pub fn new(x: &Xfem, extra: &[ElementBlock]) -> Result<Self, SolveError> {
        x.pattern()?.factor(x, extra)
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
