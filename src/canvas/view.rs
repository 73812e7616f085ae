//! The map from specimen coordinates (m, y up) to screen points (y down):
//! pan and zoom.

use egui::{Pos2, Rect, Vec2, pos2};

/// Width of the column the canvas's key and colour legend take at its
/// right, points (the key's widest row and its swatch).
pub const KEY_COLUMN: f32 = 180.0;

/// Width the colour legend takes from the canvas's right edge, and the
/// height of the key at its bottom right (five rows), points: what a
/// canvas the specimen's width bounds keeps free beside and below it.
const LEGEND_WIDTH: f32 = 104.0;
const KEY_HEIGHT: f32 = 92.0;

/// Pan and zoom of the canvas.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewTransform {
    /// The world point at the centre of the canvas, m.
    pub center_world: [f64; 2],
    /// Screen points per metre.
    pub points_per_m: f64,
    /// The canvas on screen.
    pub rect: Rect,
}

impl Default for ViewTransform {
    fn default() -> Self {
        Self {
            center_world: [0.0; 2],
            points_per_m: 1000.0,
            rect: Rect::from_min_size(Pos2::ZERO, Vec2::splat(100.0)),
        }
    }
}

impl ViewTransform {
    pub fn screen_from_world(&self, p: [f64; 2]) -> Pos2 {
        let c = self.rect.center();
        pos2(
            c.x + ((p[0] - self.center_world[0]) * self.points_per_m) as f32,
            c.y - ((p[1] - self.center_world[1]) * self.points_per_m) as f32,
        )
    }

    pub fn world_from_screen(&self, q: Pos2) -> [f64; 2] {
        let c = self.rect.center();
        [
            self.center_world[0] + f64::from(q.x - c.x) / self.points_per_m,
            self.center_world[1] - f64::from(q.y - c.y) / self.points_per_m,
        ]
    }

    /// A world vector (m, y up) as a screen vector.
    pub fn screen_vec(&self, v: [f64; 2]) -> Vec2 {
        Vec2::new(
            (v[0] * self.points_per_m) as f32,
            (-v[1] * self.points_per_m) as f32,
        )
    }

    /// Shows the rectangle `[0, width] × [0, height]` with a margin for
    /// the load arrows: 70 points on a large canvas, down to 36 on a small
    /// one (a projector's 1024 × 640), where the specimen comes first.
    ///
    /// A specimen the canvas's height bounds leaves width spare: up to
    /// [`KEY_COLUMN`] of it goes to the right, where the key and the colour
    /// legend stand (at 1024 × 640 the key covered the specimen's corner).
    /// One its width bounds (a phone's tall canvas) is drawn smaller, clear
    /// of the colour legend at its right, and moved up, clear of the key
    /// below it (at 390 × 844 both covered its right-hand corners).
    pub fn fit(&mut self, rect: Rect, width: f64, height: f64) {
        self.rect = rect;
        let margin = (0.1 * rect.width().min(rect.height())).clamp(36.0, 70.0);
        let inner = f64::from((rect.width() - 2.0 * margin).max(20.0));
        let inner_y = f64::from((rect.height() - 2.0 * margin).max(20.0));
        let sx = inner / width;
        let sy = inner_y / height;
        let legend = f64::from((LEGEND_WIDTH - margin).max(0.0));
        self.points_per_m = if sx < sy {
            ((inner - legend) / width).clamp(0.5 * sx, sy)
        } else {
            sy
        };
        let spare = (inner - width * self.points_per_m).min(f64::from(KEY_COLUMN));
        let below = (inner_y - height * self.points_per_m)
            .min(f64::from(2.0 * (KEY_HEIGHT - margin).max(0.0)));
        self.center_world = [
            0.5 * width + 0.5 * spare / self.points_per_m,
            0.5 * height - 0.5 * below / self.points_per_m,
        ];
    }

    /// Zooms by `factor` keeping the world point under `anchor` in place.
    pub fn zoom_about(&mut self, anchor: Pos2, factor: f64) {
        let w = self.world_from_screen(anchor);
        self.points_per_m = (self.points_per_m * factor).clamp(1.0, 1e7);
        let c = self.rect.center();
        self.center_world = [
            w[0] - f64::from(anchor.x - c.x) / self.points_per_m,
            w[1] + f64::from(anchor.y - c.y) / self.points_per_m,
        ];
    }

    /// Moves the view with the pointer by `delta` screen points.
    pub fn pan(&mut self, delta: Vec2) {
        self.center_world[0] -= f64::from(delta.x) / self.points_per_m;
        self.center_world[1] += f64::from(delta.y) / self.points_per_m;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view() -> ViewTransform {
        let mut v = ViewTransform::default();
        v.fit(
            Rect::from_min_size(pos2(10.0, 20.0), Vec2::new(800.0, 600.0)),
            0.3,
            0.3,
        );
        v
    }

    #[test]
    fn screen_and_world_round_trip() {
        let v = view();
        let p = [0.07, 0.21];
        let back = v.world_from_screen(v.screen_from_world(p));
        assert!((back[0] - p[0]).abs() < 1e-6 && (back[1] - p[1]).abs() < 1e-6);
    }

    #[test]
    fn world_y_points_up_on_screen() {
        let v = view();
        assert!(v.screen_from_world([0.0, 0.3]).y < v.screen_from_world([0.0, 0.0]).y);
    }

    #[test]
    fn zoom_keeps_the_anchor_fixed() {
        let mut v = view();
        let anchor = pos2(123.0, 456.0);
        let before = v.world_from_screen(anchor);
        v.zoom_about(anchor, 2.5);
        let after = v.world_from_screen(anchor);
        assert!((before[0] - after[0]).abs() < 1e-9 && (before[1] - after[1]).abs() < 1e-9);
    }

    #[test]
    fn pan_moves_content_with_the_pointer() {
        let mut v = view();
        let p = [0.1, 0.1];
        let before = v.screen_from_world(p);
        v.pan(Vec2::new(15.0, -7.0));
        let after = v.screen_from_world(p);
        assert!(
            (after.x - before.x - 15.0).abs() < 1e-3 && (after.y - before.y + 7.0).abs() < 1e-3
        );
    }
}
