//! The criterion's defaults (issue 10, item 2): r0 and σ_t from the
//! material, and a default stress sampling whose kink angle does not depend
//! on r0/h.

mod common;

use cdca::Simulation;
use cdca::report::TipReport;
use cdca::scene::{Sampling, SceneFile, SideBc};
use common::*;

/// Erdogan–Sih kink angle for K_I = K_II, degrees.
const ES_45: f64 = -53.130_102;

/// Circle radii of the kink tests, in element sizes.
const RADII: [f64; 4] = [0.3, 1.0, 2.0, 5.0];

/// Elements per side of the 1 m plates of the kink tests (h = 5 mm).
const N: usize = 200;

/// The tips of `scene` after one solve with the default sampling and
/// `r0 = f h`.
fn tips_at(mut scene: SceneFile, f: f64) -> Vec<TipReport> {
    assert_eq!(scene.criterion.sampling, Sampling::Hybrid, "the default");
    scene.criterion.r0 = Some(f / N as f64);
    let report = Simulation::new(valid(scene))
        .expect("valid")
        .solve()
        .expect("solve");
    assert_eq!(report.tips.len(), 2);
    report.tips
}

/// A 1 m plate, 200 × 200, uniaxial tension 20 MPa across an open crack of
/// half-length a = 0.1 m at 45° whose tips lie inside elements (off the grid
/// lines and the element diagonals): K_I = K_II, T ≈ 0.
///
/// With the default sampling both tips kink by the Erdogan–Sih angle
/// −53.13° ± 2° for r0 = 0.3h, h, 2h and 5h (at 5h = a/4 the exact Griffith
/// field itself would peak at −47°: the criterion follows the K-field, not
/// the higher-order terms). The old field sampling gives −37° to −52° here.
#[test]
fn default_sampling_kinks_by_erdogan_sih_at_any_radius() {
    let mut s = plate(1.0, 1.0, N, N);
    tension_top_bottom(&mut s, 20e6);
    s.cracks.push(centre_crack(0.5033, 0.4971, 0.1, 45.0));
    for f in RADII {
        for t in tips_at(s.clone(), f) {
            let angle = t.criterion.angle_deg;
            println!("r0 = {f} h, tip {}: {angle:.2}°", t.tip);
            assert!((angle - ES_45).abs() < 2.0, "r0 = {f} h: {angle:.2}°");
        }
    }
}

/// A closed crack (half-length 0.1, μ = 0.3) at `deg` in the unit plate,
/// slightly off centre so its tips sit inside elements, under P_V = 20 MPa
/// and P_H = 5 MPa (rollers on the bottom and left).
fn closed_crack_plate(deg: f64) -> SceneFile {
    let mut s = plate(1.0, 1.0, N, N);
    s.boundary.bottom = SideBc::Roller;
    s.boundary.left = SideBc::Roller;
    s.boundary.top = SideBc::Traction {
        normal: -20e6,
        shear: 0.0,
    };
    s.boundary.right = SideBc::Traction {
        normal: -5e6,
        shear: 0.0,
    };
    let mut c = centre_crack(0.5033, 0.4971, 0.1, deg);
    c.friction = 0.3;
    s.cracks.push(c);
    s
}

/// A closed frictional crack under biaxial compression (P_V = 20 MPa,
/// P_H = 5 MPa, 45°, a = 0.1 m, μ = 0.3, 200 × 200): the faces slip with
/// σ_n = 12.5 MPa and the friction traction μσ_n = 3.75 MPa. Near the tip the
/// stress is the K_II field plus the uniform tensor σ11 = σ22 = −12.5 MPa,
/// |σ12| = 3.75 MPa (the face tractions; the traction-free Williams expansion
/// has σ22 = σ12 = 0). Reference: the argmax of that σ_θθ with the computed
/// K_II. The default sampling's σ_θθ peak (the reported angle, with
/// K_IIC raised so that the shear branch stays shut) is within 2° of it at r0 = 0.3h,
/// h, 2h and 5h, and its σ_θθ at θ = 0 (K_II contributes nothing there) is
/// the face normal stress −12.5 MPa ± 4%.
#[test]
fn default_sampling_carries_the_face_stress_of_a_closed_crack() {
    let mut s = closed_crack_plate(45.0);
    // no shear growth: the reported angle is then the σ_θθ peak
    s.material.k_iic = 1e9;
    let sigma_n = 12.5e6;
    for f in RADII {
        let r0 = f / N as f64;
        let mut sim = Simulation::new(valid({
            let mut s = s.clone();
            s.criterion.r0 = Some(r0);
            s
        }))
        .expect("valid");
        let report = sim.solve().expect("solve");
        for (i, t) in report.tips.iter().enumerate() {
            let tau_f = 0.3 * sigma_n * t.k2.signum();
            let reference = (0..=18_000)
                .map(|j| (-90.0 + 0.01 * f64::from(j)).to_radians())
                .map(|th| {
                    let (st, ct) = th.sin_cos();
                    let singular = t.k2 / (2.0 * PI * r0).sqrt() * (-1.5 * st * (0.5 * th).cos());
                    let uniform = -sigma_n * (st * st + ct * ct) - 2.0 * tau_f * st * ct;
                    (th.to_degrees(), singular + uniform)
                })
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .expect("angles")
                .0;
            let angle = t.criterion.angle_deg;
            println!(
                "r0 = {f} h, tip {}: {angle:.2}° (reference {reference:.2}°)",
                t.tip
            );
            assert!(
                (angle - reference).abs() < 2.0,
                "r0 = {f} h: {angle:.2}° vs {reference:.2}°"
            );
            let curve = sim.criterion_curve(i).expect("circle");
            let k = curve.theta_deg.partition_point(|&a| a < 0.0);
            let at_zero = curve.sigma_tt[k];
            assert!(rel(at_zero, -sigma_n) < 0.04, "σ_θθ(0) = {at_zero:.4e}");
        }
    }
}

/// The default r0 and σ_t of the paper's rock (c = 15 MPa, φ = 49°,
/// K_IC = 1.03 MPa√m), by hand: σ_t = 2c cos φ/(1 + sin φ) = 30 · 0.656059 /
/// 1.754710 MPa = 11.2165 MPa, r0 = (1.03/11.2165)²/2π m = 1.3421 mm (to 1e-4).
/// An explicit r0 gives σ_t = K_IC/√(2π r0); an explicit σ_t gives r0.
#[test]
fn default_radius_and_strength_follow_the_material() {
    use cdca::fracture::criterion::radius_and_strength;
    let mut m = plate(1.0, 1.0, 1, 1).material;
    (m.cohesion, m.friction_angle_deg, m.k_ic) = (15e6, 49.0, 1.03e6);
    let (r0, st) = radius_and_strength(None, &m);
    assert!(rel(st, 11.2165e6) < 1e-4, "σ_t = {st}");
    assert!(rel(r0, 1.3421e-3) < 1e-4, "r0 = {r0}");
    let (r0, st) = radius_and_strength(Some(0.0009), &m);
    assert!(r0 == 0.0009 && rel(st, 1.03e6 / (2.0 * PI * 0.0009f64).sqrt()) < 1e-12);
    m.tensile_strength = Some(5e6);
    let (r0, st) = radius_and_strength(None, &m);
    assert!(st == 5e6 && rel(r0, (1.03f64 / 5.0).powi(2) / (2.0 * PI)) < 1e-12);
    assert_eq!(radius_and_strength(Some(0.002), &m), (0.002, 5e6));
}

/// The sampling's uniform stress takes σ11 = T + σ22: the point-force
/// interaction integral measures σ11 − σ22 on a closed crack. A closed 30°
/// crack (μ = 0.3) under P_V = 20 MPa, P_H = 5 MPa has σ11 = −8.75 MPa,
/// σ22 = −16.25 MPa along and across it: T = 7.5 MPa ± 2% at both tips.
#[test]
fn interaction_integral_t_of_a_closed_crack_is_sigma11_minus_sigma22() {
    let s = closed_crack_plate(30.0);
    let report = Simulation::new(valid(s))
        .expect("valid")
        .solve()
        .expect("solve");
    for t in &report.tips {
        assert!(rel(t.t_stress, 7.5e6) < 0.02, "T = {:.4e}", t.t_stress);
    }
}
