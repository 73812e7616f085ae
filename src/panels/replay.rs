//! The replay bar above the canvas: after a growth run, a step slider and
//! one button per event (the first wing, each secondary crack, each crack
//! started in the intact rock, the link) that shows the run as it stood
//! after that step.

use egui::Ui;

use crate::command::Command;
use crate::replay::{Replay, marks};
use crate::solution::SolutionView;

/// The bar, when the run stored at least two steps.
pub fn replay_ui(
    ui: &mut Ui,
    replay: &Replay,
    view: &SolutionView,
    shown: Option<usize>,
    cmds: &mut Vec<Command>,
) {
    let steps: Vec<usize> = replay.snapshots.iter().map(|s| s.step).collect();
    let (Some(&first), Some(&last)) = (steps.first(), steps.last()) else {
        return;
    };
    if steps.len() < 2 {
        return;
    }
    ui.horizontal(|ui| {
        let mut step = shown.unwrap_or(last);
        let label = ui.label("Replay").on_hover_text(
            "The run as it stood after each growth step: its cracks, and the contact \
             states, tips and field of the step's solve at its load (kept as the run \
             passed, not solved again).",
        );
        let slider = ui
            .add(egui::Slider::new(&mut step, first..=last).show_value(false))
            .labelled_by(label.id);
        if slider.changed() {
            cmds.push(Command::Replay((step != last).then_some(step)));
        }
        let lambda = replay
            .at(step)
            .map_or_else(String::new, |s| format!(", λ = {:.3}", s.view.load_factor));
        ui.label(format!("step {step} of {last}{lambda}"));
        if replay.at(step).is_some_and(|s| s.field.is_none()) {
            ui.weak("(no field kept for this step)");
        }
        if shown.is_some() && ui.button("Back to the end").clicked() {
            cmds.push(Command::Replay(None));
        }
    });
    // the marks on their own rows
    ui.horizontal_wrapped(|ui| {
        let link = view.coalescence.as_ref().map(|c| c.step);
        for m in marks(&view.history, view, link) {
            if replay.at(m.step).is_none() {
                continue;
            }
            let label = format!("{}: {}", m.step, m.text);
            let on = shown.unwrap_or(last) == m.step;
            if ui
                .selectable_label(on, egui::RichText::new(label).small())
                .clicked()
            {
                cmds.push(Command::Replay((m.step != last).then_some(m.step)));
            }
        }
    });
}
