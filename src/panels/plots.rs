//! Histories as plots: residual against sweeps and time (log scale), K_I and
//! K_II, angles and load factor against growth step, and the solver race's
//! error against run time. A plot with nothing to show is replaced by a
//! line saying how to fill it; every axis has numbers and units; each series
//! has one fixed colour, shared by its line, its markers and its legend.

use std::collections::BTreeMap;
use std::ops::RangeInclusive;

use egui::{Color32, ProgressBar, Ui};
use egui_plot::{GridMark, Legend, Line, LineStyle, Plot, PlotPoint, PlotPoints, Points, VLine};

use crate::command::{Command, Export};
use crate::compare::{ENERGY_FLOOR, Race};
use crate::study::{SUGGESTED_PATHS, Study, StudySetup, param_unit};
use crate::units;
use crate::view::{AppView, PlotTab};

const TABS: [(PlotTab, &str); 7] = [
    (PlotTab::ResidualBySweep, "Residual vs sweeps"),
    (PlotTab::ResidualByTime, "Residual vs time"),
    (PlotTab::Sifs, "K_I, K_II vs step"),
    (PlotTab::Angles, "Angles vs step"),
    (PlotTab::LoadFactor, "Load factor vs crack length"),
    (PlotTab::SolverComparison, "Solver race: error vs time"),
    (PlotTab::Study, "Study: angle, mode vs parameter"),
];

/// Series colours, distinguishable on the dark and the light theme.
const PALETTE: [Color32; 8] = [
    Color32::from_rgb(70, 140, 255),
    Color32::from_rgb(255, 150, 40),
    Color32::from_rgb(40, 190, 90),
    Color32::from_rgb(230, 70, 90),
    Color32::from_rgb(170, 110, 240),
    Color32::from_rgb(30, 200, 200),
    Color32::from_rgb(220, 200, 40),
    Color32::from_rgb(240, 110, 200),
];

/// Width reserved for y-axis numbers, so labels never disappear.
const Y_AXIS_WIDTH: f32 = 44.0;

fn colour(i: usize) -> Color32 {
    PALETTE[i % PALETTE.len()]
}

/// Axis numbers for log10 values: `1e-6` at whole decades when the grid
/// steps by decades or more, the value itself (`3.2e-7`) on a finer grid.
fn log_label(mark: GridMark, _range: &RangeInclusive<f64>) -> String {
    let v = mark.value;
    if mark.step_size >= 1.0 - 1e-9 {
        if (v - v.round()).abs() < 1e-9 {
            format!("1e{}", v.round())
        } else {
            String::new()
        }
    } else {
        format!("{:.1e}", 10f64.powf(v))
    }
}

/// A plot with the workbench's common settings.
fn plot<'a>(id: &'a str, x_label: &str, y_label: &str) -> Plot<'a> {
    Plot::new(id)
        .x_axis_label(x_label)
        .y_axis_label(y_label)
        .y_axis_min_width(Y_AXIS_WIDTH)
        .legend(Legend::default())
}

pub fn plots_ui(
    ui: &mut Ui,
    v: &AppView,
    plot_tab: &mut PlotTab,
    study_setup: &mut StudySetup,
    cmds: &mut Vec<Command>,
) {
    ui.horizontal_wrapped(|ui| {
        for (tab, label) in TABS {
            ui.selectable_value(plot_tab, tab, label);
        }
    });
    let view = v.solution;
    match *plot_tab {
        PlotTab::ResidualBySweep => {
            residual_plot(ui, "residual_sweep", "sweep", &view.residual_by_sweep);
        }
        PlotTab::ResidualByTime => {
            residual_plot(ui, "residual_time", "time [s]", &view.residual_by_time);
        }
        PlotTab::Sifs => {
            let mut series: BTreeMap<(usize, usize, u8), Vec<[f64; 2]>> = BTreeMap::new();
            for s in &view.history {
                for t in &s.tips {
                    series
                        .entry((t.crack, t.tip, 1))
                        .or_default()
                        .push([s.step as f64, t.k1 * 1e-6]);
                    series
                        .entry((t.crack, t.tip, 2))
                        .or_default()
                        .push([s.step as f64, t.k2 * 1e-6]);
                }
            }
            step_plot(
                ui,
                "sifs",
                "growth step",
                "K [MPa·√m]",
                series,
                |(c, t, k)| {
                    format!(
                        "K_{} crack {} end {}",
                        if k == 1 { "I" } else { "II" },
                        c + 1,
                        t + 1
                    )
                },
            );
        }
        PlotTab::Angles => {
            let mut series: BTreeMap<(usize, usize, u8), Vec<[f64; 2]>> = BTreeMap::new();
            for s in &view.history {
                for g in &s.grown {
                    series
                        .entry((g.crack, g.tip, 0))
                        .or_default()
                        .push([s.step as f64, g.angle_deg]);
                }
            }
            step_plot(
                ui,
                "angles",
                "growth step",
                "kink angle [°]",
                series,
                |(c, t, _)| format!("crack {} end {}", c + 1, t + 1),
            );
        }
        PlotTab::LoadFactor => {
            let mut series = BTreeMap::new();
            if !view.history.is_empty() {
                series.insert(
                    (0, 0, 0),
                    view.history
                        .iter()
                        .map(|s| [s.crack_length * units::MM_PER_M, s.load_factor])
                        .collect(),
                );
            }
            // λ rising with the crack length is stable growth, falling unstable
            step_plot(
                ui,
                "load",
                "total crack length [mm]",
                "load factor λ [–]",
                series,
                |_| "λ".to_owned(),
            );
        }
        PlotTab::SolverComparison => race_ui(ui, v.race, cmds),
        PlotTab::Study => study_ui(ui, v.study, study_setup, cmds),
    }
}

/// The Study tab: the parameter and its values, run / cancel / export, and
/// the first growth step's kink angle and mode against the parameter.
fn study_ui(ui: &mut Ui, study: Option<&Study>, setup: &mut StudySetup, cmds: &mut Vec<Command>) {
    let running = study.is_some_and(|s| !s.finished());
    ui.horizontal_wrapped(|ui| {
        ui.label("Parameter");
        egui::ComboBox::from_id_salt("study path")
            .selected_text(setup.path.clone())
            .show_ui(ui, |ui| {
                for p in SUGGESTED_PATHS {
                    ui.selectable_value(&mut setup.path, p.to_owned(), p);
                }
            });
        ui.add(egui::TextEdit::singleline(&mut setup.path).desired_width(150.0))
            .on_hover_text("Any numeric scene field by its path, e.g. cracks.0.friction, boundary.right.normal, criterion.r0");
        let (unit, _) = param_unit(&setup.path);
        let suffix = if unit == "–" {
            String::new()
        } else {
            format!(" {unit}")
        };
        ui.label("from");
        ui.add(egui::DragValue::new(&mut setup.from).speed(0.01).suffix(suffix.clone()));
        ui.label("to");
        ui.add(egui::DragValue::new(&mut setup.to).speed(0.01).suffix(suffix));
        ui.label("values");
        ui.add(egui::DragValue::new(&mut setup.count).range(1..=200));
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
            .add_enabled(study.is_some_and(|s| !s.points.is_empty()), egui::Button::new("Export CSV…"))
            .clicked()
        {
            cmds.push(Command::Export(Export::Study));
        }
    });
    let Some(study) = study else {
        ui.weak("Sweeps one scene parameter and plots the first growth step's kink angle and mode against it (press Run study).");
        return;
    };
    let (unit, factor) = param_unit(&study.path);
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
    let x_label = format!("{} [{unit}]", study.path);
    let modes = [
        (cdca::report::Mode::Tension, "tension", 0),
        (cdca::report::Mode::Shear, "shear", 1),
    ];
    ui.columns(2, |cols| {
        plot("study angle", &x_label, "initial kink angle [°]")
            .include_y(0.0)
            .show(&mut cols[0], |plot| {
                for (mode, name, c) in modes {
                    let pts: Vec<[f64; 2]> = study
                        .points
                        .iter()
                        .flat_map(|p| {
                            p.grown
                                .iter()
                                .filter(move |g| g.mode == mode)
                                .map(move |g| [p.value * factor, g.angle_deg])
                        })
                        .collect();
                    plot.points(
                        Points::new(name, PlotPoints::from(pts))
                            .color(colour(c))
                            .radius(4.0),
                    );
                }
            });
        plot("study mode", &x_label, "mode of the first growth")
            .include_y(-0.3)
            .include_y(2.3)
            .y_axis_formatter(|m, _| match m.value.round() as i64 {
                0 if (m.value - 0.0).abs() < 1e-9 => "none".to_owned(),
                1 if (m.value - 1.0).abs() < 1e-9 => "tension".to_owned(),
                2 if (m.value - 2.0).abs() < 1e-9 => "shear".to_owned(),
                _ => String::new(),
            })
            .show(&mut cols[1], |plot| {
                let level = |m| match m {
                    cdca::report::Mode::Tension => 1.0,
                    cdca::report::Mode::Shear => 2.0,
                    cdca::report::Mode::None => 0.0,
                };
                let mut by_mode: [Vec<[f64; 2]>; 3] = Default::default();
                for p in &study.points {
                    if p.grown.is_empty() {
                        by_mode[2].push([p.value * factor, 0.0]);
                    }
                    for g in &p.grown {
                        let i = usize::from(g.mode == cdca::report::Mode::Shear);
                        by_mode[i].push([p.value * factor, level(g.mode)]);
                    }
                }
                for (i, (pts, name)) in by_mode
                    .into_iter()
                    .zip(["tension", "shear", "none"])
                    .enumerate()
                {
                    plot.points(
                        Points::new(name, PlotPoints::from(pts))
                            .color(colour(i))
                            .radius(4.0),
                    );
                }
            });
    });
}

fn residual_plot(ui: &mut Ui, id: &str, x_label: &str, points: &[PlotPoint]) {
    if points.is_empty() {
        ui.weak("No residual history: the direct solver solves in one step. Choose an iterative solver and press Step or Relax.");
        return;
    }
    plot(id, x_label, "relative residual |f − K u| / |f| [–], log")
        .y_axis_formatter(log_label)
        .show(ui, |plot| {
            plot.line(
                Line::new("relative residual", PlotPoints::Borrowed(points)).color(colour(0)),
            );
        });
}

fn step_plot(
    ui: &mut Ui,
    id: &str,
    x_label: &str,
    y_label: &str,
    series: BTreeMap<(usize, usize, u8), Vec<[f64; 2]>>,
    name: impl Fn((usize, usize, u8)) -> String,
) {
    if series.is_empty() {
        ui.weak("No growth steps yet: press Grow one step or Run growth.");
        return;
    }
    plot(id, x_label, y_label).include_y(0.0).show(ui, |plot| {
        for (i, (key, pts)) in series.into_iter().enumerate() {
            let label = name(key);
            let c = colour(i);
            plot.line(Line::new(label.clone(), PlotPoints::from(pts.clone())).color(c));
            plot.points(
                Points::new(label, PlotPoints::from(pts))
                    .color(c)
                    .radius(2.5),
            );
        }
    });
}

fn race_ui(ui: &mut Ui, race: Option<&Race>, cmds: &mut Vec<Command>) {
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
            .add_enabled(race.finished(), egui::Button::new("Export CSV…"))
            .clicked()
        {
            cmds.push(Command::Export(Export::Race));
        }
    });
    plot(
        "race",
        "solver run time (setup included) [s]",
        "relative error [–], log",
    )
    .y_axis_formatter(log_label)
    .include_y(0.0)
    .include_y(ENERGY_FLOOR.log10())
    .include_x(0.0)
    .show(ui, |plot| {
        for (i, run) in race.runs.iter().enumerate() {
            let c = colour(i);
            let name = match &run.error {
                Some(e) => format!("{} (failed: {e})", run.racer.label()),
                None => format!("{} ({} it.)", run.racer.label(), run.iterations()),
            };
            if i == 0 {
                // the reference: its time as a vertical line
                if let Some(s) = run.samples.first() {
                    plot.vline(
                        VLine::new(
                            format!("{}: {}", run.racer.label(), units::seconds(s.seconds)),
                            s.seconds,
                        )
                        .color(c),
                    );
                }
                continue;
            }
            plot.line(
                Line::new(name.clone(), PlotPoints::Borrowed(&run.energy_points))
                    .color(c)
                    .width(2.0),
            );
            plot.line(
                Line::new(name, PlotPoints::Borrowed(&run.k_points))
                    .color(c)
                    .style(LineStyle::dashed_loose()),
            );
        }
    });
}
