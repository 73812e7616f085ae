//! The numeric supernodal Cholesky factorisation a slice of supernodes at a
//! time, so that the workbench can spread a new discretisation's
//! factorisation over frames (faer's `factorize_numeric_llt` is one call,
//! 16–18 ms in a browser at 60 × 60).
//!
//! Left-looking, step for step as faer's `factorize_supernodal_numeric_llt`
//! on targets without its x86 kernels: supernode `s` (columns
//! `c = s_start..s_end`, off-diagonal rows `P_s`) gathers its columns of
//! `A` into its block `L_s` (rows `c ∪ P_s`), subtracts the update
//! `L_d[R, :] L_d[M, :]ᵀ` of every earlier supernode `d` whose pattern has
//! rows `M` among `c` (`R`: those rows and the rest of `d`'s pattern), then
//! factorises its diagonal block, `L_s[c, c] ← chol(L_s[c, c])`, and solves
//! `L_s[P_s, c] ← L_s[P_s, c] L_s[c, c]⁻ᵀ`. Nothing but the factor's values
//! carries from one supernode to the next, so any split of `0..n_supernodes`
//! into consecutive ranges gives the same factor.

use std::ops::Range;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::{Accum, MatMut, MatRef, Par, Spec, get_global_parallelism};

/// Below this many multiply–adds an update runs on one thread (faer's
/// threshold).
const PARALLEL_WORK: usize = 32 * 32 * 32;

/// Which supernodes update which (faer keeps this to itself), and what
/// each supernode costs to factorise.
#[derive(Debug)]
pub struct Updates {
    /// `descendants[start[s]..start[s + 1]]`: the supernodes `d < s` whose
    /// off-diagonal pattern has a row among `s`'s columns, ascending.
    start: Vec<usize>,
    descendants: Vec<usize>,
    /// `flops[s]`: the floating-point operations of supernodes `0..s`.
    flops: Vec<f64>,
    /// `owner[p]`: the supernode holding row `p`.
    owner: Vec<usize>,
}

impl Updates {
    /// The updates of `symbolic`'s supernodes, from their patterns.
    pub fn new(symbolic: &SymbolicSupernodalCholesky<usize>) -> Self {
        let ns = symbolic.n_supernodes();
        let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
        let mut owner = vec![0usize; symbolic.nrows()];
        for s in 0..ns {
            owner[begin[s]..end[s]].fill(s);
        }
        let mut cost = vec![0.0; ns];
        // (s, d) with d ascending
        let mut pairs = Vec::new();
        for d in 0..ns {
            let width = (end[d] - begin[d]) as f64;
            let pattern = symbolic.supernode(d).pattern();
            cost[d] += width * width * (width / 3.0 + pattern.len() as f64);
            let mut i = 0;
            while i < pattern.len() {
                let s = owner[pattern[i]];
                let mid = pattern[i..].partition_point(|&r| r < end[s]);
                cost[s] += 2.0 * width * mid as f64 * (pattern.len() - i) as f64;
                pairs.push((s, d));
                i += mid;
            }
        }
        let mut start = vec![0usize; ns + 1];
        for &(s, _) in &pairs {
            start[s + 1] += 1;
        }
        for s in 0..ns {
            start[s + 1] += start[s];
        }
        let mut next = start.clone();
        let mut descendants = vec![0; pairs.len()];
        for (s, d) in pairs {
            descendants[next[s]] = d;
            next[s] += 1;
        }
        let mut flops = Vec::with_capacity(ns + 1);
        flops.push(0.0);
        for c in cost {
            flops.push(flops.last().copied().unwrap_or(0.0) + c);
        }
        Self {
            start,
            descendants,
            flops,
            owner,
        }
    }

    /// The supernode holding each row.
    pub fn owner(&self) -> &[usize] {
        &self.owner
    }

    /// The number of supernodes.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The floating-point operations of the whole factorisation.
    pub fn total_flops(&self) -> f64 {
        self.flops.last().copied().unwrap_or(0.0)
    }

    /// The floating-point operations of supernode `s`.
    pub fn cost(&self, s: usize) -> f64 {
        self.flops[s + 1] - self.flops[s]
    }

    /// The end of the slice of `todo` (supernodes, ascending) that starts
    /// at `todo[from]` and costs at most `flops` (at least one supernode,
    /// when any is left).
    pub fn slice_end(&self, todo: &[usize], from: usize, flops: f64) -> usize {
        let mut spent = 0.0;
        let mut end = from;
        while end < todo.len() {
            spent += self.cost(todo[end]);
            if spent > flops && end > from {
                break;
            }
            end += 1;
        }
        end
    }

    /// The supernodes whose values change when the values of `a` change
    /// from `old` (both by the entries of `a`'s lower triangle, in the
    /// symbolic factorisation's order), ascending: those holding a changed
    /// column and their ancestors ([`with_ancestors`](Self::with_ancestors)).
    /// Every other supernode is the same, to the last bit, in a
    /// factorisation of either.
    pub fn changed(
        &self,
        symbolic: &SymbolicSupernodalCholesky<usize>,
        col_ptr: &[usize],
        old: &[f64],
        a: &[f64],
    ) -> Vec<usize> {
        let changed = col_ptr.windows(2).enumerate().filter(|(_, w)| {
            let (before, now) = (&old[w[0]..w[1]], &a[w[0]..w[1]]);
            before
                .iter()
                .zip(now)
                .any(|(p, q)| p.to_bits() != q.to_bits())
        });
        let marked = self.with_ancestors(symbolic, changed.map(|(j, _)| j));
        (0..self.len()).filter(|&s| marked[s]).collect()
    }

    /// Per supernode, whether it holds one of `rows` or is an ancestor of
    /// one that does in the supernodal elimination tree (a supernode's
    /// parent holds the first row of its off-diagonal pattern, and comes
    /// after it: one ascending pass).
    pub fn with_ancestors(
        &self,
        symbolic: &SymbolicSupernodalCholesky<usize>,
        rows: impl IntoIterator<Item = usize>,
    ) -> Vec<bool> {
        let mut marked = vec![false; self.len()];
        for p in rows {
            marked[self.owner[p]] = true;
        }
        for s in 0..self.len() {
            if marked[s]
                && let Some(&row) = symbolic.supernode(s).pattern().first()
            {
                marked[self.owner[row]] = true;
            }
        }
        marked
    }
}

/// Factorises the supernodes `range` of `a` (its lower triangle, in the
/// symbolic factorisation's order) into `l` (laid out as faer's supernodal
/// factor), the supernodes before `range.start` being factorised already.
/// `Err(i)`: the pivot of column `i` was not positive.
pub fn factorise(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    updates: &Updates,
    a: SparseColMatRef<'_, usize, f64>,
    l: &mut [f64],
    range: Range<usize>,
) -> Result<(), usize> {
    let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
    let col_ptr = symbolic.col_ptr_for_val();
    let par = get_global_parallelism();
    let widest = range.clone().map(|s| end[s] - begin[s]).max().unwrap_or(0);
    let mut mem = MemBuffer::new(cholesky_in_place_scratch::<f64>(
        widest,
        par,
        Spec::default(),
    ));
    let mut local = vec![usize::MAX; symbolic.nrows()];
    let mut product = Vec::new();
    let mut targets = Vec::new();
    for s in range {
        let (s_start, s_end) = (begin[s], end[s]);
        let s_pattern = symbolic.supernode(s).pattern();
        let width = s_end - s_start;
        for (i, &row) in s_pattern.iter().enumerate() {
            local[row] = width + i;
        }
        let (head, tail) = l.split_at_mut(col_ptr[s]);
        let head = &*head;
        let block = &mut tail[..col_ptr[s + 1] - col_ptr[s]];
        block.fill(0.0);
        let mut ls = MatMut::from_column_major_slice_mut(block, width + s_pattern.len(), width);
        for j in s_start..s_end {
            for (&i, &v) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
                if i >= j {
                    let row = if i >= s_end { local[i] } else { i - s_start };
                    ls[(row, j - s_start)] += v;
                }
            }
        }
        for &d in &updates.descendants[updates.start[s]..updates.start[s + 1]] {
            let d_pattern = symbolic.supernode(d).pattern();
            let d_width = end[d] - begin[d];
            let ld = MatRef::from_column_major_slice(
                &head[col_ptr[d]..col_ptr[d + 1]],
                d_width + d_pattern.len(),
                d_width,
            );
            let first = d_pattern.partition_point(|&r| r < s_start);
            let mid = d_pattern[first..].partition_point(|&r| r < s_end);
            let rows = d_pattern.len() - first;
            let below = ld.subrows(d_width + first, rows);
            let top = below.subrows(0, mid);
            targets.clear();
            targets.extend(
                d_pattern[first..]
                    .iter()
                    .enumerate()
                    .map(|(i, &row)| if i < mid { row - s_start } else { local[row] }),
            );
            subtract_update(&mut product, ls.as_mut(), below, top, par, &targets);
        }
        let (mut diagonal, mut off) = ls.split_at_row_mut(width);
        cholesky_in_place(
            diagonal.as_mut(),
            LltRegularization::default(),
            par,
            MemStack::new(&mut mem),
            Spec::default(),
        )
        .map_err(|e| match e {
            faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
                s_start + index
            }
        })?;
        solve_lower_triangular_in_place(diagonal.as_ref(), off.as_mut().transpose_mut(), par);
        for &row in s_pattern {
            local[row] = usize::MAX;
        }
    }
    Ok(())
}

/// `ls[rows[i], rows[j]] −= (below topᵀ)[i, j]` on and below the diagonal
/// (`top`: the first `top.nrows()` rows of `below`), through the scratch
/// `product`, as faer's generic path does it: the square top part as a
/// lower-triangular product, the rest as a rectangular one.
fn subtract_update(
    product: &mut Vec<f64>,
    mut ls: MatMut<'_, f64>,
    below: MatRef<'_, f64>,
    top: MatRef<'_, f64>,
    par: Par,
    rows: &[usize],
) {
    let (m, n) = (below.nrows(), top.nrows());
    if m == 0 || n == 0 {
        return;
    }
    let par = if m * n * below.ncols() > PARALLEL_WORK {
        par
    } else {
        Par::Seq
    };
    product.resize(m * n, 0.0);
    let mut out = MatMut::from_column_major_slice_mut(product.as_mut_slice(), m, n);
    triangular::matmul(
        out.as_mut().subrows_mut(0, n),
        BlockStructure::TriangularLower,
        Accum::Replace,
        below.subrows(0, n),
        BlockStructure::Rectangular,
        top.transpose(),
        BlockStructure::Rectangular,
        -1.0,
        par,
    );
    if m > n {
        matmul(
            out.as_mut().subrows_mut(n, m - n),
            Accum::Replace,
            below.subrows(n, m - n),
            top.transpose(),
            -1.0,
            par,
        );
    }
    let products = &product[..m * n];
    for j in 0..n {
        let target = ls
            .as_mut()
            .col_mut(rows[j])
            .try_as_col_major_mut()
            .expect("a supernode's block is column-major")
            .as_slice_mut();
        for (&r, &p) in rows[j..].iter().zip(&products[j * m + j..(j + 1) * m]) {
            target[r] += p;
        }
    }
}
