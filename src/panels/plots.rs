//! The plot panel: the residual against sweeps and time, K_I and K_II,
//! angles and load factor against growth step, the solver race's error
//! against run time, and the parameter study. Each plot is a
//! [`Figure`](crate::figure::Figure) from [`figures`](crate::figures):
//! tick values on both axes (angles every 15° or 30°), titles with units,
//! the legend above the data (never on it), notes on surprising points, and
//! CSV and SVG export. A plot with nothing to show is replaced by a line
//! saying how to fill it.

use egui::{Color32, Pos2, ProgressBar, RichText, Sense, Stroke, Ui, Vec2};
use egui_plot::{
    AxisHints, GridInput, Line, LineStyle, Plot, PlotPoint, PlotPoints, Points, Text, VLine,
};

use crate::command::{Command, Export, PlotFormat};
use crate::compare::Race;
use crate::figure::{Figure, NOTE_MARKS, Style, YTicks, tick_label, tick_step};
use crate::figures::figures;
use crate::plot_tab::PlotTab;
use crate::solution::SolutionView;
use crate::study::{SUGGESTED_PATHS, Study, StudySetup, param_unit};
use crate::study_file::StudyFileSetup;
use crate::units;
use crate::view::AppView;

const TABS: [(PlotTab, &str); 7] = [
    (PlotTab::ResidualBySweep, "Residual / sweeps"),
    (PlotTab::ResidualByTime, "Residual / time"),
    (PlotTab::Sifs, "K_I, K_II"),
    (PlotTab::Angles, "Angles"),
    (PlotTab::LoadFactor, "Load factor"),
    (PlotTab::SolverComparison, "Solver race"),
    (PlotTab::Study, "Study"),
];

/// Width reserved for y-axis numbers, so labels never disappear.
const Y_AXIS_WIDTH: f32 = 52.0;

/// Smallest distance between two labelled ticks, px.
const LABEL_SPACING: f64 = 32.0;

/// The grid spacing egui_plot's `base_step_size` is scaled by, px.
const GRID_MIN: f32 = 8.0;

/// Smallest height of a plot's data area, px.
const MIN_PLOT_HEIGHT: f32 = 120.0;

pub fn plots_ui(
    ui: &mut Ui,
    v: &AppView,
    plot_tab: &mut PlotTab,
    study_setup: &mut StudySetup,
    file_setup: &mut StudyFileSetup,
    cmds: &mut Vec<Command>,
) {
    ui.horizontal_wrapped(|ui| {
        for (tab, label) in TABS {
            ui.selectable_value(plot_tab, tab, label);
        }
    });
    let tab = *plot_tab;
    let specimen = [v.scene.specimen.width, v.scene.specimen.height];
    let figs = figures(tab, v.solution, v.race, v.study, specimen);
    match tab {
        PlotTab::SolverComparison => race_ui(ui, v.race, &figs, cmds),
        PlotTab::Study | PlotTab::StudyMap => {
            // the tab runs a sweep of one field, or a study file
            if file_setup.use_file {
                super::study_file::study_file_ui(ui, v, file_setup, cmds, &|ui, i, fig, cmds| {
                    figure_ui(ui, PlotTab::StudyMap, i, fig, cmds);
                });
            } else {
                ui.horizontal(|ui| super::study_file::mode_ui(ui, file_setup));
                study_ui(ui, v.scene, v.study, study_setup, &figs, cmds);
            }
        }
        _ => match figs.first() {
            Some(fig) => figure_ui(ui, tab, 0, fig, cmds),
            None => {
                ui.weak(empty_hint(tab, v.solution));
            }
        },
    }
}

/// What an empty plot says: how to fill it; after growth steps in which no
/// tip grew (a load ramp below every tip's criterion), that; on a reopened
/// run before its next step, that its earlier steps are not plotted.
fn empty_hint(tab: PlotTab, view: &SolutionView) -> String {
    let steps = view.history.len();
    match tab {
        PlotTab::ResidualBySweep | PlotTab::ResidualByTime => {
            "No residual history: the direct solver solves in one step. Choose an iterative solver and press Step or Relax.".to_owned()
        }
        _ if steps == 0 && view.steps_done > 0 => format!(
            "This run resumes after growth step {}: the plots show the steps grown from here on (press Grow one step or Run growth).",
            view.steps_done
        ),
        _ if steps > 0 => format!(
            "No tip has grown in {steps} growth step{}: every tip stayed below its criterion (the tip inspector shows how far).",
            if steps == 1 { "" } else { "s" }
        ),
        _ => "No growth steps yet: press Grow one step or Run growth.".to_owned(),
    }
}

/// Tick steps for egui_plot: the figure's kind of step, sized so that
/// labelled ticks are at least [`LABEL_SPACING`] apart (and at least
/// `min_step`: 1 on an axis that counts).
fn spacer(kind: YTicks, min_step: f64) -> impl Fn(GridInput) -> Vec<egui_plot::GridMark> {
    egui_plot::uniform_grid_spacer(move |input: GridInput| {
        let per_px = input.base_step_size / f64::from(GRID_MIN);
        let step = tick_step(kind, per_px * LABEL_SPACING).max(min_step);
        match kind {
            YTicks::Degrees => [step / 3.0, step, 2.0 * step],
            YTicks::Log => [step, step, 10.0 * step],
            YTicks::Decimal => [step / 5.0, step, 5.0 * step],
        }
    })
}

/// The legend above the data and the export buttons, then the plot.
pub(crate) fn figure_ui(
    ui: &mut Ui,
    tab: PlotTab,
    index: usize,
    fig: &Figure,
    cmds: &mut Vec<Command>,
) {
    ui.horizontal_wrapped(|ui| {
        for s in fig.legend() {
            swatch(ui, s.colour, Some(s.style));
            // an entry moves to the next row whole, never cut mid-phrase
            ui.add(egui::Label::new(fig.legend_name(s)).extend());
        }
        for (name, _, colour) in &fig.vlines {
            swatch(ui, *colour, None);
            ui.label(name);
        }
        for (format, label, hint) in [
            (PlotFormat::Csv, "CSV…", "Save this plot's numbers as CSV"),
            (
                PlotFormat::Svg,
                "SVG…",
                "Save this plot as an SVG picture (for slides)",
            ),
        ] {
            if ui.small_button(label).on_hover_text(hint).clicked() {
                cmds.push(Command::Export(Export::Plot { tab, index, format }));
            }
        }
    });
    // the notes' lines below the plot keep their room
    let notes = fig.notes.len() as f32 * (ui.text_style_height(&egui::TextStyle::Small) + 4.0);
    let height = (ui.available_height() - notes).max(MIN_PLOT_HEIGHT);
    let kind = fig.y_ticks;
    let x_min_step = if fig.x_whole { 1.0 } else { 0.0 };
    // the x axis's tick labels at the spacing the grid spacer gives them:
    // egui_plot's default hides x labels closer than 60 px, which left the
    // Study plots (about 200 px wide) without a single number on x
    let x_axis = AxisHints::new_x()
        .label(fig.x_label.as_str())
        .label_spacing(0.75 * LABEL_SPACING as f32..=LABEL_SPACING as f32)
        .formatter(move |m, _| {
            if m.step_size < x_min_step {
                String::new()
            } else {
                tick_label(YTicks::Decimal, m.value, m.step_size)
            }
        });
    let mut plot = Plot::new(&fig.id)
        .custom_x_axes(vec![x_axis])
        .y_axis_label(&fig.y_label)
        .y_axis_min_width(Y_AXIS_WIDTH)
        .height(height)
        // room around the data, so points at the extremes are whole
        .set_margin_fraction(Vec2::new(0.03, 0.08))
        .grid_spacing(GRID_MIN..=300.0)
        .x_grid_spacer(spacer(YTicks::Decimal, x_min_step))
        .y_grid_spacer(spacer(kind, 0.0))
        .y_axis_formatter(move |m, _| tick_label(kind, m.value, m.step_size));
    for y in &fig.include_y {
        plot = plot.include_y(*y);
    }
    // one copy per series, borrowed by its line and its markers
    let points: Vec<Vec<PlotPoint>> = fig
        .series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .map(|p| PlotPoint::new(p[0], p[1]))
                .collect()
        })
        .collect();
    plot.show(ui, |plot| {
        for (s, points) in fig.series.iter().zip(&points) {
            let pts = || PlotPoints::Borrowed(points);
            match s.style {
                Style::Line => plot.line(Line::new(&s.name, pts()).color(s.colour)),
                Style::Dashed => plot.line(
                    Line::new(&s.name, pts())
                        .color(s.colour)
                        .style(LineStyle::dashed_loose()),
                ),
                Style::LineAndMarkers => {
                    plot.line(Line::new(&s.name, pts()).color(s.colour));
                    plot.points(Points::new(&s.name, pts()).color(s.colour).radius(2.5));
                }
                Style::Markers => {
                    plot.points(Points::new(&s.name, pts()).color(s.colour).radius(4.0));
                }
                Style::Gap => plot.line(
                    Line::new(&s.name, pts())
                        .color(s.colour)
                        .style(LineStyle::dotted_loose()),
                ),
            }
        }
        for (name, x, colour) in &fig.vlines {
            plot.vline(VLine::new(name, *x).color(*colour));
        }
        // numbered marks on the plot, their words below it: notes at
        // nearby points used to run into each other; a mark in the right
        // fifth of the data points at it from the left, so that it is not
        // cut off at the plot's edge
        let xs = || fig.series.iter().flat_map(|s| &s.points).map(|p| p[0]);
        let x_lo = xs().fold(f64::INFINITY, f64::min);
        let x_hi = xs().fold(f64::NEG_INFINITY, f64::max);
        for (at, numbers) in fig.note_marks() {
            let (text, anchor) = if at[0] > x_lo + 0.8 * (x_hi - x_lo) {
                (
                    format!("{numbers} {}", NOTE_MARKS[1]),
                    egui::Align2::RIGHT_CENTER,
                )
            } else {
                (
                    format!("{} {numbers}", NOTE_MARKS[0]),
                    egui::Align2::LEFT_CENTER,
                )
            };
            plot.text(
                Text::new(
                    "note",
                    PlotPoint::new(at[0], at[1]),
                    RichText::new(text).small().strong(),
                )
                .anchor(anchor),
            );
        }
    });
    for (i, n) in fig.notes.iter().enumerate() {
        ui.small(format!("{}: {}", i + 1, n.text));
    }
}

/// A legend entry's sample of the series: its line, dashes or marker (a
/// vertical line for `None`, a reference line).
pub(crate) fn swatch(ui: &mut Ui, colour: Color32, style: Option<Style>) {
    let (rect, _) = ui.allocate_exact_size(Vec2::new(20.0, 12.0), Sense::hover());
    let p = ui.painter();
    let stroke = Stroke::new(2.0, colour);
    let (l, r, c) = (rect.left_center(), rect.right_center(), rect.center());
    match style {
        None => {
            p.line_segment([rect.center_top(), rect.center_bottom()], stroke);
        }
        Some(Style::Markers) => {
            p.circle_filled(c, 4.0, colour);
        }
        Some(Style::Dashed | Style::Gap) => {
            for k in 0..3 {
                let x = l.x + 7.0 * k as f32;
                p.line_segment(
                    [Pos2::new(x, c.y), Pos2::new((x + 4.0).min(r.x), c.y)],
                    stroke,
                );
            }
        }
        Some(Style::Line) => {
            p.line_segment([l, r], stroke);
        }
        Some(Style::LineAndMarkers) => {
            p.line_segment([l, r], stroke);
            p.circle_filled(c, 3.0, colour);
        }
    }
}

/// The Study tab: the parameter and its values, run / cancel / export; then
/// the first growth's kink angle and λ_cr against the parameter, and the
/// measured values in a table beside them.
fn study_ui(
    ui: &mut Ui,
    scene: &cdca::scene::SceneFile,
    study: Option<&Study>,
    setup: &mut StudySetup,
    figs: &[Figure],
    cmds: &mut Vec<Command>,
) {
    let running = study.is_some_and(|s| !s.finished());
    ui.horizontal_wrapped(|ui| {
        let label = ui.label("Parameter");
        egui::ComboBox::from_id_salt("study path")
            .selected_text(crate::study::path_label(&setup.path))
            .show_ui(ui, |ui| {
                // only the fields this scene has (no traction on a free side)
                for p in scene.params(&SUGGESTED_PATHS) {
                    ui.selectable_value(&mut setup.path, p.to_owned(), crate::study::path_label(p));
                }
            })
            .response
            .labelled_by(label.id);
        ui.add(egui::TextEdit::singleline(&mut setup.path).desired_width(150.0))
            .labelled_by(label.id)
            .on_hover_text("Any numeric scene field by its path, e.g. cracks.0.friction, boundary.right.normal, criterion.r0");
        let (unit, _) = param_unit(&setup.path);
        let suffix = if unit == "–" {
            String::new()
        } else {
            format!(" {unit}")
        };
        let label = ui.label("from");
        ui.add(egui::DragValue::new(&mut setup.from).speed(0.01).suffix(suffix.clone()))
            .labelled_by(label.id);
        let label = ui.label("to");
        ui.add(egui::DragValue::new(&mut setup.to).speed(0.01).suffix(suffix))
            .labelled_by(label.id);
        let label = ui.label("values");
        ui.add(egui::DragValue::new(&mut setup.count).range(1..=200))
            .labelled_by(label.id);
        if ui
            .add_enabled(!running, egui::Button::new("Run study"))
            .on_hover_text("For each value: grow until the first step that extends a tip; record its angle, mode, λ, K_I, K_II")
            .clicked()
        {
            cmds.push(Command::RunStudy(setup.clone()));
        }
        if ui.add_enabled(running, egui::Button::new("Cancel")).clicked() {
            cmds.push(Command::CancelStudy);
        }
        if ui
            .add_enabled(study.is_some_and(|s| !s.points.is_empty()), egui::Button::new("Table as CSV…"))
            .clicked()
        {
            cmds.push(Command::Export(Export::Study));
        }
    });
    let Some(study) = study else {
        ui.weak("Sweeps one scene parameter and plots the first growth step's kink angle and critical load against it (press Run study).");
        return;
    };
    ui.add(ProgressBar::new(study.progress()).text(format!(
        "{} of {} values{}",
        study.points.len(),
        study.values.len(),
        if study.cancelled() {
            " (cancelled)"
        } else {
            ""
        }
    )));
    if let Some(e) = study.points.iter().find_map(|p| p.error.as_deref()) {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!("Some values failed: {e}"),
        );
    }
    // the table at its own width (five short columns), the two plots
    // sharing the rest: equal thirds squeezed the table past the panel
    // once the canvas was narrower than about 800 px
    let gap = ui.spacing().item_spacing.x;
    let table = STUDY_TABLE_WIDTH.min(0.4 * ui.available_width());
    let plot = ((ui.available_width() - table - 2.0 * gap) / 2.0).max(0.0);
    let height = ui.available_height();
    let down = egui::Layout::top_down(egui::Align::Min);
    ui.horizontal_top(|ui| {
        for (i, fig) in figs.iter().enumerate().take(2) {
            ui.allocate_ui_with_layout(egui::vec2(plot, height), down, |ui| {
                ui.set_width(plot);
                ui.push_id(i, |ui| figure_ui(ui, PlotTab::Study, i, fig, cmds));
            });
        }
        ui.allocate_ui_with_layout(egui::vec2(table, height), down, |ui| {
            ui.set_width(table);
            study_table(ui, study);
        });
    });
}

/// Width of the Study tab's table, px: its five columns at their widest
/// (a parameter such as "friction [–]", λ_cr, θ, the mode, u).
const STUDY_TABLE_WIDTH: f32 = 250.0;

/// The measured values: parameter, λ_cr, first kink angle and mode, and
/// the intact rock's utilisation of its strength at λ_cr.
fn study_table(ui: &mut Ui, study: &Study) {
    let (unit, factor) = param_unit(&study.path);
    egui::ScrollArea::vertical().show(ui, |ui| {
        egui::Grid::new("study table")
            .striped(true)
            .num_columns(5)
            .show(ui, |ui| {
                ui.strong(format!(
                    "{} [{unit}]",
                    study.path.rsplit('.').next().unwrap_or("")
                ));
                ui.strong("λ_cr [–]");
                ui.strong("θ [°]");
                ui.strong("mode");
                ui.strong("u [–]").on_hover_text(
                    "The rock away from the cracks at λ_cr: the median of its Mohr–Coulomb \
                     utilisation (≥ 1: it would fail there; see the Intact rock status)",
                );
                ui.end_row();
                for p in &study.points {
                    ui.label(units::compact(p.value * factor));
                    match (&p.error, p.grown.first()) {
                        (Some(e), _) => {
                            ui.label("–");
                            ui.label("–");
                            ui.colored_label(ui.visuals().warn_fg_color, "failed")
                                .on_hover_text(e);
                        }
                        (None, Some(g)) => {
                            ui.label(p.load_factor.map_or("–".to_owned(), |l| format!("{l:.3}")));
                            ui.label(format!("{:.1}", g.angle_deg));
                            ui.label(format!("{:?}", g.mode).to_lowercase());
                        }
                        (None, None) if !p.nucleated.is_empty() => {
                            // the intact rock failed before any tip grew
                            ui.label(p.load_factor.map_or("–".to_owned(), |l| format!("{l:.3}")));
                            ui.label("–");
                            ui.label("rock").on_hover_text(
                                "A crack started in the intact rock before any tip grew \
                                 (growth.intact_rock \"nucleate\").",
                            );
                        }
                        (None, None) => {
                            ui.label("–");
                            ui.label("–");
                            let why = p.outcome.map_or("none".to_owned(), |o| {
                                format!("none ({o:?})").to_lowercase()
                            });
                            ui.label(why);
                        }
                    }
                    match p.intact_rock {
                        Some(r) if r.utilisation >= 1.0 => {
                            ui.colored_label(
                                ui.visuals().warn_fg_color,
                                format!("{:.2}", r.utilisation),
                            );
                        }
                        Some(r) => {
                            ui.label(format!("{:.2}", r.utilisation));
                        }
                        None => {
                            ui.label("–");
                        }
                    }
                    ui.end_row();
                }
            });
    });
}

fn race_ui(ui: &mut Ui, race: Option<&Race>, figs: &[Figure], cmds: &mut Vec<Command>) {
    let Some(race) = race else {
        ui.weak("Races every solver on this scene from u = 0 against the direct solution (press Compare solvers).");
        return;
    };
    ui.horizontal(|ui| {
        if let Some((run, progress)) = race.status() {
            ui.add(
                ProgressBar::new(progress)
                    .desired_width(260.0)
                    .text(format!(
                        "{}: {}",
                        run.racer.name,
                        units::seconds(run.seconds())
                    )),
            );
        }
        ui.weak("solid: energy-norm error, dashed: K error");
        if ui
            .add_enabled(race.finished(), egui::Button::new("Race as CSV…"))
            .clicked()
        {
            cmds.push(Command::Export(Export::Race));
        }
    });
    if let Some(fig) = figs.first() {
        figure_ui(ui, PlotTab::SolverComparison, 0, fig, cmds);
    }
}
