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
    /// [`new`](Self::new)), for [`fits`](Self::fits).
    dofs: Vec<u32>,
    dof_starts: Vec<usize>,
    /// Start of each element's map in `map`, and the end of the last.
    starts: Vec<usize>,
    /// Per element, column-major like its matrix: the position in
    /// `ordered.lower`'s values of each local entry, or [`SKIP`].
    map: Vec<u32>,
}

impl Pattern {
    /// The pattern of `n` free DOFs coupled element by element, in the
    /// fill-reducing order `perm` (`perm[i]`: the DOF at position `i`):
    /// element `e`'s DOFs are `dofs[starts[e]..starts[e + 1]]` ([`FIXED`]
    /// entries are skipped), and [`add`](Self::add) takes the elements by
    /// the same index.
    pub fn new(
        n: usize,
        dofs: &[u32],
        starts: &[usize],
        perm: Vec<usize>,
    ) -> Result<Self, SolveError> {
        assert_eq!(perm.len(), n, "an ordering of every DOF");
        let not_pd = |e: FaerError| SolveError::NotPositiveDefinite {
            dofs: n,
            detail: format!("{e:?}"),
        };
        let elements = || starts.windows(2).map(|w| &dofs[w[0]..w[1]]);
        let (cp, ri) = compressed_columns(n, |push| {
            for el in elements() {
                for &dj in el.iter().filter(|&&d| d != FIXED) {
                    for &di in el.iter().filter(|&&d| d != FIXED && d >= dj) {
                        push(di as usize, dj as usize);
                    }
                }
            }
        });
        if u32::try_from(ri.len()).is_err() {
            return Err(SolveError::NotPositiveDefinite {
                dofs: n,
                detail: format!("{} stiffness entries: too many to index", ri.len()),
            });
        }
        let (cp, ri) = (cp.as_slice(), ri.as_slice());
        let mut inv = vec![0; n];
        for (i, &d) in perm.iter().enumerate() {
            inv[d] = i;
        }
        // the reordered matrix: its upper triangle (unsorted) for the
        // symbolic analysis, and the transpose, its lower triangle (sorted),
        // for the factorisations
        let (upper_ptr, upper_rows) = regroup(n, cp, ri, |r, c| {
            let (a, b) = (inv[r], inv[c]);
            (a.min(b), a.max(b))
        });
        let (lower_ptr, lower_rows) = regroup(n, &upper_ptr, &upper_rows, |r, c| (c, r));
        let upper =
            SymbolicSparseColMatRef::new_unsorted_checked(n, n, &upper_ptr, None, &upper_rows);
        let lower = SymbolicSparseColMat::new_checked(n, n, lower_ptr, None, lower_rows);
        // faer's choice between simplicial and supernodal, from the flops
        // of this elimination
        let params = CholeskySymbolicParams::default();
        let symbolic =
            factorize_symbolic_cholesky(upper, Side::Upper, SymmetricOrdering::Identity, params)
                .map_err(not_pd)?;
        let (cp, ri) = (lower.col_ptr(), lower.row_idx());
        let mut map = Vec::with_capacity(elements().map(|el| el.len() * el.len()).sum());
        let mut map_starts = Vec::with_capacity(starts.len());
        map_starts.push(0);
        for el in elements() {
            for &dj in el {
                for &di in el {
                    if di == FIXED || dj == FIXED || di < dj {
                        map.push(SKIP);
                        continue;
                    }
                    let (a, b) = (inv[di as usize], inv[dj as usize]);
                    let (r, c) = (a.max(b), a.min(b));
                    let Ok(k) = ri[cp[c]..cp[c + 1]].binary_search(&r) else {
                        unreachable!("the pattern holds every pair it was built from")
                    };
                    map.push((cp[c] + k) as u32);
                }
            }
            map_starts.push(map.len());
        }
        Ok(Self {
            ordered: Arc::new(Ordered {
                perm,
                inv,
                lower,
                symbolic,
            }),
            dofs: dofs.to_vec(),
            dof_starts: starts.to_vec(),
            starts: map_starts,
            map,
        })
    }

    /// Whether this is the pattern [`new`](Self::new) would make of the
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

/// Compressed columns (pointers, sorted distinct row indices) of an `n × n`
/// pattern from the `(row, column)` pairs `pairs` gives (it is called
/// twice, and must give the same pairs; repeats are merged).
fn compressed_columns(
    n: usize,
    pairs: impl Fn(&mut dyn FnMut(usize, usize)),
) -> (Vec<usize>, Vec<usize>) {
    let mut bounds = vec![0; n + 1];
    pairs(&mut |_, c| bounds[c + 1] += 1);
    for c in 0..n {
        bounds[c + 1] += bounds[c];
    }
    let mut next = bounds[..n].to_vec();
    let mut rows = vec![0; bounds[n]];
    pairs(&mut |r, c| {
        rows[next[c]] = r;
        next[c] += 1;
    });
    let mut col_ptr = vec![0; n + 1];
    let mut len = 0;
    for c in 0..n {
        rows[bounds[c]..bounds[c + 1]].sort_unstable();
        let mut last = usize::MAX;
        for k in bounds[c]..bounds[c + 1] {
            // len ≤ k: compacting never overwrites what is still to be read
            let r = rows[k];
            if r != last {
                rows[len] = r;
                len += 1;
                last = r;
            }
        }
        col_ptr[c + 1] = len;
    }
    rows.truncate(len);
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
