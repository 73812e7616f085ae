//! The Galerkin coarse operator `K_c = Pᵀ K P`, element by element: a fine
//! element lies inside one coarse element `E`, so
//! `K_E = Σ_{e⊂E} P_eᵀ K_e P_e`, with `P_e` the rows of `P` for the
//! child's DOFs restricted to `E`'s DOFs. Coarse elements made of four
//! ordinary children of standard size share one matrix.

use nalgebra::DMatrix;

use super::grid::{CORNER, Grid, Kind, LocalDof, hat};
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::solvers::element_op::ElementOperator;

/// The 8 standard DOFs of a Q4 element.
fn standard_layout() -> Vec<LocalDof> {
    (0..8).map(|k| (k / 2, k % 2, Kind::Std)).collect()
}

/// The coarse operator on grid `c` of the fine operator `op` on grid `g`.
pub fn galerkin(
    x: &Xfem,
    g: &Grid,
    c: &Grid,
    px: &[usize],
    py: &[usize],
    op: &ElementOperator,
    n: usize,
) -> ElementOperator {
    let std_layout = standard_layout();
    let mut opc = ElementOperator::new(n);
    let mut shared = DMatrix::zeros(8, 8);
    for (a, b) in CORNER {
        let child = Child {
            k: op.matrix(0),
            layout: &std_layout,
            fixed: &[false; 8],
            tx: [0, 1, 1, 0].map(|o| (a + o) as f64 / 2.0),
            ty: [0, 0, 1, 1].map(|o| (b + o) as f64 / 2.0),
        };
        child.add_to(&mut shared, &std_layout, &|_, _| 0.0, &|_, _| 0.0);
    }
    opc.push_matrix(shared.as_slice());
    let (hx, hy) = (g.xs[1] - g.xs[0], g.ys[1] - g.ys[0]);
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b;
    for ce in 0..c.topo.element_count() {
        let (ci, cj) = (ce % c.topo.nx, ce / c.topo.nx);
        let nodes = c.topo.element_nodes(ce);
        let layout = c.layout[ce].as_ref().unwrap_or(&std_layout);
        let dofs: Vec<u32> = layout
            .iter()
            .map(|&(q, comp, kind)| match kind {
                Kind::Heaviside(k) => c.heav[nodes[q]]
                    .iter()
                    .find(|(kk, _)| *kk == k)
                    .map_or(FIXED, |(_, d)| d[comp]),
                _ => c.std[nodes[q]][comp],
            })
            .collect();
        let (i0, i1, j0, j1) = (px[ci], px[ci + 1], py[cj], py[cj + 1]);
        let children = || (j0..j1).flat_map(move |j| (i0..i1).map(move |i| (i, j)));
        let standard = c.layout[ce].is_none()
            && i1 - i0 == 2
            && j1 - j0 == 2
            && children().all(|(i, j)| {
                let e = j * g.topo.nx + i;
                op.element_matrix_id(e) == 0
                    && !op.element_dofs(e).contains(&FIXED)
                    && same(g.xs[i + 1] - g.xs[i], hx)
                    && same(g.ys[j + 1] - g.ys[j], hy)
            });
        if standard {
            opc.push_element(&dofs, 0);
            continue;
        }
        let mut kc = DMatrix::zeros(dofs.len(), dofs.len());
        let coarse_side = |q: usize, k: usize| x.funcs.heaviside(k, c.pos(nodes[q]));
        for (i, j) in children() {
            let e = j * g.topo.nx + i;
            let fixed: Vec<bool> = op.element_dofs(e).iter().map(|&d| d == FIXED).collect();
            let local = |f: &[f64], lo: f64, hi: f64, v: usize| (f[v] - lo) / (hi - lo);
            let child = Child {
                k: op.element_matrix(e),
                layout: g.layout[e].as_ref().unwrap_or(&std_layout),
                fixed: &fixed,
                tx: CORNER.map(|(a, _)| local(&g.xs, c.xs[ci], c.xs[ci + 1], i + a)),
                ty: CORNER.map(|(_, b)| local(&g.ys, c.ys[cj], c.ys[cj + 1], j + b)),
            };
            let fine_side = |q: usize, k: usize| {
                let n = g.topo.node_id(i + CORNER[q].0, j + CORNER[q].1);
                x.funcs.heaviside(k, g.pos(n))
            };
            child.add_to(&mut kc, layout, &fine_side, &coarse_side);
        }
        regularise(&mut kc, layout);
        let id = opc.push_matrix(kc.as_slice());
        opc.push_element(&dofs, id);
    }
    opc
}

/// A fine element seen from its coarse element.
struct Child<'a> {
    /// `nd × nd` matrix.
    k: &'a [f64],
    layout: &'a [LocalDof],
    fixed: &'a [bool],
    /// Local coordinates of the child's corners in the coarse element.
    tx: [f64; 4],
    ty: [f64; 4],
}

impl Child<'_> {
    /// `kc += P_eᵀ K_e P_e`.
    fn add_to(
        &self,
        kc: &mut DMatrix<f64>,
        cols: &[LocalDof],
        fine_side: &dyn Fn(usize, usize) -> f64,
        coarse_side: &dyn Fn(usize, usize) -> f64,
    ) {
        let nd = self.layout.len();
        let mut pe = DMatrix::<f64>::zeros(nd, cols.len());
        for (r, &(q, comp, kind)) in self.layout.iter().enumerate() {
            if self.fixed[r] {
                continue;
            }
            for (col, &(cq, ccomp, ckind)) in cols.iter().enumerate() {
                let w = hat(CORNER[cq].0, self.tx[q]) * hat(CORNER[cq].1, self.ty[q]);
                if ccomp != comp || w == 0.0 {
                    continue;
                }
                pe[(r, col)] = match (kind, ckind) {
                    (Kind::Std, Kind::Std) => w,
                    (Kind::Std, Kind::Heaviside(k)) => w * (fine_side(q, k) - coarse_side(cq, k)),
                    (Kind::Heaviside(a), Kind::Heaviside(b)) if a == b => w,
                    _ => 0.0,
                };
            }
        }
        let k = DMatrix::from_row_slice(nd, nd, self.k);
        *kc += pe.transpose() * k * &pe;
    }
}

/// Relative stiffness added to coarse Heaviside diagonals.
const HEAVISIDE_REGULARISATION: f64 = 1e-8;

/// A coarse Heaviside function can vanish on its whole support (a coarse
/// node whose stencil lies on one side of the crack, or beyond a tip), so
/// `P` may have a small kernel and `Pᵀ K P` be only semidefinite. A
/// relative `1e-8` of the mean standard diagonal on the Heaviside
/// diagonals keeps every coarse block and the coarsest Cholesky SPD; the
/// kernel's directions are mapped to (nearly) zero by `P` anyway, and the
/// preconditioner stays symmetric positive definite.
fn regularise(kc: &mut DMatrix<f64>, layout: &[LocalDof]) {
    let std: Vec<f64> = (0..8).map(|k| kc[(k, k)]).filter(|&d| d > 0.0).collect();
    if std.is_empty() {
        return;
    }
    let mean = std.iter().sum::<f64>() / std.len() as f64;
    for (l, &(_, _, kind)) in layout.iter().enumerate() {
        if matches!(kind, Kind::Heaviside(_)) {
            kc[(l, l)] += HEAVISIDE_REGULARISATION * mean;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::coarsen::coarsen;
    use super::*;
    use crate::discretisation::model::Model;
    use crate::scene::Scene;

    fn plate(n: usize) -> Xfem {
        let json = format!(
            r#"{{"specimen":{{"width":2.0,"height":1.0}},"mesh":{{"nx":{n},"ny":{n}}},
            "material":{{"young":1e9,"poisson":0.3}}}}"#
        );
        let model = Model::new(Scene::from_json(&json).expect("scene"));
        model.discretise(model.initial_cracks())
    }

    /// For bilinear elements the Galerkin coarse matrix of four ordinary
    /// elements is the Q4 stiffness of the element twice as large
    /// (bilinear prolongation is exact for bilinear functions).
    #[test]
    fn shared_coarse_matrix_is_the_q4_stiffness_of_the_double_element() {
        let fine = plate(8);
        let op = ElementOperator::from_xfem(&fine, &[]);
        let (_, _, opc) = coarsen(&fine, &Grid::fine(&fine), &op);
        let coarse = plate(4);
        let k2h = coarse.k0.as_slice();
        let scale = k2h.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let diff = opc
            .matrix(0)
            .iter()
            .zip(k2h)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            diff <= 1e-12 * scale,
            "differs by {diff:e} (scale {scale:e})"
        );
    }
}
