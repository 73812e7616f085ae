//! Histories as plots: residual against sweeps and time (log scale), K_I and
//! K_II, angles and load factor against growth step, and the solvers'
//! error against run time.

use std::collections::BTreeMap;

use egui::Ui;
use egui_plot::{GridMark, Legend, Line, Plot, PlotPoint, PlotPoints, Points};

use crate::app::WorkbenchApp;
use crate::command::Command;
use crate::compare::solver_name;

/// Which plot the bottom panel shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PlotTab {
    #[default]
    ResidualBySweep,
    ResidualByTime,
    Sifs,
    Angles,
    LoadFactor,
    SolverComparison,
}

const TABS: [(PlotTab, &str); 6] = [
    (PlotTab::ResidualBySweep, "Residual vs sweeps"),
    (PlotTab::ResidualByTime, "Residual vs time"),
    (PlotTab::Sifs, "K_I, K_II vs step"),
    (PlotTab::Angles, "Angles vs step"),
    (PlotTab::LoadFactor, "Load factor vs step"),
    (PlotTab::SolverComparison, "Solvers: error vs time"),
];

/// Axis labels for log10 values: `1e-6` at whole decades, nothing between.
fn decade_label(mark: GridMark, _range: &std::ops::RangeInclusive<f64>) -> String {
    let v = mark.value;
    if (v - v.round()).abs() < 1e-9 {
        format!("1e{}", v.round())
    } else {
        String::new()
    }
}

pub fn plots_ui(ui: &mut Ui, app: &mut WorkbenchApp, cmds: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        for (tab, label) in TABS {
            ui.selectable_value(&mut app.plot_tab, tab, label);
        }
    });
    let view = &app.runner.view;
    match app.plot_tab {
        PlotTab::ResidualBySweep => log_plot(
            ui,
            "residual_sweep",
            "sweep",
            &view.residual_by_sweep,
            "|f − K u| / |f|",
        ),
        PlotTab::ResidualByTime => log_plot(
            ui,
            "residual_time",
            "time [s]",
            &view.residual_by_time,
            "|f − K u| / |f|",
        ),
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
            step_plot(ui, "sifs", "K [MPa·√m]", series, |(c, t, k)| {
                format!(
                    "K_{} crack {} end {}",
                    if k == 1 { "I" } else { "II" },
                    c + 1,
                    t + 1
                )
            });
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
            step_plot(ui, "angles", "kink angle [°]", series, |(c, t, _)| {
                format!("crack {} end {}", c + 1, t + 1)
            });
        }
        PlotTab::LoadFactor => {
            let mut series = BTreeMap::new();
            series.insert(
                (0, 0, 0),
                view.history
                    .iter()
                    .map(|s| [s.step as f64, s.load_factor])
                    .collect(),
            );
            step_plot(ui, "load", "load factor λ", series, |_| "λ".to_owned());
        }
        PlotTab::SolverComparison => comparison_ui(ui, app, cmds),
    }
}

fn log_plot(ui: &mut Ui, id: &str, x_label: &str, points: &[PlotPoint], y_label: &str) {
    if points.is_empty() {
        ui.weak("No residual history yet: choose an iterative solver and press Step or Relax.");
    }
    Plot::new(id)
        .x_axis_label(x_label)
        .y_axis_label(format!("{y_label} (log)"))
        .y_axis_formatter(decade_label)
        .legend(Legend::default())
        .show(ui, |plot| {
            plot.line(Line::new("relative residual", PlotPoints::Borrowed(points)));
        });
}

fn step_plot(
    ui: &mut Ui,
    id: &str,
    y_label: &str,
    series: BTreeMap<(usize, usize, u8), Vec<[f64; 2]>>,
    name: impl Fn((usize, usize, u8)) -> String,
) {
    if series.is_empty() {
        ui.weak("No growth steps yet: press Grow one step or Run growth.");
    }
    Plot::new(id)
        .x_axis_label("growth step")
        .y_axis_label(y_label)
        .legend(Legend::default())
        .show(ui, |plot| {
            for (key, pts) in series {
                let label = name(key);
                plot.line(Line::new(label.clone(), PlotPoints::from(pts.clone())));
                plot.points(Points::new(label, PlotPoints::from(pts)).radius(2.5));
            }
        });
}

fn comparison_ui(ui: &mut Ui, app: &WorkbenchApp, cmds: &mut Vec<Command>) {
    let Some(c) = &app.comparison else {
        ui.horizontal(|ui| {
            ui.weak("Runs every solver on the current scene; the error is measured against the direct solution at 64 probe points.");
            if ui.button("Run the comparison").clicked() {
                cmds.push(Command::CompareSolvers(super::solver::SOLVERS.to_vec()));
            }
        });
        return;
    };
    Plot::new("compare")
        .x_axis_label("run time [s]")
        .y_axis_label("relative displacement error (log)")
        .y_axis_formatter(decade_label)
        .legend(Legend::default())
        .show(ui, |plot| {
            for run in &c.runs {
                let name = match &run.error {
                    Some(e) => format!("{} (failed: {e})", solver_name(run.kind)),
                    None => format!("{} ({} it.)", solver_name(run.kind), run.iterations),
                };
                plot.line(Line::new(name.clone(), PlotPoints::Borrowed(&run.points)));
                plot.points(Points::new(name, PlotPoints::Borrowed(&run.points)).radius(2.0));
            }
        });
}
