//! In-sweep contact (`solver.contact_update: "in_sweep"`, the paper's DCA
//! rule: each face point's state and traction updated as the automaton's
//! sweep passes its cells) against the outer contact loop (states updated
//! after each converged linear solve) with the same automaton.
//!
//! Reference: both iterations stop at the same fixed point, a displacement
//! `u` with `(K + K_c(s)) u = f + f_c(s, u)` and states `s` that the return
//! mapping gives at `u`, each to the automaton's tolerance (relative
//! residual 1e-10). So the SIFs agree to 1e-6 of the tip's `|K|` =
//! `max(|K_I|, |K_II|)` (measured: 1e-10; a mode that is nearly zero, like
//! K_I ≈ −2e4 Pa√m of a closed crack next to K_II ≈ −6.6e6, is compared on
//! that scale) and every face point is in the same state.

use std::path::PathBuf;

use cdca::report::SolveReport;
use cdca::scene::{ContactUpdate, SceneFile, SolverKind};
use cdca::{ContactState, Scene, Simulation};

fn scene(name: &str) -> SceneFile {
    let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenes"))
        .join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).expect("bundled scene is readable");
    Scene::from_json(&text)
        .expect("bundled scene is valid")
        .into_file()
}

/// The scene, checked.
fn valid(scene: SceneFile) -> Scene {
    Scene::try_from(scene).expect("valid scene")
}

fn with(mut scene: SceneFile, update: ContactUpdate) -> SceneFile {
    scene.solver.kind = SolverKind::Automaton;
    scene.solver.contact_update = update;
    scene
}

/// Solves; returns the report and the state of every face point.
fn solve(scene: SceneFile) -> (SolveReport, Vec<ContactState>) {
    let mut sim = Simulation::new(valid(scene)).expect("builds");
    let report = sim.solve().expect("solve");
    let states = sim.contact_points().iter().map(|p| p.state).collect();
    (report, states)
}

/// Outer loop and in-sweep on `scene` with the automaton: see
/// [`same_answer`].
fn agree(name: &str, scene: &SceneFile) {
    let outer = solve(with(scene.clone(), ContactUpdate::Outer));
    let inner = solve(with(scene.clone(), ContactUpdate::InSweep));
    same_answer(name, &outer, &inner);
}

/// Two solves of one scene: both converged, no point frozen, the crack
/// closed, same states, K within 1e-6 of |K| at every tip.
fn same_answer(
    name: &str,
    (a, a_states): &(SolveReport, Vec<ContactState>),
    (b, b_states): &(SolveReport, Vec<ContactState>),
) {
    for r in [a, b] {
        assert!(r.converged(), "{name} {}: {:?}", r.solver.kind, r.failure());
        assert_eq!(r.contact.cycling, 0, "{name}: {:?}", r.contact);
    }
    assert!(
        a_states.iter().any(|&s| s != ContactState::Open),
        "{name}: the crack should be closed"
    );
    assert_eq!(a_states, b_states, "{name}: states differ");
    assert_eq!(a.tips.len(), b.tips.len());
    for (p, q) in a.tips.iter().zip(&b.tips) {
        let scale = p.k1.abs().max(p.k2.abs());
        let (d1, d2) = ((p.k1 - q.k1).abs() / scale, (p.k2 - q.k2).abs() / scale);
        assert!(
            d1 <= 1e-6 && d2 <= 1e-6,
            "{name} tip {}/{}: K_I {} vs {}, K_II {} vs {} (differences {d1:.1e}, {d2:.1e} of |K|)",
            p.crack,
            p.tip,
            p.k1,
            q.k1,
            p.k2,
            q.k2
        );
    }
}

/// A closed crack at 45° under biaxial compression, μ = 0.3, penalty
/// contact (k_N h/E = 100): every point slips.
#[test]
fn closed_crack_biaxial_in_sweep_matches_outer_loop() {
    agree("closed_crack_biaxial", &scene("closed_crack_biaxial"));
}

/// The single-flaw specimen with the paper's compliant joint (200 GPa/m,
/// k_N h/E = 0.02, μ = 0.5): every point sticks. The automaton needs more
/// than 100 000 sweeps at ω = 1 on its 60 × 60 mesh, so ω = 1.9 here.
#[test]
fn specimen_single_flaw_in_sweep_matches_outer_loop() {
    let mut s = scene("specimen_single_flaw");
    s.cracks[0].normal_stiffness = Some(200e9);
    s.cracks[0].shear_stiffness = Some(20e9);
    s.solver.omega = 1.9;
    agree("specimen_single_flaw", &s);
}

/// The default scene as a user gets it (penalty contact, k_N h/E = 100,
/// μ = 0.5): every point slips. Over-relaxed in-sweep ran away there (ω
/// 1.5: all open, residual 6e8 after 1e6 sweeps; 1.9: overflow), as the
/// slip friction `μ k_N |g_N|` couples the normal gap into the tangential
/// force at each visit; the cells with face points are now relaxed at
/// ω = 1 and the rest at the scene's ω. At ω = 1.9 it converges (28 270
/// sweeps against 431 712 at ω = 1) to the direct solver's outer-loop
/// answer: same states, K within 1e-6 of |K|.
#[test]
fn sliding_specimen_in_sweep_over_relaxed_matches_direct() {
    let mut s = scene("specimen_single_flaw");
    let direct = solve(s.clone());
    assert!(direct.1.iter().all(|&s| s == ContactState::Slip));
    s.solver.omega = 1.9;
    let inner = solve(with(s, ContactUpdate::InSweep));
    same_answer("specimen_single_flaw", &direct, &inner);
}

/// A 45° crack in a plate under biaxial compression (k = 0.2, μ = 0.5),
/// on a 40 × 40 mesh instead of the scene's 120 × 120 (which takes the
/// automaton minutes).
#[test]
fn plate_45_biaxial_in_sweep_matches_outer_loop() {
    let mut s = scene("plate_45_biaxial_k0.2_mu0.5");
    s.mesh.nx = 40;
    s.mesh.ny = 40;
    agree("plate_45_biaxial_k0.2_mu0.5 (40 × 40)", &s);
}

/// Regression: over-relaxed in-sweep (ω = 1.8) on the 40 × 40 plate ran
/// away to slip friction 1e30 times the load and reported `converged`
/// with K ≈ 1e30, its residual being measured against `f` with those
/// forces. With the residual measured against the load and the cells that
/// carry face points relaxed at ω = 1, it converges (2 123 sweeps) to the
/// ω = 1 answer: K_II = −4.669206e6 Pa√m at tip 0, to 1e-6.
#[test]
fn over_relaxed_in_sweep_never_claims_a_runaway_state() {
    let mut s = with(scene("plate_45_biaxial_k0.2_mu0.5"), ContactUpdate::InSweep);
    s.mesh.nx = 40;
    s.mesh.ny = 40;
    s.solver.omega = 1.8;
    s.solver.max_iterations = 6000;
    let mut sim = Simulation::new(valid(s)).expect("builds");
    let r = sim.solve().expect("solve");
    assert!(r.converged(), "{:?}", r.failure());
    let k2 = r.tips[0].k2;
    assert!((k2 + 4.669_206e6).abs() <= 1e-6 * 4.67e6 + 1.0, "K_II {k2}");
}

/// Runs the in-sweep solve in slices of `slice` sweeps; returns the
/// displacement, the face states and tractions and the report.
fn sliced(scene: &SceneFile, slice: usize) -> (Vec<f64>, Vec<[f64; 3]>, SolveReport) {
    let mut sim = Simulation::new(valid(scene.clone())).expect("builds");
    sim.start_relaxation();
    while !sim.relax(slice).expect("relax").finished {}
    let points = sim
        .contact_points()
        .iter()
        .map(|p| [f64::from(p.state as u8), p.p_n, p.p_t])
        .collect();
    (sim.displacement().to_vec(), points, sim.report(0.0))
}

/// Contact updates happen at cell visits, never at a slice's end: slices
/// of 1 sweep and of 1000 sweeps give the same bits.
#[test]
fn in_sweep_does_not_depend_on_slicing() {
    let s = with(scene("closed_crack_biaxial"), ContactUpdate::InSweep);
    let (u1, p1, r1) = sliced(&s, 1);
    let (u2, p2, r2) = sliced(&s, 1000);
    assert!(r1.converged(), "{:?}", r1.failure());
    assert_eq!(r1.solver.iterations, r2.solver.iterations);
    assert!(
        u1.iter().zip(&u2).all(|(a, b)| a.to_bits() == b.to_bits()),
        "displacements differ"
    );
    let bits =
        |p: &Vec<[f64; 3]>| -> Vec<[u64; 3]> { p.iter().map(|v| v.map(f64::to_bits)).collect() };
    assert_eq!(bits(&p1), bits(&p2), "face states differ");
    for (a, b) in r1.tips.iter().zip(&r2.tips) {
        assert_eq!(a.k1.to_bits(), b.k1.to_bits());
        assert_eq!(a.k2.to_bits(), b.k2.to_bits());
    }
}

/// The workbench sees states change inside the sweeps: after the first
/// sweep of `closed_crack_biaxial` some points have closed (in-sweep),
/// while the outer loop still shows its starting states (all open) until
/// its first linear solve ends.
#[test]
fn in_sweep_states_are_live_between_slices() {
    let closed_after_one_sweep = |update| {
        let mut sim =
            Simulation::new(valid(with(scene("closed_crack_biaxial"), update))).expect("builds");
        sim.start_relaxation();
        // a new simulation's first calls integrate its elements; the call
        // that starts the solve sets the linear solve up only; the next
        // one sweeps
        while !sim.is_relaxing() {
            sim.relax(1).expect("relax");
        }
        sim.relax(1).expect("relax");
        sim.contact_points()
            .iter()
            .filter(|p| p.state != ContactState::Open)
            .count()
    };
    assert_eq!(closed_after_one_sweep(ContactUpdate::Outer), 0);
    assert!(closed_after_one_sweep(ContactUpdate::InSweep) > 0);
}

/// `in_sweep` is a rule of the automaton's cell visits: with another
/// solver the scene is rejected, naming the field and the value.
#[test]
fn in_sweep_needs_the_automaton() {
    for kind in [SolverKind::Direct, SolverKind::Cg, SolverKind::Multigrid] {
        let mut s = scene("closed_crack_biaxial");
        s.solver.kind = kind;
        s.solver.contact_update = ContactUpdate::InSweep;
        let Err(e) = Scene::try_from(s) else {
            panic!("{kind:?} with in_sweep was accepted");
        };
        let msg = e.to_string();
        assert!(
            msg.contains("solver.contact_update") && msg.contains("in_sweep"),
            "{msg}"
        );
    }
    let text = r#"{"specimen": {"width": 1, "height": 1}, "mesh": {"nx": 4, "ny": 4},
        "material": {"young": 1e9}, "solver": {"kind": "cg", "contact_update": "in_sweep"}}"#;
    let e = Scene::from_json(text).expect_err("in_sweep with cg");
    assert!(e.to_string().contains("solver.contact_update"), "{e}");
}

/// The default (`outer`) is not written, so existing scene files
/// round-trip unchanged; `in_sweep` is.
#[test]
fn contact_update_is_written_only_when_not_default() {
    let s = scene("closed_crack_biaxial");
    assert_eq!(s.solver.contact_update, ContactUpdate::Outer);
    let json = s.to_json().expect("serialise");
    assert!(!json.contains("contact_update"), "{json}");
    let t = with(s, ContactUpdate::InSweep);
    let json = t.to_json().expect("serialise");
    assert!(json.contains(r#""contact_update": "in_sweep""#), "{json}");
    assert_eq!(Scene::from_json(&json).expect("parse").into_file(), t);
}

/// Unloading after slip: `closed_crack_biaxial` (every point slips at
/// λ = 1) solved at λ = 1, then at λ = 0.5 with the slip of the first
/// solve carried. Friction then holds the faces where they slipped: the
/// outer loop (direct solver) and in-sweep (automaton) both converge,
/// neither capped nor with a frozen point, to the same fixed point: the
/// same states (18 of 19 points stick, one slips) and K within 1e-6 of
/// |K|. The unloaded state is not the proportional one: solved from no
/// slip at λ = 0.5, every point slips.
#[test]
fn unloading_after_slip_converges_with_both_contact_updates() {
    let unload = |update| {
        let mut s = scene("closed_crack_biaxial");
        if update == ContactUpdate::InSweep {
            s = with(s, update);
        }
        let mut sim = Simulation::new(valid(s)).expect("builds");
        let first = sim.solve().expect("solve at λ = 1");
        assert!(first.converged(), "{:?}", first.failure());
        assert_eq!(first.contact.slip, 19, "{:?}", first.contact);
        sim.set_load_factor(0.5);
        let report = sim.solve().expect("solve at λ = 0.5");
        assert!(!report.contact.capped, "{:?}", report.contact);
        let states = sim.contact_points().iter().map(|p| p.state).collect();
        (report, states)
    };
    let outer = unload(ContactUpdate::Outer);
    let inner = unload(ContactUpdate::InSweep);
    same_answer("closed_crack_biaxial unloaded to λ = 0.5", &outer, &inner);
    assert_eq!((outer.0.contact.stick, outer.0.contact.slip), (18, 1));
    let mut fresh = Simulation::new(valid(scene("closed_crack_biaxial"))).expect("builds");
    fresh.set_load_factor(0.5);
    assert_eq!(fresh.solve().expect("proportional").contact.slip, 19);
}
