//! The field on screen is never wrong (issue 63): no frame shows a field
//! of zeros (a solve's start) or a direct solve's working vector (exact
//! only on the faces' DOFs: GPa stripes along the nested dissection's
//! separators). They drive the solver: run them with `--release`.

use cdca_workbench::{Command, Options, RunMode, WorkbenchApp};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

#[path = "support/harness.rs"]
mod support;
use support::{harness, open_bundled};

/// Frames until the run pauses (at most `frames`), each checked: every
/// frame with a field shows a field (`FieldScale::is_a_field`: its largest
/// |σ| at least 1e-6 of the load at its load factor, not the zeros of a
/// solve's start; its 99th percentile at most 10 times that load, not a
/// working vector's spikes). Returns the frames checked.
fn check_every_frame(h: &mut Harness<'_, WorkbenchApp>, frames: usize, what: &str) -> usize {
    let mut checked = 0;
    for frame in 0..frames {
        h.step();
        let app = h.state();
        if let Some(scale) = app.shown_field_scale() {
            assert!(scale.is_a_field(), "{what}, frame {frame}: {scale:?}");
            checked += 1;
        }
        if app.run_mode() == RunMode::Paused {
            break;
        }
    }
    assert_eq!(
        h.state().run_mode(),
        RunMode::Paused,
        "{what}: the run ends"
    );
    checked
}

/// Run growth on the stepped pair, with its direct solver on the host's
/// thread (native) and in frame slices (the host in-process), and with the
/// automaton (growth accelerated to multigrid-CG, whose iterates show
/// live) in frame slices: every frame's field is a real one.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn no_frame_of_a_run_shows_a_vanished_or_garbled_field() {
    use cdca::scene::SolverKind;
    for (thread, solver) in [
        (true, SolverKind::Direct),
        (false, SolverKind::Direct),
        (false, SolverKind::Automaton),
    ] {
        let mut h = harness(Options {
            host_thread: thread,
            ..Options::default()
        });
        h.run_steps(2);
        open_bundled(&mut h, "specimen_two_flaws_stepped.json");
        if solver == SolverKind::Direct {
            assert!(
                h.state().shown_field_scale().is_some(),
                "the solved field shows"
            );
        } else {
            let mut scene = h.state().scene().clone();
            scene.solver.kind = solver;
            h.state_mut().push(Command::SetScene {
                scene: Box::new(scene),
                ongoing: false,
            });
            h.run_steps(2);
        }
        h.get_by_label("Run growth").click();
        h.run_steps(2);
        assert_eq!(h.state().run_mode(), RunMode::Growing);
        let what = format!(
            "{solver:?}, {}",
            if thread {
                "host thread"
            } else {
                "frame slices"
            }
        );
        let checked = check_every_frame(&mut h, 40_000, &what);
        assert!(checked > 20, "{what}: {checked} frames checked");
    }
}
