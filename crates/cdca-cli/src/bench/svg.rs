//! The error-versus-run-time picture: one log–log panel per scene at the
//! largest size, one curve per solver, the direct solve as a dashed line at
//! its time (through [`crate::svg`]).

use super::Run;
use crate::svg::Svg;

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
    let mut s = Svg::new(width, PANEL_H);
    for (i, scene) in scenes.iter().enumerate() {
        let these: Vec<&Run> = runs
            .iter()
            .filter(|r| r.size == size && r.scene == *scene)
            .collect();
        panel(&mut s, &these, scene, size, PANEL_W * i as f64);
    }
    s.finish()
}

fn panel(s: &mut Svg, runs: &[&Run], scene: &str, size: usize, x0: f64) {
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
    s.rect((l, top), (r - l, bottom - top), "none", "#444");
    for d in lo..=hi {
        let x = ax.px(10f64.powi(d));
        s.line((x, top), (x, bottom), "#ddd", "");
        s.text(
            (x, bottom + 16.0),
            r#" text-anchor="middle""#,
            &format!("1e{d}"),
        );
    }
    for d in (Y_DECADES.0..=Y_DECADES.1).step_by(2) {
        let y = ax.py(10f64.powi(d));
        s.line((l, y), (r, y), "#ddd", "");
        s.text(
            (l - 6.0, y + 4.0),
            r#" text-anchor="end""#,
            &format!("1e{d}"),
        );
    }
    s.text(
        (f64::midpoint(l, r), bottom + 36.0),
        r#" text-anchor="middle""#,
        "run time, s",
    );
    s.vertical_text(
        (x0 + 18.0, f64::midpoint(top, bottom)),
        "relative energy-norm error",
    );
    s.text(
        (f64::midpoint(l, r), 24.0),
        r#" text-anchor="middle" font-size="14""#,
        &format!("{scene} crack, {size}×{size} mesh"),
    );
    for (k, run) in runs.iter().enumerate() {
        let c = colour(run.solver);
        if run.solver == "direct" {
            if let Some(p) = run.samples.first() {
                let x = ax.px(p.seconds);
                s.line((x, top), (x, bottom), c, r#" stroke-dasharray="5,4""#);
            }
        } else {
            let pts: Vec<(f64, f64)> = run
                .samples
                .iter()
                .filter(|p| p.seconds > 0.0)
                .map(|p| (ax.px(p.seconds), ax.py(p.energy)))
                .collect();
            s.polyline(&pts, c, r#" stroke-width="2""#);
        }
        let ly = bottom - 16.0 * (runs.len() - k) as f64; // lower left: empty on these plots
        s.line((l + 12.0, ly), (l + 37.0, ly), c, r#" stroke-width="2""#);
        s.text((l + 42.0, ly + 4.0), "", run.solver);
    }
}
