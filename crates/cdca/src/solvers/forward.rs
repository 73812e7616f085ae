//! Forward solves `L W = B` with a supernodal Cholesky factor for a few
//! sparse right-hand sides, on the supernodes their nonzeros reach only.
//!
//! A nonzero in row `p` of `B` changes `W` only in `p`'s supernode and its
//! ancestors in the supernodal elimination tree (the parent of a supernode
//! is the one holding the first row of its off-diagonal pattern), so a
//! right-hand side confined to the crack faces' DOFs needs the factor's
//! columns on the path from those DOFs to the root, a fraction of a whole
//! solve. Couplings between such vectors then need no backward solve:
//! with `P K Pᵀ = L Lᵀ`, `aᵀ K⁻¹ b = (L⁻¹ P a)ᵀ (L⁻¹ P b)`.

use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::{Accum, MatMut, MatRef, Par};

use crate::solvers::supernodal::Updates;

/// A sparse vector: (index, value) pairs, by DOF or, inside a factor, by
/// reordered position; an index may repeat (the values add).
pub type SparseColumn = Vec<(usize, f64)>;

/// `L⁻¹ b` for every column `b`, on the rows it can reach.
pub struct Reached {
    /// The rows reached, ascending (the reordered positions of whole
    /// supernodes).
    pub rows: Vec<usize>,
    /// `L⁻¹ b` on `rows`, column-major `rows.len() × columns`; zero on
    /// every other row.
    pub values: Vec<f64>,
    /// The number of right-hand sides.
    pub columns: usize,
}

impl Reached {
    /// `L⁻¹ B` on the rows reached from the columns `b` of `B`, with the
    /// factor `symbolic`, whose values are `l` and whose supernodes'
    /// updates are `updates`.
    pub fn forward(
        symbolic: &SymbolicSupernodalCholesky<usize>,
        updates: &Updates,
        l: &[f64],
        b: &[SparseColumn],
    ) -> Self {
        let ns = symbolic.n_supernodes();
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let owner = updates.owner();
        // supernodes holding a nonzero, and their ancestors
        let active = updates.with_ancestors(symbolic, b.iter().flatten().map(|&(p, _)| p));
        // each active supernode's first row in the compact storage
        let mut offset = vec![usize::MAX; ns];
        let mut rows = Vec::new();
        for s in (0..ns).filter(|&s| active[s]) {
            offset[s] = rows.len();
            rows.extend(begin[s]..end[s]);
        }
        let local = |p: usize| offset[owner[p]] + p - begin[owner[p]];
        let (nr, k) = (rows.len(), b.len());
        let mut w = vec![0.0; nr * k];
        for (c, column) in b.iter().enumerate() {
            for &(p, v) in column {
                w[c * nr + local(p)] += v;
            }
        }
        let mut update = Vec::new();
        let values = symbolic.col_ptr_for_val();
        for s in (0..ns).filter(|&s| active[s]) {
            let pattern = symbolic.supernode(s).pattern();
            let (ncols, below) = (end[s] - begin[s], pattern.len());
            let ls =
                MatRef::from_column_major_slice(&l[values[s]..values[s + 1]], ncols + below, ncols);
            let mut all = MatMut::from_column_major_slice_mut(&mut w, nr, k);
            solve_lower_triangular_in_place(
                ls.subrows(0, ncols),
                all.as_mut().subrows_mut(offset[s], ncols),
                Par::Seq,
            );
            if below == 0 {
                continue;
            }
            update.clear();
            update.resize(below * k, 0.0);
            matmul(
                MatMut::from_column_major_slice_mut(&mut update, below, k),
                Accum::Replace,
                ls.subrows(ncols, below),
                all.as_ref().subrows(offset[s], ncols),
                1.0,
                Par::Seq,
            );
            for (i, &p) in pattern.iter().enumerate() {
                let row = local(p);
                for c in 0..k {
                    w[c * nr + row] -= update[c * below + i];
                }
            }
        }
        Self {
            rows,
            values: w,
            columns: k,
        }
    }

    /// `W_aᵀ W_b` for the columns `a` and `b` of the result: with the
    /// whole forward solve, `aᵀ (L Lᵀ)⁻¹ b`. Column-major
    /// `a.len() × b.len()`.
    pub fn inner(&self, a: std::ops::Range<usize>, b: std::ops::Range<usize>) -> Vec<f64> {
        let nr = self.rows.len();
        let (na, nb) = (a.len(), b.len());
        let mut out = vec![0.0; na * nb];
        if nr > 0 {
            let all = MatRef::from_column_major_slice(&self.values, nr, self.columns);
            matmul(
                MatMut::from_column_major_slice_mut(&mut out, na, nb),
                Accum::Replace,
                all.subcols(a.start, na).transpose(),
                all.subcols(b.start, nb),
                1.0,
                Par::Seq,
            );
        }
        out
    }
}
