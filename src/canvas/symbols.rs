//! Drawing the specimen: outline, mesh lines, loads as arrows, supports as
//! symbols, cracks, tips and the contact state along the cracks.

use cdca::report::{Mode, TipReport};
use cdca::scene::SceneFile;
use cdca::scene::{Fix, SideBc};
use cdca::{ContactPointView, ContactState};
use egui::{Align2, Color32, FontId, Painter, Pos2, Shape, Stroke, Vec2, vec2};

use super::view::ViewTransform;
use crate::style::units;

pub const LOAD_COLOR: Color32 = Color32::from_rgb(230, 60, 60);
pub const SUPPORT_COLOR: Color32 = Color32::from_rgb(90, 160, 255);
pub const CRACK_COLOR: Color32 = Color32::from_rgb(20, 20, 20);
/// Cracks started at another crack's kink (secondary cracks).
pub const SECONDARY_COLOR: Color32 = Color32::from_rgb(150, 40, 170);
/// Cracks started in the intact rock (`growth.intact_rock` `"nucleate"`).
pub const INTACT_COLOR: Color32 = Color32::from_rgb(0, 120, 130);
pub const HANDLE_COLOR: Color32 = Color32::from_rgb(255, 210, 0);

/// Colour of a contact state: open grey-blue, stick green, slip orange.
pub fn contact_color(state: ContactState) -> Color32 {
    match state {
        ContactState::Open => Color32::from_rgb(150, 190, 255),
        ContactState::Stick => Color32::from_rgb(40, 200, 90),
        ContactState::Slip => Color32::from_rgb(255, 140, 0),
    }
}

/// Colour of a tip by the criterion's decision.
pub fn tip_color(mode: Mode) -> Color32 {
    match mode {
        Mode::Tension => Color32::from_rgb(255, 60, 60),
        Mode::Shear => Color32::from_rgb(200, 80, 255),
        Mode::None => Color32::WHITE,
    }
}

pub fn paint_outline(painter: &Painter, view: &ViewTransform, scene: &SceneFile, fill: bool) {
    let (w, h) = (scene.specimen.width, scene.specimen.height);
    let rect = egui::Rect::from_two_pos(
        view.screen_from_world([0.0, 0.0]),
        view.screen_from_world([w, h]),
    );
    if fill {
        painter.rect_filled(rect, 0.0, Color32::from_gray(200));
    }
    painter.rect_stroke(
        rect,
        0.0,
        Stroke::new(1.5, Color32::from_gray(60)),
        egui::StrokeKind::Middle,
    );
}

pub fn paint_mesh_lines(painter: &Painter, view: &ViewTransform, scene: &SceneFile) {
    let (w, h) = (scene.specimen.width, scene.specimen.height);
    let (nx, ny) = (scene.mesh.nx, scene.mesh.ny);
    let stroke = Stroke::new(0.5, Color32::from_black_alpha(70));
    for i in 0..=nx {
        let x = w * i as f64 / nx as f64;
        painter.line_segment(
            [
                view.screen_from_world([x, 0.0]),
                view.screen_from_world([x, h]),
            ],
            stroke,
        );
    }
    for j in 0..=ny {
        let y = h * j as f64 / ny as f64;
        painter.line_segment(
            [
                view.screen_from_world([0.0, y]),
                view.screen_from_world([w, y]),
            ],
            stroke,
        );
    }
}

/// One side of the rectangle: its end points and outward normal.
struct Side {
    a: [f64; 2],
    b: [f64; 2],
    outward: [f64; 2],
    bc: SideBc,
}

fn sides(scene: &SceneFile) -> [Side; 4] {
    let (w, h) = (scene.specimen.width, scene.specimen.height);
    let b = &scene.boundary;
    [
        Side {
            a: [0.0, 0.0],
            b: [w, 0.0],
            outward: [0.0, -1.0],
            bc: b.bottom,
        },
        Side {
            a: [w, 0.0],
            b: [w, h],
            outward: [1.0, 0.0],
            bc: b.right,
        },
        Side {
            a: [0.0, h],
            b: [w, h],
            outward: [0.0, 1.0],
            bc: b.top,
        },
        Side {
            a: [0.0, 0.0],
            b: [0.0, h],
            outward: [-1.0, 0.0],
            bc: b.left,
        },
    ]
}

/// Traction arrows (compression points into the specimen), roller and
/// fixed symbols, point supports. `load_factor`: the factor λ on the
/// scene's tractions of the field shown, when it is not 1 (growth under
/// critical or load control); the labels then read "λ 1.706 × σ_n …".
/// Returns the load labels' rectangles (the browser test checks that no
/// key on the canvas covers another).
pub fn paint_boundary(
    painter: &Painter,
    view: &ViewTransform,
    scene: &SceneFile,
    load_factor: Option<f64>,
) -> Vec<egui::Rect> {
    let font = FontId::proportional(12.0);
    let mut labels = Vec::new();
    for side in sides(scene) {
        let out = view.screen_vec(side.outward).normalized();
        let along = view
            .screen_vec([side.b[0] - side.a[0], side.b[1] - side.a[1]])
            .normalized();
        let pa = view.screen_from_world(side.a);
        let pb = view.screen_from_world(side.b);
        let n = 9;
        let at = |k: usize| pa + (pb - pa) * ((k as f32 + 0.5) / n as f32);
        match side.bc {
            SideBc::Free => {}
            SideBc::Roller => {
                for k in 0..n {
                    painter.circle_stroke(at(k) + out * 5.0, 4.0, Stroke::new(1.5, SUPPORT_COLOR));
                }
                painter.line_segment(
                    [pa + out * 10.0, pb + out * 10.0],
                    Stroke::new(1.5, SUPPORT_COLOR),
                );
            }
            SideBc::Fixed => {
                painter.line_segment(
                    [pa + out * 2.0, pb + out * 2.0],
                    Stroke::new(2.0, SUPPORT_COLOR),
                );
                for k in 0..2 * n {
                    let p = pa + (pb - pa) * ((k as f32 + 0.5) / (2 * n) as f32) + out * 2.0;
                    painter.line_segment(
                        [p, p + out * 8.0 + along * 6.0],
                        Stroke::new(1.0, SUPPORT_COLOR),
                    );
                }
            }
            SideBc::Traction { normal, shear } => {
                let stroke = Stroke::new(2.0, LOAD_COLOR);
                let len = 32.0;
                if normal != 0.0 {
                    for k in 0..n {
                        let p = at(k);
                        if normal < 0.0 {
                            painter.arrow(p + out * (len + 4.0), -out * len, stroke);
                        } else {
                            painter.arrow(p + out * 4.0, out * len, stroke);
                        }
                    }
                }
                if shear != 0.0 {
                    let dir = view
                        .screen_vec(if side.outward[0] == 0.0 {
                            [1.0, 0.0]
                        } else {
                            [0.0, 1.0]
                        })
                        .normalized();
                    for k in (0..n).step_by(2) {
                        let p = at(k) + out * (len + 12.0);
                        painter.arrow(
                            p - dir * 10.0 * shear.signum() as f32,
                            dir * 20.0 * shear.signum() as f32,
                            stroke,
                        );
                    }
                }
                let traction = match (normal != 0.0, shear != 0.0) {
                    (true, true) => format!("σ_n {}, τ {}", units::mpa(normal), units::mpa(shear)),
                    (false, true) => format!("τ {}", units::mpa(shear)),
                    _ => format!("σ_n {}", units::mpa(normal)),
                };
                let label = match load_factor {
                    Some(l) => format!("λ {l:.3} × {traction}"),
                    None => traction,
                };
                // Beside the arrows: above a horizontal side, between two
                // arrows and past their tails on a vertical one.
                let (at_label, align) = if side.outward[0] == 0.0 {
                    (
                        pa + (pb - pa) * 0.5 + out * (len + 24.0),
                        Align2::CENTER_CENTER,
                    )
                } else {
                    let align = if side.outward[0] > 0.0 {
                        Align2::LEFT_CENTER
                    } else {
                        Align2::RIGHT_CENTER
                    };
                    (pa + (pb - pa) * (5.0 / n as f32) + out * (len + 8.0), align)
                };
                // inside the canvas whatever the fit's margin: on a small
                // canvas the label fell past its edge and was cut off (a
                // canvas under 20 points has no room for it at all)
                let inner = view.rect.shrink(10.0);
                if !inner.is_positive() {
                    continue;
                }
                let at_label = Pos2::new(
                    at_label.x.clamp(inner.left(), inner.right()),
                    at_label.y.clamp(inner.top(), inner.bottom()),
                );
                labels.push(painter.text(at_label, align, label, font.clone(), LOAD_COLOR));
            }
        }
    }
    for p in &scene.boundary.points {
        let q = view.screen_from_world(p.at);
        let tri = vec![q, q + vec2(-7.0, 12.0), q + vec2(7.0, 12.0)];
        painter.add(Shape::convex_polygon(tri, SUPPORT_COLOR, Stroke::NONE));
        let label = match p.fix {
            Fix::X => "x",
            Fix::Y => "y",
            Fix::Xy => "xy",
        };
        painter.text(
            q + vec2(0.0, 14.0),
            Align2::CENTER_TOP,
            label,
            font.clone(),
            SUPPORT_COLOR,
        );
    }
    labels
}

/// The cracks as polylines, black, with the segments `secondary` marks
/// (per crack, per segment) in the secondary cracks' purple and the cracks
/// `intact` marks (started in the intact rock) in teal, dashed; the
/// selected crack wider.
pub fn paint_cracks(
    painter: &Painter,
    view: &ViewTransform,
    cracks: &[Vec<[f64; 2]>],
    secondary: &[Vec<bool>],
    intact: &[bool],
    selected: Option<usize>,
) {
    for (i, c) in cracks.iter().enumerate() {
        let width = if selected == Some(i) { 4.0 } else { 2.5 };
        if intact.get(i) == Some(&true) {
            // dashed as well as coloured: told apart without colour vision
            let points: Vec<Pos2> = c.iter().map(|&p| view.screen_from_world(p)).collect();
            painter.extend(Shape::dashed_line(
                &points,
                Stroke::new(width + 0.5, INTACT_COLOR),
                6.0,
                2.5,
            ));
            continue;
        }
        let flags = secondary.get(i).map_or(&[][..], Vec::as_slice);
        // runs of segments of one kind, each a polyline
        let mut start = 0;
        while start + 1 < c.len() {
            let kind = flags.get(start) == Some(&true);
            let mut end = start + 1;
            while end + 1 < c.len() && (flags.get(end) == Some(&true)) == kind {
                end += 1;
            }
            let points: Vec<Pos2> = c[start..=end]
                .iter()
                .map(|&p| view.screen_from_world(p))
                .collect();
            let colour = if kind { SECONDARY_COLOR } else { CRACK_COLOR };
            painter.add(Shape::line(points, Stroke::new(width, colour)));
            start = end;
        }
    }
}

/// The segment of `polyline` nearest to `p` (0 for a single point).
fn nearest_segment(polyline: &[[f64; 2]], p: [f64; 2]) -> usize {
    let distance = |w: &[[f64; 2]]| {
        let (a, b) = (w[0], w[1]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len2 = d[0] * d[0] + d[1] * d[1];
        let t = if len2 > 0.0 {
            (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
    };
    polyline
        .windows(2)
        .map(distance)
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(j, _)| j)
}

/// Contact points coloured by state, and the traction the other face exerts
/// on the φ > 0 face as arrows (longest arrow 25 points). `secondary`: per
/// crack `cracks`, per segment, whether it is part of a secondary crack
/// (see [`contact_dot`]; a point takes its nearest segment's).
pub fn paint_contact(
    painter: &Painter,
    view: &ViewTransform,
    contact: &[ContactPointView],
    cracks: &[Vec<[f64; 2]>],
    secondary: &[Vec<bool>],
    arrows: bool,
) {
    let max_t = contact
        .iter()
        .map(|c| c.p_n.hypot(c.p_t))
        .fold(0.0_f64, f64::max);
    for c in contact {
        let q = view.screen_from_world([c.x, c.y]);
        let on_secondary = secondary.get(c.crack).is_some_and(|flags| {
            let polyline = cracks.get(c.crack).map_or(&[][..], Vec::as_slice);
            flags.get(nearest_segment(polyline, [c.x, c.y])) == Some(&true)
        });
        let dot = contact_dot(c.state, on_secondary);
        painter.circle(q, dot.radius, dot.fill, dot.stroke);
        if arrows && max_t > 0.0 && c.state != ContactState::Open {
            let [nx, ny] = c.normal;
            let tangent = [ny, -nx];
            let t = [
                -(c.p_n * nx + c.p_t * tangent[0]),
                -(c.p_n * ny + c.p_t * tangent[1]),
            ];
            let v = view.screen_vec(t).normalized() * (25.0 * (t[0].hypot(t[1]) / max_t) as f32);
            painter.arrow(q, v, Stroke::new(1.2, contact_color(c.state)));
        }
    }
}

/// How one contact point is drawn: a disc in its state's colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactDot {
    /// Radius of the disc, points.
    pub radius: f32,
    /// The state's colour ([`contact_color`]).
    pub fill: Color32,
    /// The ring around the disc ([`Stroke::NONE`] for none).
    pub stroke: Stroke,
}

/// The dot of a contact point in `state`. On a flaw or a wing the dot is
/// a plain disc over the black crack line; the dots of a closed crack lie
/// close together and covered a secondary crack's purple line, so on a
/// secondary crack the disc is smaller and ringed in the crack's purple:
/// the state still shows inside, and the crack stays purple outside.
pub fn contact_dot(state: ContactState, secondary: bool) -> ContactDot {
    let (radius, stroke) = if secondary {
        (2.0, Stroke::new(1.5, SECONDARY_COLOR))
    } else {
        (2.5, Stroke::NONE)
    };
    ContactDot {
        radius,
        fill: contact_color(state),
        stroke,
    }
}

pub fn paint_tips(
    painter: &Painter,
    view: &ViewTransform,
    tips: &[TipReport],
    selected: Option<usize>,
) {
    for (i, t) in tips.iter().enumerate() {
        let q = view.screen_from_world([t.x, t.y]);
        painter.circle(
            q,
            5.0,
            tip_color(t.criterion.mode),
            Stroke::new(1.5, Color32::BLACK),
        );
        if selected == Some(i) {
            painter.circle_stroke(q, 10.0, Stroke::new(2.0, HANDLE_COLOR));
        }
    }
}

/// Where two flaws linked: a ring at the junction and, in the canvas's
/// top-left corner (beside the junction it covered the cracks at the
/// canvas's middle), the flaws and the step ("Crack 1 and Crack 2
/// linked, step 9") on the theme's window fill, joined to the ring by a
/// thin line. Below the load's labels where they reach the corner (at
/// 1024 × 640 the label covered the load's value).
pub fn paint_link(
    painter: &Painter,
    view: &ViewTransform,
    at: [f64; 2],
    link: &cdca::report::CoalescenceReport,
    load_labels: &[egui::Rect],
) {
    let q = view.screen_from_world(at);
    let visuals = painter.ctx().global_style().visuals.clone();
    let text = format!(
        "Crack {} and Crack {} linked, step {}",
        link.flaws[0] + 1,
        link.flaws[1] + 1,
        link.step
    );
    let galley = painter.layout_no_wrap(
        text,
        FontId::proportional(12.0),
        visuals.strong_text_color(),
    );
    let mut corner = view.rect.left_top() + vec2(10.0, 10.0);
    let backing = |corner| egui::Rect::from_min_size(corner, galley.size()).expand(3.0);
    if let Some(bottom) = load_labels
        .iter()
        .filter(|r| r.intersects(backing(corner)))
        .map(egui::Rect::bottom)
        .reduce(f32::max)
    {
        corner.y = bottom + 6.0;
    }
    let backing = backing(corner);
    painter.line_segment(
        [backing.center_bottom(), q],
        Stroke::new(1.0, visuals.strong_text_color().gamma_multiply(0.6)),
    );
    painter.circle_stroke(q, 9.0, Stroke::new(3.0, Color32::WHITE));
    painter.circle_stroke(q, 9.0, Stroke::new(1.5, Color32::BLACK));
    painter.rect_filled(backing, 3.0, visuals.window_fill.gamma_multiply(0.92));
    painter.galley(corner, galley, visuals.strong_text_color());
}

/// The canvas key's secondary-crack row (the UI tests look for it).
pub const SECONDARY_KEY: &str = "secondary crack (from a kink)";
/// The canvas key's row for cracks started in the intact rock.
pub const INTACT_KEY: &str = "crack started in intact rock";

/// The key at the canvas's bottom right (the pointer's position is at the
/// bottom left): with `tips` (tip markers shown), each marker's colour is
/// the decision at that tip and the ring the inspected tip; with
/// `secondary` (a secondary crack drawn), the secondary cracks' colour;
/// with `intact` (a crack started in the intact rock), theirs. Nothing
/// without any. Returns the rectangle it covers (`None`: no rows).
pub fn paint_key(
    painter: &Painter,
    canvas: egui::Rect,
    tips: bool,
    secondary: bool,
    intact: bool,
) -> Option<egui::Rect> {
    let rows = key_rows(tips, secondary, intact);
    if rows.is_empty() {
        return None;
    }
    // the theme's strong text on its window fill, behind the whole key:
    // legible on the field's colours and on either theme's background
    let visuals = painter.ctx().global_style().visuals.clone();
    let text_colour = visuals.strong_text_color();
    let galleys: Vec<_> = rows
        .iter()
        .map(|(_, text)| {
            painter.layout_no_wrap((*text).to_owned(), FontId::proportional(11.0), text_colour)
        })
        .collect();
    let widest = galleys.iter().map(|g| g.size().x).fold(0.0, f32::max);
    let top = canvas.bottom() - 10.0 - 16.0 * (rows.len() - 1) as f32;
    let backing = egui::Rect::from_min_max(
        Pos2::new(canvas.right() - 26.0 - widest - 6.0, top - 10.0),
        Pos2::new(canvas.right() - 2.0, canvas.bottom() - 2.0),
    );
    painter.rect_filled(backing, 3.0, visuals.window_fill.gamma_multiply(0.92));
    let mut y = top;
    for ((key, _), galley) in rows.into_iter().zip(galleys) {
        let q = Pos2::new(canvas.right() - 14.0, y);
        match key {
            Key::Tip(c) => painter.circle(q, 5.0, c, Stroke::new(1.5, Color32::BLACK)),
            Key::Ring => painter.circle_stroke(q, 7.0, Stroke::new(2.0, HANDLE_COLOR)),
            Key::Line(c) => painter.line_segment(
                [q - vec2(7.0, 0.0), q + vec2(7.0, 0.0)],
                Stroke::new(2.5, c),
            ),
        };
        let at = q - vec2(12.0 + galley.size().x, galley.size().y / 2.0);
        painter.galley(at, galley, text_colour);
        y += 16.0;
    }
    Some(backing)
}

/// The rows of [`paint_key`], top to bottom: the tip markers' with `tips`,
/// the secondary cracks' with `secondary`, the intact rock's cracks' with
/// `intact` (no row for what the canvas does not show).
fn key_rows(tips: bool, secondary: bool, intact: bool) -> Vec<(Key, &'static str)> {
    let mut rows = Vec::new();
    if tips {
        rows.extend([
            (Key::Tip(tip_color(Mode::Tension)), "tip grows in tension"),
            (Key::Tip(tip_color(Mode::Shear)), "tip grows in shear"),
            (Key::Tip(tip_color(Mode::None)), "tip does not grow"),
            (Key::Ring, "inspected tip"),
        ]);
    }
    if secondary {
        rows.push((Key::Line(SECONDARY_COLOR), SECONDARY_KEY));
    }
    if intact {
        rows.push((Key::Line(INTACT_COLOR), INTACT_KEY));
    }
    rows
}

/// A row's symbol in [`paint_key`].
enum Key {
    Tip(Color32),
    Ring,
    Line(Color32),
}

/// Editable vertices of the scene's cracks.
pub fn paint_handles(
    painter: &Painter,
    view: &ViewTransform,
    scene: &SceneFile,
    hovered: Option<(usize, usize)>,
) {
    let h = scene.element_size();
    for (i, crack) in scene.cracks.iter().enumerate() {
        if crack.points.is_none() {
            continue;
        }
        for (k, &p) in crack.polyline(h).iter().enumerate() {
            let q = view.screen_from_world(p);
            let r = if hovered == Some((i, k)) { 6.0 } else { 4.0 };
            let rect = egui::Rect::from_center_size(q, Vec2::splat(2.0 * r));
            painter.rect(
                rect,
                1.0,
                HANDLE_COLOR,
                Stroke::new(1.0, Color32::BLACK),
                egui::StrokeKind::Middle,
            );
        }
    }
}
