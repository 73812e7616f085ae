//! An edited scene solves exactly as a new simulation of it would
//! (`Simulation::with_scene`): an edit of the load, the faces' contact law
//! or the solver settings keeps the integrated discretisation; an edit of
//! the cracks keeps the elements no edited crack enriches, and the
//! stiffness pattern where the DOFs are coupled as before; any other edit
//! the discretisation depends on builds it anew, and so does a simulation
//! that has grown. Reference: `Simulation::new` of the edited scene, bit
//! for bit.

mod common;

use cdca::scene::{SceneFile, SideBc, SolverKind};
use cdca::{Scene, Simulation};
use common::{bundled, valid};

/// What a solve produced that an edit could get wrong: the displacement,
/// each free tip's K_I, K_II and decision, the contact states, and the
/// contact and linear iterations.
fn solved(mut sim: Simulation) -> (Vec<f64>, String, String, usize, usize) {
    let r = sim.solve().expect("solve");
    assert!(r.converged(), "{:?}", r.failure());
    let tips = format!(
        "{:?}",
        r.tips
            .iter()
            .map(|t| (t.k1, t.k2, t.criterion.clone()))
            .collect::<Vec<_>>()
    );
    let contact = format!("{:?}", sim.contact_points());
    (
        sim.displacement().to_vec(),
        tips,
        contact,
        r.contact.iterations,
        r.solver.iterations,
    )
}

/// The bundled scene `name` on an `n × n` mesh, solved (so its elements
/// are integrated and its matrix ordered and factorised).
fn solved_scene(name: &str, n: usize) -> (SceneFile, Simulation) {
    let mut file = bundled(name);
    file.mesh.nx = n;
    file.mesh.ny = n;
    let mut sim = Simulation::new(valid(file.clone())).expect("builds");
    sim.solve().expect("solve");
    (file, sim)
}

/// The default scene on a 30 × 30 mesh, solved.
fn base() -> (SceneFile, Simulation) {
    solved_scene("specimen_single_flaw", 30)
}

/// A named edit of a scene file.
type Edit = (&'static str, Box<dyn Fn(&mut SceneFile)>);

fn edited(file: &SceneFile, change: impl FnOnce(&mut SceneFile)) -> Scene {
    let mut file = file.clone();
    change(&mut file);
    valid(file)
}

#[test]
fn an_edit_of_the_load_the_contact_law_or_the_solver_keeps_the_discretisation() {
    let edits: [Edit; 7] = [
        (
            "top traction −60 MPa",
            Box::new(|s| {
                s.boundary.top = SideBc::Traction {
                    normal: -60e6,
                    shear: 2e6,
                }
            }),
        ),
        ("friction 0.2", Box::new(|s| s.cracks[0].friction = 0.2)),
        ("cohesion 3 MPa", Box::new(|s| s.cracks[0].cohesion = 3e6)),
        (
            "joint stiffness",
            Box::new(|s| s.cracks[0].normal_stiffness = Some(2e14)),
        ),
        ("r0 0.4 mm", Box::new(|s| s.criterion.r0 = Some(0.4e-3))),
        ("growth steps 7", Box::new(|s| s.growth.max_steps = 7)),
        (
            "multigrid solver",
            Box::new(|s| s.solver.kind = SolverKind::Multigrid),
        ),
    ];
    for (what, change) in edits {
        let (file, sim) = base();
        let scene = edited(&file, change);
        let kept = sim.with_scene(scene.clone()).expect("builds");
        assert_eq!(
            kept.xfem().points_to_integrate(),
            0,
            "{what}: the integrated elements are kept"
        );
        assert_eq!(kept.scene(), &scene, "{what}: the new scene is simulated");
        let fresh = Simulation::new(scene).expect("builds");
        assert!(fresh.xfem().points_to_integrate() > 0);
        assert!(
            solved(kept) == solved(fresh),
            "{what}: solves as a new simulation"
        );
    }
}

#[test]
fn an_edit_the_discretisation_depends_on_builds_it_anew() {
    let edits: [Edit; 5] = [
        ("mesh", Box::new(|s| s.mesh.nx = 31)),
        ("Young's modulus", Box::new(|s| s.material.young *= 2.0)),
        ("thickness", Box::new(|s| s.specimen.thickness = 0.01)),
        (
            "a crack point",
            Box::new(|s| {
                if let Some(p) = s.cracks[0].points.as_mut() {
                    p[0][0] += 0.3e-3;
                }
            }),
        ),
        ("a support", Box::new(|s| s.boundary.bottom = SideBc::Fixed)),
    ];
    for (what, change) in edits {
        let (file, sim) = base();
        let scene = edited(&file, change);
        let rebuilt = sim.with_scene(scene.clone()).expect("builds");
        assert!(
            rebuilt.xfem().points_to_integrate() > 0,
            "{what}: built anew"
        );
        let fresh = Simulation::new(scene).expect("builds");
        assert!(
            solved(rebuilt) == solved(fresh),
            "{what}: solves as a new simulation"
        );
    }
}

#[test]
fn a_simulation_that_has_grown_builds_its_scene_anew() {
    let (file, mut sim) = base();
    sim.grow_step().expect("a growth step");
    let scene = valid(file);
    let rebuilt = sim.with_scene(scene.clone()).expect("builds");
    assert!(rebuilt.xfem().points_to_integrate() > 0);
    assert!(rebuilt.history().is_empty());
    let fresh = Simulation::new(scene).expect("builds");
    assert!(solved(rebuilt) == solved(fresh));
}

/// The stepped pair on a 40 × 40 mesh, solved.
fn pair() -> (SceneFile, Simulation) {
    solved_scene("specimen_two_flaws_stepped", 40)
}

/// Moves the end point `k` of crack `c` by `(dx, dy)`, m.
fn move_point(s: &mut SceneFile, c: usize, k: usize, dx: f64, dy: f64) {
    if let Some(p) = s.cracks[c].points.as_mut() {
        p[k][0] += dx;
        p[k][1] += dy;
    }
}

#[test]
fn an_edit_of_the_cracks_keeps_what_it_does_not_touch() {
    // one flaw dragged: the other flaw's elements keep their stiffness
    let (file, sim) = pair();
    let scene = edited(&file, |s| move_point(s, 1, 1, 0.37e-3, -0.21e-3));
    let kept = sim.with_scene(scene.clone()).expect("builds");
    let fresh = Simulation::new(scene).expect("builds");
    let (left, all) = (
        kept.xfem().points_to_integrate(),
        fresh.xfem().points_to_integrate(),
    );
    assert!(
        left > 0 && 3 * left < 2 * all,
        "the unmoved flaw's elements are kept: {left} of {all} points to integrate"
    );
    assert!(solved(kept) == solved(fresh), "one flaw dragged");

    // a tip moved within the elements it cuts and enriches: the same
    // stiffness pattern, and symbolic factorisation, is kept, and the last
    // factor is redone where the values changed (on the product's 60 × 60
    // mesh a supernodal one); the same solve, to the last bit
    for n in [30, 60] {
        let (file, sim) = solved_scene("specimen_single_flaw", n);
        // (held, so that a new pattern cannot take the old one's address)
        let before = std::sync::Arc::clone(sim.xfem().pattern().expect("pattern").ordered());
        let scene = edited(&file, |s| move_point(s, 0, 1, 2e-6, 1e-6));
        let kept = sim.with_scene(scene.clone()).expect("builds");
        let after = kept.xfem().pattern().expect("pattern").ordered();
        assert!(
            std::sync::Arc::ptr_eq(&before, after),
            "{n}²: the pattern is kept"
        );
        let fresh = Simulation::new(scene).expect("builds");
        assert!(solved(kept) == solved(fresh), "{n}²: a tip moved a little");
    }

    // a crack added, and one removed (the other renumbered)
    let edits: [Edit; 2] = [
        (
            "a crack added",
            Box::new(|s| {
                let mut c = s.cracks[0].clone();
                c.points = Some(vec![[0.006, 0.022], [0.009, 0.024]]);
                s.cracks.push(c);
            }),
        ),
        ("a crack removed", Box::new(|s| drop(s.cracks.remove(0)))),
    ];
    for (what, change) in edits {
        let (file, sim) = pair();
        let scene = edited(&file, change);
        let kept = sim.with_scene(scene.clone()).expect("builds");
        let fresh = Simulation::new(scene).expect("builds");
        assert!(solved(kept) == solved(fresh), "{what}");
    }
}
