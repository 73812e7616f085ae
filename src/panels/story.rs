//! The run's story above the plots: how the run went, in time order, and
//! how it ended. It sits with the plots (not in the Solver panel, which a
//! phone hides and a short window scrolls past), so that the story and the
//! selected plot show together at any window size.

use egui::Ui;

use crate::view::AppView;

/// The story of the ended run, its lines wrapped to the panel's width;
/// nothing while a run goes on or before one ended.
pub fn story_ui(ui: &mut Ui, v: &AppView) {
    let view = v.solution;
    let Some(story) = crate::story::story(view, v.scene) else {
        return;
    };
    let colour = if story.went_wrong {
        ui.visuals().warn_fg_color
    } else {
        ui.visuals().strong_text_color()
    };
    let told = ui.vertical(|ui| {
        for line in &story.lines {
            ui.add(egui::Label::new(egui::RichText::new(line).color(colour)).wrap());
        }
    });
    // the report's note says when the peak is only a bound
    if let Some(s) = &view.strength {
        told.response.on_hover_text(&s.note);
    }
    ui.separator();
}
