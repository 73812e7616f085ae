//! A value typed into the Scene panel is taken as typed or refused with a
//! message in the panel's units and names; the scene keeps its old value
//! (issue 66). Each bad value of the issue, typed as a user types it:
//! focus the field, select its text, type, press Enter.

use cdca_workbench::WorkbenchApp;
use cdca_workbench::app::Message;
use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

#[path = "support/harness.rs"]
mod support;
use support::{harness, no_solver};

/// The default scene, its crack's fields and points open.
fn open_crack() -> Harness<'static, WorkbenchApp> {
    let mut h = harness(no_solver());
    h.run();
    h.get_by_label_contains("Crack 1: 2 points").click();
    h.run();
    h.get_by_label("Points (mm)").click();
    h.run();
    h
}

/// Types `text` into the number field labelled `label` and presses Enter.
fn type_into(h: &mut Harness<'_, WorkbenchApp>, label: &str, text: &str) {
    h.get_by_label(label).focus();
    h.run();
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    if text.is_empty() {
        h.key_press(Key::Backspace);
    } else {
        h.get_by_label(label).type_text(text);
    }
    h.run();
    h.key_press(Key::Enter);
    h.run_steps(2);
}

/// The text shown by the field labelled `label`.
fn shown(h: &Harness<'_, WorkbenchApp>, label: &str) -> String {
    h.get_by_label(label)
        .accesskit_node()
        .value()
        .unwrap_or_default()
}

/// Types `text` into `label` and checks the refusal: `message` shown, the
/// scene as it was, the field showing its old value again.
fn assert_refused(h: &mut Harness<'_, WorkbenchApp>, label: &str, text: &str, message: &str) {
    let before = h.state().scene().clone();
    let was = shown(h, label);
    type_into(h, label, text);
    assert_eq!(
        h.state().message(),
        Some(&Message::Error(message.to_owned())),
        "{label} ← {text:?}"
    );
    h.get_by_label_contains(message);
    assert_eq!(
        h.state().scene(),
        &before,
        "{label} ← {text:?}: nothing lost"
    );
    assert_eq!(shown(h, label), was, "{label} shows its old value");
}

#[test]
fn friction_nan_and_negative_are_refused() {
    let mut h = open_crack();
    assert_refused(
        &mut h,
        "Friction μ",
        "NaN",
        "Crack 1, friction μ: NaN is not a finite number. It stays 0.5.",
    );
    assert_refused(
        &mut h,
        "Friction μ",
        "-0.2",
        "Not taken: Crack 1, friction μ = -0.2: must not be negative. Crack 1, friction μ \
         stays 0.5.",
    );
    // a good value is taken as typed, not rounded nor clamped
    type_into(&mut h, "Friction μ", "0.7125");
    assert_eq!(h.state().scene().cracks[0].friction, 0.7125);
}

#[test]
fn a_nan_coordinate_and_a_point_outside_are_refused_in_mm() {
    let mut h = open_crack();
    assert_refused(
        &mut h,
        "point 1 x",
        "nan",
        "Crack 1, point 1 x: nan is not a finite number. It stays 12.89 mm.",
    );
    assert_refused(
        &mut h,
        "point 1 x",
        "50",
        "Not taken: Crack 1, point 1 = (50, 12.89) mm: outside the specimen, 0 to 30 mm × 0 \
         to 30 mm. Crack 1, point 1 x stays 12.89 mm.",
    );
}

#[test]
fn a_negative_width_and_an_empty_field_are_refused() {
    let mut h = open_crack();
    let size = shown(&h, "Element size");
    assert_refused(
        &mut h,
        "Width",
        "−5",
        "Not taken: Width = -5 mm: must be positive. Width stays 30 mm.",
    );
    assert_eq!(shown(&h, "Element size"), size);
    assert_refused(
        &mut h,
        "Width",
        "",
        "Width: the field was left empty. It stays 30 mm.",
    );
    // a good width is taken as typed
    type_into(&mut h, "Width", "40");
    assert_eq!(h.state().scene().specimen.width, 0.04);
}

#[test]
fn too_many_elements_are_refused() {
    let mut h = open_crack();
    assert_refused(
        &mut h,
        "Elements along x",
        "100 000",
        "Not taken: Mesh = 100000 × 60: more than 4000000 elements; use a coarser mesh. \
         Elements along x stays 60.",
    );
    assert_refused(
        &mut h,
        "Elements along x",
        "5000",
        "Elements along x: 5000 is above 800, the most this field takes. It stays 60.",
    );
}
