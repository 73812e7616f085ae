//! Which side panels show and how large the text is: one window layout
//! for a desktop, a classroom projector and a phone.

use serde::{Deserialize, Serialize};

/// Below this window width (logical points, after the text size's zoom)
/// the side panels start hidden and open one at a time.
pub const NARROW_WIDTH: f32 = 800.0;

/// The View menu's text sizes (egui's zoom factor).
pub const TEXT_SCALES: [f32; 4] = [1.0, 1.25, 1.5, 2.0];

/// What is kept across restarts (persisted with the view settings).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct LayoutSettings {
    /// The Scene panel (left) is shown.
    pub show_scene: bool,
    /// The Solver panel (right) is shown.
    pub show_solver: bool,
    /// Text and widget size, 1.0 = 100 %.
    pub text_scale: f32,
}

impl Default for LayoutSettings {
    fn default() -> Self {
        Self {
            show_scene: true,
            show_solver: true,
            text_scale: 1.0,
        }
    }
}

/// The layout settings and what the last frame saw of the window.
#[derive(Clone, Debug, Default)]
pub struct Layout {
    pub settings: LayoutSettings,
    /// The window was narrow last frame (`None` before the first frame).
    narrow: Option<bool>,
    /// The zoom factor this layout last set.
    applied_scale: Option<f32>,
}

impl Layout {
    pub fn new(settings: LayoutSettings) -> Self {
        Self {
            settings,
            ..Self::default()
        }
    }

    /// Follows the window's width, once a frame: a window that starts
    /// narrow, or becomes narrow, hides both side panels (the run bar
    /// stays). Returns whether the window is narrow.
    pub fn follow_width(&mut self, width: f32) -> bool {
        let narrow = width < NARROW_WIDTH;
        if narrow && self.narrow != Some(true) {
            self.settings.show_scene = false;
            self.settings.show_solver = false;
        }
        self.narrow = Some(narrow);
        narrow
    }

    /// Whether the window was narrow last frame.
    pub fn is_narrow(&self) -> bool {
        self.narrow == Some(true)
    }

    /// Shows or hides the Scene panel; on a narrow window it opens alone.
    pub fn toggle_scene(&mut self) {
        self.settings.show_scene = !self.settings.show_scene;
        if self.settings.show_scene && self.is_narrow() {
            self.settings.show_solver = false;
        }
    }

    /// Shows or hides the Solver panel; on a narrow window it opens alone.
    pub fn toggle_solver(&mut self) {
        self.settings.show_solver = !self.settings.show_solver;
        if self.settings.show_solver && self.is_narrow() {
            self.settings.show_scene = false;
        }
    }

    /// Applies the text size as egui's zoom factor. A zoom set elsewhere
    /// (egui's Ctrl + / Ctrl − natively) becomes the text size.
    pub fn apply_text_scale(&mut self, ctx: &egui::Context) {
        let zoom = ctx.zoom_factor();
        if let Some(applied) = self.applied_scale
            && (zoom - applied).abs() > 1e-3
        {
            self.settings.text_scale = zoom;
        }
        if (zoom - self.settings.text_scale).abs() > 1e-3 {
            ctx.set_zoom_factor(self.settings.text_scale);
        }
        self.applied_scale = Some(self.settings.text_scale);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_narrow_window_starts_with_both_panels_hidden_and_opens_one_at_a_time() {
        let mut l = Layout::default();
        assert!(l.follow_width(390.0));
        assert!(!l.settings.show_scene && !l.settings.show_solver);
        l.toggle_scene();
        assert!(l.settings.show_scene);
        l.toggle_solver();
        assert!(l.settings.show_solver && !l.settings.show_scene);
    }

    #[test]
    fn a_wide_window_keeps_the_saved_panels() {
        let mut l = Layout::new(LayoutSettings {
            show_scene: false,
            ..LayoutSettings::default()
        });
        assert!(!l.follow_width(1280.0));
        assert!(!l.settings.show_scene && l.settings.show_solver);
        l.toggle_scene();
        assert!(l.settings.show_scene && l.settings.show_solver);
        // becoming narrow hides both, widening again leaves them so
        l.follow_width(600.0);
        assert!(!l.settings.show_scene && !l.settings.show_solver);
        l.follow_width(1280.0);
        assert!(!l.settings.show_scene);
    }
}
