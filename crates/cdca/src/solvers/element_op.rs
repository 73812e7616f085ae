//! A stiffness operator stored element by element,
//! `K = Σ_e A_eᵀ K_e A_e`, where `A_e` gathers element `e`'s DOFs from the
//! global vector. No global matrix is formed: products, cell blocks and
//! coarse-grid operators are all built from the element matrices.
//!
//! Element matrices are shared: all ordinary elements of the fine mesh point
//! at one matrix (the Q4 stiffness `k0`), enriched elements have their own
//! (bulk stiffness plus any contact block). Local DOF order is always the
//! four corners' standard DOFs `x0 y0 x1 y1 x2 y2 x3 y3` first, then the
//! enriched DOFs; a constrained DOF is marked [`FIXED`].

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{NOT_INTEGRATED, REGULAR, Xfem};

/// Element-by-element operator over `n` DOFs.
#[derive(Clone, Debug, Default)]
pub struct ElementOperator {
    /// Number of (free) DOFs.
    pub n: usize,
    /// Element `e` owns `dofs[start[e]..start[e + 1]]`.
    start: Vec<usize>,
    dofs: Vec<u32>,
    /// Matrix of each element (index into `mat_start`).
    mat: Vec<u32>,
    /// Row-major dense matrices, concatenated.
    mats: Vec<f64>,
    mat_start: Vec<usize>,
}

impl ElementOperator {
    /// An empty operator over `n` DOFs; add matrices and elements.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            start: vec![0],
            mat_start: vec![0],
            ..Self::default()
        }
    }

    /// The fine operator of a discretisation: `K_bulk + Σ blocks`.
    /// Matrix 0 is the shared ordinary-element stiffness.
    pub fn from_xfem(x: &Xfem, blocks: &[ElementBlock]) -> Self {
        assert!(x.is_integrated(), "{NOT_INTEGRATED}");
        let mut op = Self::new(x.n_free());
        op.push_matrix(x.k0.as_slice());
        // enriched element `s` gets matrix `1 + s`: its stiffness plus blocks
        for el in &x.enriched {
            op.push_matrix(el.k.as_slice());
        }
        for b in blocks {
            let nd = x.enriched[b.slot].dofs.len();
            assert_eq!(b.k.nrows(), nd, "contact block does not match its element");
            let m = op.matrix_mut(1 + b.slot);
            for (a, v) in m.iter_mut().zip(b.k.as_slice()) {
                *a += v;
            }
        }
        for e in 0..x.mesh.element_count() {
            let slot = x.slot[e];
            if slot == REGULAR {
                op.push_element(&x.regular_dofs(e), 0);
            } else {
                op.push_element(&x.enriched[slot as usize].dofs, 1 + slot as usize);
            }
        }
        op
    }

    /// Adds a dense square matrix (any storage order: it must be symmetric)
    /// and returns its index.
    pub fn push_matrix(&mut self, m: &[f64]) -> usize {
        self.mats.extend_from_slice(m);
        self.mat_start.push(self.mats.len());
        self.mat_start.len() - 2
    }

    /// Adds an element with its DOFs (free indices or [`FIXED`]) and matrix.
    pub fn push_element(&mut self, dofs: &[u32], matrix: usize) {
        let size = self.mat_start[matrix + 1] - self.mat_start[matrix];
        assert_eq!(
            size,
            dofs.len() * dofs.len(),
            "element matrix size mismatch"
        );
        self.dofs.extend_from_slice(dofs);
        self.start.push(self.dofs.len());
        self.mat.push(matrix as u32);
    }

    pub fn element_count(&self) -> usize {
        self.mat.len()
    }

    pub fn matrix_count(&self) -> usize {
        self.mat_start.len() - 1
    }

    /// DOFs of element `e`.
    #[inline]
    pub fn element_dofs(&self, e: usize) -> &[u32] {
        &self.dofs[self.start[e]..self.start[e + 1]]
    }

    /// Matrix index of element `e`.
    #[inline]
    pub fn element_matrix_id(&self, e: usize) -> usize {
        self.mat[e] as usize
    }

    /// Matrix `i`, row-major.
    #[inline]
    pub fn matrix(&self, i: usize) -> &[f64] {
        &self.mats[self.mat_start[i]..self.mat_start[i + 1]]
    }

    fn matrix_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.mats[self.mat_start[i]..self.mat_start[i + 1]]
    }

    /// Matrix of element `e`, row-major (symmetric).
    #[inline]
    pub fn element_matrix(&self, e: usize) -> &[f64] {
        self.matrix(self.mat[e] as usize)
    }

    /// Matrix of element `e`, row-major, for changing it in place. It is
    /// shared by every element built with the same matrix index (all
    /// ordinary elements of [`from_xfem`](Self::from_xfem) share one);
    /// each enriched element there has its own.
    pub fn element_matrix_mut(&mut self, e: usize) -> &mut [f64] {
        let i = self.mat[e] as usize;
        self.matrix_mut(i)
    }

    /// `y = K u`.
    pub fn apply(&self, u: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        self.apply_add(u, y);
    }

    /// `y += K u`, element by element.
    pub fn apply_add(&self, u: &[f64], y: &mut [f64]) {
        let get = |d: u32| if d == FIXED { 0.0 } else { u[d as usize] };
        for e in 0..self.element_count() {
            let d = self.element_dofs(e);
            let m = self.element_matrix(e);
            if d.len() == 8 {
                let ue: [f64; 8] = std::array::from_fn(|j| get(d[j]));
                for (i, row) in m.chunks_exact(8).enumerate() {
                    if d[i] != FIXED {
                        let s: f64 = row.iter().zip(&ue).map(|(a, b)| a * b).sum();
                        y[d[i] as usize] += s;
                    }
                }
            } else {
                let nd = d.len();
                for (i, row) in m.chunks_exact(nd).enumerate() {
                    if d[i] != FIXED {
                        let s: f64 = row.iter().zip(d).map(|(a, &dj)| a * get(dj)).sum();
                        y[d[i] as usize] += s;
                    }
                }
            }
        }
    }

    /// `r = f − K u`.
    pub fn residual(&self, f: &[f64], u: &[f64], r: &mut [f64]) {
        self.apply(u, r);
        for (ri, fi) in r.iter_mut().zip(f) {
            *ri = fi - *ri;
        }
    }

    /// Energy `vᵀ K v` (scratch `kv` of length `n`).
    pub fn energy(&self, v: &[f64], kv: &mut [f64]) -> f64 {
        self.apply(v, kv);
        dot(v, kv)
    }
}

/// Euclidean inner product.
#[inline]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Euclidean norm.
#[inline]
pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two 1-DOF "springs" sharing a DOF: K = [[2, -1], [-1, 1]] after the
    /// first DOF of the first spring is fixed.
    #[test]
    fn apply_sums_element_contributions_and_skips_fixed_dofs() {
        let mut op = ElementOperator::new(2);
        let spring = op.push_matrix(&[1.0, -1.0, -1.0, 1.0]);
        op.push_element(&[FIXED, 0], spring);
        op.push_element(&[0, 1], spring);
        let mut y = [0.0; 2];
        op.apply(&[1.0, 3.0], &mut y);
        assert_eq!(y, [2.0 * 1.0 - 3.0, -1.0 + 3.0]);
        let mut kv = [0.0; 2];
        assert_eq!(op.energy(&[1.0, 3.0], &mut kv), -1.0 + 3.0 * 2.0);
    }
}
