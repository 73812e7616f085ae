//! Legibility: WCAG 2 contrast ratios of the colours the app draws text
//! in against what is behind it, and the theme changes that bring egui's
//! weak text to 4.5:1 (a classroom's back row reads a projector).

use egui::{Color32, Style};

#[cfg(test)]
/// WCAG 2's minimum contrast ratio of body text (level AA).
pub const MIN_TEXT_CONTRAST: f64 = 4.5;

/// Weak text (hints, units) in the light and dark themes: egui's default,
/// the normal text at 60 % opacity, measured 2.9:1 (light) and 2.7:1
/// (dark) on the panels.
const WEAK_TEXT_LIGHT: Color32 = Color32::from_gray(110);
const WEAK_TEXT_DARK: Color32 = Color32::from_gray(132);

/// Error and warning text: egui's pure red measured 3.8:1 (light) and
/// 4.3:1 (dark), its light theme's orange 2.9:1.
const ERROR_LIGHT: Color32 = Color32::from_rgb(190, 0, 0);
const WARN_LIGHT: Color32 = Color32::from_rgb(160, 70, 0);
const ERROR_DARK: Color32 = Color32::from_rgb(255, 90, 90);

/// The app's changes to an egui style: weak, error and warning text
/// legible on the panels (applied to both themes in the first frame).
pub fn legible(style: &mut Style) {
    let v = &mut style.visuals;
    if v.dark_mode {
        v.weak_text_color = Some(WEAK_TEXT_DARK);
        v.error_fg_color = ERROR_DARK;
    } else {
        v.weak_text_color = Some(WEAK_TEXT_LIGHT);
        v.error_fg_color = ERROR_LIGHT;
        v.warn_fg_color = WARN_LIGHT;
    }
}

#[cfg(test)]
/// The relative luminance of an opaque colour (WCAG 2: linear sRGB
/// weighted 0.2126, 0.7152, 0.0722).
pub fn luminance(c: Color32) -> f64 {
    let lin = |v: u8| {
        let s = f64::from(v) / 255.0;
        if s <= 0.040_45 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(c.r()) + 0.7152 * lin(c.g()) + 0.0722 * lin(c.b())
}

#[cfg(test)]
/// `fg` (premultiplied, maybe translucent) drawn over the opaque `bg`, as
/// egui blends (in gamma space).
pub fn over(fg: Color32, bg: Color32) -> Color32 {
    let keep = 1.0 - f32::from(fg.a()) / 255.0;
    let mix = |f: u8, b: u8| (f32::from(f) + keep * f32::from(b)).round().min(255.0) as u8;
    Color32::from_rgb(
        mix(fg.r(), bg.r()),
        mix(fg.g(), bg.g()),
        mix(fg.b(), bg.b()),
    )
}

#[cfg(test)]
/// The contrast ratio of text `fg` over the opaque background `bg`,
/// 1 to 21.
pub fn contrast(fg: Color32, bg: Color32) -> f64 {
    let (a, b) = (luminance(over(fg, bg)), luminance(bg));
    (a.max(b) + 0.05) / (a.min(b) + 0.05)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The app's visuals in both themes, as `legible` leaves them.
    fn themes() -> [(&'static str, egui::Visuals); 2] {
        [
            ("light", egui::Visuals::light()),
            ("dark", egui::Visuals::dark()),
        ]
        .map(|(name, visuals)| {
            let mut style = Style {
                visuals,
                ..Style::default()
            };
            legible(&mut style);
            (name, style.visuals)
        })
    }

    #[test]
    fn the_ratio_matches_wcag_reference_values() {
        assert!((contrast(Color32::BLACK, Color32::WHITE) - 21.0).abs() < 1e-9);
        assert!((contrast(Color32::WHITE, Color32::WHITE) - 1.0).abs() < 1e-9);
        // #767676 on white is the lightest grey at 4.5:1
        let r = contrast(Color32::from_gray(0x76), Color32::WHITE);
        assert!((r - 4.54).abs() < 0.01, "{r}");
        // half-transparent black over white is a mid grey
        assert_eq!(
            over(Color32::from_black_alpha(128), Color32::WHITE),
            Color32::from_gray(127)
        );
    }

    /// Every text colour the app draws, on what is behind it, in both
    /// themes: at least 4.5:1.
    #[test]
    fn every_text_the_app_draws_has_at_least_4_5_to_1() {
        let mut failures = Vec::new();
        let mut lowest = f64::INFINITY;
        for (theme, v) in themes() {
            let pairs = [
                // panels: normal, weak and strong text on the panel fill
                ("text on panel", v.text_color(), v.panel_fill),
                ("weak text on panel", v.weak_text_color(), v.panel_fill),
                ("strong text on panel", v.strong_text_color(), v.panel_fill),
                // plots: note marks (small strong) on the plot's
                // background, notes below the plot (small) on the panel
                ("plot note mark", v.strong_text_color(), v.extreme_bg_color),
                ("plot note text", v.text_color(), v.panel_fill),
                ("plot hint (weak)", v.weak_text_color(), v.panel_fill),
                // canvas: the pointer's position and the tool hint
                // (`Canvas::paint_status`) on the canvas background
                ("canvas status", v.text_color(), v.extreme_bg_color),
                // the field's colour legend: text on its opaque backing
                ("legend text", v.text_color(), v.extreme_bg_color),
                // the frame overlay: strong text on its backing
                ("frame overlay", v.strong_text_color(), v.extreme_bg_color),
                // the canvas key: strong text on the window fill (92 %
                // over whatever is behind: the worst case is either
                // extreme)
                (
                    "key on backing over white",
                    v.strong_text_color(),
                    over(v.window_fill.gamma_multiply(0.92), Color32::WHITE),
                ),
                (
                    "key on backing over black",
                    v.strong_text_color(),
                    over(v.window_fill.gamma_multiply(0.92), Color32::BLACK),
                ),
                // error and warning banners
                ("error text", v.error_fg_color, v.panel_fill),
                ("warning text", v.warn_fg_color, v.panel_fill),
            ];
            for (what, fg, bg) in pairs {
                let r = contrast(fg, bg);
                lowest = lowest.min(r);
                if r < MIN_TEXT_CONTRAST {
                    failures.push(format!("{theme}: {what} {r:.2}:1 ({fg:?} on {bg:?})"));
                }
            }
        }
        assert!(failures.is_empty(), "below 4.5:1: {failures:#?}");
        eprintln!("lowest text contrast: {lowest:.2}:1");
    }

    /// egui's own weak and error text, which `legible` replaces, are
    /// below 4.5:1 on its panels (the reason for the change).
    #[test]
    fn egui_default_weak_and_error_text_are_too_faint() {
        for v in [egui::Visuals::light(), egui::Visuals::dark()] {
            for fg in [v.weak_text_color(), v.error_fg_color] {
                let r = contrast(fg, v.panel_fill);
                assert!(r < MIN_TEXT_CONTRAST, "{r}");
            }
        }
    }
}
