//! The compact run bar shown while the Solver panel is hidden (on a phone
//! it always is at first): Solve, Run growth or Pause, Grow one step, and
//! the load factor and steps done, so that a run can be watched and driven
//! without the panels. Editing stays in the panels. After a run the replay
//! bar shows the step and its λ, and the run bar leaves them out: the bar
//! then keeps one row of a phone's height.

use egui::{Button, Ui};

use crate::run::RunMode;
use crate::state::command::Command;
use crate::state::job::Job;
use crate::state::view::AppView;

pub fn run_bar_ui(ui: &mut Ui, v: &AppView, replay_shown: bool, cmds: &mut Vec<Command>) {
    let ended = v.solution.outcome.is_some();
    let growing = v.run.job == Some(Job::Growth);
    ui.horizontal_wrapped(|ui| {
        if ui.button("Solve").clicked() {
            cmds.push(Command::Solve);
        }
        if growing || !matches!(v.run.mode, RunMode::Paused | RunMode::SolvingDrag) {
            if ui
                .button("Pause")
                .on_hover_text("Stop the solve or growth run where it is")
                .clicked()
            {
                cmds.push(Command::Pause);
            }
        } else if ui
            .add_enabled(!ended, Button::new("Run growth"))
            .on_hover_text("Grow until the run ends, animated")
            .on_disabled_hover_text("Growth has ended; the Solver panel's Reset goes back.")
            .clicked()
        {
            cmds.push(Command::RunGrowth);
        }
        if ui
            .add_enabled(!ended && !growing, Button::new("Grow one step"))
            .clicked()
        {
            cmds.push(Command::GrowOne);
        }
        if !replay_shown {
            ui.label(format!(
                "λ = {:.3}   steps {}",
                v.solution.load_factor, v.solution.steps_done
            ));
        }
    });
}
