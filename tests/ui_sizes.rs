//! The workbench at any window size and any text size (issue 65): from a
//! 320 × 480 phone to a 2560 × 1440 screen, text at 100–200 %, in each
//! plot tab, fresh, mid-run, after a run and in replay. No size panics,
//! and in every window of at least 360 × 640 points the story and the
//! selected plot stay whole in the window, the plot at least 180 points
//! tall.

use cdca_workbench::state::command::Command;
use cdca_workbench::state::layout::TEXT_SCALES;
use cdca_workbench::{Options, PlotTab, RunMode, WorkbenchApp};
use egui::{Rect, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::{By, NodeT, Queryable};

#[path = "support/harness.rs"]
mod support;
use support::{harness_sized, open_bundled, run_until_paused};

/// Window sizes, physical pixels.
const SIZES: [[f32; 2]; 7] = [
    [320.0, 480.0],
    [360.0, 640.0],
    [390.0, 844.0],
    [1024.0, 640.0],
    [1280.0, 800.0],
    [1400.0, 900.0],
    [2560.0, 1440.0],
];

/// The stepped pair opened in a harness of `size`.
fn stepped_pair(size: [f32; 2]) -> Harness<'static, WorkbenchApp> {
    let mut h = harness_sized(size, Options::default());
    h.run_steps(3);
    open_bundled(&mut h, "specimen_two_flaws_stepped.json");
    h
}

/// A window of `size` physical pixels with text at `scale`: as eframe
/// does, the window's size in points is its size over the zoom. The zoom
/// goes first, with a frame of its own: the frame in which egui applies a
/// new zoom sizes the screen from the last frame's (its guard against
/// jitter), and a size given in that frame would be lost.
fn resize(h: &mut Harness<'_, WorkbenchApp>, size: [f32; 2], scale: f32) -> Vec2 {
    h.ctx.set_zoom_factor(scale);
    h.step();
    let points = Vec2::from(size) / scale;
    h.set_size(points);
    h.step();
    points
}

/// In a window wide enough for them (not narrow), both side panels shown,
/// as the window a user widens has them: a narrow window hid them, and
/// the wider sizes after it were swept without.
fn show_side_panels(h: &mut Harness<'_, WorkbenchApp>, points: Vec2) {
    if points.x < cdca_workbench::state::layout::NARROW_WIDTH {
        return;
    }
    for (heading, button) in [("Scene", "< Scene"), ("Solver", "Solver >")] {
        if h.query_by_label(heading).is_none() {
            h.get_by_label(button).click();
            h.run_steps(2);
        }
    }
}

/// Every window size and text size, each plot tab: a few frames each.
/// The tabs are chosen by command: a tab's label may be off screen on the
/// smallest windows. Returns the text cut at the window's right edge in
/// windows at least 360 points wide, whatever their height ([`cut_text`]).
fn sweep(h: &mut Harness<'_, WorkbenchApp>, what: &str) -> Vec<String> {
    let mut cut = Vec::new();
    for size in SIZES {
        for scale in TEXT_SCALES {
            let points = resize(h, size, scale);
            show_side_panels(h, points);
            let window = Rect::from_min_size(egui::Pos2::ZERO, points).expand(0.5);
            for tab in PlotTab::TABS {
                h.state_mut().push(Command::ShowPlot(tab));
                h.run_steps(2);
                if points.x >= 360.0 {
                    let place = format!("{what}, {points:?}, {tab:?}");
                    cut.extend(
                        cut_text(h, window)
                            .into_iter()
                            .map(|c| format!("{place}: {c}")),
                    );
                }
            }
            eprintln!("{what}: {size:?} at {:.0} %", 100.0 * scale);
        }
    }
    cut
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn no_window_or_text_size_panics_fresh_mid_run_after_a_run_or_in_replay() {
    let mut h = stepped_pair([1400.0, 900.0]);
    assert!(h.state().is_solved());
    let mut cut = sweep(&mut h, "fresh");

    h.state_mut().push(Command::RunGrowth);
    h.run_steps(6);
    assert_eq!(h.state().run_mode(), RunMode::Growing);
    cut.extend(sweep(&mut h, "mid-run"));

    resize(&mut h, [1400.0, 900.0], 1.0);
    run_until_paused(&mut h, 20_000);
    assert!(h.state().growth_history().len() >= 3);
    cut.extend(sweep(&mut h, "after the run"));

    h.state_mut().push(Command::Replay(Some(2)));
    h.run_steps(2);
    cut.extend(sweep(&mut h, "replaying step 2"));
    assert!(
        cut.is_empty(),
        "text cut at the window's edge:\n{}",
        cut.join("\n")
    );
}

/// The plot (its accessible name starts `Plot: `) and the story's lines
/// on screen, by rectangle.
fn plot_and_story(h: &Harness<'_, WorkbenchApp>) -> (Option<Rect>, Vec<(String, Rect)>) {
    let plot = h
        .query_all(By::new().role(egui::accesskit::Role::Figure))
        .find(|n| {
            n.accesskit_node()
                .label()
                .is_some_and(|l| l.starts_with("Plot: "))
        })
        .map(|n| n.rect());
    let story = h.state().run_story().map(|s| s.lines).unwrap_or_default();
    let lines = story
        .into_iter()
        .map(|line| {
            let rect = h.get_by_label(&line).rect();
            (line, rect)
        })
        .collect();
    (plot, lines)
}

/// Text cut at the window's right edge: each line of text (AccessKit
/// `TextRun`) that starts inside the window and ends past its right edge.
/// Lines below the window are scrolled, not cut: the side panels scroll.
fn cut_text(h: &Harness<'_, WorkbenchApp>, window: Rect) -> Vec<String> {
    h.query_all(By::new().role(egui::accesskit::Role::TextRun))
        .filter_map(|n| {
            let r = n.rect();
            let node = n.accesskit_node();
            let text = node.value().or(node.label()).unwrap_or_default();
            (window.contains(r.left_top()) && r.right() > window.right() && !text.is_empty())
                .then(|| format!("{text:?} cut at {r:?}"))
        })
        .collect()
}

/// After the stepped pair's run, in every window of at least 360 × 640
/// points (text at 100–200 % of the sizes above): the story's lines whole
/// in the window and off the canvas and, in the tabs with a plot, the plot
/// whole in the window and at least 180 points tall; no line of text cut
/// at the window's right edge.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_story_and_a_whole_plot_show_from_360_by_640_points_up() {
    let mut h = stepped_pair([1400.0, 900.0]);
    h.state_mut().push(Command::RunGrowth);
    h.run_steps(2);
    run_until_paused(&mut h, 20_000);
    assert!(h.state().run_story().is_some());
    let mut checked = 0;
    let mut failed = Vec::new();
    for size in SIZES {
        for scale in TEXT_SCALES {
            let points = Vec2::from(size) / scale;
            if points.x < 360.0 || points.y < 640.0 {
                continue;
            }
            resize(&mut h, size, scale);
            let window = Rect::from_min_size(egui::Pos2::ZERO, points).expand(0.5);
            for tab in [PlotTab::Sifs, PlotTab::LoadFactor] {
                h.state_mut().push(Command::ShowPlot(tab));
                h.run_steps(10);
                let (plot, story) = plot_and_story(&h);
                let plot = plot.unwrap_or_else(|| panic!("{points:?} {tab:?}: no plot"));
                let canvas = h.get_by_label(cdca_workbench::app::CANVAS_LABEL).rect();
                eprintln!(
                    "canvas {canvas:?}, story {:?}",
                    story
                        .iter()
                        .map(|(_, r)| (r.top(), r.bottom()))
                        .collect::<Vec<_>>()
                );
                eprintln!(
                    "{size:?} at {:.0} % ({points:?}), {tab:?}: plot {:.0} × {:.0} at {:?}",
                    100.0 * scale,
                    plot.width(),
                    plot.height(),
                    plot.min
                );
                if !(window.contains_rect(plot) && plot.height() >= 180.0 - 0.5) {
                    failed.push(format!("{points:?} {tab:?}: plot {plot:?}"));
                }
                for (line, rect) in story {
                    if !window.contains_rect(rect) || rect.intersects(canvas) {
                        failed.push(format!("{points:?} {tab:?}: {line:?} at {rect:?}"));
                    }
                }
                for cut in cut_text(&h, window) {
                    failed.push(format!("{points:?} {tab:?}: {cut}"));
                }
                checked += 1;
            }
        }
    }
    assert!(failed.is_empty(), "{}", failed.join("\n"));
    assert!(checked >= 20, "{checked} layouts");
}
