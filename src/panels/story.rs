//! The run's story above the plots: how the run went, in time order, and
//! how it ended. It sits with the plots (not in the Solver panel, which a
//! phone hides and a short window scrolls past), so that the story and the
//! selected plot show together at any window size.

use egui::Ui;

use crate::state::view::AppView;

/// Window width below which the story is told in small text, points.
const PHONE_WIDTH: f32 = 500.0;

/// The story of the ended run, its lines wrapped to the panel's width,
/// and where it shows; nothing while a run goes on or before one ended.
pub fn story_ui(ui: &mut Ui, v: &AppView) -> Option<egui::Rect> {
    let view = v.solution;
    let story = crate::results::story::story(view, v.scene)?;
    let colour = if story.went_wrong {
        ui.visuals().warn_fg_color
    } else {
        ui.visuals().strong_text_color()
    };
    // in a phone's window the story takes small text: in body text its
    // nine lines left a 360 × 640 window no room for a whole plot
    let small = ui.ctx().content_rect().width() < PHONE_WIDTH;
    let told = ui.vertical(|ui| {
        for line in &story.lines {
            let text = egui::RichText::new(line).color(colour);
            let text = if small { text.small() } else { text };
            ui.add(egui::Label::new(text).wrap());
        }
    });
    let rect = told.response.rect;
    // the report's note says when the peak is only a bound
    if let Some(s) = &view.strength {
        told.response.on_hover_text(&s.note);
    }
    ui.separator();
    Some(rect)
}
