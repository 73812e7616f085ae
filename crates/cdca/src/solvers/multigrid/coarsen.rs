//! One coarsening step: the coarse grid, the prolongation and the Galerkin
//! coarse operator built element by element.
//!
//! Coarse grids keep the cracks' Heaviside enrichment: a coarse node `I`
//! carries a Heaviside DOF pair `a_I` for crack `c` when a fine node of its
//! stencil does. With `w_IJ` the bilinear weights and `H` the side (±1) of
//! a node, the coarse field `Σ_I N_I [u_I + (H − H_I) a_I]` is prolongated
//! exactly where all the fine nodes concerned are Heaviside-enriched:
//!
//! ```text
//! u_J = Σ_I w_IJ [u_I + (H_J − H_I) a_I],     a_J = Σ_I w_IJ a_I.
//! ```
//!
//! Tip DOFs get nothing (they are smoothed, and solved in the crack block).

use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::solvers::element_op::ElementOperator;

use super::galerkin::galerkin;
use super::grid::{CORNER, Grid, Kind, LocalDof, hat, topology};

/// Sparse prolongation from a coarse level: row `i` of `P` lists the
/// coarse DOFs and weights interpolated into fine DOF `i`.
#[derive(Clone, Debug)]
pub struct Prolongation {
    start: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl Prolongation {
    /// `t = P x_c`.
    pub fn prolong(&self, xc: &[f64], t: &mut [f64]) {
        for (i, ti) in t.iter_mut().enumerate() {
            let (a, b) = (self.start[i], self.start[i + 1]);
            *ti = self.col[a..b]
                .iter()
                .zip(&self.val[a..b])
                .map(|(&c, w)| w * xc[c as usize])
                .sum();
        }
    }

    /// `b_c = Pᵀ r`.
    pub fn restrict(&self, r: &[f64], bc: &mut [f64]) {
        bc.fill(0.0);
        for (i, ri) in r.iter().enumerate() {
            let (a, b) = (self.start[i], self.start[i + 1]);
            for (&c, w) in self.col[a..b].iter().zip(&self.val[a..b]) {
                bc[c as usize] += w * ri;
            }
        }
    }
}

/// Fine node indices kept on the coarse grid: every other one, plus the
/// last.
fn positions(n: usize) -> Vec<usize> {
    (0..=n.div_ceil(2)).map(|i| (2 * i).min(n)).collect()
}

/// Coarse interval of fine node `i` and its local coordinate `t ∈ [0, 1]`.
fn locate(i: usize, fine: &[f64], coarse: &[f64]) -> (usize, f64) {
    let k = (i / 2).min(coarse.len() - 2);
    (k, (fine[i] - coarse[k]) / (coarse[k + 1] - coarse[k]))
}

/// Coarse element containing fine node `(i, j)` and the node's bilinear
/// weights for that element's corners.
fn stencil(g: &Grid, c: &Grid, i: usize, j: usize) -> (usize, [f64; 4]) {
    let (ki, tx) = locate(i, &g.xs, &c.xs);
    let (kj, ty) = locate(j, &g.ys, &c.ys);
    (
        kj * c.topo.nx + ki,
        CORNER.map(|(a, b)| hat(a, tx) * hat(b, ty)),
    )
}

/// Coarsens `g` (with operator `op`): the coarse grid, the prolongation
/// into `g` and the Galerkin operator `Pᵀ K P`.
pub fn coarsen(x: &Xfem, g: &Grid, op: &ElementOperator) -> (Grid, Prolongation, ElementOperator) {
    let (px, py) = (positions(g.topo.nx), positions(g.topo.ny));
    let topo = topology(px.len() - 1, py.len() - 1);
    let mut c = Grid {
        xs: px.iter().map(|&i| g.xs[i]).collect(),
        ys: py.iter().map(|&j| g.ys[j]).collect(),
        std: Vec::with_capacity(topo.node_count()),
        heav: vec![Vec::new(); topo.node_count()],
        layout: Vec::new(),
        topo,
    };
    // which coarse nodes carry a Heaviside enrichment
    let mut cracks: Vec<Vec<usize>> = vec![Vec::new(); c.topo.node_count()];
    for n in 0..g.topo.node_count() {
        let (i, j) = g.topo.node_ij(n);
        let (ce, w) = stencil(g, &c, i, j);
        for (q, &nc) in c.topo.element_nodes(ce).iter().enumerate() {
            for &(crack, _) in &g.heav[n] {
                if w[q] != 0.0 && !cracks[nc].contains(&crack) {
                    cracks[nc].push(crack);
                }
            }
        }
    }
    let mut next = 0u32;
    let mut number = || {
        next += 1;
        next - 1
    };
    for (nc, list) in cracks.iter_mut().enumerate() {
        let (ic, jc) = c.topo.node_ij(nc);
        let s = g.std[g.topo.node_id(px[ic], py[jc])];
        c.std
            .push(s.map(|d| if d == FIXED { FIXED } else { number() }));
        list.sort_unstable();
        c.heav[nc] = list.iter().map(|&k| (k, [number(), number()])).collect();
    }
    c.layout = (0..c.topo.element_count())
        .map(|ce| {
            let nodes = c.topo.element_nodes(ce);
            let enriched = nodes.iter().any(|&n| !c.heav[n].is_empty());
            enriched.then(|| {
                let mut l: Vec<LocalDof> = (0..8).map(|k| (k / 2, k % 2, Kind::Std)).collect();
                for (q, &n) in nodes.iter().enumerate() {
                    l.extend(c.heav[n].iter().flat_map(|&(k, _)| {
                        [(q, 0, Kind::Heaviside(k)), (q, 1, Kind::Heaviside(k))]
                    }));
                }
                l
            })
        })
        .collect();
    let side = |grid: &Grid, n: usize, crack: usize| x.funcs.heaviside(crack, grid.pos(n));
    // prolongation rows, by fine DOF
    let mut rows: Vec<Vec<(u32, f64)>> = vec![Vec::new(); op.n];
    for n in 0..g.topo.node_count() {
        let (i, j) = g.topo.node_ij(n);
        let (ce, w) = stencil(g, &c, i, j);
        for (q, &nc) in c.topo.element_nodes(ce).iter().enumerate() {
            if w[q] == 0.0 {
                continue;
            }
            for comp in 0..2 {
                let fine = g.std[n][comp];
                if fine == FIXED {
                    continue;
                }
                if c.std[nc][comp] != FIXED {
                    rows[fine as usize].push((c.std[nc][comp], w[q]));
                }
                for &(crack, d) in &c.heav[nc] {
                    let jump = side(g, n, crack) - side(&c, nc, crack);
                    if jump != 0.0 {
                        rows[fine as usize].push((d[comp], w[q] * jump));
                    }
                }
            }
            for &(crack, fd) in &g.heav[n] {
                if let Some((_, d)) = c.heav[nc].iter().find(|(k, _)| *k == crack) {
                    for comp in 0..2 {
                        rows[fd[comp] as usize].push((d[comp], w[q]));
                    }
                }
            }
        }
    }
    let mut p = Prolongation {
        start: vec![0],
        col: Vec::new(),
        val: Vec::new(),
    };
    for row in rows {
        for (col, w) in row {
            p.col.push(col);
            p.val.push(w);
        }
        p.start.push(p.col.len());
    }
    let opc = galerkin(x, g, &c, &px, &py, op, next as usize);
    (c, p, opc)
}
