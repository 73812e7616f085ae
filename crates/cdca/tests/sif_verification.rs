//! Verification of the XFEM solver core against closed-form and handbook
//! values (issue: solver core). Every test names its reference and its
//! tolerance; tolerances are the upper bounds.

mod common;

use cdca::Simulation;
use common::docs_row::{pct, sig, verification_row};
use common::*;

/// Tada's finite-width centre crack: `K_I = σ√(πa)(1 − 0.025α² + 0.06α⁴)√sec(πα/2)`,
/// α = a/b (b the half width); plate height/width = 3.
fn centre_crack_k1(n: usize) -> (f64, f64, Vec<f64>) {
    let mut s = plate(1.0, 3.0, n, 3 * n);
    tension_top_bottom(&mut s, 1e6);
    s.cracks.push(centre_crack(0.5, 1.5, 0.15, 0.0));
    let r = solve(s);
    let al: f64 = 0.3;
    let exact = 1e6
        * (PI * 0.15f64).sqrt()
        * (1.0 - 0.025 * al * al + 0.06 * al.powi(4))
        * (1.0 / (PI * al / 2.0).cos()).sqrt();
    let k: Vec<f64> = r.tips.iter().map(|t| t.k1).collect();
    (k.iter().sum::<f64>() / k.len() as f64, exact, k)
}

/// Centre crack a/b = 0.3: within 0.5% of Tada at 80 across, 2% at 40.
#[test]
fn centre_crack_tension_matches_tada() {
    let mut measured = Vec::new();
    for (n, tol) in [(40, 0.02), (80, 0.005)] {
        let (_, exact, k) = centre_crack_k1(n);
        assert_eq!(k.len(), 2);
        let worst = k
            .iter()
            .map(|&k1| k1 / exact - 1.0)
            .fold(0.0, |a: f64, e| if e.abs() > a.abs() { e } else { a });
        measured.push(pct(worst, 2));
        for k1 in k {
            assert!(
                rel(k1, exact) < tol,
                "n = {n}: K_I = {k1:.6e}, Tada {exact:.6e}"
            );
        }
    }
    verification_row(
        "sif_verification",
        "centre_crack_tension_matches_tada",
        "centre crack a/b = 0.3, H/W = 3 (Tada), node-aligned tips",
        "40 × 120 / 80 × 240",
        &measured.join(" / "),
        "2% / 0.5%",
    );
}

/// The edge crack a/W = 0.5 in a 1 × 2 plate on an `nx × ny` mesh: 1 MPa
/// on top and bottom, the right edge held at mid-height (xy) and at the top
/// (x).
fn edge_crack_scene(nx: usize, ny: usize) -> cdca::scene::SceneFile {
    let mut s = plate(1.0, 2.0, nx, ny);
    tension_top_bottom(&mut s, 1e6);
    s.boundary.points = vec![
        cdca::scene::PointSupport {
            at: [1.0, 1.0],
            fix: cdca::scene::Fix::Xy,
        },
        cdca::scene::PointSupport {
            at: [1.0, 2.0],
            fix: cdca::scene::Fix::X,
        },
    ];
    s.cracks
        .push(cdca::scene::CrackSpec::segment([0.0, 1.0], [0.5, 1.0]));
    s
}

/// Edge crack a/W = 0.5, H/W = 2: `K_I/(σ√(πa)) = 2.8266` (Tada), within 0.5% at 80 × 160.
#[test]
fn edge_crack_tension_matches_tada() {
    let r = solve(edge_crack_scene(80, 160));
    assert_eq!(r.tips.len(), 1, "the boundary end is not a tip");
    let f = r.tips[0].k1 / (1e6 * (PI * 0.5f64).sqrt());
    assert!(rel(f, 2.8266) < 0.005, "F = {f:.5}, Tada 2.8266");
    verification_row(
        "sif_verification",
        "edge_crack_tension_matches_tada",
        "edge crack a/W = 0.5, H/W = 2, tip on a node (Tada 2.8266)",
        "80 × 160",
        &pct(f / 2.8266 - 1.0, 2),
        "0.5%",
    );
}

/// The edge-crack scene of [`edge_crack_tension_matches_tada`] on an
/// `n × (2n + 1)` mesh: for odd `n` the tip (0.5, 1) is at the centre of an
/// element and the crack runs along the middle of an element row (the
/// generic case). Returns F = K_I/(σ√(πa)).
fn edge_crack_f(n: usize) -> f64 {
    let r = solve(edge_crack_scene(n, 2 * n + 1));
    assert_eq!(r.tips.len(), 1);
    r.tips[0].k1 / (1e6 * (PI * 0.5f64).sqrt())
}

/// Edge crack a/W = 0.5, H/W = 2, tip at the centre of an element of an
/// 81 × 163 mesh: F within 0.1% of Tada's 2.8266 (measured −0.06%).
#[test]
fn edge_crack_tip_inside_an_element_matches_tada() {
    let f = edge_crack_f(81);
    assert!(rel(f, 2.8266) < 0.001, "F = {f:.5}, Tada 2.8266");
    verification_row(
        "sif_verification",
        "edge_crack_tip_inside_an_element_matches_tada",
        "edge crack, tip at an element centre (Tada 2.8266)",
        "81 × 163",
        &pct(f / 2.8266 - 1.0, 2),
        "0.1%",
    );
}

/// Mesh refinement 41, 81, 161 across with the tip at an element centre.
/// Reference: the converged F (Aitken extrapolation of the three), within
/// 0.1% of Tada's 2.8266 (whose formula is for an infinite strip; measured
/// −0.04%). The error falls monotonically at an observed order of at least
/// 1.5 (measured 2.7: the geometric enrichment zone; a zone of 2.5
/// elements converged at first order, −0.81 → −0.41 → −0.21% against Tada).
#[test]
fn edge_crack_tip_inside_an_element_converges_at_second_order() {
    let f: Vec<f64> = [41, 81, 161].iter().map(|&n| edge_crack_f(n)).collect();
    let (d1, d2) = (f[1] - f[0], f[2] - f[1]);
    let f_inf = f[2] - d2 * d2 / (d2 - d1);
    assert!(
        rel(f_inf, 2.8266) < 0.001,
        "converged F {f_inf:.5} vs Tada 2.8266 (F = {f:?})"
    );
    let errs: Vec<f64> = f.iter().map(|&v| rel(v, f_inf)).collect();
    assert!(errs[1] < errs[0] && errs[2] < errs[1], "errors {errs:?}");
    let rate = (errs[0] / errs[2]).ln() / (161.0f64 / 41.0).ln();
    println!("F = {f:?}, converged {f_inf:.6}, errors {errs:?}, observed order {rate:.2}");
    assert!(rate >= 1.5, "observed order {rate:.2} from {errs:?}");
    verification_row(
        "sif_verification",
        "edge_crack_tip_inside_an_element_converges_at_second_order",
        "edge crack, tip at an element centre, 41/81/161 across",
        "",
        &format!(
            "converged value {} from Tada; observed order {}",
            pct(f_inf / 2.8266 - 1.0, 2),
            sig(rate, 3)
        ),
        "within 0.1% of Tada; order ≥ 1.5",
    );
}

/// Centre crack a/b = 0.3 (H/W = 3) with both tips inside elements and the
/// crack along the middle of an element row (81 × 243): K_I within 0.5% of
/// Tada, as the node-aligned 80 × 240 case of
/// [`centre_crack_tension_matches_tada`].
#[test]
fn centre_crack_tips_inside_elements_match_tada() {
    let mut s = plate(1.0, 3.0, 81, 243);
    tension_top_bottom(&mut s, 1e6);
    s.cracks.push(centre_crack(0.5, 1.5, 0.15, 0.0));
    let r = solve(s);
    let al: f64 = 0.3;
    let exact = 1e6
        * (PI * 0.15f64).sqrt()
        * (1.0 - 0.025 * al * al + 0.06 * al.powi(4))
        * (1.0 / (PI * al / 2.0).cos()).sqrt();
    assert_eq!(r.tips.len(), 2);
    let worst = r
        .tips
        .iter()
        .map(|t| t.k1 / exact - 1.0)
        .fold(0.0, |a: f64, e| if e.abs() > a.abs() { e } else { a });
    verification_row(
        "sif_verification",
        "centre_crack_tips_inside_elements_match_tada",
        "centre crack, tips inside elements (Tada)",
        "81 × 243",
        &pct(worst, 2),
        "0.5%",
    );
    for t in &r.tips {
        println!(
            "K_I {:.6e}, Tada {exact:.6e}: {:+.3}%",
            t.k1,
            100.0 * (t.k1 / exact - 1.0)
        );
        assert!(
            rel(t.k1, exact) < 0.005,
            "K_I = {:.6e}, Tada {exact:.6e}",
            t.k1
        );
    }
}

/// Inclined centre crack in a large plate (a/b = 0.1) under uniaxial tension σ:
/// `K_I = σ√(πa) cos²β`, `K_II = σ√(πa) sinβ cosβ` within 3%, sign included
/// (θ counter-clockwise from each tip's outward tangent: K_II > 0 at both
/// tips of a crack turned counter-clockwise from the load-normal plane);
/// `T = −σ cos 2β` (crack-parallel stress minus crack-normal stress) within
/// 10% at β = 30°.
#[test]
fn inclined_crack_mixed_mode_and_t_stress() {
    let worst = |a: f64, e: f64| if e.abs() > a.abs() { e } else { a };
    let (mut e1, mut e2, mut et) = (0.0, 0.0, 0.0);
    for beta in [30.0f64, 45.0] {
        let mut s = plate(1.0, 1.0, 160, 160);
        tension_top_bottom(&mut s, 1e6);
        s.cracks.push(centre_crack(0.5, 0.5, 0.05, beta));
        let r = solve(s);
        let b = beta.to_radians();
        let k0 = 1e6 * (PI * 0.05f64).sqrt();
        for t in &r.tips {
            if beta == 30.0 {
                e1 = worst(e1, t.k1 / (k0 * b.cos().powi(2)) - 1.0);
                e2 = worst(e2, t.k2 / (k0 * b.sin() * b.cos()) - 1.0);
                et = worst(et, t.t_stress / (-1e6 * (2.0 * b).cos()) - 1.0);
            }
            assert!(
                rel(t.k1, k0 * b.cos().powi(2)) < 0.03,
                "β {beta}: K_I {:.4e}",
                t.k1
            );
            assert!(
                rel(t.k2, k0 * b.sin() * b.cos()) < 0.03,
                "β {beta}: K_II {:.4e}",
                t.k2
            );
            if beta == 30.0 {
                let exact = -1e6 * (2.0 * b).cos();
                assert!(
                    rel(t.t_stress, exact) < 0.10,
                    "T {:.4e} vs {exact:.4e}",
                    t.t_stress
                );
            }
        }
    }
    verification_row(
        "sif_verification",
        "inclined_crack_mixed_mode_and_t_stress",
        "inclined crack β = 30°, a/b = 0.1 (σ√πa {cos²β, sinβ cosβ}, T = −σ cos 2β), signs checked",
        "160 × 160",
        &format!(
            "K_I {}, K_II {}, T {} (β = 30°)",
            pct(e1, 2),
            pct(e2, 2),
            pct(et, 2)
        ),
        "3%, 3%, 10%",
    );
}

/// Mesh refinement 20, 40, 80, 160 across (centre crack, a/b = 0.3). The
/// reference is the converged K_I (Aitken extrapolation of the last three
/// meshes), itself within 0.5% of Tada (whose formula is for an infinite
/// strip; H/W = 3 raises K slightly). The error falls monotonically and the
/// observed rate between the first and last mesh is at least 0.5.
#[test]
fn centre_crack_error_converges() {
    let k: Vec<f64> = [20, 40, 80, 160]
        .iter()
        .map(|&n| centre_crack_k1(n).0)
        .collect();
    let (_, tada, _) = centre_crack_k1(10);
    let (d1, d2) = (k[2] - k[1], k[3] - k[2]);
    let k_inf = k[3] - d2 * d2 / (d2 - d1);
    assert!(
        rel(k_inf, tada) < 0.005,
        "converged {k_inf:.6e} vs Tada {tada:.6e}"
    );
    let errs: Vec<f64> = k.iter().map(|&v| rel(v, k_inf)).collect();
    for w in errs.windows(2) {
        assert!(w[1] < w[0], "errors {errs:?} must fall (K = {k:?})");
    }
    let rate = (errs[0] / errs[3]).ln() / 8f64.ln();
    assert!(rate >= 0.5, "observed rate {rate:.2} from {errs:?}");
    println!(
        "K_I = {k:?}, converged {k_inf:.6e}, Tada {tada:.6e}, errors {errs:?}, rate {rate:.2}"
    );
    verification_row(
        "sif_verification",
        "centre_crack_error_converges",
        "centre crack, mesh sequence 20…160 across",
        "",
        &format!("falls monotonically, observed rate {}", sig(rate, 3)),
        "rate ≥ 0.5",
    );
}

/// The interaction integral is path independent: K_I changes by less than
/// 0.5% when the domain radius goes from 2 to 4 element sizes.
#[test]
fn interaction_integral_is_path_independent() {
    let mut s = plate(1.0, 3.0, 80, 240);
    tension_top_bottom(&mut s, 1e6);
    s.cracks.push(centre_crack(0.5, 1.5, 0.15, 0.0));
    let mut sim = Simulation::new(valid(s)).expect("valid");
    sim.solve().expect("solve");
    let x = sim.xfem();
    let f = cdca::discretisation::field::Field {
        xfem: x,
        u: sim.displacement(),
    };
    let frame = cdca::geometry::cracks::TipFrame::of(&x.funcs.cracks[0], 1);
    let k = |r: f64| cdca::fracture::sif::tip_sifs(&f, 0, &frame, r * x.mesh.h(), &[]).k1;
    let (k2, k4) = (k(2.0), k(4.0));
    assert!(
        rel(k2, k4) < 0.005,
        "K_I(2h) = {k2:.5e}, K_I(4h) = {k4:.5e}"
    );
    verification_row(
        "sif_verification",
        "interaction_integral_is_path_independent",
        "interaction-integral domain 2h vs 4h",
        "80 × 240",
        &pct(k2 / k4 - 1.0, 2),
        "0.5%",
    );
}

/// A crack only 2.5 and 3 elements long, at generic angles and off the
/// grid, in a plate 27–32 times longer (infinite plate:
/// `K_I = σ cos²β √(πa)`, `K_II = σ sinβ cosβ √(πa)`, β from the x axis,
/// tension σ along y): each tip's interaction-integral domain stops an
/// element short of the other tip, so both K are within 6% of σ√(πa) at
/// 2.5 h and 5% at 3 h. With the fixed 3 h domain, which reached past the
/// other tip, they were 20–31% off.
#[test]
fn a_crack_a_few_elements_long_reads_k_from_a_domain_inside_it() {
    let h = 1.0 / 80.0;
    for (span, tol) in [(2.5, 0.06), (3.0, 0.05)] {
        for (beta, dx, dy) in [(23.0f64, 0.31, -0.17), (57.0, -0.22, 0.38)] {
            let mut s = plate(1.0, 3.0, 80, 240);
            tension_top_bottom(&mut s, 1e6);
            let a = 0.5 * span * h * (1.0 + 1e-9);
            s.cracks
                .push(centre_crack(0.5 + dx * h, 1.5 + dy * h, a, beta));
            let r = solve(s);
            let unit = 1e6 * (PI * a).sqrt();
            let (sin, cos) = beta.to_radians().sin_cos();
            for t in &r.tips {
                let e1 = (t.k1 - unit * cos * cos).abs() / unit;
                let e2 = (t.k2.abs() - unit * sin * cos).abs() / unit;
                assert!(
                    e1 < tol && e2 < tol,
                    "{span} h at {beta}°: K_I error {e1:.3}, K_II error {e2:.3} of σ√(πa)"
                );
            }
        }
    }
}

/// A circular-arc crack of radius R and half-angle α under equal biaxial
/// tension σ (Tada, Paris & Irwin, *The Stress Analysis of Cracks
/// Handbook*, after Sih, Paris & Erdogan 1962):
/// `K_I = σ √(πR sin α) cos(α/2)/(1 + sin²(α/2))`, `K_II = K_I tan(α/2)`,
/// in a plate ten times the arc's span, its centre off the grid, R = 8 h
/// (the arc sampled into segments of at most h/2, turning 3.5–5° at each
/// vertex). Each tip's interaction-integral domain stops an element short
/// of the nearest vertex where the arc turns: the worst K of the two tips
/// is 2.7%, 4.0%, 4.6% and 8.5% of the closed form's magnitude off at
/// α = 30°, 45°, 60° and 90° (asserted: 5%, and 9% at 90°). With the 3 h
/// domain across the arc's turns they were 7.0%, 8.1%, 9.6% and 11.1%.
#[test]
fn a_circular_arc_crack_matches_the_closed_form() {
    let h = 2.0 / 160.0;
    for (alpha, tol) in [(30.0f64, 0.05), (45.0, 0.05), (60.0, 0.05), (90.0, 0.09)] {
        let mut s = plate(2.0, 2.0, 160, 160);
        tension_top_bottom(&mut s, 1e6);
        let side = cdca::scene::SideBc::Traction {
            normal: 1e6,
            shear: 0.0,
        };
        (s.boundary.left, s.boundary.right) = (side, side);
        let radius = 8.0 * h;
        let mut arc = centre_crack(1.0, 1.0, 0.1, 0.0);
        arc.points = None;
        arc.arc = Some(cdca::scene::ArcSpec {
            center: [1.0037, 0.9968],
            radius,
            start_deg: 90.0 - alpha,
            end_deg: 90.0 + alpha,
        });
        s.cracks.push(arc);
        let r = solve(s);
        let a = alpha.to_radians();
        let k = 1e6 * (PI * radius * a.sin()).sqrt() / (1.0 + (0.5 * a).sin().powi(2));
        let (k1, k2) = (k * (0.5 * a).cos(), k * (0.5 * a).sin());
        assert_eq!(r.tips.len(), 2);
        for t in &r.tips {
            let (e1, e2) = ((t.k1 - k1).abs() / k, (t.k2.abs() - k2).abs() / k);
            assert!(
                e1 < tol && e2 < tol,
                "α = {alpha}°: K_I {:.4e} against {k1:.4e}, K_II {:.4e} against {k2:.4e}",
                t.k1,
                t.k2
            );
        }
    }
}

/// K at a wing one growth increment long: the default scene's closed flaw
/// with a straight segment of 3 h (1.5 mm, the default increment) kinked
/// 30° or 60° off its upper tip, on the default 60 × 60 mesh, against the
/// same cracks on 240 × 240, where the tip's 3 h domain lies well inside
/// the segment (within 0.5% of 480 × 480). The domain stops an element
/// short of the kink: both K are within 5% of |K| of the fine mesh's
/// (measured 2.2% and 4.3% at 30°, 0.4% and 1.5% at 60°). When it reached
/// the kink they were 6.0% and 10.0% off at 30°, and 2.7% and 18.4% at
/// 60° (K_II 0.48 MPa√m against 0.28), where the next growth step kinked
/// 2.4° off the converged angle.
#[test]
fn a_wing_tip_one_increment_past_a_kink_reads_k_from_the_straight_wing() {
    let wing = |n: usize, kink: f64| {
        let mut s = bundled("specimen_single_flaw");
        s.mesh.nx = n;
        s.mesh.ny = n;
        let p = s.cracks[0].points.clone().expect("a polyline flaw");
        let (a, b) = (p[0], p[1]);
        let along = (b[1] - a[1]).atan2(b[0] - a[0]) + kink.to_radians();
        let tip = [b[0] + 1.5e-3 * along.cos(), b[1] + 1.5e-3 * along.sin()];
        s.cracks[0].points = Some(vec![a, b, tip]);
        let r = solve(s);
        let t = r.tips.iter().find(|t| t.tip == 1).expect("the wing's tip");
        (t.k1, t.k2)
    };
    for kink in [30.0, 60.0] {
        let (coarse, fine) = (wing(60, kink), wing(240, kink));
        let k = fine.0.hypot(fine.1);
        let (e1, e2) = ((coarse.0 - fine.0).abs() / k, (coarse.1 - fine.1).abs() / k);
        assert!(
            e1 < 0.05 && e2 < 0.05,
            "{kink}° kink: (K_I, K_II) {coarse:?} against {fine:?} on the fine mesh"
        );
    }
}

/// Reference: the interaction integral evaluated from scratch. A tip's
/// domain kept from one solve to the next on a discretisation (its shape
/// functions, `∇q` and auxiliary fields stored) gives, at another
/// displacement, exactly the K and T a domain made afresh gives: bit for
/// bit on an inclined closed crack with friction, at the solved
/// displacement and at twice and minus it. The kept domains no longer fit
/// the discretisation of a crack whose tip moved a tenth of an element.
#[test]
fn kept_tip_domains_give_the_sifs_of_fresh_ones() {
    use cdca::fracture::tips::{TipDomains, all_tip_sifs};
    use cdca::geometry::plane::P2;
    let mut s = plate(1.0, 1.0, 40, 40);
    tension_top_bottom(&mut s, -1e6);
    let mut flaw = centre_crack(0.503, 0.497, 0.21, 33.0);
    flaw.friction = 0.4;
    s.cracks.push(flaw);
    let scene = valid(s.clone());
    let mut sim = Simulation::new(scene).expect("valid");
    sim.solve().expect("solve");
    let x = sim.xfem();
    let kept = TipDomains::new(x);
    // the contact tractions p_N n + p_T t, t = (n_y, −n_x)
    let tractions: Vec<P2> = sim
        .contact_points()
        .iter()
        .map(|c| {
            let [nx, ny] = c.normal;
            P2::new(c.p_n * nx + c.p_t * ny, c.p_n * ny - c.p_t * nx)
        })
        .collect();
    assert!(tractions.iter().any(|t| t.norm() > 0.0), "closed faces");
    for scale in [1.0, 2.0, -1.0] {
        let u: Vec<f64> = sim.displacement().iter().map(|v| scale * v).collect();
        let fresh = all_tip_sifs(x, &u, &tractions);
        let again = kept.sifs(x, &u, &tractions);
        assert_eq!(fresh.len(), 2);
        assert!(fresh.iter().all(|(_, _, _, k)| k.k1 != 0.0 && k.k2 != 0.0));
        assert_eq!(again, fresh, "scale {scale}");
    }
    assert!(kept.fits(x));
    let h = 1.0 / 40.0;
    let mut moved = s;
    moved.cracks[0] = centre_crack(0.503, 0.497, 0.21 + 0.1 * h, 33.0);
    let other = Simulation::new(valid(moved)).expect("valid");
    assert!(!kept.fits(other.xfem()));
}
