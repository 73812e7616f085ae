//! Which nodes are enriched and how (SPEC §3): the tip zones, the
//! Heaviside sets, and the layout of each enriched element's scalar shape
//! functions and DOFs.

use std::collections::{BTreeMap, BTreeSet};

use crate::discretisation::dofs::DofMap;
use crate::discretisation::enrichment::{Enrichment, EnrichmentFunctions};
use crate::discretisation::subdivision::split_by_lines;
use crate::geometry::cracks::Crack;
use crate::geometry::mesh::Mesh;
use crate::geometry::plane::{P2, clip_segment_to_box, polygon_area, polygon_centroid};

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

/// Per element, the `(crack, segment)` pairs whose segment touches it.
pub(super) type ElementSegments = BTreeMap<usize, Vec<(usize, usize)>>;

/// Distinct enrichments and scalar functions of the element with corner
/// nodes `nodes`.
pub(super) fn element_layout(
    dofs: &DofMap,
    nodes: &[usize; 4],
) -> (Vec<Enrichment>, Vec<ScalarFn>) {
    let enrs: Vec<Enrichment> = nodes
        .iter()
        .flat_map(|&n| dofs.node_enr[n].iter().map(|ne| ne.kind))
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let mut scalars: Vec<ScalarFn> = (0..4).map(|i| ScalarFn { node: i, enr: None }).collect();
    for (i, &n) in nodes.iter().enumerate() {
        for ne in &dofs.node_enr[n] {
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

/// Free DOF index of each (scalar, component) of an element's layout,
/// [`FIXED`](crate::discretisation::dofs::FIXED) if constrained.
pub(super) fn element_dofs(
    dofs: &DofMap,
    nodes: &[usize; 4],
    scalars: &[ScalarFn],
    enrs: &[Enrichment],
) -> Vec<u32> {
    let mut out = Vec::with_capacity(2 * scalars.len());
    for s in scalars {
        let n = nodes[s.node];
        let first = match s.enr {
            None => dofs.node_first[n],
            Some((k, l, _)) => {
                let ne = dofs.node_enr[n].iter().find(|ne| ne.kind == enrs[k]);
                ne.map_or(0, |ne| ne.first + 2 * l)
            }
        };
        out.push(dofs.free[first]);
        out.push(dofs.free[first + 1]);
    }
    out
}

/// For every element, the crack segments touching its closed box.
pub(super) fn element_segments(m: &Mesh, cracks: &[Crack]) -> ElementSegments {
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
pub(super) fn element_tips(m: &Mesh, cracks: &[Crack]) -> BTreeMap<usize, P2> {
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
pub(super) fn classify_nodes(
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
