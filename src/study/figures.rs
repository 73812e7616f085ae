//! The studies' plots: the solver race's errors against run time, and a
//! parameter study's first growth against the parameter (drawn by the
//! plots part through [`Plotted`]).

use crate::plots::figure::{COMPACT_CUT, Figure, Series, Style, YTicks};
use crate::plots::figures::{Plotted, colour};
use crate::style::units;

use super::race::Race;
use super::{Study, param_unit};

impl Plotted for Race {
    fn figures(&self) -> Vec<Figure> {
        vec![race_figure(self)]
    }
}

impl Plotted for Study {
    fn figures(&self) -> Vec<Figure> {
        study_figures(self)
    }
}

/// The race's errors against run time, one line per solver beside the
/// reference's time.
fn race_figure(race: &Race) -> Figure {
    let mut fig = Figure {
        id: "race".to_owned(),
        x_label: "solver run time (setup included) [s]".to_owned(),
        y_label: "relative error [–], log".to_owned(),
        y_ticks: YTicks::Log,
        include_y: vec![0.0, super::race::ENERGY_FLOOR.log10()],
        compact_legend: true,
        ..Figure::default()
    };
    for (i, run) in race.runs.iter().enumerate() {
        let c = colour(i);
        if i == 0 {
            // the reference: its time as a vertical line
            if let Some(s) = run.samples.first() {
                let name = format!("{}: {}", run.racer.label(), units::seconds(s.seconds));
                fig.vlines.push((name, s.seconds, c));
            }
            continue;
        }
        let name = match &run.error {
            Some(e) => format!("{} (failed: {e})", run.racer.label()),
            None => format!("{} ({} it.)", run.racer.label(), run.iterations()),
        };
        let pts = |v: &[egui_plot::PlotPoint]| v.iter().map(|p| [p.x, p.y]).collect();
        fig.series.push(Series {
            name: format!("{name}{COMPACT_CUT}energy-norm error"),
            colour: c,
            style: Style::Line,
            points: pts(&run.energy_points),
        });
        fig.series.push(Series {
            name: format!("{name}{COMPACT_CUT}K error"),
            colour: c,
            style: Style::Dashed,
            points: pts(&run.k_points),
        });
    }
    fig
}

/// The study's first growth against the parameter: the kink angle (one
/// series per mode) and the critical load factor λ_cr, beside the load
/// factor at which the rock away from the cracks reaches its strength.
fn study_figures(study: &Study) -> Vec<Figure> {
    let (unit, factor) = param_unit(&study.path);
    let x_label = format!("{} [{unit}]", super::path_label(&study.path));
    let modes = [
        (cdca::report::Mode::Tension, "tension"),
        (cdca::report::Mode::Shear, "shear"),
    ];
    let angle_series = modes
        .into_iter()
        .enumerate()
        .map(|(i, (mode, name))| Series {
            name: format!("{name} growth"),
            colour: colour(i),
            style: Style::Markers,
            points: study
                .points
                .iter()
                .flat_map(|p| {
                    p.grown
                        .iter()
                        .filter(move |g| g.mode == mode)
                        .map(move |g| [p.value * factor, g.angle_deg])
                })
                .collect(),
        })
        .collect();
    let lambda = study
        .points
        .iter()
        .filter_map(|p| p.load_factor.map(|l| [p.value * factor, l]))
        .collect();
    // u scales with the load: the intact rock fails at λ / u
    let rock: Vec<[f64; 2]> = study
        .points
        .iter()
        .filter_map(|p| {
            let (l, r) = (p.load_factor?, p.intact_rock?);
            (r.utilisation > 0.0).then(|| [p.value * factor, l / r.utilisation])
        })
        .collect();
    let mut load_series = vec![Series {
        name: "λ_cr of the first growth".to_owned(),
        colour: colour(2),
        style: Style::LineAndMarkers,
        points: lambda,
    }];
    if !rock.is_empty() {
        load_series.push(Series {
            name: "λ at which the intact rock reaches its strength".to_owned(),
            colour: colour(3),
            style: Style::Dashed,
            points: rock,
        });
    }
    vec![
        Figure {
            id: "study_angle".to_owned(),
            x_label: x_label.clone(),
            y_label: "first kink angle θ [°]".to_owned(),
            y_ticks: YTicks::Degrees,
            series: angle_series,
            include_y: vec![0.0],
            ..Figure::default()
        },
        Figure {
            id: "study_load".to_owned(),
            x_label,
            // short enough for the plot's height at the default panel
            // size: "critical load factor λ_cr [–]" ran into the legend
            y_label: "load factor λ_cr [–]".to_owned(),
            series: load_series,
            include_y: vec![0.0],
            ..Figure::default()
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The race's legend is one entry per iterative solver (its energy and
    /// K errors share a colour; the line styles are said once beside the
    /// legend), not two long entries per solver.
    #[test]
    fn the_race_legend_has_one_entry_per_solver() {
        let scene = cdca::Scene::try_from(crate::files::scenes::default_scene()).expect("valid");
        let fig = race_figure(&Race::new(&scene, 1.0));
        assert_eq!(fig.series.len(), 8);
        let names: Vec<&str> = fig.legend().map(|s| fig.legend_name(s)).collect();
        assert_eq!(names.len(), 4, "{names:?}");
        assert!(names.iter().all(|n| !n.contains("error")), "{names:?}");
    }
}
