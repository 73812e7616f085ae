//! UI tests of the workbench with egui_kittest: no display, no GPU. They
//! click by label and assert on the app's state.
//!
//! Tests marked `needs cdca::Simulation bodies` drive the solver; the others
//! run with solving switched off, so they exercise the UI, editing and undo
//! on their own.

#[path = "support/field.rs"]
mod field;
#[path = "support/harness.rs"]
mod support;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cdca_workbench::app::Message;
use cdca_workbench::{Command, Options, RunMode, WorkbenchApp};
use egui::{Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use support::{SIZE, harness, no_solver};

/// A file dropped on the window.
#[derive(Debug)]
struct TestFile {
    path: PathBuf,
    bytes: Vec<u8>,
}

impl egui::DroppedFile for TestFile {
    fn path(&self) -> &Path {
        &self.path
    }
    fn bytes(&self) -> Result<Vec<u8>, String> {
        Ok(self.bytes.clone())
    }
}

/// Edits a copy of the open scene and applies it, as a panel would.
fn edit_scene(h: &mut Harness<'_, WorkbenchApp>, edit: impl FnOnce(&mut cdca::scene::SceneFile)) {
    let mut s = h.state().scene().clone();
    edit(&mut s);
    h.state_mut().push(Command::SetScene {
        scene: Box::new(s),
        ongoing: false,
    });
}

/// The workbench on its default scene, solved (release builds: the solver
/// runs in the first frames).
fn solved_default() -> Harness<'static, WorkbenchApp> {
    let mut h = harness(Options::default());
    h.run_steps(20);
    assert!(h.state().is_solved());
    h
}

/// The error the workbench shows; panics naming what it shows instead.
fn error_message(h: &Harness<'_, WorkbenchApp>) -> String {
    match h.state().message() {
        Some(Message::Error(e)) => e.clone(),
        m => panic!("an error expected, got {m:?}"),
    }
}

fn click_at(h: &mut Harness<'_, WorkbenchApp>, pos: Pos2) {
    h.event(Event::PointerMoved(pos));
    for pressed in [true, false] {
        h.event(Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    h.run();
}

/// Presses the primary button at `from` and moves to `to` in eight frames,
/// the button held.
fn press_and_move(h: &mut Harness<'_, WorkbenchApp>, from: Pos2, to: Pos2) {
    h.event(Event::PointerMoved(from));
    h.event(Event::PointerButton {
        pos: from,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    for k in 1..=8 {
        h.event(Event::PointerMoved(from + (to - from) * (k as f32 / 8.0)));
        h.step();
    }
}

fn release(h: &mut Harness<'_, WorkbenchApp>, at: Pos2) {
    h.event(Event::PointerButton {
        pos: at,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
}

fn drag(h: &mut Harness<'_, WorkbenchApp>, from: Pos2, to: Pos2) {
    press_and_move(h, from, to);
    release(h, to);
    h.run();
}

/// The end point of the first crack's first segment (a tip of the default
/// scene's flaw).
fn first_tip(h: &Harness<'_, WorkbenchApp>) -> [f64; 2] {
    h.state().scene().cracks[0]
        .points
        .clone()
        .unwrap_or_default()[1]
}

#[test]
fn starts_on_the_default_scene() {
    let mut h = harness(no_solver());
    h.run();
    let app = h.state();
    assert_eq!(
        app.scene().cracks.len(),
        1,
        "the default scene has one closed crack"
    );
    assert_eq!((app.scene().mesh.nx, app.scene().mesh.ny), (60, 60));
    assert!(app.scene().cracks[0].friction > 0.0);
    assert!(
        app.message().is_none(),
        "no error on start: {:?}",
        app.message()
    );
    h.get_by_label(cdca_workbench::app::CANVAS_LABEL);
    h.get_by_label("Cracks (1)");
}

#[test]
fn drawing_a_crack_by_clicks_adds_a_crack() {
    let mut h = harness(no_solver());
    h.run();
    h.get_by_label("Draw crack").click();
    h.run();
    // positions as fractions of the specimen's width
    let w = h.state().scene().specimen.width;
    let at = |p: [f64; 2]| [p[0] * w, p[1] * w];
    let a = h.state().screen_from_world(at([0.17, 0.83]));
    let b = h.state().screen_from_world(at([0.33, 0.9]));
    click_at(&mut h, a);
    click_at(&mut h, b);
    h.key_press(Key::Enter);
    h.run();
    let scene = h.state().scene();
    assert_eq!(scene.cracks.len(), 2, "the drawn crack was added");
    let points = scene.cracks[1].points.clone().unwrap_or_default();
    assert_eq!(points.len(), 2);
    for (p, q) in points.iter().zip([at([0.17, 0.83]), at([0.33, 0.9])]) {
        assert!(
            (p[0] - q[0]).abs() < 3e-3 * w && (p[1] - q[1]).abs() < 3e-3 * w,
            "{p:?} vs {q:?}"
        );
    }
    h.get_by_label("Cracks (2)");
}

#[test]
fn dragging_a_tip_moves_it_in_one_undo_step() {
    let mut h = harness(no_solver());
    h.run();
    let tip = first_tip(&h);
    let w = h.state().scene().specimen.width;
    let target = [0.73 * w, 0.53 * w];
    let from = h.state().screen_from_world(tip);
    let to = h.state().screen_from_world(target);
    drag(&mut h, from, to);
    let moved = first_tip(&h);
    assert!(
        (moved[0] - target[0]).abs() < 3e-3 * w && (moved[1] - target[1]).abs() < 3e-3 * w,
        "tip at {moved:?}"
    );
    h.get_by_label("Undo").click();
    h.run();
    let back = first_tip(&h);
    assert_eq!(
        back, tip,
        "one undo step returns the tip to where the drag started"
    );
}

/// Moves the pointer from `from` to `to` in eight frames, the button held.
fn move_held(h: &mut Harness<'_, WorkbenchApp>, from: Pos2, to: Pos2) {
    for k in 1..=8 {
        h.event(Event::PointerMoved(from + (to - from) * (k as f32 / 8.0)));
        h.step();
    }
}

/// The dragged tip is at `target` in the solution shown, with the K that
/// `cdca solve` gives the scene shown (1e-9 relative).
/// Runs frames until `done` holds, at most `max`: a test that waits for a
/// solve by its outcome rather than a count of frames holds on a busy
/// machine (the pacer gives the solver less of a slow frame).
fn run_until(h: &mut Harness<'_, WorkbenchApp>, max: usize, done: impl Fn(&WorkbenchApp) -> bool) {
    for _ in 0..max {
        if done(h.state()) {
            return;
        }
        h.step();
    }
}

/// Whether the scene on screen is solved with a tip where the pointer is
/// (what [`assert_solved_at`] then checks against `cdca solve`).
fn solved_at(app: &WorkbenchApp, target: [f64; 2]) -> bool {
    let w = app.scene().specimen.width;
    app.is_solved()
        && app
            .tips()
            .iter()
            .any(|t| (t.x - target[0]).abs() < 3e-3 * w && (t.y - target[1]).abs() < 3e-3 * w)
}

fn assert_solved_at(h: &Harness<'_, WorkbenchApp>, target: [f64; 2], what: &str) {
    let app = h.state();
    let w = app.scene().specimen.width;
    assert!(app.is_solved(), "{what}: solved");
    assert!(
        app.tips()
            .iter()
            .any(|t| (t.x - target[0]).abs() < 3e-3 * w && (t.y - target[1]).abs() < 3e-3 * w),
        "{what}: a tip where the pointer is: {:?}",
        app.tips().iter().map(|t| (t.x, t.y)).collect::<Vec<_>>()
    );
    let scene = cdca::Scene::try_from(app.scene().clone()).expect("valid scene");
    let mut headless = cdca::Simulation::new(scene).expect("a simulation");
    headless.set_load_factor(1.0);
    let report = headless.solve().expect("the dragged scene solves");
    field::assert_same_sifs(app.tips(), &report.tips, what);
}

/// While a drag goes on, the dragged scene is solved as the pointer moves:
/// the last field stays on screen until the next solve replaces it, and
/// where the pointer stops the field is that position's, as `cdca solve`
/// solves it (K to 1e-9 relative). The release does not solve it again; it
/// checks it from bonded faces, as after Solve.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_field_follows_a_drag() {
    let mut h = harness(Options::default());
    h.run_steps(20);
    assert!(h.state().is_solved());
    let w = h.state().scene().specimen.width;
    // generic positions: inside an element, the crack at an odd angle
    let (first, second) = ([0.613 * w, 0.577 * w], [0.641 * w, 0.552 * w]);
    let from = h.state().screen_from_world(first_tip(&h));
    let to = h.state().screen_from_world(first);
    press_and_move(&mut h, from, to);
    assert!(
        h.state().field_is_shown(),
        "a field stays on screen while the pointer moves"
    );
    // (a held button repaints every frame: no `run`, which waits for rest)
    run_until(&mut h, 3000, |app| solved_at(app, first));
    assert_solved_at(&h, first, "the pointer held still");

    let next = h.state().screen_from_world(second);
    move_held(&mut h, to, next);
    assert!(h.state().field_is_shown(), "the field stays on screen");
    run_until(&mut h, 3000, |app| solved_at(app, second));
    assert_solved_at(&h, second, "moved on, the button still down");
    let shown = h
        .state()
        .shown_field()
        .expect("the field of the dragged scene");

    release(&mut h, next);
    run_until(&mut h, 3000, |app| app.second_start().0);
    assert_solved_at(&h, second, "released");
    assert_eq!(
        h.state().shown_field().map(|(version, _)| version),
        Some(shown.0),
        "the release does not solve the dragged scene again"
    );
    assert!(
        h.state().second_start().0,
        "the release checks the solve from bonded faces"
    );
}

#[test]
fn a_bad_scene_file_shows_an_error_and_keeps_the_scene() {
    let mut h = harness(no_solver());
    h.run();
    let before = h.state().scene().clone();
    // Dropped on the window, as a user would (File ▸ Open goes the same way).
    h.input_mut().dropped_files.push(Arc::new(TestFile {
        path: PathBuf::from("/tmp/broken.json"),
        bytes: b"{ \"specimen\": { \"width\": 0.3 ".to_vec(),
    }));
    h.run();
    assert_eq!(h.state().scene(), &before, "the current scene is untouched");
    assert!(matches!(h.state().message(), Some(Message::Error(_))));
    h.get_by_label_contains("Could not open broken.json");

    // A file that parses but is invalid names the field.
    let mut bad = before.clone();
    bad.specimen.width = -1.0;
    let text = serde_json::to_string(&bad).unwrap_or_default();
    h.state_mut().push(Command::OpenSceneText {
        source: "negative.json".to_owned(),
        text,
    });
    h.run();
    assert_eq!(h.state().scene(), &before);
    h.get_by_label_contains("specimen.width");
    h.get_by_label("Dismiss").click();
    h.run();
    assert!(h.state().message().is_none());
}

/// A crack drawn across the specimen, from one edge to another, cuts it in
/// two before any load: the workbench says so, naming the crack, instead of
/// failing in the factorisation; Undo gives back the solved scene.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_crack_drawn_across_the_specimen_is_refused_with_a_reason() {
    let mut h = solved_default();
    edit_scene(&mut h, |s| {
        let mut across = s.cracks[0].clone();
        across.points = Some(vec![[0.0, 0.012], [0.03, 0.018]]);
        s.cracks.push(across);
    });
    h.run_steps(5);
    assert!(matches!(h.state().message(), Some(Message::Error(_))));
    h.get_by_label_contains("`cracks[1]`");
    h.get_by_label_contains("cuts the specimen in two before any load");
    assert!(!h.state().is_solved());
    h.get_by_label("Undo").click();
    h.run_steps(20);
    assert_eq!(h.state().scene().cracks.len(), 1);
    assert!(h.state().is_solved());
}

/// Coarsening the default scene's mesh to 12 × 12 (h = 2.5 mm) leaves its
/// 6 mm flaw 2.4 elements long, below the 2.5 that K needs (K was 40% off
/// at 2): the workbench says so, naming the crack and h, instead of showing
/// a field it cannot trust; Undo gives back the solved scene.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_mesh_too_coarse_for_the_flaw_is_refused_with_a_reason() {
    let mut h = solved_default();
    edit_scene(&mut h, |s| (s.mesh.nx, s.mesh.ny) = (12, 12));
    h.run_steps(5);
    let e = error_message(&h);
    assert!(
        e.contains("`cracks[0].points`")
            && e.contains("less than 2.5 element sizes (h = 0.0025 m)"),
        "{e}"
    );
    // shown, not only kept
    h.get_by_label_contains("less than 2.5 element sizes (h = 0.0025 m)");
    assert!(!h.state().is_solved());
    h.get_by_label("Undo").click();
    h.run_steps(20);
    assert_eq!(h.state().scene().mesh.nx, 60);
    assert!(h.state().is_solved());
}

#[test]
fn undo_restores_a_deleted_crack_and_redo_deletes_it_again() {
    let mut h = harness(no_solver());
    h.run();
    let before = h.state().scene().clone();
    h.get_by_label_contains("Crack 1: 2 points").click();
    h.run();
    h.get_by_label("Delete crack 1").click();
    h.run();
    assert!(h.state().scene().cracks.is_empty());
    h.get_by_label("Undo").click();
    h.run();
    assert_eq!(
        h.state().scene(),
        &before,
        "undo restores the scene exactly"
    );
    h.get_by_label("Redo").click();
    h.run();
    assert!(h.state().scene().cracks.is_empty());
}

#[test]
fn panels_show_only_what_the_scene_can_use() {
    let mut h = harness(no_solver());
    h.run();
    // direct solver: no automaton settings; a crack: friction is offered
    assert!(h.query_by_label("Over-relaxation ω").is_none());
    h.get_by_label_contains("Crack 1: 2 points").click();
    h.run();
    assert!(h.query_by_label("Friction μ").is_some());
    h.get_by_label("Delete crack 1").click();
    h.run();
    assert!(
        h.query_by_label("Friction μ").is_none(),
        "no friction without cracks"
    );
    assert!(h.query_by_label("Max contact iterations").is_none());
    edit_scene(&mut h, |s| {
        s.solver.kind = cdca::scene::SolverKind::Automaton;
    });
    h.run();
    assert!(h.query_by_label("Over-relaxation ω").is_some());
    // K_IIC only where it sets a strength: the comprehensive criterion's
    // shear branch on the faces (c_c + K_IIC/√(2π r0))
    assert!(h.query_by_label("Shear toughness K_IIC").is_some());
    edit_scene(&mut h, |s| {
        s.criterion.shear_strength = Some(cdca::scene::ShearStrength::Rock);
    });
    h.run();
    assert!(h.query_by_label("Shear toughness K_IIC").is_none());
    edit_scene(&mut h, |s| {
        s.criterion = s.criterion.with_kind(cdca::scene::CriterionKind::Mts);
    });
    h.run();
    assert!(h.query_by_label("Shear toughness K_IIC").is_none());
}

/// The paper's in-sweep contact is offered with the automaton on a scene
/// with cracks only; chosen, growth keeps the automaton (the multigrid
/// swap cannot run it) and the acceleration option is hidden; with another
/// solver the panel sets the outer loop back, so the scene stays valid.
#[test]
fn in_sweep_contact_is_offered_with_the_automaton_only() {
    use cdca::scene::{ContactUpdate, SolverKind};
    let mut h = harness(no_solver());
    h.run();
    assert!(
        h.query_by_label("Contact update").is_none(),
        "direct solver"
    );
    with_solver(&mut h, SolverKind::Automaton);
    assert!(h.query_by_label("Contact update").is_some());
    assert_eq!(h.state().growth_solver(), SolverKind::Multigrid);
    edit_scene(&mut h, |s| s.solver.contact_update = ContactUpdate::InSweep);
    h.run_steps(2);
    assert_eq!(h.state().growth_solver(), SolverKind::Automaton);
    assert!(
        h.query_by_label("Accelerate growth (multigrid-CG)")
            .is_none()
    );
    with_solver(&mut h, SolverKind::Cg);
    assert_eq!(
        h.state().scene().solver.contact_update,
        ContactUpdate::Outer
    );
    assert!(h.query_by_label("Contact update").is_none());
}

/// With the automaton the solver panel offers Young's optimal ω for the
/// mesh (2/(1 + sin(π/60)) = 1.9005 on the default 60² scene); one click
/// sets it, the button then greys out, and Undo gives ω = 1 back. Other
/// solvers do not show it.
#[test]
fn the_automaton_offers_the_optimal_omega_of_the_mesh() {
    use cdca::scene::SolverKind;
    let mut h = harness(no_solver());
    h.run();
    assert!(h.query_by_label_contains("Use ω =").is_none(), "direct");
    with_solver(&mut h, SolverKind::Automaton);
    assert_eq!(h.state().scene().solver.omega, 1.0);
    h.get_by_label("Use ω = 1.90").click();
    h.run_steps(2);
    let best = 2.0 / (1.0 + (std::f64::consts::PI / 60.0).sin());
    assert!((h.state().scene().solver.omega - best).abs() < 1e-12);
    assert!((best - 1.9005).abs() < 1e-4);
    assert!(
        h.get_by_label("Use ω = 1.90")
            .accesskit_node()
            .is_disabled()
    );
    h.get_by_label("Undo").click();
    h.run_steps(2);
    assert_eq!(h.state().scene().solver.omega, 1.0);
    with_solver(&mut h, SolverKind::Multigrid);
    assert!(h.query_by_label_contains("Use ω =").is_none(), "multigrid");
}

/// The Growth section offers the control and only the settings it uses:
/// the default scene grows to failure (a maximum load factor, no load
/// steps); switched to a load ramp it shows load steps and growth per load
/// step instead.
#[test]
fn growth_settings_follow_the_control() {
    let mut h = harness(no_solver());
    h.run();
    h.get_by_label("Growth").click();
    h.run();
    assert_eq!(
        h.state().scene().growth.control,
        cdca::scene::GrowthControl::Critical
    );
    assert!(h.query_by_label("Max load factor λ").is_some());
    assert!(h.query_by_label("Load steps").is_none());
    edit_scene(&mut h, |s| {
        s.growth.control = cdca::scene::GrowthControl::Load;
    });
    h.run();
    assert!(h.query_by_label("Load steps").is_some());
    assert!(h.query_by_label("Max growth per load step").is_some());
    assert!(h.query_by_label("Max load factor λ").is_none());
}

/// Side-panel widgets (label or text, and rect) that reach under the
/// canvas or, in the right panel, under its scroll bar at the window's edge
/// (the last 10 px of the [`SIZE`] wide window): a control drawn there
/// cannot be used, nor a text read, without scrolling sideways.
fn widgets_under_the_canvas(h: &Harness<'_, WorkbenchApp>) -> Vec<String> {
    let canvas = h.get_by_label(cdca_workbench::app::CANVAS_LABEL).rect();
    let edge = SIZE[0] - 10.0;
    let mut out = Vec::new();
    for n in h.query_all_by(|n| n.bounding_box().is_some()) {
        let r = n.rect();
        let node = n.accesskit_node();
        let label = node.label().or_else(|| node.value()).unwrap_or_default();
        let left = r.left() < canvas.left() - 0.5 && r.right() > canvas.left() + 0.5;
        let right = r.left() < canvas.right() - 0.5 && r.right() > canvas.right() + 0.5
            || r.left() > canvas.right() && r.right() > edge;
        // below the toolbar; the plots' resize handle spans the canvas, and
        // a long name scrolls inside its text field
        let panel = r.top() >= canvas.top()
            && label != "Resize panel"
            && node.role() != egui::accesskit::Role::TextRun;
        if (left || right) && panel && !label.is_empty() {
            out.push(format!("{label:?} {r:?}"));
        }
    }
    out
}

/// Every bundled scene, all its sections open: no widget of the side
/// panels reaches under the canvas (a control drawn there cannot be used;
/// the point supports' remove buttons were, on the default scene too).
#[test]
fn side_panels_fit_beside_the_canvas_on_every_bundled_scene() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .expect("scenes")
        .map(|e| e.expect("entry").path())
        .collect();
    names.sort();
    let mut overflow = Vec::new();
    for path in names {
        // tall enough that every section is on screen: widths are checked
        let mut h = Harness::builder()
            .with_size([SIZE[0], 2400.0])
            .with_max_steps(400)
            .build_ui_state(
                |ui, app: &mut WorkbenchApp| {
                    app.logic(ui.ctx());
                    app.ui(ui);
                },
                WorkbenchApp::new(no_solver()),
            );
        h.run();
        h.state_mut().push(Command::OpenSceneText {
            source: path.display().to_string(),
            text: std::fs::read_to_string(&path).expect("scene"),
        });
        h.run();
        for header in ["Fracture criterion", "Growth"] {
            h.get_by_label(header).click();
            h.run();
        }
        let cracks: Vec<String> = h
            .query_all_by_label_contains("points, ")
            .filter_map(|n| n.accesskit_node().label())
            .collect();
        let supports: Vec<String> = h
            .query_all_by_label_contains("Point support ")
            .filter_map(|n| n.accesskit_node().label())
            .collect();
        for c in cracks.into_iter().chain(supports) {
            h.get_by_label(&c).click();
            h.run();
        }
        // the sections are open
        for label in ["Radius r0", "Control"] {
            let shown = |n: &egui_kittest::kittest::AccessKitNode<'_>| {
                n.label()
                    .or_else(|| n.value())
                    .is_some_and(|l| l.contains(label))
            };
            let found = h.query_all_by(shown).count();
            assert!(found > 0, "{label} in {}", path.display());
        }
        for w in widgets_under_the_canvas(&h) {
            overflow.push(format!("{}: {w}", path.display()));
        }
    }
    assert!(overflow.is_empty(), "{}", overflow.join("\n"));
}

/// Joint stiffness reads in GPa/m, the unit of the paper's joint
/// (200 / 20 GPa/m): the default penalty 100 E/h of the default scene
/// (E = 4.78 GPa, h = 0.5 mm) is 9.56e5 GPa/m, and a scene with the paper's
/// joint shows 200 and 20. (The panel showed Pa/m ÷ 1e6 labelled GPa/mm.)
#[test]
fn joint_stiffness_is_shown_in_gpa_per_metre() {
    let mut h = harness(no_solver());
    h.run();
    h.get_by_label_contains("Crack 1: 2 points").click();
    h.run();
    let text = |h: &Harness<'_, WorkbenchApp>, t: &str| {
        h.query_all_by(|n| n.value().as_deref() == Some(t)).count()
    };
    assert!(text(&h, "9.560e5 GPa/m") > 0, "the auto k_N");
    assert!(text(&h, "95600 GPa/m") > 0, "the auto k_T = k_N/10");
    edit_scene(&mut h, |s| {
        s.cracks[0].normal_stiffness = Some(200e9);
        s.cracks[0].shear_stiffness = Some(20e9);
    });
    h.run();
    assert!(text(&h, "200 GPa/m") > 0, "k_N typed");
    assert!(text(&h, "20.0 GPa/m") > 0, "k_T typed");
}

/// A scene whose values lie outside the panels' ranges (face friction 10,
/// a 500 × 500 mesh for multigrid-CG) opens as it is: the panels show the
/// values without clamping them, and opening it is the only undo step.
/// (The panels used to write friction 5 and a 400 × 400 mesh back at the
/// first frame.)
#[test]
fn opening_a_scene_never_changes_it() {
    let mut h = harness(no_solver());
    h.run();
    let mut scene = h.state().scene().clone();
    scene.cracks[0].friction = 10.0;
    (scene.mesh.nx, scene.mesh.ny) = (500, 500);
    scene.solver.kind = cdca::scene::SolverKind::Multigrid;
    h.state_mut().push(Command::OpenSceneText {
        source: "wide.json".to_owned(),
        text: serde_json::to_string(&scene).expect("json"),
    });
    h.run_steps(5);
    h.get_by_label_contains("Crack 1: 2 points").click();
    h.run_steps(5);
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    assert_eq!(*h.state().scene(), scene);
    h.get_by_label("Undo").click();
    h.run();
    assert_ne!(*h.state().scene(), scene, "one undo step: the opening");
}

/// Point supports can be added and edited, not only removed: without its
/// point support the default specimen is refused (nothing holds it in x),
/// "Add point support" puts one at the bottom-left corner fixing x, which
/// makes it valid again, and its position and fixed direction are fields.
#[test]
fn a_point_support_can_be_added_back_and_edited() {
    let mut h = harness(no_solver());
    h.run();
    h.get_by_label("Point support 1: (0, 0) mm, fixes x")
        .click();
    h.run();
    h.get_by_label("Remove support 1").click();
    h.run();
    assert!(h.state().scene().boundary.points.is_empty());
    assert!(
        matches!(h.state().message(), Some(Message::Error(e)) if e.contains("boundary")),
        "{:?}",
        h.state().message()
    );
    h.get_by_label("Add point support").click();
    h.run();
    let points = &h.state().scene().boundary.points;
    assert_eq!(points.len(), 1);
    assert_eq!(
        (points[0].at, points[0].fix),
        ([0.0, 0.0], cdca::scene::Fix::X)
    );
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    // the section keeps its open state from the removed support's
    if h.query_all_by_label("fixes").count() == 0 {
        h.get_by_label_contains("Point support 1:").click();
        h.run();
    }
    for label in ["x", "y", "fixes"] {
        assert!(h.query_all_by_label(label).count() > 0, "{label}");
    }
}

// --- with the solver -------------------------------------------------------

/// Contact settings go once a solve shows every crack face open (the
/// bundled centre crack under tension), and stay hidden while the next
/// solve runs; the default scene's closed flaw keeps them. A point
/// support's remove button stays inside the panel.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn contact_settings_are_left_out_where_every_face_is_open() {
    let mut h = solved_default();
    for label in [
        "Contact tolerance",
        "Max contact iterations",
        "Traction arrows",
    ] {
        assert!(h.query_by_label(label).is_some(), "{label}: a closed flaw");
    }
    h.state_mut().push(Command::OpenSceneText {
        source: "centre_crack_tension.json".to_owned(),
        text: include_str!("../assets/scenes/centre_crack_tension.json").to_owned(),
    });
    h.run_steps(20);
    assert!(h.state().is_solved() && h.state().message().is_none());
    for label in [
        "Contact tolerance",
        "Max contact iterations",
        "Traction arrows",
    ] {
        assert!(
            h.query_by_label(label).is_none(),
            "{label}: every face open"
        );
    }
    h.get_by_label_contains("Every crack face was open at the last solve");
    h.get_by_label_contains("friction and cohesion have no effect");
    h.get_by_label_contains("Point support 2:").click();
    h.run();
    let remove = h.get_by_label("Remove support 2").rect();
    let canvas = h.get_by_label(cdca_workbench::app::CANVAS_LABEL).rect();
    assert!(
        remove.right() <= canvas.left(),
        "the button lies in the scene panel: {remove:?}, canvas {canvas:?}"
    );
    // while an edit is under way (a drag, solved as it goes) the faces
    // stay open
    let mut dragged = h.state().scene().clone();
    dragged.cracks[0].points = Some(vec![[0.4, 1.5], [0.61, 1.51]]);
    h.state_mut().push(Command::SetScene {
        scene: Box::new(dragged),
        ongoing: true,
    });
    h.run();
    assert!(h.query_by_label("Contact tolerance").is_none());
    // another scene: the verdict goes with the old one
    h.state_mut().push(Command::OpenSceneText {
        source: "default.json".to_owned(),
        text: include_str!("../assets/scenes/specimen_single_flaw.json").to_owned(),
    });
    h.run_steps(20);
    assert!(h.query_by_label("Contact tolerance").is_some());
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn default_scene_opens_solved_and_a_tip_can_be_inspected() {
    let mut h = harness(Options::default());
    h.run_steps(20);
    let app = h.state();
    assert!(app.is_solved());
    assert!(app.field_is_shown(), "the colour map is sampled");
    assert!(app.message().is_none(), "{:?}", app.message());
    let tips = app.tip_positions();
    assert_eq!(tips.len(), 2, "the closed crack has two free tips");
    // the most loaded tip is inspected from the start
    let (first, curve) = app.inspected_tip().expect("a tip is inspected on open");
    assert!(first < 2 && curve, "tip {first} with its curve");
    h.get_by_label("Decision");
    let at = app.screen_from_world(tips[1 - first]);
    click_at(&mut h, at);
    h.run_steps(3);
    assert_eq!(
        h.state().inspected_tip(),
        Some((1 - first, true)),
        "the other tip inspected, with its σ_θθ / τ_rθ curve"
    );
    h.get_by_label("K_I");
    h.get_by_label("Decision");
    // a click elsewhere keeps it; "none" in the inspector clears it for good
    click_at(&mut h, egui::pos2(at.x + 80.0, at.y - 80.0));
    h.run_steps(3);
    assert_eq!(h.state().inspected_tip(), Some((1 - first, true)));
    h.state_mut().push(Command::SelectTip(None));
    h.run_steps(3);
    assert_eq!(h.state().inspected_tip(), None);
}

#[test]
fn step_grows_the_residual_history() {
    let mut h = harness(Options::default());
    h.run_steps(5);
    edit_scene(&mut h, |s| {
        s.solver.kind = cdca::scene::SolverKind::Automaton;
    });
    h.run_steps(3);
    let before = h.state().residual_samples();
    h.get_by_label("Step").click();
    h.run_steps(3);
    let after_one = h.state().residual_samples();
    h.get_by_label("Step").click();
    h.run_steps(3);
    let after_two = h.state().residual_samples();
    assert!(
        after_one > before && after_two > after_one,
        "{before} → {after_one} → {after_two}"
    );
}

/// Clicks Grow one step and runs frames until the step has ended: it runs
/// in resumable chunks, then the grown cracks are solved.
fn grow_one_step(h: &mut Harness<'_, WorkbenchApp>) {
    h.get_by_label("Grow one step").click();
    h.run_steps(2);
    for _ in 0..5000 {
        if h.state().run_mode() == RunMode::Paused {
            break;
        }
        h.step();
    }
    assert_eq!(h.state().run_mode(), RunMode::Paused, "the step ends");
}

/// Each click of Grow one step records exactly one growth step (the
/// default scene grows to failure, so every step extends a tip) and ends
/// paused.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn grow_one_step_records_one_step_per_click() {
    let mut h = harness(Options::default());
    h.run_steps(5);
    for click in 1..=3 {
        grow_one_step(&mut h);
        assert_eq!(h.state().growth_steps(), click, "click {click}");
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn grow_makes_the_crack_longer() {
    let mut h = harness(Options::default());
    h.run_steps(5);
    let length = |app: &WorkbenchApp| {
        app.simulated_cracks()
            .iter()
            .map(|c| polyline_length(c))
            .sum::<f64>()
    };
    let before = length(h.state());
    let flaw = h.state().scene().cracks[0].polyline(1e-3);
    assert!(
        before >= 0.99 * polyline_length(&flaw),
        "solved on start: {before}"
    );
    for _ in 0..10 {
        grow_one_step(&mut h);
        if length(h.state()) > before + 1e-6 {
            break;
        }
    }
    assert!(length(h.state()) > before + 1e-6, "no growth in 10 steps");
    assert!(h.state().growth_steps() > 0);
}

/// Frame time during Run growth on the default scene (logic + UI on the
/// CPU, no GPU): `cargo test --release --test ui frame_time -- --nocapture`.
#[test]
#[ignore = "a timing measurement, not a test to run on shared machines (bash scripts/frame_times.sh; measured on the default scene, 2-core machine at load 1: mean 10.7-10.8 ms, p95 16-18 ms, max 23 ms; 2026-11-27 with secondary cracks, 26 growth steps: mean 11.3 ms, p95 20.8 ms, max 25.8 ms; later, with low-rank corrections and kept tip domains made in slices of their own: 219-244 frames for the 26 steps, mean 11.7-11.9 ms, p95 15.7 ms, max 19.8 ms)"]
fn frame_time_during_run_growth() {
    let mut h = harness(Options::default());
    h.run_steps(10);
    h.get_by_label("Run growth").click();
    h.step();
    // the frame that applies the click rebuilds the simulation unloaded
    // with the growth solver (one Simulation::new): reported on its own
    let t = std::time::Instant::now();
    h.step();
    println!(
        "start frame (growth simulation built) {:.0} ms",
        t.elapsed().as_secs_f64() * 1e3
    );
    let mut times = Vec::new();
    for _ in 0..300 {
        let t = std::time::Instant::now();
        h.step();
        times.push(t.elapsed().as_secs_f64());
        if h.state().run_mode() == RunMode::Paused {
            break;
        }
    }
    let steps = h.state().growth_steps();
    let sequence: Vec<String> = times.iter().map(|t| format!("{:.0}", t * 1e3)).collect();
    println!("frame times [ms]: {}", sequence.join(" "));
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let mean = times.iter().sum::<f64>() / n as f64;
    let p95 = times[(n * 95 / 100).min(n - 1)];
    let max = times[n - 1];
    println!(
        "Run growth on the default scene: {n} frames, {steps} growth steps; frame time mean {:.1} ms, p95 {:.1} ms, max {:.1} ms",
        mean * 1e3,
        p95 * 1e3,
        max * 1e3
    );
    let median = times[n / 2];
    assert!(steps > 0);
    // Targets: median 33 ms (30 Hz), worst 50 ms (issue 11). Growth
    // advances in phases of a few ms; the direct solver's symbolic
    // factorisation after each rebuild is the longest.
    assert!(median < 0.033, "median frame time {:.1} ms", median * 1e3);
    assert!(max < 0.05, "max frame time {:.1} ms", max * 1e3);
}

fn polyline_length(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}

/// `cdca-workbench SCENE --run grow` starts the growth run by itself: with
/// no click, growth steps are recorded.
#[test]
fn a_run_asked_for_on_the_command_line_starts_by_itself() {
    let mut h = harness(Options {
        start_run: Some(cdca_workbench::StartRun::Grow),
        ..Options::default()
    });
    let grew = (0..400).any(|_| {
        h.step();
        h.state().growth_steps() > 0
    });
    assert!(
        grew,
        "a growth step was recorded: {:?}",
        h.state().message()
    );
}

/// The solver race starts every iterative solver from u = 0 on the default
/// scene and measures its error against the direct solution: each runs more
/// than one iteration, its energy-norm error starts at 1 (‖0 − u_ref‖_K /
/// ‖u_ref‖_K, to 1e-9), never rises (Gauss–Seidel, SOR and the PCG variants
/// all decrease the energy norm of the error on an SPD system; 1e-9
/// relative slack for round-off) and at least halves within the 2 s cap
/// per solver (on an idle machine the slowest, the plain automaton, reaches
/// 2e-4 in 1 s; the margin is for a loaded machine). The direct reference
/// has zero error against itself.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn compare_from_a_cold_start_gives_falling_error_curves() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    h.get_by_label("Compare solvers").click();
    h.step();
    h.state_mut()
        .push(Command::CompareSolvers { time_cap: 2.0 });
    for _ in 0..5000 {
        h.step();
        if h.state()
            .race()
            .is_some_and(cdca_workbench::study::race::Race::finished)
        {
            break;
        }
    }
    assert_eq!(
        h.state().plot_tab(),
        cdca_workbench::PlotTab::SolverComparison
    );
    let Some(race) = h.state().race() else {
        panic!("no race");
    };
    assert!(race.finished(), "the race ends within 5000 frames");
    assert!(race.runs[0].samples[0].energy < 1e-12, "direct reference");
    assert_eq!(race.runs.len(), 5);
    for run in &race.runs[1..] {
        let name = run.racer.name;
        assert!(run.error.is_none(), "{name}: {:?}", run.error);
        assert!(
            run.iterations() > 1,
            "{name}: {} iterations",
            run.iterations()
        );
        let e: Vec<f64> = run.samples.iter().map(|s| s.energy).collect();
        assert!((e[0] - 1.0).abs() < 1e-9, "{name} starts cold: {}", e[0]);
        for w in e.windows(2) {
            assert!(w[1] <= w[0] * (1.0 + 1e-9), "{name}: error rose {e:?}");
        }
        assert!(e[e.len() - 1] < 0.5 * e[0], "{name}: {e:?}");
        let t: Vec<f64> = run.samples.iter().map(|s| s.seconds).collect();
        assert!(
            t.windows(2).all(|w| w[1] >= w[0]),
            "{name}: time runs forward"
        );
    }
    let csv = race.to_csv();
    assert!(csv.lines().count() > race.runs.len());
    // the race's plots, legend and summary fit between the side panels
    let overflow = widgets_under_the_canvas(&h);
    assert!(overflow.is_empty(), "{}", overflow.join("\n"));
}

/// The side panels keep their width as their text changes: the canvas
/// stays where it is while a relaxation fills the solver panel's status
/// lines (exact equality of the canvas rectangle).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_canvas_does_not_move_while_the_status_text_changes() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    let canvas =
        |h: &Harness<'_, WorkbenchApp>| h.get_by_label(cdca_workbench::app::CANVAS_LABEL).rect();
    edit_scene(&mut h, |s| {
        s.solver.kind = cdca::scene::SolverKind::Automaton;
    });
    h.run_steps(2);
    let before = canvas(&h);
    h.get_by_label("Relax").click();
    for _ in 0..10 {
        h.step();
        assert_eq!(canvas(&h), before, "the canvas moved");
    }
    assert!(h.state().residual_samples() > 1, "the relaxation ran");
    h.get_by_label("Pause").click();
    h.run_steps(2);
    assert_eq!(canvas(&h), before);
}

/// The default scene switched to `kind` (through the solver panel's path:
/// a scene edit).
fn with_solver(h: &mut Harness<'_, WorkbenchApp>, kind: cdca::scene::SolverKind) {
    edit_scene(h, |s| s.solver.kind = kind);
    h.run_steps(2);
}

/// Relax with the plain automaton from u = 0 (31 k sweeps to converge on
/// the default scene): within the first 150 frames, long before
/// convergence, the canvas shows a sampled field of the current iterate,
/// and later frames show a different field (the stress front has moved:
/// some sample's σ changed by more than 1 % of the largest |σ| shown).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn relax_with_the_automaton_shows_the_field_before_convergence() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    with_solver(&mut h, cdca::scene::SolverKind::Automaton);
    h.get_by_label("Relax").click();
    let mut fields: Vec<(u64, Vec<[f64; 3]>)> = Vec::new();
    for _ in 0..150 {
        h.step();
        let app = h.state();
        assert!(
            app.relax_status().is_none_or(|r| !r.converged),
            "converged too soon to watch"
        );
        if let Some((version, _)) = app.shown_field()
            && fields.last().is_none_or(|(v, _)| *v != version)
        {
            fields.push((version, app.shown_stresses()));
        }
        if fields.len() >= 3 {
            break;
        }
    }
    assert!(fields.len() >= 2, "{} live fields shown", fields.len());
    let (first, last) = (&fields[0].1, &fields[fields.len() - 1].1);
    assert_eq!(first.len(), last.len());
    let scale = last
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let changed = first
        .iter()
        .zip(last)
        .flat_map(|(a, b)| a.iter().zip(b))
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .any(|(a, b)| (a - b).abs() > 0.01 * scale);
    assert!(
        scale > 0.0 && changed,
        "the field did not change (scale {scale})"
    );
    assert!(h.state().run_mode() == RunMode::Relaxing, "still relaxing");
}

/// Run growth with an iterative solver (the automaton, which growth
/// accelerates to multigrid-CG by default): every frame advances the run,
/// with a new residual sample, a new solve, a λ_cr trial taken by scaling
/// the last solve (a new load factor printed), a new growth step, a chunk
/// of the rebuild after growth (the cracked elements integrated over
/// frames) or the field at λ_cr sampled (shown before the tips move on);
/// every frame outside those with new residual samples or a new step;
/// the progress line shows the sweeps and residual, or the rebuild.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn run_growth_with_an_iterative_solver_advances_every_frame() {
    // the host in-process (frames advance it)
    let mut h = harness(Options::default());
    h.run_steps(3);
    with_solver(&mut h, cdca::scene::SolverKind::Automaton);
    assert_eq!(
        h.state().growth_solver(),
        cdca::scene::SolverKind::Multigrid
    );
    h.get_by_label("Run growth").click();
    h.run_steps(2);
    let progress = |h: &Harness<'_, WorkbenchApp>| {
        let s = h.state();
        (
            s.growth_progress(),
            s.shown_field(),
            s.field_progress(),
            s.load_factor(),
        )
    };
    let mut last = progress(&h);
    let (mut frames, mut sweeping) = (0, 0);
    while frames < 60 && h.state().run_mode() == RunMode::Growing {
        h.step();
        let now = progress(&h);
        if h.state().run_mode() == RunMode::Growing {
            assert_ne!(now, last, "frame {frames}: the run did not advance");
            let ((steps, samples, residual, rebuild), field, sampling, lambda) = now;
            let solving = rebuild.is_none()
                && last.0.3.is_none()
                && field == last.1
                && lambda.to_bits() == last.3.to_bits();
            let swept = samples != last.0.1 || residual != last.0.2 || steps != last.0.0;
            assert!(
                !solving || sampling.is_some() || swept,
                "frame {frames}: no new residual sample"
            );
            sweeping += usize::from(swept);
        }
        last = now;
        frames += 1;
    }
    assert!(sweeping > 0, "no residual samples");
    assert!(
        frames >= 10,
        "the run ended after {frames} frames: {:?} {:?}",
        h.state().message(),
        h.state().run_mode()
    );
    assert!(
        h.query_by_label_contains(", residual").is_some()
            || h.query_by_label_contains("preparing the cracked plate")
                .is_some()
            || h.state().run_mode() != RunMode::Growing,
        "progress line"
    );
    h.get_by_label("Pause").click();
    h.run_steps(2);
    assert_eq!(h.state().run_mode(), RunMode::Paused);
}

/// A study of the crack's face friction on the default scene (two values,
/// direct solver) finishes within the frame budget and records, for each
/// value, a first growth step whose kink angle is finite and inside
/// (−90°, 90°) with tension or shear mode (tensile wings are expected here:
/// K_I ≈ 0, K_II < 0 on the closed crack).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_friction_study_records_the_first_growth_of_each_value() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    h.state_mut()
        .push(Command::RunStudy(cdca_workbench::study::StudySetup {
            path: "cracks.0.friction".to_owned(),
            from: 0.2,
            to: 0.6,
            count: 2,
        }));
    for _ in 0..3000 {
        h.step();
        if h.state()
            .study()
            .is_some_and(cdca_workbench::study::Study::finished)
        {
            break;
        }
    }
    assert_eq!(h.state().plot_tab(), cdca_workbench::PlotTab::Study);
    let Some(study) = h.state().study() else {
        panic!("no study: {:?}", h.state().message());
    };
    assert!(study.finished());
    assert_eq!(study.points.len(), 2);
    for p in &study.points {
        assert!(p.error.is_none(), "{:?}", p.error);
        assert!(
            !(p.grown.is_empty() && p.nucleated.is_empty()),
            "value {}: no growth ({:?})",
            p.value,
            p.outcome
        );
        // a crack started in the intact rock (μ = 0.6 holds the flaw's
        // faces: the rock fails first) met the envelope
        for n in &p.nucleated {
            assert!(n.utilisation >= 1.0 - 1e-9, "{n:?}");
            assert!(n.direction_deg > -90.0 && n.direction_deg <= 90.0, "{n:?}");
        }
        for g in &p.grown {
            assert!(g.angle_deg.is_finite() && g.angle_deg.abs() < 90.0, "{g:?}");
            assert_ne!(g.mode, cdca::report::Mode::None);
        }
        // the first growth's λ_cr: above 1 since the reference load is
        // 50 MPa (issue 65), within the search's cap
        let cap = h.state().scene().growth.max_load_factor;
        assert!(p.load_factor.is_some_and(|l| l > 0.0 && l <= cap));
        // the rock away from the flaw carries about the far field, λ_cr ×
        // 50 MPa, against σ_c = 80.24 MPa (c = 15 MPa, φ = 49°): within 3%
        let (lambda, rock) = (p.load_factor.unwrap_or_default(), p.intact_rock);
        let u = rock.map_or(0.0, |r| r.utilisation);
        let far = lambda * 50e6 / 80.2386e6;
        assert!((u / far - 1.0).abs() < 0.03, "u {u} against {far}");
    }
    assert!(study.to_csv().lines().count() >= 3);
    // the table beside the plots shows each measured value: parameter,
    // λ_cr to 3 decimals, angle to 0.1°
    let rows: Vec<(String, String, String)> = study
        .points
        .iter()
        .filter_map(|p| {
            let g = p.grown.first()?;
            Some((
                format!("{}", p.value),
                format!("{:.3}", p.load_factor.unwrap_or_default()),
                format!("{:.1}", g.angle_deg),
            ))
        })
        .collect();
    assert!(!rows.is_empty(), "a value grew a tip first");
    h.run();
    for (value, lambda, angle) in rows {
        for text in [&value, &lambda, &angle] {
            assert!(
                h.query_all_by_label(text).next().is_some(),
                "the study table does not show {text}"
            );
        }
    }
    assert!(h.query_by_label("λ_cr [–]").is_some());
    assert!(h.query_by_label("u [–]").is_some());
    assert!(
        h.query_by_label("λ at which the intact rock reaches its strength")
            .is_some(),
        "the λ_cr plot's legend names the rock's line"
    );
    // plots and table fit between the side panels
    let overflow = widgets_under_the_canvas(&h);
    assert!(overflow.is_empty(), "{}", overflow.join("\n"));
}

/// A relaxation stopped at its cap (the automaton with at most 50 sweeps,
/// far from the 1e-10 tolerance) is shown as not converged, in the warning
/// line with its sweep count and residual; so is a direct solve whose
/// contact iteration stopped at its cap (2).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_capped_relaxation_is_shown_as_not_converged() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    edit_scene(&mut h, |s| {
        s.solver.kind = cdca::scene::SolverKind::Automaton;
        s.solver.max_iterations = 50;
    });
    h.run_steps(2);
    h.get_by_label("Relax").click();
    for _ in 0..200 {
        h.step();
        if h.state().relax_status().is_some_and(|r| r.finished) {
            break;
        }
    }
    h.run_steps(2);
    let r = h.state().relax_status();
    assert!(r.is_some_and(|r| r.finished && !r.converged), "{r:?}");
    // the test that failed, in the solver's words
    h.get_by_label_contains("Not converged: the automaton solver stopped at 50 iterations");
    h.get_by_label_contains("NOT converged");
    h.get_by_label("no (not converged)");

    // the direct solver's contact iteration stopped at its cap says so too
    // (it read "Solved: yes", with no warning, and K_II twice the value)
    edit_scene(&mut h, |s| {
        s.solver.kind = cdca::scene::SolverKind::Direct;
        s.solver.max_contact_iterations = 2;
    });
    // the edit's solve runs in slices
    h.run_steps(1);
    run_until_paused(&mut h, 200);
    h.run_steps(2);
    let r = h.state().relax_status();
    assert!(r.is_some_and(|r| r.finished && !r.converged), "{r:?}");
    h.get_by_label("no (not converged)");
    h.get_by_label_contains(
        "Not converged: the contact iteration did not settle within 2 contact iterations",
    );
}

/// Runs frames until the run in progress has ended (paused), at most
/// `frames`.
fn run_until_paused(h: &mut Harness<'_, WorkbenchApp>, frames: usize) {
    for _ in 0..frames {
        if h.state().run_mode() == RunMode::Paused {
            break;
        }
        h.step();
    }
    assert_eq!(
        h.state().run_mode(),
        RunMode::Paused,
        "the run ends within {frames} frames: {:?}",
        h.state().message()
    );
}

/// The workbench on its default scene after Run growth ran to its end.
fn grown_default() -> Harness<'static, WorkbenchApp> {
    let mut h = harness(Options::default());
    h.run_steps(5);
    h.get_by_label("Run growth").click();
    h.run_steps(2);
    run_until_paused(&mut h, 20_000);
    h.run_steps(10);
    assert!(h.state().growth_outcome().is_some(), "growth ended");
    h
}

/// A growth step's report without its wall time, as JSON (the floats
/// round-trip exactly): equal strings are bitwise-equal reports.
fn step_bits(step: &cdca::report::GrowthStepReport) -> String {
    serde_json::to_string(&step.untimed()).unwrap_or_default()
}

/// Run growth on the default scene to its end (unstable: the intact rock
/// fails beside the wings): the app records the same
/// steps, to the bit, as `Simulation::grow_step` run headless on the same
/// scene (the app's run is sliced across frames; the numbers do not
/// change). The end is a solved, shown state: the final cracks solved at
/// the last step's λ_cr (`Simulation::start_final_solve`), the panel says
/// Solved: yes at exactly that λ, and the canvas's field is of that load
/// and that solve: its stresses equal the headless final solve's at the
/// sample points (1e-9 relative to the largest, the same direct solve).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_end_of_a_growth_run_is_solved_and_shown_at_the_printed_load() {
    let h = grown_default();
    let app = h.state();
    assert!(app.message().is_none(), "{:?}", app.message());

    let scene = cdca::Scene::try_from(app.scene().clone()).expect("valid scene");
    let mut headless = cdca::Simulation::new(scene).expect("valid scene");
    while headless.growth_finished().is_none() {
        headless.grow_step().expect("step");
    }
    assert_eq!(app.growth_outcome(), headless.growth_finished());
    let (ours, theirs) = (app.growth_history(), headless.history());
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(theirs) {
        assert_eq!(step_bits(a), step_bits(b), "step {}", b.step);
    }

    let last = theirs.last().expect("steps").load_factor;
    assert_eq!(headless.start_final_solve(), Some(last));
    headless.solve().expect("the final cracks solve");
    assert!(app.is_solved() && !app.specimen_split());
    assert!(
        app.relax_status()
            .is_some_and(|r| r.finished && r.converged)
    );
    assert_eq!(app.load_factor(), last, "the printed λ is the last step's");
    assert_eq!(
        app.shown_field_load_factor(),
        Some(last),
        "the field's load"
    );
    h.get_by_label_contains(&format!("{last:.3} ("));
    // the default flaw grows its wings, then cracks start in the intact
    // rock at a load that does not rise: the specimen has failed there
    assert_eq!(app.growth_outcome(), Some(cdca::report::Outcome::Unstable));
    // the status gives its strength against the intact rock's, as the
    // report does
    let strength = headless
        .strength(cdca::report::Outcome::Unstable)
        .expect("a peak");
    let ratio = strength.ratio.expect("the uncracked rock fails");
    assert!(ratio < 1.0, "a flaw weakens the specimen: {ratio}");
    h.get_by_label_contains(&format!("{:.0} % of the intact rock's", 100.0 * ratio));

    field::assert_shown_field_is(app, &headless, 37, 100);
}

/// The solver race keeps the solved field on the canvas: started with the
/// app (`--run compare`, the solve and the race in the first frame), the
/// field of the solve at λ = 1 is sampled within a few frames, long before
/// the race ends, and stays, the same version, while the race runs. The
/// panel says how long the race takes at most (4 iterative solvers × the
/// 10 s cap), and Cancel race stops it.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_race_keeps_the_solved_field_on_the_canvas_and_can_be_cancelled() {
    let mut h = harness(Options {
        start_run: Some(cdca_workbench::StartRun::Compare),
        ..Options::default()
    });
    let mut shown = None;
    for _ in 0..20 {
        h.step();
        if let Some(field) = h.state().shown_field() {
            shown = Some(field);
            break;
        }
    }
    let Some(field) = shown else {
        panic!("no field within 20 frames of the race's start");
    };
    assert!(h.state().is_solved());
    assert_eq!(h.state().shown_field_load_factor(), Some(1.0));
    let running = |h: &Harness<'_, WorkbenchApp>| h.state().race().is_some_and(|r| !r.finished());
    assert!(running(&h), "the race is still under way");
    for _ in 0..30 {
        h.step();
        assert_eq!(h.state().shown_field(), Some(field), "the field stays");
    }
    assert!(running(&h), "the race is still under way");
    h.get_by_label_contains("About 40.00 s in all: 4 solvers × 10.00 s cap");
    h.get_by_label("Cancel race").click();
    h.run_steps(2);
    let race = h.state().race().expect("the race stays");
    assert!(race.finished() && race.cancelled());
    assert!(h.query_by_label("Cancel race").is_none());
    assert_eq!(h.state().shown_field(), Some(field));
}

/// File ▸ Save writes the scene as simulated: saved in the middle of a
/// growth step (after 2 steps, Run growth paused a few frames into the
/// third) and opened again, Grow one step records the identical next
/// step, to the bit, as the run that went on (wall time aside), with the
/// same cracks.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_scene_saved_mid_growth_reopens_and_grows_the_identical_next_step() {
    let mut h = harness(Options::default());
    h.run_steps(5);
    grow_one_step(&mut h);
    grow_one_step(&mut h);
    h.get_by_label("Run growth").click();
    h.run_steps(4);
    h.get_by_label("Pause").click();
    h.run_steps(2);
    let done = h.state().growth_steps();
    assert!(done >= 2 && h.state().growth_outcome().is_none(), "{done}");
    let saved = h.state().scene_file().expect("the scene saves");
    let resume = cdca::Scene::from_json(&saved)
        .expect("the saved scene parses")
        .growth
        .resume
        .clone()
        .expect("growth.resume");
    assert_eq!(resume.steps, done);

    grow_one_step(&mut h);
    let went_on = h.state().growth_history()[done].clone();

    let mut reopened = harness(Options::default());
    reopened.run_steps(3);
    reopened.state_mut().push(Command::OpenSceneText {
        source: "saved.json".to_owned(),
        text: saved,
    });
    // the opened scene's solve runs in slices; Grow one step waits for it
    reopened.run_steps(1);
    run_until_paused(&mut reopened, 200);
    assert!(
        reopened.state().message().is_none(),
        "{:?}",
        reopened.state().message()
    );
    grow_one_step(&mut reopened);
    // the saved steps (`growth.resume.history`: their λ and events), then
    // the one grown now
    let history = reopened.state().growth_history();
    let steps: Vec<usize> = history.iter().map(|s| s.step).collect();
    assert_eq!(steps, (1..=done + 1).collect::<Vec<_>>());
    for (saved, ran) in history.iter().zip(h.state().growth_history()) {
        assert_eq!(saved.load_factor.to_bits(), ran.load_factor.to_bits());
        assert_eq!(saved.grown, ran.grown);
    }
    assert_eq!(step_bits(&history[done]), step_bits(&went_on));
    assert_eq!(
        reopened.state().simulated_cracks(),
        h.state().simulated_cracks()
    );
}

/// A link shares the scene as drawn, never the run (issue 66): after two
/// growth steps Copy link carries the Scene panel's scene (the flaw as
/// drawn, no `growth.resume`), not the run's state that File ▸ Save
/// writes; the menu says so beside the button; Reset, and an edit, take
/// the link out of the page address.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_link_after_a_run_shares_the_scene_as_drawn() {
    let mut h = harness(Options::default());
    h.run_steps(5);
    let drawn = h.state().scene().clone();
    grow_one_step(&mut h);
    grow_one_step(&mut h);
    let run = cdca::Scene::from_json(&h.state().scene_file().expect("the run saves"))
        .expect("valid")
        .into_file();
    assert!(run.growth.resume.is_some() && run.cracks != drawn.cracks);
    h.get_by_label("File").click();
    h.run();
    h.get_by_label_contains("The scene as drawn, not the run");
    h.get_by_label("Copy link to this scene").click();
    h.run();
    let link = h.state().scene_link().expect("a link");
    assert_eq!(
        cdca_workbench::files::link::from_link(&link),
        Some(Ok(drawn))
    );
    assert!(h.state().address_holds_link());
    match h.state().message() {
        Some(Message::Info(m)) => assert!(
            m.starts_with("Link to the scene as drawn (not the run)"),
            "{m}"
        ),
        m => panic!("{m:?}"),
    }
    h.state_mut().push(Command::Reset);
    h.run();
    assert!(!h.state().address_holds_link(), "Reset takes it out");
    h.state_mut().push(Command::CopyLink);
    h.run();
    assert!(h.state().address_holds_link());
    edit_scene(&mut h, |s| s.cracks[0].friction = 0.3);
    h.run();
    assert!(!h.state().address_holds_link(), "an edit takes it out");
}

/// An edge crack in a plate pulled on top (roller at the bottom): two
/// critical steps take it through to the right side, and the upper half,
/// held by nothing, is free to move away. (Whether the direct solver's
/// factorisation meets a non-positive pivot on such a mechanism depends
/// on round-off: on this mesh it does; on 20 × 40 it returns a "solution"
/// with residual 2.9, which the direct solver's true-residual test now
/// reports as not converged.)
const SPLITTING_SCENE: &str = include_str!("scenes/edge_crack_cut_through.json");

/// When the final cracks cut the specimen in two, their solve fails (no
/// stiffness against the free piece's motion): the run ends without an
/// error, the panel says the specimen split and Solved: no, and the
/// canvas keeps the last solved field, the last step's solve at λ_cr,
/// which is the λ printed.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_run_that_cuts_the_specimen_through_says_it_split_and_keeps_the_last_field() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    h.state_mut().push(Command::OpenSceneText {
        source: "split.json".to_owned(),
        text: SPLITTING_SCENE.to_owned(),
    });
    h.run_steps(3);
    // the opened scene's solve first: it removes the contact settings (every
    // face is open), which moves the buttons below them, and a click sent
    // meanwhile (on a loaded machine) went to the wrong widget
    run_until_paused(&mut h, 2000);
    h.run_steps(1);
    h.get_by_label("Run growth").click();
    h.run_steps(2);
    run_until_paused(&mut h, 5000);
    h.run_steps(5);
    let app = h.state();
    assert!(app.message().is_none(), "{:?}", app.message());
    assert_eq!(app.growth_outcome(), Some(cdca::report::Outcome::Through));
    assert!(app.specimen_split() && !app.is_solved());
    let last = app.growth_history().last().expect("steps").load_factor;
    assert_eq!(app.load_factor(), last);
    assert_eq!(app.shown_field_load_factor(), Some(last));
    assert!(
        app.shown_stresses()
            .iter()
            .flatten()
            .any(|v| v.is_finite() && *v != 0.0),
        "a loaded field is shown"
    );
    h.get_by_label("no (specimen split)");
    // the free piece named: the edge crack cut off the part above it
    h.get_by_label_contains("The specimen is cut through: Crack 1 cut off a piece");
    // the end of a run that failed as it should is no warning: the story
    // says how
    h.get_by_label_contains("The cracks ran through the specimen at step");
    h.get_by_label_contains(&format!(
        "The field shown is the last solved state, at λ = {last:.3}."
    ));
    h.get_by_label("No free tip: the final cracks cut the specimen through.");
}

/// A shared link opens its scene (solved, as any opened scene); a
/// truncated link opens the default scene, not the last one, and says why.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_shared_link_opens_its_scene_and_a_bad_one_falls_back_with_a_message() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    let mut shared = h.state().scene().clone();
    shared.name = "Flaw at 50°, μ = 0.45".to_owned();
    shared.cracks[0].friction = 0.45;
    let fragment = cdca_workbench::files::link::to_fragment(&shared.to_json().expect("json"));
    h.state_mut().push(Command::OpenLink(format!(
        "https://example.org/cdca/#{fragment}"
    )));
    // the build and the solve's slices take a few frames
    h.run();
    assert_eq!(h.state().scene(), &shared);
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    assert!(h.state().is_solved(), "the linked scene is solved");

    let truncated = &fragment[..fragment.len() - 40];
    h.state_mut()
        .push(Command::OpenLink(format!("#{truncated}")));
    h.run_steps(3);
    assert_eq!(
        h.state().scene(),
        &cdca_workbench::files::scenes::default_scene()
    );
    let e = error_message(&h);
    assert!(
        e.starts_with("The shared link could not be opened: the link is truncated or damaged")
            && e.ends_with("Showing the default scene."),
        "{e}"
    );
}

/// A mesh refined in the panel does not start a solve that holds the
/// window still or exhausts a browser tab's memory: over 800 × 800 any
/// solver, and over 400 × 400 the direct solver (one factorisation in one
/// piece), are refused before any work with the limit and the way round
/// it; a finer mesh under the limit waits for Solve when the last solve,
/// scaled to it, would not be quick (60² → 200²: 11× the elements).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_mesh_too_fine_to_solve_at_once_is_refused_or_waits_for_solve() {
    use cdca::scene::SolverKind;
    let mut h = solved_default();
    edit_scene(&mut h, |s| (s.mesh.nx, s.mesh.ny) = (1000, 1000));
    h.run();
    let e = error_message(&h);
    assert!(
        e.contains("`mesh` = 1000 × 1000") && e.contains("up to 640000 elements"),
        "{e}"
    );
    assert!(!h.state().is_solved());
    edit_scene(&mut h, |s| (s.mesh.nx, s.mesh.ny) = (500, 500));
    h.run();
    let e = error_message(&h);
    assert!(
        e.contains("direct solver") && e.contains("multigrid-CG"),
        "{e}"
    );
    // the race needs the direct solution too
    edit_scene(&mut h, |s| s.solver.kind = SolverKind::Multigrid);
    h.run();
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    h.get_by_label("Compare solvers").click();
    h.run();
    assert!(error_message(&h).starts_with("The race cannot run"));
    edit_scene(&mut h, |s| {
        s.solver.kind = SolverKind::Direct;
        (s.mesh.nx, s.mesh.ny) = (200, 200);
    });
    h.run();
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    assert!(!h.state().is_solved(), "not solved unasked");
    h.get_by_label("Scene changed — press Solve.");
}

/// A run whose λ_cr search steps around a trial that did not converge
/// (held-out random layout 0 of the second seed with the contact cap at 20,
/// see the solver test `a_trial_that_does_not_converge_is_stepped_around`) ends `through` with
/// every step converged, and the status says which step stepped around
/// which load (steps 4 and 18 since the contact iteration's Newton steps
/// give way to the mix after two misses); the finished run's status fits
/// the solver panel.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_step_that_stepped_around_an_unsolved_trial_says_so() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    edit_scene(&mut h, |s| {
        // the far trial converges within 40 contact iterations, not 20: a cap of 20
        // keeps it unsolved (see the solver test, which records it on
        // wings alone)
        s.solver.max_contact_iterations = 20;
        s.growth.secondary_cracks = false;
        // the paper's model, as the solver test grows it
        s.growth.intact_rock = cdca::scene::IntactRock::Ignore;
        let flaw = |a: [f64; 2], b: [f64; 2], friction: f64| cdca::scene::CrackSpec {
            points: Some(vec![a, b]),
            friction,
            cohesion: 15e6,
            ..s.cracks[0].clone()
        };
        s.cracks = vec![
            flaw(
                [0.017_373_425_736_637_946, 0.011_086_036_533_432_573],
                [0.020_500_679_813_995_438, 0.017_565_268_443_355_254],
                1.2,
            ),
            flaw(
                [0.008_333_043_678_301_932, 0.013_401_749_793_131_664],
                [0.012_879_819_518_394_83, 0.015_102_858_484_064_29],
                0.2,
            ),
        ];
    });
    // the edit's solve runs in slices: Run growth waits for it
    h.run_steps(1);
    run_until_paused(&mut h, 2000);
    h.get_by_label("Run growth").click();
    h.run_steps(2);
    run_until_paused(&mut h, 20_000);
    h.run_steps(3);
    let app = h.state();
    assert_eq!(app.growth_outcome(), Some(cdca::report::Outcome::Through));
    assert!(app.growth_history().iter().all(|s| s.converged));
    let stepped = app
        .growth_history()
        .iter()
        .filter(|s| !s.unsolved_trials.is_empty())
        .count();
    assert!(stepped >= 1);
    h.get_by_label_contains(&format!(
        "{stepped} growth step(s) stepped around a λ_cr trial"
    ));
    // the status of a finished run fits its panel
    let overflow = widgets_under_the_canvas(&h);
    assert!(overflow.is_empty(), "{}", overflow.join("\n"));
}

/// An edit of the flaw's friction re-solves on the kept discretisation
/// (nothing left to integrate right after the edit), and the field shown
/// afterwards is the new one: the faces slide, so less friction moves the
/// stress next to the flaw by far more than 1%.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_friction_edit_re_solves_on_the_kept_discretisation() {
    let mut h = solved_default();
    h.run_steps(20);
    let before = h.state().shown_stresses();
    let (old_version, samples) = h.state().shown_field().expect("a field shown");
    edit_scene(&mut h, |s| s.cracks[0].friction = 0.2);
    // the frame that applies the edit: a new build would leave its cracked
    // elements to integrate in the solve's first slices
    h.step();
    assert_eq!(h.state().points_to_integrate(), Some(0));
    // until the new solve's field shows whole, at the resolution shown
    // before the edit (a coarser sampling comes first)
    run_until(&mut h, 4000, |app| {
        app.is_solved()
            && app
                .shown_field()
                .is_some_and(|(version, n)| version != old_version && n == samples)
    });
    assert!(h.state().is_solved());
    let after = h.state().shown_stresses();
    assert_eq!(before.len(), after.len());
    let largest = |v: &[[f64; 3]]| v.iter().flatten().fold(0.0_f64, |m, s| m.max(s.abs()));
    let change = before
        .iter()
        .zip(&after)
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
        .fold(0.0_f64, f64::max);
    assert!(
        change > 0.01 * largest(&before),
        "largest change {change} Pa of {} Pa",
        largest(&before)
    );
}

/// A load ramp that stays below every tip's criterion ends `completed`
/// with no tip grown: the Angles tab says that (not "no growth steps
/// yet"), and the outcome says on hover what `completed` means for a
/// load-stepped run and how near an edge the nearest free tip is.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_load_ramp_below_the_criterion_says_no_tip_grew() {
    let mut h = solved_default();
    edit_scene(&mut h, |s| {
        s.growth.control = cdca::scene::GrowthControl::Load;
        s.growth.load_steps = 3;
        // a hundredth of the default load: far below first growth (λ_cr ≈ 0.7)
        s.boundary.top = cdca::scene::SideBc::Traction {
            normal: -1e6,
            shear: 0.0,
        };
    });
    h.run_steps(5);
    h.get_by_label("Angles").click();
    h.get_by_label("Run growth").click();
    h.run_steps(2);
    run_until_paused(&mut h, 2000);
    h.run_steps(3);
    assert_eq!(
        h.state().growth_outcome(),
        Some(cdca::report::Outcome::Completed)
    );
    assert_eq!(h.state().growth_history().len(), 3);
    h.get_by_label(
        "No tip has grown in 3 growth steps: every tip stayed below its criterion (the tip inspector shows how far).",
    );
    h.get_by_label("completed").hover();
    h.run_steps(60);
    // and how far the free tip nearest an edge stopped from it (the flaw's
    // ends are 15 − 3 cos 45° = 12.87 mm from two edges each; h = 0.5 mm)
    h.get_by_label_contains(
        "All 3 load steps applied (growth.load_steps). The free tip nearest a boundary is 12.87 mm (25.7 elements) from the ",
    );
}

/// The Study tab offers only the parameters the scene has: on the default
/// scene (right side free) no lateral traction, but the flaw's friction
/// and the top traction; after the right side becomes a traction side, its
/// normal too.
#[test]
fn the_study_tab_offers_only_the_scenes_own_parameters() {
    let mut h = harness(no_solver());
    h.run();
    h.get_by_label("Study").click();
    h.run();
    let open_choices = |h: &mut Harness<'_, WorkbenchApp>| {
        h.get_all_by_label("Parameter")
            .next()
            .expect("the parameter choice")
            .click();
        h.run();
    };
    open_choices(&mut h);
    assert!(h.query_by_label("boundary.top.normal").is_some());
    // a crack's path says which panel crack it is (1-based, as the panel)
    assert!(h.query_by_label("cracks.0.cohesion (crack 1)").is_some());
    assert!(h.query_by_label("boundary.right.normal").is_none());
    h.key_press(egui::Key::Escape);
    h.run();
    edit_scene(&mut h, |s| {
        s.boundary.right = cdca::scene::SideBc::Traction {
            normal: -20e6,
            shear: 0.0,
        };
    });
    h.run();
    open_choices(&mut h);
    assert!(h.query_by_label("boundary.right.normal").is_some());
}

/// The CLI and the workbench write the same CSV tables for the same run:
/// Run growth on the default scene to its end, then File ▸ Export's crack
/// paths and growth history (`WorkbenchApp::table_csv`) against the files
/// `cdca grow SCENE --csv DIR` writes for that scene, byte for byte (both
/// go through `cdca::csv`; neither table holds a wall time).
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_workbench_and_the_cli_write_byte_identical_csv() {
    use cdca_workbench::state::command::Export;
    // the `cdca` binary beside this test's directory (target/release)
    let exe = std::env::current_exe().expect("the test binary");
    let cli = exe
        .ancestors()
        .nth(2)
        .expect("target/<profile>")
        .join("cdca");
    assert!(
        cli.exists(),
        "{} is missing: build it with cargo build --release -p cdca-cli (scripts/test.sh does)",
        cli.display()
    );
    let h = grown_default();
    let app = h.state();
    let dir = std::env::temp_dir().join(format!("cdca_ui_csv_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let scene = dir.join("scene.json");
    std::fs::write(&scene, serde_json::to_string(app.scene()).expect("JSON")).expect("written");
    let out = std::process::Command::new(&cli)
        .args(["grow", &scene.to_string_lossy(), "--csv"])
        .arg(&dir)
        .output()
        .expect("cdca runs");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for (file, what) in [
        ("history.csv", Export::History),
        ("cracks.csv", Export::CrackPaths),
    ] {
        let cli_text = std::fs::read_to_string(dir.join(file)).expect("the CLI's CSV");
        let app_text = app.table_csv(what).expect("a table export");
        assert!(cli_text.lines().count() > 2, "{file}: {cli_text}");
        assert!(
            cli_text == app_text,
            "{file} differs:\nCLI:\n{cli_text}\napp:\n{app_text}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every shape the canvas and panels painted in the last frame, nested
/// lists flattened.
fn painted(h: &Harness<'_, WorkbenchApp>) -> Vec<egui::Shape> {
    fn flatten(shape: &egui::Shape, out: &mut Vec<egui::Shape>) {
        match shape {
            egui::Shape::Vec(shapes) => shapes.iter().for_each(|s| flatten(s, out)),
            s => out.push(s.clone()),
        }
    }
    let mut out = Vec::new();
    for clipped in &h.output().shapes {
        flatten(&clipped.shape, &mut out);
    }
    out
}

/// The texts painted in the last frame (the canvas's key among them).
fn painted_texts(h: &Harness<'_, WorkbenchApp>) -> Vec<String> {
    painted(h)
        .iter()
        .filter_map(|s| match s {
            egui::Shape::Text(t) => Some(t.galley.text().to_owned()),
            _ => None,
        })
        .collect()
}

/// Polylines painted in the last frame in `colour` (cracks are polylines).
fn polylines_in(h: &Harness<'_, WorkbenchApp>, colour: egui::Color32) -> usize {
    painted(h)
        .iter()
        .filter(|s| {
            matches!(s, egui::Shape::Path(p)
                if p.stroke.color == egui::epaint::ColorMode::Solid(colour))
        })
        .count()
}

/// The workbench without the solver on opening, with `text` opened as
/// `source` (a file's name) and nothing solved.
fn opened_unsolved(source: &str, text: String) -> Harness<'static, WorkbenchApp> {
    let mut h = harness(no_solver());
    h.run();
    h.state_mut().push(Command::OpenSceneText {
        source: source.to_owned(),
        text,
    });
    h.run();
    h
}

/// Solves the scene just opened (asked for: whether an open solves by
/// itself depends on how long the last solve took) and runs frames until
/// it is solved (at most 2000).
fn solve_opened(h: &mut Harness<'_, WorkbenchApp>) {
    h.state_mut().push(Command::Solve);
    for _ in 0..2000 {
        if h.state().is_solved() || h.state().message().is_some() {
            break;
        }
        h.step();
    }
    h.run_steps(3);
}

/// A square loop of two cracks, each bent 90° and ending on the other, in
/// the 0.3 m plate under biaxial compression (`closed_crack_biaxial.json`)
/// on a 20 × 20 mesh: every crack end meets the other crack, so no tip is
/// free. Its faces close (26 stick, 4 slip, 2 open points), the fragment
/// inside is held by them, and the 90° corners are sharp kinks.
fn crack_loop() -> cdca::scene::SceneFile {
    let mut s = cdca::scene::SceneFile::from_json(include_str!(
        "../assets/scenes/closed_crack_biaxial.json"
    ))
    .expect("a bundled scene");
    (s.mesh.nx, s.mesh.ny) = (20, 20);
    let flaw = s.cracks[0].clone();
    s.cracks = [
        [[0.1, 0.1], [0.2, 0.1], [0.2, 0.2]],
        [[0.2, 0.2], [0.1, 0.2], [0.1, 0.1]],
    ]
    .map(|p| cdca::scene::CrackSpec {
        points: Some(p.to_vec()),
        ..flaw.clone()
    })
    .to_vec();
    s
}

/// [`crack_loop`] in a rock of 30° internal friction (with the bundled
/// 49°, the secondary cracks' envelope, the corners never start one) grown
/// headless until secondary cracks start (at both corners, at the second
/// load step), as File ▸ Save writes it: the grown cracks and
/// `growth.resume`, whose lineage says which are secondary. Returns the
/// file and that lineage's verdict per crack.
fn loop_with_secondary_cracks() -> (String, Vec<bool>) {
    let mut file = crack_loop();
    file.material.friction_angle_deg = 30.0;
    let scene = cdca::scene::Scene::try_from(file).expect("a valid scene");
    let mut sim = cdca::Simulation::new(scene).expect("a simulation");
    while !sim.lineage().iter().any(cdca::scene::Lineage::is_secondary) {
        assert!(
            sim.growth_finished().is_none(),
            "no secondary crack started"
        );
        sim.grow_step().expect("a growth step");
    }
    let secondary = sim
        .lineage()
        .iter()
        .map(cdca::scene::Lineage::is_secondary)
        .collect();
    (sim.scene().to_json().expect("JSON"), secondary)
}

/// The canvas key's secondary-crack row follows the scene's cracks, not
/// the tip markers: a saved run with secondary cracks, reopened and not
/// solved (no tips), draws them purple and shows the row; the same cracks
/// without the saved lineage (all drawn flaws) show neither; nor does the
/// default scene.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_key_names_secondary_cracks_exactly_when_the_scene_has_one() {
    let (saved, secondary) = loop_with_secondary_cracks();
    let count = secondary.iter().filter(|&&s| s).count();
    assert!(count > 0, "{secondary:?}");
    let purple = cdca_workbench::app::SECONDARY_COLOR;
    let key = cdca_workbench::app::SECONDARY_KEY;
    let mut h = harness(no_solver());
    h.run();
    assert!(!painted_texts(&h).iter().any(|t| t == key));
    assert_eq!(polylines_in(&h, purple), 0);
    h.state_mut().push(Command::OpenSceneText {
        source: "loop_grown.json".to_owned(),
        text: saved,
    });
    h.run();
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    assert!(!h.state().is_solved() && h.state().tips().is_empty());
    let texts = painted_texts(&h);
    assert!(texts.iter().any(|t| t == key), "the key row: {texts:?}");
    assert!(
        !texts.iter().any(|t| t == "tip grows in tension"),
        "no tip rows without tip markers: {texts:?}"
    );
    assert_eq!(
        polylines_in(&h, purple),
        count,
        "each secondary crack purple"
    );
    edit_scene(&mut h, |s| s.growth.resume = None);
    h.run();
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    assert!(!painted_texts(&h).iter().any(|t| t == key));
    assert_eq!(polylines_in(&h, purple), 0);
}

/// The contact dots on a secondary crack are ringed in its purple (closed,
/// its dots lay close together over the purple line and hid it), and
/// those on the flaws are not.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn contact_dots_on_secondary_cracks_are_ringed_in_purple() {
    let (saved, secondary) = loop_with_secondary_cracks();
    let mut h = opened_unsolved("loop_grown.json", saved);
    solve_opened(&mut h);
    let app = h.state();
    assert!(app.is_solved(), "{:?}", app.message());
    let points = app.contact_points();
    let on_secondary = |c: &cdca::ContactPointView| secondary[c.crack];
    assert!(
        points
            .iter()
            .any(|c| on_secondary(c) && c.state != cdca::ContactState::Open),
        "a closed secondary crack"
    );
    assert!(points.iter().any(|c| !on_secondary(c)), "dots on the flaws");
    assert_purple_rings(&h, on_secondary);
}

/// Asserts that each contact point's dot is ringed in the secondary
/// cracks' purple exactly when `on_secondary` says it lies on one.
fn assert_purple_rings(
    h: &Harness<'_, WorkbenchApp>,
    on_secondary: impl Fn(&cdca::ContactPointView) -> bool,
) {
    let purple = cdca_workbench::app::SECONDARY_COLOR;
    let app = h.state();
    let circles: Vec<egui::epaint::CircleShape> = painted(h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Circle(c) => Some(c),
            _ => None,
        })
        .collect();
    for c in app.contact_points() {
        let at = app.screen_from_world([c.x, c.y]);
        let ringed = circles
            .iter()
            .filter(|d| d.center.distance(at) < 1e-3)
            .map(|d| d.stroke.width > 0.0 && d.stroke.color == purple)
            .collect::<Vec<_>>();
        assert!(
            ringed.contains(&on_secondary(c)),
            "the dot at ({}, {}) on crack {}: purple rings {ringed:?}",
            c.x,
            c.y,
            c.crack
        );
    }
}

/// A flaw's end that grew first in shear is a secondary crack (the
/// lineage's part, as the growth report names it): the canvas draws that
/// segment purple and the flaw and the wing at its other end black,
/// before a solve and after one, and rings in purple exactly the contact
/// dots on that segment.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_flaw_end_grown_in_shear_is_drawn_as_a_secondary_crack() {
    use cdca::scene::{Lineage, Part, Resume};
    let purple = cdca_workbench::app::SECONDARY_COLOR;
    let mut scene = harness(no_solver()).state().scene().clone();
    let flaw = scene.cracks[0].points.clone().expect("a polyline flaw");
    let (a, b) = (flaw[0], flaw[flaw.len() - 1]);
    // 1.2 mm on along the flaw at its first end (shear), a wing at 70° at
    // its second
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    let along = [a[0] - 1.2e-3 * dx / len, a[1] - 1.2e-3 * dy / len];
    let turn = 70f64.to_radians();
    let wing = [
        b[0] + 1.2e-3 * (dx * turn.cos() - dy * turn.sin()) / len,
        b[1] + 1.2e-3 * (dx * turn.sin() + dy * turn.cos()) / len,
    ];
    let points: Vec<[f64; 2]> = std::iter::once(along)
        .chain(flaw.iter().copied())
        .chain(std::iter::once(wing))
        .collect();
    scene.cracks[0].points = Some(points.clone());
    // a saved run carries its faces' states: all open here
    let faces = cdca::Simulation::new(cdca::scene::Scene::try_from(scene.clone()).expect("valid"))
        .expect("a simulation")
        .contact_points()
        .len();
    scene.growth.resume = Some(Resume {
        steps: 2,
        load_factor: 1.0,
        increment: 1,
        growths_here: 0,
        faces: vec![[0.0; 6]; faces],
        grown: Vec::new(),
        lineage: vec![Lineage {
            flaw: 0,
            front: 1,
            drawn: flaw.len(),
            ends: [Part::Secondary, Part::Wing],
        }],
        rock_starts: None,
        history: Vec::new(),
    });
    let mut h = opened_unsolved("sheared_end.json", scene.to_json().expect("JSON"));
    assert!(h.state().message().is_none(), "{:?}", h.state().message());
    let purple_paths = |h: &Harness<'_, WorkbenchApp>| -> Vec<Vec<Pos2>> {
        painted(h)
            .into_iter()
            .filter_map(|s| match s {
                egui::Shape::Path(p)
                    if p.stroke.color == egui::epaint::ColorMode::Solid(purple) =>
                {
                    Some(p.points)
                }
                _ => None,
            })
            .collect()
    };
    let secondary_segment = |h: &Harness<'_, WorkbenchApp>| {
        vec![
            h.state().screen_from_world(points[0]),
            h.state().screen_from_world(points[1]),
        ]
    };
    for solved in [false, true] {
        if solved {
            solve_opened(&mut h);
            assert!(h.state().is_solved(), "{:?}", h.state().message());
        }
        assert_eq!(
            purple_paths(&h),
            vec![secondary_segment(&h)],
            "solved {solved}: the sheared end alone purple"
        );
    }
    // the dots: ringed exactly on the sheared end's segment
    let app = h.state();
    let on_end = |c: &cdca::ContactPointView| {
        let (p, q) = (points[0], points[1]);
        let d = [q[0] - p[0], q[1] - p[1]];
        let t = ((c.x - p[0]) * d[0] + (c.y - p[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]);
        let off = (c.x - p[0] - t * d[0]).hypot(c.y - p[1] - t * d[1]);
        (0.0..=1.0).contains(&t) && off < 1e-9
    };
    let points_here = app.contact_points();
    assert!(points_here.iter().any(on_end), "dots on the sheared end");
    assert!(points_here.iter().any(|c| !on_end(c)), "dots on the flaw");
    assert_purple_rings(&h, on_end);
}

/// A solved scene whose every crack end meets another crack has no tip to
/// inspect, and the inspector says why.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_tip_inspector_says_when_no_crack_end_is_free() {
    let mut h = opened_unsolved("loop.json", crack_loop().to_json().expect("JSON"));
    solve_opened(&mut h);
    let app = h.state();
    assert!(app.message().is_none(), "{:?}", app.message());
    assert!(app.is_solved() && !app.specimen_split());
    assert_eq!(app.scene().cracks.len(), 2);
    assert!(app.tips().is_empty());
    h.get_by_label("No free tip: every crack end meets a boundary or another crack.");
}
