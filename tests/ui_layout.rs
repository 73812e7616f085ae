//! The workbench's layout at a classroom projector's 1024 × 640 and a
//! phone's 390 × 844 (issue 56): widget rectangles measured with
//! egui_kittest (no display, no GPU).

use cdca_workbench::{Options, WorkbenchApp};
use egui::{Rect, Vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

const PROJECTOR: [f32; 2] = [1024.0, 640.0];
const LAPTOP: [f32; 2] = [1280.0, 800.0];
const PHONE: [f32; 2] = [390.0, 844.0];

#[path = "support/harness.rs"]
mod support;
use support::harness_sized as harness;

/// The default scene, solved (release builds: the first frames solve it).
fn solved(size: [f32; 2]) -> Harness<'static, WorkbenchApp> {
    let mut h = harness(size, Options::default());
    h.run_steps(20);
    assert!(h.state().is_solved());
    h
}

fn window(size: [f32; 2]) -> Rect {
    Rect::from_min_size(egui::Pos2::ZERO, Vec2::from(size))
}

fn canvas(h: &Harness<'_, WorkbenchApp>) -> Rect {
    h.get_by_label(cdca_workbench::app::CANVAS_LABEL).rect()
}

/// Whether `inner` lies inside `outer` (half a point of rounding allowed).
fn inside(inner: Rect, outer: Rect) -> bool {
    outer.expand(0.5).contains_rect(inner)
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_specimen_spans_half_a_projector_window() {
    let mut h = solved(PROJECTOR);
    let span = h.state().specimen_rect().height();
    eprintln!(
        "1024 × 640: specimen {span:.0} px high, canvas {:?}",
        canvas(&h)
    );
    assert!(span >= 0.5 * PROJECTOR[1], "specimen {span} px high");

    // opened larger, then resized: the view refits
    let mut h2 = solved(LAPTOP);
    let before = h2.state().specimen_rect().height();
    h2.set_size(Vec2::from(PROJECTOR));
    h2.run_steps(4);
    let after = h2.state().specimen_rect().height();
    eprintln!("1280 × 800 → 1024 × 640: specimen {before:.0} → {after:.0} px high");
    assert!(
        after >= 0.5 * PROJECTOR[1],
        "specimen {after} px high after the resize"
    );
    assert!(
        inside(h2.state().specimen_rect(), canvas(&h2)),
        "the specimen is cropped: {:?} in {:?}",
        h2.state().specimen_rect(),
        canvas(&h2)
    );
    // and back: it grows again with the window
    h.set_size(Vec2::from(LAPTOP));
    h.run_steps(4);
    let grown = h.state().specimen_rect().height();
    eprintln!("1024 × 640 → 1280 × 800: specimen {span:.0} → {grown:.0} px high");
    assert!(grown > span + 50.0, "{span} → {grown}");
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_canvas_key_and_the_colour_legend_do_not_overlap() {
    for size in [PROJECTOR, LAPTOP, PHONE] {
        let mut h = solved(size);
        h.run_steps(10); // the field is sampled
        let (key, legend) = h.state().canvas_keys();
        let (Some(key), Some(legend)) = (key, legend) else {
            panic!("{size:?}: key {key:?}, legend {legend:?}");
        };
        eprintln!(
            "{size:?}: key {key:?}, legend {legend:?}, gap {:.0} px",
            key.top() - legend.bottom()
        );
        assert!(
            !key.intersects(legend),
            "{size:?}: {key:?} and {legend:?} overlap"
        );
        let c = canvas(&h);
        assert!(
            inside(key, c) && inside(legend, c),
            "{size:?}: outside {c:?}"
        );
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_phone_shows_the_canvas_and_the_run_bar() {
    let mut h = solved(PHONE);
    let screen = window(PHONE);
    let c = canvas(&h);
    let run = h.get_by_label("Run growth").rect();
    let solve = h.get_by_label("Solve").rect();
    eprintln!(
        "390 × 844: canvas {c:?} ({:.0} × {:.0}), Run growth {run:?}",
        c.width(),
        c.height()
    );
    assert!(inside(c, screen), "canvas {c:?}");
    assert!(c.width() >= 300.0, "canvas {} px wide", c.width());
    assert!(c.height() >= 300.0, "canvas {} px high", c.height());
    assert!(
        inside(run, screen) && inside(solve, screen),
        "{run:?} {solve:?}"
    );
    assert!(!h.state().layout().show_scene && !h.state().layout().show_solver);

    // Run growth runs from the bar, and Pause takes its place
    h.get_by_label("Run growth").click();
    h.run_steps(3);
    assert_eq!(
        h.state().running_job(),
        Some(cdca_workbench::state::job::Job::Growth)
    );
    h.get_by_label("Pause").click();
    h.run_steps(3);
    assert_eq!(h.state().running_job(), None);

    // a panel opens on demand, one at a time
    h.get_by_label("< Scene").click();
    h.run_steps(2);
    assert!(h.state().layout().show_scene);
    h.get_by_label("Solver >").click();
    h.run_steps(2);
    let l = h.state().layout();
    assert!(l.show_solver && !l.show_scene, "{l:?}");
    let solver_run = h.get_by_label("Run growth").rect();
    assert!(
        inside(solver_run, screen),
        "the Solver panel's Run growth {solver_run:?}"
    );
}

#[test]
fn side_panels_hide_and_show_on_a_desktop() {
    let mut h = harness(
        LAPTOP,
        Options {
            solve_on_start: false,
            auto_solve: false,
            ..Options::default()
        },
    );
    h.run_steps(2);
    let wide = canvas(&h).width();
    h.get_by_label("< Scene").click();
    h.run_steps(2);
    h.get_by_label("Solver >").click();
    h.run_steps(2);
    let l = h.state().layout();
    assert!(!l.show_scene && !l.show_solver, "{l:?}");
    let full = canvas(&h).width();
    eprintln!("1280 × 800: canvas {wide:.0} px wide with the panels, {full:.0} without");
    assert!(full > wide + 400.0, "{wide} → {full}");
    // the run bar stands in for the hidden Solver panel
    assert!(inside(h.get_by_label("Run growth").rect(), window(LAPTOP)));
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_layout_holds_at_the_largest_text_size() {
    let mut h = solved(PROJECTOR);
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label("200 %").click();
    h.run_steps(2);
    assert_eq!(h.state().layout().text_scale, 2.0);
    // as eframe does, the window's size in points follows the zoom
    let points = [PROJECTOR[0] / 2.0, PROJECTOR[1] / 2.0];
    h.set_size(Vec2::from(points));
    h.run_steps(6);
    let screen = window(points);
    let c = canvas(&h);
    let run = h.get_by_label("Run growth").rect();
    eprintln!(
        "1024 × 640 at 200 %: {:.0} × {:.0} points, canvas {c:?}, Run growth {run:?}, specimen {:.0} points high",
        points[0],
        points[1],
        h.state().specimen_rect().height()
    );
    assert!(inside(c, screen) && inside(run, screen), "{c:?} {run:?}");
    assert!(c.width() >= 300.0 && c.height() >= 100.0, "canvas {c:?}");
    assert!(inside(h.state().specimen_rect(), c), "specimen cropped");
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn a_zoomed_view_survives_a_resize() {
    let mut h = solved(LAPTOP);
    let centre = canvas(&h).center();
    h.event(egui::Event::PointerMoved(centre));
    h.event(egui::Event::Zoom(1.5));
    h.run_steps(2);
    let zoomed = h.state().specimen_rect().height();
    h.set_size(Vec2::from(PROJECTOR));
    h.run_steps(4);
    let after = h.state().specimen_rect().height();
    eprintln!("zoomed to {zoomed:.0} px high, {after:.0} after the resize");
    assert!((after - zoomed).abs() < 1.0, "{zoomed} → {after}");
    // View ▸ Fit specimen fits again, and resizes refit after it
    h.get_by_label("View").click();
    h.run_steps(2);
    h.get_by_label("Fit specimen").click();
    h.run_steps(3);
    let fitted = h.state().specimen_rect().height();
    assert!(fitted < zoomed && fitted >= 0.5 * PROJECTOR[1], "{fitted}");
}
