//! `cdca study` (issue 55) against its references: each row equals the
//! row of `cdca grow` on the point's scene alone; four shards merged equal
//! the single run; a study killed halfway resumes to the same table; the
//! GNU parallel example of docs/studies.md runs; bad input exits 2 naming
//! the file and the field, and leaves the rows written. Rows are compared
//! "seconds aside": every byte but each row's last cell.
//!
//! Coarse meshes and capped steps keep the file's runs to seconds.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use cdca::report::GrowReport;
use cdca::study::row::without_seconds;
use cdca::study::{Row, Study};

const BIN: &str = env!("CARGO_BIN_EXE_cdca");

fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn scene(name: &str) -> String {
    let path = repo().join("assets/scenes").join(name);
    path.canonicalize()
        .expect("bundled scene")
        .to_string_lossy()
        .into_owned()
}

/// A fresh folder for one test.
fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cdca-study-tests-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn cdca(dir: &Path, args: &[&str]) -> Run {
    let out = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the cdca binary runs");
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Every line with its last cell (`seconds`) cut off.
fn untimed(table: &str) -> Vec<String> {
    table
        .lines()
        .map(|l| without_seconds(l).to_owned())
        .collect()
}

/// 20 pairs (zipped): every layout at four angles, 3.5 mm flaws, and
/// one pair of 20 mm flaws, too long for the specimen (invalid); 40 × 40,
/// at most 4 steps.
fn pairs_study(dir: &Path) -> PathBuf {
    let path = dir.join("pairs.json");
    let layouts = [
        "coplanar",
        "stepped",
        "overlapping",
        "overlapping_mirrored",
        "overlapping_across_the_load",
    ];
    let list = |f: &dyn Fn(usize) -> String| (0..20).map(f).collect::<Vec<_>>().join(", ");
    let text = format!(
        r#"{{
  "name": "coarse pairs",
  "scene": "{}",
  "set": {{ "mesh.nx": 40, "mesh.ny": 40, "growth.max_steps": 4 }},
  "flaws": {{ "friction": 0.4 }},
  "axes": [
    {{ "field": "flaws.layout", "values": [{}] }},
    {{ "field": "flaws.angle_deg", "values": [{}] }},
    {{ "field": "flaws.length", "values": [{}] }}
  ],
  "combine": "zip"
}}"#,
        scene("specimen_two_flaws_stepped.json"),
        list(&|k| format!("\"{}\"", layouts[k % 5])),
        list(&|k| (35 + 5 * (k / 5)).to_string()),
        list(&|k| if k == 7 { "0.02" } else { "0.0035" }.to_owned()),
    );
    std::fs::write(&path, text).expect("write study");
    path
}

/// Reference: `cdca grow` on each point's scene (`--point K`). 20 points
/// (5 layouts × 2 lengths × 2 angles, 40 × 40, 4 steps): the study's row
/// of each equals, seconds aside, the row made from `cdca grow`'s report
/// (`Row::of_report`, the function the study calls), and its outcome,
/// steps, peak λ and first link are those `cdca grow` printed, to the bit.
#[test]
fn twenty_rows_equal_cdca_grow_scene_by_scene() {
    let dir = temp_dir("grow");
    let study_path = pairs_study(&dir);
    let run = cdca(&dir, &["study", "pairs.json", "--jobs", "2"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let table = read(&dir.join("pairs.csv"));
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines.len(), 21, "{table}");
    let study = Study::parse(&read(&study_path), |p| {
        std::fs::read_to_string(p).map_err(|e| e.to_string())
    })
    .expect("valid study");
    assert_eq!(lines[0], study.header().trim_end());
    let parsed = cdca::study::Table::parse(&table).expect("a table");
    let mut invalid = 0;
    for (k, point) in study.points().iter().enumerate() {
        let id = point.id.to_string();
        let row = lines[k + 1];
        let printed = cdca(&dir, &["study", "pairs.json", "--point", &id]);
        let refused = |stderr: &str| {
            // refused: the study says invalid, with the same reason
            let reason = parsed.cell(k, "error");
            assert_eq!(parsed.cell(k, "outcome"), "invalid", "point {id}: {row}");
            assert!(
                !reason.is_empty() && stderr.contains(reason),
                "point {id}: `{reason}` not in {stderr}"
            );
        };
        if printed.code == Some(2) {
            refused(&printed.stderr);
            invalid += 1;
            continue;
        }
        assert_eq!(printed.code, Some(0), "{}", printed.stderr);
        let scene_file = dir.join(format!("p{id}.json"));
        std::fs::write(&scene_file, &printed.stdout).expect("write scene");
        let drawn =
            serde_json::from_str::<serde_json::Value>(&printed.stdout).expect("JSON")["cracks"]
                .as_array()
                .map_or(0, Vec::len);
        let grown = cdca(&dir, &["grow", scene_file.to_str().expect("UTF-8")]);
        if grown.code == Some(2) {
            refused(&grown.stderr);
            invalid += 1;
            continue;
        }
        let report: GrowReport = serde_json::from_str(&grown.stdout).expect("a grow report");
        let json: serde_json::Value = serde_json::from_str(&grown.stdout).expect("JSON");
        let reference = Row::of_report(point, &report, drawn).csv(study.short_hash());
        assert_eq!(
            without_seconds(row),
            without_seconds(&reference),
            "point {id}"
        );
        assert_eq!(
            parsed.cell(k, "outcome"),
            json["outcome"].as_str().expect("outcome")
        );
        assert_eq!(
            parsed.cell(k, "steps"),
            json["steps"].as_array().map_or(0, Vec::len).to_string()
        );
        assert_eq!(
            parsed.cell(k, "peak_load_factor"),
            json["strength"]["peak_load_factor"].to_string()
        );
        if let Some(c) = json.get("coalescence") {
            assert_eq!(parsed.cell(k, "link_step"), c["step"].to_string());
            assert_eq!(
                parsed.cell(k, "link_load_factor"),
                c["load_factor"].to_string()
            );
        }
    }
    assert_eq!(invalid, 1, "{table}");
}

/// A first-step study of 12 points: the single flaw over friction ×
/// angle of the load's side (30 × 30).
fn first_step_study(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    let text = format!(
        r#"{{
  "name": "first steps",
  "scene": "{}",
  "set": {{ "mesh.nx": 30, "mesh.ny": 30 }},
  "axes": [
    {{ "field": "cracks.0.friction", "range": {{ "from": 0.0, "to": 0.6, "count": 4 }} }},
    {{ "field": "boundary.top.normal", "values": [-5e7, -1e8, -2e8] }}
  ],
  "run": "first_step"
}}"#,
        scene("specimen_single_flaw.json")
    );
    std::fs::write(&path, text).expect("write study");
    path
}

/// Reference: the single run's table. Four shards (`--shard i/4`), each
/// writing its own table, merged (`--merge`) equal it byte for byte,
/// seconds aside; a shard's table holds every fourth point.
#[test]
fn four_shards_merged_equal_the_single_run() {
    let dir = temp_dir("shards");
    first_step_study(&dir, "s.json");
    let single = cdca(&dir, &["study", "s.json", "--jobs", "1"]);
    assert_eq!(single.code, Some(0), "{}", single.stderr);
    for i in 1..=4 {
        let shard = format!("{i}/4");
        let run = cdca(&dir, &["study", "s.json", "--shard", &shard, "--jobs", "1"]);
        assert_eq!(run.code, Some(0), "{}", run.stderr);
        let part = read(&dir.join(format!("s.shard-{i}-of-4.csv")));
        let ids: Vec<&str> = part
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap_or_default())
            .collect();
        let want: Vec<String> = (i..=12).step_by(4).map(|k| k.to_string()).collect();
        assert_eq!(ids, want, "shard {i}");
    }
    let merged = cdca(
        &dir,
        &[
            "study",
            "s.json",
            "--merge",
            "s.shard-3-of-4.csv",
            "s.shard-1-of-4.csv",
            "s.shard-4-of-4.csv",
            "s.shard-2-of-4.csv",
            "--out",
            "merged.csv",
        ],
    );
    assert_eq!(merged.code, Some(0), "{}", merged.stderr);
    let (one, joined) = (read(&dir.join("s.csv")), read(&dir.join("merged.csv")));
    assert_eq!(one.lines().count(), 13);
    assert_eq!(untimed(&joined), untimed(&one));
    assert_eq!(
        joined.len()
            - joined
                .lines()
                .map(|l| without_seconds(l).len())
                .sum::<usize>(),
        one.len() - one.lines().map(|l| without_seconds(l).len()).sum::<usize>(),
        "the seconds' cells have the same widths"
    );
    // a missing shard is named, and nothing is written
    let short = cdca(
        &dir,
        &[
            "study",
            "s.json",
            "--merge",
            "s.shard-1-of-4.csv",
            "--out",
            "short.csv",
        ],
    );
    assert_eq!(short.code, Some(2));
    assert!(
        short
            .stderr
            .contains("9 of 12 points of the study have no row"),
        "{}",
        short.stderr
    );
    assert!(!dir.join("short.csv").exists());
}

/// Reference: the uninterrupted run's table. The same study is killed
/// once its table has 3 rows, a half-written line is added to the table,
/// and the study is run again: it keeps the 3 rows (runs only the rest),
/// cuts the half line off, and ends with the same table, seconds aside.
#[test]
fn a_study_killed_halfway_resumes_to_the_same_table() {
    let dir = temp_dir("resume");
    let text = format!(
        r#"{{
  "name": "resume",
  "scene": "{}",
  "set": {{ "mesh.nx": 30, "mesh.ny": 30, "growth.max_steps": 3 }},
  "axes": [ {{ "field": "cracks.0.friction", "range": {{ "from": 0.1, "to": 0.6, "count": 8 }} }} ]
}}"#,
        scene("specimen_single_flaw.json")
    );
    std::fs::write(dir.join("r.json"), text).expect("write study");
    let whole = cdca(
        &dir,
        &["study", "r.json", "--jobs", "1", "--out", "whole.csv"],
    );
    assert_eq!(whole.code, Some(0), "{}", whole.stderr);
    let mut child = Command::new(BIN)
        .args(["study", "r.json", "--jobs", "1", "--out", "cut.csv"])
        .current_dir(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("starts");
    let table = dir.join("cut.csv");
    let start = Instant::now();
    while std::fs::read_to_string(&table).map_or(0, |t| t.lines().count()) < 4 {
        assert!(
            start.elapsed() < Duration::from_mins(2),
            "no rows after 2 minutes"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("kill");
    let _ = child.wait();
    let cut = read(&table);
    let kept = cut.lines().count() - 1;
    assert!(
        (3..8).contains(&kept),
        "killed with {kept} rows of 8: the points are too fast to stop halfway"
    );
    std::fs::write(&table, format!("{cut}{}", "9,0123,0.5,thr")).expect("a half line");
    let again = cdca(
        &dir,
        &["study", "r.json", "--jobs", "1", "--out", "cut.csv"],
    );
    assert_eq!(again.code, Some(0), "{}", again.stderr);
    assert!(
        again
            .stdout
            .contains(&format!("({kept} resumed, {} run", 8 - kept)),
        "{}",
        again.stdout
    );
    assert!(again.stderr.contains("cut short"), "{}", again.stderr);
    assert_eq!(
        untimed(&read(&table)),
        untimed(&read(&dir.join("whole.csv")))
    );
    // the rows kept are those of the first run, to the byte
    let resumed = read(&table);
    for line in cut.lines().skip(1) {
        assert!(resumed.lines().any(|l| l == line), "row lost: {line}");
    }
}

/// The example of docs/studies.md that spreads a study with GNU parallel
/// (between its `example:parallel` markers), run as it is written in a
/// fresh folder with `cdca` on the PATH; its merged table equals the
/// study's single run, seconds aside. (`.ci/run` installs GNU parallel.)
#[test]
fn the_gnu_parallel_example_of_the_docs_runs() {
    let docs = read(&repo().join("docs/studies.md"));
    let block = docs
        .split("<!-- example:parallel -->")
        .nth(1)
        .and_then(|s| s.split("<!-- end:parallel -->").next())
        .expect("docs/studies.md has the example between its markers");
    let script: String = block
        .lines()
        .filter(|l| !l.starts_with("```"))
        .collect::<Vec<_>>()
        .join("\n");
    let available = Command::new("parallel").arg("--version").output();
    assert!(
        available.is_ok_and(|o| o.status.success()),
        "GNU parallel is not installed (apt-get install parallel; .ci/run does)"
    );
    let dir = temp_dir("parallel");
    let studies = dir.join("assets/studies");
    std::fs::create_dir_all(&studies).expect("dir");
    std::fs::create_dir_all(dir.join("assets/scenes")).expect("dir");
    for (from, to) in [
        (
            "assets/studies/first_steps.json",
            "assets/studies/first_steps.json",
        ),
        (
            "assets/scenes/specimen_single_flaw.json",
            "assets/scenes/specimen_single_flaw.json",
        ),
    ] {
        std::fs::copy(repo().join(from), dir.join(to)).expect("copy");
    }
    let bin_dir = Path::new(BIN).parent().expect("bin dir");
    let path = format!(
        "{}:{}",
        bin_dir.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let out = Command::new("bash")
        .args(["-euo", "pipefail", "-c", &script])
        .current_dir(&dir)
        .env("PATH", path)
        .output()
        .expect("bash runs");
    assert!(
        out.status.success(),
        "{script}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let merged = read(&dir.join("first_steps.csv"));
    let single = cdca(
        &dir,
        &[
            "study",
            "assets/studies/first_steps.json",
            "--out",
            "single.csv",
        ],
    );
    assert_eq!(single.code, Some(0), "{}", single.stderr);
    assert_eq!(untimed(&merged), untimed(&read(&dir.join("single.csv"))));
}

/// Bad input exits 2 with one line naming the file and the field (an
/// unknown field, an empty range, a shard 5/4, a study file changed under
/// its table, an unwritable output), and the rows already written stay,
/// byte for byte.
#[test]
fn bad_input_names_the_file_and_field_and_keeps_the_rows() {
    let dir = temp_dir("bad");
    let good = first_step_study(&dir, "good.json");
    let text = read(&good);
    let run = cdca(
        &dir,
        &["study", "good.json", "--shard", "1/6", "--out", "t.csv"],
    );
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let rows = read(&dir.join("t.csv"));
    assert_eq!(rows.lines().count(), 3);
    let bad = |name: &str, from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        std::fs::write(dir.join(name), text.replacen(from, to, 1)).expect("write");
    };
    bad("unknown.json", r#""run":"#, r#""colour": "red", "run":"#);
    bad("empty.json", r#""count": 4"#, r#""count": 0"#);
    bad("changed.json", r#""from": 0.0"#, r#""from": 0.1"#);
    std::fs::create_dir_all(dir.join("a_folder")).expect("dir");
    let cases: [(&[&str], &str); 6] = [
        (
            &["study", "unknown.json", "--out", "t.csv"],
            "unknown.json: study does not parse: unknown field `colour`",
        ),
        (
            &["study", "empty.json", "--out", "t.csv"],
            "empty.json: study field `axes[0].range.count`: 0: an empty range",
        ),
        (
            &["study", "good.json", "--shard", "5/4", "--out", "t.csv"],
            "good.json: --shard 5/4: the shard must be 1 to N (N ≥ 1), here 5 of 4",
        ),
        (
            &["study", "changed.json", "--shard", "1/6", "--out", "t.csv"],
            "`t.csv`: line 2 is a row of study",
        ),
        (
            &["study", "good.json", "--out", "a_folder"],
            "cannot write `a_folder`: not a regular file",
        ),
        (
            &["study", "good.json", "--out", "no_folder/t.csv"],
            "cannot write `no_folder/t.csv`",
        ),
    ];
    for (args, needle) in cases {
        let run = cdca(&dir, args);
        assert_eq!(run.code, Some(2), "{args:?}: {}", run.stderr);
        assert!(run.stderr.starts_with("cdca: "), "{args:?}: {}", run.stderr);
        assert_eq!(run.stderr.trim_end().lines().count(), 1, "{}", run.stderr);
        assert!(
            run.stderr.contains(needle),
            "{args:?}: `{needle}` not in {}",
            run.stderr
        );
        assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
        assert_eq!(read(&dir.join("t.csv")), rows, "{args:?} changed the rows");
    }
}
