//! Small editing widgets: numbers shown in display units and written back
//! in SI, optional values with an "auto" box, and a tracker that turns
//! widget responses into one scene edit per frame. A value outside a
//! widget's range (from a scene file) is shown as it is, not clamped: only
//! what the user edits is held to the range, so opening a scene never
//! changes it.

use std::ops::RangeInclusive;

use egui::{DragValue, Response, Ui};

/// Collects what the scene widgets did this frame.
#[derive(Debug, Default)]
pub struct EditTracker {
    /// A widget is being dragged (the edit is not final yet).
    pub ongoing: bool,
    /// A drag ended this frame.
    pub ended: bool,
}

impl EditTracker {
    pub fn track(&mut self, r: &Response) {
        self.ongoing |= r.dragged();
        self.ended |= r.drag_stopped();
    }
}

/// One grid row: `label` and a drag value showing `value_si / per_unit` with
/// `unit`; the edited number is written back in SI.
pub fn quantity_row(
    ui: &mut Ui,
    t: &mut EditTracker,
    label: &str,
    value_si: &mut f64,
    per_unit: f64,
    unit: &str,
    range: RangeInclusive<f64>,
) {
    let l = ui.label(label);
    let mut v = *value_si / per_unit;
    let speed = (v.abs() * 0.005).max(1e-3);
    let suffix = if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    };
    let r = ui
        .add(
            DragValue::new(&mut v)
                .speed(speed)
                .range(range)
                .clamp_existing_to_range(false)
                .suffix(suffix)
                .custom_formatter(|v, _| crate::units::significant(v)),
        )
        .labelled_by(l.id);
    if r.changed() {
        *value_si = v * per_unit;
    }
    t.track(&r);
    ui.end_row();
}

/// A grid row for a count.
pub fn count_row(
    ui: &mut Ui,
    t: &mut EditTracker,
    label: &str,
    value: &mut usize,
    range: RangeInclusive<usize>,
) {
    let l = ui.label(label);
    let r = ui
        .add(
            DragValue::new(value)
                .speed(0.2)
                .range(range)
                .clamp_existing_to_range(false),
        )
        .labelled_by(l.id);
    t.track(&r);
    ui.end_row();
}

/// A grid row for an optional quantity: an "auto" check box (None) or a
/// value. `auto_value_si` is what "auto" stands for, used as the starting
/// value when the box is cleared.
pub fn optional_row(
    ui: &mut Ui,
    t: &mut EditTracker,
    label: &str,
    value_si: &mut Option<f64>,
    auto_value_si: f64,
    per_unit: f64,
    unit: &str,
) {
    let l = ui.label(label);
    ui.horizontal(|ui| {
        let mut auto = value_si.is_none();
        if ui.checkbox(&mut auto, "auto").changed() {
            *value_si = if auto { None } else { Some(auto_value_si) };
        }
        if let Some(v_si) = value_si {
            let mut v = *v_si / per_unit;
            let speed = (v.abs() * 0.005).max(1e-3);
            let r = ui
                .add(
                    DragValue::new(&mut v)
                        .speed(speed)
                        .range(0.0..=f64::MAX)
                        .clamp_existing_to_range(false)
                        .suffix(format!(" {unit}")),
                )
                .labelled_by(l.id);
            if r.changed() {
                *v_si = v * per_unit;
            }
            t.track(&r);
        } else {
            ui.weak(format!(
                "{} {unit}",
                crate::units::significant(auto_value_si / per_unit)
            ));
        }
    });
    ui.end_row();
}

/// A combo box over `options` with their labels.
pub fn choice<T: PartialEq + Copy>(
    ui: &mut Ui,
    label: &str,
    value: &mut T,
    options: &[(T, &str)],
) -> Response {
    let current = options
        .iter()
        .find(|(o, _)| o == value)
        .map_or("?", |(_, l)| *l);
    egui::ComboBox::from_label(label)
        .selected_text(current)
        .show_ui(ui, |ui| {
            for (o, l) in options {
                ui.selectable_value(value, *o, *l);
            }
        })
        .response
}

/// Frames a second of [`slow_spinner`].
const SLOW_SPINNER_HZ: f32 = 4.0;

/// A spinner that asks for a frame 4 times a second, not every frame as
/// egui's does: natively a growth run works on its own thread, and a UI
/// repainting continuously took most of a core from it where painting is
/// done in software (Xvfb), for nothing the run shows. In a browser the
/// run works between frames on the one thread (`web_work`), and at 10
/// frames a second software painting took most of that thread: Run growth
/// on the stepped pair took 21.1 s against 17.7 s at 4 (one run each).
pub fn slow_spinner(ui: &mut Ui) -> Response {
    let size = ui.style().spacing.interact_size.y;
    let (rect, response) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
    response.widget_info(|| egui::WidgetInfo::new(egui::Role::ProgressIndicator));
    if ui.is_rect_visible(rect) {
        ui.ctx()
            .request_repaint_after(std::time::Duration::from_secs_f32(1.0 / SLOW_SPINNER_HZ));
        let time = ui.input(|i| i.time);
        // the angle steps with the frames asked for
        let time = (time * f64::from(SLOW_SPINNER_HZ)).floor() / f64::from(SLOW_SPINNER_HZ);
        let start = time * std::f64::consts::TAU;
        let end = start + 240f64.to_radians() * time.sin();
        let radius = rect.height().min(rect.width()) * 0.5 - 2.0;
        let n = 24;
        let points: Vec<egui::Pos2> = (0..n)
            .map(|i| {
                let angle = egui::emath::lerp(start..=end, f64::from(i) / f64::from(n));
                let (sin, cos) = angle.sin_cos();
                rect.center() + radius * egui::vec2(cos as f32, sin as f32)
            })
            .collect();
        ui.painter().add(egui::Shape::line(
            points,
            egui::Stroke::new(3.0, ui.visuals().strong_text_color()),
        ));
    }
    response
}

/// Gives a drop-down list shown without its label (to keep a narrow row)
/// the accessible name `name`, its selected text `value` as its value.
pub fn name_list(response: &egui::Response, name: &str, value: &str) {
    response.widget_info(|| {
        let mut info = egui::WidgetInfo::labeled(egui::Role::ComboBox, true, name);
        info.current_text_value = Some(value.to_owned());
        info
    });
}
