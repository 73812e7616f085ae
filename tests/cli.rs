//! The command line of the workbench binary: bad arguments are reported
//! before any window opens (so these tests need no display).

use std::process::Command;

/// Runs the binary with `args`; returns (exit code, stderr).
fn run(args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_cdca-workbench"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot start the workbench binary: {e}"));
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_missing_scene_file_is_named_and_the_exit_code_is_2() {
    let (code, err) = run(&["/nonexistent/scene.json"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("cannot read /nonexistent/scene.json"), "{err}");
}

#[test]
fn an_invalid_scene_names_the_file_and_the_problem() {
    let path = std::env::temp_dir().join(format!("cdca_cli_bad_{}.json", std::process::id()));
    std::fs::write(&path, "{ \"specimen\": ").unwrap_or_else(|e| panic!("{e}"));
    let (code, err) = run(&[path.to_string_lossy().as_ref()]);
    let _ = std::fs::remove_file(&path);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("is not a valid scene"), "{err}");
}

#[test]
fn a_bad_run_mode_is_refused() {
    let (code, err) = run(&["--run", "fly"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("--run fly: expected relax, grow or compare"),
        "{err}"
    );
    let (code, err) = run(&["--run"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--run needs relax, grow or compare"), "{err}");
}

#[test]
fn help_prints_the_usage_and_succeeds() {
    let out = Command::new(env!("CARGO_BIN_EXE_cdca-workbench"))
        .arg("--help")
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("usage: cdca-workbench"));
}
