//! The figures of a study file's run (the Study tab's *Study file* mode),
//! as [`Figure`]s, so that they are drawn and exported like every plot:
//! with two numeric axes, a map per layout (each point a marker coloured by
//! what its first link joins, or by its peak λ); with one, the peak λ and
//! the first link's step against it, a series per layout; with none, the
//! peak λ against the point's number.

use cdca::study::{Axis, Input, Row, Study};
use egui::Color32;

use crate::plots::figure::YTicks;
use crate::plots::figure::{Figure, Series, Style};
use crate::plots::figures::colour;

/// What the colours of a map show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MapColour {
    /// What the first link joins.
    Link,
    /// The peak λ, in four bands.
    Peak,
    /// Which cracks grew from the flaws: wings (first in tension),
    /// secondary cracks (first in shear, or started at a kink), or both
    /// (a first step's mode).
    #[default]
    Cracks,
}

/// The colour of "no link" and of an invalid point on a map.
pub const NO_LINK: Color32 = Color32::from_rgb(150, 150, 150);

/// The colour of the `k`-th link category.
pub fn link_colour(k: usize) -> Color32 {
    colour(k)
}

/// Markers of a map: one series per category, in the given order.
fn marker_series(name: String, colour: Color32, points: Vec<[f64; 2]>) -> Series {
    Series {
        name,
        colour,
        style: Style::Markers,
        points,
    }
}

/// An empty figure with these axes (the map's and the plot's frame).
fn frame(id: String, x_label: String, y_label: String) -> Figure {
    Figure {
        id,
        x_label,
        y_label,
        y_ticks: YTicks::Decimal,
        ..Figure::default()
    }
}

/// Bands of the peak λ on a map, lightest (lowest) first.
const PEAK_BANDS: [Color32; 4] = [
    Color32::from_rgb(160, 200, 255),
    Color32::from_rgb(90, 150, 240),
    Color32::from_rgb(40, 90, 200),
    Color32::from_rgb(20, 40, 130),
];

/// The figures of `rows` of `study`.
pub fn figures(study: &Study, rows: &[Row], colour_by: MapColour) -> Vec<Figure> {
    if rows.is_empty() {
        return Vec::new();
    }
    let numeric: Vec<usize> = (0..study.axes.len())
        .filter(|&k| study.axes[k].is_numeric())
        .collect();
    let groups = groups(study, rows);
    match numeric[..] {
        [a, b, ..] => groups
            .iter()
            .map(|(name, members)| map(study, rows, members, name, [a, b], colour_by))
            .collect(),
        [a] => {
            let (x_label, factor) = axis_label(&study.axes[a]);
            let x = |r: &Row| r.inputs[a].as_f64().map(|v| v * factor);
            over_one(rows, &groups, &x_label, &x)
        }
        [] => {
            let x = |r: &Row| Some(r.point as f64);
            over_one(rows, &groups, "point [–]", &x)
        }
    }
}

/// The rows per layout (`flaws.layout` when it is an axis), in order of
/// first appearance; one group `""` otherwise.
fn groups(study: &Study, rows: &[Row]) -> Vec<(String, Vec<usize>)> {
    let axis = study.axes.iter().position(|a| a.field == "flaws.layout");
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let name = match axis.map(|k| &r.inputs[k]) {
            Some(Input::Json(serde_json::Value::String(s))) => {
                cdca::study::Layout::from_name(s).map_or(s.clone(), |l| l.label().to_owned())
            }
            _ => String::new(),
        };
        match groups.iter_mut().find(|g| g.0 == name) {
            Some(g) => g.1.push(i),
            None => groups.push((name, vec![i])),
        }
    }
    groups
}

/// An axis's title with its unit, and the factor from its values to the
/// shown ones.
/// An axis's title in the UI's words and units (`flaw angle [°]`), and
/// the factor from its SI values to that unit.
pub fn axis_label(axis: &Axis) -> (String, f64) {
    match axis.field.as_str() {
        "flaws.angle_deg" => ("flaw angle [°]".to_owned(), 1.0),
        "flaws.bridge_over_flaw" => ("bridge / flaw length [–]".to_owned(), 1.0),
        "flaws.length" => ("flaw length [mm]".to_owned(), 1e3),
        "flaws.friction" => ("face friction μ [–]".to_owned(), 1.0),
        path => {
            let (unit, factor) = crate::study::param_unit(path);
            (
                format!("{} [{unit}]", crate::study::path_label(path)),
                factor,
            )
        }
    }
}

fn peak(r: &Row) -> Option<f64> {
    r.run
        .as_ref()
        .and_then(|run| run.strength.as_ref())
        .map(|s| s.peak_load_factor)
}

fn link(r: &Row) -> Option<&str> {
    r.run
        .as_ref()
        .and_then(|run| run.link.as_ref())
        .map(|l| l.category.as_str())
}

/// One layout's map over axes `a` (x) and `b` (y).
fn map(
    study: &Study,
    rows: &[Row],
    members: &[usize],
    name: &str,
    [a, b]: [usize; 2],
    colour_by: MapColour,
) -> Figure {
    let (x_label, fx) = axis_label(&study.axes[a]);
    let (y_label, fy) = axis_label(&study.axes[b]);
    let at = |r: &Row| Some([r.inputs[a].as_f64()? * fx, r.inputs[b].as_f64()? * fy]);
    let id = if name.is_empty() {
        "study_map".to_owned()
    } else {
        format!("study_map_{}", name.replace(", ", "_").replace(' ', "_"))
    };
    let x_label = if name.is_empty() {
        x_label
    } else {
        format!("{x_label} — {name}")
    };
    let mut fig = frame(id, x_label, y_label);
    // the classes over every row, so that a colour means the same in
    // every layout's map
    let mut classes: Vec<(String, Color32)> = Vec::new();
    let class_of = |r: &Row| -> String {
        match colour_by {
            MapColour::Link => link(r).map_or_else(
                || {
                    if r.outcome == "invalid" {
                        "invalid".to_owned()
                    } else {
                        "no link".to_owned()
                    }
                },
                |l| format!("first link {l}"),
            ),
            MapColour::Peak => band(rows, r),
            MapColour::Cracks => cracks(r),
        }
    };
    let mut names: Vec<String> = rows.iter().map(class_of).collect();
    names.sort();
    names.dedup();
    let mut k = 0;
    for n in names {
        let c = if n == "no link" || n == "no peak" || n == "nothing grew" {
            NO_LINK
        } else if n == "invalid" {
            Color32::from_rgb(90, 90, 90)
        } else if colour_by == MapColour::Peak {
            PEAK_BANDS[band_index(rows, &n)]
        } else if colour_by == MapColour::Cracks {
            match n.as_str() {
                "wings" => link_colour(0),
                "secondary cracks" => link_colour(4),
                "rock cracks" => link_colour(2),
                _ => link_colour(1),
            }
        } else {
            k += 1;
            link_colour(k - 1)
        };
        classes.push((n, c));
    }
    for (n, c) in classes {
        let points: Vec<[f64; 2]> = members
            .iter()
            .map(|&i| &rows[i])
            .filter(|r| class_of(r) == n)
            .filter_map(at)
            .collect();
        if !points.is_empty() {
            fig.series.push(marker_series(n, c, points));
        }
    }
    fig
}

/// Which cracks a row's run grew: wings and secondary cracks from the
/// flaws, cracks started in the intact rock, any mix of them, or none.
fn cracks(r: &Row) -> String {
    let Some(run) = r.run.as_ref() else {
        return "invalid".to_owned();
    };
    let kinds: Vec<&str> = [
        (run.wings > 0, "wings"),
        (run.secondary_cracks > 0, "secondary cracks"),
        (run.intact_rock_cracks > 0, "rock cracks"),
    ]
    .into_iter()
    .filter_map(|(grew, kind)| grew.then_some(kind))
    .collect();
    match kinds.as_slice() {
        [] => "nothing grew".to_owned(),
        [one] => (*one).to_owned(),
        [first @ .., last] => format!("{} and {last}", first.join(", ")),
    }
}

/// The band of the peak λ a row falls in, by name (`peak λ 1.20–1.50`).
fn band(rows: &[Row], r: &Row) -> String {
    let Some(p) = peak(r) else {
        return "no peak".to_owned();
    };
    let (lo, hi) = range(rows);
    let k = band_of(p, lo, hi);
    let w = (hi - lo) / PEAK_BANDS.len() as f64;
    format!(
        "peak λ {:.2}–{:.2}",
        lo + w * k as f64,
        lo + w * (k + 1) as f64
    )
}

fn band_index(rows: &[Row], name: &str) -> usize {
    rows.iter()
        .find(|r| band(rows, r) == name)
        .and_then(peak)
        .map_or(0, |p| {
            let (lo, hi) = range(rows);
            band_of(p, lo, hi)
        })
}

fn band_of(p: f64, lo: f64, hi: f64) -> usize {
    if hi > lo {
        (((p - lo) / (hi - lo) * PEAK_BANDS.len() as f64) as usize).min(PEAK_BANDS.len() - 1)
    } else {
        0
    }
}

/// The lowest and highest peak λ of the rows.
fn range(rows: &[Row]) -> (f64, f64) {
    rows.iter()
        .filter_map(peak)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p), b.max(p))
        })
}

/// The peak λ and the first link's step against one axis, a series per
/// layout.
fn over_one(
    rows: &[Row],
    groups: &[(String, Vec<usize>)],
    x_label: &str,
    x: &dyn Fn(&Row) -> Option<f64>,
) -> Vec<Figure> {
    let series = |y: &dyn Fn(&Row) -> Option<f64>, style: Style| -> Vec<Series> {
        groups
            .iter()
            .enumerate()
            .map(|(k, (name, members))| Series {
                name: if name.is_empty() {
                    "all points".to_owned()
                } else {
                    name.clone()
                },
                colour: link_colour(k),
                style,
                points: members
                    .iter()
                    .filter_map(|&i| Some([x(&rows[i])?, y(&rows[i])?]))
                    .collect(),
            })
            .filter(|s| !s.points.is_empty())
            .collect()
    };
    let mut peak_fig = frame(
        "study_peak".to_owned(),
        x_label.to_owned(),
        "peak load factor λ [–]".to_owned(),
    );
    peak_fig.series = series(&peak, Style::LineAndMarkers);
    peak_fig.include_y = vec![0.0];
    let mut link_fig = frame(
        "study_link".to_owned(),
        x_label.to_owned(),
        "first link at step [–]".to_owned(),
    );
    link_fig.series = series(
        &|r: &Row| {
            r.run
                .as_ref()
                .and_then(|run| run.link.as_ref())
                .map(|l| l.step as f64)
        },
        Style::Markers,
    );
    link_fig.include_y = vec![0.0];
    vec![peak_fig, link_fig]
}
