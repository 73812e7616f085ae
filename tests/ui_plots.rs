//! UI tests (egui_kittest) of issue 54 item 4: every plot is readable at
//! 1400 × 900. After the default scene's growth run and after the bundled
//! overlapping pair's, every plot tab (residual by sweep and by time, K,
//! angles, load factor, the solver race, the study) shows a plot of at
//! least [`MIN_PLOT`] with numbers on both axes, and nothing the bottom
//! panel paints is cut off by its clip rectangle. They drive the solver:
//! run them with `--release`.

use cdca_workbench::{Command, Options, WorkbenchApp};
use egui::Rect;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

#[path = "support/harness.rs"]
mod harness;
use harness::{SIZE, grow, harness, run_study, run_until_paused};

/// Smallest data area of a plot, px (width, height): the Study tab's two
/// plots share the panel's width with its table.
const MIN_PLOT: [f32; 2] = [400.0, 150.0];

/// The workbench with `file` (a bundled scene; `None`: the default scene)
/// opened, solved and grown to the end of its run.
fn grown(file: Option<&str>) -> Harness<'static, WorkbenchApp> {
    let mut h = harness(Options::default());
    h.run_steps(3);
    run_until_paused(&mut h, 2000);
    if let Some(file) = file {
        let i = cdca_workbench::files::scenes::BUNDLED
            .iter()
            .position(|b| b.json.contains(file) || b.file == file)
            .expect("bundled");
        h.state_mut().push(Command::OpenBundled(i));
        h.run_steps(2);
        run_until_paused(&mut h, 5000);
        h.run_steps(1);
    }
    grow(&mut h, "Run growth");
    assert!(h.state().growth_outcome().is_some(), "growth ended");
    h
}

/// Runs the solver race (1 s per solver) to its end.
fn race(h: &mut Harness<'_, WorkbenchApp>) {
    h.state_mut()
        .push(Command::CompareSolvers { time_cap: 1.0 });
    for _ in 0..5000 {
        h.step();
        if h.state()
            .race()
            .is_some_and(cdca_workbench::study::race::Race::finished)
        {
            break;
        }
    }
    assert!(
        h.state()
            .race()
            .is_some_and(cdca_workbench::study::race::Race::finished)
    );
    h.run_steps(3);
}

/// A text painted in the last frame: its words, where it is, and the clip
/// rectangle it was painted in.
#[derive(Debug)]
struct Painted {
    text: String,
    rect: Rect,
    clip: Rect,
}

/// Every unrotated text painted in the last frame.
fn painted_texts(h: &Harness<'_, WorkbenchApp>) -> Vec<Painted> {
    fn flatten(shape: &egui::Shape, clip: Rect, out: &mut Vec<Painted>) {
        match shape {
            egui::Shape::Vec(shapes) => shapes.iter().for_each(|s| flatten(s, clip, out)),
            egui::Shape::Text(t) if t.angle == 0.0 && !t.galley.is_empty() => out.push(Painted {
                text: t.galley.text().to_owned(),
                rect: t.galley.rect.translate(t.pos.to_vec2()),
                clip,
            }),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for clipped in &h.output().shapes {
        flatten(&clipped.shape, clipped.clip_rect, &mut out);
    }
    out
}

/// The plots on screen: their names and data rectangles.
fn plots(h: &Harness<'_, WorkbenchApp>) -> Vec<(String, Rect)> {
    h.query_all_by(|n| n.role() == egui::accesskit::Role::Figure)
        .filter_map(|n| {
            let label = n.accesskit_node().label()?;
            label.starts_with("Plot: ").then(|| (label, n.rect()))
        })
        .collect()
}

/// The tick labels of a plot with data area `plot`: the texts right of its
/// left edge (y) and just below it (x).
fn ticks(texts: &[Painted], plot: Rect) -> (Vec<String>, Vec<String>) {
    let y = texts
        .iter()
        .filter(|t| {
            t.rect.right() <= plot.left() + 1.0
                && t.rect.right() >= plot.left() - 12.0
                && plot.y_range().contains(t.rect.center().y)
        })
        .map(|t| t.text.clone())
        .collect();
    let x = texts
        .iter()
        .filter(|t| {
            t.rect.top() >= plot.bottom() - 1.0
                && t.rect.top() <= plot.bottom() + 6.0
                && plot.x_range().contains(t.rect.center().x)
        })
        .map(|t| t.text.clone())
        .collect();
    (y, x)
}

/// Smallest data area of a Study plot, px: it shares the panel's width
/// with the study's table.
const MIN_STUDY_PLOT: [f32; 2] = [300.0, 200.0];

/// What is wrong with `tab` as shown (empty: readable), and its plots'
/// sizes and tick labels for the report: every plot at least `min`, at
/// least two labelled ticks on each axis, no text the bottom panel paints
/// cut off by its clip rectangle, and no widget under the canvas outside
/// the panel (between the side panels, above the window's bottom).
fn check_tab(h: &mut Harness<'_, WorkbenchApp>, tab: &str, min: [f32; 2]) -> Vec<String> {
    h.get_by_label(tab).click();
    h.run_steps(3);
    let canvas = h.get_by_label(cdca_workbench::app::CANVAS_LABEL).rect();
    let panel = Rect::from_x_y_ranges(
        canvas.left() - 10.0..=canvas.right() + 10.0,
        canvas.bottom()..=SIZE[1],
    );
    let texts = painted_texts(h);
    let mut problems = Vec::new();
    let shown = plots(h);
    // a run in which no tip grew (the overlapping pair: every step started
    // cracks in the intact rock) has no angles: the tab says so
    let none_grew = h
        .state()
        .growth_history()
        .iter()
        .all(|s| s.grown.is_empty());
    if tab == "Angles" && none_grew {
        assert!(shown.is_empty(), "{shown:?}");
        h.get_by_label_contains("No tip of a crack grew in");
    } else if shown.is_empty() {
        let hint: Vec<String> = texts
            .iter()
            .filter(|t| t.rect.top() > canvas.bottom())
            .map(|t| t.text.clone())
            .collect();
        problems.push(format!(
            "{tab}: no plot ({:?}): {hint:?}",
            h.state().plot_tab()
        ));
    }
    for (name, r) in &shown {
        let (y, x) = ticks(&texts, *r);
        println!(
            "{tab}: {name}: {:.0} × {:.0} px, y ticks {y:?}, x ticks {x:?}",
            r.width(),
            r.height()
        );
        if r.width() < min[0] || r.height() < min[1] {
            problems.push(format!("{tab}: {name} is {r:?}, under {min:?}"));
        }
        if y.len() < 2 || x.len() < 2 {
            problems.push(format!("{tab}: {name}: y ticks {y:?}, x ticks {x:?}"));
        }
    }
    // the legend beside a plot scrolls (its last lines cut by the scroll
    // area are a scroll away): left out
    let legend = shown
        .iter()
        .map(|p| p.1.right())
        .fold(f32::INFINITY, f32::min)
        + 4.0;
    for t in texts
        .iter()
        .filter(|t| t.rect.left() < legend)
        .filter(|t| panel.contains_rect(t.clip) || t.clip.top() >= canvas.bottom())
        .filter(|t| t.clip.center().x > canvas.left() && t.clip.center().x < canvas.right())
    {
        if !t.clip.contains_rect(t.rect.shrink(0.5)) {
            problems.push(format!(
                "{tab}: {:?} at {:?} cut by {:?}",
                t.text, t.rect, t.clip
            ));
        }
    }
    for n in h.query_all_by(|n| n.bounding_box().is_some()) {
        let r = n.rect();
        let below = r.top() >= canvas.bottom()
            && r.center().x > canvas.left()
            && r.center().x < canvas.right();
        if below && !panel.contains_rect(r.shrink(0.5)) {
            let node = n.accesskit_node();
            let label = node.label().or_else(|| node.value()).unwrap_or_default();
            problems.push(format!(
                "{tab}: {label:?} at {r:?} outside the panel {panel:?}"
            ));
        }
    }
    problems
}

/// Every plot tab after a run, the race and a study of `file`'s scene
/// (`None`: the default scene).
fn every_tab_is_readable(file: Option<&str>) {
    let mut h = grown(file);
    let mut problems = Vec::new();
    for tab in [
        "Residual / sweeps",
        "Residual / time",
        "K_I, K_II",
        "Angles",
        "Load factor",
    ] {
        problems.extend(check_tab(&mut h, tab, MIN_PLOT));
    }
    race(&mut h);
    problems.extend(check_tab(&mut h, "Solver race", MIN_PLOT));
    run_study(&mut h, 0.2, 0.6, 3);
    problems.extend(check_tab(&mut h, "Study", MIN_STUDY_PLOT));
    assert!(problems.is_empty(), "{file:?}:\n{}", problems.join("\n"));
}

/// The default scene grown to its end (14 steps, eleven crack ends: the
/// flaw's two and nine cracks started in the intact rock). Before: the K
/// plot's 28-entry legend left it 656 × 86 px with one y tick ("0"), and
/// the Study's plots were 169 × 86 and 209 × 86 px, their x ticks and
/// titles cut off at the panel's bottom and the table's last column at its
/// right.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn every_plot_is_readable_after_the_default_run() {
    every_tab_is_readable(None);
}

/// The bundled overlapping pair grown to its end: two flaw families.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn every_plot_is_readable_after_the_overlapping_pairs_run() {
    every_tab_is_readable(Some("specimen_two_flaws_overlapping.json"));
}
