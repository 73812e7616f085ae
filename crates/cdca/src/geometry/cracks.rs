//! Cracks as explicit polylines with the kind of each tip (SPEC §2).
//!
//! The level sets are evaluated exactly from the polyline: `φ` is the signed
//! distance (positive on the left of the polyline's direction) and, for tip
//! `k`, `ψ = (x − x_tip)·t_tip` with `t_tip` the outward tangent.

use crate::geometry::plane::{
    P2, cross, distance_to_segment, perp, segment_intersection, signed_distance,
};
use crate::scene::CrackSpec;

/// What a crack end is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TipKind {
    /// A free tip: tip-enriched, may grow.
    Free,
    /// On the specimen boundary: no tip enrichment.
    Boundary,
    /// Ends on crack `main`: no tip enrichment; junction enrichment.
    Junction { main: usize },
}

/// One crack: geometry, tip kinds and face properties.
#[derive(Clone, Debug, PartialEq)]
pub struct Crack {
    pub points: Vec<P2>,
    pub tips: [TipKind; 2],
    /// Coulomb friction coefficient μ.
    pub friction: f64,
    /// Face cohesion c_c, Pa.
    pub cohesion: f64,
    /// Normal stiffness k_N, Pa/m.
    pub kn: f64,
    /// Tangential stiffness k_T, Pa/m.
    pub kt: f64,
}

impl Crack {
    /// Builds a crack from the scene; `h` is the element size and `young`
    /// Young's modulus (for the penalty default `k_N = 100 E/h`).
    pub fn from_spec(spec: &CrackSpec, h: f64, young: f64) -> Self {
        let points: Vec<P2> = spec
            .polyline(h)
            .into_iter()
            .map(crate::geometry::plane::p2)
            .collect();
        let kn = spec.normal_stiffness.unwrap_or(100.0 * young / h);
        let kt = spec.shear_stiffness.unwrap_or(0.1 * kn);
        Self {
            points,
            tips: [TipKind::Free; 2],
            friction: spec.friction,
            cohesion: spec.cohesion,
            kn,
            kt,
        }
    }

    /// Position of tip `k` (0 = first point, 1 = last).
    pub fn tip_point(&self, k: usize) -> P2 {
        if k == 0 {
            self.points[0]
        } else {
            self.points[self.points.len() - 1]
        }
    }

    /// The segment at end `k`, from its inner point to the end: `(inner,
    /// end)`.
    pub fn end_segment(&self, k: usize) -> (P2, P2) {
        let n = self.points.len();
        if k == 0 {
            (self.points[1], self.points[0])
        } else {
            (self.points[n - 2], self.points[n - 1])
        }
    }

    /// Outward unit tangent at tip `k`.
    pub fn tip_dir(&self, k: usize) -> P2 {
        let (inner, end) = self.end_segment(k);
        (end - inner).normalize()
    }

    /// Signed distance φ(x) to the polyline.
    pub fn phi(&self, x: P2) -> f64 {
        signed_distance(x, &self.points)
    }

    /// Distance from `x` to the crack.
    pub fn distance(&self, x: P2) -> f64 {
        self.points
            .windows(2)
            .map(|w| distance_to_segment(x, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
    }

    /// Total length, m.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
    }

    /// Segments `(a, b)` of the polyline.
    pub fn segments(&self) -> impl Iterator<Item = (P2, P2)> + '_ {
        self.points.windows(2).map(|w| (w[0], w[1]))
    }

    /// Free tips (0, 1 or 2 of them).
    pub fn free_tips(&self) -> impl Iterator<Item = usize> + '_ {
        (0..2).filter(|&k| self.tips[k] == TipKind::Free)
    }

    /// The first point `k` at which the polyline meets itself, if it does:
    /// segment `k − 1 → k` turns straight back along the one before it
    /// (within a thousandth of a radian of opposite), or crosses or comes
    /// within `tol` of a segment that is not its neighbour.
    pub fn self_contact(&self, tol: f64) -> Option<usize> {
        let p = &self.points;
        for j in 2..p.len() {
            let (d, before) = (p[j] - p[j - 1], p[j - 1] - p[j - 2]);
            if d.dot(&before) < 0.0 && cross(d, before).abs() <= 1e-3 * d.norm() * before.norm() {
                return Some(j);
            }
            for i in 1..j - 1 {
                let (a, b, c, e) = (p[i - 1], p[i], p[j - 1], p[j]);
                let touch = segment_intersection(a, b, c, e).is_some()
                    || [(c, a, b), (e, a, b), (a, c, e), (b, c, e)]
                        .iter()
                        .any(|&(x, s0, s1)| distance_to_segment(x, s0, s1) <= tol);
                if touch {
                    return Some(j);
                }
            }
        }
        None
    }
}

#[cfg(test)]
impl Crack {
    /// A crack through `points` with tip kinds `tips` and neutral faces
    /// (no friction or cohesion, unit stiffness), for the geometry tests.
    pub(crate) fn bare(points: &[[f64; 2]], tips: [TipKind; 2]) -> Self {
        Self {
            points: points
                .iter()
                .map(|&p| crate::geometry::plane::p2(p))
                .collect(),
            tips,
            friction: 0.0,
            cohesion: 0.0,
            kn: 1.0,
            kt: 1.0,
        }
    }
}

/// Local frame of a tip: origin at the tip, `e1` along the outward tangent,
/// `e2 = e1` turned +90°.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TipFrame {
    pub origin: P2,
    pub e1: P2,
    pub e2: P2,
}

impl TipFrame {
    pub fn of(crack: &Crack, k: usize) -> Self {
        let e1 = crack.tip_dir(k);
        Self {
            origin: crack.tip_point(k),
            e1,
            e2: perp(e1),
        }
    }

    /// Local coordinates `(x1, x2)` of a global point.
    pub fn local(&self, x: P2) -> P2 {
        let d = x - self.origin;
        P2::new(d.dot(&self.e1), d.dot(&self.e2))
    }

    /// Global components of a local vector.
    pub fn global(&self, v: P2) -> P2 {
        self.e1 * v.x + self.e2 * v.y
    }
}

/// Classifies every tip: on the boundary of `[0,w]×[0,h]`, on another crack
/// (junction), or free. `tol` is the snapping distance.
pub fn classify_tips(cracks: &mut [Crack], width: f64, height: f64, tol: f64) {
    for j in 0..cracks.len() {
        for k in 0..2 {
            let p = cracks[j].tip_point(k);
            let on_boundary = p.x <= tol || p.y <= tol || p.x >= width - tol || p.y >= height - tol;
            let kind = if on_boundary {
                TipKind::Boundary
            } else if let Some(m) =
                (0..cracks.len()).find(|&m| m != j && cracks[m].distance(p) <= tol)
            {
                TipKind::Junction { main: m }
            } else {
                TipKind::Free
            };
            cracks[j].tips[k] = kind;
        }
    }
}

/// Whether the cracks split the specimen: a chain of cracks linked at
/// junctions runs from the boundary back to the boundary, so that the
/// pieces on either side hold together only through their crack faces
/// (once those open a piece has a rigid motion and the stiffness is
/// singular). A closed loop of cracks inside the specimen cuts out a
/// fragment but leaves the specimen whole around it.
///
/// In the graph whose vertices are the cracks and the boundary, and whose
/// edges are the non-free tips (a boundary tip joins its crack to the
/// boundary, a junction its crack to the main one) and the crossings (two
/// drawn cracks that cross away from their tips), that is a cycle through
/// the boundary: one of the boundary's edges joins two vertices that the
/// other edges join too. The tips must be classified ([`classify_tips`]).
pub fn split_specimen(cracks: &[Crack]) -> bool {
    let boundary = cracks.len();
    let edges: Vec<(usize, usize)> = tip_edges(cracks).chain(crossings(cracks)).collect();
    edges.iter().enumerate().any(|(i, &(a, b))| {
        if b != boundary {
            return false;
        }
        let mut parent: Vec<usize> = (0..=boundary).collect();
        for (j, &(c, d)) in edges.iter().enumerate() {
            if j != i {
                let (rc, rd) = (root(&mut parent, c), root(&mut parent, d));
                parent[rc] = rd;
            }
        }
        root(&mut parent, a) == root(&mut parent, b)
    })
}

/// The edges of the graph of [`split_specimen`]: each non-free tip joins its
/// crack to the boundary (index `cracks.len()`) or to its main crack.
fn tip_edges(cracks: &[Crack]) -> impl Iterator<Item = (usize, usize)> + '_ {
    cracks.iter().enumerate().flat_map(move |(c, crack)| {
        crack.tips.iter().filter_map(move |tip| match tip {
            TipKind::Free => None,
            TipKind::Boundary => Some((c, cracks.len())),
            TipKind::Junction { main } => Some((c, *main)),
        })
    })
}

/// The pairs of cracks whose polylines cross or touch (a junction's pair
/// too: an edge twice between two cracks makes no cycle through the
/// boundary).
fn crossings(cracks: &[Crack]) -> impl Iterator<Item = (usize, usize)> + '_ {
    (0..cracks.len()).flat_map(move |i| {
        (i + 1..cracks.len())
            .filter(move |&j| {
                cracks[j]
                    .segments()
                    .any(|(a, b)| first_crossing(&cracks[i], a, b).is_some())
            })
            .map(move |j| (i, j))
    })
}

/// Total length of the crack system each crack belongs to, m: cracks
/// joined at junctions (a crack started at another's kink, a wing that ran
/// onto another crack) count as one crack, as the polyline of a flaw and
/// its wings does. How a crack system is split into polylines is a matter
/// of representation, not of the crack.
pub fn system_lengths(cracks: &[Crack]) -> Vec<f64> {
    let mut parent: Vec<usize> = (0..cracks.len()).collect();
    for (c, crack) in cracks.iter().enumerate() {
        for tip in crack.tips {
            if let TipKind::Junction { main } = tip {
                let (a, b) = (root(&mut parent, c), root(&mut parent, main));
                parent[a] = b;
            }
        }
    }
    let mut total = vec![0.0; cracks.len()];
    for (c, crack) in cracks.iter().enumerate() {
        let r = root(&mut parent, c);
        total[r] += crack.length();
    }
    (0..cracks.len())
        .map(|c| total[root(&mut parent, c)])
        .collect()
}

/// Root of `i` in a union–find forest (with path halving).
pub fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Reference side of a junction: the sign of `φ_main` on the secondary
/// crack's own body (at the middle of its segment next to tip `k`).
pub fn junction_side(secondary: &Crack, k: usize, main: &Crack) -> f64 {
    let n = secondary.points.len();
    let (a, b) = if k == 0 {
        (secondary.points[0], secondary.points[1])
    } else {
        (secondary.points[n - 1], secondary.points[n - 2])
    };
    let probe = a + 0.5 * (b - a);
    let s = main.phi(probe);
    if s == 0.0 {
        // the segment lies on the main crack: fall back to its far end
        main.phi(b).signum()
    } else {
        s.signum()
    }
}

/// Whether the segment `ab` crosses the crack; returns the first crossing
/// along `ab` as `(parameter on ab, point)`.
pub fn first_crossing(crack: &Crack, a: P2, b: P2) -> Option<(f64, P2)> {
    let mut best: Option<(f64, P2)> = None;
    for (c, d) in crack.segments() {
        if let Some((s, _)) = crate::geometry::plane::segment_intersection(a, b, c, d)
            && best.is_none_or(|(bs, _)| s < bs)
        {
            best = Some((s, a + s * (b - a)));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crack(tips: [TipKind; 2]) -> Crack {
        Crack::bare(&[[0.0, 0.0], [1.0, 0.0]], tips)
    }

    /// A chain from boundary to boundary splits the specimen; a closed loop
    /// inside it, or a chain with one end on the boundary, does not.
    #[test]
    fn split_specimen_needs_a_chain_from_boundary_to_boundary() {
        use TipKind::{Boundary, Free, Junction};
        let j = |main| Junction { main };
        assert!(!split_specimen(&[]));
        assert!(!split_specimen(&[crack([Boundary, Free])]));
        assert!(split_specimen(&[crack([Boundary, Boundary])]));
        assert!(split_specimen(&[
            crack([Boundary, Free]),
            crack([j(0), Boundary])
        ]));
        // through a third crack
        assert!(split_specimen(&[
            crack([Boundary, Free]),
            crack([j(0), j(2)]),
            crack([Free, Boundary])
        ]));
        // a wing from the boundary ends on an edge crack: still one edge crack
        assert!(!split_specimen(&[
            crack([Boundary, Free]),
            crack([j(0), Free])
        ]));
        // the pivot scene after step 42: crack 1 runs bottom to top, crack
        // 0 has a free tip
        assert!(split_specimen(&[
            crack([Free, Boundary]),
            crack([Boundary, Boundary])
        ]));
        // loops inside the specimen cut out a fragment only
        assert!(!split_specimen(&[crack([Free, Free]), crack([j(0), j(0)])]));
        assert!(!split_specimen(&[crack([j(1), Free]), crack([j(0), Free])]));
        // a loop hanging off an edge crack
        assert!(!split_specimen(&[
            crack([Boundary, Free]),
            crack([j(0), j(0)])
        ]));
    }

    /// Drawn cracks that cross away from their tips link like a junction:
    /// two edge cracks from the left and the bottom side that cross cut the
    /// corner off; crossing inside the specimen, or crossing with only one
    /// of them on the boundary, they do not.
    #[test]
    fn crossing_cracks_split_the_specimen_when_they_join_two_edges() {
        use TipKind::{Boundary, Free};
        let segment = |a: [f64; 2], b: [f64; 2], tips| Crack {
            points: vec![P2::new(a[0], a[1]), P2::new(b[0], b[1])],
            tips,
            ..crack([Free, Free])
        };
        // from the left side at y = 0.4 to (0.7, 0.45); from the bottom at
        // x = 0.31 up to (0.33, 0.8): they cross near (0.31, 0.39)
        let from_left = |tips| segment([0.0, 0.4], [0.7, 0.45], tips);
        let from_bottom = |tips| segment([0.31, 0.0], [0.33, 0.8], tips);
        assert!(split_specimen(&[
            from_left([Boundary, Free]),
            from_bottom([Boundary, Free])
        ]));
        assert!(!split_specimen(&[
            from_left([Free, Free]),
            from_bottom([Boundary, Free])
        ]));
        assert!(!split_specimen(&[
            from_left([Free, Free]),
            from_bottom([Free, Free])
        ]));
        // the same two, apart (the bottom one moved right past the other's
        // end): no crossing, no split
        let apart = segment([0.75, 0.0], [0.77, 0.8], [Boundary, Free]);
        assert!(!split_specimen(&[from_left([Boundary, Free]), apart]));
    }
}
