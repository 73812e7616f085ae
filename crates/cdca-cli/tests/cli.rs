//! Runs the built `cdca` binary: exit codes, one-line messages that name the
//! problem, no panics on bad input (SPEC §11).

use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "../../cdca/tests/support/docs_row.rs"]
mod docs_row;

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
        "crack shorter than the mesh resolves",
        "[[0.1, 0.1], [0.2, 0.2]]",
        "[[0.1, 0.1], [0.15, 0.1]]",
        "cracks[0].points` = 0.04999999999999999 m: its ends are less than 2.5 element sizes (h = 0.03 m)",
    ),
    (
        "crack outside",
        "[0.2, 0.2]]",
        "[0.4, 0.2]]",
        "cracks[0].points[1]",
    ),
    (
        "crack from edge to edge",
        "[[0.1, 0.1], [0.2, 0.2]]",
        "[[0.0, 0.1], [0.3, 0.2]]",
        "cracks[0]` = from [0, 0.1] to [0.3, 0.2]: this crack runs from the boundary back",
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
    // Magnitudes the arithmetic cannot carry: each of these used to run,
    // to a non-finite solution (exit 1) or a report with a NaN angle
    // (exit 0).
    (
        "young far below any rock",
        r#""young": 4.78e9"#,
        r#""young": 1e-300"#,
        "`material.young` = 1e-300: is outside 1e-30 to 1e30",
    ),
    (
        "cohesion beyond any rock",
        r#""poisson": 0.25"#,
        r#""poisson": 0.25, "cohesion": 1e300"#,
        "`material.cohesion` = 1e300: is outside 1e-30 to 1e30",
    ),
    (
        "traction above E",
        r#""normal": -10e6"#,
        r#""normal": -5e9"#,
        "`boundary.top.normal` = -5000000000: is not below Young's modulus",
    ),
    (
        "joint stiffer than round-off allows",
        r#""normal_stiffness": 200e9"#,
        r#""normal_stiffness": 1e29"#,
        "`cracks[0].normal_stiffness` = 1e29: k h/E = 6.276e17",
    ),
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

/// Issue 62: the bundled coplanar pair in a rock of 1 Pa cohesion (and
/// 0.5 Pa, 1e-12 Pa) on 50 × 50 was valid, and its growth aborted the
/// process (allocating 1.6e16 bytes for the intact rock's site stencil,
/// exit 134) or panicked ("capacity overflow", exit 101): its process
/// zone r_p = (K_IC/σ_t)²/2π is 3.0e11 m. Now validate, solve and grow
/// refuse it before any work, naming the cohesion, σ_t and r_p.
#[test]
fn a_rock_whose_process_zone_outgrows_the_specimen_is_refused() {
    let dir = temp_dir("tiny-cohesion");
    let text = std::fs::read_to_string(scenes_dir().join("specimen_two_flaws_coplanar.json"))
        .expect("bundled pair");
    for (cohesion, written, r_p) in [
        (1.0, "1", "3.020e11 m"),
        (0.5, "0.5", "1.208e12 m"),
        (1e-12, "1e-12", "3.020e35 m"),
    ] {
        let mut scene: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        scene["material"]["cohesion"] = cohesion.into();
        scene["mesh"] = serde_json::json!({ "nx": 50, "ny": 50 });
        let path = dir.join("rock.json");
        std::fs::write(&path, scene.to_string()).expect("write scene");
        for command in ["validate", "solve", "grow"] {
            let run = cdca(&[command, path_str(&path)]);
            let what = format!("{command}, cohesion {cohesion} Pa");
            assert_rejected(&run, 2, &format!("`material.cohesion` = {written}:"), &what);
            assert!(
                run.stderr
                    .contains(&format!("r_p = (K_IC/σ_t)²/2π = {r_p}")),
                "{what}: {}",
                run.stderr
            );
            assert!(
                run.stderr.contains("shorter side 0.03 m"),
                "{what}: {}",
                run.stderr
            );
        }
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

/// `cdca solve` notes on stderr when the rock away from the cracks is past
/// its strength: the default scene at twice its reference load (100 MPa
/// against σ_c = 2c cos φ/(1 − sin φ) = 80.24 MPa, so u = 1.246 in the
/// far field; the median 1.2% above it, within 3%), and says nothing on
/// the default scene as bundled (50 MPa since issue 65: u = 0.623, a load
/// the rock carries) nor on the centre crack under 1 MPa tension.
#[test]
fn solve_notes_an_intact_rock_past_its_strength() {
    let bundled = scenes_dir().join("specimen_single_flaw.json");
    let carried = cdca(&["solve", path_str(&bundled)]);
    assert_eq!(carried.code, Some(0), "{}", carried.stderr);
    let report: serde_json::Value = serde_json::from_str(&carried.stdout).expect("stdout is JSON");
    let u = report["intact_rock"]["utilisation"].as_f64().expect("u");
    assert!((u / (50.0 / 80.2386) - 1.0).abs() < 0.03, "u {u}");
    assert!(!carried.stderr.contains("note"), "{}", carried.stderr);

    let dir = temp_dir("past_strength");
    let mut scene: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&bundled).expect("scene")).expect("JSON");
    scene["boundary"]["top"]["normal"] = serde_json::json!(-100e6);
    let path = dir.join("at_100_mpa.json");
    std::fs::write(&path, scene.to_string()).expect("write");
    let run = cdca(&["solve", path_str(&path)]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).expect("stdout is JSON");
    let u = report["intact_rock"]["utilisation"].as_f64().expect("u");
    assert!((u / (100.0 / 80.2386) - 1.0).abs() < 0.03, "u {u}");
    assert!(
        run.stderr
            .contains("cdca: note: at full load the rock away from the cracks"),
        "{}",
        run.stderr
    );
    let quiet = cdca(&[
        "solve",
        path_str(&scenes_dir().join("centre_crack_tension.json")),
    ]);
    assert!(!quiet.stderr.contains("note"), "{}", quiet.stderr);
}

#[test]
fn grow_prints_the_history_and_writes_matching_csv() {
    let dir = temp_dir("grow");
    let csv = dir.join("out");
    let path = scenes_dir().join("specimen_single_flaw.json");
    let run = cdca(&["grow", path_str(&path), "--csv", path_str(&csv)]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).expect("stdout is JSON");
    let outcome = report["outcome"].as_str().expect("outcome");
    assert!(["completed", "unstable", "through", "max_steps"].contains(&outcome));
    let steps = report["steps"].as_array().expect("steps");
    // one row per step and free tip (one for a step without a free tip)
    let rows: usize = steps
        .iter()
        .map(|s| s["tips"].as_array().map_or(0, Vec::len).max(1))
        .sum();
    let history = std::fs::read_to_string(csv.join("history.csv")).expect("history.csv");
    assert!(history.starts_with(&format!("{}\n", cdca::csv::GROWTH_HISTORY_HEADER)));
    // the rock away from the flaw carries about the far field, λ·50 MPa,
    // against σ_c = 2c cos φ/(1 − sin φ) = 80.24 MPa (c = 15 MPa, φ = 49°):
    // the median 1.2% above it at the first step, and up to 10.2% above as
    // the cracks take area from the load path (never below)
    for (k, s) in steps.iter().enumerate() {
        let lambda = s["load_factor"].as_f64().expect("λ");
        let u = s["intact_rock"]["utilisation"]
            .as_f64()
            .expect("utilisation");
        let excess = u / (lambda * 50e6 / 80.2386e6) - 1.0;
        let limit = if k == 0 { 0.02 } else { 0.12 };
        assert!(
            (-0.005..limit).contains(&excess),
            "step {}: u {u}, {excess:.4} above the far field",
            s["step"]
        );
    }
    // the intact rock fails (the scene's growth.intact_rock = "nucleate"):
    // the specimen's strength is below the uncracked rock's, and stderr
    // says so
    let ratio = report["strength"]["ratio"]
        .as_f64()
        .expect("a strength ratio");
    assert!(ratio > 0.5 && ratio < 1.0, "strength / intact = {ratio}");
    assert!(
        run.stderr.contains("cdca: note: specimen strength ")
            && run.stderr.contains("of the intact rock's"),
        "{}",
        run.stderr
    );
    assert_eq!(history.lines().count(), 1 + rows);
    // the grew column marks every grown tip once
    let grown: usize = steps
        .iter()
        .map(|s| s["grown"].as_array().map_or(0, Vec::len))
        .sum();
    let marked = history
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(11) == Some("1"))
        .count();
    assert_eq!(marked, grown);
    let cracks = report["cracks"].as_array().expect("cracks");
    let vertices: usize = cracks
        .iter()
        .map(|c| c.as_array().map_or(0, Vec::len))
        .sum();
    let paths = std::fs::read_to_string(csv.join("cracks.csv")).expect("cracks.csv");
    assert!(paths.starts_with("crack,vertex,x_m,y_m\n"));
    assert_eq!(paths.lines().count(), 1 + vertices);
}

/// The frictional scene of the exit-code tests: a closed 45° crack with
/// face friction 0.5 under 10 MPa compression and a 2 MPa confinement.
fn frictional_scene(solver: &str) -> String {
    BASE.replace(
        r#""boundary": { "top""#,
        &format!(
            r#""solver": {solver},
  "boundary": {{ "left": {{ "kind": "roller" }}, "bottom": {{ "kind": "roller" }},
                "right": {{ "kind": "traction", "normal": -2e6 }}, "top""#
        ),
    )
}

/// Writes `text` as a scene file and runs `cdca <command>` on it.
fn run_scene(tag: &str, command: &str, text: &str) -> (Run, serde_json::Value) {
    let dir = temp_dir(tag);
    let path = dir.join("scene.json");
    std::fs::write(&path, text).expect("scene written");
    let run = cdca(&[command, path_str(&path)]);
    assert!(!run.stderr.contains("panicked"), "{tag}: {}", run.stderr);
    let report = serde_json::from_str(&run.stdout)
        .unwrap_or_else(|e| panic!("{tag}: stdout is not JSON ({e}): {}", run.stdout));
    (run, report)
}

/// A capped contact iteration is not a trustworthy answer: `cdca solve`
/// prints the report with `contact.converged: false` and exits 1 with one
/// line naming the contact iteration (SPEC §11 "Exit status"). With the
/// default cap the same scene converges and exits 0.
#[test]
fn solve_exits_1_when_the_contact_iteration_is_capped() {
    let (run, report) = run_scene(
        "contact-capped",
        "solve",
        &frictional_scene(r#"{ "max_contact_iterations": 1 }"#),
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert_eq!(report["contact"]["converged"], false);
    assert_eq!(report["contact"]["iterations"], 1);
    assert_eq!(report["solver"]["converged"], true);
    assert_eq!(report["contact"]["capped"], true);
    // the test that failed, by count: points left out of their Coulomb state
    let unsettled = report["contact"]["unsettled"].as_u64().unwrap_or(0);
    assert!(unsettled > 0, "{}", report["contact"]);
    assert!(
        run.stderr.contains(&format!(
            "{unsettled} points not yet in their Coulomb state"
        )),
        "{}",
        run.stderr
    );
    assert_eq!(run.stderr.trim_end().lines().count(), 1, "{}", run.stderr);
    assert!(
        run.stderr.starts_with(
            "cdca: the contact iteration did not settle within 1 contact iterations \
             (solver.max_contact_iterations)"
        ),
        "{}",
        run.stderr
    );

    let (run, report) = run_scene("contact-free", "solve", &frictional_scene("{}"));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert_eq!(report["contact"]["converged"], true);
    assert!(report["contact"]["iterations"].as_u64() > Some(1));
    assert_eq!(report["contact"]["cycling"], 0);
    assert!(
        report["contact"].get("capped").is_none(),
        "written only when true"
    );
    assert!(
        report["contact"].get("unsettled").is_none(),
        "written only when not zero"
    );
}

/// The automaton stopped at `max_iterations` prints its report (the last
/// iterate, its iteration count and residual) and exits 1.
#[test]
fn solve_exits_1_with_the_report_when_the_automaton_is_capped() {
    let (run, report) = run_scene(
        "automaton-capped",
        "solve",
        &frictional_scene(r#"{ "kind": "automaton", "max_iterations": 25 }"#),
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert_eq!(report["solver"]["kind"], "automaton");
    assert_eq!(report["solver"]["converged"], false);
    assert_eq!(report["solver"]["iterations"], 25);
    let residual = report["solver"]["residual"].as_f64().expect("residual");
    assert!(
        residual.is_finite() && residual > 1e-10,
        "residual {residual}"
    );
    assert!(
        run.stderr
            .contains("the automaton solver stopped at 25 iterations with relative residual"),
        "{}",
        run.stderr
    );
}

/// Growth does not go on from an unconverged solve: the step is recorded
/// with `converged: false`, the outcome is `not_converged`, no tip grew,
/// and the exit code is 1 with the report printed.
#[test]
fn grow_stops_with_not_converged_and_exits_1() {
    let (run, report) = run_scene(
        "grow-capped",
        "grow",
        &frictional_scene(r#"{ "kind": "cg", "max_iterations": 3 }"#),
    );
    assert_eq!(run.code, Some(1), "{}", run.stderr);
    assert_eq!(report["outcome"], "not_converged");
    let steps = report["steps"].as_array().expect("steps");
    assert_eq!(steps.len(), 1, "growth went on after an unconverged step");
    assert_eq!(steps[0]["converged"], false);
    assert_eq!(steps[0]["grown"].as_array().map(Vec::len), Some(0));
    // the reason names the failed test: the linear solver's cap, not the
    // contact iteration's relative change
    let failure = steps[0]["failure"].as_str().expect("failure");
    assert!(failure.starts_with("the cg solver stopped at"), "{failure}");
    assert!(
        run.stderr.contains(&format!(
            "step 1 did not converge: {failure}; growth stopped"
        )),
        "{}",
        run.stderr
    );
}

/// Every step of a converged growth run says so, contact included.
#[test]
fn grow_records_the_status_of_every_step() {
    let path = scenes_dir().join("specimen_single_flaw.json");
    let run = cdca(&["grow", path_str(&path)]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let report: serde_json::Value = serde_json::from_str(&run.stdout).expect("stdout is JSON");
    let steps = report["steps"].as_array().expect("steps");
    assert!(!steps.is_empty());
    for s in steps {
        assert_eq!(s["converged"], true, "step {}", s["step"]);
        assert_eq!(s["contact"]["converged"], true, "step {}", s["step"]);
        assert!(s["contact"]["iterations"].as_u64() >= Some(1));
    }
}

/// `cdca sweep`: face friction 0.32 and 0.83 on the paper's plate (45°
/// closed crack, P_H/P_V = 0.2, coarsened to 40 × 40) prints one table row
/// and writes one CSV row per value; the low-friction crack initiates in
/// tension at a large angle (> 45°), the high-friction one at a smaller
/// angle or not at all (the paper's trend); a bad path is rejected (exit 2)
/// before any work.
/// The paper's plate (`plate_45_biaxial_k0.2_mu0.5.json`) on a 40 × 40
/// mesh, written to a fresh directory: (directory, scene path).
fn coarse_plate(name: &str) -> (PathBuf, PathBuf) {
    let dir = temp_dir(name);
    let text = std::fs::read_to_string(scenes_dir().join("plate_45_biaxial_k0.2_mu0.5.json"))
        .expect("scene")
        .replace("\"nx\": 120", "\"nx\": 40")
        .replace("\"ny\": 120", "\"ny\": 40");
    let scene = dir.join("plate.json");
    std::fs::write(&scene, text).expect("write");
    (dir, scene)
}

/// Regression: negative values (compressive loads) were taken for flags
/// (`unexpected argument '-1'`). Sweeping the lateral pressure of the
/// paper's plate (P_V = 150 MPa, P_H = 15, 30, 45 MPa: k = 0.1, 0.2, 0.3,
/// μ = 0.5, 40 × 40) turns tension into shear: the first value grows in
/// tension at more than 45° to the flaw, the last in shear within 35°, the
/// angles never rise, and λ_cr rises with the confinement.
#[test]
fn sweep_takes_negative_values_and_shows_the_confinement_transition() {
    let (_dir, scene) = coarse_plate("sweep_negative");
    let run = cdca(&[
        "sweep",
        path_str(&scene),
        "--param",
        "boundary.right.normal",
        "--values",
        "-15e6,-30e6,-45e6",
    ]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let rows: Vec<Vec<&str>> = run
        .stdout
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(rows.len(), 3, "{}", run.stdout);
    let angle = |r: &[&str]| r[1].parse::<f64>().expect("angle").abs();
    let lambda = |r: &[&str]| r[3].parse::<f64>().expect("lambda");
    assert_eq!(rows[0][2], "tension", "{}", run.stdout);
    assert!(angle(&rows[0]) > 45.0, "{}", run.stdout);
    assert_eq!(rows[2][2], "shear", "{}", run.stdout);
    assert!(angle(&rows[2]) < 35.0, "{}", run.stdout);
    for w in rows.windows(2) {
        assert!(angle(&w[1]) <= angle(&w[0]) + 1e-9, "{}", run.stdout);
        assert!(lambda(&w[1]) > lambda(&w[0]), "{}", run.stdout);
    }
    let steps: Vec<String> = rows
        .iter()
        .map(|r| format!("{:.1}° {}", angle(r), r[2]))
        .collect();
    docs_row::verification_row(
        "cli",
        "sweep_takes_negative_values_and_shows_the_confinement_transition",
        "the same confinement series through `cdca sweep` (negative values)",
        "40 × 40",
        &format!("{}; λ_cr rising", steps.join(", ")),
        "first tension > 45°, last shear < 35°, angles never rise",
    );
}

#[test]
fn sweep_prints_a_table_and_writes_csv() {
    let (dir, scene) = coarse_plate("sweep");
    let csv = dir.join("sweep.csv");
    let run = cdca(&[
        "sweep",
        path_str(&scene),
        "--param",
        "cracks.0.friction",
        "--values",
        "0.32,0.83",
        "--csv",
        path_str(&csv),
    ]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert_eq!(run.stdout.lines().count(), 3, "{}", run.stdout);
    let csv = std::fs::read_to_string(&csv).expect("csv");
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0],
        [
            "cracks.0.friction",
            "angle_deg",
            "mode",
            "lambda_cr",
            "k1",
            "k2",
            "converged"
        ]
    );
    assert_eq!(rows.len(), 3);
    let angle = |r: &[&str]| r[1].parse::<f64>().expect("angle").abs();
    assert_eq!(rows[1][2], "tension");
    assert!(angle(&rows[1]) > 45.0, "{csv}");
    assert!(angle(&rows[2]) < angle(&rows[1]), "{csv}");
    let bad = cdca(&[
        "sweep",
        path_str(&scene),
        "--param",
        "cracks.3.friction",
        "--values",
        "0.5",
    ]);
    assert_rejected(&bad, 2, "cracks.3.friction", "sweep with a bad path");
}
