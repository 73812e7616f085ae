//! The criterion's defaults (issue 10, item 2): r0 and σ_t from the
//! material, and a default stress sampling whose kink angle does not depend
//! on r0/h.

mod common;

use cdca::Simulation;
use cdca::report::{Mode, TipReport};
use cdca::scene::{Sampling, SceneFile, SideBc};
use common::docs_row::{pct, sig, verification_row};
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
    assert_eq!(
        valid(scene.clone()).criterion_settings().sampling(),
        Some(Sampling::Hybrid),
        "the default"
    );
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
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for f in RADII {
        for t in tips_at(s.clone(), f) {
            let angle = t.criterion.angle_deg;
            println!("r0 = {f} h, tip {}: {angle:.2}°", t.tip);
            assert!((angle - ES_45).abs() < 2.0, "r0 = {f} h: {angle:.2}°");
            (lo, hi) = (lo.min(angle), hi.max(angle));
        }
    }
    verification_row(
        "criterion",
        "default_sampling_kinks_by_erdogan_sih_at_any_radius",
        "kink of a 45° open crack in tension (Erdogan–Sih −53.13°), default sampling, r0 = 0.3h, h, 2h, 5h",
        "200 × 200",
        &format!("{hi:.1}° … {lo:.1}°"),
        "2°",
    );
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
    let (mut worst_angle, mut worst_stress): (f64, f64) = (0.0, 0.0);
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
            worst_angle = worst_angle.max((angle - reference).abs());
            worst_stress = worst_stress.max(rel(at_zero, -sigma_n));
        }
    }
    verification_row(
        "criterion",
        "default_sampling_carries_the_face_stress_of_a_closed_crack",
        "closed crack: σ_θθ(0) = face normal stress, peak angle",
        "200 × 200",
        &format!(
            "peak within {:.2}°, σ_θθ(0) within {}",
            worst_angle,
            pct(worst_stress, 2).trim_start_matches('+')
        ),
        "2°, 4%",
    );
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
    verification_row(
        "criterion",
        "default_radius_and_strength_follow_the_material",
        "default r0, σ_t from the material (hand values)",
        "",
        &format!("{} MPa, {} mm", sig(st / 1e6, 6), sig(r0 * 1e3, 5)),
        "1e-4",
    );

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

/// Half-length of the sliding-crack plate's crack, m.
const A_SLIDE: f64 = 0.03;

/// Reference vertical compression of the sliding-crack plate, Pa.
const P_SLIDE: f64 = 10e6;

/// The paper's 0.3 m plate (its rock, plane stress), 100 × 100 (h = 3 mm =
/// a/10), with a closed crack of half-length 30 mm at 45° off the grid
/// lines and diagonals, face friction `mu`, penalty contact, under uniaxial
/// compression P_SLIDE (roller bottom and left, right free), `r0 = a /
/// a_over_r0`.
fn sliding_plate(mu: f64, a_over_r0: f64) -> cdca::Scene {
    let mut s = bundled("plate_45_biaxial_k0.2_mu0.5");
    (s.mesh.nx, s.mesh.ny) = (100, 100);
    s.boundary.right = SideBc::Free;
    s.boundary.top = SideBc::Traction {
        normal: -P_SLIDE,
        shear: 0.0,
    };
    let mut crack = centre_crack(0.1507, 0.1496, A_SLIDE, 45.0);
    crack.friction = mu;
    s.cracks = vec![crack];
    s.criterion.r0 = Some(A_SLIDE / a_over_r0);
    valid(s)
}

/// λ of the wing from a sliding crack at 45° to a uniaxial compression
/// λ P_SLIDE (σ_n = τ = λP/2), and its kink angle (degrees, magnitude), as
/// the default (hybrid) sampling sees it with the exact infinite-plate
/// K_II = (τ − μσ_n)√(πa) (K_I = 0): σ_θθ(θ, r0) = K_II/√(2πr0) ·
/// (−3/2 sin θ cos θ/2) − σ_n − 2 μσ_n sin θ cos θ ≥ σ_t = K_IC/√(2πr0).
/// As r0/a → 0 the uniform terms vanish against the singular one and this
/// tends to the LEFM sliding-crack form [`lefm_wing_load`].
fn finite_r0_wing_load(mu: f64, r0: f64, k_ic: f64) -> (f64, f64) {
    let (g, angle) = sliding_crack_kink(45.0, mu, A_SLIDE, r0);
    (k_ic / (2.0 * PI * r0).sqrt() / g / P_SLIDE, angle)
}

/// λ at which the LEFM sliding crack starts a wing: the kink's largest
/// K_I, (2/√3) K_II at θ = 70.5° for a pure K_II tip (Erdogan & Sih 1963),
/// with the sliding crack's K_II = (τ − μσ_n)√(πa) (Horii & Nemat-Nasser
/// 1986; Ashby & Hallam 1986), reaches K_IC: (2/√3)(τ − μσ_n)√(πa) = K_IC,
/// with σ_n = τ = λ P_SLIDE / 2 at 45°.
fn lefm_wing_load(mu: f64, k_ic: f64) -> f64 {
    k_ic / ((2.0 / 3f64.sqrt()) * 0.5 * (1.0 - mu) * (PI * A_SLIDE).sqrt()) / P_SLIDE
}

/// Issue 17, item 3: how the initiation load of a closed frictional crack
/// under uniaxial compression approaches the sliding-crack closed form as
/// a/r0 grows (a = 30 mm in the 0.3 m plate, r0 = a/3 … a/100; μ = 0 and
/// 0.5; critical control, `cdca::initiation`).
///
/// For a/r0 ≥ 10 the first growth is a tension wing whose λ_cr is within
/// 6% (measured 2.7–4.5% below) and whose angle is within 2° (measured
/// ≤ 0.3°) of the hybrid sampling's own closed form
/// ([`finite_r0_wing_load`]; the computed K_II is ≈ 2% above the
/// infinite-plate value, a/W = 0.1, and the uniform term amplifies that
/// at small a/r0); the excess over LEFM
/// ([`lefm_wing_load`]) falls strictly with a/r0 and is below 20% at
/// a/r0 = 100, where the uniform compression at r0 still costs
/// ≈ (√3/2)√(2r0/a)/(1 − μ) of the singular term (12% at μ = 0). The
/// a/r0 = 3 row is printed, not asserted (the faces' shear branch,
/// K_II = K_IIC, fires first there: the small-flaw problem).
#[test]
fn initiation_load_approaches_the_sliding_crack_closed_form() {
    let k_ic = bundled("plate_45_biaxial_k0.2_mu0.5").material.k_ic;
    let (mut below_lo, mut below_hi, mut angle_worst) = (f64::INFINITY, 0.0f64, 0.0f64);
    let mut lefm_at_100 = Vec::new();
    for mu in [0.0, 0.5] {
        let lefm = lefm_wing_load(mu, k_ic);
        let mut last_ratio = f64::INFINITY;
        for a_over_r0 in [3.0, 10.0, 30.0, 100.0] {
            let r0 = A_SLIDE / a_over_r0;
            let init = cdca::initiation(&sliding_plate(mu, a_over_r0)).expect("initiation");
            let (model, model_angle) = finite_r0_wing_load(mu, r0, k_ic);
            let ratio = init.lambda_cr / lefm;
            println!(
                "μ = {mu}, a/r0 = {a_over_r0}: {:?} {:.1}° λ_cr {:.4}, LEFM {lefm:.4} \
                 (×{ratio:.3}), finite-r0 form {model:.4} at {model_angle:.1}° (×{:.3})",
                init.mode,
                init.angle_deg.abs(),
                init.lambda_cr,
                init.lambda_cr / model
            );
            assert!(init.converged, "a/r0 = {a_over_r0}");
            if a_over_r0 < 10.0 {
                continue;
            }
            assert_eq!(init.mode, Mode::Tension, "a/r0 = {a_over_r0}");
            assert!(rel(init.lambda_cr, model) < 0.06, "a/r0 = {a_over_r0}");
            assert!((init.angle_deg.abs() - model_angle).abs() < 2.0);
            assert!(ratio < last_ratio && ratio >= 1.0, "a/r0 = {a_over_r0}");
            last_ratio = ratio;
            below_lo = below_lo.min(1.0 - init.lambda_cr / model);
            below_hi = below_hi.max(1.0 - init.lambda_cr / model);
            angle_worst = angle_worst.max((init.angle_deg.abs() - model_angle).abs());
        }
        assert!(last_ratio < 1.2, "μ = {mu}: ×{last_ratio:.3} at a/r0 = 100");
        lefm_at_100.push(format!("×{}", sig(last_ratio, 3)));
    }
    verification_row(
        "criterion",
        "initiation_load_approaches_the_sliding_crack_closed_form",
        "closed 45° crack, uniaxial compression, a/r0 = 10, 30, 100, μ = 0 and 0.5: initiation against the sliding-crack closed form (see *Initiation against the sliding-crack closed form* in [the fracture model](fracture-model.md))",
        "100 × 100",
        &format!(
            "tension; λ_cr {}–{}% below the finite-r0 form, angle within {:.1}°; {} LEFM at a/r0 = 100",
            sig(100.0 * below_lo, 2),
            sig(100.0 * below_hi, 2),
            angle_worst,
            lefm_at_100.join(" / ")
        ),
        "6%, 2°; excess over LEFM falls, < 20% at 100",
    );
}

/// Issue 17, item 3, with the default radius: the sliding-crack plate
/// scaled to flaws of half-length a = 1.3, 3, 10 and 30 process-zone sizes
/// r_p = (K_IC/σ_t)²/2π = 1.34 mm (the plate and mesh scaled with a, so
/// h = a/10; μ = 0 and 0.5; no `criterion.r0`). The radius is then
/// min(r_p, a/5π) ([`cdca::fracture::criterion::CriterionParams::for_crack`]):
/// every flaw, down to the 3.5 mm one of the issue (a = 1.3 r_p, which grew
/// coplanar in shear with r0 = r_p), starts a tension wing at 55–80° to
/// the flaw, and λ_cr is within 6% of the hybrid sampling's closed form
/// ([`finite_r0_wing_load`]) at the radius the rule gives. The excess over
/// LEFM is that form's uniform compression at r0, the same for every flaw
/// up to a = 5π r_p (a/r0 = 5π) and falling beyond: measured ×1.39 (μ = 0)
/// and ×1.54 (μ = 0.5) up to a = 10 r_p, ×1.25 and ×1.34 at 30 r_p, and
/// 0.96–0.97 of the closed form; angles 70.5° (μ = 0) and 59.6–61.7°
/// (μ = 0.5).
#[test]
fn the_default_radius_gives_wings_at_every_flaw_size() {
    let plate = bundled("plate_45_biaxial_k0.2_mu0.5");
    let k_ic = plate.material.k_ic;
    let (r_p, _) = cdca::fracture::criterion::radius_and_strength(None, &plate.material);
    println!("r_p = {:.3} mm", r_p * 1e3);
    for mu in [0.0, 0.5] {
        let lefm = lefm_wing_load(mu, k_ic);
        for a_over_rp in [1.3, 3.0, 10.0, 30.0] {
            let a = a_over_rp * r_p;
            let f = a / A_SLIDE;
            let scene = sliding_plate(mu, 10.0)
                .edit(|s| {
                    s.criterion.r0 = None;
                    s.specimen.width *= f;
                    s.specimen.height *= f;
                    s.cracks = vec![centre_crack(0.1507 * f, 0.1496 * f, a, 45.0)];
                    s.cracks[0].friction = mu;
                })
                .expect("valid");
            let init = cdca::initiation(&scene).expect("initiation");
            let r0 = r_p.min(a / cdca::fracture::criterion::LEFM_SIZE_RATIO);
            // the closed form at this a: λ scales with 1/√a
            let (model, model_angle) = finite_r0_wing_load(mu, r0 / f, k_ic * f.sqrt().recip());
            println!(
                "μ = {mu}, a = {a_over_rp} r_p, r0 = {:.3} mm: {:?} {:.1}° λ_cr {:.4} \
                 (×{:.3} LEFM, ×{:.3} the finite-r0 form at {model_angle:.1}°)",
                r0 * 1e3,
                init.mode,
                init.angle_deg.abs(),
                init.lambda_cr,
                init.lambda_cr / (lefm / f.sqrt()),
                init.lambda_cr / model
            );
            assert!(init.converged, "a = {a_over_rp} r_p");
            assert_eq!(init.mode, Mode::Tension, "a = {a_over_rp} r_p");
            let angle = init.angle_deg.abs();
            assert!(
                (55.0..80.0).contains(&angle),
                "a = {a_over_rp} r_p: {angle}°"
            );
            assert!(rel(init.lambda_cr, model) < 0.06, "a = {a_over_rp} r_p");
        }
    }
}

/// The same plate with `criterion.sampling = "williams"` (the K_I, K_II, T
/// expansion, no face tractions): the check is then σ_θθ√(2πr0) =
/// K-terms + T sin²θ √(2πr0) ≥ K_IC with T ≈ 0 on a 45° crack in uniaxial
/// compression, so λ_cr is the LEFM sliding-crack load at every a/r0
/// (measured ×0.977–0.980 at μ = 0 and 0.5, a/r0 = 3…100: the computed K_II
/// is ≈ 2% above the infinite-plate value) and the wing starts at 70.5° at
/// both frictions, within 3% and 1°. The excess of the default sampling over
/// LEFM at small a/r0 (and its shear at a/r0 = 3) is its uniform
/// compression at r0, not the K-field.
#[test]
fn williams_sampling_gives_the_sliding_crack_load_at_any_radius() {
    let k_ic = bundled("plate_45_biaxial_k0.2_mu0.5").material.k_ic;
    let (mut a_lo, mut a_hi, mut r_lo, mut r_hi) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for mu in [0.0, 0.5] {
        let lefm = lefm_wing_load(mu, k_ic);
        for a_over_r0 in [3.0, 10.0, 30.0, 100.0] {
            let scene = sliding_plate(mu, a_over_r0)
                .edit(|s| s.criterion.sampling = Some(Sampling::Williams))
                .expect("valid");
            let init = cdca::initiation(&scene).expect("initiation");
            println!(
                "μ = {mu}, a/r0 = {a_over_r0}: {:?} {:.2}° λ_cr {:.4} (×{:.3} LEFM)",
                init.mode,
                init.angle_deg.abs(),
                init.lambda_cr,
                init.lambda_cr / lefm
            );
            assert!(init.converged && init.mode == Mode::Tension);
            assert!(rel(init.lambda_cr, lefm) < 0.03, "a/r0 = {a_over_r0}");
            assert!((init.angle_deg.abs() - 70.53).abs() < 1.0);
            (a_lo, a_hi) = (
                a_lo.min(init.angle_deg.abs()),
                a_hi.max(init.angle_deg.abs()),
            );
            (r_lo, r_hi) = (
                r_lo.min(init.lambda_cr / lefm),
                r_hi.max(init.lambda_cr / lefm),
            );
        }
    }
    verification_row(
        "criterion",
        "williams_sampling_gives_the_sliding_crack_load_at_any_radius",
        "the same crack with `criterion.sampling = \"williams\"`, a/r0 = 3…100 (LEFM sliding crack)",
        "100 × 100",
        &format!(
            "tension {a_lo:.1}–{a_hi:.1}°, ×{}–{} of LEFM",
            sig(r_lo, 3),
            sig(r_hi, 3)
        ),
        "3%, 1°",
    );
}

/// Face friction on the default scene (issue 17, item 2), initiation under
/// critical control at μ = 0, 0.2, 0.4, 0.6 with the default criterion
/// (r0 = a/5π = 0.19 mm for the 6 mm flaw). With the soft joint
/// (200 / 20 GPa/m) the faces stick for every μ ≥ 0.2 and λ_cr is the same
/// there (0.1872, then 0.1934 three times; printed, not asserted: that is
/// what the joint does). With the contact a drawn crack gets (the penalty)
/// friction acts as in the sliding-crack picture: every μ starts a tension
/// wing, λ_cr rises strictly (measured 0.255, 0.330, 0.459, 0.721) and the
/// wing angle falls strictly (70.6°, 66.8°, 62.2°, 57.0°).
#[test]
fn friction_raises_the_wing_load_with_the_default_contact() {
    let run = |penalty: bool| -> Vec<cdca::Initiation> {
        [0.0, 0.2, 0.4, 0.6]
            .iter()
            .map(|&mu| {
                let mut s = bundled("specimen_single_flaw");
                s.cracks[0].friction = mu;
                if !penalty {
                    // the paper's soft joint
                    s.cracks[0].normal_stiffness = Some(200e9);
                    s.cracks[0].shear_stiffness = Some(20e9);
                }
                let i = cdca::initiation(&valid(s)).expect("initiation");
                println!(
                    "penalty {penalty}, μ = {mu}: {:?} {:.1}° λ_cr {:.4}",
                    i.mode, i.angle_deg, i.lambda_cr
                );
                assert!(i.converged, "μ = {mu}");
                i
            })
            .collect()
    };
    run(false);
    let rows = run(true);
    assert!(rows.iter().all(|i| i.mode == Mode::Tension), "{rows:?}");
    for w in rows.windows(2) {
        assert!(w[1].lambda_cr > w[0].lambda_cr, "{rows:?}");
        assert!(w[1].angle_deg.abs() < w[0].angle_deg.abs(), "{rows:?}");
    }
    let loads: Vec<String> = rows.iter().map(|i| sig(i.lambda_cr, 3)).collect();
    let angles: Vec<String> = rows
        .iter()
        .map(|i| format!("{:.1}°", i.angle_deg.abs()))
        .collect();
    verification_row(
        "criterion",
        "friction_raises_the_wing_load_with_the_default_contact",
        "face friction μ = 0…0.6 on the default scene with the penalty joint and r0 = a/5π (sliding-crack picture)",
        "60 × 60",
        &format!("tension; λ_cr {}; {}", loads.join(", "), angles.join(", ")),
        "λ_cr strictly rising, angle strictly falling",
    );
}
