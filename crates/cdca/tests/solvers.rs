//! The solver family (SPEC §6) against the direct solver: agreement on the
//! verification scenes, iteration growth with the mesh, and stiff cases.
//!
//! Heavy parts run at full size only in release mode
//! (`cargo test -p cdca --release --test solvers -- --nocapture` prints
//! the tables).

use cdca::contact::iteration::solve_with_contact;
use cdca::contact::law::{FaceState, face_tractions};
use cdca::contact::status::{ContactInfo, ContactParams, relative_change};
use cdca::discretisation::model::Model;
use cdca::discretisation::xfem::Xfem;
use cdca::fracture::tips::all_tip_sifs;
use cdca::scene::{Scene, SolverKind, SolverSpec};
use cdca::solvers::choice::{kind_name, make_solver};
use cdca::solvers::linear::LinearSolver;
use cdca::solvers::relaxation::Relaxation;
use cdca::{ContactState, SolveError};

const ITERATIVE: [SolverKind; 3] = [SolverKind::Automaton, SolverKind::Cg, SolverKind::Multigrid];

/// Closed 45° crack under biaxial compression (the paper's setting):
/// 0.3 m plate, E = 4.78 GPa, ν = 0.25, plane stress, top −10 MPa,
/// right −2 MPa, rollers bottom and left, friction 0.5.
fn closed_scene(n: usize, normal_stiffness: Option<f64>) -> Scene {
    let kn = normal_stiffness.map_or(String::new(), |k| format!(r#","normal_stiffness":{k:e}"#));
    Scene::from_json(&format!(
        r#"{{"specimen":{{"width":0.3,"height":0.3}},"mesh":{{"nx":{n},"ny":{n}}},
        "material":{{"young":4.78e9,"poisson":0.25,"plane":"stress"}},
        "cracks":[{{"points":[[0.1,0.1],[0.2,0.2]],"friction":0.5{kn}}}],
        "boundary":{{"bottom":{{"kind":"roller"}},"left":{{"kind":"roller"}},
          "top":{{"kind":"traction","normal":-10e6}},"right":{{"kind":"traction","normal":-2e6}}}}}}"#
    ))
    .expect("closed-crack scene")
}

/// Open horizontal centre crack in tension: same plate, top +10 MPa,
/// crack from (0.1, 0.15) to (0.2, 0.15).
fn open_scene(n: usize, poisson: f64, plane: &str) -> Scene {
    Scene::from_json(&format!(
        r#"{{"specimen":{{"width":0.3,"height":0.3}},"mesh":{{"nx":{n},"ny":{n}}},
        "material":{{"young":4.78e9,"poisson":{poisson},"plane":"{plane}"}},
        "cracks":[{{"points":[[0.1,0.1525],[0.2,0.1525]]}}],
        "boundary":{{"bottom":{{"kind":"roller"}},"left":{{"kind":"roller"}},
          "top":{{"kind":"traction","normal":10e6}}}}}}"#
    ))
    .expect("open-crack scene")
}

struct Problem {
    x: Xfem,
    f: Vec<f64>,
}

fn problem(scene: &Scene) -> Problem {
    let model = Model::new(scene.clone());
    let x = model.discretise(model.initial_cracks());
    let f = cdca::discretisation::loads::traction_forces(&x, &scene.boundary);
    Problem { x, f }
}

fn spec(kind: SolverKind, tolerance: f64, max_iterations: usize) -> SolverSpec {
    SolverSpec {
        kind,
        tolerance,
        max_iterations,
        ..SolverSpec::default()
    }
}

/// Solve with contact; returns displacement, states and linear iterations.
fn solve(
    p: &Problem,
    solver: &mut dyn LinearSolver,
) -> Result<(Vec<f64>, Vec<FaceState>, usize), SolveError> {
    let (u, states, info) = solve_status(p, solver)?;
    assert!(
        info.converged,
        "contact iteration did not converge: {info:?}"
    );
    Ok((u, states, info.linear_iterations))
}

/// The contact iteration from open faces and u = 0, with its status.
fn solve_status(
    p: &Problem,
    solver: &mut dyn LinearSolver,
) -> Result<(Vec<f64>, Vec<FaceState>, ContactInfo), SolveError> {
    let committed = vec![FaceState::default(); p.x.faces.len()];
    let mut u = vec![0.0; p.x.n_free()];
    let params = ContactParams {
        tolerance: 1e-11,
        max_iterations: 100,
        ..ContactParams::default()
    };
    let (states, info) = solve_with_contact(&p.x, &p.f, &committed, &mut u, solver, params)?;
    Ok((u, states, info))
}

/// (K_I, K_II) of every free tip, contact tractions included.
fn sifs(x: &Xfem, u: &[f64], states: &[FaceState]) -> Vec<(f64, f64)> {
    all_tip_sifs(x, u, &face_tractions(x, states))
        .into_iter()
        .map(|(_, _, _, s)| (s.k1, s.k2))
        .collect()
}

/// `‖a − b‖ / ‖b‖`.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    relative_change(b, a)
}

/// Reference: the direct sparse Cholesky solution with the same contact
/// iteration. Every iterative solver (tolerance 1e-13 on the relative
/// residual) must give the displacement to 1e-8 relative (Euclidean) and
/// each tip's K_I, K_II to 1e-6 of the tip's largest |K|.
fn agrees_with_direct(scene: &Scene, expect_closed: bool) {
    let p = problem(scene);
    let (u_ref, st_ref, _) =
        solve(&p, make_solver(&spec(SolverKind::Direct, 0.0, 1)).as_mut()).expect("direct");
    let closed = st_ref
        .iter()
        .filter(|s| s.state != ContactState::Open)
        .count();
    assert_eq!(closed > 0, expect_closed, "{closed} closed face points");
    let k_ref = sifs(&p.x, &u_ref, &st_ref);
    assert!(!k_ref.is_empty());
    for kind in ITERATIVE {
        let (u, st, its) = solve(&p, make_solver(&spec(kind, 1e-13, 200_000)).as_mut())
            .unwrap_or_else(|e| panic!("{}: {e}", kind_name(kind)));
        let e = rel_diff(&u, &u_ref);
        let k = sifs(&p.x, &u, &st);
        println!(
            "{:10} {its:7} linear iterations, displacement error {e:.2e}",
            kind_name(kind)
        );
        assert!(
            e <= 1e-8,
            "{}: displacement differs by {e:.3e}",
            kind_name(kind)
        );
        for ((k1, k2), (r1, r2)) in k.iter().zip(&k_ref) {
            let scale = r1.abs().max(r2.abs());
            let (d1, d2) = ((k1 - r1).abs() / scale, (k2 - r2).abs() / scale);
            println!("    K_I {k1:.6e} (ref {r1:.6e}), K_II {k2:.6e} (ref {r2:.6e})");
            assert!(
                d1 <= 1e-6 && d2 <= 1e-6,
                "{}: K differs by {d1:.2e}, {d2:.2e}",
                kind_name(kind)
            );
        }
    }
}

/// Verification mesh: 30×30 in release, 16×16 in debug builds.
fn verification_size() -> usize {
    if cfg!(debug_assertions) { 16 } else { 30 }
}

/// Open centre crack in tension (30×30): no face point in contact.
#[test]
fn open_centre_crack_every_solver_matches_direct() {
    agrees_with_direct(&open_scene(verification_size(), 0.25, "stress"), false);
}

/// Closed 45° frictional crack under biaxial compression (30×30): the
/// faces close (stick and slip) and every solver, inside the same contact
/// iteration, reaches the direct solution.
#[test]
fn closed_frictional_crack_every_solver_matches_direct() {
    agrees_with_direct(&closed_scene(verification_size(), None), true);
}

/// Iterations to reach ‖r‖ ≤ 1e-8 ‖f‖ from zero on the open-crack scene.
fn iterations(kind: SolverKind, n: usize) -> usize {
    let p = problem(&open_scene(n, 0.25, "stress"));
    let s = spec(kind, 1e-8, 1_000_000);
    let u0 = vec![0.0; p.x.n_free()];
    let mut r = Relaxation::new(kind, &s, &p.x, &[], &p.f, &u0).expect("setup");
    let status = r
        .run(&p.x, &[], s.max_iterations, &mut |_| {})
        .expect("run");
    assert!(
        status.converged,
        "{} did not converge at {n}²",
        kind_name(kind)
    );
    status.iterations
}

/// Least-squares slope of log(iterations) against log(n).
fn growth_exponent(ns: &[usize], its: &[usize]) -> f64 {
    let pts: Vec<(f64, f64)> = ns
        .iter()
        .zip(its)
        .map(|(&n, &i)| ((n as f64).ln(), (i as f64).ln()))
        .collect();
    let k = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / k,
        pts.iter().map(|p| p.1).sum::<f64>() / k,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

/// Mesh refinement of the iteration counts (open crack, tolerance 1e-8):
/// plain relaxation grows like n^2 (classical Gauss–Seidel analysis,
/// asserted between 1.5 and 2.5); CG with the symmetric sweep in between;
/// the multigrid-preconditioned CG stays flat (exponent ≤ 0.5).
/// Meshes 20², 40², 80² (+160² for CG and multigrid); release only (the
/// debug build would take minutes), halved sizes if run in debug anyway.
#[test]
#[cfg_attr(debug_assertions, ignore = "minutes unoptimised: run with --release")]
fn iteration_growth_with_mesh_size() {
    let release = !cfg!(debug_assertions);
    let small: &[usize] = if release {
        &[20, 40, 80]
    } else {
        &[10, 20, 40]
    };
    let large: &[usize] = if release {
        &[20, 40, 80, 160]
    } else {
        &[20, 40, 80]
    };
    println!("solver     n     iterations");
    let mut exps = Vec::new();
    for (kind, ns) in [
        (SolverKind::Automaton, small),
        (SolverKind::Cg, large),
        (SolverKind::Multigrid, large),
    ] {
        let its: Vec<usize> = ns.iter().map(|&n| iterations(kind, n)).collect();
        for (n, i) in ns.iter().zip(&its) {
            println!("{:10} {n:4} {i:8}", kind_name(kind));
        }
        let e = growth_exponent(ns, &its);
        println!("{:10} growth exponent {e:.2}", kind_name(kind));
        exps.push(e);
    }
    assert!(
        (1.5..=2.5).contains(&exps[0]),
        "automaton exponent {:.2}",
        exps[0]
    );
    assert!(
        exps[1] < exps[0],
        "cg exponent {:.2} not below the automaton's",
        exps[1]
    );
    assert!(exps[2] <= 0.5, "multigrid exponent {:.2}", exps[2]);
}

/// A stiff case must end with an explicit status: converged, or stopped at
/// the iteration cap with `converged: false`, the cap's iteration count and
/// a finite residual above the tolerance. Never NaN, never a panic.
fn explicit_status(name: &str, p: &Problem, kind: SolverKind, max_iterations: usize) {
    let mut solver = make_solver(&spec(kind, 1e-10, max_iterations));
    let (u, _, info) = solve_status(p, solver.as_mut())
        .unwrap_or_else(|e| panic!("{name}: {}: unexpected error {e}", kind_name(kind)));
    assert!(
        u.iter().all(|v| v.is_finite()),
        "{name}: non-finite displacement"
    );
    let last = &info.last;
    if info.converged {
        assert!(last.converged && last.residual <= 1e-10, "{name}: {info:?}");
        println!(
            "{name}: {:10} converged, {} linear iterations",
            kind_name(kind),
            info.linear_iterations
        );
    } else {
        assert!(
            !last.converged,
            "{name}: contact unconverged with a converged solve: {info:?}"
        );
        assert_eq!(
            last.iterations, max_iterations,
            "{name}: stopped before the cap"
        );
        assert!(
            last.residual.is_finite() && last.residual > 1e-10,
            "{name}: residual {:e}",
            last.residual
        );
        println!(
            "{name}: {:10} no convergence after {}, residual {:.2e}",
            kind_name(kind),
            last.iterations,
            last.residual
        );
    }
}

/// Iterations allowed per linear solve in the stiff cases.
fn stiff_budget() -> usize {
    if cfg!(debug_assertions) { 500 } else { 3000 }
}

/// Penalty k_N h/E = 1e6 on the closed crack (20×20).
#[test]
fn stiff_penalty_ends_with_an_explicit_status() {
    let n = 20;
    let h = 0.3 / n as f64;
    let p = problem(&closed_scene(n, Some(1e6 * 4.78e9 / h)));
    for kind in ITERATIVE {
        explicit_status("k_N h/E = 1e6", &p, kind, stiff_budget());
    }
}

/// Nearly incompressible plane strain, ν = 0.49 (open crack, 20×20).
#[test]
fn nearly_incompressible_ends_with_an_explicit_status() {
    let p = problem(&open_scene(20, 0.49, "strain"));
    for kind in ITERATIVE {
        explicit_status("nu = 0.49", &p, kind, stiff_budget());
    }
}

/// The direct solver's fill-reducing order (the mesh's nested dissection)
/// against approximate minimum degree, faer's AMD on the same matrix:
/// on a 100 × 100 plate with a closed crack at 45° (tips inside
/// elements) it leaves at least 5% fewer entries in `L` (measured 7.6%;
/// the flops of the factorisation fall by 28–41%, see the Benchmarks
/// docs).
#[test]
fn nested_dissection_leaves_less_fill_than_amd() {
    use faer::sparse::linalg::cholesky::{
        CholeskySymbolicParams, SymmetricOrdering, factorize_symbolic_cholesky,
    };
    let scene = closed_scene(100, None);
    let model = Model::new(scene);
    let x = model.discretise(model.initial_cracks());
    let ordered = x.pattern().expect("pattern").ordered();
    let amd = factorize_symbolic_cholesky(
        ordered.lower.as_ref(),
        faer::Side::Lower,
        SymmetricOrdering::Amd,
        CholeskySymbolicParams::default(),
    )
    .expect("AMD");
    let (nd, amd) = (ordered.symbolic.len_val(), amd.len_val());
    println!("L entries: nested dissection {nd}, AMD {amd}");
    assert!((nd as f64) < 0.95 * amd as f64, "{nd} against AMD's {amd}");
}

/// The closed-crack plate at 56 × 56 with a second, kinked crack at odd
/// angles (tips inside elements): large enough for a supernodal factor.
fn two_cracks_56() -> Problem {
    let scene = closed_scene(56, None)
        .edit(|file| {
            let mut second = file.cracks[0].clone();
            second.points = Some(vec![[0.061, 0.213], [0.1347, 0.2391], [0.1882, 0.2274]]);
            file.cracks.push(second);
        })
        .expect("scene");
    problem(&scene)
}

/// A factor refactorised on its own pattern after a change of a few
/// element blocks (contact at one crack's faces, or a crack moved within
/// its elements, as the workbench's drag does) redoes only the supernodes
/// of the changed columns and their ancestors, and is the factor made
/// anew, bit for bit: the same solution to the last bit, in slices or at
/// once. A plate with two cracks at odd angles, 56 × 56.
#[test]
fn a_factor_redone_where_the_values_changed_is_the_factor_made_anew() {
    use cdca::discretisation::assembly::ElementBlock;
    use cdca::solvers::direct::Factor;
    let Problem { x, f } = two_cracks_56();
    // a penalty-like block on a few enriched elements of the second crack
    let block = |slot: usize, k: f64| {
        let n = 2 * x.enriched[slot].scalars.len();
        ElementBlock {
            slot,
            k: nalgebra::DMatrix::identity(n, n) * k,
        }
    };
    let last = x.enriched.len() - 1;
    let before = [block(last, 1e9), block(last - 3, 2e9)];
    let after = [block(last, 3e9), block(last - 5, 2e9)];
    let anew = Factor::new(&x, &after).expect("factor");
    let all = anew.supernodes_to_factorise();
    let reference = anew.solve(&f).expect("solve");
    for slices in [1.0, 7.0] {
        let mut old = Factor::new(&x, &before).expect("factor");
        assert!(
            old.solve(&f).expect("solve") != reference,
            "the blocks matter"
        );
        old = old.reassemble(&x, &after).expect("reassembled");
        let redone = old.supernodes_to_factorise();
        let updates = old.updates().expect("a supernodal factor").clone();
        while !old
            .factorise_slice(updates.total_flops() / slices)
            .expect("slice")
        {}
        println!("{redone} of {all} supernodes redone ({slices} slices)");
        assert!(
            redone < all / 2,
            "{redone} of {all} supernodes redone for three changed elements"
        );
        let u = old.solve(&f).expect("solve");
        assert!(
            u == reference,
            "redone in {slices} slices: not the factor anew"
        );
    }
    // the same values: nothing to redo
    let same = Factor::new(&x, &after)
        .expect("factor")
        .reassemble(&x, &after)
        .expect("reassembled");
    assert_eq!(same.supernodes_to_factorise(), 0);
    assert!(same.is_factorised(), "nothing left to factorise");
    assert!(same.solve(&f).expect("solve") == reference);
}

/// A factorisation spread over slices of supernodes (as the workbench
/// spreads it over frames) is the factorisation done at once, bit for bit,
/// whatever the slices; and it solves the system to round-off (true
/// relative residual ≤ 1e-12, where faer's single call reached
/// 2.5–9e-13 at 100 × 100). A plate with two cracks at odd angles, tips
/// inside elements, on a mesh large enough for a supernodal factor.
#[test]
fn a_factorisation_in_slices_is_the_factorisation_at_once() {
    use cdca::solvers::direct::Factor;
    let Problem { x, f } = two_cracks_56();
    let at_once = Factor::new(&x, &[]).expect("factor");
    let updates = at_once.updates().expect("a supernodal factor").clone();
    let reference = at_once.solve(&f).expect("solve");
    let residual = at_once.relative_residual(&f, &reference);
    assert!(residual <= 1e-12, "residual {residual:e}");
    for slices in [3.0, 17.0, 1000.0] {
        let mut sliced = Factor::assembled(&x, &[], None).expect("assembled");
        let mut calls = 0;
        while !sliced
            .factorise_slice(updates.total_flops() / slices)
            .expect("slice")
        {
            calls += 1;
            assert!(!sliced.is_factorised());
        }
        assert!(calls + 1 >= 3, "{} slices of {slices} asked", calls + 1);
        let u = sliced.solve(&f).expect("solve");
        assert!(u == reference, "{slices} slices differ");
    }
}
