//! Solver choice and settings, the run controls and the progress of the
//! work in hand.

use cdca::report::{Outcome, TipReport};
use cdca::scene::{
    ContactUpdate, GrowthControl, GrowthSpec, IntactRock, Ordering, SceneFile, SolverKind,
};
use cdca::solvers::automaton::sor_omega;
use egui::{Button, Grid, ProgressBar, Ui};

use super::widgets::{EditTracker, choice, count_row, quantity_row};
use crate::results::solution::SecondStart;
use crate::run::RunMode;
use crate::state::command::Command;
use crate::state::job::{Job, capitalised};
use crate::state::view::AppView;
use crate::study::race::solver_name;
use crate::style::units;

pub const SOLVERS: [SolverKind; 4] = [
    SolverKind::Direct,
    SolverKind::Automaton,
    SolverKind::Cg,
    SolverKind::Multigrid,
];

/// The solver panel; `race_time_cap` (s) is the race's time cap per solver.
pub fn solver_ui(ui: &mut Ui, v: &AppView, race_time_cap: &mut f64, cmds: &mut Vec<Command>) {
    ui.heading("Solver");
    settings_ui(ui, v, cmds);
    ui.separator();
    controls_ui(ui, v, race_time_cap, cmds);
    ui.separator();
    status_ui(ui, v, cmds);
}

fn settings_ui(ui: &mut Ui, v: &AppView, cmds: &mut Vec<Command>) {
    let mut draft = v.scene.clone();
    let mut t = EditTracker::default();
    let options: Vec<(SolverKind, &str)> = SOLVERS.iter().map(|&k| (k, solver_name(k))).collect();
    choice(ui, "Linear solver", &mut draft.solver.kind, &options);
    let s = &mut draft.solver;
    let iterative = s.kind != SolverKind::Direct;
    // the contact iteration's settings, while a face can be in contact
    let contact = !v.scene.cracks.is_empty() && !v.solution.all_faces_open();
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
            if s.kind == SolverKind::Automaton {
                omega_optimum_row(ui, &mut s.omega, draft.mesh.nx.max(draft.mesh.ny));
            }
        }
        if contact {
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
    if !v.scene.cracks.is_empty() && !contact {
        ui.weak("Every crack face was open at the last solve: no contact settings apply.");
    }
    if s.kind == SolverKind::Automaton && contact {
        choice(
            ui,
            "Contact update",
            &mut s.contact_update,
            &[
                (ContactUpdate::Outer, "after each solve"),
                (ContactUpdate::InSweep, "in the sweep (the paper's)"),
            ],
        )
        .on_hover_text(
            "When the crack faces' open/stick/slip states are updated: after each converged \
             linear solve (an outer loop), or as the sweep passes each cell, the paper's rule \
             (one pass of sweeps; the states change live on the canvas). In the sweep, cells \
             with crack-face points relax at ω = 1 and the rest at Over-relaxation ω: on the \
             default scene ω = 1.9 converges in 28 k sweeps, ω = 1 in 432 k.",
        );
    } else if s.kind != SolverKind::Automaton {
        // the in-sweep rule belongs to the automaton's cell visits
        s.contact_update = ContactUpdate::Outer;
    }
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
    if draft != *v.scene {
        cmds.push(Command::SetScene {
            scene: Box::new(draft),
            ongoing: t.ongoing,
        });
    } else if t.ended {
        cmds.push(Command::EndDrag);
    }
}

/// A button that sets the automaton's ω to Young's optimum for the mesh
/// (`sor_omega`), greyed out when ω is already there.
fn omega_optimum_row(ui: &mut Ui, omega: &mut f64, n: usize) {
    let best = sor_omega(n);
    ui.label("");
    let r = ui
        .add_enabled(
            (*omega - best).abs() > 5e-3,
            Button::new(format!("Use ω = {best:.2}")),
        )
        .on_hover_text(format!(
            "Young's optimal over-relaxation 2/(1 + sin(π/n)) for this {n}-element mesh. \
             ω = 1 is the paper's plain cell-by-cell relaxation (block Gauss–Seidel); \
             on the default scene with in-sweep contact ω = 1.90 converges in 28 k sweeps, \
             ω = 1 in 432 k."
        ));
    if r.clicked() {
        *omega = best;
    }
    ui.end_row();
}

/// A button that starts a job: disabled with `why_not` on hover when it
/// cannot act; while another job holds the slot, its hover says that a
/// press offers to cancel that job.
fn job_button(
    ui: &mut Ui,
    v: &AppView,
    (label, hint): (&str, &str),
    why_not: Option<&str>,
    cmd: Command,
    cmds: &mut Vec<Command>,
) {
    let running = v.run.job.filter(|&j| Some(j) != Job::of_command(&cmd));
    let hint = match running {
        Some(j) => format!(
            "{hint}. {} is running: pressing this offers to cancel it.",
            capitalised(j.name())
        ),
        None => hint.to_owned(),
    };
    let r = ui
        .add_enabled(why_not.is_none(), Button::new(label))
        .on_hover_text(hint)
        .on_disabled_hover_text(why_not.unwrap_or_default());
    if r.clicked() {
        cmds.push(cmd);
    }
}

fn controls_ui(ui: &mut Ui, v: &AppView, race_time_cap: &mut f64, cmds: &mut Vec<Command>) {
    let mode = v.run.mode;
    // (a drag's solves come and go every few frames: the buttons stay)
    let paused = matches!(mode, RunMode::Paused | RunMode::SolvingDrag);
    let iterative = v.scene.solver.kind != SolverKind::Direct;
    let finished = v.solution.outcome.is_some();
    let ended = "Growth has ended (see Outcome); Reset goes back to the scene's cracks.";
    ui.horizontal_wrapped(|ui| {
        job_button(
            ui,
            v,
            ("Solve", "Full solve with contact at the current load, from the scene's initial state as `cdca solve` solves it"),
            None,
            Command::Solve,
            cmds,
        );
        job_button(
            ui,
            v,
            ("Step", "One sweep of the iterative solver (the direct solver solves at once)"),
            None,
            Command::Step,
            cmds,
        );
        job_button(
            ui,
            v,
            ("Relax", "Sweep until converged, animated"),
            (!iterative).then_some("The direct solver solves at once: press Solve (Relax animates the iterative solvers)."),
            Command::Relax,
            cmds,
        );
        job_button(
            ui,
            v,
            ("Grow one step", "Solve, evaluate the tips, grow those that meet the criterion"),
            finished.then_some(ended),
            Command::GrowOne,
            cmds,
        );
    });
    ui.horizontal_wrapped(|ui| {
        job_button(
            ui,
            v,
            ("Run growth", "Grow until the run ends, animated"),
            finished.then_some(ended),
            Command::RunGrowth,
            cmds,
        );
        if ui
            .add_enabled(!paused, egui::Button::new("Pause"))
            .on_hover_text("Stop the solve or growth run where it is")
            .on_disabled_hover_text("Nothing to pause: no solve or growth run is going on.")
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
    pace_ui(ui, v, cmds);
    ui.horizontal(|ui| {
        job_button(
            ui,
            v,
            ("Compare solvers", "Race every solver from u = 0 on this scene: error against the direct solution over run time"),
            None,
            Command::CompareSolvers {
                time_cap: *race_time_cap,
            },
            cmds,
        );
        let l = ui.label("cap");
        ui.add(
            egui::DragValue::new(race_time_cap)
                .range(0.1..=600.0)
                .speed(0.1)
                .suffix(" s"),
        )
        .labelled_by(l.id)
        .on_hover_text("Time cap of each iterative solver in the race");
    });
}

/// Sweeps per frame, and the growth solver.
fn pace_ui(ui: &mut Ui, v: &AppView, cmds: &mut Vec<Command>) {
    let iterative = v.scene.solver.kind != SolverKind::Direct;
    if iterative {
        ui.horizontal(|ui| {
            let mut paced = v.run.pace.is_some();
            let mut n = v.run.pace.unwrap_or(10);
            let check = ui
                .checkbox(&mut paced, "Sweeps per frame")
                .on_hover_text(
                    "Slow the relaxation down to watch the stress front move: this many sweeps per frame (unticked: as many as the frame allows)",
                );
            let dragged = ui
                .add_enabled(paced, egui::DragValue::new(&mut n).range(1..=10_000))
                .labelled_by(check.id)
                .changed();
            let changed = check.changed();
            if changed || dragged {
                cmds.push(Command::SetPace(paced.then_some(n)));
            }
        });
    }
    if v.scene.solver.kind == SolverKind::Automaton
        && v.scene.solver.contact_update == ContactUpdate::Outer
    {
        let mut on = v.run.accelerate_growth;
        if ui
            .checkbox(&mut on, "Accelerate growth (multigrid-CG)")
            .on_hover_text(
                "Growth solves with the automaton's sweeps inside multigrid-preconditioned CG (tens of iterations instead of tens of thousands of sweeps); untick for the plain automaton. Applies from the next growth run (Reset).",
            )
            .changed()
        {
            cmds.push(Command::SetAccelerateGrowth(on));
        }
    }
    if iterative {
        ui.weak(format!(
            "Growth solves to |r|/|f| ≤ {:.0e} (K_I, K_II within 1e-6 of the direct solver on the default scene), warm-started from the last state.",
            crate::run::host::GROWTH_TOLERANCE
        ));
    }
}

/// The race under way: progress, how long it takes at most, and Cancel.
fn race_progress_ui(ui: &mut Ui, v: &AppView, cmds: &mut Vec<Command>) {
    let Some(race) = v.race else {
        return;
    };
    let Some((run, progress)) = race.status() else {
        return;
    };
    ui.add(ProgressBar::new(progress).text(format!(
        "Race: {} ({})",
        run.racer.name,
        units::seconds(run.wall_seconds())
    )));
    ui.horizontal_wrapped(|ui| {
        ui.label(format!(
            "About {} in all: {} solvers × {} cap",
            units::seconds(race.estimate_seconds()),
            race.iterative_runs(),
            units::seconds(race.time_cap)
        ));
        if ui.button("Cancel race").clicked() {
            cmds.push(Command::CancelRace);
        }
    });
}

fn status_ui(ui: &mut Ui, v: &AppView, cmds: &mut Vec<Command>) {
    let view = &v.solution;
    if v.run.dragging && v.run.solves_on_release {
        ui.label("Dragging — the field follows the pointer.");
    } else if v.run.dragging {
        ui.label("Dragging — press Solve after release.");
    } else if v.run.stale && !view.solved {
        ui.colored_label(ui.visuals().warn_fg_color, "Scene changed — press Solve.");
    }
    match v.run.mode {
        RunMode::Paused | RunMode::SolvingDrag => {}
        RunMode::Relaxing => {
            // the direct solver solves, in its own unit: it used to say
            // "Relaxing… sweep 0" for its first second
            let direct = view.solver == SolverKind::Direct;
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label(if direct { "Solving…" } else { "Relaxing…" });
            });
            if let Some(r) = view.relax {
                // progress on a log scale from residual 1 to the tolerance
                let goal = v.scene.solver.tolerance.max(1e-300).log10();
                let done = (r.residual.max(1e-300).log10() / goal).clamp(0.0, 1.0) as f32;
                ui.add(ProgressBar::new(done).text(format!(
                    "{}, residual {:.2e}",
                    iterations(view.solver, r.iterations),
                    r.residual
                )));
            }
        }
        RunMode::Growing | RunMode::GrowingOne => {
            ui.horizontal(|ui| {
                super::widgets::slow_spinner(ui);
                ui.label(format!("Growing ({})…", solver_name(v.run.growth_solver)));
            });
            // under load control λ is the share of the ramp done; under
            // critical control λ_cr can be any value, and only the steps
            // have a bound
            let g = &v.scene.growth;
            let (done, text) = match g.control {
                GrowthControl::Load => (
                    view.load_factor,
                    format!("load factor λ = {:.3} of 1", view.load_factor),
                ),
                GrowthControl::Critical => (
                    view.steps_done as f64 / g.max_steps.max(1) as f64,
                    format!(
                        "{} of at most {} steps (growth.max_steps)",
                        view.steps_done, g.max_steps
                    ),
                ),
            };
            ui.add(ProgressBar::new(done.clamp(0.0, 1.0) as f32).text(text));
            ui.label(growth_progress(view));
        }
    }
    unconverged_ui(ui, view);
    if let Some(p) = v.run.field_progress {
        ui.add(ProgressBar::new(p).text("sampling the field"));
    }
    race_progress_ui(ui, v, cmds);
    if let Some(cap) = &view.load_cap {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!(
                "Growth stopped at the load cap: no free tip meets its criterion at any \
                 λ below {} (growth.max_load_factor).",
                cap.max_load_factor
            ),
        );
    }
    if let Some(piece) = view.free_piece.as_ref().filter(|_| view.split) {
        // after growth the canvas keeps the last step's solved field; a
        // run that ended with the specimen cut through did not go wrong
        let (kept, colour) = if view.history.is_empty() {
            (String::new(), ui.visuals().warn_fg_color)
        } else {
            (
                format!(
                    " The field shown is the last solved state, at λ = {:.3}.",
                    view.load_factor
                ),
                ui.visuals().text_color(),
            )
        };
        ui.colored_label(
            colour,
            format!(
                "The specimen is cut through: {}, so the final cracks have no solution.{kept}",
                free_piece_words(piece, view)
            ),
        );
    } else if view.split {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!(
                "Specimen split: the final cracks cut it through, so they cannot be solved. The field shown is the last solved state, at λ = {:.3}.",
                view.load_factor
            ),
        );
    }
    Grid::new("status").num_columns(2).show(ui, |ui| {
        // values wrap at the panel's edge (at 1400 × 900 with text at 150 %
        // "median 0.76 × strength" ran past the window); the names keep
        // their line (`key`)
        ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Wrap);
        key(ui, "Solved");
        let capped = view.relax.is_some_and(|r| r.finished && !r.converged);
        ui.label(match (view.solved, view.split) {
            (true, _) if capped => "no (not converged)",
            (true, _) => "yes",
            (false, true) => "no (specimen split)",
            (false, false) => "no",
        });
        ui.end_row();
        if let Some(r) = view.relax {
            // the count and the residual on rows of their own, and the
            // verdict on a third: on one line they widened the panel past
            // the window, and the text below wrapped as wide, off screen
            let count = iterations(view.solver, r.iterations);
            let residual = format!("{:.2e}", r.residual);
            key(ui, "Last solve");
            if r.finished && !r.converged {
                let warn = ui.visuals().warn_fg_color;
                ui.colored_label(warn, count);
                ui.end_row();
                key(ui, "Residual");
                ui.colored_label(warn, residual);
                ui.end_row();
                key(ui, "");
                ui.colored_label(warn, "NOT converged");
            } else {
                ui.label(count);
                ui.end_row();
                key(ui, "Residual");
                ui.label(residual);
            }
            ui.end_row();
        }
        if let Some(s) = v.run.last_solve_seconds {
            key(ui, "Last build + solve");
            ui.label(format!(
                "{} + {}",
                units::seconds(v.run.last_build_seconds),
                units::seconds(s)
            ));
            ui.end_row();
        }
        // the steps counted as the plots and reports count them (a
        // reopened run's earlier steps included), on λ's row: a row of
        // their own pushed the tip inspector's plot past the window
        key(ui, "Load factor λ");
        // no load is applied to an unsolved, edited scene: no 0.000
        let lambda = if view.solved || view.live || !view.history.is_empty() {
            format!("{:.3}", view.load_factor)
        } else {
            "–".to_owned()
        };
        let steps = match view.steps_done {
            1 => "1 step".to_owned(),
            n => format!("{n} steps"),
        };
        ui.label(format!("{lambda} ({steps})"));
        ui.end_row();
        if let Some(r) = view.intact_rock {
            intact_rock_row(ui, &r);
        }
        if let Some(o) = view.outcome {
            key(ui, "Outcome");
            let (text, mut meaning) = outcome_text(o, &v.scene.growth);
            if o == Outcome::Completed
                && let Some((gap, side)) = nearest_edge(&view.tips, v.scene)
            {
                meaning = format!(
                    "{meaning} The free tip nearest a boundary is {} ({:.1} elements) from the {side} edge.",
                    units::mm(gap),
                    gap / v.scene.element_size()
                );
            }
            if o == Outcome::NotConverged {
                let why = view.history.iter().rev().find_map(|s| s.failure.clone());
                ui.colored_label(ui.visuals().warn_fg_color, text)
                    .on_hover_text(why.unwrap_or_default());
            } else {
                ui.label(text).on_hover_text(meaning);
            }
            ui.end_row();
        }
        if !view.contact.is_empty() {
            let count = |s| view.contact.iter().filter(|c| c.state == s).count();
            key(ui, "Contact points");
            let counts = ui.label(format!(
                "{} open, {} stick, {} slip",
                count(cdca::ContactState::Open),
                count(cdca::ContactState::Stick),
                count(cdca::ContactState::Slip)
            ));
            if view.second_start == SecondStart::Done && view.other_solution.is_none() {
                // no news, no row: the hover says the check was made
                counts.on_hover_text(
                    "The only solution: solved again from the opposite start, bonded faces \
                     (every point stuck, friction limits far above any traction), it gave the \
                     same contact counts and K (within 1e-6). Coulomb friction need not have \
                     one solution; here it has.",
                );
            }
            ui.end_row();
        }
        match (view.second_start, &view.other_solution) {
            (SecondStart::Running, _) => {
                key(ui, "Solutions");
                ui.label("checking from bonded faces…");
                ui.end_row();
            }
            (SecondStart::Done, Some(sentence)) => {
                key(ui, "Solutions");
                ui.colored_label(ui.visuals().warn_fg_color, "more than one (hover)")
                    .on_hover_text(sentence);
                ui.end_row();
            }
            _ => {}
        }
    });
    if let Some(r) = view.intact_rock {
        ui.label(intact_rock_words(
            &r,
            view.load_factor,
            view.intact_load_factor,
            v.scene.growth.intact_rock,
        ));
    }
    stepped_around_ui(ui, &view.history);
}

/// The free tip nearest the specimen's boundary: its distance (m) and the
/// side (`None` without free tips). A run that ends `completed` often has a
/// wing an element or two short of an edge, which reads as failed.
fn nearest_edge(tips: &[TipReport], scene: &SceneFile) -> Option<(f64, &'static str)> {
    let (w, h) = (scene.specimen.width, scene.specimen.height);
    tips.iter()
        .flat_map(|t| {
            [
                (t.x, "left"),
                (w - t.x, "right"),
                (t.y, "bottom"),
                (h - t.y, "top"),
            ]
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// How a growth run ended, as the report spells it (`outcome`), and what
/// that means for this scene's growth control (shown on hover).
fn outcome_text(o: Outcome, growth: &GrowthSpec) -> (&'static str, String) {
    match o {
        Outcome::Completed if growth.control == GrowthControl::Critical => (
            "completed",
            format!(
                "No free tip meets its criterion up to λ = {} (growth.max_load_factor).",
                growth.max_load_factor
            ),
        ),
        Outcome::Completed => (
            "completed",
            format!(
                "All {} load steps applied (growth.load_steps).",
                growth.load_steps
            ),
        ),
        Outcome::Unstable => (
            "unstable",
            format!(
                "A tip went on growing at one load for {} steps (growth.max_growth_per_step): \
                 unstable growth.",
                growth.max_growth_per_step
            ),
        ),
        Outcome::Through => (
            "through",
            "The cracks run through the specimen: it has failed.".to_owned(),
        ),
        Outcome::MaxSteps => (
            "max_steps",
            format!(
                "Stopped after {} steps (growth.max_steps).",
                growth.max_steps
            ),
        ),
        Outcome::NotConverged => ("not_converged", String::new()),
        Outcome::Error => (
            "error",
            "A step's solve failed with an error: growth stopped before it.".to_owned(),
        ),
    }
}

/// Steps whose λ_cr search moved away from a trial that did not converge
/// (`unsolved_trials`): said under the status, the loads on hover.
fn stepped_around_ui(ui: &mut Ui, history: &[cdca::report::GrowthStepReport]) {
    let steps: Vec<String> = history
        .iter()
        .filter(|s| !s.unsolved_trials.is_empty())
        .map(|s| {
            let at: Vec<String> = s
                .unsolved_trials
                .iter()
                .map(|l| format!("{l:.4}"))
                .collect();
            format!("step {}: λ = {}", s.step, at.join(", "))
        })
        .collect();
    if !steps.is_empty() {
        ui.weak(format!(
            "{} growth step(s) stepped around a λ_cr trial whose solve did not converge; \
             λ_cr is a converged trial (hover for the loads).",
            steps.len()
        ))
        .on_hover_text(steps.join("\n"));
    }
}

/// The rock away from the cracks against its own strength: its median
/// utilisation, in the warning colour once it has failed there.
/// A status row's name, on one line whatever the grid's wrapping.
fn key(ui: &mut Ui, name: &str) -> egui::Response {
    ui.add(egui::Label::new(name).extend())
}

fn intact_rock_row(ui: &mut Ui, r: &cdca::report::IntactRockReport) {
    let why = format!(
        "Median over the elements no crack touches of u = max((σ1 − N_φ σ3)/σ_c, −σ3/σ_t), \
         Mohr–Coulomb with a tension cut-off from the rock's c, φ and σ_t \
         (σ_c = {:.1} MPa). u ≥ 1: the uncracked rock would fail there. The crack-tip \
         criterion does not check it; growth goes on.",
        r.ucs / units::PA_PER_MPA
    );
    key(ui, "Intact rock").on_hover_text(&why);
    let text = format!("median {:.2} × strength", r.utilisation);
    if r.utilisation >= 1.0 {
        ui.colored_label(ui.visuals().warn_fg_color, text)
    } else {
        ui.label(text)
    }
    .on_hover_text(why);
    ui.end_row();
}

/// A piece cut off by the final cracks, in the UI's words: the cracks by
/// their Scene panel names, its size in elements, its centre in mm.
fn free_piece_words(
    piece: &cdca::report::FreePieceReport,
    view: &crate::results::solution::SolutionView,
) -> String {
    let mut names: Vec<String> = piece.cracks.iter().map(|&c| view.crack_name(c)).collect();
    names.dedup();
    let by = if names.is_empty() {
        "the cracks".to_owned()
    } else {
        names.join(" and ")
    };
    let elements = if piece.elements == 1 {
        "1 element".to_owned()
    } else {
        format!("{} elements", piece.elements)
    };
    format!(
        "{by} cut off a piece of {elements} around ({}, {}) that nothing holds",
        units::mm(piece.centroid[0]),
        units::mm(piece.centroid[1])
    )
}

/// The intact rock's number in words, under the status: how much of the
/// uncracked area is past its strength at this load, the median's
/// utilisation, and, once known (after the first growth step), the one λ of
/// the rock's strength the workbench shows: the uncracked specimen's. "0.98
/// × strength, 47% failed" used to read as a contradiction, "1.26 ×
/// strength" as a specimen failed before any crack grew, and the median's
/// λ / u (0.79, then 0.78) as a second strength beside the plot's 0.802.
fn intact_rock_words(
    r: &cdca::report::IntactRockReport,
    load_factor: f64,
    uncracked: Option<f64>,
    model: IntactRock,
) -> String {
    let past = format!(
        "{:.0}% of the uncracked rock is past its strength at λ = {load_factor:.2}, its median at {:.2} × strength",
        100.0 * r.failed_fraction,
        r.utilisation
    );
    let checked = match model {
        IntactRock::Nucleate => "Growth starts a crack where its reading over r0 first reaches it.",
        IntactRock::Ignore => {
            "The paper's model (growth.intact_rock \"ignore\") does not check it."
        }
    };
    match uncracked {
        Some(l) => format!(
            "Intact rock: {past}. The uncracked specimen reaches its strength at λ = {l:.3}. {checked}"
        ),
        None => format!("Intact rock: {past}. {checked}"),
    }
}

/// `n` iterations of a solve by `kind`, in that solver's own unit: the
/// automaton's sweeps, conjugate-gradient iterations, or the direct
/// solver's linear solves (one per contact iteration).
fn iterations(kind: SolverKind, n: usize) -> String {
    let unit = match (kind, n) {
        (SolverKind::Automaton, 1) => "sweep",
        (SolverKind::Automaton, _) => "sweeps",
        (SolverKind::Cg | SolverKind::Multigrid, 1) => "CG iteration",
        (SolverKind::Cg | SolverKind::Multigrid, _) => "CG iterations",
        (SolverKind::Direct, 1) => "linear solve",
        (SolverKind::Direct, _) => "linear solves",
    };
    format!("{n} {unit}")
}

/// The growth run's progress line: step, λ, iterations and residual of the
/// step's solve.
fn growth_progress(view: &crate::results::solution::SolutionView) -> String {
    let step = view.steps_done + 1;
    if let Some(done) = view.rebuild {
        return format!(
            "step {step}: preparing the cracked plate (stiffness, pattern, tip domains), {:.0}%",
            100.0 * done
        );
    }
    match view.last_residual {
        Some(r) => format!(
            "step {step}, λ = {:.3}, {}, residual {:.2e}",
            view.load_factor,
            iterations(view.solver, r.iteration),
            r.residual
        ),
        None => format!("step {step}, λ = {:.3}", view.load_factor),
    }
}

/// Results that did not converge, in the warning colour with the
/// iteration count and residual: a relaxation that ended at a cap, a growth
/// step whose solve did not converge.
fn unconverged_ui(ui: &mut Ui, view: &crate::results::solution::SolutionView) {
    let warn = ui.visuals().warn_fg_color;
    if let Some(r) = view.relax.filter(|r| r.finished && !r.converged) {
        // the test that failed in the solver's words (as `cdca solve`
        // prints it), else the count and residual
        let why = view.failure.clone().unwrap_or_else(|| {
            format!(
                "the solve stopped at a cap after {}, residual {:.2e}",
                iterations(view.solver, r.iterations),
                r.residual
            )
        });
        ui.colored_label(
            warn,
            format!("Not converged: {why}. The field shown is not a solution."),
        );
    }
    if let Some(s) = view.history.iter().rev().find(|s| !s.converged) {
        ui.colored_label(
            warn,
            format!(
                "Growth step {} did not converge ({} iterations, {} contact iterations, contact change {:.2e}); growth stopped there.",
                s.step, s.solver_iterations, s.contact.iterations, s.contact.residual
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each solver counts in its own unit: with the direct solver a contact
    /// solve is a number of linear solves, not sweeps.
    #[test]
    fn iterations_are_named_by_the_solver() {
        assert_eq!(iterations(SolverKind::Direct, 13), "13 linear solves");
        assert_eq!(iterations(SolverKind::Direct, 1), "1 linear solve");
        assert_eq!(iterations(SolverKind::Automaton, 1), "1 sweep");
        assert_eq!(iterations(SolverKind::Automaton, 2400), "2400 sweeps");
        assert_eq!(iterations(SolverKind::Multigrid, 13), "13 CG iterations");
        assert_eq!(iterations(SolverKind::Cg, 1), "1 CG iteration");
    }

    /// The nearest edge is found on every side, in the scene's coordinates
    /// (origin at the bottom-left corner).
    #[test]
    fn the_nearest_edge_is_the_closest_side_of_any_free_tip() {
        let scene = SceneFile::from_json(include_str!(
            "../../assets/scenes/specimen_single_flaw.json"
        ))
        .expect("bundled scene");
        let tip = |x: f64, y: f64| TipReport {
            x,
            y,
            ..TipReport::default()
        };
        assert_eq!(nearest_edge(&[], &scene), None);
        let (gap, side) =
            nearest_edge(&[tip(0.015, 0.0296), tip(0.010, 0.012)], &scene).expect("two tips");
        assert!(
            (gap - 0.0004).abs() < 1e-12 && side == "top",
            "{gap} {side}"
        );
        let (gap, side) =
            nearest_edge(&[tip(0.0007, 0.015), tip(0.02, 0.0009)], &scene).expect("two tips");
        assert!(
            (gap - 0.0007).abs() < 1e-12 && side == "left",
            "{gap} {side}"
        );
        let (gap, side) = nearest_edge(&[tip(0.0293, 0.0105)], &scene).expect("one tip");
        assert!(
            (gap - 0.0007).abs() < 1e-12 && side == "right",
            "{gap} {side}"
        );
    }
}
