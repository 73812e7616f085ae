//! The workbench's plots as [`Figure`]s, built from what the solver
//! produced: the residual history, the growth history (K, angles, load
//! factor), the solver race and the parameter study. The plot panel draws
//! them and the export writes them, so both show the same numbers.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use egui::Color32;

use crate::plots::figure::{COMPACT_CUT, Figure, Note, Series, Style, YTicks};
use crate::plots::plot_tab::PlotTab;
use crate::results::solution::SolutionView;
use crate::style::units;

/// Series colours, distinguishable on the dark and the light theme (and on
/// the white of an exported SVG).
pub const PALETTE: [Color32; 8] = [
    Color32::from_rgb(70, 140, 255),
    Color32::from_rgb(255, 150, 40),
    Color32::from_rgb(40, 190, 90),
    Color32::from_rgb(230, 70, 90),
    Color32::from_rgb(170, 110, 240),
    Color32::from_rgb(30, 200, 200),
    Color32::from_rgb(220, 200, 40),
    Color32::from_rgb(240, 110, 200),
];

pub fn colour(i: usize) -> Color32 {
    PALETTE[i % PALETTE.len()]
}

/// The hues of the drawn flaws' families (flaw k: `FLAW_HUES[k % 5]`): a
/// flaw, its ends and its secondary cracks are shades of one hue.
const FLAW_HUES: [Color32; 5] = [PALETTE[0], PALETTE[1], PALETTE[2], PALETTE[4], PALETTE[5]];

/// The hue of the cracks started in the intact rock: a family of their own.
const ROCK_HUE: Color32 = PALETTE[3];

/// Shade `k` of `hue`: the hue itself, then alternately darker and lighter,
/// each a step further (kept legible on the dark and the light theme).
pub fn shade(hue: Color32, k: usize) -> Color32 {
    let step = k.div_ceil(2).min(3) as f32;
    let mix = |c: u8, to: f32, t: f32| (f32::from(c) + (to - f32::from(c)) * t).round() as u8;
    let (to, t) = if k == 0 {
        return hue;
    } else if k % 2 == 1 {
        (0.0, 0.22 * step)
    } else {
        (255.0, 0.3 * step)
    };
    Color32::from_rgb(
        mix(hue.r(), to, t),
        mix(hue.g(), to, t),
        mix(hue.b(), to, t),
    )
}

/// Which family a crack belongs to: its drawn flaw, or the intact rock.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Family {
    Flaw(usize),
    Rock,
}

fn family(view: &SolutionView, crack: usize) -> Family {
    match view.lineage.get(crack) {
        Some(l) if l.is_intact() => Family::Rock,
        Some(l) => Family::Flaw(l.flaw),
        None => Family::Flaw(crack),
    }
}

/// The colour of each (crack, end) of `tips`: its family's hue, shaded by
/// its place in the family (the flaw's end 1, end 2, then its secondary
/// cracks' ends in order).
fn tip_colours(
    view: &SolutionView,
    tips: impl Iterator<Item = (usize, usize)>,
) -> BTreeMap<(usize, usize), Color32> {
    let mut by_family: BTreeMap<Family, Vec<(usize, usize)>> = BTreeMap::new();
    for t in tips {
        let members = by_family.entry(family(view, t.0)).or_default();
        if !members.contains(&t) {
            members.push(t);
        }
    }
    let mut out = BTreeMap::new();
    for (f, mut members) in by_family {
        // the drawn flaw's own ends first, then its secondary cracks
        members.sort_by_key(|&(c, t)| (view.lineage.get(c).is_none_or(|l| l.drawn == 0), c, t));
        let hue = match f {
            Family::Flaw(k) => FLAW_HUES[k % FLAW_HUES.len()],
            Family::Rock => ROCK_HUE,
        };
        for (k, m) in members.into_iter().enumerate() {
            // the rock's cracks, one colour: a run of a dozen drew as many
            // near-identical shades, one legend entry each
            let colour = if f == Family::Rock {
                hue
            } else {
                shade(hue, k)
            };
            out.insert(m, colour);
        }
    }
    out
}

/// What a study draws in its tab: its figures (the solver race's, a
/// parameter study's), made by the study itself, so that the plots know
/// nothing of studies.
pub trait Plotted {
    fn figures(&self) -> Vec<Figure>;
}

/// The figures of a plot tab (empty when there is nothing to show yet; the
/// Study tab has two: angle and λ_cr against the parameter). `specimen` is
/// the specimen's width and height, m.
pub fn figures(
    tab: PlotTab,
    view: &SolutionView,
    race: Option<&dyn Plotted>,
    study: Option<&dyn Plotted>,
    specimen: [f64; 2],
) -> Vec<Figure> {
    let figure = match tab {
        PlotTab::ResidualBySweep => residual(
            "residual_by_sweep",
            iteration_label(view.solver),
            true,
            view.residual_by_sweep.iter().map(|p| [p.x, p.y]),
        ),
        PlotTab::ResidualByTime => residual(
            "residual_by_time",
            "time [s]",
            false,
            view.residual_by_time.iter().map(|p| [p.x, p.y]),
        ),
        PlotTab::Sifs => sifs(view),
        PlotTab::Angles => angles(view),
        PlotTab::LoadFactor => load_factor(view, specimen),
        PlotTab::SolverComparison => return race.map(Plotted::figures).unwrap_or_default(),
        PlotTab::Study => return study.map(Plotted::figures).unwrap_or_default(),
        // a study file's figures come with its run (`study_map`)
        PlotTab::StudyMap => None,
    };
    figure.into_iter().collect()
}

/// The residual plot's x axis: what the solver counts (the status line's
/// unit): the automaton's sweeps, CG iterations, or the direct solver's
/// linear solves (one per contact iteration).
pub fn iteration_label(kind: cdca::scene::SolverKind) -> &'static str {
    match kind {
        cdca::scene::SolverKind::Automaton => "sweep [–]",
        cdca::scene::SolverKind::Cg | cdca::scene::SolverKind::Multigrid => "CG iteration [–]",
        cdca::scene::SolverKind::Direct => "linear solve [–]",
    }
}

/// The residual against iterations (`counted`: from 0, whole numbers) or
/// time. The y axis spans whole decades around the values, so that it
/// carries at least two labelled ticks (a residual within one decade had
/// none), and x starts at 0 (one Step's single point sat alone on an axis
/// from 0.50 to 1.45).
fn residual(
    id: &str,
    x_label: &str,
    counted: bool,
    points: impl Iterator<Item = [f64; 2]>,
) -> Option<Figure> {
    let points: Vec<[f64; 2]> = points.collect();
    let finite = || points.iter().map(|p| p[1]).filter(|y| y.is_finite());
    let lo = finite().fold(f64::INFINITY, f64::min).floor();
    let hi = finite().fold(f64::NEG_INFINITY, f64::max).ceil();
    let include_y = if lo.is_finite() && hi.is_finite() {
        vec![lo.min(hi - 1.0), hi]
    } else {
        Vec::new()
    };
    (!points.is_empty()).then(|| Figure {
        id: id.to_owned(),
        x_label: x_label.to_owned(),
        y_label: "relative residual |f − K u| / |f| [–], log".to_owned(),
        y_ticks: YTicks::Log,
        include_y,
        include_x: vec![0.0],
        x_whole: counted,
        series: vec![Series {
            name: "relative residual".to_owned(),
            colour: colour(0),
            style: Style::Line,
            points,
        }],
        ..Figure::default()
    })
}

/// Series per (crack, end) in the order met, from the growth history.
fn per_tip(
    view: &SolutionView,
    value: impl Fn(&cdca::report::GrowthStepReport) -> Vec<((usize, usize, u8), f64)>,
) -> BTreeMap<(usize, usize, u8), Vec<[f64; 2]>> {
    let mut series: BTreeMap<_, Vec<[f64; 2]>> = BTreeMap::new();
    for s in &view.history {
        for (key, v) in value(s) {
            series.entry(key).or_default().push([s.step as f64, v]);
        }
    }
    series
}

/// The legend's one entry for every crack started in the intact rock.
const ROCK_CRACKS: &str = "Rock cracks (every end)";

/// One series per (crack, end), drawn in pieces of consecutive steps: a
/// solid line joins two values only when no step lies between them, and a
/// dotted [`Style::Gap`] links a piece to the next across steps in which
/// the tip did not grow.
/// Each (crack, end) is coloured by its flaw's family ([`tip_colours`]),
/// end 1 solid and end 2 dashed; the third key's 2 (K_II) has diamonds.
fn step_series(
    view: &SolutionView,
    series: BTreeMap<(usize, usize, u8), Vec<[f64; 2]>>,
    name: impl Fn((usize, usize, u8)) -> String,
) -> Vec<Series> {
    let colours = tip_colours(view, series.keys().map(|&(c, t, _)| (c, t)));
    let mut out = Vec::new();
    for (key, points) in series {
        // a compact legend names the rock's cracks once (the CSV keeps
        // each crack's name after the cut)
        let name = if family(view, key.0) == Family::Rock {
            format!("{ROCK_CRACKS}{COMPACT_CUT}{}", name(key))
        } else {
            name(key)
        };
        let colour = colours.get(&(key.0, key.1)).copied().unwrap_or(PALETTE[0]);
        let style = Style::of_end(key.1, key.2 == 2);
        let piece = |style, points: Vec<[f64; 2]>| Series {
            name: name.clone(),
            colour,
            style,
            points,
        };
        let mut last: Option<[f64; 2]> = None;
        for run in points.chunk_by(|a, b| b[0] - a[0] <= 1.0) {
            if let Some(end) = last {
                out.push(piece(Style::Gap, vec![end, run[0]]));
            }
            out.push(piece(style, run.to_vec()));
            last = run.last().copied();
        }
    }
    out
}

fn sifs(view: &SolutionView) -> Option<Figure> {
    let series = per_tip(view, |s| {
        s.tips
            .iter()
            .flat_map(|t| {
                [
                    ((t.crack, t.tip, 1), t.k1 / units::PA_PER_MPA),
                    ((t.crack, t.tip, 2), t.k2 / units::PA_PER_MPA),
                ]
            })
            .collect()
    });
    (!series.is_empty()).then(|| Figure {
        id: "sifs".to_owned(),
        x_label: "growth step [–]".to_owned(),
        y_label: "K [MPa·√m]".to_owned(),
        x_whole: true,
        // one legend entry per crack end (its colour and line), the modes
        // told apart by their markers
        series: step_series(view, series, |(c, t, k)| {
            let mode = if k == 1 { "I" } else { "II" };
            format!("{} end {}{COMPACT_CUT}K_{mode}", view.crack_name(c), t + 1)
        }),
        compact_legend: true,
        key: "circles: K_I, diamonds: K_II; solid: end 1, dashed: end 2".to_owned(),
        include_y: vec![0.0],
        ..Figure::default()
    })
}

/// The kink angle of each tip grown, against the growth step. The x axis
/// spans the whole run, and the key names the steps in which no tip grew
/// but cracks started in the intact rock (after the default run the plot
/// showed steps 1–2 of 14 and said nothing of the other twelve).
fn angles(view: &SolutionView) -> Option<Figure> {
    let series = per_tip(view, |s| {
        s.grown
            .iter()
            .map(|g| ((g.crack, g.tip, 0), g.angle_deg))
            .collect()
    });
    if series.is_empty() {
        return None;
    }
    let mut key = "solid: end 1, dashed: end 2".to_owned();
    let started_only: Vec<usize> = view
        .history
        .iter()
        .filter(|s| s.grown.is_empty() && !s.nucleated.is_empty())
        .map(|s| s.step)
        .collect();
    if !started_only.is_empty() {
        let (s, pronoun) = if started_only.len() == 1 {
            ("", "it")
        } else {
            ("s", "they")
        };
        let _ = write!(
            key,
            "; no tip grew at step{s} {}: {pronoun} started cracks in the intact rock",
            units::step_list(&started_only),
        );
    }
    let steps = view.history.iter().map(|s| s.step as f64);
    Some(Figure {
        id: "angles".to_owned(),
        x_label: "growth step [–]".to_owned(),
        y_label: "kink angle θ [°]".to_owned(),
        x_whole: true,
        y_ticks: YTicks::Degrees,
        series: step_series(view, series, |(c, t, _)| {
            format!("{} end {}", view.crack_name(c), t + 1)
        }),
        compact_legend: true,
        key,
        include_y: vec![0.0],
        include_x: [steps.clone().reduce(f64::min), steps.reduce(f64::max)]
            .into_iter()
            .flatten()
            .collect(),
        ..Figure::default()
    })
}

/// λ against the total crack length. Two kinds of step are marked, as the
/// load can jump there: one whose crack ran to the specimen's edge (the
/// last ligament, next to a support or the loaded side, needs a higher
/// load), and one after which fewer tips are free (saying why when the
/// step's report does: a tip that ended on a crack, or reached the edge).
/// Beside it, dashed, the load factor at which the rock
/// away from the cracks reaches its own strength. A last step that grew
/// nothing because the λ_cr search reached `growth.max_load_factor` is a
/// note at the last growth, not a point: its λ (the cap, say 100) would
/// flatten the reached range.
fn load_factor(view: &SolutionView, [width, height]: [f64; 2]) -> Option<Figure> {
    let all = &view.history;
    let capped =
        view.load_cap.is_some() && all.len() > 1 && all.last().is_some_and(|s| s.grown.is_empty());
    let h = if capped {
        &all[..all.len() - 1]
    } else {
        &all[..]
    };
    if h.is_empty() {
        return None;
    }
    let point =
        |s: &cdca::report::GrowthStepReport| [s.crack_length * units::MM_PER_M, s.load_factor];
    let tol = 1e-9 * width.max(height);
    let on_edge = |x: f64, y: f64| x <= tol || y <= tol || x >= width - tol || y >= height - tol;
    // each note names the crack as the canvas does (a rock crack's tip is
    // no wing) and claims only what the step's report holds
    let mut notes: Vec<Note> = h
        .iter()
        .filter_map(|s| {
            let g = s.grown.iter().find(|g| on_edge(g.x, g.y))?;
            Some(Note {
                at: point(s),
                text: format!(
                    "λ = {:.3}: {} ran to the specimen's edge",
                    s.load_factor,
                    view.crack_name(g.crack)
                ),
            })
        })
        .collect();
    notes.extend(
        h.windows(2)
            .filter(|pair| pair[1].tips.len() < pair[0].tips.len())
            .map(|pair| {
                let s = &pair[1];
                let edge = s.grown.iter().any(|g| on_edge(g.x, g.y));
                let why = match (s.links.first(), edge) {
                    (Some(l), _) => format!(
                        ": {} ended on {}",
                        view.crack_name(l.crack),
                        view.crack_name(l.main)
                    ),
                    (None, true) => ": a tip reached the specimen's edge".to_owned(),
                    (None, false) => String::new(),
                };
                Note {
                    at: point(s),
                    text: format!("{} to {} free tips{why}", pair[0].tips.len(), s.tips.len()),
                }
            }),
    );
    // the first link between two flaws (coalescence), named as the story
    // and the canvas name it: the drawn flaws a crack from the intact rock
    // joined, not that crack's own number
    if let Some(c) = &view.coalescence
        && let Some(s) = h.iter().find(|s| s.step == c.step)
    {
        notes.push(Note {
            at: point(s),
            text: format!(
                "λ = {:.3}: Crack {} and Crack {} linked ({})",
                c.load_factor,
                c.flaws[0] + 1,
                c.flaws[1] + 1,
                c.category
            ),
        });
    }
    if let (true, Some(cap), Some(last)) = (capped, &view.load_cap, h.last()) {
        notes.push(Note {
            at: point(last),
            text: format!(
                "then no tip grew up to the cap λ = {} (growth.max_load_factor): the run stopped",
                cap.max_load_factor
            ),
        });
    }
    let mut series = vec![Series {
        name: "λ of each growth step".to_owned(),
        colour: colour(0),
        style: Style::LineAndMarkers,
        points: h.iter().map(point).collect(),
    }];
    let started: Vec<[f64; 2]> = h
        .iter()
        .filter(|s| !s.started.is_empty())
        .map(point)
        .collect();
    if !started.is_empty() {
        series.push(Series {
            name: "a secondary crack started at a kink".to_owned(),
            colour: colour(2),
            style: Style::Markers,
            points: started,
        });
    }
    let nucleated: Vec<[f64; 2]> = h
        .iter()
        .filter(|s| !s.nucleated.is_empty())
        .map(point)
        .collect();
    if !nucleated.is_empty() {
        series.push(Series {
            name: "a crack started in the intact rock".to_owned(),
            colour: colour(4),
            style: Style::Markers,
            points: nucleated,
        });
    }
    if let Some(s) = &view.strength {
        let at = h
            .iter()
            .find(|x| x.step == s.peak_step)
            .map_or([0.0, s.peak_load_factor], point);
        series.push(Series {
            name: format!("peak: specimen strength {}", units::mpa(s.peak_stress)),
            colour: colour(5),
            style: Style::Markers,
            points: vec![at],
        });
    }
    // the uncracked specimen's strength, as a level line across the run:
    // the one λ of the intact rock's strength the workbench shows (the
    // cracked scene's median at λ / u read as a second, different one)
    if let (Some(intact), Some(first), Some(last)) = (view.intact_load_factor, h.first(), h.last())
    {
        let stress = view.strength.as_ref().map_or_else(String::new, |s| {
            format!(", {}", units::mpa(intact * s.reference_stress))
        });
        series.push(Series {
            name: format!("intact rock's strength (uncracked specimen): λ = {intact:.3}{stress}"),
            colour: colour(3),
            style: Style::Dashed,
            points: vec![[point(first)[0], intact], [point(last)[0], intact]],
        });
    }
    let mut fig = Figure {
        id: "load_factor".to_owned(),
        x_label: "total crack length [mm]".to_owned(),
        y_label: "load factor λ [–]".to_owned(),
        series,
        notes,
        include_y: vec![0.0],
        ..Figure::default()
    };
    fig.y_max = robust_top(
        fig.series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p[1])),
    );
    if let Some(top) = fig.y_max {
        for p in h.iter().map(point).filter(|p| p[1] > top) {
            fig.notes.push(Note {
                at: p,
                text: format!(
                    "λ = {:.3} at {:.1} mm: off the scale (the axis stops at {top:.2}), marked at its top edge",
                    p[1], p[0]
                ),
            });
        }
    }
    Some(fig)
}

/// The top of a y axis that shows an outlier without flattening the rest:
/// `None` unless the largest value lies beyond the upper fence (the upper
/// quartile plus three interquartile ranges) and is more than 1.5 times
/// the largest value within it; then 1.15 times that value. (The default
/// run's λ = 7.02 at its last step flattened steps near 0.6.)
pub fn robust_top(values: impl Iterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    if v.len() < 4 {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let quartile = |f: f64| v[((v.len() - 1) as f64 * f).round() as usize];
    let (q1, q3) = (quartile(0.25), quartile(0.75));
    let fence = q3 + 3.0 * (q3 - q1).max(0.05 * q3.abs());
    let kept = v
        .iter()
        .copied()
        .filter(|&x| x <= fence)
        .fold(f64::NEG_INFINITY, f64::max);
    let top = v[v.len() - 1];
    (top > fence && kept > 0.0 && top > 1.5 * kept).then_some(1.15 * kept)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::race::Race;
    use cdca::report::{GrownTip, GrowthStepReport, TipReport};
    use egui_plot::PlotPoint;

    /// The specimen: 30 mm square.
    const SIZE: [f64; 2] = [0.03, 0.03];

    /// The default run's load factors with its last step's λ = 7.02: the
    /// axis stops at 1.15 × 0.70 (the largest of the rest), the outlier
    /// marked at the edge with a note; an even rise is not clipped.
    #[test]
    fn an_outlier_lambda_is_clipped_with_a_note() {
        let top = robust_top([0.5, 0.55, 0.6, 0.62, 0.65, 0.7, 7.02].into_iter());
        assert!(top.is_some_and(|t| (t - 0.805).abs() < 1e-12), "{top:?}");
        assert_eq!(robust_top([0.5, 0.8, 1.1, 1.4, 1.7, 2.0].into_iter()), None);
        let mut history: Vec<GrowthStepReport> = (1..=7)
            .map(|k| step(k, [0.5, 0.55, 0.6, 0.62, 0.65, 0.7, 7.02][k - 1], 2, 10.0))
            .collect();
        for s in &mut history {
            s.grown[0].y = 0.015;
        }
        let view = SolutionView {
            history,
            ..SolutionView::default()
        };
        let load = &figures(PlotTab::LoadFactor, &view, None, None, SIZE)[0];
        assert!(load.y_max.is_some_and(|t| (t - 0.805).abs() < 1e-12));
        assert_eq!(load.notes.len(), 1, "{:?}", load.notes);
        assert!(
            load.notes[0]
                .text
                .starts_with("λ = 7.020 at 7.5 mm: off the scale")
        );
        assert_eq!(load.shown_y(7.02), load.y_max.unwrap_or_default());
        // the numbers exported keep the outlier
        assert!(load.to_csv().contains(",7.02\n"));
    }

    /// K and angles are coloured by family: a flaw's ends and its secondary
    /// crack are shades of one hue, every (crack, end) its own colour, the
    /// cracks started in the intact rock another hue; end 2 is dashed, K_II
    /// has diamonds. (Ten series used to cycle eight colours: two blues.)
    #[test]
    fn k_series_are_coloured_by_flaw_family() {
        use cdca::scene::Lineage;
        let mut rock = Lineage::secondary(0);
        rock.ends = [cdca::report::Part::Intact; 2];
        let lineage = vec![
            Lineage::drawn(0, 2),
            Lineage::drawn(1, 2),
            Lineage::secondary(0),
            rock,
        ];
        let mut s = step(1, 0.5, 0, 10.0);
        s.tips = [(0, 0), (0, 1), (1, 0), (1, 1), (2, 0), (3, 1)]
            .iter()
            .map(|&(crack, tip)| TipReport {
                crack,
                tip,
                k1: 1e6,
                ..TipReport::default()
            })
            .collect();
        let view = SolutionView {
            history: vec![s],
            lineage,
            ..SolutionView::default()
        };
        let sifs = &figures(PlotTab::Sifs, &view, None, None, SIZE)[0];
        let colour = |name: &str| {
            sifs.series
                .iter()
                .find(|s| s.name == name)
                .map_or_else(|| panic!("{name}"), |s| (s.colour, s.style))
        };
        let c1e1 = colour("Crack 1 end 1 — K_I");
        assert_eq!(c1e1, (FLAW_HUES[0], Style::LineAndMarkers));
        assert_eq!(
            colour("Crack 1 end 2 — K_II"),
            (shade(FLAW_HUES[0], 1), Style::DashedAndDiamonds)
        );
        assert_eq!(
            colour("Crack 1 · secondary 1 end 1 — K_I").0,
            shade(FLAW_HUES[0], 2)
        );
        assert_eq!(colour("Crack 2 end 1 — K_I").0, FLAW_HUES[1]);
        assert_eq!(
            colour("Rock cracks (every end) — Rock crack 1 end 2 — K_I"),
            (ROCK_HUE, Style::DashedAndMarkers)
        );
        let legend: Vec<&str> = sifs.legend().map(|s| sifs.legend_name(s)).collect();
        assert_eq!(
            legend.last(),
            Some(&"Rock cracks (every end)"),
            "{legend:?}"
        );
        let mut colours: Vec<[u8; 4]> = sifs.legend().map(|s| s.colour.to_array()).collect();
        assert_eq!(colours.len(), 6, "one legend entry per crack end");
        colours.sort_unstable();
        colours.dedup();
        assert_eq!(colours.len(), 6, "six crack ends, six colours");
    }

    fn step(step: usize, lambda: f64, free_tips: usize, angle: f64) -> GrowthStepReport {
        GrowthStepReport {
            step,
            load_factor: lambda,
            crack_length: 0.004 + 0.0005 * step as f64,
            tips: (0..free_tips)
                .map(|t| TipReport {
                    tip: t,
                    k1: 1e6 * step as f64,
                    ..TipReport::default()
                })
                .collect(),
            grown: vec![GrownTip {
                tip: 1,
                angle_deg: angle,
                x: 0.01,
                y: if free_tips == 1 { 0.03 } else { 0.02 },
                ..GrownTip::default()
            }],
            ..GrowthStepReport::default()
        }
    }

    /// The growth plots carry the history's numbers in display units, and
    /// the load-factor plot marks the step after which a tip stopped being
    /// free (the jump in λ a class would otherwise not understand).
    #[test]
    fn growth_figures_hold_the_history_and_mark_lost_tips() {
        let view = SolutionView {
            history: vec![
                step(1, 0.2, 2, 70.5),
                step(2, 0.3, 2, 12.0),
                step(3, 3.4, 1, -4.0),
            ],
            ..SolutionView::default()
        };
        let angles = &figures(PlotTab::Angles, &view, None, None, SIZE)[0];
        assert_eq!(angles.series.len(), 1);
        assert_eq!(
            angles.series[0].points,
            vec![[1.0, 70.5], [2.0, 12.0], [3.0, -4.0]]
        );
        assert_eq!(angles.y_ticks, YTicks::Degrees);
        let sifs = &figures(PlotTab::Sifs, &view, None, None, SIZE)[0];
        let k1_tip0 = &sifs.series[0];
        assert_eq!(k1_tip0.name, "Crack 1 end 1 — K_I");
        assert_eq!(k1_tip0.points[2], [3.0, 3.0], "K in MPa·√m");
        let load = &figures(PlotTab::LoadFactor, &view, None, None, SIZE)[0];
        // step 3 ran a wing to the top edge (y = 30 mm) and left one tip free
        assert_eq!(load.notes.len(), 2);
        assert_eq!(load.notes[0].at, [5.5, 3.4], "x in mm");
        assert_eq!(
            load.notes[0].text,
            "λ = 3.400: Crack 1 ran to the specimen's edge"
        );
        assert_eq!(
            load.notes[1].text, "2 to 1 free tips: a tip reached the specimen's edge",
            "{}",
            load.notes[1].text
        );
        assert!(figures(PlotTab::ResidualBySweep, &view, None, None, SIZE).is_empty());
    }

    /// A tip that did not grow for some steps has its angle line dotted
    /// across them (one legend entry, each value exported once), and the
    /// load-factor plot shows the uncracked specimen's strength as a level
    /// line, and no λ of the cracked scene's median (λ / u).
    #[test]
    fn angle_lines_break_at_gaps_and_the_rock_strength_is_drawn() {
        let mut history = vec![
            step(1, 0.5, 2, 70.0),
            step(2, 0.6, 2, 60.0),
            step(5, 0.8, 2, 20.0),
        ];
        for (s, u) in history.iter_mut().zip([0.625, 0.75, 1.25]) {
            s.intact_rock = Some(cdca::report::IntactRockReport {
                utilisation: u,
                failed_fraction: 0.0,
                ucs: 80e6,
            });
        }
        let view = SolutionView {
            history,
            ..SolutionView::default()
        };
        let angles = &figures(PlotTab::Angles, &view, None, None, SIZE)[0];
        let pieces: Vec<(Style, &Vec<[f64; 2]>)> =
            angles.series.iter().map(|s| (s.style, &s.points)).collect();
        assert_eq!(
            pieces,
            // the tip is end 2: dashed
            vec![
                (Style::DashedAndMarkers, &vec![[1.0, 70.0], [2.0, 60.0]]),
                (Style::Gap, &vec![[2.0, 60.0], [5.0, 20.0]]),
                (Style::DashedAndMarkers, &vec![[5.0, 20.0]]),
            ]
        );
        assert_eq!(angles.legend().count(), 1);
        // the numbers exported: each growth once, the gap left out
        assert_eq!(angles.to_csv().lines().count(), 1 + 3);
        let load = &figures(PlotTab::LoadFactor, &view, None, None, SIZE)[0];
        assert_eq!(load.series.len(), 1, "no line from the median");
        let view = SolutionView {
            intact_load_factor: Some(0.802),
            ..view
        };
        let load = &figures(PlotTab::LoadFactor, &view, None, None, SIZE)[0];
        let rock = &load.series[1];
        assert_eq!(
            rock.name,
            "intact rock's strength (uncracked specimen): λ = 0.802"
        );
        let x: Vec<[f64; 2]> = rock
            .points
            .iter()
            .map(|p| [(p[0] * 1e9).round() / 1e9, p[1]])
            .collect();
        assert_eq!(x, vec![[4.5, 0.802], [6.5, 0.802]], "x in mm");
    }

    /// Every text the plots draw is in egui's default fonts (Ubuntu Light
    /// and egui's icons; the emoji fonts are no longer built in): the
    /// load-factor plot's note marks "◀" and its note "2 → 1 free tips"
    /// were drawn with missing-glyph boxes. Checked on every growth plot
    /// with all its notes (an edge, a lost tip, the load cap), the residual
    /// plots and the race. The notes on one point share one numbered mark:
    /// their numbers were drawn over each other.
    #[test]
    fn every_plot_text_is_in_the_default_fonts() {
        let mut history = vec![
            step(1, 0.2, 2, 70.5),
            step(2, 0.3, 2, 12.0),
            step(3, 3.4, 1, -4.0),
            step(4, 100.0, 1, 0.0),
        ];
        history[3].grown.clear();
        for s in &mut history {
            s.intact_rock = Some(cdca::report::IntactRockReport {
                utilisation: 0.5,
                failed_fraction: 0.0,
                ucs: 80e6,
            });
        }
        let view = SolutionView {
            history,
            load_cap: Some(cdca::report::LoadCapReport::at(100.0)),
            residual_by_sweep: vec![PlotPoint::new(1.0, -3.0)],
            residual_by_time: vec![PlotPoint::new(0.1, -3.0)],
            ..SolutionView::default()
        };
        let scene = cdca::Scene::try_from(crate::files::scenes::default_scene()).expect("valid");
        let race = Race::new(&scene, 1.0);
        let mut texts: Vec<String> = crate::plots::figure::NOTE_MARKS.map(str::to_owned).into();
        for tab in PlotTab::TABS.into_iter().filter(|&t| t != PlotTab::Study) {
            let figs = figures(tab, &view, Some(&race), None, SIZE);
            assert_eq!(figs.len(), 1, "{tab:?} has its plot");
            for fig in &figs {
                texts.extend([fig.x_label.clone(), fig.y_label.clone()]);
                texts.extend(fig.legend().map(|s| fig.legend_name(s).to_owned()));
                texts.extend(fig.vlines.iter().map(|v| v.0.clone()));
                texts.extend(fig.notes.iter().map(|n| n.text.clone()));
            }
        }
        let load = &figures(PlotTab::LoadFactor, &view, None, None, SIZE)[0];
        assert_eq!(
            load.notes.len(),
            3,
            "edge, lost tip and cap: {:?}",
            load.notes
        );
        // step 3 ran to the edge, lost a tip and was the last growth: its
        // three notes share one mark
        assert_eq!(
            load.note_marks(),
            vec![([5.5, 3.4], "1, 2, 3".to_owned())],
            "{:?}",
            load.notes
        );

        let ctx = egui::Context::default();
        // the font atlas's first upload, not applied here: cleared, as
        // epaint's debug build refuses to drop it unapplied
        ctx.run_ui(egui::RawInput::default(), |_| {})
            .textures_delta
            .clear();
        let font = egui::FontId::proportional(12.0);
        // and the marks of secondary cracks and of the first link
        let linked = SolutionView {
            history: linked_history(),
            ..SolutionView::default()
        };
        let load = &figures(PlotTab::LoadFactor, &linked, None, None, SIZE)[0];
        texts.extend(load.notes.iter().map(|n| n.text.clone()));
        texts.extend(load.legend().map(|s| load.legend_name(s).to_owned()));
        let missing: Vec<char> = ctx.fonts_mut(|f| {
            texts
                .iter()
                .flat_map(|t| t.chars())
                .filter(|&c| !f.has_glyph(&font, c))
                .collect()
        });
        assert!(missing.is_empty(), "no glyph for {missing:?}");
    }

    /// Three steps of a pair: a secondary crack starts at step 2, and at
    /// step 3 it ends on the other flaw's wing (the first link).
    fn linked_history() -> Vec<GrowthStepReport> {
        use cdca::report::{LinkReport, Part, StartedCrack};
        let mut history = vec![
            step(1, 0.6, 4, 60.0),
            step(2, 0.7, 4, 1.0),
            step(3, 0.9, 3, 2.0),
        ];
        history[1].started = vec![StartedCrack::default()];
        history[2].links = vec![LinkReport {
            crack: 2,
            tip: 1,
            main: 1,
            joins: [Part::Secondary, Part::Wing],
            flaws: [0, 1],
            coalescence: true,
        }];
        history
    }

    /// The load-factor plot marks where secondary cracks started (a
    /// series of markers) and the first link between two flaws (a note
    /// naming the flaws, 1-based as the panel counts, and what it joins).
    #[test]
    fn the_first_link_and_the_secondary_starts_are_marked() {
        let history = linked_history();
        let link = &history[2].links[0];
        let view = SolutionView {
            coalescence: Some(cdca::report::CoalescenceReport {
                step: 3,
                load_factor: 0.9,
                category: link.category(),
                flaws: link.flaws,
            }),
            history,
            ..SolutionView::default()
        };
        let load = &figures(PlotTab::LoadFactor, &view, None, None, SIZE)[0];
        let started = load
            .series
            .iter()
            .find(|s| s.name == "a secondary crack started at a kink")
            .expect("the starts' series");
        assert_eq!(started.points, vec![[5.0, 0.7]], "step 2, x in mm");
        let link = load
            .notes
            .iter()
            .find(|n| n.text.contains("linked"))
            .expect("the link's note");
        assert_eq!(link.at, [5.5, 0.9]);
        assert_eq!(
            link.text,
            "λ = 0.900: Crack 1 and Crack 2 linked (secondary–wing)"
        );
    }
}
