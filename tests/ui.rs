//! UI tests of the workbench with egui_kittest: no display, no GPU. They
//! click by label and assert on the app's state.
//!
//! Tests marked `needs cdca::Simulation bodies` drive the solver; the others
//! run with solving switched off, so they exercise the UI, editing and undo
//! on their own.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use cdca_workbench::app::Message;
use cdca_workbench::{Command, Options, RunMode, WorkbenchApp};
use egui::{Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

const SIZE: [f32; 2] = [1400.0, 900.0];

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

fn no_solver() -> Options {
    Options {
        solve_on_start: false,
        auto_solve: false,
        ..Options::default()
    }
}

fn harness(options: Options) -> Harness<'static, WorkbenchApp> {
    Harness::builder()
        .with_size(SIZE)
        .with_max_steps(400)
        .build_ui_state(
            |ui, app: &mut WorkbenchApp| {
                app.logic(ui.ctx());
                app.ui(ui);
            },
            WorkbenchApp::new(options),
        )
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

fn drag(h: &mut Harness<'_, WorkbenchApp>, from: Pos2, to: Pos2) {
    h.event(Event::PointerMoved(from));
    h.event(Event::PointerButton {
        pos: from,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    for k in 1..=8 {
        h.event(Event::PointerMoved(from + (to - from) * (k as f32 / 8.0)));
    }
    h.event(Event::PointerButton {
        pos: to,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    h.run();
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
    assert_eq!((app.scene().mesh.nx, app.scene().mesh.ny), (40, 40));
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
    let a = h.state().screen_from_world([0.05, 0.25]);
    let b = h.state().screen_from_world([0.10, 0.27]);
    click_at(&mut h, a);
    click_at(&mut h, b);
    h.key_press(Key::Enter);
    h.run();
    let scene = h.state().scene();
    assert_eq!(scene.cracks.len(), 2, "the drawn crack was added");
    let points = scene.cracks[1].points.clone().unwrap_or_default();
    assert_eq!(points.len(), 2);
    for (p, q) in points.iter().zip([[0.05, 0.25], [0.10, 0.27]]) {
        assert!(
            (p[0] - q[0]).abs() < 1e-3 && (p[1] - q[1]).abs() < 1e-3,
            "{p:?} vs {q:?}"
        );
    }
    h.get_by_label("Cracks (2)");
}

#[test]
fn dragging_a_tip_moves_it_in_one_undo_step() {
    let mut h = harness(no_solver());
    h.run();
    let tip = h.state().scene().cracks[0]
        .points
        .clone()
        .unwrap_or_default()[1];
    let from = h.state().screen_from_world(tip);
    let to = h.state().screen_from_world([0.22, 0.16]);
    drag(&mut h, from, to);
    let moved = h.state().scene().cracks[0]
        .points
        .clone()
        .unwrap_or_default()[1];
    assert!(
        (moved[0] - 0.22).abs() < 1e-3 && (moved[1] - 0.16).abs() < 1e-3,
        "tip at {moved:?}"
    );
    h.get_by_label("Undo").click();
    h.run();
    let back = h.state().scene().cracks[0]
        .points
        .clone()
        .unwrap_or_default()[1];
    assert_eq!(
        back, tip,
        "one undo step returns the tip to where the drag started"
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
    let mut s = h.state().scene().clone();
    s.solver.kind = cdca::scene::SolverKind::Automaton;
    h.state_mut().push(Command::SetScene {
        scene: Box::new(s),
        ongoing: false,
    });
    h.run();
    assert!(h.query_by_label("Over-relaxation ω").is_some());
}

// --- with the solver -------------------------------------------------------

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
    let at = app.screen_from_world(tips[1]);
    click_at(&mut h, at);
    h.run_steps(3);
    assert_eq!(
        h.state().inspected_tip(),
        Some((1, true)),
        "tip 2 inspected, with its σ_θθ / τ_rθ curve"
    );
    h.get_by_label("K_I");
    h.get_by_label("Decision");
}

#[test]
fn step_grows_the_residual_history() {
    let mut h = harness(Options::default());
    h.run_steps(5);
    let mut s = h.state().scene().clone();
    s.solver.kind = cdca::scene::SolverKind::Automaton;
    h.state_mut().push(Command::SetScene {
        scene: Box::new(s),
        ongoing: false,
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
    assert!(before > 0.05, "solved on start: {before}");
    for _ in 0..10 {
        h.get_by_label("Grow one step").click();
        h.run_steps(3);
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
#[ignore = "a timing measurement, not a test to run on shared machines: growth runs in resumable chunks (measured on an idle 2-core machine: mean 20.8 ms, p95 25.2 ms, max 123 ms; the chunk that extends the tips and rebuilds the discretisation is the maximum); run with --release --include-ignored --nocapture"]
fn frame_time_during_run_growth() {
    let mut h = harness(Options::default());
    h.run_steps(10);
    h.get_by_label("Run growth").click();
    h.step();
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
    // Target 33 ms (30 Hz). Growth advances in chunks; the chunk that
    // extends the tips and rebuilds the discretisation is the longest.
    assert!(median < 0.033, "median frame time {:.1} ms", median * 1e3);
    assert!(max < 0.15, "max frame time {:.1} ms", max * 1e3);
}

fn polyline_length(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}
