//! The sparsity pattern (lower triangle) of one discretisation's stiffness
//! and its symbolic Cholesky factorisation (in a fill-reducing order the
//! discretisation gives: the mesh's nested dissection,
//! [`Mesh::nested_dissection`](crate::geometry::mesh::Mesh::nested_dissection)),
//! computed once and reused for every numeric factorisation on that
//! discretisation: contact blocks live on enriched elements, whose DOFs are
//! already coupled, so they never change the pattern.
//!
//! The pattern is stored in the fill-reducing order, so a factorisation
//! assembles straight into the matrix it factorises; and every element
//! keeps the positions of its entries in that matrix (a scatter map), so
//! assembly is `vals[pos] += k` with no search.
//!
//! The discretisation owns it ([`Xfem::pattern`](crate::discretisation::xfem::Xfem::pattern));
//! the direct solver fills it ([`Factor`](crate::solvers::direct::Factor)).

use std::sync::Arc;

use faer::Side;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{FaerError, SymbolicSparseColMat, SymbolicSparseColMatRef};

use crate::discretisation::dofs::FIXED;
use crate::error::SolveError;

/// A local entry of an element matrix that is not assembled (a constrained
/// DOF, or the upper triangle).
const SKIP: u32 = u32::MAX;

/// What every factorisation on a pattern shares: the fill-reducing
/// ordering, the reordered lower triangle and its symbolic factorisation.
#[derive(Debug)]
pub struct Ordered {
    /// `perm[i]`: the DOF at position `i` of the reordered matrix.
    pub perm: Vec<usize>,
    /// `inv[d]`: the position of DOF `d` in the reordered matrix.
    pub inv: Vec<usize>,
    /// Lower triangle of the reordered matrix (sorted rows).
    pub lower: SymbolicSparseColMat<usize>,
    /// Symbolic Cholesky factorisation of `lower` (no further reordering).
    pub symbolic: SymbolicCholesky<usize>,
}

/// Pattern, ordering and symbolic factorisation of a stiffness matrix, and
/// each element's scatter map into it.
#[derive(Clone, Debug)]
pub struct Pattern {
    ordered: Arc<Ordered>,
    /// The element DOF lists it was built from (`dofs`, `starts` of
    /// [`structure`](Self::structure)), for [`fits`](Self::fits).
    dofs: Vec<u32>,
    dof_starts: Vec<usize>,
    /// Start of each element's map in `map`, and the end of the last.
    starts: Vec<usize>,
    /// Per element, column-major like its matrix: the position in
    /// `ordered.lower`'s values of each local entry, or [`SKIP`].
    map: Vec<u32>,
}

/// A [`Pattern`] before its symbolic factorisation
/// ([`Pattern::structure`], then [`analyse`](Self::analyse)).
#[derive(Clone, Debug)]
pub struct Unanalysed {
    perm: Vec<usize>,
    inv: Vec<usize>,
    lower: SymbolicSparseColMat<usize>,
    dofs: Vec<u32>,
    dof_starts: Vec<usize>,
    starts: Vec<usize>,
    map: Vec<u32>,
}

impl Unanalysed {
    /// The second half of [`Pattern::structure`]: the symbolic factorisation of
    /// the lower triangle, from its transpose (faer's choice between
    /// simplicial and supernodal, from the flops of this elimination).
    pub fn analyse(self) -> Result<Pattern, SolveError> {
        let n = self.perm.len();
        let (upper_ptr, upper_rows) =
            regroup(n, self.lower.col_ptr(), self.lower.row_idx(), |r, c| (c, r));
        let upper =
            SymbolicSparseColMatRef::new_unsorted_checked(n, n, &upper_ptr, None, &upper_rows);
        let params = CholeskySymbolicParams::default();
        let symbolic =
            factorize_symbolic_cholesky(upper, Side::Upper, SymmetricOrdering::Identity, params)
                .map_err(|e: FaerError| SolveError::NotPositiveDefinite {
                    dofs: n,
                    detail: format!("{e:?}"),
                })?;
        Ok(Pattern {
            ordered: Arc::new(Ordered {
                perm: self.perm,
                inv: self.inv,
                lower: self.lower,
                symbolic,
            }),
            dofs: self.dofs,
            dof_starts: self.dof_starts,
            starts: self.starts,
            map: self.map,
        })
    }
}

impl Pattern {
    /// The pattern of `n` free DOFs coupled element by element, in the
    /// fill-reducing order `perm` (`perm[i]`: the DOF at position `i`):
    /// element `e`'s DOFs are `dofs[starts[e]..starts[e + 1]]` ([`FIXED`]
    /// entries are skipped), and [`add`](Self::add) takes the elements by
    /// the same index. This is its first half, the reordered lower
    /// triangle and the scatter maps (about two thirds of the time);
    /// [`Unanalysed::analyse`] adds the symbolic factorisation (the
    /// workbench makes each half in a call of its own).
    pub fn structure(
        n: usize,
        dofs: &[u32],
        starts: &[usize],
        perm: Vec<usize>,
    ) -> Result<Unanalysed, SolveError> {
        assert_eq!(perm.len(), n, "an ordering of every DOF");
        let mut map_starts = Vec::with_capacity(starts.len());
        map_starts.push(0);
        for w in starts.windows(2) {
            let len = w[1] - w[0];
            map_starts.push(map_starts[map_starts.len() - 1] + len * len);
        }
        let entries = map_starts[map_starts.len() - 1];
        if u32::try_from(entries).is_err() || u32::try_from(n).is_err() {
            return Err(SolveError::NotPositiveDefinite {
                dofs: n,
                detail: format!("{entries} element matrix entries: too many to index"),
            });
        }
        let mut inv = vec![0; n];
        for (i, &d) in perm.iter().enumerate() {
            inv[d] = i;
        }
        // the reordered matrix: its lower triangle (sorted) for the
        // factorisations, with every element entry's position in it
        let mut map = vec![SKIP; entries];
        let (lower_ptr, lower_rows) = lower_triangle(n, dofs, starts, &inv, &mut map);
        Ok(Unanalysed {
            perm,
            inv,
            lower: SymbolicSparseColMat::new_checked(n, n, lower_ptr, None, lower_rows),
            dofs: dofs.to_vec(),
            dof_starts: starts.to_vec(),
            starts: map_starts,
            map,
        })
    }

    /// Whether this is the pattern [`structure`](Self::structure) would make of the
    /// same arguments: another discretisation whose elements couple the
    /// same DOFs in the same order (a crack moved within the elements it
    /// cuts and enriches) shares it.
    pub fn fits(&self, dofs: &[u32], starts: &[usize], perm: &[usize]) -> bool {
        self.dofs == dofs && self.dof_starts == starts && self.ordered.perm == perm
    }

    /// Ordering, reordered lower triangle and symbolic factorisation,
    /// shared with the factors made on this pattern.
    pub fn ordered(&self) -> &Arc<Ordered> {
        &self.ordered
    }

    /// Adds element `e`'s matrix `k` (column-major, in the element's DOF
    /// order) to `vals`, the values of the reordered lower triangle: its
    /// entries `(i, j)` with `dofs[i] ≥ dofs[j]`, both free.
    pub fn add(&self, e: usize, k: &[f64], vals: &mut [f64]) {
        let map = &self.map[self.starts[e]..self.starts[e + 1]];
        assert_eq!(map.len(), k.len(), "element {e}: matrix size");
        for (&p, &v) in map.iter().zip(k) {
            if p != SKIP {
                vals[p as usize] += v;
            }
        }
    }
}

/// Calls `f(row, column, k)` for every assembled entry of the elements'
/// matrices (element `e`'s DOFs `dofs[starts[e]..starts[e + 1]]`, its
/// entries `(i, j)` with both free and `dofs[i] ≥ dofs[j]`), at its
/// position in the lower triangle of the matrix reordered by `inv`, `k`
/// counting the entries of the element matrices one after the other
/// (column-major, assembled or not).
fn each_entry(
    dofs: &[u32],
    starts: &[usize],
    inv: &[usize],
    mut f: impl FnMut(usize, usize, usize),
) {
    let mut k = 0;
    for w in starts.windows(2) {
        let el = &dofs[w[0]..w[1]];
        for &dj in el {
            for &di in el {
                if di != FIXED && dj != FIXED && di >= dj {
                    let (a, b) = (inv[di as usize], inv[dj as usize]);
                    f(a.max(b), a.min(b), k);
                }
                k += 1;
            }
        }
    }
}

/// Compressed columns (pointers, sorted distinct row indices) of the lower
/// triangle of the elements' matrix reordered by `inv` (elements as in
/// [`each_entry`]), and the position of each assembled element entry in
/// its row indices, set in `map` (indexed as `each_entry` counts; fewer
/// than 2³² entries and DOFs).
fn lower_triangle(
    n: usize,
    dofs: &[u32],
    starts: &[usize],
    inv: &[usize],
    map: &mut [u32],
) -> (Vec<usize>, Vec<usize>) {
    let mut bounds = vec![0; n + 1];
    each_entry(dofs, starts, inv, |_, c, _| bounds[c + 1] += 1);
    for c in 0..n {
        bounds[c + 1] += bounds[c];
    }
    // per column, each entry's row (high half) and index (low half)
    let mut next = bounds[..n].to_vec();
    let mut entries = vec![0_u64; bounds[n]];
    each_entry(dofs, starts, inv, |r, c, k| {
        entries[next[c]] = ((r as u64) << 32) | k as u64;
        next[c] += 1;
    });
    let mut col_ptr = vec![0; n + 1];
    let mut rows = Vec::with_capacity(bounds[n]);
    for c in 0..n {
        let column = &mut entries[bounds[c]..bounds[c + 1]];
        column.sort_unstable();
        let mut last = usize::MAX;
        for &e in column.iter() {
            let r = (e >> 32) as usize;
            if r != last {
                rows.push(r);
                last = r;
            }
            map[(e & u64::from(u32::MAX)) as usize] = (rows.len() - 1) as u32;
        }
        col_ptr[c + 1] = rows.len();
    }
    // (the repeats' room freed: the pattern is kept)
    rows.shrink_to_fit();
    (col_ptr, rows)
}

/// The entries of the `n × n` pattern `(col_ptr, row_idx)` moved to the
/// `(row, column)` that `to` gives for their `(row, column)`. A new column
/// lists its rows in the order of the old columns (so sorted when `to`
/// transposes).
fn regroup(
    n: usize,
    col_ptr: &[usize],
    row_idx: &[usize],
    to: impl Fn(usize, usize) -> (usize, usize),
) -> (Vec<usize>, Vec<usize>) {
    let mut ptr = vec![0; n + 1];
    for c in 0..n {
        for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
            ptr[to(r, c).1 + 1] += 1;
        }
    }
    for c in 0..n {
        ptr[c + 1] += ptr[c];
    }
    let mut next = ptr[..n].to_vec();
    let mut rows = vec![0; row_idx.len()];
    for c in 0..n {
        for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
            let (r, c) = to(r, c);
            rows[next[c]] = r;
            next[c] += 1;
        }
    }
    (ptr, rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Element matrices added through the scatter maps give the reordered
    /// lower triangle of the matrix assembled densely, on elements that
    /// share DOFs, list them out of order and hold constrained ones; the
    /// pattern's rows are sorted and distinct.
    #[test]
    fn scatter_maps_assemble_the_reordered_lower_triangle() {
        let n = 7;
        let dofs = [0, 3, FIXED, 5, 2, 3, 6, 1, FIXED, 4, 5, 0, 6];
        let starts = [0, 4, 8, 13];
        let perm = vec![4, 0, 6, 2, 5, 1, 3];
        let p = Pattern::structure(n, &dofs, &starts, perm.clone())
            .and_then(Unanalysed::analyse)
            .expect("a pattern");
        let lower = &p.ordered().lower;
        let mut vals = vec![0.0; lower.row_idx().len()];
        let mut dense = vec![vec![0.0; n]; n];
        for (e, w) in starts.windows(2).enumerate() {
            let el = &dofs[w[0]..w[1]];
            let m = el.len();
            // symmetric, nonzero
            let k: Vec<f64> = (0..m * m)
                .map(|q| {
                    let (i, j) = (q % m, q / m);
                    (1 + 10 * e + i.max(j) * m + i.min(j)) as f64
                })
                .collect();
            p.add(e, &k, &mut vals);
            for (j, &dj) in el.iter().enumerate() {
                for (i, &di) in el.iter().enumerate() {
                    if di != FIXED && dj != FIXED {
                        dense[di as usize][dj as usize] += k[j * m + i];
                    }
                }
            }
        }
        let (cp, ri) = (lower.col_ptr(), lower.row_idx());
        let mut seen = 0;
        for c in 0..n {
            let rows = &ri[cp[c]..cp[c + 1]];
            assert!(rows.windows(2).all(|w| w[0] < w[1]), "column {c}: {rows:?}");
            for (k, &r) in rows.iter().enumerate() {
                assert!(r >= c, "lower triangle");
                assert_eq!(vals[cp[c] + k], dense[perm[r]][perm[c]], "({r}, {c})");
            }
            seen += (c..n).filter(|&r| dense[perm[r]][perm[c]] != 0.0).count();
        }
        assert_eq!(seen, ri.len(), "every coupled pair, once");
    }
}
