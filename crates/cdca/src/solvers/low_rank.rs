//! A change of the contact blocks as a low-rank correction of a factorised
//! matrix (Woodbury), so that a contact iteration or λ trial whose states
//! differ from a factorised matrix's at a few points needs a few
//! triangular solves instead of a numeric factorisation.
//!
//! A face point adds `w k_N J_N J_Nᵀ` (closed) and `w k_T J_T J_Tᵀ` (stuck)
//! to its element's block, so a state change at `m` points changes the
//! matrix by a symmetric matrix of rank at most `2m`. Per changed element,
//! the difference of its blocks `D = Σ λᵢ vᵢ vᵢᵀ` (its eigenpairs, those
//! above [`DROP`] of the largest), so the changed matrix is
//!
//! `K' = K + U C Uᵀ`, `U = [v₁ … v_r]`, `C = diag(λ)`,
//!
//! `K'⁻¹ f = y − Z (I + C Uᵀ Z)⁻¹ C Uᵀ y`, `y = K⁻¹ f`, `Z = K⁻¹ U`
//!
//! (the form without `C⁻¹`: a penalty's eigenvalues span many decades).
//! With `K = L Lᵀ` (reordered), `Uᵀ Z = Wᵀ W` and `Uᵀ y = Wᵀ z` for
//! `W = L⁻¹ U` and the forward solve `z = L⁻¹ f`, and `Z s = L⁻ᵀ (W s)`:
//! so the correction is made between the two triangular solves of the
//! factor ([`Correction::adjust_forward`]), and a corrected solve costs what
//! a factorised one does. Setting it up costs the forward solves of the
//! `r` sparse columns of `U` on the part of the factor they reach
//! ([`Reached`]), not `r` whole solves. The caller
//! checks the true residual with `K'` and refines, so the dropped
//! eigenpairs (round-off of the difference) do not reach the solution.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::solvers::forward::{Reached, SparseColumn};

/// Eigenvalues of a block difference below this fraction of its largest
/// are round-off (a difference of whole penalty terms has `2m` nonzero
/// eigenvalues and the rest at ~1e-16 of them).
pub const DROP: f64 = 1e-12;

/// The largest rank of a correction. Set up from forward solves on the
/// part of the factor the changed points reach, a correction of rank 9–24
/// costs 0.4 ms on 60 × 60 elements and 0.7 ms on 100 × 100, against a
/// numeric factorisation's 3.6 and 16 ms, so the crossover lies far above
/// this cap; raised to 64 and 128 it changed no run's time (the
/// factorisations left are each discretisation's first), so it stays
/// where the correction's accuracy was checked (`docs/benchmarks.md`,
/// "Contact solves on the part of the factor the faces reach").
pub const MAX_RANK: usize = 24;

/// The difference between two sets of contact blocks on one
/// discretisation as rank-one terms `λ v vᵀ`, each `v` as (reordered
/// position, value) pairs.
pub struct Terms {
    /// `λ` per term.
    lambda: Vec<f64>,
    /// `v` per term.
    vectors: Vec<SparseColumn>,
    /// The changed blocks: slot and `new − old`, element DOF order.
    changed: Vec<(usize, DMatrix<f64>)>,
}

impl Terms {
    /// `new − old` (blocks sorted by slot, as the contact system gives
    /// them) as rank-one terms at the reordered positions `inv`, or `None`
    /// when its rank is over `max_rank`.
    pub fn between(
        x: &Xfem,
        inv: &[usize],
        old: &[ElementBlock],
        new: &[ElementBlock],
        max_rank: usize,
    ) -> Option<Self> {
        let mut terms = Self {
            lambda: Vec::new(),
            vectors: Vec::new(),
            changed: Vec::new(),
        };
        let (mut i, mut j) = (0, 0);
        while i < old.len() || j < new.len() {
            let slot_old = old.get(i).map_or(usize::MAX, |b| b.slot);
            let slot_new = new.get(j).map_or(usize::MAX, |b| b.slot);
            let slot = slot_old.min(slot_new);
            let d = match (slot_old == slot, slot_new == slot) {
                (true, true) if old[i].k == new[j].k => None,
                (true, true) => Some(&new[j].k - &old[i].k),
                (true, false) => Some(-&old[i].k),
                _ => Some(new[j].k.clone()),
            };
            i += usize::from(slot_old == slot);
            j += usize::from(slot_new == slot);
            let Some(d) = d else { continue };
            let dofs = &x.enriched[slot].dofs;
            let eig = SymmetricEigen::new(d.clone());
            let largest = eig.eigenvalues.amax();
            for (k, &l) in eig.eigenvalues.iter().enumerate() {
                if l.abs() <= DROP * largest {
                    continue;
                }
                if terms.lambda.len() == max_rank {
                    return None;
                }
                terms.lambda.push(l);
                terms
                    .vectors
                    .push(scatter(dofs, &eig.eigenvectors.column(k).into(), inv));
            }
            terms.changed.push((slot, d));
        }
        Some(terms)
    }

    /// The rank of the correction.
    pub fn rank(&self) -> usize {
        self.lambda.len()
    }
}

/// An element vector at the reordered positions of its free DOFs.
fn scatter(dofs: &[u32], v: &DVector<f64>, inv: &[usize]) -> SparseColumn {
    dofs.iter()
        .zip(v.iter())
        .filter(|&(&d, &a)| d != FIXED && a != 0.0)
        .map(|(&d, &a)| (inv[d as usize], a))
        .collect()
}

/// A factorised matrix's correction `U C Uᵀ`, set up for solves.
pub struct Correction {
    /// The contact blocks of the corrected matrix.
    pub blocks: Vec<ElementBlock>,
    /// Values of the corrected matrix (the reordered lower triangle).
    pub a: Vec<f64>,
    terms: Terms,
    /// `W = L⁻¹ U` (`K = L Lᵀ`, reordered) on the rows it reaches.
    w: Reached,
    /// LU of `I + C Wᵀ W = I + C Uᵀ K⁻¹ U`.
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl Correction {
    /// Sets up the correction `terms` of a matrix whose values are `a`,
    /// giving the contact blocks `blocks`: `add` adds a changed block
    /// (slot, `new − old`) into a copy of `a`; `forward` gives `L⁻¹` of
    /// sparse reordered columns ([`Reached`]). `None` when `I + C Uᵀ K⁻¹ U`
    /// is singular (so is the corrected matrix).
    pub fn new(
        terms: Terms,
        blocks: &[ElementBlock],
        a: &[f64],
        add: impl Fn(usize, &DMatrix<f64>, &mut [f64]),
        forward: impl FnOnce(&[SparseColumn]) -> Reached,
    ) -> Option<Self> {
        let r = terms.rank();
        let w = forward(&terms.vectors);
        let wtw = DMatrix::from_column_slice(r, r, &w.inner(0..r, 0..r));
        let mut m = DMatrix::identity(r, r);
        for i in 0..r {
            for k in 0..r {
                m[(i, k)] += terms.lambda[i] * wtw[(i, k)];
            }
        }
        let lu = m.lu();
        if !lu.is_invertible() {
            return None;
        }
        let mut values = a.to_vec();
        for (slot, d) in &terms.changed {
            add(*slot, d, &mut values);
        }
        Some(Self {
            blocks: blocks.to_vec(),
            a: values,
            terms,
            w,
            lu,
        })
    }

    /// The rank of the correction.
    pub fn rank(&self) -> usize {
        self.terms.rank()
    }

    /// The columns `U` of the correction (sparse, reordered).
    pub fn vectors(&self) -> &[SparseColumn] {
        &self.terms.vectors
    }

    /// `(I + C Uᵀ K⁻¹ U)⁻¹ C v`: what the correction does with `v = Uᵀ K⁻¹ b`.
    pub fn weights(&self, v: &DMatrix<f64>) -> DMatrix<f64> {
        let cv = DMatrix::from_fn(v.nrows(), v.ncols(), |k, j| {
            self.terms.lambda[k] * v[(k, j)]
        });
        self.lu.solve(&cv).expect("checked invertible when set up")
    }

    /// Turns the forward solve `z = L⁻¹ P f` of `K u = f` into that of
    /// `K' u = f`, so that the backward solve `Lᵀ` of it gives `K'⁻¹ f`:
    /// `K'⁻¹ f = K⁻¹ f − K⁻¹ U s` with `s = (I + C Uᵀ K⁻¹ U)⁻¹ C Uᵀ K⁻¹ f`,
    /// and `Uᵀ K⁻¹ f = Wᵀ z`, `K⁻¹ U s = L⁻ᵀ (W s)`, so `z ← z − W s`.
    pub fn adjust_forward(&self, z: &mut [f64]) {
        let r = self.rank();
        if r == 0 {
            // blocks that differ by zero blocks only
            return;
        }
        let rows = &self.w.rows;
        let nr = rows.len();
        let column = |k: usize| &self.w.values[k * nr..(k + 1) * nr];
        let v = DMatrix::from_fn(r, 1, |k, _| {
            column(k).iter().zip(rows).map(|(a, &p)| a * z[p]).sum()
        });
        let s = self.weights(&v);
        for k in 0..r {
            for (a, &p) in column(k).iter().zip(rows) {
                z[p] -= s[k] * a;
            }
        }
    }
}
