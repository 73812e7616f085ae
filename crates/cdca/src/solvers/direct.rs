//! Direct solver: sparse Cholesky (faer, nested-dissection ordering) of the assembled
//! matrix, corrected by low rank when only a few contact states changed
//! ([`low_rank`](crate::solvers::low_rank)). The reference for every other
//! solver.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::linalg::matmul::matmul_with_conj;
use faer::linalg::triangular_solve::solve_upper_triangular_in_place_with_conj;
use faer::sparse::SparseColMatRef;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_lower_triangular_transpose_in_place,
};
use faer::{Accum, Conj, MatMut, MatRef, Side, Spec, get_global_parallelism};
use nalgebra::DMatrix;

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::pattern::{Ordered, Pattern};
use crate::discretisation::xfem::{NOT_INTEGRATED, REGULAR, Xfem};
use crate::error::SolveError;
use crate::solvers::forward::{Reached, SparseColumn};
use crate::solvers::low_rank::{Correction, MAX_RANK, Terms};
use crate::solvers::supernodal::{self, Updates};

/// The floating-point operations of one slice of a numeric factorisation
/// ([`Factor::factorise_slice`]): about 1 ms natively and 4–5 ms in a
/// browser, a quarter of a factorisation of the default scene (60 × 60,
/// 5–7e7 as [`Updates`] counts them).
pub const FACTOR_SLICE_FLOPS: f64 = 1.5e7;

/// A factorised stiffness matrix, reusable for several right-hand sides.
pub struct Factor {
    ordered: Arc<Ordered>,
    /// The factorised matrix: the values of `ordered.lower`.
    a: Vec<f64>,
    /// The values factorised before the last reassembly, kept as the
    /// storage of the next one's.
    before: Vec<f64>,
    /// The values of its Cholesky factor.
    l: Vec<f64>,
    /// The contact blocks assembled into it.
    blocks: Vec<ElementBlock>,
    /// Regular elements: the pattern's index of enriched element `s` is
    /// `regular + s`.
    regular: usize,
    /// When set, the factor solves the matrix with these blocks instead.
    correction: Option<Correction>,
    /// The relative residual the factorised matrix's last solve reached
    /// (0 before one).
    floor: f64,
    /// A supernodal factor's updates, shared by the factors of one
    /// pattern.
    updates: Option<Arc<Updates>>,
    /// The supernodes to factorise, ascending: all of them, or, when the
    /// factor was refactorised on its own pattern, those whose values
    /// change ([`Updates::changed`]).
    todo: Vec<usize>,
    /// The next of `todo` to factorise, while the numeric factorisation is
    /// under way ([`factorise_slice`](Self::factorise_slice)).
    pending: Option<usize>,
    /// A load and its forward solve `L⁻¹ P load` with this factor, kept
    /// for [`solve_reaching`](Self::solve_reaching).
    load_forward: Option<(Vec<f64>, Vec<f64>)>,
}

impl Factor {
    /// Assembles and factorises `K` (bulk plus `extra` blocks) into the
    /// discretisation's stiffness pattern, reusing its symbolic factorisation.
    pub fn new(x: &Xfem, extra: &[ElementBlock]) -> Result<Self, SolveError> {
        Self::assembled(x, extra, None)?.factorised()
    }

    /// `K` (bulk plus `extra` blocks) assembled, not yet factorised (see
    /// [`factorise_slice`](Self::factorise_slice)); `updates` are those of
    /// another factor on the same pattern, if any.
    pub fn assembled(
        x: &Xfem,
        extra: &[ElementBlock],
        updates: Option<Arc<Updates>>,
    ) -> Result<Self, SolveError> {
        let factor = Self {
            ordered: Arc::clone(x.pattern()?.ordered()),
            a: Vec::new(),
            before: Vec::new(),
            l: Vec::new(),
            blocks: Vec::new(),
            regular: 0,
            correction: None,
            floor: 0.0,
            updates,
            todo: Vec::new(),
            // nothing factorised yet
            pending: Some(0),
            load_forward: None,
        };
        factor.reassemble(x, extra)
    }

    /// [`Factor::assembled`] in this factor's storage. On the same
    /// pattern, a factorised supernodal factor is refactorised only where
    /// the values changed ([`Updates::changed`]): the supernodes of changed
    /// columns and their ancestors. The factor is the same, to the last
    /// bit, as one factorised anew.
    pub fn reassemble(mut self, x: &Xfem, extra: &[ElementBlock]) -> Result<Self, SolveError> {
        assert!(x.is_integrated(), "{NOT_INTEGRATED}");
        let pattern = x.pattern()?;
        let same = Arc::ptr_eq(&self.ordered, pattern.ordered());
        if !same {
            self.updates = None;
        }
        let compare = same && self.is_factorised();
        // the values factorised go to `before`, its storage takes the new
        std::mem::swap(&mut self.a, &mut self.before);
        self.ordered = Arc::clone(pattern.ordered());
        resize_spare(&mut self.a, self.ordered.lower.row_idx().len());
        self.a.fill(0.0);
        // the pattern's elements: regular ones in mesh order, then enriched
        let mut e = 0;
        for &slot in &x.slot {
            if slot == REGULAR {
                pattern.add(e, x.k0.as_slice(), &mut self.a);
                e += 1;
            }
        }
        for (s, el) in x.enriched.iter().enumerate() {
            pattern.add(e + s, el.k.as_slice(), &mut self.a);
        }
        for b in extra {
            pattern.add(e + b.slot, b.k.as_slice(), &mut self.a);
        }
        self.blocks.clear();
        self.blocks.extend_from_slice(extra);
        self.regular = e;
        self.correction = None;
        self.floor = 0.0;
        self.load_forward = None;
        let ordered = Arc::clone(&self.ordered);
        let supernodal = match ordered.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(symbolic) => Some(symbolic),
            SymbolicCholeskyRaw::Simplicial(_) => None,
        };
        self.todo = match (supernodal, &self.updates) {
            (Some(symbolic), Some(updates)) if compare => {
                updates.changed(symbolic, ordered.lower.col_ptr(), &self.before, &self.a)
            }
            _ => {
                // zeroed by the factorisation
                resize_spare(&mut self.l, ordered.symbolic.len_val());
                supernodal.map_or_else(Vec::new, |s| (0..s.n_supernodes()).collect())
            }
        };
        // a simplicial factor is factorised at once, in one call
        self.pending = (supernodal.is_none() || !self.todo.is_empty()).then_some(0);
        Ok(self)
    }

    /// This factor with its factorisation finished.
    fn factorised(mut self) -> Result<Self, SolveError> {
        while !self.factorise_slice(f64::INFINITY)? {}
        Ok(self)
    }

    /// The supernodes the last (re)factorisation computes: all of them, or
    /// on the factor's own pattern those whose values changed.
    pub fn supernodes_to_factorise(&self) -> usize {
        self.todo.len()
    }

    /// Whether the numeric factorisation is complete (only then does the
    /// factor solve).
    pub fn is_factorised(&self) -> bool {
        self.pending.is_none()
    }

    /// Factorises the next supernodes, about `flops` floating-point
    /// operations of them (at least one supernode; a simplicial factor all
    /// at once): whether the factorisation is now complete.
    pub fn factorise_slice(&mut self, flops: f64) -> Result<bool, SolveError> {
        let Some(from) = self.pending else {
            return Ok(true);
        };
        let o = &*self.ordered;
        let SymbolicCholeskyRaw::Supernodal(symbolic) = o.symbolic.raw() else {
            self.factorise()?;
            self.pending = None;
            return Ok(true);
        };
        let updates = Arc::clone(
            self.updates
                .get_or_insert_with(|| Arc::new(Updates::new(symbolic))),
        );
        let to = updates.slice_end(&self.todo, from, flops);
        let a = SparseColMatRef::new(o.lower.as_ref(), &self.a);
        // each run of consecutive supernodes in a call
        let mut run = from;
        while run < to {
            let first = self.todo[run];
            let end = run
                + self.todo[run..to]
                    .iter()
                    .enumerate()
                    .take_while(|&(i, &s)| s == first + i)
                    .count();
            supernodal::factorise(symbolic, &updates, a, &mut self.l, first..first + end - run)
                .map_err(|column| {
                    not_positive_definite(
                        o.perm.len(),
                        &format!("non-positive pivot at column {column}"),
                    )
                })?;
            run = end;
        }
        self.pending = (to < self.todo.len()).then_some(to);
        Ok(self.pending.is_none())
    }

    /// Whether this factor is of the discretisation that owns `pattern`.
    pub fn is_on(&self, pattern: &Pattern) -> bool {
        Arc::ptr_eq(&self.ordered, pattern.ordered())
    }

    /// The updates of this factor's supernodes, once made.
    pub fn updates(&self) -> Option<&Arc<Updates>> {
        self.updates.as_ref()
    }

    /// The numeric factorisation of the assembled values `a` into `l`, in
    /// one call (a simplicial factor).
    fn factorise(&mut self) -> Result<(), SolveError> {
        let o = &*self.ordered;
        let n = o.perm.len();
        let par = get_global_parallelism();
        let not_pd = |detail: String| not_positive_definite(n, &detail);
        let mut mem = MemBuffer::try_new(
            o.symbolic
                .factorize_numeric_llt_scratch::<f64>(par, Spec::default()),
        )
        .map_err(|e| not_pd(format!("{e:?}")))?;
        o.symbolic
            .factorize_numeric_llt(
                &mut self.l,
                SparseColMatRef::new(o.lower.as_ref(), &self.a),
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Spec::default(),
            )
            .map_err(|e| not_pd(format!("{e:?}")))?;
        Ok(())
    }

    /// Whether this factor solves `K` plus `blocks` on the discretisation
    /// that owns `pattern` (whose stiffness never changes once built),
    /// factorised or through its correction; the factorised matrix drops
    /// the correction.
    pub fn select(&mut self, pattern: &Pattern, blocks: &[ElementBlock]) -> bool {
        if !self.is_on(pattern) {
            return false;
        }
        if self.blocks == blocks {
            self.correction = None;
            return true;
        }
        self.correction.as_ref().is_some_and(|c| c.blocks == blocks)
    }

    /// The change from the factorised matrix to `K` plus `blocks` on `x`
    /// as rank-one terms, when `x` is this factor's discretisation and the
    /// rank is at most [`MAX_RANK`].
    pub fn difference(&self, x: &Xfem, blocks: &[ElementBlock]) -> Option<Terms> {
        let pattern = x.pattern().ok()?;
        if !self.is_factorised() || !Arc::ptr_eq(&self.ordered, pattern.ordered()) {
            return None;
        }
        Terms::between(x, &self.ordered.inv, &self.blocks, blocks, MAX_RANK)
    }

    /// Makes this factor solve `K` plus `blocks` by the correction `terms`
    /// ([`difference`](Self::difference)): `false` (and no change) when
    /// the corrected matrix is singular.
    pub fn correct(&mut self, x: &Xfem, terms: Terms, blocks: &[ElementBlock]) -> bool {
        let Ok(pattern) = x.pattern() else {
            return false;
        };
        let regular = self.regular;
        let correction = Correction::new(
            terms,
            blocks,
            &self.a,
            |slot, d, vals| pattern.add(regular + slot, d.as_slice(), vals),
            |columns| self.forward_columns(columns),
        );
        self.correction = correction;
        self.correction.is_some()
    }

    /// The relative residual the factorised matrix's last solve reached:
    /// the round-off floor a solve through a correction is held to.
    pub fn floor(&self) -> f64 {
        self.floor
    }

    /// Records the relative residual of a solve of the factorised matrix.
    pub fn set_floor(&mut self, residual: f64) {
        if residual.is_finite() {
            self.floor = residual;
        }
    }

    /// The rank of the correction in use, if any.
    pub fn correction_rank(&self) -> Option<usize> {
        self.correction.as_ref().map(Correction::rank)
    }

    /// `y ← L⁻¹ y` for the `r` reordered columns of `y` (column-major).
    fn forward(&self, y: &mut [f64], r: usize) {
        self.triangular(y, r, true);
    }

    /// `y ← L⁻ᵀ y` for the `r` reordered columns of `y` (column-major).
    fn backward(&self, y: &mut [f64], r: usize) {
        self.triangular(y, r, false);
    }

    fn triangular(&self, y: &mut [f64], r: usize, lower: bool) {
        debug_assert!(self.is_factorised(), "a factor solves once factorised");
        let o = &*self.ordered;
        let n = o.perm.len();
        let par = get_global_parallelism();
        let y = MatMut::from_column_major_slice_mut(y, n, r);
        match o.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(symbolic) => {
                let mut mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(r, par));
                let l = SupernodalLltRef::new(symbolic, &self.l);
                let stack = MemStack::new(&mut mem);
                if lower {
                    l.l_solve_with_conj(Conj::No, y, par, stack);
                } else {
                    l.l_transpose_solve_with_conj(Conj::No, y, par, stack);
                }
            }
            SymbolicCholeskyRaw::Simplicial(symbolic) => {
                let l = SparseColMatRef::new(symbolic.factor(), &self.l);
                if lower {
                    solve_lower_triangular_in_place(l, Conj::No, y, par);
                } else {
                    solve_lower_triangular_transpose_in_place(l, Conj::No, y, par);
                }
            }
        }
    }

    /// `L⁻¹ b` for the sparse reordered columns `b`: on the supernodes they
    /// reach, or, with a simplicial factor, on every row.
    fn forward_columns(&self, b: &[SparseColumn]) -> Reached {
        match self.ordered.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(symbolic) => {
                let updates = self
                    .updates
                    .as_ref()
                    .expect("a factorised supernodal factor");
                Reached::forward(symbolic, updates, &self.l, b)
            }
            SymbolicCholeskyRaw::Simplicial(_) => {
                let n = self.ordered.perm.len();
                let mut values = vec![0.0; n * b.len()];
                for (j, column) in b.iter().enumerate() {
                    for &(p, v) in column {
                        values[j * n + p] += v;
                    }
                }
                self.forward(&mut values, b.len());
                Reached {
                    rows: (0..n).collect(),
                    values,
                    columns: b.len(),
                }
            }
        }
    }

    /// `aᵀ K⁻¹ b` for every `a` of `rows` and `b` of `cols` (sparse, by
    /// DOF; `K` the matrix this factor solves, through its correction if
    /// any), column-major `rows.len() × cols.len()`: from the forward
    /// solves of the vectors alone, `(L⁻¹ a)ᵀ (L⁻¹ b)` on the part of the
    /// factor they reach ([`Reached`]), with the correction's
    /// `(aᵀ K⁻¹ U) (I + C Uᵀ K⁻¹ U)⁻¹ C (Uᵀ K⁻¹ b)` taken off.
    pub fn coupling(&self, rows: &[SparseColumn], cols: &[SparseColumn]) -> DMatrix<f64> {
        let inv = &self.ordered.inv;
        let reorder =
            |c: &SparseColumn| -> SparseColumn { c.iter().map(|&(d, a)| (inv[d], a)).collect() };
        let (na, nb) = (rows.len(), cols.len());
        let mut all: Vec<SparseColumn> = rows.iter().chain(cols).map(reorder).collect();
        if let Some(c) = &self.correction {
            all.extend_from_slice(c.vectors());
        }
        let w = self.forward_columns(&all);
        let inner = |a: std::ops::Range<usize>, b: std::ops::Range<usize>| {
            DMatrix::from_vec(a.len(), b.len(), w.inner(a, b))
        };
        let mut m = inner(0..na, na..na + nb);
        if let Some(c) = &self.correction {
            let (u, r) = (na + nb, c.rank());
            if r > 0 {
                let s = c.weights(&inner(u..u + r, na..na + nb));
                m -= inner(0..na, u..u + r) * s;
            }
        }
        m
    }

    /// The values of the matrix this factor solves.
    fn values(&self) -> &[f64] {
        self.correction.as_ref().map_or(&self.a, |c| &c.a)
    }

    /// Solves `K u = f` (`K`: the matrix this factor solves).
    pub fn solve(&self, f: &[f64]) -> Result<Vec<f64>, SolveError> {
        let o = &*self.ordered;
        let mut y: Vec<f64> = o.perm.iter().map(|&d| f[d]).collect();
        self.forward(&mut y, 1);
        if let Some(c) = &self.correction {
            c.adjust_forward(&mut y);
        }
        self.backward(&mut y, 1);
        self.solution(&y)
    }

    /// The solution by DOF from the reordered solution `y`; an error names
    /// the first DOF that is not finite.
    fn solution(&self, y: &[f64]) -> Result<Vec<f64>, SolveError> {
        let u: Vec<f64> = self.ordered.inv.iter().map(|&i| y[i]).collect();
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite {
                place: format!("direct solution, DOF {i}"),
            });
        }
        Ok(u)
    }

    /// The solve of `f` taken on the rows that the DOFs `dofs` need only,
    /// for an `f` that differs from `load` on `dofs` alone (a contact
    /// iteration's right-hand side: the load, plus contact forces on the
    /// faces' DOFs). The forward solve is that of `load`, kept per factor,
    /// plus that of `f − load` on the supernodes it reaches
    /// ([`Reached::forward`]); the backward solve runs on the supernodes
    /// holding `dofs` and their ancestors (a row's value in `L⁻ᵀ z`
    /// depends on its ancestors' alone). [`complete`](Self::complete)
    /// finishes it into the whole solution. `None` for a simplicial factor
    /// and for an `f` that differs from `load` off `dofs`.
    pub fn solve_reaching(&mut self, f: &[f64], load: &[f64], dofs: &[usize]) -> Option<Partial> {
        let ordered = Arc::clone(&self.ordered);
        let SymbolicCholeskyRaw::Supernodal(symbolic) = ordered.symbolic.raw() else {
            return None;
        };
        let mut on_dofs = vec![false; f.len()];
        for &d in dofs {
            on_dofs[d] = true;
        }
        let off_load = f.len() != load.len()
            || f.iter()
                .zip(load)
                .zip(&on_dofs)
                .any(|((a, b), &on)| !on && a != b);
        if off_load {
            return None;
        }
        if self.load_forward.as_ref().is_none_or(|(l, _)| l != load) {
            let mut z: Vec<f64> = ordered.perm.iter().map(|&d| load[d]).collect();
            self.forward(&mut z, 1);
            self.load_forward = Some((load.to_vec(), z));
        }
        let o = &*ordered;
        let updates = self.updates.as_ref()?;
        let (_, z_load) = self.load_forward.as_ref()?;
        let mut y = z_load.clone();
        let forces: SparseColumn = dofs
            .iter()
            .map(|&d| (o.inv[d], f[d] - load[d]))
            .filter(|&(_, v)| v != 0.0)
            .collect();
        let done = self.solve_sparse_into(symbolic, updates, forces, dofs, &mut y);
        Some(Partial { y, done })
    }

    /// Adds `L⁻¹ forces` (reordered positions) to the forward solution
    /// `y` on the supernodes the forces reach, then takes the backward
    /// solve on the supernodes holding `dofs` and their ancestors: which
    /// supernodes it solved.
    fn solve_sparse_into(
        &self,
        symbolic: &SymbolicSupernodalCholesky<usize>,
        updates: &Updates,
        forces: SparseColumn,
        dofs: &[usize],
        y: &mut [f64],
    ) -> Vec<bool> {
        let reached = Reached::forward(symbolic, updates, &self.l, &[forces]);
        for (&row, &v) in reached.rows.iter().zip(&reached.values) {
            y[row] += v;
        }
        if let Some(c) = &self.correction {
            c.adjust_forward(y);
        }
        let inv = &self.ordered.inv;
        let done = updates.with_ancestors(symbolic, dofs.iter().map(|&d| inv[d]));
        self.backward_on(y, |s| done[s]);
        done
    }

    /// `K⁻¹ b` for a sparse `b` (by DOF), on the DOFs `dofs` alone: the
    /// forward solve on the supernodes `b` reaches, the backward solve on
    /// those holding `dofs` and their ancestors, as in
    /// [`solve_reaching`](Self::solve_reaching). By DOF, exact (to
    /// round-off) on `dofs` and every row their supernodes hold, zero
    /// where the backward solve did not reach. `None` for a simplicial or
    /// unfinished factor.
    pub fn solve_on(&self, b: &SparseColumn, dofs: &[usize]) -> Option<Vec<f64>> {
        let o = &*self.ordered;
        let SymbolicCholeskyRaw::Supernodal(symbolic) = o.symbolic.raw() else {
            return None;
        };
        let updates = self.updates.as_ref().filter(|_| self.is_factorised())?;
        let forces: SparseColumn = b.iter().map(|&(d, v)| (o.inv[d], v)).collect();
        let mut y = vec![0.0; o.perm.len()];
        let done = self.solve_sparse_into(symbolic, updates, forces, dofs, &mut y);
        let mut u = vec![0.0; y.len()];
        self.reached_rows(&Partial { y, done }, &mut u);
        Some(u)
    }

    /// The rows of `partial` that its backward solve has reached, as DOF
    /// values in `u` (the others left as they are).
    pub fn reached_rows(&self, partial: &Partial, u: &mut [f64]) {
        let o = &*self.ordered;
        if let SymbolicCholeskyRaw::Supernodal(symbolic) = o.symbolic.raw() {
            let (begin, end) = (symbolic.supernode_begin(), symbolic.supernode_end());
            for s in (0..partial.done.len()).filter(|&s| partial.done[s]) {
                for i in begin[s]..end[s] {
                    u[o.perm[i]] = partial.y[i];
                }
            }
        }
    }

    /// The whole solution from a [`solve_reaching`](Self::solve_reaching)
    /// of this factor: the backward solve on the supernodes it left.
    pub fn complete(&self, mut partial: Partial) -> Result<Vec<f64>, SolveError> {
        let done = std::mem::take(&mut partial.done);
        self.backward_on(&mut partial.y, |s| !done[s]);
        self.solution(&partial.y)
    }

    /// `y ← L⁻ᵀ y` on the supernodes `take` selects, from the last down (as
    /// faer's `l_transpose_solve_with_conj`, whose kernels it calls): the
    /// whole backward solve when the ancestors of every selected
    /// supernode are solved first or selected.
    fn backward_on(&self, y: &mut [f64], take: impl Fn(usize) -> bool) {
        let o = &*self.ordered;
        let SymbolicCholeskyRaw::Supernodal(symbolic) = o.symbolic.raw() else {
            return;
        };
        let l = SupernodalLltRef::new(symbolic, &self.l);
        let par = get_global_parallelism();
        let mut gathered = Vec::new();
        for s in (0..symbolic.n_supernodes()).rev().filter(|&s| take(s)) {
            let node = l.supernode(s);
            let (start, pattern) = (node.start(), node.pattern());
            let ls = node.val();
            let size = ls.ncols();
            let (top, bottom) = ls.split_at_row(size);
            gathered.clear();
            gathered.extend(pattern.iter().map(|&i| y[i]));
            let mut x = MatMut::from_column_major_slice_mut(y, o.perm.len(), 1);
            let mut x_top = x.as_mut().subrows_mut(start, size);
            matmul_with_conj(
                x_top.as_mut(),
                Accum::Add,
                bottom.transpose(),
                Conj::No,
                MatRef::from_column_major_slice(&gathered, pattern.len(), 1),
                Conj::No,
                -1.0,
                par,
            );
            solve_upper_triangular_in_place_with_conj(top.transpose(), Conj::No, x_top, par);
        }
    }

    /// `‖f − K u‖ / ‖f‖` (or ‖K u‖ when f = 0) with the factorised `K`.
    pub fn relative_residual(&self, f: &[f64], u: &[f64]) -> f64 {
        let mut r = vec![0.0; f.len()];
        self.residual(f, u, &mut r);
        let norm = |w: &[f64]| w.iter().map(|a| a * a).sum::<f64>().sqrt();
        let nf = norm(f);
        if nf > 0.0 { norm(&r) / nf } else { norm(&r) }
    }

    /// `r = f − K u` with the factorised `K`.
    pub fn residual(&self, f: &[f64], u: &[f64], r: &mut [f64]) {
        let o = &*self.ordered;
        let (col_ptr, row_idx) = (o.lower.col_ptr(), o.lower.row_idx());
        let vals = self.values();
        let v: Vec<f64> = o.perm.iter().map(|&d| u[d]).collect();
        let mut rp: Vec<f64> = o.perm.iter().map(|&d| f[d]).collect();
        for (c, &vc) in v.iter().enumerate() {
            let column = col_ptr[c]..col_ptr[c + 1];
            let mut sum = 0.0;
            for (&i, &a) in row_idx[column.clone()].iter().zip(&vals[column]) {
                rp[i] -= a * vc;
                if i != c {
                    sum += a * v[i];
                }
            }
            rp[c] -= sum;
        }
        for (d, &i) in o.inv.iter().enumerate() {
            r[d] = rp[i];
        }
    }
}

/// A solve taken on part of a supernodal factor
/// ([`Factor::solve_reaching`]): the reordered right-hand side after the
/// forward solve, and after the backward solve on the supernodes `done`.
pub struct Partial {
    y: Vec<f64>,
    done: Vec<bool>,
}

/// A factorisation that met a non-positive pivot.
fn not_positive_definite(dofs: usize, detail: &str) -> SolveError {
    SolveError::NotPositiveDefinite {
        dofs,
        detail: format!("{detail} (a mechanism: check supports, or a singular enrichment)"),
    }
}

/// Gives `v` the length `len` (its values unspecified). Factors are large,
/// kept, and grow a little with the cracks: a new allocation leaves a
/// sixteenth spare, which lasts several growth steps (fresh memory costs a
/// page fault per 4 KiB on first touch).
fn resize_spare(v: &mut Vec<f64>, len: usize) {
    if v.capacity() < len {
        *v = Vec::new();
        v.reserve_exact(len + len / 16);
    }
    v.resize(len, 0.0);
}
