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

/// Enrichments an element's point evaluation keeps on the stack (a tip's
/// branch functions and a Heaviside or two; more only where cracks meet).
const FEW_ENRICHMENTS: usize = 6;

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
    // on the stack for the usual few enrichments: this runs per quadrature
    // point, thousands of times for one element
    let mut near = [EnrValue::default(); FEW_ENRICHMENTS];
    let many: Vec<EnrValue>;
    let ev: &[EnrValue] = if el.enrs.len() <= FEW_ENRICHMENTS {
        for (v, &e) in near.iter_mut().zip(&el.enrs) {
            *v = funcs.eval_sided(e, x, face);
        }
        &near[..el.enrs.len()]
    } else {
        many = el
            .enrs
            .iter()
            .map(|&e| funcs.eval_sided(e, x, face))
            .collect();
        &many
    };
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

/// Quadrature points whose gradients [`add_stiffness`] sums in one matrix
/// product. Callers that integrate an element in slices start each slice at
/// a multiple of it, so that the sums do not depend on the slicing.
pub(super) const STIFFNESS_BATCH: usize = 64;

/// Adds `Σ_q Bᵀ D B w t` over the element's quadrature points `points`
/// to `k` (over all of them: the element stiffness `K_e`).
///
/// With `B`'s columns `(2a, 2a+1)` the strains of the scalar gradient
/// `(g_x, g_y)` of function `a` (`[[g_x, 0], [0, g_y], [g_y, g_x]]`), the
/// 2 × 2 block of functions
/// `a, b` is a combination of D's entries with the four moments
/// `G_xx = Σ w t g_x g_xᵀ`, `G_xy = Σ w t g_x g_yᵀ`, `G_yx = G_xyᵀ` and
/// `G_yy`, e.g. `K_{u_a u_b} = D₁₁ G_xx + D₁₃ G_xy + D₃₁ G_yx + D₃₃ G_yy`.
/// The moments of each batch of [`STIFFNESS_BATCH`] points (counted from
/// the element's first point) are matrix products, `G_xx = (W G_x) G_xᵀ`,
/// and each batch's block is added to `k` in turn: near a tip an element
/// has thousands of points (up to 6 400 in the default scene's growth).
pub(super) fn add_stiffness(
    mesh: &Mesh,
    funcs: &EnrichmentFunctions,
    elastic: &Elastic,
    thickness: f64,
    el: &EnrichedElement,
    points: Range<usize>,
    k: &mut DMatrix<f64>,
) {
    debug_assert!(
        points.start.is_multiple_of(STIFFNESS_BATCH),
        "a slice starts on a batch"
    );
    let n = el.scalars.len();
    let (mut gxx, mut gxy, mut gyy) = (
        DMatrix::zeros(n, n),
        DMatrix::zeros(n, n),
        DMatrix::zeros(n, n),
    );
    // one point per column: the gradients, and the same times w t
    let mut gx = DMatrix::zeros(n, STIFFNESS_BATCH);
    let mut gy = DMatrix::zeros(n, STIFFNESS_BATCH);
    let mut wx = DMatrix::zeros(n, STIFFNESS_BATCH);
    let mut wy = DMatrix::zeros(n, STIFFNESS_BATCH);
    let (mut vals, mut grads) = (Vec::new(), Vec::new());
    let d = &elastic.d;
    for batch in el.qps[points].chunks(STIFFNESS_BATCH) {
        for (c, q) in batch.iter().enumerate() {
            eval_scalars(mesh, funcs, el, q.x, None, &mut vals, &mut grads);
            let w = q.w * thickness;
            for (a, g) in grads.iter().enumerate() {
                gx[(a, c)] = g.x;
                gy[(a, c)] = g.y;
                wx[(a, c)] = w * g.x;
                wy[(a, c)] = w * g.y;
            }
        }
        let m = batch.len();
        let (gxt, gyt) = (gx.columns(0, m).transpose(), gy.columns(0, m).transpose());
        gxx.gemm(1.0, &wx.columns(0, m), &gxt, 0.0);
        gxy.gemm(1.0, &wx.columns(0, m), &gyt, 0.0);
        gyy.gemm(1.0, &wy.columns(0, m), &gyt, 0.0);
        for b in 0..n {
            for a in 0..n {
                let (xx, xy, yx, yy) = (gxx[(a, b)], gxy[(a, b)], gxy[(b, a)], gyy[(a, b)]);
                k[(2 * a, 2 * b)] +=
                    d[(0, 0)] * xx + d[(0, 2)] * xy + d[(2, 0)] * yx + d[(2, 2)] * yy;
                k[(2 * a, 2 * b + 1)] +=
                    d[(0, 1)] * xy + d[(0, 2)] * xx + d[(2, 1)] * yy + d[(2, 2)] * yx;
                k[(2 * a + 1, 2 * b)] +=
                    d[(1, 0)] * yx + d[(1, 2)] * yy + d[(2, 0)] * xx + d[(2, 2)] * xy;
                k[(2 * a + 1, 2 * b + 1)] +=
                    d[(1, 1)] * yy + d[(1, 2)] * yx + d[(2, 1)] * xy + d[(2, 2)] * xx;
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::model::Model;
    use crate::scene::Scene;
    use nalgebra::Matrix3;

    /// Strain-displacement matrix from scalar gradients: columns
    /// `(2s, 2s+1)` are `[[g_x, 0], [0, g_y], [g_y, g_x]]`.
    fn fill_b(grads: &[P2], b: &mut DMatrix<f64>) {
        for (s, g) in grads.iter().enumerate() {
            b[(0, 2 * s)] = g.x;
            b[(1, 2 * s)] = 0.0;
            b[(2, 2 * s)] = g.y;
            b[(0, 2 * s + 1)] = 0.0;
            b[(1, 2 * s + 1)] = g.y;
            b[(2, 2 * s + 1)] = g.x;
        }
    }

    /// The stiffness from the gradient moments equals `Σ Bᵀ D B w t` summed
    /// point by point, for a full (anisotropic) D whose shear couplings
    /// `D₁₃, D₂₃` exercise every term, on the tip element of a 33° crack
    /// whose tip lies inside an element (branch and Heaviside functions),
    /// in two slices of its points: to 1e-12 of the largest entry.
    #[test]
    fn stiffness_from_gradient_moments_is_the_sum_of_bt_d_b() {
        let json = r#"{"specimen":{"width":1.0,"height":1.0},"mesh":{"nx":9,"ny":9},
            "material":{"young":1e9,"poisson":0.3},
            "cracks":[{"points":[[0.21,0.33],[0.5437,0.5468]]}]}"#;
        let model = Model::new(Scene::from_json(json).expect("scene"));
        let mut x = model.discretise(model.initial_cracks());
        x.elastic.d = Matrix3::new(3.1, 1.2, 0.4, 1.2, 2.7, -0.3, 0.4, -0.3, 0.9) * 1e9;
        let el = x
            .enriched
            .iter()
            .max_by_key(|e| e.qps.len())
            .expect("an enriched element");
        let (n, nd) = (el.qps.len(), 2 * el.scalars.len());
        let mut k = DMatrix::zeros(nd, nd);
        let half = (n / 2).next_multiple_of(STIFFNESS_BATCH);
        add_stiffness(&x.mesh, &x.funcs, &x.elastic, 0.7, el, 0..half, &mut k);
        add_stiffness(&x.mesh, &x.funcs, &x.elastic, 0.7, el, half..n, &mut k);
        let mut want = DMatrix::zeros(nd, nd);
        let mut b = DMatrix::zeros(3, nd);
        let (mut vals, mut grads) = (Vec::new(), Vec::new());
        for q in &el.qps {
            eval_scalars(&x.mesh, &x.funcs, el, q.x, None, &mut vals, &mut grads);
            fill_b(&grads, &mut b);
            want += b.transpose() * x.elastic.d * &b * (q.w * 0.7);
        }
        let scale = want.amax();
        let diff = (&k - &want).amax();
        assert!(
            n > 100 && nd > 16,
            "{n} points, {nd} DOFs: not a tip element"
        );
        assert!(diff <= 1e-12 * scale, "{diff:e} against {scale:e}");
    }
}
