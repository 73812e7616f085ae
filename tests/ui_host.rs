//! The run protocol (issue 63): the simulation's host answers the same on
//! a thread of its own as in-process, and the UI's thread, whose host
//! works elsewhere, makes no call of the host (no solver work) through a
//! whole run. They drive the solver: run them with `--release`.

use cdca_workbench::{Options, RunMode, WorkbenchApp, host_calls_on_this_thread};
use egui_kittest::Harness;

#[path = "support/harness.rs"]
mod support;
use support::{grow, harness, open_bundled};

/// Opens the stepped pair, runs growth to its end, and returns each step's
/// load factor.
fn grown(h: &mut Harness<'_, WorkbenchApp>) -> Vec<f64> {
    h.run_steps(2);
    open_bundled(h, "specimen_two_flaws_stepped.json");
    grow(h, "Run growth");
    assert_eq!(h.state().run_mode(), RunMode::Paused);
    h.state()
        .growth_history()
        .iter()
        .map(|s| s.load_factor)
        .collect()
}

/// The stepped pair's Run growth with the host on its own thread and
/// in-process: the same steps at the same λ (to 1e-12, the bits of the
/// same run sliced differently), and no host call on the UI's thread
/// when the host has a thread, from the first frame to the run's end.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_host_thread_grows_what_the_frames_grow_and_the_ui_thread_solves_nothing() {
    let calls = host_calls_on_this_thread();
    let mut away = harness(Options {
        host_thread: true,
        ..Options::default()
    });
    let on_thread = grown(&mut away);
    assert_eq!(
        host_calls_on_this_thread(),
        calls,
        "the UI thread made no call of the host"
    );
    let mut frames = harness(Options::default());
    let in_process = grown(&mut frames);
    assert!(
        host_calls_on_this_thread() > calls,
        "in-process, the frames call the host (the count counts)"
    );
    assert!(on_thread.len() > 5, "{} steps", on_thread.len());
    assert_eq!(on_thread.len(), in_process.len(), "the same steps");
    for (step, (a, b)) in on_thread.iter().zip(&in_process).enumerate() {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs(),
            "step {step}: λ {a} and {b}"
        );
    }
}

/// Export fields asks the host and saves its answer when it comes: on the
/// host thread the VTU file is the in-process one, byte for byte (the same
/// solve of the default scene), with the mesh's points and cells.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn export_fields_comes_from_the_host_as_in_process() {
    use cdca_workbench::state::command::{Command, Export};
    let dir = std::env::temp_dir().join(format!("cdca_ui_host_vtu_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let mut files = Vec::new();
    for host_thread in [true, false] {
        let mut h = harness(Options {
            host_thread,
            file_dialogs: false,
            ..Options::default()
        });
        h.run_steps(2);
        support::run_until_paused(&mut h, 5000);
        assert!(h.state().is_solved(), "the default scene is solved");
        h.state_mut().push(Command::Export(Export::Fields));
        let mut frames = 0;
        while h.state().typed_path().is_none() && frames < 500 {
            h.step();
            frames += 1;
        }
        let offered = h.state().typed_path().unwrap_or_default().to_owned();
        assert!(
            std::path::Path::new(&offered)
                .extension()
                .is_some_and(|e| e == "vtu"),
            "the path offered: {offered:?}"
        );
        let path = dir.join(format!("fields_{host_thread}.vtu"));
        h.state_mut().set_typed_path(&path.display().to_string());
        h.state_mut().push(Command::UseTypedPath);
        h.step();
        files.push(std::fs::read_to_string(&path).expect("the fields were written"));
    }
    let _ = std::fs::remove_dir_all(&dir);
    let scene = cdca_workbench::files::scenes::default_scene();
    let (nx, ny) = (scene.mesh.nx, scene.mesh.ny);
    assert!(
        files[0].contains(&format!(
            "NumberOfPoints=\"{}\" NumberOfCells=\"{}\"",
            (nx + 1) * (ny + 1),
            nx * ny
        )),
        "the mesh's points and cells"
    );
    assert!(
        files[0] == files[1],
        "the host thread's file is the in-process one"
    );
}
