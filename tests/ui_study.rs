//! UI tests (egui_kittest) of the Study tab's *Study file* mode (issue
//! 55): the workbench runs the same study files as `cdca study`, and its
//! rows are the CLI's (each the library's `Study::run_point`, which `cdca
//! study` calls), seconds aside; its map and table export like every plot.
//! They drive the solver: run them with `--release`.

use cdca::study::row::without_seconds;
use cdca::study::{RunKind, Study};
use cdca_workbench::state::command::{Export, PlotFormat};
use cdca_workbench::study::file::LoadedStudy;
use cdca_workbench::{Command, PlotTab, WorkbenchApp};
use egui_kittest::Harness;
use egui_kittest::kittest::{By, NodeT, Queryable};

#[path = "support/harness.rs"]
mod support;

fn harness() -> Harness<'static, WorkbenchApp> {
    support::harness(support::no_solver())
}

/// Steps frames until the study file's run has finished.
fn run_until_finished(h: &mut Harness<'_, WorkbenchApp>, frames: usize) {
    for _ in 0..frames {
        if h.state()
            .file_study()
            .is_some_and(cdca_workbench::study::file::FileStudy::finished)
        {
            return;
        }
        h.step();
    }
    panic!(
        "the study did not finish in {frames} frames: {:?}",
        h.state().message()
    );
}

/// The rows `cdca study` writes for `study` (its `run_point`), seconds
/// aside.
fn cli_rows(study: &Study, points: usize) -> Vec<String> {
    study.points()[..points]
        .iter()
        .map(|p| without_seconds(&study.run_point(p).csv(study.short_hash())).to_owned())
        .collect()
}

/// Reference: the library's rows (what `cdca study` writes). Clicking
/// *Study file*, choosing the bundled first steps and *Run study file*
/// shows the time estimate before it starts, runs every point's first step
/// within the frame budget, and gives the rows of `cdca study` on the same
/// file with `run: first_step`, seconds aside; its map (angle × friction)
/// and its table export as CSV.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_study_tab_runs_a_study_files_first_steps_as_the_cli_does() {
    let mut h = harness();
    h.run_steps(2);
    // the Study tab, its Study file mode, the bundled first steps
    h.get_by_label("Study").click();
    h.run_steps(2);
    h.get_by_label("Study file").click();
    h.run_steps(2);
    h.get_all_by_label("Study to run")
        .next()
        .expect("the study's choice")
        .click();
    h.run_steps(2);
    h.get_by_label("First steps of one flaw").click();
    h.run_steps(2);
    let loaded = h.state().loaded_study().expect("a study read").clone();
    assert_eq!(loaded.source, "first_steps.json");
    assert_eq!(loaded.study.points().len(), 16);
    // the estimate before it starts: 16 first steps of 60 × 60 elements
    assert!(
        h.query_by_label_contains("16 runs, about").is_some(),
        "no time estimate"
    );
    h.get_by_label("Run study file").click();
    run_until_finished(&mut h, 3000);
    assert_eq!(h.state().plot_tab(), PlotTab::Study);
    let run = h.state().file_study().expect("a run");
    assert_eq!(run.rows.len(), 16);
    let reference = loaded.study.clone().with_run(RunKind::FirstStep);
    let table = run.to_csv();
    let got: Vec<&str> = table.lines().skip(1).map(without_seconds).collect();
    assert_eq!(got, cli_rows(&reference, 16));
    assert_eq!(table.lines().next(), reference.header().lines().next());
    assert_eq!(
        h.state().table_csv(Export::StudyTable).as_deref(),
        Some(table.as_str())
    );
    // one map (two numeric axes, no layout axis), its points exported
    let map = h
        .state()
        .table_csv(Export::Plot {
            tab: PlotTab::StudyMap,
            index: 0,
            format: PlotFormat::Csv,
        })
        .expect("the map's numbers");
    assert_eq!(map.lines().count(), 1 + 16, "{map}");
    assert_eq!(
        map.lines().next(),
        Some("series,flaw angle [°],face friction μ [–]")
    );
    // each point's class names the cracks its row counts (issue 65: the
    // points whose first crack started in the intact rock said "nothing
    // grew")
    let count = |label: &str| map.lines().filter(|l| l.starts_with(label)).count();
    let runs = || run.rows.iter().filter_map(|r| r.run.as_ref());
    let rock = runs().filter(|r| r.intact_rock_cracks > 0).count();
    let none = runs()
        .filter(|r| r.wings + r.secondary_cracks + r.intact_rock_cracks == 0)
        .count();
    eprintln!("map classes: {rock} points with rock cracks, {none} with nothing grown");
    assert!(rock > 0, "first_steps.json starts rock cracks");
    assert_eq!(count("nothing grew,"), none, "{map}");
    assert_eq!(
        map.lines().filter(|l| l.contains("rock cracks")).count(),
        rock,
        "{map}"
    );

    // the rows as a table (issue 65: it sat under the maps, below the
    // fold): its "rock cracks" column reads each row's count, top down
    let expected: Vec<String> = run
        .rows
        .iter()
        .map(|r| {
            r.run
                .as_ref()
                .map_or("–".to_owned(), |r| r.intact_rock_cracks.to_string())
        })
        .collect();
    h.get_by_label("Table").click();
    h.run_steps(3);
    let header = h.get_by_label("rock cracks").rect();
    let mut column: Vec<(f32, String)> = h
        .query_all(By::new().role(egui::accesskit::Role::Label))
        .filter_map(|n| {
            let r = n.rect();
            let node = n.accesskit_node();
            let text = node.value().or(node.label())?;
            (r.top() > header.bottom()
                && r.center().x > header.left()
                && r.center().x < header.right())
            .then_some((r.top(), text))
        })
        .collect();
    column.sort_by(|a, b| a.0.total_cmp(&b.0));
    let shown: Vec<String> = column.into_iter().map(|(_, t)| t).collect();
    assert!(shown.len() >= 4, "{shown:?}");
    assert_eq!(shown, expected[..shown.len()], "the table's rock cracks");
}

/// Reference: the library's rows. A study file with its scene inline,
/// opened as a file is (File ▸ Open, a dropped file), leaves the scene as
/// it was and shows in the Study tab; growing its first 3 of 4 points to
/// the end gives the rows of `cdca study` on those points, seconds aside.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_study_file_opened_grows_its_first_points_as_the_cli_does() {
    let single = cdca_workbench::files::scenes::BUNDLED[0].json;
    let text = format!(
        r#"{{"name":"coarse growth","scene":{single},
            "set":{{"mesh.nx":30,"mesh.ny":30,"growth.max_steps":3}},
            "axes":[{{"field":"cracks.0.friction","values":[0.2,0.4,0.6,0.8]}}]}}"#
    );
    let mut h = harness();
    let before = h.state().scene().clone();
    h.state_mut().push(Command::OpenSceneText {
        source: "coarse.json".to_owned(),
        text: text.clone(),
    });
    h.run_steps(2);
    assert_eq!(h.state().scene(), &before, "a study file is not a scene");
    let loaded = LoadedStudy::parse("coarse.json", &text).expect("valid");
    assert_eq!(
        h.state().loaded_study().map(|l| l.study.hash.clone()),
        Some(loaded.study.hash.clone())
    );
    let mut setup = h.state().study_file_setup().clone();
    setup.first_steps = false;
    setup.cap = 3;
    h.state_mut().push(Command::RunStudyFile(setup));
    run_until_finished(&mut h, 3000);
    let table = h.state().file_study().expect("a run").to_csv();
    let got: Vec<&str> = table.lines().skip(1).map(without_seconds).collect();
    assert_eq!(got, cli_rows(&loaded.study, 3));
    // one numeric axis: the peak λ and the first link's step against it
    let peak = h
        .state()
        .table_csv(Export::Plot {
            tab: PlotTab::StudyMap,
            index: 0,
            format: PlotFormat::Csv,
        })
        .expect("the peak's numbers");
    assert_eq!(peak.lines().count(), 1 + 3, "{peak}");
}
