//! The plot panel: the residual against sweeps and time, K_I and K_II,
//! angles and load factor against growth step, the solver race's error
//! against run time, and the parameter study. Each plot is a
//! [`Figure`](crate::plots::figure::Figure) from [`figures`](crate::plots::figures):
//! tick values on both axes (angles every 15° or 30°), titles with units,
//! the legend above the data (never on it), notes on surprising points, and
//! CSV and SVG export. A plot with nothing to show is replaced by a line
//! saying how to fill it.

use egui::{Color32, Pos2, ProgressBar, RichText, Sense, Stroke, Ui, Vec2};
use egui_plot::{
    AxisHints, GridInput, Line, LineStyle, MarkerShape, Plot, PlotPoint, PlotPoints, Points, Text,
    VLine,
};

use crate::plots::figure::{Figure, Marker, NOTE_MARKS, Style, YTicks, tick_label, tick_step};
use crate::plots::figures::{Plotted, figures};
use crate::plots::plot_tab::PlotTab;
use crate::results::solution::SolutionView;
use crate::state::command::{Command, Export, PlotFormat};
use crate::state::view::AppView;
use crate::study::file::StudyFileSetup;
use crate::study::race::Race;
use crate::study::{SUGGESTED_PATHS, Study, StudySetup, param_unit};
use crate::style::units;

/// Width the plot tabs take in one row, points; a narrower panel lists
/// them in a drop-down.
const TABS_IN_A_ROW: f32 = 600.0;

/// Width reserved for y-axis numbers, so labels never disappear.
const Y_AXIS_WIDTH: f32 = 52.0;

/// Smallest distance between two labelled ticks, px.
const LABEL_SPACING: f64 = 32.0;

/// The grid spacing egui_plot's `base_step_size` is scaled by, px.
const GRID_MIN: f32 = 8.0;

/// Smallest height of a plot, px: its ticks read on a phone (at 100 px
/// only its 60° and 30° ticks showed).
pub const MIN_PLOT_HEIGHT: f32 = 186.0;

pub fn plots_ui(
    ui: &mut Ui,
    v: &AppView,
    study_setup: &mut StudySetup,
    file_setup: &mut StudyFileSetup,
    cmds: &mut Vec<Command>,
) -> Option<egui::Rect> {
    if ui.available_width() >= TABS_IN_A_ROW {
        ui.horizontal_wrapped(|ui| {
            for tab in PlotTab::TABS {
                if ui
                    .selectable_label(v.plot_tab == tab, tab.label())
                    .clicked()
                {
                    cmds.push(Command::ShowPlot(tab));
                }
            }
        });
    } else {
        // narrower, the tabs took three rows of a phone's height: a list
        egui::ComboBox::from_label("Plot")
            .selected_text(v.plot_tab.label())
            .show_ui(ui, |ui| {
                for tab in PlotTab::TABS {
                    if ui
                        .selectable_label(v.plot_tab == tab, tab.label())
                        .clicked()
                    {
                        cmds.push(Command::ShowPlot(tab));
                    }
                }
            });
    }
    let tab = v.plot_tab;
    let specimen = [v.scene.specimen.width, v.scene.specimen.height];
    let figs = figures(
        tab,
        v.solution,
        v.race.map(|r| r as &dyn Plotted),
        v.study.map(|s| s as &dyn Plotted),
        specimen,
    );
    match tab {
        PlotTab::SolverComparison => race_ui(ui, v.race, &figs, cmds),
        PlotTab::Study | PlotTab::StudyMap => {
            // the tab runs a sweep of one field, or a study file
            if file_setup.use_file {
                super::study_file::study_file_ui(ui, v, file_setup, cmds, &|ui, i, fig, cmds| {
                    figure_ui(ui, PlotTab::StudyMap, i, fig, cmds);
                });
            } else {
                study_ui(ui, v.scene, v.study, study_setup, file_setup, &figs, cmds);
            }
            None
        }
        _ => {
            if let Some(fig) = figs.first() {
                Some(figure_ui(ui, tab, 0, fig, cmds))
            } else {
                ui.add(egui::Label::new(RichText::new(empty_hint(tab, v.solution)).weak()).wrap());
                None
            }
        }
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
        _ if steps > 0 => {
            let plural = if steps == 1 { "" } else { "s" };
            let rock: usize = view.history.iter().map(|s| s.nucleated.len()).sum();
            if rock > 0 {
                format!(
                    "No tip of a crack grew in {steps} growth step{plural}: the run started {rock} crack{} in the intact rock instead (the story says where; the Load factor plot marks the steps).",
                    if rock == 1 { "" } else { "s" }
                )
            } else {
                format!(
                    "No tip has grown in {steps} growth step{plural}: every tip stayed below its criterion (the tip inspector shows how far)."
                )
            }
        }
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

/// Width of the legend beside a plot, px.
const LEGEND_WIDTH: f32 = 210.0;

/// Room kept right of a plot, px: its last x tick label is centred on the
/// data's right edge and was cut off there ("0.6(" on the race).
const RIGHT_ROOM: f32 = 18.0;

/// The legend, the key and the export buttons beside the plot (above it
/// where the panel is narrow), then the plot. Beside it, a long legend (a
/// run with ten crack ends) no longer takes the plot's height.
pub(crate) fn figure_ui(
    ui: &mut Ui,
    tab: PlotTab,
    index: usize,
    fig: &Figure,
    cmds: &mut Vec<Command>,
) -> egui::Rect {
    if ui.available_width() >= 2.5 * LEGEND_WIDTH {
        let plot_width = ui.available_width() - LEGEND_WIDTH - ui.spacing().item_spacing.x;
        let height = ui.available_height();
        ui.horizontal_top(|ui| {
            let plot = ui.allocate_ui_with_layout(
                egui::vec2(plot_width, height),
                egui::Layout::top_down(egui::Align::Min),
                |ui| plot_and_notes_ui(ui, fig),
            );
            ui.allocate_ui_with_layout(
                egui::vec2(LEGEND_WIDTH, height),
                egui::Layout::top_down(egui::Align::Min),
                |ui| {
                    ui.set_width(LEGEND_WIDTH);
                    // within the panel's clip (its inner margin below)
                    let room = (ui.clip_rect().bottom() - ui.cursor().top()).min(height);
                    egui::ScrollArea::vertical()
                        .id_salt(("legend", &fig.id))
                        .max_height(room)
                        .show(ui, |ui| {
                            ui.horizontal(|ui| export_buttons_ui(ui, tab, index, cmds));
                            legend_ui(ui, fig, true);
                        });
                },
            );
            plot.inner
        })
        .inner
    } else {
        // above the plot, the legend keeps to what the plot leaves (a run
        // with 16 crack ends pushed a phone's plot out of the panel), at
        // most three rows (five took the canvas's room on a phone), and
        // scrolls
        let row = ui.text_style_height(&egui::TextStyle::Body) + ui.spacing().item_spacing.y;
        let room = ui.available_height() - MIN_PLOT_HEIGHT - notes_height(ui, fig);
        egui::ScrollArea::vertical()
            .id_salt(("legend row", &fig.id))
            .max_height(room.clamp(2.0 * row, 3.0 * row))
            .show(ui, |ui| {
                ui.horizontal_wrapped(|ui| {
                    legend_ui(ui, fig, false);
                    export_buttons_ui(ui, tab, index, cmds);
                });
            });
        plot_and_notes_ui(ui, fig)
    }
}

/// The height the notes' lines below a plot take.
fn notes_height(ui: &Ui, fig: &Figure) -> f32 {
    fig.notes.len() as f32 * (ui.text_style_height(&egui::TextStyle::Small) + 4.0)
}

/// The legend's entries (one per line in a column, else wrapped whole) and
/// the key to the line styles.
fn legend_ui(ui: &mut Ui, fig: &Figure, column: bool) {
    let entry = |ui: &mut Ui, colour, style, name: &str| {
        if column {
            swatch(ui, colour, style);
            ui.add(egui::Label::new(name).wrap());
        } else if wider_than_a_row(ui, name) {
            // on a row of its own, wrapped: unwrapped, it widened the
            // panel past a phone's window and the plot with it
            ui.end_row();
            swatch(ui, colour, style);
            ui.add(egui::Label::new(name).wrap());
        } else {
            // an entry moves to the next row whole, never cut mid-phrase
            swatch(ui, colour, style);
            ui.add(egui::Label::new(name).extend());
        }
    };
    for s in fig.legend() {
        if column {
            ui.horizontal_top(|ui| entry(ui, s.colour, Some(s.style), fig.legend_name(s)));
        } else {
            entry(ui, s.colour, Some(s.style), fig.legend_name(s));
        }
    }
    for (name, _, colour) in &fig.vlines {
        if column {
            ui.horizontal_top(|ui| entry(ui, *colour, None, name));
        } else {
            entry(ui, *colour, None, name);
        }
    }
    if !fig.key.is_empty() {
        if column || wider_than_a_row(ui, &fig.key) {
            ui.add(egui::Label::new(RichText::new(&fig.key).weak()).wrap());
        } else {
            ui.add(egui::Label::new(RichText::new(&fig.key).weak()).extend());
        }
    }
}

/// Whether `text` with a swatch before it is wider than a whole row of
/// the legend.
fn wider_than_a_row(ui: &Ui, text: &str) -> bool {
    let width = super::widgets::text_width(ui, text, &egui::TextStyle::Body);
    width + 2.0 * ui.spacing().interact_size.y > ui.max_rect().width()
}

fn export_buttons_ui(ui: &mut Ui, tab: PlotTab, index: usize, cmds: &mut Vec<Command>) {
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
}

/// The plot, its numbered note marks, and the notes' words below it.
/// Returns the plot's rectangle.
fn plot_and_notes_ui(ui: &mut Ui, fig: &Figure) -> egui::Rect {
    // the notes' lines below the plot keep their room
    let notes = notes_height(ui, fig);
    let height = (ui.available_height() - notes).max(MIN_PLOT_HEIGHT);
    let width = (ui.available_width() - RIGHT_ROOM).max(0.0);
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
        .width(width)
        .height(height)
        // room around the data, so points at the extremes are whole
        .set_margin_fraction(Vec2::new(0.03, 0.08))
        .grid_spacing(GRID_MIN..=300.0)
        .x_grid_spacer(spacer(YTicks::Decimal, x_min_step))
        .y_grid_spacer(spacer(kind, 0.0))
        .y_axis_formatter(move |m, _| tick_label(kind, m.value, m.step_size));
    for x in &fig.include_x {
        plot = plot.include_x(*x);
    }
    let (x0, x1, y0, y1) = fig.bounds();
    if let Some(top) = fig.y_max {
        // the axis stops at `top`: an outlier is a mark at the edge
        plot = plot.default_y_bounds(y0, top + 0.02 * (top - y0));
    } else {
        for y in &fig.include_y {
            plot = plot.include_y(*y);
        }
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
    let shown = plot.show(ui, |plot| {
        for (s, points) in fig.series.iter().zip(&points) {
            let pts = || PlotPoints::Borrowed(points);
            if s.style.has_line() {
                let style = if s.style == Style::Gap {
                    LineStyle::dotted_loose()
                } else if s.style.dashed() {
                    LineStyle::dashed_loose()
                } else {
                    LineStyle::Solid
                };
                plot.line(Line::new(&s.name, pts()).color(s.colour).style(style));
            }
            let (shape, radius) = match (s.style.marker(), s.style) {
                (None, _) => continue,
                (Some(_), Style::Markers) => (MarkerShape::Circle, 4.0),
                (Some(Marker::Circle), _) => (MarkerShape::Circle, 2.5),
                (Some(Marker::Diamond), _) => (MarkerShape::Diamond, 3.5),
            };
            plot.points(
                Points::new(&s.name, pts())
                    .color(s.colour)
                    .shape(shape)
                    .radius(radius),
            );
            // points above the axis's top: a triangle at the edge
            if let Some(top) = fig.y_max {
                let above: Vec<[f64; 2]> = s
                    .points
                    .iter()
                    .filter(|p| p[1] > top)
                    .map(|p| [p[0], top])
                    .collect();
                if !above.is_empty() {
                    plot.points(
                        Points::new(&s.name, above)
                            .color(s.colour)
                            .shape(MarkerShape::Up)
                            .filled(true)
                            .radius(6.0),
                    );
                }
            }
        }
        for (name, x, colour) in &fig.vlines {
            plot.vline(VLine::new(name, *x).color(*colour));
        }
        // numbered marks on the plot, their words below it: notes at
        // nearby points share a mark; a mark in the right fifth of the
        // data points at it from the left, so that it is not cut off at
        // the plot's edge
        let near = [0.06 * (x1 - x0), 0.12 * (y1 - y0)];
        for (at, numbers) in fig.note_marks_near(near) {
            let (text, anchor) = if at[0] > x0 + 0.8 * (x1 - x0) {
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
                    PlotPoint::new(at[0], fig.shown_y(at[1])),
                    RichText::new(text).small().strong(),
                )
                .anchor(anchor),
            );
        }
    });
    // named for assistive technology (and the UI tests): its axes
    let name = plot_label(fig);
    shown
        .response
        .widget_info(|| egui::WidgetInfo::labeled(egui::Role::Figure, true, &name));
    for (i, n) in fig.notes.iter().enumerate() {
        ui.small(format!("{}: {}", i + 1, n.text));
    }
    shown.response.rect
}

/// A plot's name for assistive technology: `Plot: y against x`.
pub fn plot_label(fig: &Figure) -> String {
    format!("Plot: {} against {}", fig.y_label, fig.x_label)
}

/// A legend entry's sample of the series: its line, dashes or marker (a
/// vertical line for `None`, a reference line).
pub(crate) fn swatch(ui: &mut Ui, colour: Color32, style: Option<Style>) {
    let (rect, _) = ui.allocate_exact_size(Vec2::new(20.0, 12.0), Sense::hover());
    let p = ui.painter();
    let stroke = Stroke::new(2.0, colour);
    let (l, r, c) = (rect.left_center(), rect.right_center(), rect.center());
    let Some(style) = style else {
        p.line_segment([rect.center_top(), rect.center_bottom()], stroke);
        return;
    };
    if style.dashed() || style == Style::Gap {
        for k in 0..3 {
            let x = l.x + 7.0 * k as f32;
            p.line_segment(
                [Pos2::new(x, c.y), Pos2::new((x + 4.0).min(r.x), c.y)],
                stroke,
            );
        }
    } else if style.has_line() {
        p.line_segment([l, r], stroke);
    }
    match style.marker() {
        Some(Marker::Circle) if style == Style::Markers => {
            p.circle_filled(c, 4.0, colour);
        }
        Some(Marker::Circle) => {
            p.circle_filled(c, 3.0, colour);
        }
        Some(Marker::Diamond) => {
            p.add(egui::Shape::convex_polygon(
                vec![
                    c + Vec2::new(0.0, -4.0),
                    c + Vec2::new(4.0, 0.0),
                    c + Vec2::new(0.0, 4.0),
                    c + Vec2::new(-4.0, 0.0),
                ],
                colour,
                Stroke::NONE,
            ));
        }
        None => {}
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
    file_setup: &mut StudyFileSetup,
    figs: &[Figure],
    cmds: &mut Vec<Command>,
) {
    let running = study.is_some_and(|s| !s.finished());
    // which of the two plots shows (λ_cr first): one at a time, each as
    // tall as the panel allows (side by side beside the table they were
    // about 200 × 90 px)
    let shown_id = ui.scope_id().with("study plot");
    let mut shown: usize = ui.data(|d| d.get_temp(shown_id)).unwrap_or(1);
    // the mode, the run's progress and the plot on one row
    ui.horizontal(|ui| {
        super::study_file::mode_ui(ui, file_setup);
        if let Some(study) = study {
            ui.separator();
            ui.add(
                ProgressBar::new(study.progress())
                    .desired_width(160.0)
                    .text(format!(
                        "{} of {} values{}",
                        study.points.len(),
                        study.values.len(),
                        if study.cancelled() {
                            " (cancelled)"
                        } else {
                            ""
                        }
                    )),
            );
            ui.separator();
            ui.selectable_value(&mut shown, 1, "λ_cr plot");
            ui.selectable_value(&mut shown, 0, "Kink angle plot");
        }
    });
    ui.data_mut(|d| d.insert_temp(shown_id, shown));
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
    if let Some(e) = study.points.iter().find_map(|p| p.error.as_deref()) {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!("Some values failed: {e}"),
        );
    }
    // the table at its own width (five short columns), the plot the rest:
    // equal thirds squeezed the table past the panel once the canvas was
    // narrower than about 800 px
    let gap = ui.spacing().item_spacing.x;
    let table = STUDY_TABLE_WIDTH.min(0.4 * ui.available_width());
    let plot = (ui.available_width() - table - 2.0 * gap).max(0.0);
    let height = ui.available_height();
    let down = egui::Layout::top_down(egui::Align::Min);
    ui.horizontal_top(|ui| {
        if let Some(fig) = figs.get(shown).or(figs.first()) {
            let i = figs.get(shown).map_or(0, |_| shown);
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

/// The race's progress and plot; returns the plot's rectangle.
fn race_ui(
    ui: &mut Ui,
    race: Option<&Race>,
    figs: &[Figure],
    cmds: &mut Vec<Command>,
) -> Option<egui::Rect> {
    let Some(race) = race else {
        ui.weak("Races every solver on this scene from u = 0 against the direct solution (press Compare solvers).");
        return None;
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
    figs.first()
        .map(|fig| figure_ui(ui, PlotTab::SolverComparison, 0, fig, cmds))
}
