//! The replay bar above the canvas: after a growth run, a step slider and
//! one button per event (the first wing, each secondary crack, each crack
//! started in the intact rock, the link) that shows the run as it stood
//! after that step. Where the buttons would take more than one row, the
//! events are a drop-down list instead: twelve rock cracks took three rows
//! at 1024 × 640 and four of a phone's height.

use egui::Ui;

use crate::results::replay::{Replay, marks};
use crate::results::solution::SolutionView;
use crate::state::command::Command;

/// The events list's text while the step shown is none of them.
pub const REPLAY_EVENTS_HINT: &str = "Go to an event";

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
    let link = view.coalescence.as_ref().map(|c| c.step);
    let marks: Vec<(usize, String)> = marks(&view.history, view, link)
        .into_iter()
        .filter(|m| replay.at(m.step).is_some())
        .map(|m| (m.step, format!("{}: {}", m.step, m.text)))
        .collect();
    let at = shown.unwrap_or(last);
    let mut go = |step: usize| cmds.push(Command::Replay((step != last).then_some(step)));
    if marks.is_empty() {
        return;
    }
    if !in_one_row(ui, &marks) {
        let selected = marks
            .iter()
            .find(|(step, _)| *step == at)
            .map_or(REPLAY_EVENTS_HINT, |(_, text)| text.as_str());
        let list = egui::ComboBox::from_id_salt("replay events")
            .selected_text(selected)
            // as tall as the window allows: a run has tens of events
            .height(ui.ctx().content_rect().height())
            .show_ui(ui, |ui| {
                for (step, text) in &marks {
                    if ui.selectable_label(at == *step, text).clicked() {
                        go(*step);
                    }
                }
            });
        super::widgets::name_list(&list.response, "Replay events", selected);
        return;
    }
    // the marks in a row of their own
    ui.horizontal(|ui| {
        for (step, text) in &marks {
            if ui
                .selectable_label(at == *step, egui::RichText::new(text).small())
                .clicked()
            {
                go(*step);
            }
        }
    });
}

/// Whether the marks' buttons (small text) fit in one row of `ui`.
fn in_one_row(ui: &Ui, marks: &[(usize, String)]) -> bool {
    let spacing = ui.spacing();
    let width: f32 = marks
        .iter()
        .map(|(_, text)| {
            super::widgets::text_width(ui, text, &egui::TextStyle::Small)
                + 2.0 * spacing.button_padding.x
                + spacing.item_spacing.x
        })
        .sum();
    width <= ui.available_width()
}
