//! Experiments with the iterative solvers: `solver_lab N SCENE KIND TOL`.
//! SCENE: plain | open | closed. Prints iterations and time.
#![allow(clippy::unwrap_used)]
use cdca::discretisation::model::Model;
use cdca::scene::{Scene, SolverKind, SolverSpec};
use cdca::solvers::relaxation::Relaxation;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n: usize = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(40);
    let which = a.get(2).map_or("open", String::as_str);
    let kind = match a.get(3).map_or("multigrid", String::as_str) {
        "automaton" => SolverKind::Automaton,
        "cg" => SolverKind::Cg,
        "direct" => SolverKind::Direct,
        _ => SolverKind::Multigrid,
    };
    let tol: f64 = a.get(4).and_then(|s| s.parse().ok()).unwrap_or(1e-8);
    let cracks = match which {
        "plain" => "",
        "closed" => r#""cracks":[{"points":[[0.1,0.1],[0.2,0.2]],"friction":0.5}],"#,
        _ => r#""cracks":[{"points":[[0.1,0.1525],[0.2,0.1525]]}],"#,
    };
    let json = format!(
        r#"{{"specimen":{{"width":0.3,"height":0.3}},"mesh":{{"nx":{n},"ny":{n}}},
        "material":{{"young":4.78e9,"poisson":0.25,"plane":"stress"}}, {cracks}
        "boundary":{{"bottom":{{"kind":"roller"}},"left":{{"kind":"roller"}},
          "top":{{"kind":"traction","normal":10e6}}}}}}"#
    );
    let scene = Scene::from_json(&json).unwrap();
    let t0 = std::time::Instant::now();
    let model = Model::new(scene.clone());
    let x = model.discretise(model.initial_cracks());
    let f = cdca::discretisation::loads::traction_forces(&x, &scene.boundary);
    let t1 = t0.elapsed().as_secs_f64();
    let spec = SolverSpec {
        kind,
        tolerance: tol,
        max_iterations: 1_000_000,
        ..SolverSpec::default()
    };
    let u0 = vec![0.0; x.n_free()];
    let mut r = Relaxation::new(kind, &spec, &x, &[], &f, &u0).unwrap();
    let setup = r.seconds();
    let st = r.run(&x, &[], 1_000_000, &mut |_| {}).unwrap();
    println!(
        "n={n} {which} {kind:?}: dofs {} enr {} xfem {t1:.3}s setup {setup:.3}s total {:.3}s iterations {} residual {:.2e}",
        x.n_free(),
        x.dofs.n_enriched,
        r.seconds(),
        st.iterations,
        st.residual
    );
    let h = r.history();
    for s in h.iter().step_by((h.len() / 12).max(1)) {
        println!("  {:6} {:.3e}", s.iteration, s.residual);
    }
}
