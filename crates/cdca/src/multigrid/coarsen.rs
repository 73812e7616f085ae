//! One coarsening step: the coarse grid, the bilinear prolongation and the
//! Galerkin coarse operator built element by element.

use crate::dofs::FIXED;
use crate::element_op::ElementOperator;
use crate::mesh::Mesh;
use crate::xfem::Xfem;

/// Grid offsets of the corners of an element, in local corner order.
const CORNER: [(usize, usize); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

/// Geometry and standard DOFs of one level.
#[derive(Clone, Debug)]
pub struct Grid {
    /// Topology (node and element numbering); sizes are in `xs`, `ys`.
    pub topo: Mesh,
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    /// Standard free DOFs `(x, y)` of each node, [`FIXED`] if constrained.
    pub std: Vec<[u32; 2]>,
}

impl Grid {
    /// The fine grid of a discretisation.
    pub fn fine(x: &Xfem) -> Self {
        let m = &x.mesh;
        Self {
            topo: super::topology(m.nx, m.ny),
            xs: (0..=m.nx).map(|i| i as f64 * m.hx).collect(),
            ys: (0..=m.ny).map(|j| j as f64 * m.hy).collect(),
            std: (0..m.node_count())
                .map(|n| [x.dofs.std_free(n, 0), x.dofs.std_free(n, 1)])
                .collect(),
        }
    }

    /// Free DOFs of each node (coarse levels carry standard DOFs only).
    pub fn node_dofs(&self) -> Vec<Vec<u32>> {
        self.std
            .iter()
            .map(|s| s.iter().copied().filter(|&d| d != FIXED).collect())
            .collect()
    }
}

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
    let nc = n.div_ceil(2);
    (0..=nc).map(|i| (2 * i).min(n)).collect()
}

/// Coarse interval of fine node `i` and its local coordinate `t ∈ [0, 1]`.
fn locate(i: usize, fine: &[f64], coarse: &[f64]) -> (usize, f64) {
    let k = (i / 2).min(coarse.len() - 2);
    (k, (fine[i] - coarse[k]) / (coarse[k + 1] - coarse[k]))
}

/// Linear weight of coarse end `side` (0 left, 1 right) at local `t`.
fn hat(side: usize, t: f64) -> f64 {
    if side == 0 { 1.0 - t } else { t }
}

/// Coarsens `g` (with operator `op`): the coarse grid, the prolongation
/// into `g` and the Galerkin operator `Pᵀ K P`.
pub fn coarsen(g: &Grid, op: &ElementOperator) -> (Grid, Prolongation, ElementOperator) {
    let (nx, ny) = (g.topo.nx, g.topo.ny);
    let (px, py) = (positions(nx), positions(ny));
    let (ncx, ncy) = (px.len() - 1, py.len() - 1);
    let xs: Vec<f64> = px.iter().map(|&i| g.xs[i]).collect();
    let ys: Vec<f64> = py.iter().map(|&j| g.ys[j]).collect();
    let topo = super::topology(ncx, ncy);
    let mut next = 0u32;
    let mut std = Vec::with_capacity(topo.node_count());
    for &j in &py {
        for &i in &px {
            let s = g.std[g.topo.node_id(i, j)];
            std.push(s.map(|d| {
                if d == FIXED {
                    FIXED
                } else {
                    next += 1;
                    next - 1
                }
            }));
        }
    }
    let coarse = Grid { topo, xs, ys, std };
    // prolongation rows, by fine DOF
    let mut rows: Vec<Vec<(u32, f64)>> = vec![Vec::new(); op.n];
    for j in 0..=ny {
        let (kj, ty) = locate(j, &g.ys, &coarse.ys);
        for i in 0..=nx {
            let (ki, tx) = locate(i, &g.xs, &coarse.xs);
            let fine = g.std[g.topo.node_id(i, j)];
            for &(a, b) in &CORNER {
                let w = hat(a, tx) * hat(b, ty);
                let cs = coarse.std[coarse.topo.node_id(ki + a, kj + b)];
                for c in 0..2 {
                    if w != 0.0 && fine[c] != FIXED && cs[c] != FIXED {
                        rows[fine[c] as usize].push((cs[c], w));
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
        for (c, w) in row {
            p.col.push(c);
            p.val.push(w);
        }
        p.start.push(p.col.len());
    }
    let opc = galerkin(g, &coarse, &px, &py, op, next as usize);
    (coarse, p, opc)
}

/// `K_E = Σ_{e⊂E} P_eᵀ K_e P_e` for every coarse element `E`.
fn galerkin(
    g: &Grid,
    c: &Grid,
    px: &[usize],
    py: &[usize],
    op: &ElementOperator,
    n: usize,
) -> ElementOperator {
    let mut opc = ElementOperator::new(n);
    // the shared matrix: four ordinary children of standard size
    let mut shared = [0.0; 64];
    for (a, b) in CORNER {
        let tx = [0, 1, 1, 0].map(|o| (a + o) as f64 / 2.0);
        let ty = [0, 0, 1, 1].map(|o| (b + o) as f64 / 2.0);
        add_child(&mut shared, op.matrix(0), 8, [false; 8], tx, ty);
    }
    opc.push_matrix(&shared);
    let (hx, hy) = (g.xs[1] - g.xs[0], g.ys[1] - g.ys[0]);
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b;
    for cj in 0..c.topo.ny {
        for ci in 0..c.topo.nx {
            let ce = cj * c.topo.nx + ci;
            let dofs: [u32; 8] =
                std::array::from_fn(|k| c.std[c.topo.element_nodes(ce)[k / 2]][k % 2]);
            let (i0, i1, j0, j1) = (px[ci], px[ci + 1], py[cj], py[cj + 1]);
            let mut standard = i1 - i0 == 2 && j1 - j0 == 2;
            let mut k = [0.0; 64];
            for j in j0..j1 {
                for i in i0..i1 {
                    let e = j * g.topo.nx + i;
                    let ed = op.element_dofs(e);
                    let fixed: [bool; 8] = std::array::from_fn(|a| ed[a] == FIXED);
                    standard &= op.element_matrix_id(e) == 0
                        && !fixed.iter().any(|&f| f)
                        && same(g.xs[i + 1] - g.xs[i], hx)
                        && same(g.ys[j + 1] - g.ys[j], hy);
                    let t = |f: &[f64], lo: f64, hi: f64, v: usize| (f[v] - lo) / (hi - lo);
                    let tx = CORNER.map(|(a, _)| t(&g.xs, c.xs[ci], c.xs[ci + 1], i + a));
                    let ty = CORNER.map(|(_, b)| t(&g.ys, c.ys[cj], c.ys[cj + 1], j + b));
                    add_child(&mut k, op.element_matrix(e), ed.len(), fixed, tx, ty);
                }
            }
            let id = if standard { 0 } else { opc.push_matrix(&k) };
            opc.push_element(&dofs, id);
        }
    }
    opc
}

/// Adds `P_eᵀ K_e P_e` of one child to the coarse element matrix `kc`.
/// `tx[q]`, `ty[q]`: local coordinates of the child's corner `q` in the
/// coarse element; `k` is the child's `nd × nd` matrix, of which the
/// standard block (first 8 DOFs) is used.
fn add_child(
    kc: &mut [f64; 64],
    k: &[f64],
    nd: usize,
    fixed: [bool; 8],
    tx: [f64; 4],
    ty: [f64; 4],
) {
    let mut pe = [[0.0; 8]; 8];
    for q in 0..4 {
        for (cq, &(a, b)) in CORNER.iter().enumerate() {
            let w = hat(a, tx[q]) * hat(b, ty[q]);
            for comp in 0..2 {
                if !fixed[2 * q + comp] {
                    pe[2 * q + comp][2 * cq + comp] = w;
                }
            }
        }
    }
    let mut kp = [[0.0; 8]; 8];
    for (a, row) in kp.iter_mut().enumerate() {
        for (b, v) in row.iter_mut().enumerate() {
            *v = (0..8).map(|c| k[a * nd + c] * pe[c][b]).sum();
        }
    }
    for b1 in 0..8 {
        for b2 in 0..8 {
            kc[b1 * 8 + b2] += (0..8).map(|a| pe[a][b1] * kp[a][b2]).sum::<f64>();
        }
    }
}
