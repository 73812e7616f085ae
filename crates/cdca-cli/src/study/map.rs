//! `--map FILE.svg`: a finished table over its first two numeric axes
//! (x the first, y the second), one panel per layout: each cell coloured
//! by what the first link joins (grey: no link) and labelled with the
//! peak λ; a cell whose run did not converge at every step is marked ×.

use cdca::study::{Layout, Study, Table};

use crate::svg::Svg;

const CELL: f64 = 46.0;
const MARGIN: (f64, f64, f64, f64) = (80.0, 30.0, 56.0, 60.0); // left, right, top, bottom
const LEGEND_ROW: f64 = 20.0;
const NO_LINK: &str = "#e4e4e4";
/// Colours of the links, by what they join, in order of first use.
const COLOURS: [&str; 8] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf",
];

/// The map as SVG, or why the table has none.
pub fn draw(table: &Table, study: &Study) -> Result<String, String> {
    let numeric: Vec<&str> = study
        .axes
        .iter()
        .filter(|a| a.is_numeric())
        .map(|a| a.field.as_str())
        .collect();
    let [x_field, y_field, ..] = numeric[..] else {
        return Err(format!(
            "a map needs two numeric axes; the study has {}",
            numeric.len()
        ));
    };
    let number = |r: usize, c: &str| table.cell(r, c).parse::<f64>().ok();
    let xs = distinct((0..table.rows.len()).filter_map(|r| number(r, x_field)));
    let ys = distinct((0..table.rows.len()).filter_map(|r| number(r, y_field)));
    // panels: the layouts in their order, else one
    let mut panels: Vec<(usize, String)> = Vec::new();
    for r in 0..table.rows.len() {
        let name = table.cell(r, "flaws.layout");
        let rank = Layout::from_name(name)
            .and_then(|l| Layout::ALL.iter().position(|x| *x == l))
            .unwrap_or(Layout::ALL.len());
        if !panels.iter().any(|p| p.1 == name) {
            panels.push((rank, name.to_owned()));
        }
    }
    panels.sort();
    let mut links: Vec<String> = Vec::new();
    for r in 0..table.rows.len() {
        let l = table.cell(r, "link_joins");
        if !l.is_empty() && !links.iter().any(|k| k == l) {
            links.push(l.to_owned());
        }
    }
    links.sort();
    let colour = |link: &str| {
        links
            .iter()
            .position(|k| k == link)
            .map_or(NO_LINK, |i| COLOURS[i % COLOURS.len()])
    };
    let plot = (CELL * xs.len() as f64, CELL * ys.len() as f64);
    let panel_w = MARGIN.0 + plot.0 + MARGIN.1;
    let legend_h = LEGEND_ROW * (links.len() + 2) as f64 + 16.0;
    let height = MARGIN.2 + plot.1 + MARGIN.3 + legend_h;
    // wide enough for the title (about 7.5 px a character at 14 px)
    let width =
        (panel_w * panels.len().max(1) as f64).max(24.0 + 7.5 * study.name.chars().count() as f64);
    let mut s = Svg::new(width, height);
    s.text((12.0, 20.0), r#" font-size="14""#, &study.name);
    for (k, (_, name)) in panels.iter().enumerate() {
        let x0 = panel_w * k as f64 + MARGIN.0;
        let top = MARGIN.2;
        let title = Layout::from_name(name).map_or(name.as_str(), |l| l.label());
        s.text(
            (x0 + plot.0 / 2.0, top - 10.0),
            r#" text-anchor="middle" font-size="13""#,
            if title.is_empty() {
                "all points"
            } else {
                title
            },
        );
        for r in (0..table.rows.len()).filter(|&r| table.cell(r, "flaws.layout") == name) {
            let (Some(x), Some(y)) = (number(r, x_field), number(r, y_field)) else {
                continue;
            };
            let (Some(i), Some(j)) = (
                xs.iter().position(|v| *v == x),
                ys.iter().position(|v| *v == y),
            ) else {
                continue;
            };
            let cx = x0 + CELL * i as f64;
            let cy = top + plot.1 - CELL * (j + 1) as f64;
            let fill = colour(table.cell(r, "link_joins"));
            s.rect((cx, cy), (CELL, CELL), fill, "white");
            let peak = number(r, "peak_load_factor").map_or_else(
                || table.cell(r, "outcome").to_owned(),
                |p| format!("{p:.2}"),
            );
            let ink = if fill == NO_LINK { "#222" } else { "white" };
            s.text(
                (cx + CELL / 2.0, cy + CELL / 2.0 + 4.0),
                &format!(r#" text-anchor="middle" fill="{ink}" font-size="11""#),
                &peak,
            );
            if table.cell(r, "every_step_converged") == "false" {
                s.text(
                    (cx + CELL - 9.0, cy + 12.0),
                    &format!(r#" fill="{ink}""#),
                    "×",
                );
            }
        }
        let bottom = top + plot.1;
        s.rect((x0, top), plot, "none", "#444");
        for (i, x) in xs.iter().enumerate() {
            let at = x0 + CELL * (i as f64 + 0.5);
            s.text((at, bottom + 16.0), r#" text-anchor="middle""#, &tick(*x));
        }
        for (j, y) in ys.iter().enumerate() {
            let at = bottom - CELL * (j as f64 + 0.5);
            s.text((x0 - 6.0, at + 4.0), r#" text-anchor="end""#, &tick(*y));
        }
        s.text(
            (x0 + plot.0 / 2.0, bottom + 36.0),
            r#" text-anchor="middle""#,
            &label(x_field),
        );
        s.vertical_text((x0 - 58.0, top + plot.1 / 2.0), &label(y_field));
    }
    // the legend, under the panels
    let mut y = MARGIN.2 + plot.1 + MARGIN.3;
    let entries = links
        .iter()
        .map(|l| (colour(l), format!("first link {l}")))
        .chain([(NO_LINK, "no link".to_owned())]);
    for (fill, text) in entries {
        s.rect((MARGIN.0, y - 11.0), (14.0, 14.0), fill, "#888");
        s.text((MARGIN.0 + 22.0, y), "", &text);
        y += LEGEND_ROW;
    }
    s.text(
        (MARGIN.0, y),
        "",
        "number: the peak load factor λ (or the outcome); ×: a step did not converge",
    );
    Ok(s.finish())
}

/// An axis's title: the flaws generator's inputs in words, with units;
/// a scene field as its path.
fn label(field: &str) -> String {
    match field {
        "flaws.angle_deg" => "flaw angle to the horizontal (°)".to_owned(),
        "flaws.bridge_over_flaw" => "bridge / flaw length".to_owned(),
        "flaws.length" => "flaw length (m)".to_owned(),
        "flaws.friction" => "face friction μ".to_owned(),
        other => other.to_owned(),
    }
}

/// The distinct values, sorted.
fn distinct(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// A tick's label: up to four significant digits.
fn tick(x: f64) -> String {
    let text = format!("{x:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if x != 0.0 && x.abs() < 1e-3 {
        format!("{x:.3e}")
    } else {
        text.to_owned()
    }
}
