//! The workbench under egui_kittest (no display, no GPU), shared by the UI
//! tests: a harness at a window size, and the waits for a run to end.
#![allow(dead_code)] // each test file uses its own part

use cdca_workbench::state::command::Command;
use cdca_workbench::study::{Study, StudySetup};
use cdca_workbench::{Options, RunMode, WorkbenchApp};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

/// The default window, points.
pub const SIZE: [f32; 2] = [1400.0, 900.0];

/// The workbench with `options` in a `size` window; each frame runs the
/// app's logic, then its UI, as eframe does.
pub fn harness_sized(size: [f32; 2], options: Options) -> Harness<'static, WorkbenchApp> {
    Harness::builder()
        .with_size(size)
        .with_max_steps(400)
        .build_ui_state(
            |ui, app: &mut WorkbenchApp| {
                app.logic(ui.ctx());
                app.ui(ui);
            },
            WorkbenchApp::new(options),
        )
}

/// [`harness_sized`] at [`SIZE`].
pub fn harness(options: Options) -> Harness<'static, WorkbenchApp> {
    harness_sized(SIZE, options)
}

/// Options that solve nothing by themselves.
pub fn no_solver() -> Options {
    Options {
        solve_on_start: false,
        auto_solve: false,
        ..Options::default()
    }
}

/// Steps frames until the runner pauses (at most `frames`).
pub fn run_until_paused(h: &mut Harness<'_, WorkbenchApp>, frames: usize) {
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

/// Opens the bundled scene `file` (`assets/scenes/`) and waits for its
/// solve.
pub fn open_bundled(h: &mut Harness<'_, WorkbenchApp>, file: &str) {
    let i = cdca_workbench::files::scenes::BUNDLED
        .iter()
        .position(|b| b.file == file)
        .expect("bundled");
    h.state_mut().push(Command::OpenBundled(i));
    h.run_steps(2);
    run_until_paused(h, 5000);
}

/// Clicks `button` (Grow one step, Run growth) and waits for the run to end.
pub fn grow(h: &mut Harness<'_, WorkbenchApp>, button: &str) {
    h.get_by_label(button).click();
    h.run_steps(2);
    run_until_paused(h, 20_000);
    h.run_steps(2);
}

/// Runs a study of the first crack's friction, `count` values from `from`
/// to `to`, to its end.
pub fn run_study(h: &mut Harness<'_, WorkbenchApp>, from: f64, to: f64, count: usize) {
    h.state_mut().push(Command::RunStudy(StudySetup {
        path: "cracks.0.friction".to_owned(),
        from,
        to,
        count,
    }));
    for _ in 0..5000 {
        h.step();
        if h.state().study().is_some_and(Study::finished) {
            break;
        }
    }
    assert!(h.state().study().is_some_and(Study::finished));
    h.run_steps(3);
}
