//! Stress intensity factors and T-stress by the interaction integral in
//! domain form (SPEC §7), in the tip frame:
//!
//! `I = ∫_A [σ_ij u^aux_i,1 + σ^aux_ij u_i,1 − σ_jk ε^aux_jk δ_1j] q,j dA + ∫_Γc p·[[u^aux_,1]] q ds`
//!
//! `K_I = E'/2 · I(mode I aux)`, `K_II = E'/2 · I(mode II aux)` with the
//! Williams fields, and `T = E' · I(point force aux)` with the field of a
//! unit force on the tip along the crack (Kfouri). `q` is 1 at nodes within
//! `r_J` of the tip and 0 elsewhere, interpolated by the Q4 functions. The
//! face term carries the contact tractions `p` (force per area that the `−`
//! side exerts against the `+` side), without which K of a closed,
//! frictional crack is wrong.
//!
//! The contact traction is constant per crack piece (the part of the crack
//! in one element), and on pieces of unequal length it oscillates from
//! piece to piece (±40% about σ_n on a crack at 20° to the mesh) while its
//! resultant over a few elements is right. Weighted by the `1/√r` of
//! `[[u^aux_,1]]`, the oscillation near the tip leaks into K: spurious
//! K_I of 2% of K_II on a sliding crack, K_II of 6% of the sliding value on
//! a stuck one (half-length 8 h). The face term therefore uses the
//! traction averaged over the pieces within [`TRACTION_BAND`] element
//! sizes along the crack (weights: piece lengths): 0.1% and 1.7%. A tip's
//! sliver piece, whose traction is a copy of its neighbour's, is left out
//! of the average (unless it is alone in the band): counted, it weighed
//! that neighbour twice next to the tip, and a closed flaw of the default
//! scene read K_I up to 8.5% of K_II at some tip positions (now 6.1%).

use std::f64::consts::PI;

use crate::discretisation::field::{Field, PointBasis};
use crate::discretisation::material::Elastic;
use crate::discretisation::quadrature::{QPoint, box_rule};
use crate::discretisation::xfem::{FacePoint, REGULAR, Xfem};
use crate::geometry::cracks::TipFrame;
use crate::geometry::plane::P2;

/// Half-width, in element sizes, of the band along the crack over which
/// the contact traction is averaged for the face term.
pub const TRACTION_BAND: f64 = 2.0;

/// K_I, K_II (Pa·√m) and T (Pa) of one tip.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sifs {
    pub k1: f64,
    pub k2: f64,
    pub t: f64,
}

/// An auxiliary field in the tip frame at one point: stress (σ11, σ22, σ12)
/// and `∂u/∂x1`.
#[derive(Clone, Copy, Debug, Default)]
struct Aux {
    s: [f64; 3],
    du1: [f64; 2],
}

/// Williams mode-I (`mode = 0`) or mode-II (`1`) field with K = 1 at local
/// polar `(r, θ)`.
fn williams(mode: usize, r: f64, th: f64, mu: f64, kappa: f64) -> Aux {
    let (s, c) = (0.5 * th).sin_cos();
    let (s3, c3) = (1.5 * th).sin_cos();
    let (st, ct) = th.sin_cos();
    let a = 1.0 / (2.0 * PI * r).sqrt();
    let (stress, g, dg) = if mode == 0 {
        (
            [c * (1.0 - s * s3), c * (1.0 + s * s3), s * c * c3],
            [
                c * (kappa - 1.0 + 2.0 * s * s),
                s * (kappa + 1.0 - 2.0 * c * c),
            ],
            [
                -0.5 * s * (kappa - 1.0 + 2.0 * s * s) + 2.0 * s * c * c,
                0.5 * c * (kappa + 1.0 - 2.0 * c * c) + 2.0 * c * s * s,
            ],
        )
    } else {
        (
            [-s * (2.0 + c * c3), s * c * c3, c * (1.0 - s * s3)],
            [
                s * (kappa + 1.0 + 2.0 * c * c),
                -c * (kappa - 1.0 - 2.0 * s * s),
            ],
            [
                0.5 * c * (kappa + 1.0 + 2.0 * c * c) - 2.0 * s * s * c,
                0.5 * s * (kappa - 1.0 - 2.0 * s * s) + 2.0 * s * c * c,
            ],
        )
    };
    let k = a / (2.0 * mu);
    Aux {
        s: stress.map(|v| v * a),
        du1: [
            k * (0.5 * ct * g[0] - st * dg[0]),
            k * (0.5 * ct * g[1] - st * dg[1]),
        ],
    }
}

/// Field of a unit point force on the tip along `e1` (for the T-stress).
fn point_force(r: f64, th: f64, mu: f64, kappa: f64) -> Aux {
    let (st, ct) = th.sin_cos();
    let a = 1.0 / (PI * r);
    Aux {
        s: [-a * ct.powi(3), -a * ct * st * st, -a * ct * ct * st],
        du1: [
            (-(kappa + 1.0) * ct / (8.0 * PI * mu) + st * st * ct / (2.0 * PI * mu)) / r,
            ((kappa - 1.0) * st / (8.0 * PI * mu) - (2.0 * th).cos() * st / (4.0 * PI * mu)) / r,
        ],
    }
}

/// Auxiliary field number `m` (0: mode I, 1: mode II, 2: point force).
fn aux(m: usize, r: f64, th: f64, el: &Elastic) -> Aux {
    let (mu, kappa) = (el.shear_modulus(), el.kappa());
    if m < 2 {
        williams(m, r, th, mu, kappa)
    } else {
        point_force(r, th, mu, kappa)
    }
}

/// Interaction integrals of one tip; `tractions[i]` is the contact traction
/// (global) at face point `i` of the discretisation (empty: none).
pub fn tip_sifs(field: &Field, crack: usize, frame: &TipFrame, r_j: f64, tractions: &[P2]) -> Sifs {
    Domain::new(field.xfem, crack, *frame, r_j).sifs(field, tractions)
}

/// One quadrature point of a domain: what its term needs besides the
/// displacement.
#[derive(Clone, Debug)]
struct DomainPoint {
    /// `∇q` in the tip frame.
    dq: P2,
    /// The quadrature weight.
    w: f64,
    /// Per auxiliary field: the field and its strain.
    aux: [(Aux, [f64; 3]); 3],
}

/// The part of one tip's interaction integral that does not depend on the
/// displacement: its domain's quadrature points (those of the elements the
/// circle `r_J` cuts, where `∇q ≠ 0`) with their shape functions, `∇q` and
/// auxiliary fields. It depends on the discretisation alone, so the
/// integrals after every solve on one discretisation share it.
#[derive(Clone, Debug)]
pub struct Domain {
    crack: usize,
    frame: TipFrame,
    r_j: f64,
    basis: PointBasis,
    points: Vec<DomainPoint>,
}

impl Domain {
    /// The domain of radius `r_j` around the tip `frame` of crack `crack`
    /// on `x`.
    pub fn new(x: &Xfem, crack: usize, frame: TipFrame, r_j: f64) -> Self {
        let m = &x.mesh;
        let el = &x.elastic;
        let q_node = |n: usize| q_at_node(x, &frame, r_j, n);
        let pad = P2::new(r_j + m.h(), r_j + m.h());
        let mut qps: Vec<QPoint> = Vec::new();
        let mut basis = PointBasis::default();
        let mut points = Vec::new();
        for e in m.elements_in_box(frame.origin - pad, frame.origin + pad, 0.0) {
            let nodes = m.element_nodes(e);
            let q: [f64; 4] = nodes.map(q_node);
            let inside = q.iter().filter(|&&v| v > 0.0).count();
            if inside == 0 || inside == 4 {
                continue;
            }
            qps.clear();
            if x.slot[e] == REGULAR {
                let (lo, hi) = m.element_box(e);
                box_rule(lo, hi, 4, &mut qps);
            } else {
                qps.extend_from_slice(&x.enriched[x.slot[e] as usize].qps);
            }
            basis.reserve(x, e, qps.len());
            for p in &qps {
                let (_, dn) = m.shape(e, p.x);
                let dq = (0..4).fold(P2::zeros(), |acc, i| acc + dn[i] * q[i]);
                let dq = P2::new(dq.dot(&frame.e1), dq.dot(&frame.e2));
                basis.push(x, e, p.x);
                let loc = frame.local(p.x);
                let (r, th) = (loc.norm(), loc.y.atan2(loc.x));
                let aux = [0, 1, 2].map(|mi| {
                    let a = aux(mi, r, th, el);
                    (a, el.strain_from_stress(a.s))
                });
                points.push(DomainPoint { dq, w: p.w, aux });
            }
        }
        basis.shrink_to_fit();
        Self {
            crack,
            frame,
            r_j,
            basis,
            points,
        }
    }

    /// `K_I`, `K_II` and `T` of the field `field` (on the discretisation
    /// the domain was made on); `tractions[i]` is the contact traction
    /// (global) at face point `i` (empty: none).
    pub fn sifs(&self, field: &Field, tractions: &[P2]) -> Sifs {
        let x = field.xfem;
        let m = &x.mesh;
        let el = &x.elastic;
        let (frame, r_j, crack) = (&self.frame, self.r_j, self.crack);
        let q_node = |n: usize| q_at_node(x, frame, r_j, n);
        let mut integral = [0.0; 3];
        for (i, p) in self.points.iter().enumerate() {
            let v = field.at_point(&self.basis, i);
            let s = field.stress(&v);
            let sl = rotate_stress(s, frame);
            let gl = rotate_grad(v.grad, frame);
            let dq = p.dq;
            for (out, (a, ea)) in integral.iter_mut().zip(&p.aux) {
                let w = sl[0] * ea[0] + sl[1] * ea[1] + sl[2] * ea[2];
                // j = 1
                let t1 =
                    sl[0] * a.du1[0] + sl[2] * a.du1[1] + a.s[0] * gl[0][0] + a.s[2] * gl[1][0] - w;
                // j = 2
                let t2 =
                    sl[2] * a.du1[0] + sl[1] * a.du1[1] + a.s[2] * gl[0][0] + a.s[1] * gl[1][0];
                *out += (t1 * dq.x + t2 * dq.y) * p.w * x.thickness;
            }
        }
        // crack-face term with the contact tractions
        if !tractions.is_empty() {
            let faces: Vec<(&FacePoint, P2)> = x
                .faces
                .iter()
                .zip(tractions)
                .filter(|(fp, _)| fp.crack == crack)
                .map(|(fp, p)| (fp, *p))
                .collect();
            let band = TRACTION_BAND * m.h();
            for &(fp, _) in &faces {
                let e = x.enriched[fp.slot].elem;
                let qn: [f64; 4] = m.element_nodes(e).map(q_node);
                if qn.iter().all(|&v| v == 0.0) {
                    continue;
                }
                // a tip sliver's traction is a copy of its neighbour's, not a
                // sample of its own: counted, it weighs that neighbour twice
                // where the face term's weight 1/√r is largest
                let average = |own: bool| {
                    faces
                        .iter()
                        .filter(|(other, _)| {
                            (other.s - fp.s).abs() <= band && (own || other.follows.is_none())
                        })
                        .fold((P2::zeros(), 0.0), |(sum, w), (other, p)| {
                            (sum + p * other.w, w + other.w)
                        })
                };
                let (sum, weight) = match average(false) {
                    (_, 0.0) => average(true),
                    a => a,
                };
                let p = sum / weight;
                if p == P2::zeros() {
                    continue;
                }
                // the + side (φ > 0) is on the e2 side when n·e2 > 0
                let plus = if fp.n.dot(&frame.e2) >= 0.0 { PI } else { -PI };
                let pl = P2::new(p.dot(&frame.e1), p.dot(&frame.e2));
                for qp in &fp.qps {
                    let (nsh, _) = m.shape(e, qp.x);
                    let q = (0..4).map(|i| nsh[i] * qn[i]).sum::<f64>();
                    if q <= 0.0 {
                        continue;
                    }
                    let r = frame.local(qp.x).norm();
                    for (mi, out) in integral.iter_mut().enumerate() {
                        let up = aux(mi, r, plus, el).du1;
                        let dn = aux(mi, r, -plus, el).du1;
                        *out += (pl.x * (up[0] - dn[0]) + pl.y * (up[1] - dn[1])) * q * qp.w;
                    }
                }
            }
        }
        let ep = el.e_prime();
        let t = x.thickness;
        Sifs {
            k1: 0.5 * ep * integral[0] / t,
            k2: 0.5 * ep * integral[1] / t,
            t: ep * integral[2] / t,
        }
    }
}

/// `q` at node `n`: 1 within `r_j` of the tip, 0 outside.
fn q_at_node(x: &Xfem, frame: &TipFrame, r_j: f64, n: usize) -> f64 {
    if (x.mesh.node_pos(n) - frame.origin).norm() < r_j {
        1.0
    } else {
        0.0
    }
}

/// Stress `[σ11, σ22, σ12]` in the tip frame.
fn rotate_stress(s: [f64; 3], f: &TipFrame) -> [f64; 3] {
    let (c, sn) = (f.e1.x, f.e1.y);
    let s11 = c * c * s[0] + sn * sn * s[1] + 2.0 * c * sn * s[2];
    let s22 = sn * sn * s[0] + c * c * s[1] - 2.0 * c * sn * s[2];
    let s12 = -c * sn * s[0] + c * sn * s[1] + (c * c - sn * sn) * s[2];
    [s11, s22, s12]
}

/// Displacement gradient in the tip frame: `R G Rᵀ` with `R = [e1; e2]`.
fn rotate_grad(g: [[f64; 2]; 2], f: &TipFrame) -> [[f64; 2]; 2] {
    let r = [[f.e1.x, f.e1.y], [f.e2.x, f.e2.y]];
    let mut out = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            for a in 0..2 {
                for b in 0..2 {
                    out[i][j] += r[i][a] * g[a][b] * r[j][b];
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn williams_derivative_matches_finite_difference_of_displacement() {
        // u = 1/(2μ) √(r/2π) g(θ); check ∂u/∂x1 by differencing u in x1
        let (mu, kappa) = (1.3, 1.8);
        let disp = |mode: usize, x1: f64, x2: f64| {
            let r = (x1 * x1 + x2 * x2).sqrt();
            let th = x2.atan2(x1);
            let (s, c) = (0.5 * th).sin_cos();
            let g = if mode == 0 {
                [
                    c * (kappa - 1.0 + 2.0 * s * s),
                    s * (kappa + 1.0 - 2.0 * c * c),
                ]
            } else {
                [
                    s * (kappa + 1.0 + 2.0 * c * c),
                    -c * (kappa - 1.0 - 2.0 * s * s),
                ]
            };
            let k = (r / (2.0 * PI)).sqrt() / (2.0 * mu);
            [k * g[0], k * g[1]]
        };
        for mode in 0..2 {
            for &(x1, x2) in &[(0.3, 0.2), (-0.2, 0.15), (0.1, -0.4)] {
                let h = 1e-6;
                let (p, m) = (disp(mode, x1 + h, x2), disp(mode, x1 - h, x2));
                let r = f64::hypot(x1, x2);
                let a = williams(mode, r, x2.atan2(x1), mu, kappa);
                for c in 0..2 {
                    let fd = (p[c] - m[c]) / (2.0 * h);
                    assert!(
                        (fd - a.du1[c]).abs() < 1e-7,
                        "mode {mode} comp {c}: {fd} vs {}",
                        a.du1[c]
                    );
                }
            }
        }
    }
}
