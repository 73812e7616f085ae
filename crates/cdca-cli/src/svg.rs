//! Hand-written SVG, the few elements the CLI's figures draw (`cdca bench`'s
//! error against run time, `cdca study --map`): a white page, lines,
//! rectangles, polylines and text (escaped).

use std::fmt::Write as _;

/// An SVG picture being written.
pub struct Svg {
    out: String,
}

impl Svg {
    /// A white page `width × height` px, sans-serif 12 px text.
    pub fn new(width: f64, height: f64) -> Self {
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
        );
        let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
        Self { out }
    }

    /// A line from `a` to `b`; `attrs` (with a leading space) adds to the
    /// stroke, e.g. ` stroke-width="2"`.
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), stroke: &str, attrs: &str) {
        let _ = writeln!(
            self.out,
            r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{stroke}"{attrs}/>"#,
            a.0, a.1, b.0, b.1
        );
    }

    /// A rectangle at (x, y) of `w × h`.
    pub fn rect(&mut self, (x, y): (f64, f64), (w, h): (f64, f64), fill: &str, stroke: &str) {
        let _ = writeln!(
            self.out,
            r#"<rect x="{x}" y="{y}" width="{w}" height="{h}" fill="{fill}" stroke="{stroke}"/>"#
        );
    }

    /// A polyline through `points` (written with one decimal).
    pub fn polyline(&mut self, points: &[(f64, f64)], stroke: &str, attrs: &str) {
        let pts: Vec<String> = points
            .iter()
            .map(|(x, y)| format!("{x:.1},{y:.1}"))
            .collect();
        let _ = writeln!(
            self.out,
            r#"<polyline points="{}" fill="none" stroke="{stroke}"{attrs}/>"#,
            pts.join(" ")
        );
    }

    /// `text` at (x, y); `attrs` (with a leading space) sets its anchor,
    /// size or colour.
    pub fn text(&mut self, (x, y): (f64, f64), attrs: &str, text: &str) {
        let _ = writeln!(
            self.out,
            r#"<text x="{x}" y="{y}"{attrs}>{}</text>"#,
            escape(text)
        );
    }

    /// `text` turned to read upwards, centred on (x, y).
    pub fn vertical_text(&mut self, (x, y): (f64, f64), text: &str) {
        let _ = writeln!(
            self.out,
            r#"<text transform="translate({x},{y}) rotate(-90)" text-anchor="middle">{}</text>"#,
            escape(text)
        );
    }

    /// The finished picture.
    pub fn finish(mut self) -> String {
        self.out.push_str("</svg>\n");
        self.out
    }
}

/// Text with `&`, `<` and `>` escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
