//! A run saved mid-way and opened again is the same run (issue 66): the
//! bundled stepped pair saved after step 9 through the path field (no file
//! dialog), opened through it and run on, tells the story of the
//! uninterrupted run, names its cracks as it does ("Rock crack 3"), and
//! has its peak and its link. A file saved before `growth.resume.history`
//! existed tells the story from its resume step on, and says so. They drive
//! the solver: run them with `--release`.

use cdca_workbench::{Options, WorkbenchApp};
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

#[path = "support/harness.rs"]
mod support;
use support::{grow, harness, open_bundled, run_until_paused};

const STEPPED: &str = "specimen_two_flaws_stepped.json";

/// The workbench without file dialogs (Save and Open ask for a path).
fn workbench() -> Harness<'static, WorkbenchApp> {
    let mut h = harness(Options {
        file_dialogs: false,
        ..Options::default()
    });
    h.run_steps(3);
    run_until_paused(&mut h, 2000);
    h
}

/// Types `path` into the path field and presses `button`.
fn use_path(h: &mut Harness<'_, WorkbenchApp>, path: &str, button: &str) {
    h.get_by_label("Path").focus();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.get_by_label("Path").type_text(path);
    h.run();
    h.get_by_label(button).click();
    h.run();
}

/// File ▸ `item`.
fn file_menu(h: &mut Harness<'_, WorkbenchApp>, item: &str) {
    h.get_by_label("File").click();
    h.run();
    h.get_by_label(item).click();
    h.run();
}

/// What the run tells: its story, its cracks' names, its peak (step, λ,
/// stress, against the intact rock) and its link.
#[derive(Debug, PartialEq)]
struct Told {
    story: Vec<String>,
    names: Vec<String>,
    peak: Option<(usize, f64, f64, Option<f64>)>,
    link: Option<(usize, String, [usize; 2])>,
    marks: Vec<(usize, String)>,
}

fn told(h: &Harness<'_, WorkbenchApp>) -> Told {
    let s = h.state();
    Told {
        story: s.run_story().map(|s| s.lines).unwrap_or_default(),
        names: s.crack_names(),
        peak: s
            .strength()
            .map(|p| (p.peak_step, p.peak_load_factor, p.peak_stress, p.ratio)),
        link: s
            .coalescence()
            .map(|c| (c.step, c.category.clone(), c.flaws)),
        marks: s.replay_marks(),
    }
}

/// The stepped pair saved after step 9 through the path field: the file's
/// text.
fn saved_after_nine_steps(dir: &std::path::Path) -> String {
    let mut h = workbench();
    open_bundled(&mut h, STEPPED);
    for _ in 0..9 {
        grow(&mut h, "Grow one step");
    }
    assert_eq!(h.state().growth_steps(), 9);
    let path = dir.join("stepped_9.json").display().to_string();
    file_menu(&mut h, "Save scene…");
    use_path(&mut h, &path, "Save here");
    std::fs::read_to_string(&path).expect("the scene was written")
}

/// `text` opened through the path field in a new workbench and run on to
/// the end.
fn opened_and_run_on(
    dir: &std::path::Path,
    name: &str,
    text: &str,
) -> Harness<'static, WorkbenchApp> {
    let path = dir.join(name).display().to_string();
    std::fs::write(&path, text).expect("written");
    let mut h = workbench();
    file_menu(&mut h, "Open scene…");
    use_path(&mut h, &path, "Open this file");
    h.run_steps(2);
    run_until_paused(&mut h, 2000);
    assert_eq!(h.state().growth_steps(), 9, "{:?}", h.state().message());
    grow(&mut h, "Run growth");
    h
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_run_saved_mid_way_and_opened_again_tells_the_same_run() {
    let mut whole = workbench();
    open_bundled(&mut whole, STEPPED);
    grow(&mut whole, "Run growth");
    let expected = told(&whole);
    eprintln!("{expected:#?}");
    assert!(
        expected.names.iter().any(|n| n.starts_with("Rock crack"))
            && expected.peak.is_some()
            && expected.link.is_some(),
        "the stepped pair's run starts cracks in the rock, peaks and links"
    );

    let dir = std::env::temp_dir().join(format!("cdca_ui_resume_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let saved = saved_after_nine_steps(&dir);
    let resumed = opened_and_run_on(&dir, "reopened.json", &saved);
    let last = |h: &Harness<'_, WorkbenchApp>| {
        h.state()
            .growth_history()
            .last()
            .map(cdca::report::GrowthStepReport::untimed)
    };
    assert_eq!(last(&resumed), last(&whole), "the same last step");
    assert_eq!(told(&resumed), expected);

    // the same file as written before `growth.resume.history`
    let mut old: serde_json::Value = serde_json::from_str(&saved).expect("JSON");
    let history = old["growth"]["resume"]
        .as_object_mut()
        .and_then(|r| r.remove("history"));
    let bytes = history.as_ref().map_or(0, |h| h.to_string().len());
    eprintln!("growth.resume.history: {bytes} bytes for 9 steps");
    assert!(history.is_some(), "the saved file holds the history");
    let old_text = serde_json::to_string(&old).expect("JSON");
    let older = opened_and_run_on(&dir, "older.json", &old_text);
    let t = told(&older);
    assert_eq!(t.names, expected.names, "the kinds come from the lineage");
    assert_eq!(
        t.story.first().map(String::as_str),
        Some(
            "Steps 1–9 ran before this scene was saved, in a file without their history \
             (growth.resume.history): the story, the peak and the link are told from step \
             10 on."
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}
