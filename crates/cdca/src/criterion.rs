//! Fracture criteria at a free tip (SPEC §8).
//!
//! Comprehensive (the paper's): tensile first, `θ0 = argmax σ_θθ(θ, r0)`,
//! grows in tension if `σ_θθ(θ0) ≥ σ_t`; otherwise shear,
//! `θ1 = argmax |τ_rθ(θ, r0)|`, grows if `|τ_rθ(θ1)| ≥ max(σ_n, 0) tan φ + c`
//! with `σ_n = −σ_θθ(θ1)`. MTS (Erdogan–Sih) and its T-stress variant are
//! offered for comparison.

use std::f64::consts::PI;

use crate::cracks::TipFrame;
use crate::geometry::P2;
use crate::report::{CriterionReport, Mode};
use crate::scene::{CriterionKind, Material};
use crate::sif::Sifs;

/// Largest kink angle searched, degrees. Beyond ±90° a crack would grow
/// backwards, into its own faces; the circle there lies on the flaw.
pub const MAX_KINK_DEG: f64 = 90.0;

/// Number of samples on the circle (one every half degree, ±MAX_KINK_DEG).
const SAMPLES: usize = 361;

/// Angle of sample `i`, rad.
fn sample_angle(i: usize) -> f64 {
    (-MAX_KINK_DEG + 2.0 * MAX_KINK_DEG * i as f64 / (SAMPLES - 1) as f64).to_radians()
}

/// σ_θθ and τ_rθ sampled on the circle r0 around a tip.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Circle {
    /// Angles in the tip frame, rad.
    pub theta: Vec<f64>,
    pub sigma_tt: Vec<f64>,
    pub tau_rt: Vec<f64>,
}

/// Settings resolved from the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CriterionParams {
    pub kind: CriterionKind,
    /// m
    pub r0: f64,
    /// Tensile strength σ_t, Pa.
    pub sigma_t: f64,
    /// Rock cohesion c, Pa, and friction angle φ, rad.
    pub cohesion: f64,
    pub friction_angle: f64,
    /// K_IC, Pa·√m.
    pub k_ic: f64,
}

impl CriterionParams {
    pub fn new(kind: CriterionKind, r0: f64, m: &Material) -> Self {
        Self {
            kind,
            r0,
            sigma_t: m
                .tensile_strength
                .unwrap_or(m.k_ic / (2.0 * PI * r0).sqrt()),
            cohesion: m.cohesion,
            friction_angle: m.friction_angle_deg.to_radians(),
            k_ic: m.k_ic,
        }
    }
}

/// Samples the circle from a stress function (global σxx, σyy, τxy);
/// points where it gives `None` (outside the body) are skipped.
pub fn sample_field(frame: &TipFrame, r0: f64, stress: &dyn Fn(P2) -> Option<[f64; 3]>) -> Circle {
    let mut c = Circle::default();
    for i in 0..SAMPLES {
        let th = sample_angle(i);
        let er = frame.global(P2::new(th.cos(), th.sin()));
        let et = frame.global(P2::new(-th.sin(), th.cos()));
        let Some(s) = stress(frame.origin + r0 * er) else {
            continue;
        };
        let traction =
            |a: P2, b: P2| a.x * (s[0] * b.x + s[2] * b.y) + a.y * (s[2] * b.x + s[1] * b.y);
        c.theta.push(th);
        c.sigma_tt.push(traction(et, et));
        c.tau_rt.push(traction(er, et));
    }
    c
}

/// Samples the circle from the Williams expansion with K_I, K_II and T.
pub fn sample_williams(s: &Sifs, r0: f64) -> Circle {
    let mut c = Circle::default();
    let a = 1.0 / (2.0 * PI * r0).sqrt();
    for i in 0..SAMPLES {
        let th = sample_angle(i);
        let hc = (0.5 * th).cos();
        let (st, ct) = th.sin_cos();
        c.theta.push(th);
        c.sigma_tt
            .push(a * hc * (s.k1 * hc * hc - 1.5 * s.k2 * st) + s.t * st * st);
        c.tau_rt
            .push(0.5 * a * hc * (s.k1 * st + s.k2 * (3.0 * ct - 1.0)) - s.t * st * ct);
    }
    c
}

/// Half width of the window fitted around a maximum, rad.
const FIT_WINDOW_DEG: f64 = 10.0;

/// Angle and value of the largest sample, refined by a least-squares
/// parabola over the samples within ±10° of it: robust to flat or slightly
/// split peaks of a sampled (discretised) field. Falls back to the sample
/// when the fit has no interior maximum.
fn argmax(theta: &[f64], v: &[f64]) -> Option<(f64, f64)> {
    let i = (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b]))?;
    let w = FIT_WINDOW_DEG.to_radians();
    let t0 = theta[i];
    // normal equations of v ≈ a + b x + c x² with x = θ − θ_i
    let mut m = nalgebra::Matrix3::<f64>::zeros();
    let mut r = nalgebra::Vector3::<f64>::zeros();
    for (t, y) in theta.iter().zip(v) {
        let x = t - t0;
        if x.abs() > w {
            continue;
        }
        let p = nalgebra::Vector3::new(1.0, x, x * x);
        m += p * p.transpose();
        r += p * *y;
    }
    let Some(c) = m.lu().solve(&r) else {
        return Some((t0, v[i]));
    };
    if c[2] >= 0.0 {
        return Some((t0, v[i]));
    }
    let x = -c[1] / (2.0 * c[2]);
    if x.abs() > w || t0 + x < theta[0] || t0 + x > theta[theta.len() - 1] {
        return Some((t0, v[i]));
    }
    Some((t0 + x, v[i].max(c[0] + c[1] * x + c[2] * x * x)))
}

/// Decision of the chosen criterion at one tip.
pub fn decide(p: &CriterionParams, circle: &Circle, s: &Sifs) -> CriterionReport {
    let sigma_theta_max = circle
        .sigma_tt
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    let tau_max = circle.tau_rt.iter().map(|v| v.abs()).fold(0.0, f64::max);
    let mut out = CriterionReport {
        mode: Mode::None,
        angle_deg: 0.0,
        sigma_theta_max: if sigma_theta_max.is_finite() {
            sigma_theta_max
        } else {
            0.0
        },
        tau_max,
    };
    match p.kind {
        CriterionKind::Comprehensive => {
            let Some((t0, s0)) = argmax(&circle.theta, &circle.sigma_tt) else {
                return out;
            };
            if s0 >= p.sigma_t {
                out.mode = Mode::Tension;
                out.angle_deg = t0.to_degrees();
                return out;
            }
            let abs_tau: Vec<f64> = circle.tau_rt.iter().map(|v| v.abs()).collect();
            let Some((t1, tau)) = argmax(&circle.theta, &abs_tau) else {
                return out;
            };
            let sigma_n = -interpolate(&circle.theta, &circle.sigma_tt, t1);
            out.angle_deg = t1.to_degrees();
            if tau >= sigma_n.max(0.0) * p.friction_angle.tan() + p.cohesion {
                out.mode = Mode::Shear;
            } else {
                out.angle_deg = t0.to_degrees();
            }
        }
        CriterionKind::Mts => {
            let th = mts_angle(s.k1, s.k2);
            out.angle_deg = th.to_degrees();
            let hc = (0.5 * th).cos();
            let keq = s.k1 * hc.powi(3) - 1.5 * s.k2 * hc * th.sin();
            if keq >= p.k_ic {
                out.mode = Mode::Tension;
            }
        }
        CriterionKind::MtsT => {
            let w = sample_williams(s, p.r0);
            if let Some((th, smax)) = argmax(&w.theta, &w.sigma_tt) {
                out.angle_deg = th.to_degrees();
                if smax * (2.0 * PI * p.r0).sqrt() >= p.k_ic {
                    out.mode = Mode::Tension;
                }
            }
        }
    }
    out
}

/// Erdogan–Sih kink angle `θc = 2 arctan[(K_I − √(K_I² + 8K_II²)) / (4K_II)]`.
pub fn mts_angle(k1: f64, k2: f64) -> f64 {
    if k2.abs() <= 1e-14 * k1.abs().max(1e-300) {
        return 0.0;
    }
    2.0 * ((k1 - (k1 * k1 + 8.0 * k2 * k2).sqrt()) / (4.0 * k2)).atan()
}

/// Linear interpolation of samples at angle `t`.
fn interpolate(theta: &[f64], v: &[f64], t: f64) -> f64 {
    let i = theta.partition_point(|&a| a < t);
    if i == 0 {
        return v[0];
    }
    if i >= theta.len() {
        return v[v.len() - 1];
    }
    let s = (t - theta[i - 1]) / (theta[i] - theta[i - 1]);
    v[i - 1] + s * (v[i] - v[i - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Erdogan–Sih: K_I = K_II gives θc = −53.13°; pure mode II −70.53°.
    #[test]
    fn mts_angles_match_closed_form() {
        assert!((mts_angle(1.0, 1.0).to_degrees() + 53.130_102).abs() < 1e-5);
        assert!((mts_angle(0.0, 1.0).to_degrees() + 70.528_779).abs() < 1e-5);
        assert_eq!(mts_angle(1.0, 0.0), 0.0);
    }

    /// The Williams circle's σ_θθ maximum reproduces the MTS angle.
    #[test]
    fn williams_sampling_peaks_at_mts_angle() {
        let s = Sifs {
            k1: 1e6,
            k2: 1e6,
            t: 0.0,
        };
        let c = sample_williams(&s, 0.01);
        let (th, _) = argmax(&c.theta, &c.sigma_tt).expect("samples");
        assert!((th.to_degrees() + 53.13).abs() < 0.1, "{}", th.to_degrees());
    }
}
