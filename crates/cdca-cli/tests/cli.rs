//! Runs the built `cdca` binary: exit codes, one-line messages that name the
//! problem, no panics on bad input (SPEC §11).

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_cdca");

/// A small valid scene; the bad cases below edit one piece of it.
const BASE: &str = r#"{
  "name": "cli test",
  "specimen": { "width": 0.3, "height": 0.3, "thickness": 1.0 },
  "mesh": { "nx": 10, "ny": 10 },
  "material": { "young": 4.78e9, "poisson": 0.25 },
  "cracks": [
    { "points": [[0.1, 0.1], [0.2, 0.2]], "friction": 0.5,
      "normal_stiffness": 200e9, "shear_stiffness": 20e9 }
  ],
  "boundary": { "top": { "kind": "traction", "normal": -10e6, "shear": 0.0 } }
}"#;

/// (what, replace this in BASE, by this, stderr must contain).
const BAD: &[(&str, &str, &str, &str)] = &[
    (
        "negative width",
        r#""width": 0.3"#,
        r#""width": -0.3"#,
        "specimen.width",
    ),
    (
        "zero height",
        r#""height": 0.3"#,
        r#""height": 0"#,
        "specimen.height",
    ),
    (
        "zero thickness",
        r#""thickness": 1.0"#,
        r#""thickness": 0.0"#,
        "specimen.thickness",
    ),
    (
        "nu = 0.5",
        r#""poisson": 0.25"#,
        r#""poisson": 0.5"#,
        "material.poisson",
    ),
    (
        "nu above 0.5",
        r#""poisson": 0.25"#,
        r#""poisson": 0.7"#,
        "material.poisson",
    ),
    (
        "nu below -1",
        r#""poisson": 0.25"#,
        r#""poisson": -1.5"#,
        "material.poisson",
    ),
    (
        "zero young",
        r#""young": 4.78e9"#,
        r#""young": 0"#,
        "material.young",
    ),
    ("nx = 0", r#""nx": 10"#, r#""nx": 0"#, "mesh.nx"),
    ("ny = 0", r#""ny": 10"#, r#""ny": 0"#, "mesh.ny"),
    ("huge mesh", r#""nx": 10"#, r#""nx": 1000000"#, "mesh"),
    (
        "zero-length crack",
        "[[0.1, 0.1], [0.2, 0.2]]",
        "[[0.1, 0.1], [0.1, 0.1]]",
        "cracks[0].points",
    ),
    (
        "crack outside",
        "[0.2, 0.2]]",
        "[0.4, 0.2]]",
        "cracks[0].points[1]",
    ),
    (
        "normal stiffness 0",
        r#""normal_stiffness": 200e9"#,
        r#""normal_stiffness": 0"#,
        "cracks[0].normal_stiffness",
    ),
    (
        "shear stiffness < 0",
        r#""shear_stiffness": 20e9"#,
        r#""shear_stiffness": -1"#,
        "cracks[0].shear_stiffness",
    ),
    (
        "friction < 0",
        r#""friction": 0.5"#,
        r#""friction": -0.5"#,
        "cracks[0].friction",
    ),
    (
        "rigid-body motion",
        r#""boundary": {"#,
        r#""boundary": { "left": { "kind": "free" },"#,
        "boundary",
    ),
    (
        "unknown field",
        r#""material""#,
        r#""materail""#,
        "materail",
    ),
    ("unknown nested field", r#""young""#, r#""yong""#, "yong"),
    (
        "missing specimen",
        r#""specimen": { "width": 0.3, "height": 0.3, "thickness": 1.0 },"#,
        "",
        "specimen",
    ),
    ("wrong type", r#""nx": 10"#, r#""nx": -10"#, "line 4"),
];

/// Where each test writes its files: a fresh folder under the system's
/// temporary directory.
fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cdca-cli-tests-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn scenes_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenes"))
}

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn cdca(args: &[&str]) -> Run {
    let out = Command::new(BIN)
        .args(args)
        .output()
        .expect("the cdca binary runs");
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

fn path_str(p: &Path) -> &str {
    p.to_str().expect("UTF-8 temp path")
}

/// Asserts a failed run: exit code, one line `cdca: …` naming `needle`.
fn assert_rejected(run: &Run, code: i32, needle: &str, what: &str) {
    assert_eq!(
        run.code,
        Some(code),
        "{what}: exit code; stderr: {}",
        run.stderr
    );
    assert!(
        !run.stderr.contains("panicked"),
        "{what}: panicked: {}",
        run.stderr
    );
    assert!(run.stderr.starts_with("cdca: "), "{what}: {}", run.stderr);
    assert_eq!(
        run.stderr.trim_end().lines().count(),
        1,
        "{what}: not one line: {}",
        run.stderr
    );
    assert!(
        run.stderr.contains(needle),
        "{what}: `{needle}` not in: {}",
        run.stderr
    );
    assert!(run.stdout.is_empty(), "{what}: stdout: {}", run.stdout);
}

/// Every bad case, written to files: (what, path, stderr must contain).
fn bad_files(dir: &Path) -> Vec<(String, PathBuf, String)> {
    let mut files = Vec::new();
    for (k, (what, from, to, needle)) in BAD.iter().enumerate() {
        assert!(BASE.contains(from), "{what}: `{from}` is not in BASE");
        let path = dir.join(format!("bad{k}.json"));
        std::fs::write(&path, BASE.replacen(from, to, 1)).expect("write scene");
        files.push(((*what).to_owned(), path, (*needle).to_owned()));
    }
    for (what, text, needle) in [
        ("not JSON", "this is not a scene", "line 1 column"),
        ("empty file", "", "line 1 column 0"),
    ] {
        let path = dir.join(format!("{}.json", what.replace(' ', "_")));
        std::fs::write(&path, text).expect("write scene");
        files.push((what.to_owned(), path, needle.to_owned()));
    }
    let missing = dir.join("no_such_scene.json");
    files.push((
        "missing file".to_owned(),
        missing.clone(),
        path_str(&missing).to_owned(),
    ));
    files
}

#[test]
fn validate_accepts_every_bundled_scene_silently() {
    let mut count = 0;
    for entry in std::fs::read_dir(scenes_dir()).expect("assets/scenes") {
        let path = entry.expect("entry").path();
        let run = cdca(&["validate", path_str(&path)]);
        assert_eq!(run.code, Some(0), "{}: {}", path.display(), run.stderr);
        assert!(
            run.stdout.is_empty() && run.stderr.is_empty(),
            "{}",
            path.display()
        );
        count += 1;
    }
    assert!(count >= 10, "only {count} bundled scenes");
}

#[test]
fn the_base_scene_is_valid() {
    let dir = temp_dir("base");
    let path = dir.join("base.json");
    std::fs::write(&path, BASE).expect("write scene");
    let run = cdca(&["validate", path_str(&path)]);
    assert_eq!((run.code, run.stderr.as_str()), (Some(0), ""));
}

#[test]
fn bad_scenes_are_rejected_by_validate_solve_and_grow_alike() {
    let dir = temp_dir("bad");
    for (what, path, needle) in bad_files(&dir) {
        let validate = cdca(&["validate", path_str(&path)]);
        assert_rejected(&validate, 2, &needle, &what);
        // `solve` and `grow` stop at the same check, before any work.
        let solve = cdca(&["solve", path_str(&path)]);
        assert_rejected(&solve, 2, &needle, &what);
        assert_eq!(solve.stderr, validate.stderr, "{what}");
        let csv = dir.join("csv-out");
        let grow = cdca(&["grow", path_str(&path), "--csv", path_str(&csv)]);
        assert_eq!(grow.stderr, validate.stderr, "{what}");
        assert!(!csv.exists(), "{what}: grow wrote CSV for a bad scene");
    }
}

#[test]
fn messages_name_the_value_too() {
    let dir = temp_dir("value");
    let path = dir.join("nu.json");
    std::fs::write(
        &path,
        BASE.replacen(r#""poisson": 0.25"#, r#""poisson": 0.5"#, 1),
    )
    .expect("write");
    let run = cdca(&["validate", path_str(&path)]);
    assert!(
        run.stderr.contains("`material.poisson` = 0.5"),
        "{}",
        run.stderr
    );
    assert!(
        run.stderr.contains(path_str(&path)),
        "names the file: {}",
        run.stderr
    );
}

/// JSON has no NaN literal; an overflowing number is the nearest thing.
/// serde_json refuses it at parse time ("number out of range"), so the message
/// gives the position instead of the field.
#[test]
fn an_overflowing_number_is_rejected() {
    let dir = temp_dir("inf");
    let path = dir.join("inf.json");
    std::fs::write(&path, BASE.replacen("4.78e9", "1e999", 1)).expect("write");
    for command in ["validate", "solve"] {
        let run = cdca(&[command, path_str(&path)]);
        assert_ne!(run.code, Some(0));
        let named = run.stderr.contains("material.young") || run.stderr.contains("line 5");
        assert!(named, "neither field nor position: {}", run.stderr);
        assert_rejected(&run, 2, "cdca: ", command);
    }
}

#[test]
fn usage_errors_are_one_line_with_exit_code_2() {
    for (args, needle) in [
        (&[][..], "subcommand"),
        (&["frobnicate"][..], "frobnicate"),
        (&["validate"][..], "SCENE"),
        (&["solve", "a.json", "--bogus"][..], "--bogus"),
    ] {
        let run = cdca(args);
        assert_rejected(&run, 2, needle, &format!("{args:?}"));
    }
    let help = cdca(&["--help"]);
    assert_eq!(help.code, Some(0));
    assert!(help.stdout.contains("validate") && help.stdout.contains("grow"));
}

#[test]
fn solve_prints_the_report_of_spec_11() {
    let path = scenes_dir().join("centre_crack_tension.json");
    let run = cdca(&["solve", path_str(&path)]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).expect("stdout is JSON");
    for key in [
        "/dofs",
        "/enriched_dofs",
        "/solver/kind",
        "/solver/iterations",
        "/solver/residual",
    ] {
        assert!(report.pointer(key).is_some(), "{key} missing");
    }
    assert!(
        report
            .pointer("/contact/kn_h_over_e")
            .is_some_and(serde_json::Value::is_f64)
    );
    assert_eq!(report["solver"]["kind"], "direct");
    assert_eq!(report["solver"]["converged"], true);
    let dofs = report["dofs"].as_u64().expect("dofs");
    assert!(dofs > 2 * 81 * 241 - 10 && report["enriched_dofs"].as_u64() > Some(0));
    // Tada: K_I = σ√(πa)·F(a/b) = 0.726 MPa√m for a/b = 0.3 (infinite height).
    let tips = report["tips"].as_array().expect("tips");
    assert_eq!(tips.len(), 2);
    for tip in tips {
        let k1 = tip["k1"].as_f64().expect("k1");
        let k2 = tip["k2"].as_f64().expect("k2");
        assert!((k1 / 0.726e6 - 1.0).abs() < 0.1, "k1 = {k1}");
        assert!(k2.abs() < 0.02 * k1, "k2 = {k2}");
        assert!(tip["criterion"]["mode"].is_string());
    }
}

#[test]
fn grow_prints_the_history_and_writes_matching_csv() {
    let dir = temp_dir("grow");
    let csv = dir.join("out");
    let path = scenes_dir().join("closed_crack_biaxial.json");
    let run = cdca(&["grow", path_str(&path), "--csv", path_str(&csv)]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).expect("stdout is JSON");
    let outcome = report["outcome"].as_str().expect("outcome");
    assert!(["completed", "unstable", "through", "max_steps"].contains(&outcome));
    let steps = report["steps"].as_array().expect("steps");
    let grown: usize = steps
        .iter()
        .map(|s| s["grown"].as_array().map_or(0, Vec::len))
        .sum();
    let history = std::fs::read_to_string(csv.join("history.csv")).expect("history.csv");
    assert!(history.starts_with("step,load_factor,crack,tip,x,y,mode,angle_deg,k1,k2\n"));
    assert_eq!(history.lines().count(), 1 + grown);
    let cracks = report["cracks"].as_array().expect("cracks");
    let vertices: usize = cracks
        .iter()
        .map(|c| c.as_array().map_or(0, Vec::len))
        .sum();
    let paths = std::fs::read_to_string(csv.join("cracks.csv")).expect("cracks.csv");
    assert!(paths.starts_with("crack,point,x,y\n"));
    assert_eq!(paths.lines().count(), 1 + vertices);
}
