//! Solver choice and settings, the run controls and the progress of the
//! work in hand.

use cdca::scene::{Ordering, SolverKind};
use egui::{Grid, ProgressBar, Ui};

use super::widgets::{EditTracker, choice, count_row, quantity_row};
use crate::app::WorkbenchApp;
use crate::command::Command;
use crate::compare::solver_name;
use crate::runner::RunMode;
use crate::units;

pub const SOLVERS: [SolverKind; 4] = [
    SolverKind::Direct,
    SolverKind::Automaton,
    SolverKind::Cg,
    SolverKind::Multigrid,
];

pub fn solver_ui(ui: &mut Ui, app: &WorkbenchApp, cmds: &mut Vec<Command>) {
    ui.heading("Solver");
    settings_ui(ui, app, cmds);
    ui.separator();
    controls_ui(ui, app, cmds);
    ui.separator();
    status_ui(ui, app);
}

fn settings_ui(ui: &mut Ui, app: &WorkbenchApp, cmds: &mut Vec<Command>) {
    let mut draft = app.scene.clone();
    let mut t = EditTracker::default();
    let options: Vec<(SolverKind, &str)> = SOLVERS.iter().map(|&k| (k, solver_name(k))).collect();
    choice(ui, "Linear solver", &mut draft.solver.kind, &options);
    let s = &mut draft.solver;
    let iterative = s.kind != SolverKind::Direct;
    Grid::new("solver settings").num_columns(2).show(ui, |ui| {
        if iterative {
            quantity_row(
                ui,
                &mut t,
                "Tolerance |r| / |f|",
                &mut s.tolerance,
                1.0,
                "",
                1e-16..=1.0,
            );
            count_row(
                ui,
                &mut t,
                "Max iterations",
                &mut s.max_iterations,
                1..=10_000_000,
            );
            quantity_row(
                ui,
                &mut t,
                "Over-relaxation ω",
                &mut s.omega,
                1.0,
                "",
                0.01..=1.99,
            );
        }
        if !app.scene.cracks.is_empty() {
            quantity_row(
                ui,
                &mut t,
                "Contact tolerance",
                &mut s.contact_tolerance,
                1.0,
                "",
                1e-16..=1.0,
            );
            count_row(
                ui,
                &mut t,
                "Max contact iterations",
                &mut s.max_contact_iterations,
                1..=10_000,
            );
        }
    });
    if iterative {
        choice(
            ui,
            "Cell order",
            &mut s.ordering,
            &[
                (Ordering::Lexicographic, "lexicographic"),
                (Ordering::RedBlack, "four-colour"),
            ],
        );
    }
    if draft != app.scene {
        cmds.push(Command::SetScene {
            scene: Box::new(draft),
            ongoing: t.ongoing,
        });
    } else if t.ended {
        cmds.push(Command::EndDrag);
    }
}

fn controls_ui(ui: &mut Ui, app: &WorkbenchApp, cmds: &mut Vec<Command>) {
    let mode = app.runner.mode;
    let paused = mode == RunMode::Paused;
    let iterative = app.scene.solver.kind != SolverKind::Direct;
    ui.horizontal_wrapped(|ui| {
        let buttons: [(&str, &str, Command, bool); 4] = [
            (
                "Solve",
                "Full solve with contact at the current load",
                Command::Solve,
                paused,
            ),
            (
                "Step",
                "One sweep of the iterative solver (the direct solver solves at once)",
                Command::Step,
                paused,
            ),
            (
                "Relax",
                "Sweep until converged, animated",
                Command::Relax,
                paused && iterative,
            ),
            (
                "Grow one step",
                "Solve, evaluate the tips, grow those that meet the criterion",
                Command::GrowOne,
                paused,
            ),
        ];
        for (label, hint, cmd, enabled) in buttons {
            if ui
                .add_enabled(enabled, egui::Button::new(label))
                .on_hover_text(hint)
                .clicked()
            {
                cmds.push(cmd);
            }
        }
    });
    ui.horizontal_wrapped(|ui| {
        let finished = app.runner.view.outcome.is_some();
        if ui
            .add_enabled(paused && !finished, egui::Button::new("Run growth"))
            .clicked()
        {
            cmds.push(Command::RunGrowth);
        }
        if ui
            .add_enabled(!paused, egui::Button::new("Pause"))
            .clicked()
        {
            cmds.push(Command::Pause);
        }
        if ui
            .button("Reset")
            .on_hover_text("Back to the scene's cracks, solve again")
            .clicked()
        {
            cmds.push(Command::Reset);
        }
    });
    if ui
        .button("Compare solvers")
        .on_hover_text("Error against run time of every solver on this scene")
        .clicked()
    {
        cmds.push(Command::CompareSolvers(SOLVERS.to_vec()));
    }
}

fn status_ui(ui: &mut Ui, app: &WorkbenchApp) {
    let view = &app.runner.view;
    if app.runner.stale && !view.solved {
        ui.colored_label(ui.visuals().warn_fg_color, "Scene changed — press Solve.");
    }
    match app.runner.mode {
        RunMode::Paused => {}
        RunMode::Relaxing => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("Relaxing…");
            });
            if let Some(r) = view.relax {
                // progress on a log scale from residual 1 to the tolerance
                let goal = app.scene.solver.tolerance.max(1e-300).log10();
                let done = (r.residual.max(1e-300).log10() / goal).clamp(0.0, 1.0) as f32;
                ui.add(ProgressBar::new(done).text(format!(
                    "sweep {}, residual {:.2e}",
                    r.iterations, r.residual
                )));
            }
        }
        RunMode::Growing => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("Growing…");
            });
            ui.add(
                ProgressBar::new(view.load_factor as f32)
                    .text(format!("load factor λ = {:.3}", view.load_factor)),
            );
        }
    }
    if let Some(p) = app.runner.field.progress() {
        ui.add(ProgressBar::new(p).text("sampling the field"));
    }
    if let Some((kind, seconds)) = app
        .comparison
        .as_ref()
        .and_then(crate::compare::Comparison::status)
    {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(format!(
                "Comparing: {} ({})",
                solver_name(kind),
                units::seconds(seconds)
            ));
        });
    }
    Grid::new("status").num_columns(2).show(ui, |ui| {
        ui.label("Solved");
        ui.label(if view.solved { "yes" } else { "no" });
        ui.end_row();
        if let Some(r) = view.relax {
            ui.label("Relaxation");
            ui.label(format!(
                "{} sweeps, residual {:.2e}{}",
                r.iterations,
                r.residual,
                if r.converged { ", converged" } else { "" }
            ));
            ui.end_row();
        }
        if let Some(s) = app.runner.last_solve_seconds {
            ui.label("Last build + solve");
            ui.label(format!(
                "{} + {}",
                units::seconds(app.runner.last_build_seconds),
                units::seconds(s)
            ));
            ui.end_row();
        }
        ui.label("Growth steps");
        ui.label(view.history.len().to_string());
        ui.end_row();
        ui.label("Load factor λ");
        ui.label(format!("{:.3}", view.load_factor));
        ui.end_row();
        if let Some(o) = view.outcome {
            ui.label("Outcome");
            ui.label(format!("{o:?}").to_lowercase());
            ui.end_row();
        }
        if !view.contact.is_empty() {
            let count = |s| view.contact.iter().filter(|c| c.state == s).count();
            ui.label("Contact points");
            ui.label(format!(
                "{} open, {} stick, {} slip",
                count(cdca::ContactState::Open),
                count(cdca::ContactState::Stick),
                count(cdca::ContactState::Slip)
            ));
            ui.end_row();
        }
    });
}
