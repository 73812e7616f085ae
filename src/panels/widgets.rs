//! Small editing widgets: numbers shown in display units and written back
//! in SI, optional values with an "auto" box, and a tracker that turns
//! widget responses into one scene edit per frame. A value outside a
//! widget's range (from a scene file) is shown as it is, not clamped: only
//! a drag is held to the range. A typed value is never clamped nor
//! dropped: the tracker holds it, and the panel takes it or refuses it
//! with a message ([`crate::panels::typed`]).

use std::cell::RefCell;
use std::ops::RangeInclusive;

use egui::{DragValue, Response, Ui};

use crate::panels::typed::{self, Shown};

/// Collects what the scene widgets did this frame.
#[derive(Debug, Default)]
pub struct EditTracker {
    /// A widget is being dragged (the edit is not final yet).
    pub ongoing: bool,
    /// A drag ended this frame.
    pub ended: bool,
    /// The group of the rows being drawn ("Crack 1"): their names in
    /// messages.
    pub group: Option<String>,
    /// The value typed this frame, if any.
    pub typed: Option<Typed>,
}

/// A value typed into a field and written into the draft scene, or
/// refused already (not a number).
#[derive(Debug)]
pub struct Typed {
    /// The field's name in messages ("Crack 1, friction μ").
    pub name: String,
    /// The value the field keeps if the typed one is refused, with its
    /// unit.
    pub kept: String,
    /// Why the field itself refuses the typed value: not a number, or
    /// outside the field's range.
    pub refused: Option<String>,
    /// Whether the value was written into the draft scene (it is a
    /// number): the solver crate's checks of that scene then speak
    /// before the field's range.
    pub in_scene: bool,
}

impl Typed {
    /// The value typed into the field `shown`, which keeps `kept`: `read`
    /// is the number in SI (written into the draft) or why it is not
    /// one; a number is held to the field's `range` (display units).
    fn new(shown: Shown, kept: String, read: Result<f64, String>, range: (f64, f64)) -> Self {
        let (refused, in_scene) = match read {
            Ok(si) => (typed::outside_range(&shown, si, range, &kept), true),
            Err(refusal) => (Some(refusal), false),
        };
        Self {
            name: shown.name,
            kept,
            refused,
            in_scene,
        }
    }
}

impl EditTracker {
    pub fn track(&mut self, r: &Response) {
        self.ongoing |= r.dragged();
        self.ended |= r.drag_stopped();
    }

    fn shown(&self, label: &str, per_unit: f64, unit: &'static str) -> Shown {
        Shown {
            name: typed::full_name(self.group.as_deref(), label),
            per_unit,
            unit,
        }
    }
}

/// A number field whose typed text is handed back in `text` instead of
/// parsed by egui (which clamps it to the range, or drops it without a
/// word when it does not parse); a drag still moves within the range.
fn handing_back_text<'a>(drag: DragValue<'a>, text: &'a RefCell<Option<String>>) -> DragValue<'a> {
    drag.clamp_existing_to_range(false).custom_parser(|t| {
        text.replace(Some(t.to_owned()));
        None
    })
}

/// One grid row: `label` and a drag value showing `value_si / per_unit` with
/// `unit`; the edited number is written back in SI.
pub fn quantity_row(
    ui: &mut Ui,
    t: &mut EditTracker,
    label: &str,
    value_si: &mut f64,
    per_unit: f64,
    unit: &'static str,
    range: RangeInclusive<f64>,
) {
    let l = ui.label(label);
    let unit = (per_unit, unit);
    quantity_field(ui, t, l.id, label, value_si, unit, range, true);
    ui.end_row();
}

/// The number field of [`quantity_row`] and [`optional_row`], in four
/// significant digits where `significant` (else as egui writes it).
#[allow(clippy::too_many_arguments)] // one row's parts, passed on
fn quantity_field(
    ui: &mut Ui,
    t: &mut EditTracker,
    label_id: egui::Id,
    label: &str,
    value_si: &mut f64,
    (per_unit, unit): (f64, &'static str),
    range: RangeInclusive<f64>,
    significant: bool,
) {
    let shown = t.shown(label, per_unit, unit);
    let mut v = *value_si / per_unit;
    let (low, high) = (*range.start(), *range.end());
    let text = RefCell::new(None);
    let speed = (v.abs() * 0.005).max(1e-3);
    let mut drag = DragValue::new(&mut v).speed(speed).range(range);
    if !unit.is_empty() {
        drag = drag.suffix(format!(" {unit}"));
    }
    if significant {
        drag = drag.custom_formatter(|v, _| crate::style::units::significant(v));
    }
    let r = ui.add(handing_back_text(drag, &text)).labelled_by(label_id);
    if r.changed() {
        *value_si = v * per_unit;
    }
    t.track(&r);
    if let Some(text) = text.into_inner() {
        let kept = shown.value(*value_si);
        let read = typed::read_number(&text, &shown, *value_si);
        if let Ok(si) = read {
            *value_si = si;
        }
        t.typed = Some(Typed::new(shown, kept, read, (low, high)));
    }
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
    let (low, high) = (*range.start(), *range.end());
    let text = RefCell::new(None);
    let drag = DragValue::new(value).speed(0.2).range(range);
    let r = ui.add(handing_back_text(drag, &text)).labelled_by(l.id);
    t.track(&r);
    if let Some(text) = text.into_inner() {
        let shown = t.shown(label, 1.0, "");
        let kept = value.to_string();
        let read = typed::read_count(&text, &shown.name, *value);
        if let Ok(n) = read {
            *value = n;
        }
        let range = (low as f64, high as f64);
        t.typed = Some(Typed::new(shown, kept, read.map(|n| n as f64), range));
    }
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
    unit: &'static str,
) {
    let l = ui.label(label);
    ui.horizontal(|ui| {
        let mut auto = value_si.is_none();
        if ui.checkbox(&mut auto, "auto").changed() {
            *value_si = if auto { None } else { Some(auto_value_si) };
        }
        if let Some(v_si) = value_si {
            let range = 0.0..=f64::MAX;
            quantity_field(ui, t, l.id, label, v_si, (per_unit, unit), range, false);
        } else {
            ui.weak(format!(
                "{} {unit}",
                crate::style::units::significant(auto_value_si / per_unit)
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

/// The width of `text` on one line in the text style `style`, points.
pub fn text_width(ui: &Ui, text: &str, style: &egui::TextStyle) -> f32 {
    let font = style.resolve(ui.style());
    ui.painter()
        .layout_no_wrap(text.to_owned(), font, egui::Color32::PLACEHOLDER)
        .size()
        .x
}
