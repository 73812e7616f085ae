//! The error-versus-run-time picture: one log–log panel per scene at the
//! largest size, one curve per solver, the direct solve as a dashed line at
//! its time. Hand-written SVG.

use std::fmt::Write as _;

use super::Run;

const PANEL_W: f64 = 520.0;
const PANEL_H: f64 = 400.0;
const MARGIN: (f64, f64, f64, f64) = (70.0, 20.0, 40.0, 55.0); // left, right, top, bottom
const Y_DECADES: (i32, i32) = (-12, 0);
const COLOURS: [(&str, &str); 5] = [
    ("direct", "#000000"),
    ("automaton", "#d62728"),
    ("automaton-sor", "#ff7f0e"),
    ("cg", "#1f77b4"),
    ("multigrid", "#2ca02c"),
];

fn colour(solver: &str) -> &'static str {
    COLOURS
        .iter()
        .find(|(s, _)| *s == solver)
        .map_or("#7f7f7f", |(_, c)| c)
}

/// Log-scale axes of one panel.
struct Axes {
    x0: f64,
    y0: f64,
    decades_x: (i32, i32),
}

impl Axes {
    fn px(&self, seconds: f64) -> f64 {
        let (a, b) = self.decades_x;
        let w = PANEL_W - MARGIN.0 - MARGIN.1;
        let t = (seconds.max(1e-300).log10() - f64::from(a)) / f64::from(b - a);
        self.x0 + MARGIN.0 + t.clamp(0.0, 1.0) * w
    }

    fn py(&self, error: f64) -> f64 {
        let (a, b) = Y_DECADES;
        let h = PANEL_H - MARGIN.2 - MARGIN.3;
        let t = (error.max(1e-300).log10() - f64::from(a)) / f64::from(b - a);
        self.y0 + MARGIN.2 + (1.0 - t.clamp(0.0, 1.0)) * h
    }
}

/// The picture of the runs at size `size`.
pub fn draw(runs: &[Run], size: usize) -> String {
    let scenes: Vec<&str> = runs
        .iter()
        .filter(|r| r.size == size)
        .fold(Vec::new(), |mut v, r| {
            if !v.contains(&r.scene) {
                v.push(r.scene);
            }
            v
        });
    let width = PANEL_W * scenes.len().max(1) as f64;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{PANEL_H}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for (i, scene) in scenes.iter().enumerate() {
        let these: Vec<&Run> = runs
            .iter()
            .filter(|r| r.size == size && r.scene == *scene)
            .collect();
        panel(&mut s, &these, scene, size, PANEL_W * i as f64);
    }
    s.push_str("</svg>\n");
    s
}

fn panel(s: &mut String, runs: &[&Run], scene: &str, size: usize, x0: f64) {
    let times = runs
        .iter()
        .flat_map(|r| r.samples.iter().map(|p| p.seconds))
        .filter(|t| *t > 0.0);
    let (tmin, tmax) = times.fold((f64::INFINITY, 0.0_f64), |(a, b), t| (a.min(t), b.max(t)));
    let lo = if tmin.is_finite() {
        tmin.log10().floor() as i32
    } else {
        -4
    };
    let hi = (tmax.max(1e-3).log10().ceil() as i32).max(lo + 1);
    let ax = Axes {
        x0,
        y0: 0.0,
        decades_x: (lo, hi),
    };
    let (l, r) = (ax.px(10f64.powi(lo)), ax.px(10f64.powi(hi)));
    let (top, bottom) = (ax.py(1.0), ax.py(10f64.powi(Y_DECADES.0)));
    let _ = writeln!(
        s,
        r##"<rect x="{l}" y="{top}" width="{}" height="{}" fill="none" stroke="#444"/>"##,
        r - l,
        bottom - top
    );
    for d in lo..=hi {
        let x = ax.px(10f64.powi(d));
        let _ = writeln!(
            s,
            r##"<line x1="{x}" y1="{top}" x2="{x}" y2="{bottom}" stroke="#ddd"/>"##
        );
        let _ = writeln!(
            s,
            r#"<text x="{x}" y="{}" text-anchor="middle">1e{d}</text>"#,
            bottom + 16.0
        );
    }
    for d in (Y_DECADES.0..=Y_DECADES.1).step_by(2) {
        let y = ax.py(10f64.powi(d));
        let _ = writeln!(
            s,
            r##"<line x1="{l}" y1="{y}" x2="{r}" y2="{y}" stroke="#ddd"/>"##
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="end">1e{d}</text>"#,
            l - 6.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">run time, s</text>"#,
        f64::midpoint(l, r),
        bottom + 36.0
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate({},{}) rotate(-90)" text-anchor="middle">relative energy-norm error</text>"#,
        x0 + 18.0,
        f64::midpoint(top, bottom)
    );
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" text-anchor="middle" font-size="14">{scene} crack, {size}×{size} mesh</text>"#,
        f64::midpoint(l, r)
    );
    for (k, run) in runs.iter().enumerate() {
        let c = colour(run.solver);
        if run.solver == "direct" {
            if let Some(p) = run.samples.first() {
                let x = ax.px(p.seconds);
                let _ = writeln!(
                    s,
                    r#"<line x1="{x}" y1="{top}" x2="{x}" y2="{bottom}" stroke="{c}" stroke-dasharray="5,4"/>"#
                );
            }
        } else {
            let pts: Vec<String> = run
                .samples
                .iter()
                .filter(|p| p.seconds > 0.0)
                .map(|p| format!("{:.1},{:.1}", ax.px(p.seconds), ax.py(p.energy)))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="2"/>"#,
                pts.join(" ")
            );
        }
        let ly = bottom - 16.0 * (runs.len() - k) as f64; // lower left: empty on these plots
        let _ = writeln!(
            s,
            r#"<line x1="{}" y1="{ly}" x2="{}" y2="{ly}" stroke="{c}" stroke-width="2"/>"#,
            l + 12.0,
            l + 37.0
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}">{}</text>"#,
            l + 42.0,
            ly + 4.0,
            run.solver
        );
    }
}
