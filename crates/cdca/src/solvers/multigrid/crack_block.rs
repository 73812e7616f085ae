//! The crack block of the fine level: every DOF of every enriched node,
//! solved together exactly.
//!
//! The coarse grids carry standard DOFs only, so the discontinuous part of
//! the error (a crack opening that varies smoothly along the crack) is seen
//! by neither the coarse correction nor, efficiently, by the point-wise
//! sweeps. The crack block `S` closes that gap: `x_S += K_SS⁻¹ r_S`, then
//! `r −= K_{·S} Δx_S` over the elements touching `S`. `K_SS` is small (the
//! enriched nodes only) and is factorised once (sparse Cholesky). Contact
//! blocks live on enriched elements, so a stiff penalty is handled here
//! exactly too.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::solvers::element_op::ElementOperator;

/// The factorised crack block.
pub struct CrackBlock {
    /// Global DOF of each block DOF.
    dofs: Vec<u32>,
    /// Elements with at least one block DOF.
    elems: Vec<u32>,
    llt: Llt<usize, f64>,
    rhs: Mat<f64>,
    /// Block correction scattered to the global numbering (zero elsewhere).
    t: Vec<f64>,
}

impl CrackBlock {
    /// `None` when the discretisation has no enriched node.
    pub fn new(x: &Xfem, op: &ElementOperator) -> Result<Option<Self>, SolveError> {
        let mut index = vec![u32::MAX; op.n];
        let mut dofs = Vec::new();
        for n in 0..x.mesh.node_count() {
            if x.dofs.is_enriched(n) {
                for d in x.dofs.node_free(n) {
                    index[d as usize] = dofs.len() as u32;
                    dofs.push(d);
                }
            }
        }
        if dofs.is_empty() {
            return Ok(None);
        }
        let mut elems = Vec::new();
        let mut trip = Vec::new();
        for e in 0..op.element_count() {
            let ed = op.element_dofs(e);
            if !ed
                .iter()
                .any(|&d| d != FIXED && index[d as usize] != u32::MAX)
            {
                continue;
            }
            elems.push(e as u32);
            let k = op.element_matrix(e);
            let nd = ed.len();
            for (i, &di) in ed.iter().enumerate() {
                for (j, &dj) in ed.iter().enumerate() {
                    if di == FIXED || dj == FIXED {
                        continue;
                    }
                    let (a, b) = (index[di as usize], index[dj as usize]);
                    if a != u32::MAX && b != u32::MAX && a >= b {
                        trip.push(Triplet::new(a as usize, b as usize, k[i * nd + j]));
                    }
                }
            }
        }
        let m = dofs.len();
        let fail = |detail: String| SolveError::NotPositiveDefinite { dofs: m, detail };
        let kss = SparseColMat::try_new_from_triplets(m, m, &trip)
            .map_err(|e| fail(format!("crack block: {e:?}")))?;
        let llt = kss
            .sp_cholesky(Side::Lower)
            .map_err(|e| fail(format!("crack block Cholesky: {e:?}")))?;
        Ok(Some(Self {
            dofs,
            elems,
            llt,
            rhs: Mat::zeros(m, 1),
            t: vec![0.0; op.n],
        }))
    }

    /// Number of DOFs in the block.
    pub fn len(&self) -> usize {
        self.dofs.len()
    }

    /// `x_S += K_SS⁻¹ r_S`, `r −= K Δx` (running residual kept exact).
    pub fn correct(
        &mut self,
        op: &ElementOperator,
        x: &mut [f64],
        r: &mut [f64],
    ) -> Result<(), SolveError> {
        for (i, &d) in self.dofs.iter().enumerate() {
            self.rhs[(i, 0)] = r[d as usize];
        }
        self.llt.solve_in_place(self.rhs.as_mut());
        for (i, &d) in self.dofs.iter().enumerate() {
            let v = self.rhs[(i, 0)];
            if !v.is_finite() {
                return Err(SolveError::NonFinite {
                    place: format!("crack block solve, DOF {d}"),
                });
            }
            self.t[d as usize] = v;
            x[d as usize] += v;
        }
        let t = &self.t;
        for &e in &self.elems {
            let ed = op.element_dofs(e as usize);
            let k = op.element_matrix(e as usize);
            let nd = ed.len();
            for (i, &di) in ed.iter().enumerate() {
                if di == FIXED {
                    continue;
                }
                let row = &k[i * nd..(i + 1) * nd];
                let s: f64 = row
                    .iter()
                    .zip(ed)
                    .map(|(kv, &dj)| {
                        if dj == FIXED {
                            0.0
                        } else {
                            kv * t[dj as usize]
                        }
                    })
                    .sum();
                r[di as usize] -= s;
            }
        }
        for &d in &self.dofs {
            self.t[d as usize] = 0.0;
        }
        Ok(())
    }
}
