//! A plot as data: named series with one colour each, axis titles with
//! units, tick steps, and notes on surprising points. The plot panel draws a
//! `Figure` with egui_plot; the same `Figure` is written as CSV (the
//! numbers) and SVG (the picture, for slides), so what is exported is what
//! is shown.

use std::fmt::Write as _;

use egui::Color32;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// A line through the points, with a marker at each.
    LineAndMarkers,
    /// A dashed line through the points, with a marker at each (a crack's
    /// second end beside its first, solid).
    DashedAndMarkers,
    /// A line with a diamond at each point (K_II beside K_I's circles).
    LineAndDiamonds,
    /// A dashed line with a diamond at each point.
    DashedAndDiamonds,
    /// A line only (long histories).
    Line,
    /// A dashed line only.
    Dashed,
    /// Markers only (one value per parameter).
    Markers,
    /// A dotted link between two values of another series across x where
    /// that series has none (a tip that did not grow for some steps):
    /// drawn, but neither in the legend nor in the exported numbers.
    Gap,
}

/// The marker drawn at each point of a series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Diamond,
}

impl Style {
    /// A line is drawn through the points.
    pub fn has_line(self) -> bool {
        self != Self::Markers
    }

    /// The line is dashed.
    pub fn dashed(self) -> bool {
        matches!(
            self,
            Self::Dashed | Self::DashedAndMarkers | Self::DashedAndDiamonds
        )
    }

    /// The marker at each point, if any.
    pub fn marker(self) -> Option<Marker> {
        match self {
            Self::LineAndMarkers | Self::DashedAndMarkers | Self::Markers => Some(Marker::Circle),
            Self::LineAndDiamonds | Self::DashedAndDiamonds => Some(Marker::Diamond),
            Self::Line | Self::Dashed | Self::Gap => None,
        }
    }

    /// The style of a crack end's series: end 1 (`tip` 0) solid, end 2
    /// dashed; circles, or diamonds for `diamonds` (K_II).
    pub fn of_end(tip: usize, diamonds: bool) -> Self {
        match (tip == 0, diamonds) {
            (true, false) => Self::LineAndMarkers,
            (false, false) => Self::DashedAndMarkers,
            (true, true) => Self::LineAndDiamonds,
            (false, true) => Self::DashedAndDiamonds,
        }
    }
}

/// One named series.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub colour: Color32,
    pub style: Style,
    /// `[x, y]` in the axis units (y as log10 on a log axis).
    pub points: Vec<[f64; 2]>,
}

/// A note on a point: what it means where it is surprising.
#[derive(Clone, Debug, PartialEq)]
pub struct Note {
    pub at: [f64; 2],
    pub text: String,
}

/// Tick steps of the y axis.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum YTicks {
    /// 1, 2 or 5 × 10^k, whichever keeps the labels apart.
    #[default]
    Decimal,
    /// Angles: 15°, 30°, 45° or 90°.
    Degrees,
    /// y is log10 of the value: ticks at whole decades, labelled `1e-6`.
    Log,
}

/// A plot: series, axes and notes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Figure {
    /// File-name stem and plot id (`angles`, `sifs`, …).
    pub id: String,
    pub x_label: String,
    pub y_label: String,
    pub y_ticks: YTicks,
    pub series: Vec<Series>,
    /// Vertical reference lines: name, x, colour.
    pub vlines: Vec<(String, f64, Color32)>,
    pub notes: Vec<Note>,
    /// y values the axis range always includes.
    pub include_y: Vec<f64>,
    /// x values the axis range always includes.
    pub include_x: Vec<f64>,
    /// The y axis stops here: a point above it (an outlier that would
    /// flatten the rest) is drawn as a mark at the axis's top edge, with
    /// its value in a note; the exported numbers keep it.
    pub y_max: Option<f64>,
    /// What the line styles and markers mean, said once beside the legend
    /// (`solid: end 1, dashed: end 2`).
    pub key: String,
    /// x counts something (growth steps): ticks at whole numbers only.
    pub x_whole: bool,
    /// One legend entry per colour, named up to [`COMPACT_CUT`] (the race:
    /// one per solver; which line style is which is said once beside it).
    pub compact_legend: bool,
}

/// Where a series' name is cut in a compact legend.
pub const COMPACT_CUT: &str = " — ";

/// The marks beside a noted point, pointing at it from its right and from
/// its left, with the notes' numbers: glyphs egui's default font has (its
/// "◀" was drawn as a missing-glyph box).
pub const NOTE_MARKS: [&str; 2] = ["‹", "›"];

/// Smallest tick step of `kind` that is at least `min_step`.
pub fn tick_step(kind: YTicks, min_step: f64) -> f64 {
    if !(min_step.is_finite() && min_step > 0.0) {
        return 1.0;
    }
    match kind {
        YTicks::Degrees => [15.0, 30.0, 45.0, 90.0, 180.0]
            .into_iter()
            .find(|&s| s >= min_step)
            .unwrap_or(360.0),
        YTicks::Log => min_step.ceil().max(1.0),
        YTicks::Decimal => {
            let decade = 10f64.powf(min_step.log10().floor());
            [1.0, 2.0, 5.0, 10.0]
                .into_iter()
                .map(|m| m * decade)
                .find(|&s| s >= min_step * (1.0 - 1e-12))
                .unwrap_or(10.0 * decade)
        }
    }
}

/// Tick values in `[lo, hi]` at multiples of `step`.
pub fn ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last.min(first + 1000))
        .map(|k| k as f64 * step)
        .collect()
}

/// A tick label: whole numbers plainly, others with the digits the step
/// needs; on a log axis `1e-6`.
pub fn tick_label(kind: YTicks, value: f64, step: f64) -> String {
    match kind {
        YTicks::Log => format!("1e{}", value.round()),
        YTicks::Degrees => format!("{value:.0}°"),
        YTicks::Decimal => {
            // the decimals that write the step itself: the step's magnitude
            // alone gave 2.5 (the major step of a 0.5 grid) none, and the
            // ticks at 2.5 and 7.5 read "2" and "8"
            let digits = (0..=12)
                .find(|&d| {
                    let scaled = step.abs() * 10f64.powi(d);
                    (scaled - scaled.round()).abs() <= 1e-6 * scaled.max(1.0)
                })
                .unwrap_or(12) as usize;
            let v = if value.abs() < 0.5 * step { 0.0 } else { value };
            format!("{v:.digits$}")
        }
    }
}

impl Figure {
    /// The legend's entries: each series name once (a series drawn in
    /// pieces, broken where it has no value, repeats its name and colour),
    /// gaps left out.
    pub fn legend(&self) -> impl Iterator<Item = &Series> {
        self.series
            .iter()
            .enumerate()
            .filter(|(i, s)| {
                s.style != Style::Gap
                    && !self.series[..*i]
                        .iter()
                        .any(|t| t.name == s.name || (self.compact_legend && t.colour == s.colour))
            })
            .map(|(_, s)| s)
    }

    /// The notes' numbered marks, one per noted point in the order of its
    /// first note: the point and its notes' numbers (from 1), so that two
    /// notes on one point share a mark ("2, 3") instead of drawing their
    /// numbers over each other.
    pub fn note_marks(&self) -> Vec<([f64; 2], String)> {
        let mut marks: Vec<([f64; 2], String)> = Vec::new();
        for (i, n) in self.notes.iter().enumerate() {
            match marks.iter_mut().find(|(at, _)| *at == n.at) {
                Some((_, numbers)) => {
                    let _ = write!(numbers, ", {}", i + 1);
                }
                None => marks.push((n.at, (i + 1).to_string())),
            }
        }
        marks
    }

    /// The notes' marks as [`note_marks`](Self::note_marks), with marks
    /// closer than `near` (x, y, in axis units) merged into the first:
    /// numbers at nearby points were drawn over each other ("3, 9" on
    /// "4").
    pub fn note_marks_near(&self, near: [f64; 2]) -> Vec<([f64; 2], String)> {
        let mut merged: Vec<([f64; 2], String)> = Vec::new();
        for (at, numbers) in self.note_marks() {
            let close = |m: &&mut ([f64; 2], String)| {
                (m.0[0] - at[0]).abs() <= near[0] && (m.0[1] - at[1]).abs() <= near[1]
            };
            match merged.iter_mut().find(|m| close(m)) {
                Some((_, first)) => {
                    let _ = write!(first, ", {numbers}");
                }
                None => merged.push((at, numbers)),
            }
        }
        merged
    }

    /// Where a point is drawn: at the axis's top edge when above
    /// [`y_max`](Self::y_max).
    pub fn shown_y(&self, y: f64) -> f64 {
        self.y_max.map_or(y, |top| y.min(top))
    }

    /// A series' name in the legend (cut short in a compact legend).
    pub fn legend_name<'a>(&self, s: &'a Series) -> &'a str {
        if self.compact_legend {
            s.name.split(COMPACT_CUT).next().unwrap_or(&s.name)
        } else {
            &s.name
        }
    }

    /// The series as CSV, one row per point: `series,x,y` with the axis
    /// titles (and units) in the header; log axes are written as values.
    pub fn to_csv(&self) -> String {
        let mut out = format!(
            "series,{},{}\n",
            cdca::csv::field(&self.x_label),
            cdca::csv::field(&self.y_label.replace(", log", ""))
        );
        for s in self.series.iter().filter(|s| s.style != Style::Gap) {
            for p in &s.points {
                let y = if self.y_ticks == YTicks::Log {
                    10f64.powf(p[1])
                } else {
                    p[1]
                };
                let _ = writeln!(out, "{},{},{}", cdca::csv::field(&s.name), p[0], y);
            }
        }
        for (name, x, _) in &self.vlines {
            let _ = writeln!(out, "{},{},", cdca::csv::field(name), x);
        }
        out
    }

    /// Data range `(x_lo, x_hi, y_lo, y_hi)`, padded (y at most
    /// [`y_max`](Self::y_max)).
    pub fn bounds(&self) -> (f64, f64, f64, f64) {
        let points = || self.series.iter().flat_map(|s| &s.points);
        let (x0, x1) = padded_range(
            points()
                .map(|p| p[0])
                .chain(self.vlines.iter().map(|v| v.1))
                .chain(self.include_x.iter().copied()),
        );
        let (y0, y1) = padded_range(
            points()
                .map(|p| self.shown_y(p[1]))
                .chain(self.include_y.iter().copied()),
        );
        (x0, x1, y0, y1)
    }

    /// The figure as an SVG picture `width × height` px: axes with ticks and
    /// their values, the axis titles, the series, the notes, and the legend
    /// to the right of the data.
    pub fn to_svg(&self, width: f64, height: f64) -> String {
        let (left, right, top, bottom) = (70.0, 230.0, 20.0, 50.0);
        let (pw, ph) = (width - left - right, height - top - bottom);
        let (x0, x1, y0, y1) = self.bounds();
        let sx = |x: f64| left + (x - x0) / (x1 - x0) * pw;
        let sy = |y: f64| top + (y1 - y) / (y1 - y0) * ph;
        let mut svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
             font-family=\"sans-serif\" font-size=\"12\">\n\
             <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
             <rect x=\"{left}\" y=\"{top}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#444\"/>\n"
        );
        let mut x_step = tick_step(YTicks::Decimal, (x1 - x0) / 8.0);
        if self.x_whole {
            x_step = x_step.max(1.0);
        }
        for x in ticks(x0, x1, x_step) {
            let _ = writeln!(
                svg,
                "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{0:.1}\" y2=\"{2:.1}\" stroke=\"#ddd\"/>\
                 <text x=\"{0:.1}\" y=\"{3:.1}\" text-anchor=\"middle\">{4}</text>",
                sx(x),
                top,
                top + ph,
                top + ph + 16.0,
                tick_label(YTicks::Decimal, x, x_step)
            );
        }
        let y_step = tick_step(self.y_ticks, (y1 - y0) / 6.0);
        for y in ticks(y0, y1, y_step) {
            let _ = writeln!(
                svg,
                "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{2:.1}\" y2=\"{1:.1}\" stroke=\"#ddd\"/>\
                 <text x=\"{3:.1}\" y=\"{4:.1}\" text-anchor=\"end\">{5}</text>",
                left,
                sy(y),
                left + pw,
                left - 6.0,
                sy(y) + 4.0,
                tick_label(self.y_ticks, y, y_step)
            );
        }
        let _ = writeln!(
            svg,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n\
             <text transform=\"translate(16 {:.1}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
            left + 0.5 * pw,
            height - 12.0,
            escape(&self.x_label),
            top + 0.5 * ph,
            escape(&self.y_label)
        );
        for s in &self.series {
            let c = hex(s.colour);
            let at: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|p| p[1].is_finite())
                .map(|p| (sx(p[0]), sy(self.shown_y(p[1]))))
                .collect();
            if s.style.has_line() && at.len() > 1 {
                let path: Vec<String> = at.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
                let dash = match s.style {
                    Style::Gap => " stroke-dasharray=\"1.5 4\"",
                    style if style.dashed() => " stroke-dasharray=\"6 4\"",
                    _ => "",
                };
                let _ = writeln!(
                    svg,
                    "<polyline fill=\"none\" stroke=\"{c}\" stroke-width=\"1.5\"{dash} points=\"{}\"/>",
                    path.join(" ")
                );
            }
            for (x, y) in &at {
                let _ = match s.style.marker() {
                    Some(Marker::Circle) => writeln!(
                        svg,
                        "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3\" fill=\"{c}\"/>"
                    ),
                    Some(Marker::Diamond) => writeln!(
                        svg,
                        "<polygon points=\"{x:.1},{:.1} {:.1},{y:.1} {x:.1},{:.1} {:.1},{y:.1}\" fill=\"{c}\"/>",
                        y - 4.0,
                        x + 4.0,
                        y + 4.0,
                        x - 4.0
                    ),
                    None => Ok(()),
                };
            }
        }
        for (name, x, colour) in &self.vlines {
            let _ = writeln!(
                svg,
                "<line x1=\"{0:.1}\" y1=\"{1:.1}\" x2=\"{0:.1}\" y2=\"{2:.1}\" stroke=\"{3}\"><title>{4}</title></line>",
                sx(*x),
                top,
                top + ph,
                hex(*colour),
                escape(name)
            );
        }
        for n in &self.notes {
            let _ = writeln!(
                svg,
                "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"#a00\">{} {}</text>",
                sx(n.at[0]) + 6.0,
                sy(self.shown_y(n.at[1])) + 4.0,
                NOTE_MARKS[0],
                escape(&n.text)
            );
        }
        let legend = self
            .legend()
            .map(|s| (self.legend_name(s), s.colour))
            .chain(self.vlines.iter().map(|v| (v.0.as_str(), v.2)));
        for (k, (name, colour)) in legend.enumerate() {
            let y = top + 14.0 + 18.0 * k as f64;
            let x = left + pw + 16.0;
            let _ = writeln!(
                svg,
                "<rect x=\"{x:.1}\" y=\"{:.1}\" width=\"14\" height=\"4\" fill=\"{}\"/>\
                 <text x=\"{:.1}\" y=\"{y:.1}\">{}</text>",
                y - 6.0,
                hex(colour),
                x + 20.0,
                escape(name)
            );
        }
        svg.push_str("</svg>\n");
        svg
    }
}

/// The finite values' range with 5% room each side (a flat or empty range
/// gets a unit-sized one).
fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        (0.0, 1.0)
    } else if hi - lo < 1e-12 * hi.abs().max(1.0) {
        (lo - 0.5 * lo.abs().max(1.0), hi + 0.5 * hi.abs().max(1.0))
    } else {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

fn hex(c: Color32) -> String {
    format!("#{:02x}{:02x}{:02x}", c.r(), c.g(), c.b())
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_steps_keep_labels_apart_with_round_values() {
        assert_eq!(tick_step(YTicks::Decimal, 0.013), 0.02);
        assert_eq!(tick_step(YTicks::Decimal, 3.0), 5.0);
        assert_eq!(tick_step(YTicks::Decimal, 7.0), 10.0);
        assert_eq!(tick_step(YTicks::Decimal, 10.0), 10.0);
        assert_eq!(tick_step(YTicks::Degrees, 4.0), 15.0);
        assert_eq!(tick_step(YTicks::Degrees, 20.0), 30.0);
        assert_eq!(tick_step(YTicks::Log, 0.3), 1.0);
        assert_eq!(
            ticks(-7.0, 82.0, 15.0),
            vec![0.0, 15.0, 30.0, 45.0, 60.0, 75.0]
        );
        assert_eq!(tick_label(YTicks::Decimal, 0.30000000000000004, 0.1), "0.3");
        // a 0.5 grid's major ticks, every 2.5: egui_plot hands each tick
        // the largest step it lies on (2.5 and 7.5 used to read "2", "8")
        assert_eq!(tick_label(YTicks::Decimal, 2.5, 2.5), "2.5");
        assert_eq!(tick_label(YTicks::Decimal, 7.5, 2.5), "7.5");
        assert_eq!(tick_label(YTicks::Decimal, 5.0, 2.5), "5.0");
        assert_eq!(tick_label(YTicks::Decimal, 0.75, 0.25), "0.75");
        assert_eq!(tick_label(YTicks::Decimal, 4.0, 2.0), "4");
        assert_eq!(tick_label(YTicks::Decimal, 3000.0, 500.0), "3000");
        assert_eq!(tick_label(YTicks::Log, -6.0, 1.0), "1e-6");
        assert_eq!(tick_label(YTicks::Degrees, 75.0, 15.0), "75°");
    }

    fn angles() -> Figure {
        Figure {
            id: "angles".into(),
            x_label: "growth step".into(),
            y_label: "kink angle [°]".into(),
            y_ticks: YTicks::Degrees,
            series: vec![Series {
                name: "crack 1, end 2".into(),
                colour: Color32::from_rgb(70, 140, 255),
                style: Style::LineAndMarkers,
                points: vec![[1.0, 70.2], [2.0, 12.5], [3.0, -4.0]],
            }],
            notes: vec![Note {
                at: [3.0, -4.0],
                text: "a tip left the specimen".into(),
            }],
            ..Figure::default()
        }
    }

    /// The CSV holds every point with the axis titles and units.
    #[test]
    fn csv_has_the_units_and_every_point() {
        let csv = angles().to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "series,growth step,kink angle [°]");
        assert_eq!(lines[1], "\"crack 1, end 2\",1,70.2");
        assert_eq!(lines.len(), 4);
        let log = Figure {
            y_ticks: YTicks::Log,
            y_label: "relative residual [–], log".into(),
            series: vec![Series {
                name: "r".into(),
                colour: Color32::BLACK,
                style: Style::Line,
                points: vec![[1.0, -6.0]],
            }],
            ..Figure::default()
        };
        let csv = log.to_csv();
        assert!(csv.starts_with("series,,relative residual [–]\n"), "{csv}");
        let y: f64 = csv
            .lines()
            .nth(1)
            .and_then(|l| l.rsplit(',').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0);
        assert!((y - 1e-6).abs() < 1e-18, "{y}");
    }

    /// The SVG labels the y axis every 15° or 30° across the data, shows
    /// the axis titles, the legend and the note.
    #[test]
    fn svg_has_ticks_titles_legend_and_notes() {
        let svg = angles().to_svg(800.0, 450.0);
        for label in ["0°", "15°", "30°", "45°", "60°"] {
            assert!(svg.contains(&format!(">{label}</text>")), "{label} missing");
        }
        assert!(svg.contains(">kink angle [°]</text>"));
        assert!(svg.contains(">growth step</text>"));
        assert!(svg.contains(">crack 1, end 2</text>"));
        assert!(svg.contains("a tip left the specimen"));
        assert_eq!(svg.matches("<circle").count(), 3);
    }
}
