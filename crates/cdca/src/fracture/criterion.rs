//! Fracture criteria at a free tip (SPEC §8).
//!
//! Comprehensive (the paper's), one rule at every free tip: tensile first,
//! `θ0 = argmax σ_θθ(θ, r0)`, grows in tension if `σ_θθ(θ0) ≥ σ_t`;
//! otherwise shear on the Mohr–Coulomb critical plane of the circle,
//! `θ1 = argmax |τ_rθ(θ, r0)| / (max(σ_n(θ), 0) μ_s + c_s)` with
//! `σ_n = −σ_θθ`, grows if that ratio reaches 1, with the envelope of
//! [`ShearStrength`]. The radius follows the crack's size
//! ([`CriterionParams::for_crack`]). MTS (Erdogan–Sih) and its T-stress
//! variant are offered for comparison.

use std::f64::consts::PI;

use crate::fracture::sif::Sifs;
use crate::geometry::cracks::TipFrame;
use crate::geometry::plane::P2;
use crate::report::{CriterionReport, Mode};
use crate::scene::{CriterionKind, Material, Scene, ShearStrength};

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

impl Circle {
    /// Adds the sample at angle `th` of the global stress `s` (σxx, σyy,
    /// τxy), with the circle's radial and tangential unit vectors `er`,
    /// `et` there: `σ_θθ = e_θ·σ·e_θ`, `τ_rθ = e_r·σ·e_θ`.
    pub fn push(&mut self, th: f64, s: [f64; 3], er: P2, et: P2) {
        let traction =
            |a: P2, b: P2| a.x * (s[0] * b.x + s[2] * b.y) + a.y * (s[2] * b.x + s[1] * b.y);
        self.theta.push(th);
        self.sigma_tt.push(traction(et, et));
        self.tau_rt.push(traction(er, et));
    }
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
    /// K_IIC, Pa·√m.
    pub k_iic: f64,
    /// The shear branch's envelope; `None`: the criterion has none (MTS).
    pub shear: Option<ShearStrength>,
    /// Whether the scene gives r0 (`criterion.r0`); if not, r0 follows
    /// the crack's size ([`for_crack`](Self::for_crack)).
    pub radius_given: bool,
}

/// Smallest half-length over process-zone size, `a / r_p`, at which a crack
/// is long enough for linear elastic fracture mechanics: ASTM E399's size
/// requirement `a ≥ 2.5 (K_IC/σ_t)²` with `r_p = (K_IC/σ_t)² / 2π` is
/// `a ≥ 5π r_p`.
pub const LEFM_SIZE_RATIO: f64 = 5.0 * PI;

/// The faces of the crack whose tip is evaluated: friction coefficient μ,
/// cohesion c_c (Pa), and whether the faces next to the tip are in contact.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Faces {
    pub friction: f64,
    pub cohesion: f64,
    /// Most of the face length within two element sizes of the tip is
    /// closed (stick or slip).
    pub closed: bool,
}

impl Faces {
    /// What a crack starting at a kink (a secondary-crack site) meets: it
    /// is driven by the kinked crack's faces sliding (the branch applies
    /// where they are `closed`), but it breaks intact rock, so the Faces
    /// envelope's pressure term is the rock's `tan φ` (SPEC §8's own term)
    /// and the faces' cohesion does not count: `σ_n tan φ + K_IIC/√(2π r0)`.
    pub fn at_kink(params: &CriterionParams, closed: bool) -> Self {
        Self {
            friction: params.friction_angle.tan(),
            cohesion: 0.0,
            closed,
        }
    }
}

impl CriterionParams {
    /// The scene's settings, with the defaults resolved by
    /// [`radius_and_strength`].
    pub fn of_scene(scene: &Scene) -> Self {
        let m = &scene.material;
        let criterion = scene.criterion_settings();
        let (r0, sigma_t) = radius_and_strength(criterion.r0(), m);
        Self {
            kind: criterion.kind(),
            r0,
            sigma_t,
            cohesion: m.cohesion,
            friction_angle: m.friction_angle_deg.to_radians(),
            k_ic: m.k_ic,
            k_iic: m.k_iic,
            shear: criterion.shear_strength(),
            radius_given: criterion.r0().is_some(),
        }
    }

    /// The settings at a tip of a crack of total length `length` (m).
    ///
    /// With r0 given by the scene, the scene's settings. Otherwise r0 is
    /// the process-zone size `r_p` of [`radius_and_strength`] for a crack
    /// whose half-length `a` is at least [`LEFM_SIZE_RATIO`]` r_p`, and
    /// `a / LEFM_SIZE_RATIO` for a shorter one, with σ_t raised to
    /// `σ_t √(r_p / r0)` so that the tensile check in a pure mode-I field
    /// is still `K_I ≥ K_IC`.
    ///
    /// Why: on a flaw only a few r_p long the circle r_p lies outside the
    /// flaw's K-dominated zone and reads the far field. Under uniaxial
    /// compression that field's compression cancels the sliding flaw's
    /// tension at r_p, so a 3.5 mm flaw (a = 1.3 r_p) grew coplanar in
    /// shear, where experiments and the sliding-crack model (the wing's
    /// `K_I = (2/√3) K_II`) give tension wings at every flaw size. The
    /// criterion is a tip criterion only where LEFM holds, so r0 is kept
    /// inside that zone. The rule depends on the crack's current length
    /// alone: the same at every tip, drawn or grown, and a saved scene
    /// carries it.
    #[must_use]
    pub fn for_crack(&self, length: f64) -> Self {
        let limit = 0.5 * length / LEFM_SIZE_RATIO;
        if self.radius_given || limit >= self.r0 || limit <= 0.0 {
            return *self;
        }
        Self {
            r0: limit,
            sigma_t: self.sigma_t * (self.r0 / limit).sqrt(),
            ..*self
        }
    }

    /// Friction coefficient and cohesion (Pa) of the shear branch at a tip
    /// of a crack with `faces`, or `None` where the branch does not apply:
    /// see [`ShearStrength`] (and none for MTS).
    ///
    /// The `Faces` envelope is the crack's own faces extending in shear, a
    /// sliding mechanism: it needs those faces in contact next to the tip.
    /// At an open tip (a tensile wing) the faces carry no friction and the
    /// tip's own field is mode I, whose tension comes first (K_IIC > K_IC);
    /// the peak of |τ_rθ| there is the bulk's compression (the T-stress),
    /// not the tip. Checked there too, it turned wings under uniaxial
    /// compression ±40° in shear once the load passed about 110 MPa, then
    /// back in tension from the closed segment that left: a zig-zag
    /// instead of wings parallel to the load.
    pub fn shear_envelope(&self, faces: Faces) -> Option<(f64, f64)> {
        match self.shear? {
            ShearStrength::Faces if !faces.closed => None,
            ShearStrength::Faces => Some((
                faces.friction,
                faces.cohesion + self.k_iic / (2.0 * PI * self.r0).sqrt(),
            )),
            ShearStrength::Rock => Some((self.friction_angle.tan(), self.cohesion)),
        }
    }
}

/// The circle radius r0 (m) and tensile strength σ_t (Pa). Each one left
/// out follows from the other through `σ_t = K_IC / √(2π r0)`, so that in a
/// pure mode-I field the tensile check is `K_I ≥ K_IC`; with neither given
/// σ_t is the Mohr–Coulomb [`tension_cutoff`](Material::tension_cutoff) of c and φ and
/// `r0 = (K_IC/σ_t)² / 2π`, the size of the tip's process (plastic) zone
/// (Irwin's estimate). Both given: used as they are.
pub fn radius_and_strength(r0: Option<f64>, m: &Material) -> (f64, f64) {
    match (r0, m.tensile_strength) {
        (Some(r0), Some(st)) => (r0, st),
        (Some(r0), None) => (r0, m.k_ic / (2.0 * PI * r0).sqrt()),
        (None, _) => (m.process_zone(m.tensile()), m.tensile()),
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
        c.push(th, s, er, et);
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

/// σ_θθ and τ_rθ at angle `th` of a uniform stress `[σ11, σ22, σ12]` given
/// in the tip frame.
fn polar(s: [f64; 3], th: f64) -> (f64, f64) {
    let (st, ct) = th.sin_cos();
    (
        s[0] * st * st + s[1] * ct * ct - 2.0 * s[2] * st * ct,
        (s[1] - s[0]) * st * ct + s[2] * (ct * ct - st * st),
    )
}

/// Samples the circle as the singular Williams terms with the
/// interaction-integral K_I, K_II at r0 plus the uniform (r⁰) stress at the
/// tip, `uniform = [σ11, σ22, σ12]` in the tip frame (see
/// [`uniform_stress`]). The result follows the K-field at any r0, however
/// small against the element size, and carries the normal and shear
/// tractions of a closed crack's faces, which the traction-free expansion
/// ([`sample_williams`]) lacks.
///
/// The singular term uses `K_I⁺ = max(K_I, 0)`: faces cannot pass through
/// each other, so a closed tip has K_I = 0 and its compression is the
/// faces' σ22 of the uniform term. A negative K_I is the compliance of the
/// contact law (a joint of 200 GPa/m lets compressed faces overlap by
/// σ_n/k_N ≈ 0.25 mm, about an element); counted in the singular term as
/// well it pushed the tension kink of a sliding tip from the classic ≈70°
/// to the ±90° search limit, and closed wings saw-toothed at ±90°.
pub fn sample_hybrid(s: &Sifs, uniform: [f64; 3], r0: f64) -> Circle {
    let singular = Sifs {
        k1: s.k1.max(0.0),
        t: 0.0,
        ..*s
    };
    let mut c = sample_williams(&singular, r0);
    for (i, &th) in c.theta.iter().enumerate() {
        let (stt, trt) = polar(uniform, th);
        c.sigma_tt[i] += stt;
        c.tau_rt[i] += trt;
    }
    c
}

/// Uniform part of the stress at a tip, `[σ11, σ22, σ12]` in the tip frame,
/// from the stress `f = [σ12, σ22]` that the faces next to the tip carry
/// (zero when open) and the interaction-integral T. The faces' boundary
/// condition fixes σ22 and σ12; the point-force interaction integral
/// measures `σ11 − σ22` (T = 0 on a closed 45° crack in biaxial compression,
/// where σ11 = σ22 = −σ_n; T = 7.5 MPa on a closed 30° crack with
/// σ11 − σ22 = 7.5 MPa), so `σ11 = T + σ22`. On an open crack this is
/// `[T, 0, 0]`.
pub fn uniform_stress(s: &Sifs, f: P2) -> [f64; 3] {
    [s.t + f.y, f.y, f.x]
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
pub fn decide(p: &CriterionParams, circle: &Circle, s: &Sifs, faces: Faces) -> CriterionReport {
    assess(p, circle, s, faces).0
}

/// Demand over strength, `d / s`, of one check `d ≥ s`: ≥ 1 exactly when
/// the check passes (∞ when it passes against a strength ≤ 0, 0 when it
/// fails there).
fn ratio(demand: f64, strength: f64) -> f64 {
    if strength > 0.0 {
        demand / strength
    } else if demand >= strength {
        f64::INFINITY
    } else {
        0.0
    }
}

/// The decision of the chosen criterion at one tip, and its utilisation:
/// the largest demand-over-strength ratio of its checks, ≥ 1 exactly when
/// the tip grows. Comprehensive: `max(σ_θθ(θ0)/σ_t,
/// |τ_rθ(θ1)| / (max(σ_n, 0) μ_s + c_s))`; MTS: `K_eq / K_IC`; MTS with T:
/// `σ_θθ,max √(2π r0) / K_IC`. The growth driver's λ_cr search (SPEC §9,
/// critical control) finds the load at which the largest one over the
/// free tips reaches 1.
pub fn assess(
    p: &CriterionParams,
    circle: &Circle,
    s: &Sifs,
    faces: Faces,
) -> (CriterionReport, f64) {
    let mut utilisation = 0.0;
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
                return (out, utilisation);
            };
            utilisation = ratio(s0, p.sigma_t);
            if s0 >= p.sigma_t {
                out.mode = Mode::Tension;
                out.angle_deg = t0.to_degrees();
                return (out, utilisation);
            }
            out.angle_deg = t0.to_degrees();
            let Some((friction, cohesion)) = p.shear_envelope(faces) else {
                return (out, utilisation);
            };
            // the Mohr–Coulomb critical plane: the largest demand over
            // strength on the circle
            let strength_at = |stt: f64| (-stt).max(0.0) * friction + cohesion;
            let demand: Vec<f64> = circle
                .tau_rt
                .iter()
                .zip(&circle.sigma_tt)
                // a plane without strength (no cohesion, σ_n ≤ 0) counts as
                // 10⁶ times over: finite, for the fit of the peak
                .map(|(t, s)| ratio(t.abs(), strength_at(*s)).min(1e6))
                .collect();
            let Some((t1, _)) = argmax(&circle.theta, &demand) else {
                return (out, utilisation);
            };
            let tau = interpolate(&circle.theta, &circle.tau_rt, t1).abs();
            out.angle_deg = t1.to_degrees();
            let strength = strength_at(interpolate(&circle.theta, &circle.sigma_tt, t1));
            utilisation = f64::max(utilisation, ratio(tau, strength));
            if tau >= strength {
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
            utilisation = ratio(keq, p.k_ic);
            if keq >= p.k_ic {
                out.mode = Mode::Tension;
            }
        }
        CriterionKind::MtsT => {
            let w = sample_williams(s, p.r0);
            if let Some((th, smax)) = argmax(&w.theta, &w.sigma_tt) {
                out.angle_deg = th.to_degrees();
                utilisation = ratio(smax * (2.0 * PI * p.r0).sqrt(), p.k_ic);
                if smax * (2.0 * PI * p.r0).sqrt() >= p.k_ic {
                    out.mode = Mode::Tension;
                }
            }
        }
    }
    (out, utilisation)
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

    /// The comprehensive criterion with the faces' envelope on a closed
    /// mode-II tip under face compression: K_II = 1.2 K_IIC with no face
    /// friction gives |τ_rθ(0)| = 1.2 K_IIC/√(2πr0) against the strength
    /// K_IIC/√(2πr0), so a closed tip grows in shear straight ahead
    /// (utilisation 1.2 ± 1%); the same circle at an open tip (the faces'
    /// envelope does not apply) does not grow, its utilisation that of
    /// the tension check alone.
    #[test]
    fn shear_branch_applies_only_at_closed_tips() {
        let r0 = 1e-3;
        let p = CriterionParams {
            kind: CriterionKind::Comprehensive,
            r0,
            sigma_t: 10e6,
            cohesion: 15e6,
            friction_angle: 49f64.to_radians(),
            k_ic: 1e6,
            k_iic: 2e6,
            shear: Some(ShearStrength::Faces),
            radius_given: true,
        };
        let s = Sifs {
            k1: 0.0,
            k2: 2.4e6,
            t: 0.0,
        };
        // faces closed under 30 MPa: σ22 = σ11 = −30 MPa, σ12 = 0
        let circle = sample_hybrid(&s, [-30e6, -30e6, 0.0], r0);
        let mut faces = Faces {
            friction: 0.0,
            cohesion: 0.0,
            closed: true,
        };
        let (closed, u_closed) = assess(&p, &circle, &s, faces);
        assert_eq!(closed.mode, Mode::Shear);
        assert!(closed.angle_deg.abs() < 0.5, "{}", closed.angle_deg);
        assert!((u_closed - 1.2).abs() < 0.012, "{u_closed}");
        faces.closed = false;
        let (open, u_open) = assess(&p, &circle, &s, faces);
        assert_eq!(open.mode, Mode::None);
        let tension = circle.sigma_tt.iter().copied().fold(f64::MIN, f64::max) / p.sigma_t;
        assert!(
            u_open < 1.0 && (u_open - tension).abs() < 0.02 * tension.abs(),
            "{u_open} {tension}"
        );
    }

    /// The hybrid sampling's singular term uses K_I⁺: a negative K_I (the
    /// contact law's compliance) samples the same circle as K_I = 0, and
    /// its σ_θθ peak for pure K_II is the classical −70.5° (Erdogan–Sih).
    #[test]
    fn hybrid_sampling_takes_the_positive_part_of_k1() {
        let s = |k1| Sifs {
            k1,
            k2: 1e6,
            t: 0.0,
        };
        let a = sample_hybrid(&s(-3e6), [0.0; 3], 1e-3);
        let b = sample_hybrid(&s(0.0), [0.0; 3], 1e-3);
        assert_eq!(a, b);
        let (th, _) = argmax(&b.theta, &b.sigma_tt).expect("samples");
        assert!((th.to_degrees() + 70.53).abs() < 0.2, "{}", th.to_degrees());
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
