//! Verification of frictional contact on closed crack faces (issue:
//! contact). Reference: a closed centre crack of half-length a at 45° in a
//! large plate (a/b = 0.1) under biaxial compression P_V, P_H = k P_V, with
//! τ = P_V(1−k)/2 and σ_n = P_V(1+k)/2 resolved on the crack plane:
//! `K_II = (τ − μσ_n − c_c)√(πa)` when positive (sliding), `K_II = 0` when
//! the crack sticks, `K_I = 0` (closed).

mod common;

use cdca::report::SolveReport;
use cdca::scene::{Plane, SceneFile, SideBc};
use cdca::{ContactState, Simulation};
use common::docs_row::{pct_abs, record_row, tiny, verification_row};
use common::*;

const A: f64 = 0.05;
const N: usize = 100;

/// 1 m plate, 45° crack of half-length 0.05 at the centre, rollers on the
/// bottom and left, `-p` on top and `-k p` on the right.
fn biaxial(k: f64, mu: f64, cohesion: f64, kn_h_over_e: Option<f64>, p: f64) -> SceneFile {
    biaxial_on(N, k, mu, cohesion, kn_h_over_e, p)
}

fn biaxial_on(
    n: usize,
    k: f64,
    mu: f64,
    cohesion: f64,
    kn_h_over_e: Option<f64>,
    p: f64,
) -> SceneFile {
    let mut s = plate(1.0, 1.0, n, n);
    s.material.young = 4.78e9;
    s.material.poisson = 0.25;
    s.material.plane = Plane::Stress;
    s.boundary.bottom = SideBc::Roller;
    s.boundary.left = SideBc::Roller;
    s.boundary.top = SideBc::Traction {
        normal: -p,
        shear: 0.0,
    };
    s.boundary.right = SideBc::Traction {
        normal: -k * p,
        shear: 0.0,
    };
    let mut c = centre_crack(0.5 + 1e-4, 0.5, A, 45.0);
    c.friction = mu;
    c.cohesion = cohesion;
    if let Some(alpha) = kn_h_over_e {
        let kn = alpha * s.material.young / (1.0 / n as f64);
        c.normal_stiffness = Some(kn);
        c.shear_stiffness = Some(0.1 * kn);
    }
    s.cracks.push(c);
    s
}

fn resolved(k: f64, p: f64) -> (f64, f64) {
    (p * (1.0 - k) / 2.0, p * (1.0 + k) / 2.0)
}

fn k2_exact(k: f64, mu: f64, c: f64, p: f64) -> f64 {
    let (tau, sn) = resolved(k, p);
    (tau - mu * sn - c).max(0.0) * (PI * A).sqrt()
}

/// K_II within 3% of `(τ − μσ_n)√(πa)` over k ∈ {0, 0.1, 0.2} × μ ∈ {0, 0.2,
/// 0.32, 0.5}; |K_I| < 2% of σ_n√(πa); with μ ≥ (1−k)/(1+k) the crack sticks
/// and |K_II| < 2% of τ√(πa). A sticking crack still shears elastically by
/// τ/k_T (the default k_T = 10 E/h), which leaves K_II ∝ h: the sticking
/// cases run on a finer mesh (160 across, a = 8h).
#[test]
fn closed_crack_k2_table() {
    let p = 10e6;
    let root = (PI * A).sqrt();
    let mut cases: Vec<(f64, f64)> = Vec::new();
    for k in [0.0, 0.1, 0.2] {
        for mu in [0.0, 0.2, 0.32, 0.5] {
            cases.push((k, mu));
        }
    }
    cases.push((0.2, 0.83));
    cases.push((0.0, 1.2));
    println!("   k     μ   K_II/(τ√πa)  exact   error   K_I/(σn√πa)  contact");
    // sliding: the K_II error range and the largest |K_I|/(σ_n√πa); stuck:
    // the largest |K_II|/(τ√πa)
    let (mut slide_lo, mut slide_hi, mut k1_worst, mut stuck_worst) =
        (f64::INFINITY, 0.0f64, 0.0f64, 0.0f64);
    for (k, mu) in cases {
        let sticks = mu >= (1.0 - k) / (1.0 + k);
        let r = solve(biaxial_on(
            if sticks { 160 } else { N },
            k,
            mu,
            0.0,
            None,
            p,
        ));
        let (tau, sn) = resolved(k, p);
        let exact = k2_exact(k, mu, 0.0, p);
        assert!(r.contact.converged, "k {k} μ {mu}: {:?}", r.contact);
        for t in &r.tips {
            let err = if exact > 0.0 {
                rel(t.k2.abs(), exact)
            } else {
                t.k2.abs() / (tau * root)
            };
            println!(
                "{k:5.2} {mu:5.2}  {:10.4}  {:7.4}  {err:7.4}  {:10.4}   it {} stick {} slip {}",
                t.k2.abs() / (tau * root),
                exact / (tau * root),
                t.k1 / (sn * root),
                r.contact.iterations,
                r.contact.stick,
                r.contact.slip
            );
            if exact > 0.0 {
                slide_lo = slide_lo.min(err);
                slide_hi = slide_hi.max(err);
                k1_worst = k1_worst.max(t.k1.abs() / (sn * root));
            } else {
                stuck_worst = stuck_worst.max(err);
            }
            let tol = if exact > 0.0 { 0.03 } else { 0.02 };
            assert!(err < tol, "k {k} μ {mu}: K_II {:.4e} vs {exact:.4e}", t.k2);
            assert!(
                t.k1.abs() < 0.02 * sn * root,
                "k {k} μ {mu}: K_I {:.4e}",
                t.k1
            );
        }
        if exact == 0.0 {
            assert_eq!(r.contact.slip, 0, "a sticking crack has no slip point");
        }
    }
    record_row(
        "verification",
        "contact_verification-closed_crack_k2_table-1",
        &[
            "closed 45° crack, biaxial compression, k ∈ {0, 0.1, 0.2} × μ ∈ {0, 0.2, 0.32, 0.5} ((τ − μσ_n)√πa)",
            "`closed_crack_k2_table`",
            "100 × 100",
            &format!(
                "K_II within {}–{}, |K_I| ≤ {} of σ_n√πa",
                pct_abs(slide_lo, 2),
                pct_abs(slide_hi, 2),
                pct_abs(k1_worst, 2)
            ),
            "3%, 2%",
        ],
    );
    record_row(
        "verification",
        "contact_verification-closed_crack_k2_table-2",
        &[
            "sticking 45° crack (μ ≥ (1−k)/(1+k))",
            "`closed_crack_k2_table`",
            "160 × 160",
            &format!(
                "|K_II| ≤ {} of τ√πa (elastic pre-slip τ/k_T)",
                pct_abs(stuck_worst, 2)
            ),
            "2%",
        ],
    );
}

/// Face cohesion c_c lowers K_II by `c_c√(πa)` (within 3%).
#[test]
fn face_cohesion_lowers_k2() {
    let (p, k, mu, c) = (10e6, 0.1, 0.2, 1e6);
    let without = solve(biaxial(k, mu, 0.0, None, p));
    let with = solve(biaxial(k, mu, c, None, p));
    let mut worst: f64 = 0.0;
    for (a, b) in without.tips.iter().zip(&with.tips) {
        let drop = a.k2.abs() - b.k2.abs();
        assert!(rel(drop, c * (PI * A).sqrt()) < 0.03, "drop {drop:.4e}");
        assert!(rel(b.k2.abs(), k2_exact(k, mu, c, p)) < 0.03);
        worst = worst.max(rel(drop, c * (PI * A).sqrt()));
    }
    verification_row(
        "contact_verification",
        "face_cohesion_lowers_k2",
        "face cohesion c_c (K_II drops by c_c√πa)",
        "100 × 100",
        &format!("within {}", pct_abs(worst, 2)),
        "3%",
    );
}

/// The slip of a frictionless sliding crack follows the elliptical profile
/// `δ(s) = 4τ/E' √(a² − s²)` within 5% for |s| ≤ 0.7a.
#[test]
fn slip_profile_is_elliptical() {
    let p = 10e6;
    let mut sim = Simulation::new(valid(biaxial(0.0, 0.0, 0.0, None, p))).expect("valid");
    let r = sim.solve().expect("solve");
    assert!(r.converged() && r.contact.cycling == 0, "{:?}", r.contact);
    let (tau, _) = resolved(0.0, p);
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for cp in sim.contact_points() {
        let s = ((cp.x - 0.5 - 1e-4).powi(2) + (cp.y - 0.5).powi(2)).sqrt();
        if s > 0.7 * A {
            continue;
        }
        let exact = 4.0 * tau / 4.78e9 * (A * A - s * s).sqrt();
        assert!(
            rel(cp.slip.abs(), exact) < 0.05,
            "s = {s:.4}: slip {:.4e} vs {exact:.4e}",
            cp.slip
        );
        worst = worst.max(rel(cp.slip.abs(), exact));
        checked += 1;
    }
    assert!(checked >= 6, "only {checked} points checked");
    verification_row(
        "contact_verification",
        "slip_profile_is_elliptical",
        "slip profile ∝ √(a² − s²)",
        "100 × 100",
        &format!("within {} for |s| ≤ 0.7a", pct_abs(worst, 2)),
        "5%",
    );
}

/// An open crack in tension with contact switched on: every point open,
/// one contact iteration, and K identical (1e-10) to the solve without
/// contact (direct linear solve, no face term).
#[test]
fn open_crack_costs_nothing_and_matches_no_contact() {
    let mut s = plate(1.0, 1.0, 60, 60);
    tension_top_bottom(&mut s, 1e6);
    let mut c = centre_crack(0.5, 0.5, 0.1, 30.0);
    c.friction = 0.6;
    s.cracks.push(c);
    let mut sim = Simulation::new(valid(s.clone())).expect("valid");
    let r = sim.solve().expect("solve");
    assert!(r.converged() && r.contact.cycling == 0, "{:?}", r.contact);
    assert_eq!(r.contact.iterations, 1);
    assert_eq!(r.contact.stick + r.contact.slip, 0);
    assert!(r.contact.open > 0);
    // without contact: the plain linear problem
    let model = cdca::discretisation::model::Model::new(valid(s.clone()));
    let x = model.discretise(model.initial_cracks());
    let f = cdca::discretisation::loads::traction_forces(&x, &s.boundary);
    let u = cdca::solvers::direct::Factor::new(&x, &[])
        .expect("factor")
        .solve(&f)
        .expect("solve");
    let field = cdca::discretisation::field::Field { xfem: &x, u: &u };
    for t in &r.tips {
        let frame = cdca::geometry::cracks::TipFrame::of(&x.funcs.cracks[t.crack], t.tip);
        let plain = cdca::fracture::sif::tip_sifs(
            &field,
            t.crack,
            &frame,
            cdca::fracture::tips::DOMAIN_RADIUS * x.mesh.h(),
            &[],
        );
        assert!(
            rel(t.k1, plain.k1) < 1e-10 && rel(t.k2, plain.k2) < 1e-10,
            "{t:?} vs {plain:?}"
        );
    }
    verification_row(
        "contact_verification",
        "open_crack_costs_nothing_and_matches_no_contact",
        "open crack in tension with contact on",
        "60 × 60",
        &format!("{} contact iteration, K identical", r.contact.iterations),
        "1e-10",
    );
}

/// Doubling every load doubles K to 1e-8 (friction, no cohesion: the
/// problem is positively homogeneous of degree one).
#[test]
fn doubling_the_load_doubles_k() {
    let a = solve(biaxial(0.1, 0.32, 0.0, None, 10e6));
    let b = solve(biaxial(0.1, 0.32, 0.0, None, 20e6));
    let mut worst: f64 = 0.0;
    for (x, y) in a.tips.iter().zip(&b.tips) {
        worst = worst.max(rel(y.k2, 2.0 * x.k2));
        assert!(
            rel(y.k2, 2.0 * x.k2) < 1e-8 && rel(y.k1, 2.0 * x.k1) < 1e-7,
            "{} {}",
            x.k2,
            y.k2
        );
    }
    verification_row(
        "contact_verification",
        "doubling_the_load_doubles_k",
        "doubling every load doubles K",
        "100 × 100",
        &format!("K_II to {}", tiny(worst)),
        "1e-8 (K_II), 1e-7 (K_I)",
    );
}

fn finite(r: &SolveReport) -> bool {
    r.tips
        .iter()
        .all(|t| t.k1.is_finite() && t.k2.is_finite() && t.t_stress.is_finite())
        && r.contact.residual.is_finite()
}

/// Stiff and extreme cases: penalty k_N h/E from 1 to 1e6, μ from 0 to 10,
/// loads from 1 Pa to 1 GPa. Every run converges (linear solve and contact
/// iteration, no cycling point) with finite numbers. Reference
/// `K_II = (τ − μσ_n)√(πa)` for a sliding crack: within 0.5% for
/// k_N h/E ≥ 100; a sticking crack (μ = 10) keeps `|K_II|` below 3% of
/// `τ√(πa)` (the elastic pre-slip of the penalty joint) for k_N h/E ≥ 100.
/// k_N h/E = 1 is a compliant joint, physically another problem: only the
/// status is asserted there.
#[test]
fn stiff_and_extreme_cases_end_cleanly() {
    println!("k_N h/E      μ       P [Pa]   status     it  cyc   K_II error");
    let (mut slide_lo, mut slide_hi, mut stuck_worst) = (f64::INFINITY, 0.0f64, 0.0f64);
    for alpha in [1.0, 1e2, 1e4, 1e6] {
        for mu in [0.0, 0.32, 10.0] {
            for p in [1.0, 10e6, 1e9] {
                let mut sim =
                    Simulation::new(valid(biaxial(0.2, mu, 0.0, Some(alpha), p))).expect("valid");
                let r = sim.solve().expect("an explicit status, not an error");
                let case = format!("α {alpha:e} μ {mu} p {p:e}");
                assert!(finite(&r), "{case}: {r:?}");
                let exact = k2_exact(0.2, mu, 0.0, p);
                let (tau, _) = resolved(0.2, p);
                let k2 = r.tips[0].k2.abs();
                let err = if exact > 0.0 {
                    rel(k2, exact)
                } else {
                    k2 / (tau * (PI * A).sqrt())
                };
                println!(
                    "{alpha:8.0e} {mu:6.2} {p:12.0e}   {:9} {:3} {:4}   {err:.4}",
                    if r.converged() {
                        "converged"
                    } else {
                        "NOT conv."
                    },
                    r.contact.iterations,
                    r.contact.cycling
                );
                assert!(r.converged(), "{case}: {:?}", r.failure());
                assert_eq!(r.contact.cycling, 0, "{case}: cycling points");
                if alpha >= 1e2 {
                    if exact > 0.0 {
                        slide_lo = slide_lo.min(err);
                        slide_hi = slide_hi.max(err);
                    } else {
                        stuck_worst = stuck_worst.max(err);
                    }
                    let bound = if exact > 0.0 { 0.005 } else { 0.03 };
                    assert!(err < bound, "{case}: K_II error {err:.4} above {bound}");
                }
            }
        }
    }
    verification_row(
        "contact_verification",
        "stiff_and_extreme_cases_end_cleanly",
        "k_N h/E = 1…1e6, μ = 0…10, loads 1 Pa…1 GPa",
        "100 × 100",
        &format!(
            "every run converged, 0 cycling; sliding K_II error {}–{}, stuck |K_II| ≤ {} of τ√πa for k_N h/E ≥ 100",
            pct_abs(slide_lo, 2),
            pct_abs(slide_hi, 2),
            pct_abs(stuck_worst, 2)
        ),
        "converged; 0.5% / 3%",
    );
}

/// A case built on the stick/slip threshold (μ = (1−k)/(1+k), τ = μσ_n)
/// converges with every point obeying the contact law, no face open, and
/// |K_II| below 5% of τ√(πa) (the crack is just stuck).
#[test]
fn threshold_case_terminates() {
    let k = 0.2;
    let mu = (1.0 - k) / (1.0 + k);
    let mut sim = Simulation::new(valid(biaxial(k, mu, 0.0, None, 10e6))).expect("valid");
    let r = sim.solve().expect("explicit status");
    assert!(r.contact.iterations <= 50);
    // at the threshold a point may cycle; it must still obey the law
    assert!(r.converged(), "{:?}", r.failure());
    assert_eq!(r.contact.violating, 0, "{:?}", r.contact);
    assert!(finite(&r));
    println!(
        "threshold: converged {} iterations {} cycling {} stick {} slip {}",
        r.contact.converged,
        r.contact.iterations,
        r.contact.cycling,
        r.contact.stick,
        r.contact.slip
    );
    let (tau, _) = resolved(k, 10e6);
    assert!(
        r.tips
            .iter()
            .all(|t| t.k2.abs() < 0.05 * tau * (PI * A).sqrt())
    );
    let states: Vec<ContactState> = sim.contact_points().iter().map(|c| c.state).collect();
    assert!(states.iter().all(|s| *s != ContactState::Open));
    let worst = r
        .tips
        .iter()
        .map(|t| t.k2.abs() / (tau * (PI * A).sqrt()))
        .fold(0.0, f64::max);
    verification_row(
        "contact_verification",
        "threshold_case_terminates",
        "stick/slip threshold μ = (1−k)/(1+k)",
        "100 × 100",
        &format!(
            "converged, no open face, |K_II| = {} of τ√πa",
            pct_abs(worst, 2)
        ),
        "|K_II| < 5% of τ√πa",
    );
}

/// Same problem, two starts (issue 37): solved from open faces and from
/// the faces bonded (every point stuck, friction limits far above any
/// traction), the frictional problem has one solution on
/// cases chosen to be where it could have two: the stick/slip threshold
/// μ = (1−k)/(1+k) and just below and above it (1% off), where part of the
/// crack sticks and part slips. Both starts converge, to the same contact
/// counts and K within `SAME_SOLUTION_K` (1e-6 of the largest |K|), so
/// `OtherSolutionReport::between` finds none. The two starts take other
/// paths (the bonded start's contact iteration a different number of
/// iterations), so the check compares two iterations, not one twice.
/// `cdca solve` runs the second start wherever faces close and prints a
/// note when it finds another solution; none of the bundled scenes, nor 20
/// near-threshold variants of the pairs, the single flaw and the plate,
/// has one. The workbench's different answers of issue 37 came from warm
/// starts with another slip history, which its Solve no longer uses.
#[test]
fn the_frictional_problem_has_one_solution_from_both_starts() {
    let k = 0.2;
    let threshold = (1.0 - k) / (1.0 + k);
    for mu in [0.99 * threshold, threshold, 1.01 * threshold] {
        let scene = valid(biaxial(k, mu, 0.0, None, 10e6));
        let mut open = Simulation::new(scene).expect("valid");
        let first = open.solve().expect("solve");
        let second = open.bonded_start().expect("valid").solve().expect("solve");
        println!(
            "μ = {mu:.4}: open start {} stick {} slip in {} iterations; bonded start {} stick {} \
             slip in {}",
            first.contact.stick,
            first.contact.slip,
            first.contact.iterations,
            second.contact.stick,
            second.contact.slip,
            second.contact.iterations
        );
        assert!(first.converged() && second.converged(), "μ = {mu}");
        assert_ne!(
            first.contact.iterations, second.contact.iterations,
            "μ = {mu}: one path"
        );
        assert!(
            cdca::report::OtherSolutionReport::worth_checking(&first),
            "μ = {mu}: converged, faces closed"
        );
        assert_eq!(
            cdca::report::OtherSolutionReport::between(&first, &second, "bonded"),
            None,
            "μ = {mu}"
        );
    }
    // the comparison itself: other contact counts are another solution
    let base = valid(biaxial(k, threshold, 0.0, None, 10e6));
    let first = Simulation::new(base)
        .expect("valid")
        .solve()
        .expect("solve");
    let mut other = first.clone();
    other.contact.slip += 1;
    other.contact.stick -= 1;
    let o = cdca::report::OtherSolutionReport::between(&first, &other, "bonded").expect("another");
    assert_eq!((o.stick, o.slip), (other.contact.stick, other.contact.slip));
    assert!(
        o.sentence(&first.contact)
            .contains("more than one solution")
    );
}

/// The solve with contact gives the same answer whatever the slices it is
/// run in: the workbench's relaxation (`relax(n)` once a frame, here one
/// sweep and 1000 sweeps a call) ends at the same contact states and the
/// same K, to the last bit, as the one-call solve of `cdca solve`, for the
/// direct solver, multigrid-CG and the paper's automaton; and each ends
/// within its tolerance of the direct reference (direct 1e-9,
/// multigrid-CG and automaton 1e-6, relative to K_II).
#[test]
fn relaxation_does_not_depend_on_the_slice_size() {
    for (kind, n, tol) in [
        (cdca::scene::SolverKind::Direct, 40, 1e-9),
        (cdca::scene::SolverKind::Multigrid, 40, 1e-6),
        (cdca::scene::SolverKind::Automaton, 26, 1e-6),
    ] {
        let mut s = biaxial_on(n, 0.1, 0.2, 0.0, None, 10e6);
        let reference = solve(s.clone());
        s.solver.kind = kind;
        let one_call = solve(s.clone());
        assert!(one_call.converged(), "{kind:?}: {:?}", one_call.contact);
        for slice in [1, 1000] {
            let mut sim = Simulation::new(valid(s.clone())).expect("valid");
            sim.start_relaxation();
            let mut calls = 0;
            while !sim.relax(slice).expect("relax").finished {
                calls += 1;
                assert!(calls < 200_000, "{kind:?} never finished");
            }
            let sliced = sim.report(0.0);
            assert_eq!(sliced.tips, one_call.tips, "{kind:?}, slices of {slice}");
            assert_eq!(
                (
                    sliced.contact.open,
                    sliced.contact.stick,
                    sliced.contact.slip
                ),
                (
                    one_call.contact.open,
                    one_call.contact.stick,
                    one_call.contact.slip
                ),
                "{kind:?}, slices of {slice}"
            );
            assert_eq!(sliced.solver.iterations, one_call.solver.iterations);
            let history = sim.residual_history();
            assert!(
                !history.is_empty() && history.windows(2).all(|w| w[1].iteration > w[0].iteration)
            );
        }
        for (a, b) in one_call.tips.iter().zip(&reference.tips) {
            assert!(
                rel(a.k2, b.k2) < tol && (a.k1 - b.k1).abs() < tol * b.k2.abs(),
                "{kind:?}: {a:?} vs {b:?}"
            );
        }
    }
}

/// A kinked closed flaw in a 30 mm specimen (60 × 60) under 100 MPa
/// compression: stuck, slipping and open points on one crack.
fn kinked_flaw_in_compression() -> cdca::scene::Scene {
    cdca::scene::Scene::from_json(
        r#"{"specimen":{"width":0.03,"height":0.03,"thickness":0.015},"mesh":{"nx":60,"ny":60},
        "material":{"young":4.78e9,"poisson":0.25,"plane":"stress"},
        "cracks":[{"friction":0.6,"points":[[0.013422997823968622,0.007952845776435466],
          [0.013056893294392255,0.009407482319845423],[0.012689086498414534,0.010861689375540245],
          [0.013407102881642185,0.012178675508123533],[0.014132653513636467,0.01349152594911546],
          [0.017327346486363533,0.01572847405088454],[0.01804686296978976,0.01704464122494639],
          [0.01883531958064606,0.018320703987038053],[0.018480235065011483,0.019778069756759765],
          [0.018225088699127114,0.02125621059307273]]}],
        "boundary":{"bottom":{"kind":"roller"},"left":{"kind":"free"},"right":{"kind":"free"},
          "top":{"kind":"traction","normal":-100e6,"shear":0.0},
          "points":[{"at":[0.0,0.0],"fix":"x"}]}}"#,
    )
    .expect("scene")
}

/// [`kinked_flaw_in_compression`] discretised and solved with contact
/// (direct solver, no slip history): the discretisation, the load, the
/// committed states, the displacement, the states and how it ended.
fn solved_kinked_flaw() -> (
    cdca::discretisation::xfem::Xfem,
    Vec<f64>,
    Vec<cdca::contact::law::FaceState>,
    Vec<f64>,
    Vec<cdca::contact::law::FaceState>,
    cdca::contact::status::ContactInfo,
) {
    use cdca::contact::law::FaceState;
    let scene = kinked_flaw_in_compression();
    let model = cdca::discretisation::model::Model::new(scene.clone());
    let x = model.discretise(model.initial_cracks());
    let load = cdca::discretisation::loads::traction_forces(&x, &scene.boundary);
    let committed = vec![FaceState::default(); x.faces.len()];
    let mut u = vec![0.0; x.n_free()];
    let (states, info) = cdca::contact::iteration::solve_with_contact(
        &x,
        &load,
        &committed,
        &mut u,
        &mut cdca::solvers::linear::DirectSolver::default(),
        cdca::contact::status::ContactParams::default(),
    )
    .expect("solve");
    (x, load, committed, u, states, info)
}

/// Converged means a fixed point (default contact, `k_N = 100 E/h`): the
/// kinked crack of the 3.9 mm 35° μ = 0.6 flaw after its growth run (tension
/// wings on both ends), solved under −100 MPa. The iteration must end
/// converged, and one more solve of the system of its final states must
/// move `u` by at most the tolerance (1e-8 relative) and change no state.
/// Before the test was taken on the undamped step, this problem was
/// declared converged after 36 iterations on a step cut to β ≈ 1.5e-5
/// while that solve still moved `u` by 3.9e-4.
#[test]
fn converged_contact_is_a_fixed_point() {
    use cdca::contact::iteration::solve_with_contact_from;
    use cdca::contact::status::{ContactParams, relative_change};
    use cdca::solvers::linear::DirectSolver;

    let (x, f, committed, u, states, info) = solved_kinked_flaw();
    let params = ContactParams::default();
    assert!(info.converged, "{info:?}");
    assert_eq!(info.violating, 0, "{info:?}");
    let mut again = u.clone();
    let one = ContactParams {
        max_iterations: 1,
        ..params
    };
    let (states_again, _) = solve_with_contact_from(
        &x,
        &f,
        &committed,
        states.clone(),
        &mut None,
        &mut again,
        &mut DirectSolver::default(),
        one,
    )
    .expect("one more solve");
    let moved = relative_change(&again, &u);
    assert!(
        moved <= params.tolerance,
        "one more solve moved u by {moved:e}"
    );
    // every point is in the state the return mapping gives
    let changed = states
        .iter()
        .zip(&states_again)
        .filter(|(a, b)| a.state != b.state)
        .count();
    assert_eq!(changed, 0, "{changed} states changed");
}

/// Reference: the direct solve of a matrix factorised for the new states.
/// A contact solve whose states differ from a factorised matrix's at a
/// few points goes through a low-rank (Woodbury) correction of that
/// factor instead of a factorisation: the solutions agree to 1e-10
/// relative (both residuals are ~1e-13). A change of rank above
/// `MAX_RANK` is factorised.
#[test]
fn a_few_changed_contact_states_solve_as_the_factorised_matrix() {
    use cdca::contact::law::{ContactState, FaceState, contact_system};
    use cdca::solvers::linear::{DirectSolver, LinearSolver};
    use cdca::solvers::low_rank::MAX_RANK;

    let (x, load, committed, mut u, states, info) = solved_kinked_flaw();
    assert!(info.converged, "{info:?}");
    let system = |st: &[FaceState]| {
        let mut f = load.clone();
        let blocks = contact_system(&x, st, &committed, &mut f);
        (blocks, f)
    };
    // the first `count` closed points (that carry their own terms) turned
    // to `to`, or from stick to slip and back when `to` is `None`
    let leading: Vec<usize> = (0..states.len())
        .filter(|&i| states[i].state != ContactState::Open && x.faces[i].follows.is_none())
        .collect();
    let with = |to: Option<ContactState>, count: usize| {
        let mut st = states.clone();
        for &i in &leading[..count] {
            st[i].state = to.unwrap_or(match st[i].state {
                ContactState::Stick => ContactState::Slip,
                _ => ContactState::Stick,
            });
        }
        st
    };
    let (blocks, f) = system(&states);
    let mut solver = DirectSolver::default();
    solver.solve(&x, &blocks, &f, &mut u, true).expect("solve");
    assert_eq!(solver.correction_rank(), None);
    for (to, count) in [(None, 1), (None, 3), (Some(ContactState::Open), 2)] {
        let (blocks, f) = system(&with(to, count));
        let mut corrected = u.clone();
        let info = solver
            .solve(&x, &blocks, &f, &mut corrected, true)
            .expect("corrected");
        let rank = solver.correction_rank().unwrap_or(0);
        assert!(
            (1..=MAX_RANK).contains(&rank),
            "{count} points to {to:?}: rank {rank}"
        );
        assert!(info.converged, "{info:?}");
        let mut reference = u.clone();
        DirectSolver::default()
            .solve(&x, &blocks, &f, &mut reference, true)
            .expect("factorised");
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        let diff: Vec<f64> = corrected
            .iter()
            .zip(&reference)
            .map(|(a, b)| a - b)
            .collect();
        let rel = norm(&diff) / norm(&reference);
        assert!(rel <= 1e-10, "{count} points to {to:?}: differs by {rel:e}");
    }
    // every closed point stuck, then open: two penalty terms a point
    let closed = leading.len();
    assert!(2 * closed > MAX_RANK, "{closed} closed points");
    let mut solver = DirectSolver::default();
    let (blocks, f) = system(&with(Some(ContactState::Stick), closed));
    solver
        .solve(&x, &blocks, &f, &mut u, true)
        .expect("factorised");
    let (blocks, f) = system(&with(Some(ContactState::Open), closed));
    solver
        .solve(&x, &blocks, &f, &mut u, true)
        .expect("factorised");
    assert_eq!(solver.correction_rank(), None, "{closed} points opened");
}

/// The DOFs of the elements that hold face points: what a contact
/// iteration's gaps and contact blocks read.
fn face_dofs(x: &cdca::discretisation::xfem::Xfem) -> Vec<usize> {
    let mut dofs: Vec<usize> = x
        .faces
        .iter()
        .flat_map(|fp| &x.enriched[fp.slot].dofs)
        .filter(|&&d| d != cdca::discretisation::dofs::FIXED)
        .map(|&d| d as usize)
        .collect();
    dofs.sort_unstable();
    dofs.dedup();
    dofs
}

/// A solve taken on the faces' rows alone (`solve_reaching`: the load's
/// forward solve kept, the contact forces' on the part of the factor they
/// reach, the backward solve on the faces' supernodes and their ancestors)
/// gives the whole solve's values on the faces' DOFs to 1e-12 of the
/// largest, leaves most other DOFs as they were, and completes into the
/// whole solution (same tolerance, residual ~1e-13), factorised and
/// through a low-rank correction; a right-hand side that differs from the
/// load off the faces' DOFs is not taken.
#[test]
fn a_solve_on_the_faces_rows_is_the_whole_solve_there() {
    use cdca::contact::law::{ContactState, FaceState, contact_system};
    use cdca::contact::status::relative_change;
    use cdca::solvers::linear::{DirectSolver, LinearSolver};

    let (x, load, committed, u, states, info) = solved_kinked_flaw();
    assert!(info.converged, "{info:?}");
    let dofs = face_dofs(&x);
    let system = |st: &[FaceState]| {
        let mut f = load.clone();
        let blocks = contact_system(&x, st, &committed, &mut f);
        (blocks, f)
    };
    let mut stuck = states.clone();
    let flipped = stuck
        .iter_mut()
        .zip(&x.faces)
        .filter(|(s, fp)| s.state == ContactState::Slip && fp.follows.is_none())
        .take(2)
        .map(|(s, _)| s.state = ContactState::Stick)
        .count();
    assert_eq!(flipped, 2, "slipping points to change");
    let mut solver = DirectSolver::default();
    let (blocks, f) = system(&states);
    // factorised here; the solves below start on that factor
    solver
        .solve(&x, &blocks, &f, &mut u.clone(), true)
        .expect("solve");
    for (case, st) in [("factorised", &states), ("corrected", &stuck)] {
        let (blocks, f) = system(st);
        let mut reference = u.clone();
        let ref_info = DirectSolver::default()
            .solve(&x, &blocks, &f, &mut reference, true)
            .expect("whole solve");
        assert!(ref_info.converged, "{ref_info:?}");
        let largest = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        solver
            .start(&x, &blocks, &f, &u, case == "corrected")
            .expect("start");
        assert_eq!(
            solver.correction_rank().is_some(),
            case == "corrected",
            "{case}"
        );
        let elsewhere = vec![7.0; u.len()];
        let partial = solver
            .solve_reaching(&load, &dofs, &elsewhere)
            .expect("a factor on the faces' rows");
        for &d in &dofs {
            let e = (partial[d] - reference[d]).abs() / largest;
            assert!(e <= 1e-12, "{case}: DOF {d} off by {e:e}");
        }
        let kept = partial.iter().filter(|&&v| v == 7.0).count();
        assert!(
            2 * kept > u.len(),
            "{case}: only {kept} of {} rows left",
            u.len()
        );
        let status = solver.run(&x, &blocks, usize::MAX).expect("completed");
        assert!(status.finished && status.converged, "{case}: {status:?}");
        let rel = relative_change(&reference, solver.u());
        assert!(rel <= 1e-12, "{case}: completed solve differs by {rel:e}");
    }
    // a load on a DOF away from the faces: not a faces' solve
    let (blocks, f) = system(&states);
    let away = (0..u.len())
        .find(|d| dofs.binary_search(d).is_err())
        .expect("a DOF");
    let mut other = load.clone();
    other[away] += 1.0;
    solver.start(&x, &blocks, &f, &u, false).expect("start");
    assert!(solver.solve_reaching(&other, &dofs, &u).is_none());
}

/// The kinked flaw with μ = 1.5 on a penalty 100 times stiffer, and 40% of
/// its load.
fn stiff_and_light(
    x: &cdca::discretisation::xfem::Xfem,
    load: &[f64],
) -> (cdca::discretisation::xfem::Xfem, Vec<f64>) {
    let mut stiff = x.clone();
    for c in &mut stiff.funcs.cracks {
        c.friction = 1.5;
        c.kn *= 100.0;
        c.kt *= 100.0;
    }
    (stiff, load.iter().map(|v| 0.4 * v).collect())
}

/// The contact iteration with its state changes found on the faces' rows
/// ends where the same iteration with whole solves throughout does: the
/// same iterations and states, and the displacement to 1e-11 (the kinked
/// flaw, and the same flaw under 40% of the load with the faces' friction
/// at 1.5 on a penalty 100 times stiffer; the two differ by round-off,
/// 1.0e-12 on the stiff penalty, where every solve's residual is ~1e-13).
#[test]
fn contact_solves_on_the_faces_rows_end_where_whole_solves_do() {
    use cdca::contact::iteration::solve_with_contact;
    use cdca::contact::status::{ContactParams, relative_change};
    use cdca::solvers::linear::{DirectSolver, LinearSolver};

    let (x, load, committed, _, _, _) = solved_kinked_flaw();
    let (stiff, light) = stiff_and_light(&x, &load);
    for (case, x, load) in [("kinked flaw", &x, &load), ("stiff, μ 1.5", &stiff, &light)] {
        let solve = |solver: &mut dyn LinearSolver| {
            let mut u = vec![0.0; x.n_free()];
            // the damped fixed point, whose state changes the faces' rows
            // find (Newton's steps need whole solves)
            let params = ContactParams {
                newton: false,
                ..ContactParams::default()
            };
            let (states, info) = solve_with_contact(x, load, &committed, &mut u, solver, params)
                .expect("contact solve");
            (u, states, info)
        };
        let (u, states, info) = solve(&mut DirectSolver::default());
        let mut whole = Restricted {
            couplings: true,
            ..Restricted::default()
        };
        let (u_whole, states_whole, info_whole) = solve(&mut whole);
        assert!(
            info.converged && info_whole.converged,
            "{case}: {info:?} {info_whole:?}"
        );
        assert!(
            info.face_solves > 0,
            "{case}: no state change on the faces' rows"
        );
        assert_eq!(info_whole.face_solves, 0, "{case}");
        assert_eq!(info.iterations, info_whole.iterations, "{case}");
        let same = states
            .iter()
            .zip(&states_whole)
            .all(|(a, b)| a.state == b.state);
        assert!(same, "{case}: contact states differ");
        let rel = relative_change(&u_whole, &u);
        assert!(rel <= 1e-11, "{case}: displacement differs by {rel:e}");
    }
}

/// Reference: whole solves. The coupling `aᵀ K⁻¹ b` between face vectors
/// (each face point's normal jump against each one's tangential jump) that
/// the friction limits' Newton step reads comes from forward solves of the
/// vectors alone on the part of the factor they reach; through a low-rank
/// correction (three points turned from stick to slip or back) it takes
/// the correction's term off. Both agree with `aᵀ` times the direct
/// solution for `b` to 1e-10 of the largest entry.
#[test]
fn couplings_between_face_vectors_are_those_of_whole_solves() {
    use cdca::contact::law::{ContactState, FaceState, contact_system, jump_operators};
    use cdca::contact::limit_newton::by_dof;
    use cdca::solvers::linear::{DirectSolver, LinearSolver};

    let (x, load, committed, mut u, states, info) = solved_kinked_flaw();
    assert!(info.converged, "{info:?}");
    let leading: Vec<usize> = (0..states.len())
        .filter(|&i| states[i].state != ContactState::Open && x.faces[i].follows.is_none())
        .collect();
    let rows: Vec<_> = leading
        .iter()
        .map(|&i| by_dof(&x, &x.faces[i], &jump_operators(&x.faces[i]).0, 1.0))
        .collect();
    let cols: Vec<_> = leading
        .iter()
        .map(|&i| by_dof(&x, &x.faces[i], &jump_operators(&x.faces[i]).1, 1.0))
        .collect();
    let mut flipped = states.clone();
    for &i in &leading[..3] {
        flipped[i].state = match flipped[i].state {
            ContactState::Stick => ContactState::Slip,
            _ => ContactState::Stick,
        };
    }
    let mut solver = DirectSolver::default();
    for (st, corrected) in [(&states, false), (&flipped, true)] {
        let st: &[FaceState] = st;
        let mut f = load.clone();
        let blocks = contact_system(&x, st, &committed, &mut f);
        solver.solve(&x, &blocks, &f, &mut u, true).expect("solve");
        assert_eq!(solver.correction_rank().is_some(), corrected);
        let m = solver.coupling(&rows, &cols).expect("a factor");
        let mut largest = 0.0f64;
        let mut worst = 0.0f64;
        for (j, b) in cols.iter().enumerate() {
            let mut fb = vec![0.0; x.n_free()];
            for &(d, v) in b {
                fb[d] += v;
            }
            let mut ub = vec![0.0; x.n_free()];
            DirectSolver::default()
                .solve(&x, &blocks, &fb, &mut ub, true)
                .expect("whole solve");
            for (i, a) in rows.iter().enumerate() {
                let reference: f64 = a.iter().map(|&(d, v)| v * ub[d]).sum();
                largest = largest.max(reference.abs());
                worst = worst.max((m[(i, j)] - reference).abs());
            }
        }
        println!(
            "{}×{} couplings, corrected {corrected}: largest {largest:e}, worst difference {worst:e}",
            rows.len(),
            cols.len()
        );
        assert!(worst <= 1e-10 * largest, "{worst:e} of {largest:e}");
    }
}

/// Reference: the same contact iteration with the friction limits
/// Anderson-mixed (a solver that offers no couplings). Where the direct
/// solver takes Newton's step to the limits' fixed point instead, the
/// kinked flaw's contact solve ends in the same states with the same
/// displacement (to the contact tolerance, 1e-8), in fewer iterations.
#[test]
fn the_friction_limits_newton_step_ends_where_the_mix_does() {
    use cdca::contact::iteration::solve_with_contact;
    use cdca::contact::law::FaceState;
    use cdca::contact::status::{ContactParams, relative_change};

    let (x, load, _, newton_u, newton, info) = solved_kinked_flaw();
    let committed = vec![FaceState::default(); x.faces.len()];
    let mut mixed_u = vec![0.0; x.n_free()];
    let (mixed, mixed_info) = solve_with_contact(
        &x,
        &load,
        &committed,
        &mut mixed_u,
        &mut Restricted::default(),
        ContactParams::default(),
    )
    .expect("solve");
    println!(
        "Newton: {} iterations, mix: {} iterations",
        info.iterations, mixed_info.iterations
    );
    assert!(info.converged && mixed_info.converged);
    let differ = newton
        .iter()
        .zip(&mixed)
        .filter(|(a, b)| a.state != b.state)
        .count();
    assert_eq!(differ, 0);
    let moved = relative_change(&newton_u, &mixed_u);
    assert!(moved <= 1e-8, "{moved:e}");
    assert!(info.iterations < mixed_info.iterations);
}

/// The direct solver restricted: every contact iteration solves the whole
/// system (no `solve_reaching`), and without `couplings` the contact
/// iteration mixes the friction limits (Anderson) instead of taking
/// Newton's step.
#[derive(Default)]
struct Restricted {
    direct: cdca::solvers::linear::DirectSolver,
    couplings: bool,
}
impl cdca::solvers::linear::LinearSolver for Restricted {
    fn name(&self) -> &'static str {
        self.direct.name()
    }
    fn start(
        &mut self,
        x: &cdca::discretisation::xfem::Xfem,
        blocks: &[cdca::discretisation::assembly::ElementBlock],
        f: &[f64],
        u0: &[f64],
        changed: bool,
    ) -> Result<(), cdca::error::SolveError> {
        self.direct.start(x, blocks, f, u0, changed)
    }
    fn run(
        &mut self,
        x: &cdca::discretisation::xfem::Xfem,
        blocks: &[cdca::discretisation::assembly::ElementBlock],
        max: usize,
    ) -> Result<cdca::solvers::relaxation::RelaxStatus, cdca::error::SolveError> {
        self.direct.run(x, blocks, max)
    }
    fn u(&self) -> &[f64] {
        self.direct.u()
    }
    fn info(&self) -> cdca::solvers::linear::LinearInfo {
        self.direct.info()
    }
    fn samples(&self) -> &[cdca::solvers::relaxation::ResidualSample] {
        self.direct.samples()
    }
    fn coupling(
        &self,
        rows: &[cdca::solvers::forward::SparseColumn],
        cols: &[cdca::solvers::forward::SparseColumn],
    ) -> Option<nalgebra::DMatrix<f64>> {
        self.couplings
            .then(|| self.direct.coupling(rows, cols))
            .flatten()
    }
}

/// Reference: the contact counts of the same solve with the limits mixed
/// (663186d, before Newton's step: 7 open, 23 stuck, converged in 18
/// iterations). A fuzzed scene (`scripts/fuzz_scenes.sh 100 11`, geometry
/// 35, kept as `tests/scenes/fuzz_mu5_edge_cracks.json`): three cracks of
/// the default specimen on a 20 × 20 mesh, along element edges and through
/// nodes, one with a segment 1.5e-6 m long, all at μ = 5. Newton's steps
/// to the friction limits flipped the same points between stick and slip
/// in a cycle of four iterations until the 200-iteration cap; after
/// `NEWTON_MISSES` missed steps the mix takes over, and the solve
/// converges to the mix's states.
#[test]
fn newton_steps_that_keep_missing_give_way_to_the_mix() {
    let scene = SceneFile::from_json(include_str!(
        "../../../tests/scenes/fuzz_mu5_edge_cracks.json"
    ))
    .expect("scene");
    let mut sim = Simulation::new(valid(scene)).expect("valid");
    let r = sim.solve().expect("solve");
    println!("{:?}", r.contact);
    assert!(r.converged(), "{:?}", r.contact);
    assert_eq!(r.contact.violating, 0);
    assert_eq!(
        (r.contact.open, r.contact.stick, r.contact.slip),
        (7, 23, 0)
    );
}

/// The contact iteration's Newton steps (the direct solver) and the damped
/// fixed point (`newton: false`, as CG and the automaton iterate) end in
/// the same solution: every face point in the same state and the
/// displacement within the contact tolerance (1e-8; measured 1e-12 and
/// 4e-13), on the kinked flaw and on it with μ = 1.5 and a 100 times
/// stiffer penalty under 40% of the load.
#[test]
fn newton_steps_and_the_fixed_point_reach_the_same_states() {
    use cdca::contact::iteration::solve_with_contact;
    use cdca::contact::status::{ContactParams, relative_change};
    use cdca::solvers::linear::DirectSolver;

    let (x, load, committed, _, _, _) = solved_kinked_flaw();
    let (stiff, light) = stiff_and_light(&x, &load);
    let mut worst: f64 = 0.0;
    for (case, x, load) in [("kinked flaw", &x, &load), ("stiff, μ 1.5", &stiff, &light)] {
        let solve = |newton: bool| {
            let mut u = vec![0.0; x.n_free()];
            let params = ContactParams {
                newton,
                ..ContactParams::default()
            };
            let mut solver = DirectSolver::default();
            let (states, info) =
                solve_with_contact(x, load, &committed, &mut u, &mut solver, params)
                    .expect("contact solve");
            (u, states, info)
        };
        let (u, states, info) = solve(true);
        let (u_fixed, states_fixed, info_fixed) = solve(false);
        assert!(info.converged && !info.newton_fallback, "{case}: {info:?}");
        assert!(info_fixed.converged, "{case}: {info_fixed:?}");
        let differ = states
            .iter()
            .zip(&states_fixed)
            .filter(|(a, b)| a.state != b.state)
            .count();
        assert_eq!(differ, 0, "{case}: states differ at {differ} points");
        let rel = relative_change(&u_fixed, &u);
        assert!(rel <= 1e-8, "{case}: displacement differs by {rel:e}");
        worst = worst.max(rel);
    }
    verification_row(
        "contact_verification",
        "newton_steps_and_the_fixed_point_reach_the_same_states",
        "Newton steps against the damped fixed point (kinked flaw; μ 1.5, stiff penalty)",
        "60 × 60",
        &format!("same states, u within {}", tiny(worst)),
        "same states, 1e-8",
    );
}

/// Issue 61: a solve of many closed cracks takes a handful of contact
/// iterations, not dozens. `tests/scenes/many_closed_cracks.json` is the
/// held-out overlapping pair of point 24 of
/// `assets/studies/held_out_pairs_rock.json` after 45 growth steps at
/// 71b3a5e, its 42 cracks drawn (28 310 DOFs, 8 010 enriched; 287 open,
/// 3 stuck and 304 slipping face points at full load, 39 cracks with a
/// closed point). The damped fixed point took 50 contact iterations there;
/// the Newton steps must take at most 15 (measured 10) to the same states.
#[test]
fn many_closed_cracks_solve_in_a_handful_of_newton_steps() {
    use cdca::contact::iteration::solve_with_contact;
    use cdca::contact::law::ContactState;
    use cdca::contact::status::{ContactParams, relative_change};
    use cdca::solvers::linear::DirectSolver;

    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/scenes/many_closed_cracks.json"
    );
    let text = std::fs::read_to_string(path).expect("tests/scenes/many_closed_cracks.json");
    let scene = cdca::Scene::from_json(&text).expect("valid");
    let model = cdca::discretisation::model::Model::new(scene.clone());
    let x = model.discretise(model.initial_cracks());
    let load = cdca::discretisation::loads::traction_forces(&x, &scene.boundary);
    let committed = vec![cdca::contact::law::FaceState::default(); x.faces.len()];
    let solve = |newton: bool| {
        let mut u = vec![0.0; x.n_free()];
        let params = ContactParams {
            newton,
            ..ContactParams::default()
        };
        let (states, info) = solve_with_contact(
            &x,
            &load,
            &committed,
            &mut u,
            &mut DirectSolver::default(),
            params,
        )
        .expect("contact solve");
        (u, states, info)
    };
    let (u, states, info) = solve(true);
    assert!(info.converged && !info.newton_fallback, "{info:?}");
    assert!(
        info.iterations <= 15,
        "{} contact iterations",
        info.iterations
    );
    let closed_cracks = (0..x.funcs.cracks.len())
        .filter(|&c| {
            x.faces
                .iter()
                .zip(&states)
                .any(|(fp, s)| fp.crack == c && s.state != ContactState::Open)
        })
        .count();
    assert!(
        closed_cracks >= 35,
        "{closed_cracks} cracks with a closed point"
    );
    let (u_fixed, states_fixed, info_fixed) = solve(false);
    assert!(
        info_fixed.converged && info_fixed.iterations >= 40,
        "{info_fixed:?}"
    );
    let differ = states
        .iter()
        .zip(&states_fixed)
        .filter(|(a, b)| a.state != b.state)
        .count();
    assert_eq!(differ, 0, "states differ at {differ} points");
    let rel = relative_change(&u_fixed, &u);
    assert!(rel <= 1e-8, "displacement differs by {rel:e}");
    verification_row(
        "contact_verification",
        "many_closed_cracks_solve_in_a_handful_of_newton_steps",
        "39 closed cracks: Newton steps against the fixed point's states",
        "100 × 100",
        &format!(
            "{} contact iterations ({} fixed point), same states, u within {}",
            info.iterations,
            info_fixed.iterations,
            tiny(rel)
        ),
        "≤ 15, same states, 1e-8",
    );
}
