//! The enriched elements (SPEC §4): each one's layout, its quadrature on
//! the sub-cells the cracks cut it into, the values and gradients of its
//! scalar shape functions, and its stiffness `K_e = Σ_q Bᵀ D B w t`.

use std::collections::BTreeMap;
use std::ops::Range;

use nalgebra::{DMatrix, SMatrix};

use crate::discretisation::dofs::DofMap;
use crate::discretisation::enrichment::{EnrValue, Enrichment, EnrichmentFunctions};
use crate::discretisation::material::Elastic;
use crate::discretisation::quadrature::{QPoint, box_rule};
use crate::discretisation::subdivision::{element_rule, split_by_lines};
use crate::discretisation::xfem::classify::{
    ElementSegments, ScalarFn, element_dofs, element_layout,
};
use crate::geometry::mesh::Mesh;
use crate::geometry::plane::P2;

/// Marks an element without its own data (an ordinary element).
pub const REGULAR: u32 = u32::MAX;

/// An element with at least one enriched node: its own layout, quadrature
/// and stiffness.
#[derive(Clone, Debug)]
pub struct EnrichedElement {
    pub elem: usize,
    /// Distinct enrichments of its nodes.
    pub enrs: Vec<Enrichment>,
    pub scalars: Vec<ScalarFn>,
    /// Free DOF index of each (scalar, component), [`FIXED`](crate::discretisation::dofs::FIXED) if constrained.
    pub dofs: Vec<u32>,
    pub qps: Vec<QPoint>,
    pub k: DMatrix<f64>,
    /// The crack-segment lines it was split along (for reuse checks).
    pub lines: Vec<(P2, P2)>,
}

/// The previous discretisation's enriched elements, offered for reuse
/// after a crack change.
pub(super) struct Previous<'a> {
    pub slot: &'a [u32],
    pub enriched: &'a [EnrichedElement],
    /// Old and new positions of the tips that changed.
    pub moved: &'a [P2],
    /// Elements farther than this from every moved tip may be reused (the
    /// largest enrichment radius plus two elements), m.
    pub far: f64,
    /// Per crack (new numbering): its tip kinds changed (a tip met another
    /// crack or the boundary), or it is new. Its Heaviside function then
    /// changes far from any moved tip (a junction function is cut by the
    /// main crack), so no element it enriches is reused.
    pub changed: &'a [bool],
}

/// The enriched elements of a discretisation.
pub(super) struct Elements {
    /// Per element: index into `enriched`, or [`REGULAR`].
    pub slot: Vec<u32>,
    pub enriched: Vec<EnrichedElement>,
    /// Slots whose stiffness is still to be integrated.
    pub unintegrated: Vec<u32>,
}

/// Every element with an enriched node: its layout and quadrature, and its
/// stiffness where `previous` has it (otherwise left to integrate).
pub(super) fn build_elements(
    m: &Mesh,
    funcs: &EnrichmentFunctions,
    dofs: &DofMap,
    segs: &ElementSegments,
    tips: &BTreeMap<usize, P2>,
    previous: Option<&Previous>,
) -> Elements {
    let mut out = Elements {
        slot: vec![REGULAR; m.element_count()],
        enriched: Vec::new(),
        unintegrated: Vec::new(),
    };
    let eps = 1e-12 * m.h();
    for e in 0..m.element_count() {
        let nodes = m.element_nodes(e);
        if !nodes.iter().any(|&n| dofs.is_enriched(n)) {
            continue;
        }
        let (enrs, scalars) = element_layout(dofs, &nodes);
        let el_dofs = element_dofs(dofs, &nodes, &scalars, &enrs);
        let (lo, hi) = m.element_box(e);
        let lines: Vec<(P2, P2)> = segs
            .get(&e)
            .map(|v| {
                v.iter()
                    .map(|&(c, s)| {
                        let p = &funcs.cracks[c].points;
                        (p[s], p[s + 1] - p[s])
                    })
                    .collect()
            })
            .unwrap_or_default();
        let pieces = split_by_lines(&m.element_polygon(e), &lines, eps, 1e-14 * m.hx * m.hy);
        let centre = 0.5 * (lo + hi);
        if let Some(old) = previous.and_then(|p| reusable(p, e, &enrs, &scalars, &lines, centre)) {
            out.slot[e] = out.enriched.len() as u32;
            out.enriched.push(EnrichedElement {
                elem: e,
                enrs,
                scalars,
                dofs: el_dofs,
                qps: old.qps.clone(),
                k: old.k.clone(),
                lines,
            });
            continue;
        }
        let near_tip = enrs
            .iter()
            .filter_map(|en| match *en {
                Enrichment::Tip { crack, tip } => Some(funcs.cracks[crack].tip_point(tip)),
                Enrichment::Heaviside { .. } => None,
            })
            .min_by(|a, b| (a - centre).norm().total_cmp(&(b - centre).norm()));
        let pieces = if lines.is_empty() && near_tip.is_some() {
            // an uncut tip-enriched element: two triangles, refined near the tip
            let p = m.element_polygon(e);
            vec![vec![p[0], p[1], p[2]], vec![p[0], p[2], p[3]]]
        } else {
            pieces
        };
        let qps = element_rule(
            lo,
            hi,
            &pieces,
            tips.get(&e).copied(),
            near_tip,
            !lines.is_empty(),
            eps,
        );
        out.slot[e] = out.enriched.len() as u32;
        out.unintegrated.push(out.slot[e]);
        out.enriched.push(EnrichedElement {
            elem: e,
            enrs,
            scalars,
            dofs: el_dofs,
            qps,
            k: DMatrix::zeros(0, 0),
            lines,
        });
    }
    out
}

/// The previous discretisation's data of element `e`, if it can serve
/// unchanged: same enrichments and shifts, same cutting lines, and farther
/// than `p.far` from every moved tip.
fn reusable<'a>(
    p: &Previous<'a>,
    e: usize,
    enrs: &[Enrichment],
    scalars: &[ScalarFn],
    lines: &[(P2, P2)],
    centre: P2,
) -> Option<&'a EnrichedElement> {
    let slot = *p.slot.get(e)?;
    if slot == REGULAR {
        return None;
    }
    let changed = |e: &Enrichment| match *e {
        Enrichment::Heaviside { crack } | Enrichment::Tip { crack, .. } => p.changed[crack],
    };
    if enrs.iter().any(changed) {
        return None;
    }
    let old = &p.enriched[slot as usize];
    let same = old.enrs == enrs && old.scalars == scalars && old.lines == lines;
    (same && p.moved.iter().all(|q| (q - centre).norm() > p.far)).then_some(old)
}

/// Values and gradients of the scalar shape functions of an enriched
/// element at `x`; at a point of crack `face.0`, taken on side `face.1`
/// (±1).
pub(super) fn eval_scalars(
    mesh: &Mesh,
    funcs: &EnrichmentFunctions,
    el: &EnrichedElement,
    x: P2,
    face: Option<(usize, f64)>,
    vals: &mut Vec<f64>,
    grads: &mut Vec<P2>,
) {
    let (n, dn) = mesh.shape(el.elem, x);
    let ev: Vec<EnrValue> = el
        .enrs
        .iter()
        .map(|&e| funcs.eval_sided(e, x, face))
        .collect();
    vals.clear();
    grads.clear();
    for s in &el.scalars {
        let i = s.node;
        match s.enr {
            None => {
                vals.push(n[i]);
                grads.push(dn[i]);
            }
            Some((k, l, shift)) => {
                let v = ev[k].f[l] - shift;
                vals.push(n[i] * v);
                grads.push(dn[i] * v + n[i] * ev[k].g[l]);
            }
        }
    }
}

/// Adds `Σ_q Bᵀ D B w t` over the element's quadrature points `points`
/// to `k` (over all of them: the element stiffness `K_e`).
pub(super) fn add_stiffness(
    mesh: &Mesh,
    funcs: &EnrichmentFunctions,
    elastic: &Elastic,
    thickness: f64,
    el: &EnrichedElement,
    points: Range<usize>,
    k: &mut DMatrix<f64>,
) {
    let nd = 2 * el.scalars.len();
    let mut b = DMatrix::zeros(3, nd);
    let mut db = DMatrix::zeros(3, nd);
    let (mut vals, mut grads) = (Vec::new(), Vec::new());
    for q in &el.qps[points] {
        eval_scalars(mesh, funcs, el, q.x, None, &mut vals, &mut grads);
        fill_b(&grads, &mut b);
        db.gemm(1.0, &elastic.d, &b, 0.0);
        add_bt_db(k, q.w * thickness, &grads, &db);
    }
}

/// Strain-displacement matrix from scalar gradients: columns `(2s, 2s+1)`
/// are `[[g_x, 0], [0, g_y], [g_y, g_x]]`.
pub fn fill_b(grads: &[P2], b: &mut DMatrix<f64>) {
    for (s, g) in grads.iter().enumerate() {
        b[(0, 2 * s)] = g.x;
        b[(1, 2 * s)] = 0.0;
        b[(2, 2 * s)] = g.y;
        b[(0, 2 * s + 1)] = 0.0;
        b[(1, 2 * s + 1)] = g.y;
        b[(2, 2 * s + 1)] = g.x;
    }
}

/// `k += alpha Bᵀ DB` for the `B` that [`fill_b`] makes from `grads`: the
/// sums of nalgebra's `gemm_tr`, in its order, without the products with
/// `B`'s zeros (which add ±0): a third of the work of an element's
/// stiffness.
fn add_bt_db(k: &mut DMatrix<f64>, alpha: f64, grads: &[P2], db: &DMatrix<f64>) {
    let nd = 2 * grads.len();
    for (kj, dbj) in k
        .as_mut_slice()
        .chunks_exact_mut(nd)
        .zip(db.as_slice().chunks_exact(3))
    {
        for (ks, g) in kj.chunks_exact_mut(2).zip(grads) {
            ks[0] += alpha * (g.x * dbj[0] + g.y * dbj[2]);
            ks[1] += alpha * (g.y * dbj[1] + g.x * dbj[2]);
        }
    }
}

/// Stiffness of an ordinary element (2×2 Gauss), shared by all of them.
pub(super) fn regular_stiffness(m: &Mesh, el: &Elastic, t: f64) -> SMatrix<f64, 8, 8> {
    let mut q = Vec::new();
    let (lo, hi) = m.element_box(0);
    box_rule(lo, hi, 2, &mut q);
    let mut k = SMatrix::<f64, 8, 8>::zeros();
    for p in q {
        let (_, dn) = m.shape(0, p.x);
        let mut b = SMatrix::<f64, 3, 8>::zeros();
        for i in 0..4 {
            b[(0, 2 * i)] = dn[i].x;
            b[(1, 2 * i + 1)] = dn[i].y;
            b[(2, 2 * i)] = dn[i].y;
            b[(2, 2 * i + 1)] = dn[i].x;
        }
        k += b.transpose() * el.d * b * (p.w * t);
    }
    k
}
