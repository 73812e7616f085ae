//! Plane geometry on `f64` points: segments, polylines, convex polygons.

use nalgebra::Vector2;

/// A point or vector in the plane, m.
pub type P2 = Vector2<f64>;

/// Builds a point from an `[x, y]` pair.
pub fn p2(a: [f64; 2]) -> P2 {
    P2::new(a[0], a[1])
}

/// 2D cross product `a × b` (z component).
pub fn cross(a: P2, b: P2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// `v` turned +90° (counter-clockwise).
pub fn perp(v: P2) -> P2 {
    P2::new(-v.y, v.x)
}

/// Closest point on segment `ab` to `p`: returns the parameter `t ∈ [0, 1]`.
pub fn closest_on_segment(p: P2, a: P2, b: P2) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    if l2 == 0.0 {
        return 0.0;
    }
    ((p - a).dot(&d) / l2).clamp(0.0, 1.0)
}

/// Crack level set φ of the polyline `pts` at `p` and its gradient: the
/// signed distance (positive on the left of the polyline's direction).
/// The sign comes from the closest segment; at a shared vertex from the
/// angle-bisecting pseudo-normal. Beyond an end point φ is the signed
/// distance to the end segment's line (the level set extended past the
/// tips), so that `θ = atan2(φ, ψ)` is the polar angle ahead of a tip.
pub fn level_set(p: P2, pts: &[P2]) -> (f64, P2) {
    let mut best = f64::INFINITY;
    let mut best_seg = 0;
    let mut best_t = 0.0;
    for (k, w) in pts.windows(2).enumerate() {
        let t = closest_on_segment(p, w[0], w[1]);
        let d = (p - (w[0] + t * (w[1] - w[0]))).norm_squared();
        if d < best {
            best = d;
            best_seg = k;
            best_t = t;
        }
    }
    let n_seg = pts.len() - 1;
    let (a, b) = (pts[best_seg], pts[best_seg + 1]);
    let normal = perp((b - a).normalize());
    let beyond_start = best_seg == 0 && best_t <= 0.0;
    let beyond_end = best_seg + 1 == n_seg && best_t >= 1.0;
    if beyond_start || beyond_end || (best_t > 0.0 && best_t < 1.0) {
        return ((p - a).dot(&normal), normal);
    }
    // closest to an interior vertex
    let k = if best_t <= 0.0 {
        best_seg
    } else {
        best_seg + 1
    };
    let d = p - pts[k];
    let dist = d.norm();
    let side = vertex_side(p, pts, k);
    let sign = if side >= 0.0 { 1.0 } else { -1.0 };
    if dist < 1e-300 {
        return (0.0, normal);
    }
    (sign * dist, d / dist * sign)
}

/// Signed distance φ (see [`level_set`]).
pub fn signed_distance(p: P2, pts: &[P2]) -> f64 {
    level_set(p, pts).0
}

/// Side of `p` at interior vertex `k` by the pseudo-normal (sum of the unit
/// normals of the two segments meeting there).
fn vertex_side(p: P2, pts: &[P2], k: usize) -> f64 {
    let t0 = (pts[k] - pts[k - 1]).normalize();
    let t1 = (pts[k + 1] - pts[k]).normalize();
    let n = perp(t0) + perp(t1);
    let n = if n.norm_squared() < 1e-24 {
        perp(t0)
    } else {
        n
    };
    (p - pts[k]).dot(&n)
}

/// Intersection of segments `ab` and `cd`: parameters `(s, t)` along each,
/// both in [0, 1], or `None` when they do not cross (parallel ones never do).
pub fn segment_intersection(a: P2, b: P2, c: P2, d: P2) -> Option<(f64, f64)> {
    let r = b - a;
    let s = d - c;
    let den = cross(r, s);
    if den.abs() <= 1e-14 * r.norm() * s.norm() {
        return None;
    }
    let t = cross(c - a, s) / den;
    let u = cross(c - a, r) / den;
    let tol = 1e-12;
    if (-tol..=1.0 + tol).contains(&t) && (-tol..=1.0 + tol).contains(&u) {
        Some((t.clamp(0.0, 1.0), u.clamp(0.0, 1.0)))
    } else {
        None
    }
}

/// Part of segment `ab` inside the closed box `[lo, hi]` (Liang–Barsky):
/// parameters `(t0, t1)` with `t0 < t1`, or `None`.
pub fn clip_segment_to_box(a: P2, b: P2, lo: P2, hi: P2) -> Option<(f64, f64)> {
    let d = b - a;
    let mut t0: f64 = 0.0;
    let mut t1: f64 = 1.0;
    for (p, q) in [
        (-d.x, a.x - lo.x),
        (d.x, hi.x - a.x),
        (-d.y, a.y - lo.y),
        (d.y, hi.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 < t1).then_some((t0, t1))
}

/// Area of a polygon (positive when counter-clockwise).
pub fn polygon_area(poly: &[P2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| cross(poly[i], poly[(i + 1) % n]))
        .sum::<f64>()
        * 0.5
}

/// Centroid of a non-degenerate polygon.
pub fn polygon_centroid(poly: &[P2]) -> P2 {
    let n = poly.len();
    let mut c = P2::zeros();
    let mut a = 0.0;
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let w = cross(p, q);
        a += w;
        c += (p + q) * w;
    }
    if a.abs() < 1e-300 {
        return poly.iter().sum::<P2>() / n as f64;
    }
    c / (3.0 * a)
}

/// Splits a convex polygon by the line through `o` with direction `d`:
/// `(left, right)` pieces (either may be empty). Vertices within `eps` of
/// the line are put on it.
pub fn split_convex(poly: &[P2], o: P2, d: P2, eps: f64) -> (Vec<P2>, Vec<P2>) {
    let n = poly.len();
    let dn = d.normalize();
    let side: Vec<f64> = poly
        .iter()
        .map(|p| {
            let s = cross(dn, p - o);
            if s.abs() <= eps { 0.0 } else { s }
        })
        .collect();
    let mut left = Vec::with_capacity(n + 2);
    let mut right = Vec::with_capacity(n + 2);
    for i in 0..n {
        let j = (i + 1) % n;
        let (p, sp, sq) = (poly[i], side[i], side[j]);
        if sp >= 0.0 {
            left.push(p);
        }
        if sp <= 0.0 {
            right.push(p);
        }
        if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
            let x = p + (poly[j] - p) * (sp / (sp - sq));
            left.push(x);
            right.push(x);
        }
    }
    (left, right)
}

/// Distance from `p` to the segment `ab`.
pub fn distance_to_segment(p: P2, a: P2, b: P2) -> f64 {
    let t = closest_on_segment(p, a, b);
    (p - (a + t * (b - a))).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_distance_sign_follows_left_side() {
        let pts = [P2::new(0.0, 0.0), P2::new(1.0, 0.0), P2::new(2.0, 1.0)];
        assert!((signed_distance(P2::new(0.5, 0.3), &pts) - 0.3).abs() < 1e-15);
        assert!((signed_distance(P2::new(0.5, -0.2), &pts) + 0.2).abs() < 1e-15);
        // beyond the first end: the distance to the end segment's line
        assert!((signed_distance(P2::new(-1.0, 0.1), &pts) - 0.1).abs() < 1e-15);
        // at the kink, outside the bend
        assert!(signed_distance(P2::new(1.1, -0.2), &pts) < 0.0);
    }

    #[test]
    fn split_square_by_diagonal_keeps_area() {
        let sq = [
            P2::new(0.0, 0.0),
            P2::new(1.0, 0.0),
            P2::new(1.0, 1.0),
            P2::new(0.0, 1.0),
        ];
        let (l, r) = split_convex(&sq, P2::new(0.0, 0.0), P2::new(1.0, 1.0), 1e-14);
        assert!((polygon_area(&l) - 0.5).abs() < 1e-15);
        assert!((polygon_area(&r) - 0.5).abs() < 1e-15);
        let (l, r) = split_convex(&sq, P2::new(0.0, 1.0), P2::new(1.0, 0.0), 1e-14);
        assert!((polygon_area(&l) - 0.0).abs() < 1e-15 && (polygon_area(&r) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn clip_segment_to_unit_box() {
        let (t0, t1) = clip_segment_to_box(
            P2::new(-1.0, 0.5),
            P2::new(3.0, 0.5),
            P2::new(0.0, 0.0),
            P2::new(1.0, 1.0),
        )
        .expect("crosses");
        assert!((t0 - 0.25).abs() < 1e-15 && (t1 - 0.5).abs() < 1e-15);
    }
}
