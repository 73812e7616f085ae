//! Enrichment functions of the extended finite element approximation
//! (SPEC §3):
//!
//! `u(x) = Σ N_I u_I + Σ_J N_J [H(x) − H(x_J)] a_J + Σ_K N_K Σ_l [F_l(x) − F_l(x_K)] b_K^l`
//!
//! with `H = sign φ` (0 counts as +; for a crack ending on another crack the
//! junction function `H · [x on the crack's side of the main crack]`) and the
//! branch functions `F = √r {sin θ/2, cos θ/2, sin θ sin θ/2, sin θ cos θ/2}`
//! in the tip frame.

use crate::geometry::cracks::{Crack, TipFrame, TipKind, junction_side};
use crate::geometry::plane::P2;

/// One enrichment a node can carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Enrichment {
    /// Heaviside (or junction) function of a crack: 1 scalar function.
    Heaviside { crack: usize },
    /// The four branch functions of a free tip: 4 scalar functions.
    Tip { crack: usize, tip: usize },
}

impl Enrichment {
    /// Number of scalar functions (each carries an x and a y DOF).
    pub fn functions(self) -> usize {
        match self {
            Self::Heaviside { .. } => 1,
            Self::Tip { .. } => 4,
        }
    }
}

/// Values and gradients of an enrichment's scalar functions at a point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnrValue {
    pub f: [f64; 4],
    pub g: [P2; 4],
}

/// The cracks as seen by the enrichment functions, with the junction data
/// needed by the Heaviside functions precomputed.
#[derive(Clone, Debug)]
pub struct EnrichmentFunctions {
    pub cracks: Vec<Crack>,
    /// Per crack: `(main crack, reference sign)` of each junction tip.
    junctions: Vec<Vec<(usize, f64)>>,
    frames: Vec<[TipFrame; 2]>,
    /// Distance below which φ counts as 0 (and so as positive).
    snap: f64,
}

impl EnrichmentFunctions {
    pub fn new(cracks: Vec<Crack>, snap: f64) -> Self {
        let junctions = cracks
            .iter()
            .map(|c| {
                (0..2)
                    .filter_map(|k| match c.tips[k] {
                        TipKind::Junction { main } => {
                            Some((main, junction_side(c, k, &cracks[main])))
                        }
                        _ => None,
                    })
                    .collect()
            })
            .collect();
        let frames = cracks
            .iter()
            .map(|c| [TipFrame::of(c, 0), TipFrame::of(c, 1)])
            .collect();
        Self {
            cracks,
            junctions,
            frames,
            snap,
        }
    }

    pub fn frame(&self, crack: usize, tip: usize) -> &TipFrame {
        &self.frames[crack][tip]
    }

    /// Sign of φ_j with 0 (within the snapping distance) counted as +1.
    pub fn side(&self, crack: usize, x: P2) -> f64 {
        if self.cracks[crack].phi(x) >= -self.snap {
            1.0
        } else {
            -1.0
        }
    }

    /// The Heaviside/junction function of crack `j` at `x` (±1, or 0 on the
    /// far side of a main crack it ends on).
    pub fn heaviside(&self, j: usize, x: P2) -> f64 {
        for &(main, reference) in &self.junctions[j] {
            if self.side(main, x) != reference {
                return 0.0;
            }
        }
        self.side(j, x)
    }

    /// Values and gradients of an enrichment at `x`.
    pub fn eval(&self, e: Enrichment, x: P2) -> EnrValue {
        self.eval_sided(e, x, None)
    }

    /// Like [`eval`](Self::eval), but a point on crack `face.0` is taken on
    /// its side `face.1` (±1): used for the jumps at crack-face points.
    pub fn eval_sided(&self, e: Enrichment, x: P2, face: Option<(usize, f64)>) -> EnrValue {
        match e {
            Enrichment::Heaviside { crack } => {
                let mut v = EnrValue::default();
                v.f[0] = match face {
                    Some((c, side)) if c == crack => {
                        let mask = self.junctions[crack]
                            .iter()
                            .all(|&(m, r)| self.side(m, x) == r);
                        if mask { side } else { 0.0 }
                    }
                    _ => self.heaviside(crack, x),
                };
                v
            }
            Enrichment::Tip { crack, tip } => {
                let (phi, grad) = match face {
                    Some((c, side)) if c == crack => {
                        (if side > 0.0 { 0.0 } else { -0.0 }, P2::zeros())
                    }
                    _ => crate::geometry::plane::level_set(x, &self.cracks[crack].points),
                };
                branch(self.frame(crack, tip), x, phi, grad)
            }
        }
    }
}

/// Branch functions and their global gradients at `x` for a tip, in the
/// level-set coordinates `r = √(φ² + ψ²)`, `θ = atan2(φ, ψ)` with
/// `ψ = (x − x_tip)·e1`: the discontinuity at θ = ±π follows the crack
/// itself, kinks included. For a straight crack these are the polar
/// coordinates of the tip frame (up to θ → −θ at tip 0, which leaves the
/// span of the four functions unchanged).
pub fn branch(frame: &TipFrame, x: P2, phi: f64, grad_phi: P2) -> EnrValue {
    let psi = (x - frame.origin).dot(&frame.e1);
    let r = phi.hypot(psi);
    let mut v = EnrValue::default();
    if r <= 0.0 {
        return v; // values vanish at the tip; gradients are never needed there
    }
    let grad_r = (grad_phi * phi + frame.e1 * psi) / r;
    let grad_th = (grad_phi * psi - frame.e1 * phi) / (r * r);
    let sr = r.sqrt();
    // sin θ, cos θ and the half angles without trigonometry (this runs at
    // every quadrature point of every tip element): cos(θ/2) ≥ 0 on
    // θ ∈ [−π, π], sin(θ/2) takes φ's sign (θ = ±π on the faces behind
    // the tip, as atan2 of a signed zero), and each from the side where
    // it does not cancel
    let (s, c) = (phi / r, psi / r);
    let (s2, c2) = if psi >= 0.0 {
        let c2 = ((r + psi) / (2.0 * r)).sqrt();
        (phi / (2.0 * r * c2), c2)
    } else {
        let s2 = ((r - psi) / (2.0 * r)).sqrt().copysign(phi);
        (s2, phi / (2.0 * r * s2))
    };
    let f = [sr * s2, sr * c2, sr * s * s2, sr * s * c2];
    // ∂F/∂r and ∂F/∂θ
    let fr = [
        f[0] / (2.0 * r),
        f[1] / (2.0 * r),
        f[2] / (2.0 * r),
        f[3] / (2.0 * r),
    ];
    let ft = [
        0.5 * sr * c2,
        -0.5 * sr * s2,
        sr * (c * s2 + 0.5 * s * c2),
        sr * (c * c2 - 0.5 * s * s2),
    ];
    for i in 0..4 {
        v.f[i] = f[i];
        v.g[i] = grad_r * fr[i] + grad_th * ft[i];
    }
    v
}

/// Branch functions of a straight crack along the tip frame's `e1` axis.
#[cfg(test)]
fn branch_straight(frame: &TipFrame, x: P2) -> EnrValue {
    branch(frame, x, (x - frame.origin).dot(&frame.e2), frame.e2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn branch_gradients_match_finite_differences() {
        let frame = TipFrame {
            origin: P2::new(0.3, 0.2),
            e1: P2::new(0.6, 0.8),
            e2: P2::new(-0.8, 0.6),
        };
        let x = P2::new(0.1, 0.45);
        let v = branch_straight(&frame, x);
        let h = 1e-7;
        for i in 0..4 {
            let dx = (branch_straight(&frame, x + P2::new(h, 0.0)).f[i]
                - branch_straight(&frame, x - P2::new(h, 0.0)).f[i])
                / (2.0 * h);
            let dy = (branch_straight(&frame, x + P2::new(0.0, h)).f[i]
                - branch_straight(&frame, x - P2::new(0.0, h)).f[i])
                / (2.0 * h);
            assert!(
                (dx - v.g[i].x).abs() < 1e-6 && (dy - v.g[i].y).abs() < 1e-6,
                "F{i}"
            );
        }
    }

    /// Reference: the four functions `√r (sin θ/2, cos θ/2, sin θ sin θ/2,
    /// sin θ cos θ/2)` with θ from atan2, around the tip (θ near 0, ±π/2
    /// and on the faces behind it, φ = ±0 exactly: θ = ±π), to 1e-15.
    #[test]
    fn branch_functions_match_their_trigonometric_form() {
        let frame = TipFrame {
            origin: P2::new(0.0, 0.0),
            e1: P2::new(1.0, 0.0),
            e2: P2::new(0.0, 1.0),
        };
        let points = [
            (0.3, 1e-9),
            (0.3, -1e-9),
            (1e-9, 0.4),
            (-0.2, 0.7),
            (-0.5, 1e-12),
            (-0.5, 0.0),
            (-0.5, -0.0),
            (0.1, -0.9),
        ];
        for (psi, phi) in points {
            let v = branch(&frame, P2::new(psi, phi), phi, frame.e2);
            let (r, th) = (f64::hypot(phi, psi), f64::atan2(phi, psi));
            let (s2, c2) = (0.5 * th).sin_cos();
            let want = [s2, c2, th.sin() * s2, th.sin() * c2].map(|f| r.sqrt() * f);
            for (i, (got, want)) in v.f.iter().zip(want).enumerate() {
                assert!(
                    (got - want).abs() <= 1e-15,
                    "F{i} at ψ {psi}, φ {phi}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn first_branch_function_jumps_by_two_root_r_across_the_faces() {
        let frame = TipFrame {
            origin: P2::new(0.0, 0.0),
            e1: P2::new(1.0, 0.0),
            e2: P2::new(0.0, 1.0),
        };
        let up = branch_straight(&frame, P2::new(-0.25, 1e-14));
        let dn = branch_straight(&frame, P2::new(-0.25, -1e-14));
        assert!((up.f[0] - dn.f[0] - 2.0 * 0.5).abs() < 1e-12);
        for i in 1..4 {
            assert!((up.f[i] - dn.f[i]).abs() < 1e-12);
        }
    }
}
