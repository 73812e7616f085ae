//! The menu bar (files, bundled scenes, exports, undo), the toolbar (tools
//! and what the canvas shows), the message banner and the frame overlay.

use egui::{Key, KeyboardShortcut, Modifiers, Rect, Ui};

use crate::files::path_prompt::PathPrompt;
use crate::files::scenes::BUNDLED;
use crate::results::field::FieldKind;
use crate::state::command::{Command, Export};
use crate::state::edit::Tool;
use crate::state::frame_stats::FrameStats;
use crate::state::job::Waiting;
use crate::state::layout::TEXT_SCALES;
use crate::state::view::{AppView, Message, ViewState};
use crate::style::units;

/// What Copy link shares, said beside it (see [`crate::files::link`]).
const LINK_SHARES: &str = "The scene as drawn, not the run (its grown cracks, story and \
     plots stay here). An edit or Reset takes the link out of the address.";

const UNDO: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Z);
const REDO: KeyboardShortcut =
    KeyboardShortcut::new(Modifiers::COMMAND.plus(Modifiers::SHIFT), Key::Z);
const REDO_Y: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::Y);
/// Show or hide the Scene panel (left) and the Solver panel (right).
const SCENE_PANEL: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::OpenBracket);
const SOLVER_PANEL: KeyboardShortcut = KeyboardShortcut::new(Modifiers::COMMAND, Key::CloseBracket);

pub fn menu_bar_ui(ui: &mut Ui, v: &AppView, s: &mut ViewState, cmds: &mut Vec<Command>) {
    shortcuts(ui, s, cmds);
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            if ui.button("Open scene…").clicked() {
                cmds.push(Command::OpenDialog);
            }
            ui.menu_button("Bundled scenes", |ui| {
                for (i, b) in BUNDLED.iter().enumerate() {
                    if ui.button(b.title).clicked() {
                        cmds.push(Command::OpenBundled(i));
                    }
                }
            });
            if ui.button("Save scene…").clicked() {
                cmds.push(Command::Export(Export::Scene));
            }
            if ui
                .button("Copy link to this scene")
                .on_hover_text(
                    "The scene as drawn in a web address (#scene=…): whoever opens it sees \
                     the same crack layout, solved, and can run it",
                )
                .clicked()
            {
                cmds.push(Command::CopyLink);
            }
            ui.weak(LINK_SHARES);
            ui.separator();
            let exports = [
                ("Export crack paths (CSV)…", Export::CrackPaths),
                ("Export growth history (CSV)…", Export::History),
                ("Export fields (VTK .vtu)…", Export::Fields),
                ("Export canvas (PNG)…", Export::CanvasPng),
                ("Export solver race (CSV)…", Export::Race),
            ];
            for (label, what) in exports {
                if ui.button(label).clicked() {
                    cmds.push(Command::Export(what));
                }
            }
        });
        ui.menu_button("Edit", |ui| {
            let undo = ui.add_enabled(
                v.can_undo,
                egui::Button::new("Undo").shortcut_text(ui.ctx().format_shortcut(&UNDO)),
            );
            if undo.clicked() {
                cmds.push(Command::Undo);
            }
            let redo = ui.add_enabled(
                v.can_redo,
                egui::Button::new("Redo").shortcut_text(ui.ctx().format_shortcut(&REDO)),
            );
            if redo.clicked() {
                cmds.push(Command::Redo);
            }
        });
        ui.menu_button("View", |ui| {
            if ui.button("Fit specimen").clicked() {
                *s.fit_requested = true;
            }
            ui.checkbox(&mut s.settings.frame_overlay, "Frame-time overlay");
            ui.checkbox(&mut s.settings.clip_range, "Colour range 1–99 %");
            ui.horizontal(|ui| {
                let l = ui.label("Field samples per element side");
                ui.add(egui::DragValue::new(&mut s.settings.samples_per_cell).range(1..=4))
                    .labelled_by(l.id);
            });
            ui.separator();
            ui.label("Text size");
            for scale in TEXT_SCALES {
                let label = format!("{:.0} %", 100.0 * scale);
                let on = (s.layout.settings.text_scale - scale).abs() < 1e-3;
                if ui.radio(on, label).clicked() {
                    s.layout.settings.text_scale = scale;
                }
            }
        });
        ui.separator();
        panel_toggles(ui, s);
        if !s.layout.is_narrow() {
            ui.separator();
            // cut to the window, the whole title on hover: a long one
            // widened the menu bar past the window and pushed the Solver
            // panel's right edge, and the text in it, off screen
            let title = scene_title(v);
            ui.add(egui::Label::new(&title).truncate())
                .on_hover_text(title);
        }
    });
}

/// The title: the scene's own name, where it came from when that is not
/// the name (a file, a shared link), and "edited" once it differs from
/// what was opened: a shared two-flaw scene read "shared link", a drawn
/// second flaw left "Single flaw under uniaxial compression" unqualified.
fn scene_title(v: &AppView) -> String {
    let name = v.scene.name.trim();
    let mut title = if name.is_empty() || name == v.scene_source {
        format!("Scene: {}", v.scene_source)
    } else {
        format!("Scene: {name} ({})", v.scene_source)
    };
    if v.scene_edited {
        title.push_str(", edited");
    }
    title
}

/// The buttons that show and hide the side panels, lit while shown.
fn panel_toggles(ui: &mut Ui, s: &mut ViewState) {
    let shown = s.layout.settings.show_scene;
    let scene = ui.selectable_label(shown, "< Scene").on_hover_text(format!(
        "{} the Scene panel ({})",
        if shown { "Hide" } else { "Show" },
        ui.ctx().format_shortcut(&SCENE_PANEL)
    ));
    if scene.clicked() {
        s.layout.toggle_scene();
    }
    let shown = s.layout.settings.show_solver;
    let solver = ui
        .selectable_label(shown, "Solver >")
        .on_hover_text(format!(
            "{} the Solver panel ({})",
            if shown { "Hide" } else { "Show" },
            ui.ctx().format_shortcut(&SOLVER_PANEL)
        ));
    if solver.clicked() {
        s.layout.toggle_solver();
    }
}

fn shortcuts(ui: &mut Ui, s: &mut ViewState, cmds: &mut Vec<Command>) {
    if ui.memory(|m| m.focused().is_some()) {
        return; // text fields keep their own undo
    }
    ui.input_mut(|i| {
        if i.consume_shortcut(&REDO) || i.consume_shortcut(&REDO_Y) {
            cmds.push(Command::Redo);
        } else if i.consume_shortcut(&UNDO) {
            cmds.push(Command::Undo);
        }
        if i.consume_shortcut(&SCENE_PANEL) {
            s.layout.toggle_scene();
        }
        if i.consume_shortcut(&SOLVER_PANEL) {
            s.layout.toggle_solver();
        }
    });
}

pub fn toolbar_ui(ui: &mut Ui, v: &AppView, state: &mut ViewState, cmds: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        let editor = &mut *state.editor;
        if ui
            .selectable_label(editor.tool == Tool::Select, "Select")
            .clicked()
        {
            editor.tool = Tool::Select;
            editor.drawing.clear();
        }
        if ui
            .selectable_label(editor.tool == Tool::DrawCrack, "Draw crack")
            .on_hover_text("Click points; double-click or Enter finishes")
            .clicked()
        {
            editor.tool = Tool::DrawCrack;
            editor.drawing.clear();
        }
        // a narrow window leaves Undo and Redo to the Edit menu
        if !state.layout.is_narrow() {
            if ui
                .add_enabled(v.can_undo, egui::Button::new("Undo"))
                .clicked()
            {
                cmds.push(Command::Undo);
            }
            if ui
                .add_enabled(v.can_redo, egui::Button::new("Redo"))
                .clicked()
            {
                cmds.push(Command::Redo);
            }
        }
        ui.separator();
        let s = &mut *state.settings;
        // a narrow window leaves out the label: the toolbar then keeps one row
        let field = if state.layout.is_narrow() {
            egui::ComboBox::from_id_salt("Field")
        } else {
            egui::ComboBox::from_label("Field")
        };
        let list = field.selected_text(s.field.label()).show_ui(ui, |ui| {
            // a rock without cohesion has no strength to use
            let has_strength =
                cdca::fracture::rock::RockStrength::of_material(&v.scene.material).is_some();
            for k in FieldKind::ALL {
                if k == FieldKind::Strength && !has_strength {
                    continue;
                }
                let item = ui.selectable_value(&mut s.field, k, k.label());
                if k == FieldKind::Strength {
                    item.on_hover_text(
                        "u = max((σ1 − N_φ σ3)/σ_c, −σ3/σ_t) with the principal \
                             compressions σ1 ≥ σ3: Mohr–Coulomb with a tension cut-off from \
                             the rock's c, φ and σ_t. u ≥ 1 where the uncracked rock fails; \
                             the tip criterion does not check it.",
                    );
                }
            }
        });
        if state.layout.is_narrow() {
            super::widgets::name_list(&list.response, "Field", s.field.label());
        }
        // a narrow window keeps the layers in a menu: wrapped, they took
        // three rows of a phone's height
        if state.layout.is_narrow() {
            ui.menu_button("Show", |ui| layers_ui(ui, v, s));
        } else {
            layers_ui(ui, v, s);
        }
    });
}

/// The canvas's layers: mesh, loads, contact, traction arrows, deformed
/// shape and its scale.
fn layers_ui(ui: &mut Ui, v: &AppView, s: &mut crate::state::settings::ViewSettings) {
    ui.checkbox(&mut s.show_mesh, "Mesh");
    ui.checkbox(&mut s.show_loads, "Loads & supports");
    if !v.scene.cracks.is_empty() {
        ui.checkbox(&mut s.show_contact, "Contact");
        // open faces carry no traction
        if s.show_contact && !v.solution.all_faces_open() {
            ui.checkbox(&mut s.show_traction_arrows, "Traction arrows");
        }
    }
    ui.checkbox(&mut s.deformed, "Deformed");
    if s.deformed {
        let mut scale = s.deform_scale.unwrap_or(v.deform_scale_used);
        let speed = scale.abs() * 0.01 + 0.1;
        let l = ui.label("scale ×");
        let r = ui
            .add(
                egui::DragValue::new(&mut scale)
                    .speed(speed)
                    .range(0.0..=1e9),
            )
            .labelled_by(l.id);
        if r.changed() {
            s.deform_scale = Some(scale);
        }
        if ui
            .add_enabled(s.deform_scale.is_some(), egui::Button::new("Auto scale"))
            .clicked()
        {
            s.deform_scale = None;
        }
    }
}

/// The error or information banner above the canvas.
pub fn message_ui(ui: &mut Ui, message: Option<&Message>, cmds: &mut Vec<Command>) {
    let Some(message) = message else {
        return;
    };
    let (text, color) = match message {
        Message::Error(e) => (e.as_str(), ui.visuals().error_fg_color),
        Message::Info(i) => (i.as_str(), ui.visuals().text_color()),
    };
    egui::Frame::group(ui.style())
        .stroke(egui::Stroke::new(1.5, color))
        .show(ui, |ui| {
            ui.horizontal_wrapped(|ui| {
                ui.colored_label(color, text);
                if ui.button("Dismiss").clicked() {
                    cmds.push(Command::DismissMessage);
                }
            });
        });
}

/// The job asked for while another runs: what runs, and the choice to
/// cancel it and start the new one, or keep it.
pub fn waiting_ui(ui: &mut Ui, waiting: Option<&Waiting>, cmds: &mut Vec<Command>) {
    let Some(w) = waiting else {
        return;
    };
    let color = ui.visuals().warn_fg_color;
    egui::Frame::group(ui.style())
        .stroke(egui::Stroke::new(1.5, color))
        .show(ui, |ui| {
            ui.horizontal_wrapped(|ui| {
                ui.colored_label(color, w.text());
                if ui.button(w.confirm_label()).clicked() {
                    cmds.push(Command::StartWaiting);
                }
                if ui.button(w.drop_label()).clicked() {
                    cmds.push(Command::DropWaiting);
                }
            });
        });
}

/// The path field where no file dialog could open: what it is for, the
/// path, and the buttons that use it or close it.
pub fn path_prompt_ui(ui: &mut Ui, prompt: Option<&mut PathPrompt>, cmds: &mut Vec<Command>) {
    let Some(prompt) = prompt else {
        return;
    };
    let color = ui.visuals().warn_fg_color;
    egui::Frame::group(ui.style())
        .stroke(egui::Stroke::new(1.5, color))
        .show(ui, |ui| {
            ui.colored_label(color, prompt.text());
            // the field within the panel, the buttons on a row of their
            // own: a 420-point field and its buttons on one row ran past
            // the panel's edge in a 900 × 600 window, and "Open this file"
            // lay under the Solver panel, where a click did nothing
            // (issue 66: "File ▸ Open does nothing while a banner is up")
            let entered = ui
                .horizontal(|ui| {
                    let label = ui.label("Path");
                    let width = ui.available_width().min(420.0);
                    let field = ui
                        .add(
                            egui::TextEdit::singleline(&mut prompt.path)
                                .desired_width(width)
                                .hint_text("path/to/file"),
                        )
                        .labelled_by(label.id);
                    field.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter))
                })
                .inner;
            ui.horizontal(|ui| {
                if ui.button(prompt.button()).clicked() || entered {
                    cmds.push(Command::UseTypedPath);
                }
                if ui.button("Cancel").clicked() {
                    cmds.push(Command::CancelTypedPath);
                }
            });
        });
}

/// Frame times at the canvas's bottom left, above the pointer's position (the
/// load label is at the top, the colour scale at the top right).
pub fn frame_overlay_ui(ui: &Ui, canvas: Rect, stats: &FrameStats) {
    let text = format!(
        "frame (logic + UI): last {}  mean {}  p95 {}  max {}\nsolver per frame: {}   frame interval: {}   ({} frames)",
        units::seconds(stats.last()),
        units::seconds(stats.mean()),
        units::seconds(stats.p95()),
        units::seconds(stats.max()),
        units::seconds(stats.mean_solver()),
        units::seconds(stats.mean_interval()),
        stats.len(),
    );
    let painter = ui.painter_at(canvas);
    let galley = painter.layout_no_wrap(
        text,
        egui::FontId::proportional(11.0),
        ui.visuals().strong_text_color(),
    );
    // the pointer's line is 12 pt, 8 px above the bottom edge
    let pos = canvas.left_bottom() + egui::vec2(8.0, -30.0 - galley.size().y);
    painter.rect_filled(
        Rect::from_min_size(pos, galley.size()).expand(4.0),
        3.0,
        ui.visuals().extreme_bg_color,
    );
    painter.galley(pos, galley, egui::Color32::WHITE);
}
