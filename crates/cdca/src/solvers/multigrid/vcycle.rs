//! Coarse-grid correction for the automaton: geometric multigrid on the
//! structured mesh, used as a V-cycle preconditioner inside CG.
//!
//! Levels: the fine grid (all DOFs, enriched ones included) and grids
//! coarsened by 2 per level in each direction (an odd count keeps its last
//! node, so the last coarse element is one fine element wide), down to at
//! most [`MultigridParams::coarsest_cells`] elements per side.
//!
//! - Prolongation `P`: bilinear interpolation of the coarse DOFs, with
//!   the cracks' Heaviside enrichment kept on the coarse grids (see
//!   `coarsen`); tip DOFs get nothing. A coarse standard DOF is
//!   constrained when the fine DOF at the same node is.
//! - Coarse operator: Galerkin `K_c = Pᵀ K P`, element by element: a fine
//!   element lies inside one coarse element `E`, so
//!   `K_E = Σ_{e⊂E} P_eᵀ K_e P_e`. No fine global matrix is formed; coarse
//!   elements made of four ordinary elements share one matrix, as on the
//!   fine grid.
//! - Crack block: all DOFs of the enriched fine nodes solved together
//!   exactly, after pre-smoothing and before post-smoothing.
//! - Smoother: the automaton's cell sweeps, forward before and backward
//!   after the correction, so the V-cycle is symmetric.
//! - Coarsest grid: sparse Cholesky (faer) of the assembled coarse matrix.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::scene::Ordering;
use crate::solvers::cells::{Cells, node_dofs};
use crate::solvers::element_op::ElementOperator;
use crate::solvers::pcg::Preconditioner;

use super::coarsen::{Prolongation, coarsen};
use super::crack_block::CrackBlock;
use super::grid::Grid;

/// Settings of the multigrid preconditioner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MultigridParams {
    /// Coarsening stops when a grid has at most this many elements per side.
    pub coarsest_cells: usize,
    /// Cell sweeps before (forward) and after (backward) the correction.
    pub smoothing: usize,
    /// Relaxation factor of the smoothing sweeps.
    pub omega: f64,
    /// Solve the block of all enriched nodes' DOFs exactly on the fine
    /// level, after pre-smoothing and before post-smoothing.
    pub crack_block: bool,
}

impl Default for MultigridParams {
    fn default() -> Self {
        Self {
            coarsest_cells: 8,
            smoothing: 1,
            omega: 1.0,
            crack_block: true,
        }
    }
}

/// One level that is smoothed, with its work vectors.
#[derive(Clone, Debug)]
struct Level {
    cells: Cells,
    /// From the next coarser level into this one.
    p: Prolongation,
    x: Vec<f64>,
    r: Vec<f64>,
    t: Vec<f64>,
    kt: Vec<f64>,
}

/// The V-cycle: `z = V(r)`, symmetric positive definite.
pub struct Vcycle {
    params: MultigridParams,
    levels: Vec<Level>,
    /// Operators of levels 1.. (level 0's is the caller's).
    ops: Vec<ElementOperator>,
    crack: Option<CrackBlock>,
    llt: Llt<usize, f64>,
    rhs: Mat<f64>,
    xc: Vec<f64>,
    bc: Vec<f64>,
}

impl Vcycle {
    /// Builds the hierarchy under the fine operator `op` of `x`.
    pub fn new(
        x: &Xfem,
        op: &ElementOperator,
        params: MultigridParams,
    ) -> Result<Self, SolveError> {
        let mut grids = vec![Grid::fine(x)];
        let mut ops: Vec<ElementOperator> = Vec::new();
        let mut ps = Vec::new();
        loop {
            let g = &grids[grids.len() - 1];
            let (nx, ny) = (g.topo.nx, g.topo.ny);
            if nx.max(ny) <= params.coarsest_cells || nx.min(ny) < 2 {
                break;
            }
            let (gc, p, opc) = coarsen(x, g, ops.last().unwrap_or(op));
            grids.push(gc);
            ps.push(p);
            ops.push(opc);
        }
        let mut levels = Vec::with_capacity(ps.len());
        for (l, p) in ps.into_iter().enumerate() {
            let op_l = if l == 0 { op } else { &ops[l - 1] };
            let nd = if l == 0 {
                node_dofs(x)
            } else {
                grids[l].node_dofs()
            };
            let cells = Cells::new(op_l, &grids[l].topo, &nd, Ordering::Lexicographic)?;
            let n = op_l.n;
            levels.push(Level {
                cells,
                p,
                x: vec![0.0; n],
                r: vec![0.0; n],
                t: vec![0.0; n],
                kt: vec![0.0; n],
            });
        }
        let crack = if params.crack_block {
            CrackBlock::new(x, op)?
        } else {
            None
        };
        let coarsest = ops.last().unwrap_or(op);
        let nc = coarsest.n;
        let llt = factor(coarsest)?;
        Ok(Self {
            params,
            levels,
            ops,
            crack,
            llt,
            rhs: Mat::zeros(nc, 1),
            xc: vec![0.0; nc],
            bc: vec![0.0; nc],
        })
    }

    /// Number of grid levels (the coarsest included).
    pub fn depth(&self) -> usize {
        self.levels.len() + 1
    }

    /// DOFs of the fine crack block (0 without enrichment).
    pub fn crack_block_dofs(&self) -> usize {
        self.crack.as_ref().map_or(0, CrackBlock::len)
    }

    /// DOFs of the coarsest grid.
    pub fn coarsest_dofs(&self) -> usize {
        self.xc.len()
    }

    fn coarse_solve(&mut self) -> Result<(), SolveError> {
        for (i, b) in self.bc.iter().enumerate() {
            self.rhs[(i, 0)] = *b;
        }
        self.llt.solve_in_place(self.rhs.as_mut());
        for (i, x) in self.xc.iter_mut().enumerate() {
            *x = self.rhs[(i, 0)];
            if !x.is_finite() {
                return Err(SolveError::NonFinite {
                    place: format!("multigrid coarsest solve, DOF {i}"),
                });
            }
        }
        Ok(())
    }
}

impl Preconditioner for Vcycle {
    fn precondition(
        &mut self,
        op: &ElementOperator,
        r: &[f64],
        z: &mut [f64],
    ) -> Result<(), SolveError> {
        let depth = self.levels.len();
        if depth == 0 {
            self.bc.copy_from_slice(r);
            self.coarse_solve()?;
            z.copy_from_slice(&self.xc);
            return Ok(());
        }
        let (s, omega) = (self.params.smoothing, self.params.omega);
        self.levels[0].r.copy_from_slice(r);
        for l in 0..depth {
            let op_l = if l == 0 { op } else { &self.ops[l - 1] };
            let (head, tail) = self.levels.split_at_mut(l + 1);
            let lev = &mut head[l];
            lev.x.fill(0.0);
            for _ in 0..s {
                lev.cells
                    .sweep(op_l, omega, false, &mut lev.x, &mut lev.r)?;
            }
            if let (0, Some(c)) = (l, &mut self.crack) {
                c.correct(op_l, &mut lev.x, &mut lev.r)?;
            }
            let next = if let Some(n) = tail.first_mut() {
                &mut n.r
            } else {
                &mut self.bc
            };
            lev.p.restrict(&lev.r, next);
        }
        self.coarse_solve()?;
        for l in (0..depth).rev() {
            let op_l = if l == 0 { op } else { &self.ops[l - 1] };
            let (head, tail) = self.levels.split_at_mut(l + 1);
            let lev = &mut head[l];
            let xc = if let Some(n) = tail.first() {
                &n.x
            } else {
                &self.xc
            };
            lev.p.prolong(xc, &mut lev.t);
            op_l.apply(&lev.t, &mut lev.kt);
            for ((x, r), (t, kt)) in lev
                .x
                .iter_mut()
                .zip(lev.r.iter_mut())
                .zip(lev.t.iter().zip(&lev.kt))
            {
                *x += t;
                *r -= kt;
            }
            if let (0, Some(c)) = (l, &mut self.crack) {
                c.correct(op_l, &mut lev.x, &mut lev.r)?;
            }
            for _ in 0..s {
                lev.cells.sweep(op_l, omega, true, &mut lev.x, &mut lev.r)?;
            }
        }
        z.copy_from_slice(&self.levels[0].x);
        Ok(())
    }
}

/// Sparse Cholesky of an element operator (assembled: used for the
/// coarsest grid only).
fn factor(op: &ElementOperator) -> Result<Llt<usize, f64>, SolveError> {
    let mut trip = Vec::new();
    for e in 0..op.element_count() {
        let d = op.element_dofs(e);
        let k = op.element_matrix(e);
        let nd = d.len();
        for (i, &di) in d.iter().enumerate() {
            for (j, &dj) in d.iter().enumerate() {
                if di != FIXED && dj != FIXED && di >= dj {
                    trip.push(Triplet::new(di as usize, dj as usize, k[i * nd + j]));
                }
            }
        }
    }
    let n = op.n;
    let fail = |detail: String| SolveError::NotPositiveDefinite { dofs: n, detail };
    let k = SparseColMat::try_new_from_triplets(n, n, &trip)
        .map_err(|e| fail(format!("coarse grid: {e:?}")))?;
    k.sp_cholesky(Side::Lower)
        .map_err(|e| fail(format!("coarse grid Cholesky: {e:?}")))
}
