//! The colour map: sampled sub-cells as coloured quads (optionally at their
//! deformed positions), cached until the samples or the settings change,
//! and the legend.

use cdca::scene::Material;
use egui::{Align2, Color32, FontId, Mesh, Painter, Pos2, Rect, Stroke, Vec2, pos2, vec2};

use super::view::ViewTransform;
use crate::results::field::{FieldKey, FieldKind, FieldSamples, Rock, value_range};

/// What a cached mesh was built from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshKey {
    pub field: FieldKey,
    pub kind: FieldKind,
    pub deform_scale: f64,
    pub clip: bool,
}

/// Quads in world coordinates with their colours, and the colour range.
pub struct FieldMesh {
    pub key: MeshKey,
    /// Four corners per quad, m.
    corners: Vec<[[f64; 2]; 4]>,
    colors: Vec<Color32>,
    /// Colour range in SI units, if the field has values.
    pub range: Option<(f64, f64)>,
}

/// Neutral fill of the deformed shape when no field is chosen.
const PLAIN: Color32 = Color32::from_gray(150);

impl FieldMesh {
    pub fn build(key: MeshKey, samples: &FieldSamples, material: &Material) -> Self {
        let rock = Rock::of(material);
        let values: Vec<f64> = samples
            .samples
            .iter()
            .map(|s| {
                if s.stress[0].is_finite() {
                    key.kind.value(s, &rock)
                } else {
                    f64::NAN
                }
            })
            .collect();
        let range = (key.kind != FieldKind::None)
            .then(|| value_range(&values, key.clip))
            .flatten();
        let [dx, dy] = samples.cell();
        let cols = samples.key.cols;
        let mut corners = Vec::with_capacity(values.len());
        let mut colors = Vec::with_capacity(values.len());
        for (i, (s, v)) in samples.samples.iter().zip(&values).enumerate() {
            if !s.stress[0].is_finite() {
                continue;
            }
            let (col, row) = (i % cols, i / cols);
            let (x0, y0) = (col as f64 * dx, row as f64 * dy);
            let mut quad = [[x0, y0], [x0 + dx, y0], [x0 + dx, y0 + dy], [x0, y0 + dy]];
            for (c, u) in quad.iter_mut().zip(&s.corner_disp) {
                c[0] += key.deform_scale * u[0];
                c[1] += key.deform_scale * u[1];
            }
            corners.push(quad);
            colors.push(match range {
                Some((lo, hi)) => range_colour(((v - lo) / (hi - lo)) as f32),
                None => PLAIN,
            });
        }
        Self {
            key,
            corners,
            colors,
            range,
        }
    }

    /// The quads on screen.
    pub fn paint(&self, painter: &Painter, view: &ViewTransform) {
        let mut mesh = Mesh::default();
        mesh.reserve_vertices(4 * self.corners.len());
        mesh.reserve_triangles(2 * self.corners.len());
        for (quad, &color) in self.corners.iter().zip(&self.colors) {
            let base = mesh.vertices.len() as u32;
            for &c in quad {
                mesh.colored_vertex(view.screen_from_world(c), color);
            }
            mesh.add_triangle(base, base + 1, base + 2);
            mesh.add_triangle(base, base + 2, base + 3);
        }
        painter.add(egui::Shape::mesh(mesh));
    }
}

/// Colour of a value below the colour range (the 1–99 % range leaves the
/// extremes out): grey, unlike any colour of the map (the map's own end,
/// near-black, read as part of it).
pub const BELOW_RANGE: Color32 = Color32::from_rgb(150, 150, 150);
/// Colour of a value above the colour range: pink.
pub const ABOVE_RANGE: Color32 = Color32::from_rgb(255, 150, 220);

/// The colour of `t` = (v − lo)/(hi − lo): the map inside [0, 1], the
/// out-of-range colours outside it.
pub fn range_colour(t: f32) -> Color32 {
    if t < -1e-6 {
        BELOW_RANGE
    } else if t > 1.0 + 1e-6 {
        ABOVE_RANGE
    } else {
        turbo(t)
    }
}

/// Google's "turbo" colour map (polynomial fit), `t` in [0, 1].
pub fn turbo(t: f32) -> Color32 {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let poly = |c: [f32; 6]| c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
    let r = poly([
        0.135_721_38,
        4.615_392_6,
        -42.660_324,
        132.131_08,
        -152.942_4,
        59.286_38,
    ]);
    let g = poly([
        0.091_402_61,
        2.194_188_4,
        4.842_966_6,
        -14.185_033,
        4.277_298_6,
        2.829_566,
    ]);
    let b = poly([
        0.106_673_3,
        12.641_946,
        -60.582_05,
        110.362_77,
        -89.903_11,
        27.348_25,
    ]);
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    Color32::from_rgb(byte(r), byte(g), byte(b))
}

/// A vertical colour bar with ticks in the field's unit, in the canvas's
/// top-right corner, ending above `bottom` (the key's top) where the
/// canvas is short; returns the rectangle it covers. Its backing is
/// opaque: the text keeps its contrast over any field colour.
pub fn paint_legend(
    painter: &Painter,
    canvas: Rect,
    bottom: f32,
    kind: FieldKind,
    (lo, hi): (f64, f64),
    clipped: bool,
) -> Rect {
    let (unit, factor) = kind.unit();
    // 200 px high where the canvas has room, shorter above the key
    let below = if clipped { 38.0 } else { 26.0 };
    let height = (bottom - canvas.top() - 40.0 - below).clamp(40.0, 200.0);
    let bar = Rect::from_min_size(
        pos2(canvas.right() - 90.0, canvas.top() + 40.0),
        vec2(16.0, height),
    );
    let text_color = painter.ctx().global_style().visuals.text_color();
    let bg = Rect::from_min_max(
        bar.min - vec2(8.0, 30.0),
        pos2(canvas.right() - 4.0, bar.bottom() + below),
    );
    painter.rect_filled(
        bg,
        4.0,
        painter.ctx().global_style().visuals.extreme_bg_color,
    );
    let steps = 48;
    let mut mesh = Mesh::default();
    for k in 0..steps {
        let t0 = k as f32 / steps as f32;
        let t1 = (k + 1) as f32 / steps as f32;
        let r = Rect::from_x_y_ranges(
            bar.x_range(),
            bar.bottom() - t1 * bar.height()..=bar.bottom() - t0 * bar.height(),
        );
        mesh.add_colored_rect(r, turbo(0.5 * (t0 + t1)));
    }
    painter.add(egui::Shape::mesh(mesh));
    painter.rect_stroke(
        bar,
        0.0,
        Stroke::new(1.0, text_color),
        egui::StrokeKind::Outside,
    );
    let font = FontId::proportional(11.0);
    painter.text(
        bar.left_top() - vec2(0.0, 8.0),
        Align2::LEFT_BOTTOM,
        format!("{} [{unit}]", kind.label()),
        font.clone(),
        text_color,
    );
    for k in 0..=4 {
        let t = f64::from(k) / 4.0;
        let y = bar.bottom() - t as f32 * bar.height();
        let v = (lo + t * (hi - lo)) * factor;
        let p = Pos2::new(bar.right() + 4.0, y);
        painter.line_segment([p - Vec2::X * 4.0, p], Stroke::new(1.0, text_color));
        painter.text(
            p + Vec2::X * 2.0,
            Align2::LEFT_CENTER,
            crate::style::units::significant(v),
            font.clone(),
            text_color,
        );
    }
    if clipped {
        painter.text(
            bar.left_bottom() + vec2(0.0, 6.0),
            Align2::LEFT_TOP,
            "1–99 % range",
            font.clone(),
            text_color,
        );
        // the out-of-range colours, in a row under the range's note
        for (colour, dx, text) in [(ABOVE_RANGE, 0.0, "above"), (BELOW_RANGE, 42.0, "below")] {
            let swatch = Rect::from_min_size(bar.left_bottom() + vec2(dx, 24.0), vec2(8.0, 8.0));
            painter.rect_filled(swatch, 0.0, colour);
            painter.text(
                swatch.right_center() + vec2(4.0, 0.0),
                Align2::LEFT_CENTER,
                text,
                font.clone(),
                text_color,
            );
        }
    }
    bg
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values beyond the colour range are marked by colours of their own,
    /// not the map's dark ends.
    #[test]
    fn out_of_range_values_have_their_own_colours() {
        assert_eq!(range_colour(-0.2), BELOW_RANGE);
        assert_eq!(range_colour(1.2), ABOVE_RANGE);
        assert_eq!(range_colour(0.0), turbo(0.0));
        assert_eq!(range_colour(1.0), turbo(1.0));
        assert_ne!(BELOW_RANGE, turbo(0.0));
        assert_ne!(ABOVE_RANGE, turbo(1.0));
    }

    #[test]
    fn turbo_runs_from_blue_to_red() {
        let lo = turbo(0.15);
        let hi = turbo(0.9);
        assert!(lo.b() > lo.r());
        assert!(hi.r() > hi.b());
        assert_eq!(turbo(f32::NAN), turbo(0.0));
    }
}
