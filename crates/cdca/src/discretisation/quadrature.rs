//! Quadrature rules: Gauss–Legendre on [−1, 1], tensor rules on rectangles,
//! and collapsed (Duffy) Gauss rules on triangles.
//!
//! The collapsed rule maps the square onto a triangle with one edge shrunk
//! to a vertex; its Jacobian vanishes like `r` at that vertex, which cancels
//! the `1/√r · 1/√r` of the crack-tip stiffness integrand (almost-polar
//! integration).

use crate::geometry::plane::P2;

/// Rules of up to this many points are computed once and kept.
const KEPT_ORDERS: usize = 64;

/// Gauss–Legendre points and weights on [−1, 1] (Newton on P_n), each
/// order computed once (an enriched element's sub-cell rules ask for the
/// same few orders thousands of times a discretisation).
pub fn gauss_legendre(n: usize) -> std::borrow::Cow<'static, [(f64, f64)]> {
    static KEPT: [std::sync::OnceLock<Vec<(f64, f64)>>; KEPT_ORDERS] =
        [const { std::sync::OnceLock::new() }; KEPT_ORDERS];
    match KEPT.get(n.wrapping_sub(1)) {
        Some(kept) => std::borrow::Cow::Borrowed(kept.get_or_init(|| legendre_rule(n))),
        None => std::borrow::Cow::Owned(legendre_rule(n)),
    }
}

fn legendre_rule(n: usize) -> Vec<(f64, f64)> {
    assert!(n >= 1, "at least one Gauss point");
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { x } else { p1 };
            let pm = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * pn - pm) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        out.push((x, 2.0 / ((1.0 - x * x) * dp * dp)));
    }
    out
}

/// A quadrature point in physical coordinates with its weight (area or
/// length already included).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QPoint {
    pub x: P2,
    pub w: f64,
}

/// `n × n` Gauss rule on the axis-aligned box `[lo, hi]`.
pub fn box_rule(lo: P2, hi: P2, n: usize, out: &mut Vec<QPoint>) {
    let g = gauss_legendre(n);
    let (cx, cy) = (0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y));
    let (ax, ay) = (0.5 * (hi.x - lo.x), 0.5 * (hi.y - lo.y));
    for &(s, ws) in g.iter() {
        for &(t, wt) in g.iter() {
            out.push(QPoint {
                x: P2::new(cx + ax * s, cy + ay * t),
                w: ws * wt * ax * ay,
            });
        }
    }
}

/// Collapsed `n × n` Gauss rule on triangle `(apex, b, c)`, the square's
/// collapsed edge mapped to `apex`: `x = apex + u((1−v) b' + v c')` with
/// `u, v ∈ [0,1]`, Jacobian `u · |(b−apex) × (c−apex)|`.
pub fn collapsed_triangle_rule(apex: P2, b: P2, c: P2, n: usize, out: &mut Vec<QPoint>) {
    let g = gauss_legendre(n);
    let (eb, ec) = (b - apex, c - apex);
    let det = (eb.x * ec.y - eb.y * ec.x).abs();
    for &(s, ws) in g.iter() {
        let u = 0.5 * (s + 1.0);
        for &(t, wt) in g.iter() {
            let v = 0.5 * (t + 1.0);
            out.push(QPoint {
                x: apex + u * ((1.0 - v) * eb + v * ec),
                w: 0.25 * ws * wt * u * det,
            });
        }
    }
}

/// Collapsed rule on triangle `(apex, b, c)` graded toward the apex: the
/// radial coordinate is `u = s²`, Jacobian `2 s³ |(b−apex) × (c−apex)|`.
/// Integrands like `r^(-1/2)` and `r^(-1)` near a crack tip at the apex
/// become polynomials in `s`, so both the enriched stiffness (∝ 1/r) and its
/// coupling with smooth fields (∝ 1/√r) are integrated accurately.
pub fn graded_triangle_rule(apex: P2, b: P2, c: P2, n: usize, out: &mut Vec<QPoint>) {
    let g = gauss_legendre(n);
    let (eb, ec) = (b - apex, c - apex);
    let det = (eb.x * ec.y - eb.y * ec.x).abs();
    for &(sg, ws) in g.iter() {
        let s = 0.5 * (sg + 1.0);
        let u = s * s;
        for &(t, wt) in g.iter() {
            let v = 0.5 * (t + 1.0);
            out.push(QPoint {
                x: apex + u * ((1.0 - v) * eb + v * ec),
                w: 0.25 * ws * wt * 2.0 * s * s * s * det,
            });
        }
    }
}

/// Gauss rule with `n` points on the segment `ab`.
pub fn segment_rule(a: P2, b: P2, n: usize, out: &mut Vec<QPoint>) {
    let half = 0.5 * (b - a).norm();
    for &(s, w) in gauss_legendre(n).iter() {
        out.push(QPoint {
            x: a + 0.5 * (s + 1.0) * (b - a),
            w: w * half,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_degree_2n_minus_1() {
        for n in 1..=8 {
            let g = gauss_legendre(n);
            let deg = 2 * n - 1;
            let num: f64 = g.iter().map(|&(x, w)| w * x.powi(deg as i32 - 1)).sum();
            let exact = if (deg - 1) % 2 == 0 {
                2.0 / deg as f64
            } else {
                0.0
            };
            assert!((num - exact).abs() < 1e-14, "n = {n}");
        }
    }

    #[test]
    fn collapsed_rule_area_and_singular_integrand() {
        let mut q = Vec::new();
        let (a, b, c) = (P2::new(0.0, 0.0), P2::new(1.0, 0.0), P2::new(0.0, 1.0));
        collapsed_triangle_rule(a, b, c, 8, &mut q);
        let area: f64 = q.iter().map(|p| p.w).sum();
        assert!((area - 0.5).abs() < 1e-15);
        // ∫ 1/r over the triangle = ∫_0^{π/2} 1/(cos θ + sin θ) dθ = √2 ln(1+√2):
        // the radial singularity is cancelled; the angular factor is smooth
        let num: f64 = q.iter().map(|p| p.w / p.x.norm()).sum();
        let exact = 2f64.sqrt() * (1.0 + 2f64.sqrt()).ln();
        assert!((num - exact).abs() < 1e-6 * exact, "{num} vs {exact}");
    }

    #[test]
    fn graded_rule_integrates_inverse_root_r() {
        let mut q = Vec::new();
        let (a, b, c) = (P2::new(0.0, 0.0), P2::new(1.0, 0.0), P2::new(0.0, 1.0));
        graded_triangle_rule(a, b, c, 7, &mut q);
        let area: f64 = q.iter().map(|p| p.w).sum();
        assert!((area - 0.5).abs() < 1e-14);
        // ∫ r^(-1/2) dA = ∫_0^{π/2} (2/3) (cos θ + sin θ)^(-3/2) dθ, by fine quadrature
        let g = gauss_legendre(40);
        let exact: f64 = g
            .iter()
            .map(|&(t, w)| {
                let th = 0.25 * std::f64::consts::PI * (t + 1.0);
                w * 0.25 * std::f64::consts::PI * (2.0 / 3.0) * (th.cos() + th.sin()).powf(-1.5)
            })
            .sum();
        let num: f64 = q.iter().map(|p| p.w / p.x.norm().sqrt()).sum();
        assert!((num - exact).abs() < 1e-6 * exact, "{num} vs {exact}");
    }
}
