//! Integration of cut and tip elements by subdivision (SPEC §4).
//!
//! An element crossed by cracks is split along the lines of every crack
//! segment that touches it into convex pieces, each on one side of every
//! crack. Pieces are fanned into triangles: from the tip when the piece
//! touches a crack tip (collapsed Gauss, almost-polar), from the centroid
//! otherwise.

use crate::discretisation::quadrature::{
    QPoint, box_rule, collapsed_triangle_rule, graded_triangle_rule,
};
use crate::geometry::plane::{P2, polygon_area, polygon_centroid, split_convex};

/// Gauss order per direction on the rectangle of an uncut element with no
/// tip-enriched node.
pub const ORDER_PLAIN: usize = 2;
/// Collapsed order on triangles of cut elements without tip enrichment.
pub const ORDER_CUT: usize = 3;
/// Collapsed order on triangles of cut elements with tip enrichment (and
/// of uncut ones near their tip), before `refined_rule` splits them:
/// with `ORDER_REFINED` on the pieces it makes, ∫ 1/r over an element
/// whose tip lies 0.001–0.3 h outside it is exact to 2e-7
/// (`near_tip_rules_integrate_one_over_r`). The orders before, 8 and 6,
/// took 1.4 times the points; against them K moves by at most 6.2e-8 of
/// |K| at 53 generic tip positions, where tip-fan orders ([`ORDER_TIP`])
/// 10 and 12–20 differ by 5e-6–1.3e-3: the tip's own rule is the
/// quadrature error that counts. Order 4 on the refined pieces left the
/// crack-parallel patch test at 1.3e-5 instead of 2e-6.
pub const ORDER_CUT_TIP_ENRICHED: usize = 6;
/// Collapsed order on triangles fanned from a tip.
pub const ORDER_TIP: usize = 10;

/// Splits the convex polygon `poly` along the lines `(point, direction)`;
/// drops slivers below `min_area`.
pub fn split_by_lines(poly: &[P2], lines: &[(P2, P2)], eps: f64, min_area: f64) -> Vec<Vec<P2>> {
    let mut pieces = vec![poly.to_vec()];
    for &(o, d) in lines {
        let mut next = Vec::with_capacity(pieces.len() * 2);
        for p in &pieces {
            let (l, r) = split_convex(p, o, d, eps);
            for q in [l, r] {
                if q.len() >= 3 && polygon_area(&q).abs() > min_area {
                    next.push(q);
                }
            }
        }
        pieces = next;
    }
    pieces
}

/// Gauss order per direction on tip-enriched elements far from the tip
/// (see [`FAR_FROM_TIP`]): uncut ones on the rectangle, cut ones on the
/// collapsed triangles of their pieces.
pub const ORDER_FAR_TIP_ENRICHED: usize = 5;
/// A tip-enriched element is far from its tip when the distance exceeds
/// this many element diagonals: there the branch functions are smooth over
/// the element and order 5 integrates them as well as the near-tip rules
/// (K_I of the edge crack at 81 × 163 is the same to 7 digits, the stress
/// of the crack-parallel patch test the same to 1e-8; order 4 loses 4e-5
/// there, order 2 leaves spurious modes). With the geometric enrichment
/// zone most tip-enriched elements are far: this cuts their quadrature
/// points five-fold.
pub const FAR_FROM_TIP: f64 = 1.0;

/// Depth of the refinement of triangles near (not at) a tip.
const NEAR_TIP_DEPTH: usize = 8;
/// Collapsed order on the sub-triangles of that refinement (see
/// [`ORDER_CUT_TIP_ENRICHED`]).
const ORDER_REFINED: usize = 5;

/// Quadrature of one element given its pieces.
///
/// `tip`: a crack tip inside or on the element; `near_tip`: the nearest
/// tip of the branch functions its nodes carry (None without tip
/// enrichment); `cut`: whether any crack touches it. Triangles of
/// tip-enriched elements that do not touch the tip are refined while they
/// are closer to the tip than their size, so that the `1/√r` variation of
/// the branch-function gradients is resolved however close the tip is.
pub fn element_rule(
    lo: P2,
    hi: P2,
    pieces: &[Vec<P2>],
    tip: Option<P2>,
    near_tip: Option<P2>,
    cut: bool,
    eps: f64,
) -> Vec<QPoint> {
    let mut q = Vec::new();
    let diagonal = (hi - lo).norm();
    let far = tip.is_none()
        && near_tip.is_some_and(|t| distance_to_box(t, lo, hi) > FAR_FROM_TIP * diagonal);
    let tip_enriched = near_tip.is_some() && !far;
    if !cut && tip.is_none() && !tip_enriched {
        let order = if far {
            ORDER_FAR_TIP_ENRICHED
        } else {
            ORDER_PLAIN
        };
        box_rule(lo, hi, order, &mut q);
        return q;
    }
    let min_tri = 1e-14 * (hi.x - lo.x) * (hi.y - lo.y);
    for piece in pieces {
        let apex_at_tip = tip.filter(|&t| touches(piece, t, eps));
        let (apex, order) = match apex_at_tip {
            Some(t) => (t, ORDER_TIP),
            None if tip_enriched => (polygon_centroid(piece), ORDER_CUT_TIP_ENRICHED),
            None if far => (polygon_centroid(piece), ORDER_FAR_TIP_ENRICHED),
            None => (polygon_centroid(piece), ORDER_CUT),
        };
        let n = piece.len();
        for i in 0..n {
            let (b, c) = (piece[i], piece[(i + 1) % n]);
            let area = 0.5 * crate::geometry::plane::cross(b - apex, c - apex).abs();
            if area > min_tri {
                match (apex_at_tip, near_tip.filter(|_| tip_enriched)) {
                    (Some(_), _) => graded_triangle_rule(apex, b, c, order, &mut q),
                    (None, Some(t)) => refined_rule([apex, b, c], t, NEAR_TIP_DEPTH, order, &mut q),
                    (None, None) => collapsed_triangle_rule(apex, b, c, order, &mut q),
                }
            }
        }
    }
    q
}

/// Collapsed Gauss on a triangle, split in four while it is closer to
/// `tip` than its diameter (at most `depth` times).
fn refined_rule(t: [P2; 3], tip: P2, depth: usize, order: usize, out: &mut Vec<QPoint>) {
    let diam = (t[0] - t[1])
        .norm()
        .max((t[1] - t[2]).norm())
        .max((t[2] - t[0]).norm());
    if depth == 0 || distance_to_triangle(tip, &t) > diam {
        collapsed_triangle_rule(t[0], t[1], t[2], order, out);
        return;
    }
    let m = [
        0.5 * (t[0] + t[1]),
        0.5 * (t[1] + t[2]),
        0.5 * (t[2] + t[0]),
    ];
    // sub-triangles are smaller relative to their distance to the tip: a
    // lower order suffices on them
    let sub_order = order.min(ORDER_REFINED);
    for sub in [
        [t[0], m[0], m[2]],
        [m[0], t[1], m[1]],
        [m[2], m[1], t[2]],
        [m[0], m[1], m[2]],
    ] {
        refined_rule(sub, tip, depth - 1, sub_order, out);
    }
}

/// Distance from `p` to the box `[lo, hi]` (0 inside).
fn distance_to_box(p: P2, lo: P2, hi: P2) -> f64 {
    (lo - p).sup(&(p - hi)).sup(&P2::zeros()).norm()
}

/// Distance from `p` to a triangle (0 inside).
fn distance_to_triangle(p: P2, t: &[P2; 3]) -> f64 {
    let inside = {
        let s: Vec<f64> = (0..3)
            .map(|i| crate::geometry::plane::cross(t[(i + 1) % 3] - t[i], p - t[i]))
            .collect();
        s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0)
    };
    if inside {
        return 0.0;
    }
    (0..3)
        .map(|i| crate::geometry::plane::distance_to_segment(p, t[i], t[(i + 1) % 3]))
        .fold(f64::INFINITY, f64::min)
}

/// Whether point `t` lies in or on the convex polygon (within `eps`).
fn touches(poly: &[P2], t: P2, eps: f64) -> bool {
    let n = poly.len();
    let area_sign = polygon_area(poly).signum();
    (0..n).all(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let d = b - a;
        let len = d.norm().max(1e-300);
        area_sign * crate::geometry::plane::cross(d, t - a) / len >= -eps
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> Vec<P2> {
        vec![
            P2::new(0.0, 0.0),
            P2::new(1.0, 0.0),
            P2::new(1.0, 1.0),
            P2::new(0.0, 1.0),
        ]
    }

    #[test]
    fn pieces_and_rules_sum_to_element_area() {
        let lines = [
            (P2::new(0.0, 0.3), P2::new(1.0, 0.2)),
            (P2::new(0.5, 0.4), P2::new(0.3, 1.0)),
        ];
        let pieces = split_by_lines(&unit_square(), &lines, 1e-12, 1e-16);
        let area: f64 = pieces.iter().map(|p| polygon_area(p).abs()).sum();
        assert!((area - 1.0).abs() < 1e-12);
        let t = Some(P2::new(0.5, 0.4));
        for (tip, near) in [(None, None), (None, Some(P2::new(0.5, 1.01))), (t, t)] {
            let q = element_rule(
                P2::zeros(),
                P2::new(1.0, 1.0),
                &pieces,
                tip,
                near,
                true,
                1e-12,
            );
            let a: f64 = q.iter().map(|p| p.w).sum();
            assert!((a - 1.0).abs() < 1e-12, "{tip:?} {near:?}: {a}");
        }
    }

    /// `∫∫ 1/|x − p| dA` over the rectangle `[lo, hi]` (p outside it):
    /// `F(x2, y2) − F(x1, y2) − F(x2, y1) + F(x1, y1)` with
    /// `F(x, y) = x ln(y + r) + y ln(x + r)` in coordinates relative to p.
    fn one_over_r_on_rectangle(lo: P2, hi: P2, p: P2) -> f64 {
        let f = |x: f64, y: f64| {
            let r = x.hypot(y);
            x * (y + r).ln() + y * (x + r).ln()
        };
        let (x1, x2, y1, y2) = (lo.x - p.x, hi.x - p.x, lo.y - p.y, hi.y - p.y);
        f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)
    }

    /// The rule of an uncut tip-enriched element next to its tip (two
    /// triangles, refined toward the tip) integrates 1/r, the order of the
    /// branch functions' gradient products in the stiffness, to its closed
    /// form within 1e-6 for tips 0.001–0.3 element sizes outside the
    /// element, off the grid (2e-7 at most); within 1e-4 at 1e-4 h, where
    /// the refinement depth ends (6e-5).
    #[test]
    fn near_tip_rules_integrate_one_over_r() {
        let (lo, hi) = (P2::zeros(), P2::new(1.0, 1.0));
        let sq = unit_square();
        let halves = [vec![sq[0], sq[1], sq[2]], vec![sq[0], sq[2], sq[3]]];
        for (tip, tol) in [
            (P2::new(1.3, 0.37), 1e-6),
            (P2::new(1.05, 0.61), 1e-6),
            (P2::new(1.001, 0.29), 1e-6),
            (P2::new(1.02, 1.03), 1e-6),
            (P2::new(0.43, -0.0007), 1e-6),
            (P2::new(1.0001, 0.713), 1e-4),
        ] {
            let q = element_rule(lo, hi, &halves, None, Some(tip), false, 1e-12);
            let sum: f64 = q.iter().map(|p| p.w / (p.x - tip).norm()).sum();
            let exact = one_over_r_on_rectangle(lo, hi, tip);
            let err = (sum - exact).abs() / exact;
            assert!(
                err < tol,
                "tip {tip:?}: {} points, relative error {err:.2e}",
                q.len()
            );
        }
    }

    #[test]
    fn tiny_corner_fragment_is_kept_and_integrated() {
        // a line cutting 1e-6 of the area off a corner
        let s = (2e-6f64).sqrt();
        let lines = [(P2::new(s, 0.0), P2::new(-s, s))];
        let pieces = split_by_lines(&unit_square(), &lines, 1e-14, 1e-16);
        assert_eq!(pieces.len(), 2);
        let small = pieces
            .iter()
            .map(|p| polygon_area(p).abs())
            .fold(f64::INFINITY, f64::min);
        assert!((small - 1e-6).abs() < 1e-12);
    }
}
