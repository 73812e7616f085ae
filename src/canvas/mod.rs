//! The specimen view: field colour map, mesh, loads and supports, cracks,
//! tips and contact; pan and zoom; crack drawing and dragging.

mod field_mesh;
mod symbols;
mod view;

use cdca::scene::SceneFile;
use egui::{Align2, FontId, Key, PointerButton, Pos2, Response, Sense, Stroke, Ui};

use crate::results::field::{FieldKind, FieldSamples};
use crate::results::solution::SolutionView;
use crate::state::command::Command;
use crate::state::edit::{Editor, Tool, VertexRef, move_vertex};
use crate::state::settings::ViewSettings;
use crate::style::units;
use field_mesh::{FieldMesh, MeshKey, paint_legend};
pub use symbols::{SECONDARY_COLOR, SECONDARY_KEY};
pub use view::ViewTransform;

/// The accessible name of the canvas (tests find it by this label).
pub const CANVAS_LABEL: &str = "Specimen canvas";

/// What the canvas shows this frame.
pub struct CanvasInput<'a> {
    pub scene: &'a SceneFile,
    pub solution: &'a SolutionView,
    pub field: Option<&'a FieldSamples>,
    pub settings: &'a ViewSettings,
    pub selected_tip: Option<usize>,
}

/// Canvas state kept between frames.
#[derive(Default)]
pub struct Canvas {
    pub view: ViewTransform,
    /// Specimen size the view was last fitted to.
    fitted_to: Option<[f64; 2]>,
    pub fit_requested: bool,
    /// The user zoomed or panned since the last fit: a new canvas size
    /// keeps their view instead of refitting.
    moved_since_fit: bool,
    /// The key and the colour legend as last drawn.
    pub key_rect: Option<egui::Rect>,
    pub legend_rect: Option<egui::Rect>,
    /// The load labels beside the traction arrows, as last drawn.
    pub load_label_rects: Vec<egui::Rect>,
    mesh: Option<FieldMesh>,
    /// Pointer position in the specimen, m.
    pub hover_world: Option<[f64; 2]>,
    /// Deformation magnification in use.
    pub deform_scale_used: f64,
}

/// Pick radius around handles and tips, points.
const PICK_RADIUS: f32 = 9.0;

/// Least canvas size (width, height), points, that shows the symbols' key
/// and the link's label besides the specimen and its colour legend.
const ROOMY_CANVAS: [f32; 2] = [300.0, 200.0];

impl Canvas {
    pub fn ui(
        &mut self,
        ui: &mut Ui,
        input: &CanvasInput<'_>,
        editor: &mut Editor,
        cmds: &mut Vec<Command>,
    ) -> Response {
        let (rect, response) = ui.allocate_exact_size(ui.available_size(), Sense::click_and_drag());
        response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, CANVAS_LABEL));
        let size = [input.scene.specimen.width, input.scene.specimen.height];
        // refit to a new specimen, and to a resized canvas (window or
        // panels) unless the user has zoomed or panned since the last fit
        let resized = self.view.rect.size() != rect.size() && !self.moved_since_fit;
        if self.fit_requested || self.fitted_to != Some(size) || resized {
            self.view.fit(rect, size[0], size[1]);
            self.fitted_to = Some(size);
            self.fit_requested = false;
            self.moved_since_fit = false;
        } else if self.view.rect != rect {
            self.view.rect = rect;
        }
        self.hover_world = response.hover_pos().map(|p| self.view.world_from_screen(p));
        let hovered_vertex = response
            .hover_pos()
            .and_then(|p| self.vertex_near(input.scene, p));
        match editor.tool {
            Tool::Select => self.select_tool(ui, &response, input, editor, hovered_vertex, cmds),
            Tool::DrawCrack => self.draw_tool(ui, &response, input.scene, editor, cmds),
        }
        self.navigate(ui, &response, editor);
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, ui.visuals().extreme_bg_color);
        self.paint(&painter, input, editor, hovered_vertex);
        response
    }

    /// Zoom with the wheel or pinch, pan with the secondary or middle button
    /// (or the primary one on empty space with the select tool).
    fn navigate(&mut self, ui: &Ui, response: &Response, editor: &Editor) {
        if let Some(p) = response.hover_pos() {
            let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
            let factor = f64::from(zoom) * (f64::from(scroll) * 0.002).exp();
            if (factor - 1.0).abs() > 1e-6 {
                self.view.zoom_about(p, factor);
                self.moved_since_fit = true;
            }
        }
        let pans = response.dragged_by(PointerButton::Secondary)
            || response.dragged_by(PointerButton::Middle)
            || (response.dragged_by(PointerButton::Primary)
                && editor.tool == Tool::Select
                && editor.dragging.is_none());
        if pans && response.drag_delta() != egui::Vec2::ZERO {
            self.view.pan(response.drag_delta());
            self.moved_since_fit = true;
        }
    }

    fn vertex_near(&self, scene: &SceneFile, p: Pos2) -> Option<(usize, usize)> {
        let h = scene.element_size();
        let mut best: Option<((usize, usize), f32)> = None;
        for (i, crack) in scene.cracks.iter().enumerate() {
            if crack.points.is_none() {
                continue;
            }
            for (k, &v) in crack.polyline(h).iter().enumerate() {
                let d = self.view.screen_from_world(v).distance(p);
                if d < PICK_RADIUS && best.is_none_or(|(_, bd)| d < bd) {
                    best = Some(((i, k), d));
                }
            }
        }
        best.map(|(v, _)| v)
    }

    /// A point inside the specimen (clamped half a percent from the sides).
    fn clamp_inside(scene: &SceneFile, p: [f64; 2]) -> [f64; 2] {
        let (w, h) = (scene.specimen.width, scene.specimen.height);
        let m = 0.005 * w.min(h);
        [p[0].clamp(m, w - m), p[1].clamp(m, h - m)]
    }

    fn select_tool(
        &mut self,
        ui: &Ui,
        response: &Response,
        input: &CanvasInput<'_>,
        editor: &mut Editor,
        hovered_vertex: Option<(usize, usize)>,
        cmds: &mut Vec<Command>,
    ) {
        if response.drag_started_by(PointerButton::Primary) {
            let start = ui.input(|i| i.pointer.press_origin());
            editor.dragging = start
                .and_then(|p| self.vertex_near(input.scene, p))
                .or(hovered_vertex)
                .map(|(crack, vertex)| VertexRef { crack, vertex });
        }
        if let (Some(v), Some(p)) = (editor.dragging, response.interact_pointer_pos())
            && response.dragged_by(PointerButton::Primary)
        {
            let to = Self::clamp_inside(input.scene, self.view.world_from_screen(p));
            cmds.push(Command::SetScene {
                scene: Box::new(move_vertex(input.scene, v, to)),
                ongoing: true,
            });
        }
        if response.drag_stopped() && editor.dragging.take().is_some() {
            cmds.push(Command::EndDrag);
        }
        if response.clicked()
            && let Some(p) = response.interact_pointer_pos()
        {
            let tip =
                input.solution.tips.iter().position(|t| {
                    self.view.screen_from_world([t.x, t.y]).distance(p) < PICK_RADIUS
                });
            // a click on a tip inspects it; elsewhere the inspected tip
            // stays (the inspector's "none" clears it)
            if tip.is_some() {
                cmds.push(Command::SelectTip(tip));
            }
            editor.selected_crack = hovered_vertex
                .map(|(c, _)| c)
                .or_else(|| self.crack_near(input.scene, p));
        }
        if let Some(i) = editor.selected_crack
            && response.hovered()
            && ui.input(|inp| inp.key_pressed(Key::Delete))
            && i < input.scene.cracks.len()
        {
            let mut scene = input.scene.clone();
            scene.cracks.remove(i);
            editor.selected_crack = None;
            cmds.push(Command::SetScene {
                scene: Box::new(scene),
                ongoing: false,
            });
        }
    }

    fn crack_near(&self, scene: &SceneFile, p: Pos2) -> Option<usize> {
        let h = scene.element_size();
        scene.cracks.iter().position(|c| {
            c.polyline(h).windows(2).any(|w| {
                let (a, b) = (
                    self.view.screen_from_world(w[0]),
                    self.view.screen_from_world(w[1]),
                );
                let ab = b - a;
                let t = ((p - a).dot(ab) / ab.length_sq().max(1e-6)).clamp(0.0, 1.0);
                (a + ab * t).distance(p) < PICK_RADIUS
            })
        })
    }

    fn draw_tool(
        &mut self,
        ui: &Ui,
        response: &Response,
        scene: &SceneFile,
        editor: &mut Editor,
        cmds: &mut Vec<Command>,
    ) {
        if response.clicked()
            && !response.double_clicked()
            && let Some(p) = response.interact_pointer_pos()
        {
            editor
                .drawing
                .push(Self::clamp_inside(scene, self.view.world_from_screen(p)));
        }
        let (enter, escape) = ui.input(|i| (i.key_pressed(Key::Enter), i.key_pressed(Key::Escape)));
        if escape {
            editor.drawing.clear();
            editor.tool = Tool::Select;
        } else if (response.double_clicked() || enter)
            && let Some(crack) = editor.finish_drawing()
        {
            editor.selected_crack = Some(scene.cracks.len());
            cmds.push(Command::AddCrack(Box::new(crack)));
        }
    }

    fn paint(
        &mut self,
        painter: &egui::Painter,
        input: &CanvasInput<'_>,
        editor: &Editor,
        hovered_vertex: Option<(usize, usize)>,
    ) {
        let view = self.view;
        let s = input.settings;
        let scene = input.scene;
        let wants_field = s.field != FieldKind::None || s.deformed;
        // the last sampled field: a solution, or the iterate of a solve
        // under way (the runner forgets it when the scene changes)
        let field = input.field.filter(|_| wants_field);
        symbols::paint_outline(painter, &view, scene, true);
        if let Some(samples) = field {
            self.deform_scale_used = if s.deformed {
                s.deform_scale
                    .unwrap_or_else(|| auto_deform_scale(samples, scene))
            } else {
                0.0
            };
            let key = MeshKey {
                field: samples.key,
                kind: s.field,
                deform_scale: self.deform_scale_used,
                clip: s.clip_range,
            };
            if self.mesh.as_ref().is_none_or(|m| m.key != key) {
                self.mesh = Some(FieldMesh::build(key, samples, &scene.material));
            }
            if let Some(mesh) = &self.mesh {
                mesh.paint(painter, &view);
            }
        }
        if s.show_mesh {
            symbols::paint_mesh_lines(painter, &view, scene);
        }
        self.load_label_rects.clear();
        if s.show_loads {
            // the field shown is at λ times the scene's tractions: the
            // label gives the load of the field on screen (after a split
            // the last solved state's), else the solver's
            let sol = input.solution;
            let load_factor = input
                .field
                .map(|f| f.load_factor)
                .or_else(|| (sol.solved || sol.live).then_some(sol.load_factor))
                .filter(|l| (l - 1.0).abs() > 1e-9);
            self.load_label_rects = symbols::paint_boundary(painter, &view, scene, load_factor);
        }
        // before a solve (or after an edit) the scene's own cracks, and
        // which of them are secondary from its saved lineage
        let scene_cracks: Vec<Vec<[f64; 2]>>;
        let (scene_secondary, scene_intact): (Vec<Vec<bool>>, Vec<bool>);
        let (cracks, secondary, intact) = if input.solution.cracks.is_empty() {
            let h = scene.element_size();
            scene_cracks = scene.cracks.iter().map(|c| c.polyline(h)).collect();
            (scene_secondary, scene_intact) = parts_in_scene(scene, &scene_cracks);
            (&scene_cracks, &scene_secondary, &scene_intact)
        } else {
            let s = input.solution;
            (&s.cracks, &s.secondary, &s.intact)
        };
        symbols::paint_cracks(
            painter,
            &view,
            cracks,
            secondary,
            intact,
            editor.selected_crack,
        );
        if s.show_contact {
            symbols::paint_contact(
                painter,
                &view,
                &input.solution.contact,
                cracks,
                secondary,
                s.show_traction_arrows,
            );
        }
        symbols::paint_tips(painter, &view, &input.solution.tips, input.selected_tip);
        // a phone's canvas under a story and a plot (about 100 points tall)
        // keeps the specimen and its colour legend: the symbols' key and
        // the link's label covered both, and the story tells the link
        let roomy = view.rect.height() >= ROOMY_CANVAS[1] && view.rect.width() >= ROOMY_CANVAS[0];
        self.key_rect = roomy
            .then(|| {
                symbols::paint_key(
                    painter,
                    view.rect,
                    !input.solution.tips.is_empty(),
                    secondary.iter().flatten().any(|&s| s),
                    intact.iter().any(|&i| i),
                )
            })
            .flatten();
        // the legend above the key, shortened to clear it
        self.legend_rect = None;
        if let Some((mesh, range)) = field
            .and(self.mesh.as_ref())
            .and_then(|m| m.range.map(|r| (m, r)))
        {
            let bottom = self.key_rect.map_or(view.rect.bottom(), |k| k.top() - 6.0);
            self.legend_rect = Some(paint_legend(
                painter,
                view.rect,
                bottom,
                mesh.key.kind,
                range,
                s.clip_range,
            ));
        }
        if editor.tool == Tool::Select {
            symbols::paint_handles(painter, &view, scene, hovered_vertex);
        }
        // the link's label over the handles, which covered its first word
        if let (true, Some(at), Some(c)) =
            (roomy, input.solution.junction, &input.solution.coalescence)
        {
            symbols::paint_link(painter, &view, at, c, &self.load_label_rects);
        }
        self.paint_drawing(painter, editor);
        self.paint_status(painter, editor);
    }

    fn paint_drawing(&self, painter: &egui::Painter, editor: &Editor) {
        if editor.tool != Tool::DrawCrack {
            return;
        }
        let mut points: Vec<Pos2> = editor
            .drawing
            .iter()
            .map(|&p| self.view.screen_from_world(p))
            .collect();
        if let Some(w) = self.hover_world {
            points.push(self.view.screen_from_world(w));
        }
        painter.add(egui::Shape::dashed_line(
            &points,
            Stroke::new(2.0, symbols::HANDLE_COLOR),
            6.0,
            4.0,
        ));
        for p in &points {
            painter.circle_filled(*p, 3.5, symbols::HANDLE_COLOR);
        }
    }

    /// Pointer coordinates in mm and the tool's hint, bottom-left.
    fn paint_status(&self, painter: &egui::Painter, editor: &Editor) {
        let mut text = match self.hover_world {
            Some([x, y]) => format!("x = {}   y = {}", units::mm(x), units::mm(y)),
            None => String::new(),
        };
        if editor.tool == Tool::DrawCrack {
            text.push_str("   — click points; double-click or Enter finishes, Esc cancels");
        }
        let pos = self.view.rect.left_bottom() + egui::vec2(8.0, -8.0);
        // the theme's text colour: grey 120 measured 4.4:1 on the light
        // theme's canvas (`crate::style::contrast`)
        let colour = painter.ctx().global_style().visuals.text_color();
        painter.text(
            pos,
            Align2::LEFT_BOTTOM,
            text,
            FontId::proportional(12.0),
            colour,
        );
    }
}

/// Per crack of `scene`, as its saved growth run's lineage says
/// (`Resume::lineage_of`, as the simulation reads it): per segment,
/// whether it is part of a secondary crack, and whether the crack started
/// in the intact rock. Every crack is a flaw without one.
fn parts_in_scene(scene: &SceneFile, polylines: &[Vec<[f64; 2]>]) -> (Vec<Vec<bool>>, Vec<bool>) {
    let lineage = scene
        .growth
        .resume
        .as_ref()
        .and_then(|r| r.lineage_of(polylines.len()));
    polylines
        .iter()
        .enumerate()
        .map(|(i, p)| match lineage {
            Some(l) => (l[i].secondary_segments(p.len()), l[i].is_intact()),
            None => (vec![false; p.len().saturating_sub(1)], false),
        })
        .unzip()
}

/// A magnification that shows the largest displacement as 5 % of the
/// specimen's larger side.
fn auto_deform_scale(samples: &FieldSamples, scene: &SceneFile) -> f64 {
    let max_u = samples
        .samples
        .iter()
        .flat_map(|s| s.corner_disp.iter())
        .map(|u| u[0].hypot(u[1]))
        .filter(|u| u.is_finite())
        .fold(0.0_f64, f64::max);
    if max_u > 0.0 {
        0.05 * scene.specimen.width.max(scene.specimen.height) / max_u
    } else {
        1.0
    }
}
