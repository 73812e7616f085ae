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
//! Setting it up costs `r` solves with the factor (one block solve); each
//! solve after that one solve with the factor and `O(n r)`. The caller
//! checks the true residual with `K'` and refines, so the dropped
//! eigenpairs (round-off of the difference) do not reach the solution.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;

/// Eigenvalues of a block difference below this fraction of its largest
/// are round-off (a difference of whole penalty terms has `2m` nonzero
/// eigenvalues and the rest at ~1e-16 of them).
pub const DROP: f64 = 1e-12;

/// The largest rank of a correction. Setting one up costs about as much
/// as a numeric factorisation at rank ≈ 30 on 60 × 60 elements and ≈ 40
/// on 100 × 100 (the crossover grows with the mesh: a factorisation costs
/// `O(n^1.5)`, a solve `O(n log n)`); measured in `docs/benchmarks.md`,
/// "Contact changes as low-rank corrections".
pub const MAX_RANK: usize = 24;

/// The difference between two sets of contact blocks on one
/// discretisation as rank-one terms `λ v vᵀ`, each `v` as (reordered
/// position, value) pairs.
pub struct Terms {
    /// `λ` per term.
    lambda: Vec<f64>,
    /// `v` per term.
    vectors: Vec<Vec<(usize, f64)>>,
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
fn scatter(dofs: &[u32], v: &DVector<f64>, inv: &[usize]) -> Vec<(usize, f64)> {
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
    /// `Z = K⁻¹ U`, reordered, column-major `n × r`.
    z: Vec<f64>,
    /// LU of `I + C Uᵀ Z`.
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl Correction {
    /// Sets up the correction `terms` of an `n × n` matrix whose values
    /// are `a`, giving the contact blocks `blocks`: `add` adds a changed
    /// block (slot, `new − old`) into a copy of `a`; `solve_block` solves
    /// with the factorised matrix in place (reordered, column-major
    /// `n × r`). `None` when `I + C Uᵀ Z` is singular (so is the corrected
    /// matrix).
    pub fn new(
        n: usize,
        terms: Terms,
        blocks: &[ElementBlock],
        a: &[f64],
        add: impl Fn(usize, &DMatrix<f64>, &mut [f64]),
        solve_block: impl FnOnce(&mut [f64], usize),
    ) -> Option<Self> {
        let r = terms.rank();
        let mut z = vec![0.0; n * r];
        for (k, v) in terms.vectors.iter().enumerate() {
            for &(p, a) in v {
                z[k * n + p] = a;
            }
        }
        solve_block(&mut z, r);
        let mut m = DMatrix::identity(r, r);
        for (i, v) in terms.vectors.iter().enumerate() {
            for k in 0..r {
                let uz: f64 = v.iter().map(|&(p, a)| a * z[k * n + p]).sum();
                m[(i, k)] += terms.lambda[i] * uz;
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
            z,
            lu,
        })
    }

    /// The rank of the correction.
    pub fn rank(&self) -> usize {
        self.terms.rank()
    }

    /// Turns `y = K⁻¹ f` (reordered) into `K'⁻¹ f`:
    /// `y ← y − Z (I + C Uᵀ Z)⁻¹ C Uᵀ y`.
    pub fn apply(&self, y: &mut [f64]) {
        if self.rank() == 0 {
            // blocks that differ by zero blocks only
            return;
        }
        let n = y.len();
        let t = DVector::from_iterator(
            self.rank(),
            self.terms
                .vectors
                .iter()
                .zip(&self.terms.lambda)
                .map(|(v, l)| l * v.iter().map(|&(p, a)| a * y[p]).sum::<f64>()),
        );
        let s = self.lu.solve(&t).expect("checked invertible when set up");
        for (k, &sk) in s.iter().enumerate() {
            for (yi, zi) in y.iter_mut().zip(&self.z[k * n..(k + 1) * n]) {
                *yi -= sk * zi;
            }
        }
    }
}
