//! The extended finite element discretisation of one crack configuration:
//! which nodes are enriched and how, the DOF map, element quadrature and
//! stiffness, and the crack-face integration points.
//!
//! Built from the model (mesh, material, supports) and the current cracks;
//! rebuilt when cracks change. Elements with no enriched node share one
//! stiffness matrix `k0`, computed once.

use std::cell::OnceCell;
use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;

use nalgebra::{DMatrix, SMatrix};

use crate::discretisation::dofs::{DofMap, FIXED};
use crate::discretisation::enrichment::{EnrValue, Enrichment, EnrichmentFunctions};
use crate::discretisation::material::Elastic;
use crate::discretisation::pattern::Pattern;
use crate::discretisation::quadrature::{QPoint, box_rule, segment_rule};
use crate::discretisation::subdivision::{element_rule, split_by_lines};
use crate::error::SolveError;
use crate::geometry::cracks::Crack;
use crate::geometry::mesh::Mesh;
use crate::geometry::plane::{P2, clip_segment_to_box, polygon_area, polygon_centroid};

/// Gauss points per crack piece away from tips.
pub const FACE_ORDER: usize = 2;

/// Marks an element without its own data (an ordinary element).
pub const REGULAR: u32 = u32::MAX;

/// Panic message for a solver given a discretisation built with
/// [`Xfem::build`] before [`Xfem::integrate`] completed it.
pub const NOT_INTEGRATED: &str = "element stiffness not yet integrated (Xfem::integrate)";

/// Settings of the discretisation where SPEC leaves room.
///
/// The tip-enrichment zone of a tip is geometric: its radius
///
/// `r_e = max(enrichment_radius · h, min(zone_fraction · min(a, ℓ), max_zone_radius · h))`
///
/// with `a` the crack's length per free tip (the depth of an edge crack, the
/// half-length of a centre crack) and `ℓ` the length of the straight end
/// segment at the tip, does not shrink with the mesh, which keeps the SIF
/// error converging at second order (a zone of a fixed number of elements
/// converges at first order). `zone_fraction · a` stays well inside the
/// crack, so the zones of a crack's two tips never overlap; `ℓ` keeps the
/// zone off the kinks of a grown crack, where the branch functions of a
/// straight tip no longer fit (a growing wing has short segments, so its
/// zone stays at the minimum); the cap of `max_zone_radius` elements bounds
/// the number of tip DOFs on fine meshes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct XfemParams {
    /// Smallest radius of the tip enrichment, in element sizes h.
    pub enrichment_radius: f64,
    /// Geometric radius of the tip enrichment as a fraction of the crack's
    /// length per free tip.
    pub zone_fraction: f64,
    /// Largest geometric radius, in element sizes h.
    pub max_zone_radius: f64,
    /// Heaviside enrichment is dropped when the smaller side of a node's
    /// support is below this fraction of the support area.
    pub min_fragment: f64,
}

impl Default for XfemParams {
    fn default() -> Self {
        Self {
            enrichment_radius: 2.5,
            zone_fraction: 0.2,
            max_zone_radius: 16.0,
            min_fragment: 1e-4,
        }
    }
}

impl XfemParams {
    /// Radius `r_e` of the enrichment zone of tip `tip` (0 or 1) of `crack`
    /// on a mesh of element size `h`, m.
    pub fn zone_radius(&self, crack: &Crack, tip: usize, h: f64) -> f64 {
        let tips = crack.free_tips().count().max(1);
        let a = crack.length() / tips as f64;
        let n = crack.points.len();
        let end = if tip == 0 {
            (crack.points[1] - crack.points[0]).norm()
        } else {
            (crack.points[n - 1] - crack.points[n - 2]).norm()
        };
        let geometric = (self.zone_fraction * a.min(end)).min(self.max_zone_radius * h);
        geometric.max(self.enrichment_radius * h)
    }
}

/// One scalar shape function of an element: `N_i` or `N_i (E_l − E_l(x_i))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalarFn {
    /// Local corner 0..4.
    pub node: usize,
    /// `(index into the element's distinct enrichments, function l, shift)`.
    pub enr: Option<(usize, usize, f64)>,
}

/// An element with at least one enriched node: its own layout, quadrature
/// and stiffness.
#[derive(Clone, Debug)]
pub struct EnrichedElement {
    pub elem: usize,
    /// Distinct enrichments of its nodes.
    pub enrs: Vec<Enrichment>,
    pub scalars: Vec<ScalarFn>,
    /// Free DOF index of each (scalar, component), [`FIXED`] if constrained.
    pub dofs: Vec<u32>,
    pub qps: Vec<QPoint>,
    pub k: DMatrix<f64>,
    /// The crack-segment lines it was split along (for reuse checks).
    pub lines: Vec<(P2, P2)>,
}

/// What may be reused from the previous discretisation after a crack
/// change: element data far enough from every point that moved.
pub struct Reuse<'a> {
    pub previous: &'a Xfem,
    /// Old and new positions of the tips that changed.
    pub moved: Vec<P2>,
}

/// A crack piece (the part of a crack segment inside one element) carrying
/// one contact state: its gap is the mean of the jump over the piece and its
/// traction is uniform on it (a piecewise-constant multiplier space, stable
/// where point-wise penalties lock: near a tip the jump vanishes like √r and
/// point-wise tractions would be forced to zero there).
#[derive(Clone, Debug)]
pub struct FacePoint {
    pub crack: usize,
    /// Midpoint, m.
    pub x: P2,
    /// Length times thickness, m².
    pub w: f64,
    /// Gauss points on the piece (weights: length times thickness), for
    /// integrals of the traction against other fields.
    pub qps: Vec<QPoint>,
    /// Unit normal into the φ > 0 side.
    pub n: P2,
    /// Unit tangent along the polyline's direction.
    pub t: P2,
    /// Arc length from the crack's first point, m.
    pub s: f64,
    /// Index of the owning element in [`Xfem::enriched`].
    pub slot: usize,
    /// Mean over the piece of the jump `ψ(x⁺) − ψ(x⁻)` of each scalar
    /// shape function of the element.
    pub jump: Vec<f64>,
    /// For a sliver at a tip (see [`MIN_TIP_PIECE`]): the face point whose
    /// contact state it takes; it adds no contact stiffness of its own.
    pub follows: Option<usize>,
}

/// A crack piece that ends at a tip and is shorter than this many element
/// sizes is a sliver: its mean jump (which vanishes like √r at the tip) is
/// dominated by the coupling of the tip element's branch-function DOFs, not
/// by contact, and left to itself it reports "open" on a crack closed by
/// compression (g_N ≈ +2e-3 g_T on a sliding crack at 20° to the mesh). It
/// takes the state and traction of the nearest piece of its crack instead,
/// and keeps its quadrature for the face term of the interaction integral.
pub const MIN_TIP_PIECE: f64 = 0.25;

/// The discretisation.
#[derive(Clone, Debug)]
pub struct Xfem {
    pub mesh: Mesh,
    pub elastic: Elastic,
    pub thickness: f64,
    pub params: XfemParams,
    pub funcs: EnrichmentFunctions,
    pub dofs: DofMap,
    /// Per element: index into `enriched`, or [`REGULAR`].
    pub slot: Vec<u32>,
    pub enriched: Vec<EnrichedElement>,
    /// Stiffness of an ordinary element (DOF order `x0 y0 x1 y1 …`).
    pub k0: SMatrix<f64, 8, 8>,
    pub faces: Vec<FacePoint>,
    /// Sparsity pattern and symbolic Cholesky of the stiffness, computed on
    /// first use and shared by every factorisation on this discretisation.
    pattern: OnceCell<Pattern>,
    /// Slots of enriched elements whose stiffness is still to be integrated
    /// (see [`build`](Self::build)); empty once usable.
    unintegrated: Vec<u32>,
    /// Quadrature points of the last of `unintegrated` already summed.
    integrated_points: usize,
}

/// Per element, the `(crack, segment)` pairs whose segment touches it.
type ElementSegments = BTreeMap<usize, Vec<(usize, usize)>>;

impl Xfem {
    /// Builds everything for the given cracks (tips already classified)
    /// but the stiffness of the enriched elements that could not be reused
    /// (the costly part of a rebuild after growth): [`integrate`](Self::integrate)
    /// computes it, at once or in chunks (so that the workbench can spread a
    /// rebuild over frames); solvers need it complete.
    pub fn build(
        mesh: Mesh,
        elastic: Elastic,
        thickness: f64,
        cracks: Vec<Crack>,
        fixed: &[bool],
        params: XfemParams,
        reuse: Option<&Reuse>,
    ) -> Self {
        let h = mesh.h();
        let funcs = EnrichmentFunctions::new(cracks, 1e-9 * h);
        let segs = element_segments(&mesh, &funcs.cracks);
        let tips = element_tips(&mesh, &funcs.cracks);
        let node_enr = classify_nodes(&mesh, &funcs, &segs, params);
        let dofs = DofMap::new(node_enr, fixed);
        let mut x = Self {
            k0: regular_stiffness(&mesh, &elastic, thickness),
            mesh,
            elastic,
            thickness,
            params,
            funcs,
            dofs,
            slot: Vec::new(),
            enriched: Vec::new(),
            faces: Vec::new(),
            pattern: OnceCell::new(),
            unintegrated: Vec::new(),
            integrated_points: 0,
        };
        x.build_elements(&segs, &tips, reuse);
        x.build_faces();
        x
    }

    fn build_elements(
        &mut self,
        segs: &ElementSegments,
        tips: &BTreeMap<usize, P2>,
        reuse: Option<&Reuse>,
    ) {
        let m = &self.mesh;
        self.slot = vec![REGULAR; m.element_count()];
        let eps = 1e-12 * m.h();
        let far = reuse.map_or(0.0, |r| {
            r.previous
                .funcs
                .cracks
                .iter()
                .chain(&self.funcs.cracks)
                .flat_map(|c| c.free_tips().map(|k| self.params.zone_radius(c, k, m.h())))
                .fold(0.0, f64::max)
                + 2.0 * m.h()
        });
        for e in 0..m.element_count() {
            let nodes = m.element_nodes(e);
            if !nodes.iter().any(|&n| self.dofs.is_enriched(n)) {
                continue;
            }
            let (enrs, scalars) = self.layout(&nodes);
            let dofs = self.layout_dofs(&nodes, &scalars, &enrs);
            let (lo, hi) = m.element_box(e);
            let lines: Vec<(P2, P2)> = segs
                .get(&e)
                .map(|v| {
                    v.iter()
                        .map(|&(c, s)| {
                            let p = &self.funcs.cracks[c].points;
                            (p[s], p[s + 1] - p[s])
                        })
                        .collect()
                })
                .unwrap_or_default();
            let pieces = split_by_lines(&m.element_polygon(e), &lines, eps, 1e-14 * m.hx * m.hy);
            let centre = 0.5 * (lo + hi);
            if let Some(old) =
                reuse.and_then(|r| reusable(r, e, &enrs, &scalars, &lines, centre, far))
            {
                self.slot[e] = self.enriched.len() as u32;
                self.enriched.push(EnrichedElement {
                    elem: e,
                    enrs,
                    scalars,
                    dofs,
                    qps: old.qps.clone(),
                    k: old.k.clone(),
                    lines,
                });
                continue;
            }
            let near_tip = enrs
                .iter()
                .filter_map(|en| match *en {
                    Enrichment::Tip { crack, tip } => Some(self.funcs.cracks[crack].tip_point(tip)),
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
            let el = EnrichedElement {
                elem: e,
                enrs,
                scalars,
                dofs,
                qps,
                k: DMatrix::zeros(0, 0),
                lines,
            };
            self.slot[e] = self.enriched.len() as u32;
            self.unintegrated.push(self.slot[e]);
            self.enriched.push(el);
        }
    }

    /// Distinct enrichments and scalar functions of an element's nodes.
    fn layout(&self, nodes: &[usize; 4]) -> (Vec<Enrichment>, Vec<ScalarFn>) {
        let enrs: Vec<Enrichment> = nodes
            .iter()
            .flat_map(|&n| self.dofs.node_enr[n].iter().map(|ne| ne.kind))
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        let mut scalars: Vec<ScalarFn> = (0..4).map(|i| ScalarFn { node: i, enr: None }).collect();
        for (i, &n) in nodes.iter().enumerate() {
            for ne in &self.dofs.node_enr[n] {
                let k = enrs.iter().position(|&e| e == ne.kind).unwrap_or(0);
                for l in 0..ne.kind.functions() {
                    scalars.push(ScalarFn {
                        node: i,
                        enr: Some((k, l, ne.shift[l])),
                    });
                }
            }
        }
        (enrs, scalars)
    }

    fn layout_dofs(
        &self,
        nodes: &[usize; 4],
        scalars: &[ScalarFn],
        enrs: &[Enrichment],
    ) -> Vec<u32> {
        let mut dofs = Vec::with_capacity(2 * scalars.len());
        for s in scalars {
            let n = nodes[s.node];
            let first = match s.enr {
                None => self.dofs.node_first[n],
                Some((k, l, _)) => {
                    let ne = self.dofs.node_enr[n].iter().find(|ne| ne.kind == enrs[k]);
                    ne.map_or(0, |ne| ne.first + 2 * l)
                }
            };
            dofs.push(self.dofs.free[first]);
            dofs.push(self.dofs.free[first + 1]);
        }
        dofs
    }

    /// Integrates the stiffness of the enriched elements still without one,
    /// over at most `max_points` quadrature points (an element may take
    /// several calls: near a tip one can have 20 000 points); returns
    /// whether all have their stiffness now.
    pub fn integrate(&mut self, max_points: usize) -> bool {
        let mut left = max_points;
        while left > 0
            && let Some(&slot) = self.unintegrated.last()
        {
            let slot = slot as usize;
            let (from, n) = (self.integrated_points, self.enriched[slot].qps.len());
            let to = n.min(from.saturating_add(left));
            let mut k = if from == 0 {
                let nd = 2 * self.enriched[slot].scalars.len();
                DMatrix::zeros(nd, nd)
            } else {
                std::mem::take(&mut self.enriched[slot].k)
            };
            self.add_stiffness(&self.enriched[slot], from..to, &mut k);
            self.enriched[slot].k = k;
            left -= to - from;
            if to == n {
                self.unintegrated.pop();
                self.integrated_points = 0;
            } else {
                self.integrated_points = to;
            }
        }
        self.unintegrated.is_empty()
    }

    /// Whether every element's stiffness is integrated (needed by every
    /// solver; see [`build`](Self::build)).
    pub fn is_integrated(&self) -> bool {
        self.unintegrated.is_empty()
    }

    /// Quadrature points still to be summed by [`integrate`](Self::integrate).
    pub fn points_to_integrate(&self) -> usize {
        self.unintegrated
            .iter()
            .map(|&s| self.enriched[s as usize].qps.len())
            .sum::<usize>()
            - self.integrated_points
    }

    /// Whether [`pattern`](Self::pattern) has been computed.
    pub fn has_pattern(&self) -> bool {
        self.pattern.get().is_some()
    }

    /// Adds `Σ_q Bᵀ D B w t` over the element's quadrature points `points`
    /// to `k` (over all of them: the element stiffness `K_e`).
    fn add_stiffness(&self, el: &EnrichedElement, points: Range<usize>, k: &mut DMatrix<f64>) {
        let nd = 2 * el.scalars.len();
        let mut b = DMatrix::zeros(3, nd);
        let mut db = DMatrix::zeros(3, nd);
        let (mut vals, mut grads) = (Vec::new(), Vec::new());
        for q in &el.qps[points] {
            self.eval_enriched(el, q.x, &mut vals, &mut grads);
            fill_b(&grads, &mut b);
            db.gemm(1.0, &self.elastic.d, &b, 0.0);
            add_bt_db(k, q.w * self.thickness, &grads, &db);
        }
    }

    /// Values and gradients of the scalar shape functions of an enriched
    /// element at `x`.
    pub fn eval_enriched(
        &self,
        el: &EnrichedElement,
        x: P2,
        vals: &mut Vec<f64>,
        grads: &mut Vec<P2>,
    ) {
        self.eval_enriched_sided(el, x, None, vals, grads);
    }

    /// The same at a point of crack `face.0`, taken on side `face.1` (±1).
    pub fn eval_enriched_sided(
        &self,
        el: &EnrichedElement,
        x: P2,
        face: Option<(usize, f64)>,
        vals: &mut Vec<f64>,
        grads: &mut Vec<P2>,
    ) {
        let (n, dn) = self.mesh.shape(el.elem, x);
        let ev: Vec<EnrValue> = el
            .enrs
            .iter()
            .map(|&e| self.funcs.eval_sided(e, x, face))
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

    /// Scalar shape functions of any element at `x` and the element's free
    /// DOFs (two per scalar).
    pub fn eval_element(
        &self,
        e: usize,
        x: P2,
        vals: &mut Vec<f64>,
        grads: &mut Vec<P2>,
        dofs: &mut Vec<u32>,
    ) {
        dofs.clear();
        let slot = self.slot[e];
        if slot == REGULAR {
            let (n, dn) = self.mesh.shape(e, x);
            vals.clear();
            grads.clear();
            vals.extend_from_slice(&n);
            grads.extend_from_slice(&dn);
            dofs.extend_from_slice(&self.regular_dofs(e));
        } else {
            let el = &self.enriched[slot as usize];
            self.eval_enriched(el, x, vals, grads);
            dofs.extend_from_slice(&el.dofs);
        }
    }

    /// Free DOFs of an ordinary element, order `x0 y0 … x3 y3`.
    pub fn regular_dofs(&self, e: usize) -> [u32; 8] {
        let nodes = self.mesh.element_nodes(e);
        let mut d = [FIXED; 8];
        for (i, &n) in nodes.iter().enumerate() {
            d[2 * i] = self.dofs.std_free(n, 0);
            d[2 * i + 1] = self.dofs.std_free(n, 1);
        }
        d
    }

    fn build_faces(&mut self) {
        let m = &self.mesh;
        let h = m.h();
        let mut faces: Vec<FacePoint> = Vec::new();
        let mut slivers = Vec::new();
        let (mut vals, mut grads, mut vm) = (Vec::new(), Vec::new(), Vec::new());
        for (c, crack) in self.funcs.cracks.iter().enumerate() {
            let mut s0 = 0.0;
            for (a, b) in crack.segments() {
                let len = (b - a).norm();
                let t = (b - a) / len;
                let n = crate::geometry::plane::perp(t);
                let (lo, hi) = (a.inf(&b), a.sup(&b));
                for e in m.elements_in_box(lo, hi, 1e-9 * h) {
                    let slot = self.slot[e];
                    if slot == REGULAR {
                        continue;
                    }
                    let (blo, bhi) = m.element_box(e);
                    let pad = P2::new(1e-9 * h, 1e-9 * h);
                    let Some((t0, t1)) = clip_segment_to_box(a, b, blo - pad, bhi + pad) else {
                        continue;
                    };
                    if (t1 - t0) * len < 1e-9 * h {
                        continue;
                    }
                    let mid = a + 0.5 * (t0 + t1) * (b - a);
                    if m.element_at(mid - 1e-7 * h * n) != Some(e) {
                        continue; // a piece along an edge belongs to one element
                    }
                    let el = &self.enriched[slot as usize];
                    let tipped = el
                        .enrs
                        .iter()
                        .any(|x| matches!(x, Enrichment::Tip { crack, .. } if *crack == c));
                    let (pa, pb) = (a + t0 * (b - a), a + t1 * (b - a));
                    let mut q = Vec::new();
                    let at_tip = |p: P2| {
                        crack
                            .free_tips()
                            .any(|k| (crack.tip_point(k) - p).norm() < 1e-9 * h)
                    };
                    if at_tip(pb) {
                        graded_segment_rule(pa, pb, 6, &mut q);
                    } else if at_tip(pa) {
                        graded_segment_rule(pb, pa, 6, &mut q);
                    } else {
                        segment_rule(pa, pb, if tipped { 6 } else { FACE_ORDER }, &mut q);
                    }
                    let length: f64 = q.iter().map(|p| p.w).sum();
                    let mut jump = vec![0.0; el.scalars.len()];
                    for p in &q {
                        self.eval_enriched_sided(el, p.x, Some((c, 1.0)), &mut vals, &mut grads);
                        self.eval_enriched_sided(el, p.x, Some((c, -1.0)), &mut vm, &mut grads);
                        for (j, (u, v)) in jump.iter_mut().zip(vals.iter().zip(&vm)) {
                            *j += (u - v) * p.w / length;
                        }
                    }
                    faces.push(FacePoint {
                        crack: c,
                        x: mid,
                        w: length * self.thickness,
                        qps: q
                            .iter()
                            .map(|p| QPoint {
                                x: p.x,
                                w: p.w * self.thickness,
                            })
                            .collect(),
                        n,
                        t,
                        s: s0 + (mid - a).norm(),
                        slot: slot as usize,
                        jump,
                        follows: None,
                    });
                    if (at_tip(pa) || at_tip(pb)) && (pb - pa).norm() < MIN_TIP_PIECE * h {
                        slivers.push(faces.len() - 1);
                    }
                }
                s0 += len;
            }
        }
        for &i in &slivers {
            faces[i].follows = faces
                .iter()
                .enumerate()
                .filter(|(j, f)| f.crack == faces[i].crack && !slivers.contains(j))
                .min_by(|a, b| {
                    let d = |f: &FacePoint| (f.s - faces[i].s).abs();
                    d(a.1).total_cmp(&d(b.1))
                })
                .map(|(j, _)| j);
        }
        self.faces = faces;
    }

    /// The stiffness pattern with its symbolic factorisation (computed once).
    /// Its elements are the regular elements in mesh order, then the
    /// enriched ones in slot order.
    pub fn pattern(&self) -> Result<&Pattern, SolveError> {
        if let Some(p) = self.pattern.get() {
            return Ok(p);
        }
        let n_elements = self.mesh.element_count();
        let mut dofs = Vec::with_capacity(8 * n_elements);
        let mut starts = Vec::with_capacity(n_elements + 1);
        starts.push(0);
        for e in 0..n_elements {
            if self.slot[e] == REGULAR {
                dofs.extend_from_slice(&self.regular_dofs(e));
                starts.push(dofs.len());
            }
        }
        for el in &self.enriched {
            dofs.extend_from_slice(&el.dofs);
            starts.push(dofs.len());
        }
        let p = Pattern::new(self.n_free(), &dofs, &starts)?;
        Ok(self.pattern.get_or_init(|| p))
    }

    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.dofs.n_free
    }
}

/// The previous discretisation's data of element `e`, if it can serve
/// unchanged: same enrichments and shifts, same cutting lines, and farther
/// than `far` (the largest enrichment radius plus two elements) from every
/// moved tip.
fn reusable<'a>(
    r: &'a Reuse,
    e: usize,
    enrs: &[Enrichment],
    scalars: &[ScalarFn],
    lines: &[(P2, P2)],
    centre: P2,
    far: f64,
) -> Option<&'a EnrichedElement> {
    let slot = *r.previous.slot.get(e)?;
    if slot == REGULAR {
        return None;
    }
    let old = &r.previous.enriched[slot as usize];
    let same = old.enrs == enrs && old.scalars == scalars && old.lines == lines;
    (same && r.moved.iter().all(|p| (p - centre).norm() > far)).then_some(old)
}

/// Gauss rule on the segment from `far` to a crack tip `tip`, graded as
/// `r = t²` so that integrands like `f(r)/√r` (the face term of the
/// interaction integral) become smooth: weights carry `dr = 2t dt`.
fn graded_segment_rule(far: P2, tip: P2, n: usize, out: &mut Vec<QPoint>) {
    let len = (far - tip).norm();
    let dir = (far - tip) / len;
    let root = len.sqrt();
    for (s, w) in crate::discretisation::quadrature::gauss_legendre(n) {
        let t = 0.5 * (s + 1.0) * root;
        out.push(QPoint {
            x: tip + dir * (t * t),
            w: w * 0.5 * root * 2.0 * t,
        });
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
fn regular_stiffness(m: &Mesh, el: &Elastic, t: f64) -> SMatrix<f64, 8, 8> {
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

/// For every element, the crack segments touching its closed box.
fn element_segments(m: &Mesh, cracks: &[Crack]) -> ElementSegments {
    let h = m.h();
    let pad = P2::new(1e-9 * h, 1e-9 * h);
    let mut out: ElementSegments = BTreeMap::new();
    for (c, crack) in cracks.iter().enumerate() {
        for (s, (a, b)) in crack.segments().enumerate() {
            let len = (b - a).norm();
            for e in m.elements_in_box(a.inf(&b), a.sup(&b), 1e-9 * h) {
                let (lo, hi) = m.element_box(e);
                if let Some((t0, t1)) = clip_segment_to_box(a, b, lo - pad, hi + pad)
                    && (t1 - t0) * len > 1e-12 * h
                {
                    out.entry(e).or_default().push((c, s));
                }
            }
        }
    }
    out
}

/// Elements whose closed box holds a free tip (the first one found).
fn element_tips(m: &Mesh, cracks: &[Crack]) -> BTreeMap<usize, P2> {
    let h = m.h();
    let mut out = BTreeMap::new();
    for crack in cracks {
        for k in crack.free_tips() {
            let p = crack.tip_point(k);
            for e in m.elements_in_box(p, p, 1e-9 * h) {
                out.entry(e).or_insert(p);
            }
        }
    }
    out
}

/// Enrichments (with shifts) of every node.
fn classify_nodes(
    m: &Mesh,
    funcs: &EnrichmentFunctions,
    segs: &ElementSegments,
    params: XfemParams,
) -> Vec<Vec<(Enrichment, [f64; 4])>> {
    let h = m.h();
    let mut enr: Vec<Vec<(Enrichment, [f64; 4])>> = vec![Vec::new(); m.node_count()];
    for (c, crack) in funcs.cracks.iter().enumerate() {
        // tip sets: nodes within r_e of a free tip, and all nodes of the
        // elements holding it
        let mut tip_elements = BTreeSet::new();
        for k in crack.free_tips() {
            let p = crack.tip_point(k);
            let r = params.zone_radius(crack, k, h);
            let lo = p - P2::new(r, r);
            let hi = p + P2::new(r, r);
            let mut set = BTreeSet::new();
            for e in m.elements_in_box(lo, hi, 0.0) {
                for n in m.element_nodes(e) {
                    if (m.node_pos(n) - p).norm() <= r {
                        set.insert(n);
                    }
                }
            }
            for e in m.elements_in_box(p, p, 1e-9 * h) {
                set.extend(m.element_nodes(e));
                tip_elements.insert(e);
            }
            for &n in &set {
                let kind = Enrichment::Tip { crack: c, tip: k };
                enr[n].push((kind, funcs.eval(kind, m.node_pos(n)).f));
            }
        }
        // Heaviside set: nodes of touched elements whose support has a
        // non-negligible part on each side, outside the inner tip zone
        // (`enrichment_radius · h`). In a geometric zone the outer tip nodes
        // keep it too: there the opening is no longer √r times a bilinear
        // field, and without the step the jump across cut elements of the
        // zone is poorly represented (K_I of an edge crack through the
        // middle of an element row: −0.19% → −0.06% at 81 × 163). Near the
        // tip the level set extends past the crack, so the step would open
        // the ligament: nodes whose support holds a tip never carry it.
        let inner = params.enrichment_radius * h;
        let cand: BTreeSet<usize> = segs
            .iter()
            .filter(|(_, v)| v.iter().any(|&(cc, _)| cc == c))
            .flat_map(|(&e, _)| m.element_nodes(e))
            .filter(|&n| {
                let x = m.node_pos(n);
                crack
                    .free_tips()
                    .all(|k| (x - crack.tip_point(k)).norm() > inner)
                    && !m.node_elements(n).any(|e| tip_elements.contains(&e))
            })
            .collect();
        for n in cand {
            let (mut plus, mut minus, mut total) = (0.0, 0.0, 0.0);
            for e in m.node_elements(n) {
                let lines: Vec<(P2, P2)> = segs
                    .get(&e)
                    .map(|v| {
                        v.iter()
                            .filter(|&&(cc, _)| cc == c)
                            .map(|&(_, s)| (crack.points[s], crack.points[s + 1] - crack.points[s]))
                            .collect()
                    })
                    .unwrap_or_default();
                let pieces = split_by_lines(&m.element_polygon(e), &lines, 1e-12 * h, 0.0);
                for piece in pieces {
                    let a = polygon_area(&piece).abs();
                    total += a;
                    match funcs.heaviside(c, polygon_centroid(&piece)) {
                        v if v > 0.0 => plus += a,
                        v if v < 0.0 => minus += a,
                        _ => {}
                    }
                }
            }
            if plus.min(minus) >= params.min_fragment * total {
                let hv = funcs.heaviside(c, m.node_pos(n));
                enr[n].push((Enrichment::Heaviside { crack: c }, [hv, 0.0, 0.0, 0.0]));
            }
        }
    }
    for list in &mut enr {
        list.sort_by_key(|a| a.0);
    }
    enr
}

/// Cracks with their tip kinds classified for a specimen.
pub fn prepare_cracks(mut cracks: Vec<Crack>, m: &Mesh) -> Vec<Crack> {
    crate::geometry::cracks::classify_tips(&mut cracks, m.width, m.height, 1e-9 * m.h());
    cracks
}
