//! The report tables as CSV, one writer per table, shared by the CLI
//! (`cdca grow --csv`, `cdca bench`) and the workbench's exports, so both
//! write the same columns (listed in `docs/cli.md`). Each writes to a
//! `String`; the callers do the file I/O. Numbers are written in Rust's
//! shortest round-trip form, so a value reads back to the same bits, and no
//! table holds a wall time except the race's, whose subject it is.

use std::fmt::Write as _;

use crate::race::Sample;
use crate::report::GrowthStepReport;

/// Header of [`crack_paths`].
pub const CRACK_PATHS_HEADER: &str = "crack,vertex,x_m,y_m";

/// Header of [`growth_history`].
pub const GROWTH_HISTORY_HEADER: &str = "step,load_factor,crack,tip,x_m,y_m,k1_pa_sqrt_m,\
     k2_pa_sqrt_m,t_stress_pa,mode,angle_deg,grew,open,stick,slip,solver_iterations,\
     converged,intact_rock_utilisation";

/// Header of [`race`].
pub const RACE_HEADER: &str = "scene,size,solver,iteration,seconds,energy_error,k1_error,k2_error";

/// The crack paths: one row per polyline vertex, `crack,vertex,x_m,y_m`.
pub fn crack_paths(cracks: &[Vec<[f64; 2]>]) -> String {
    let mut out = format!("{CRACK_PATHS_HEADER}\n");
    for (i, c) in cracks.iter().enumerate() {
        for (k, [x, y]) in c.iter().enumerate() {
            let _ = writeln!(out, "{i},{k},{x},{y}");
        }
    }
    out
}

/// The growth history: one row per step and free tip (a step without a
/// free tip has one row with the tip's columns empty): the tip's SIFs
/// (Pa·√m) and T-stress (Pa), the criterion's mode and kink angle (degrees,
/// tip frame), whether the tip grew (1) in that step, the step's contact
/// counts, linear-solver iterations, convergence and the intact rock's
/// utilisation of its strength (empty for a rock without cohesion).
pub fn growth_history(steps: &[GrowthStepReport]) -> String {
    let mut out = format!("{GROWTH_HISTORY_HEADER}\n");
    for s in steps {
        let tail = format!(
            "{},{},{},{},{},{}",
            s.contact.open,
            s.contact.stick,
            s.contact.slip,
            s.solver_iterations,
            s.converged,
            s.intact_rock
                .map(|r| r.utilisation.to_string())
                .unwrap_or_default()
        );
        if s.tips.is_empty() {
            let _ = writeln!(out, "{},{},,,,,,,,,,,{tail}", s.step, s.load_factor);
        }
        for t in &s.tips {
            let grew = s.grown.iter().any(|g| g.crack == t.crack && g.tip == t.tip);
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{},{},{},{},{tail}",
                s.step,
                s.load_factor,
                t.crack,
                t.tip,
                t.x,
                t.y,
                t.k1,
                t.k2,
                t.t_stress,
                t.criterion.mode.name(),
                t.criterion.angle_deg,
                u8::from(grew),
            );
        }
    }
    out
}

/// One solver's run in a race: its samples of the error against time.
#[derive(Clone, Copy, Debug)]
pub struct RaceRun<'a> {
    /// The scene's name.
    pub scene: &'a str,
    /// Elements along x.
    pub size: usize,
    /// The solver's name.
    pub solver: &'a str,
    pub samples: &'a [Sample],
}

/// The solver race (error against run time): one row per sample, the
/// relative energy-norm error of the displacement and the relative K_I,
/// K_II errors against the direct solution.
pub fn race<'a>(runs: impl IntoIterator<Item = RaceRun<'a>>) -> String {
    let mut out = format!("{RACE_HEADER}\n");
    for r in runs {
        let scene = field(r.scene);
        for p in r.samples {
            let _ = writeln!(
                out,
                "{scene},{},{},{},{},{},{},{}",
                r.size, r.solver, p.iteration, p.seconds, p.energy, p.k1, p.k2
            );
        }
    }
    out
}

/// A text field, quoted when it holds a comma, a quote or a line break.
pub fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{CriterionReport, Mode, TipReport};

    #[test]
    fn crack_paths_have_one_row_per_vertex() {
        let csv = crack_paths(&[vec![[0.0, 0.0], [1.0, 0.5]], vec![[0.25, 1e-3]]]);
        assert_eq!(
            csv,
            "crack,vertex,x_m,y_m\n0,0,0,0\n0,1,1,0.5\n1,0,0.25,0.001\n"
        );
    }

    #[test]
    fn history_marks_the_tips_that_grew_in_every_column() {
        let tip = |tip| TipReport {
            crack: 0,
            tip,
            criterion: CriterionReport {
                mode: Mode::Tension,
                angle_deg: 60.0,
                ..CriterionReport::default()
            },
            ..TipReport::default()
        };
        let mut step = GrowthStepReport {
            step: 3,
            tips: vec![tip(0), tip(1)],
            ..GrowthStepReport::default()
        };
        step.grown = vec![crate::report::GrownTip {
            crack: 0,
            tip: 1,
            ..crate::report::GrownTip::default()
        }];
        let csv = growth_history(&[step]);
        let columns = GROWTH_HISTORY_HEADER.split(',').count();
        assert!(
            csv.lines().all(|l| l.split(',').count() == columns),
            "{csv}"
        );
        let grew: Vec<&str> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(11).unwrap_or_default())
            .collect();
        assert_eq!(grew, ["0", "1"]);
        assert!(
            csv.lines()
                .nth(1)
                .is_some_and(|l| l.contains(",tension,60,"))
        );
    }

    #[test]
    fn text_fields_are_quoted_only_when_needed() {
        assert_eq!(field("plate"), "plate");
        assert_eq!(field("a, b"), "\"a, b\"");
        assert_eq!(field("say \"x\""), "\"say \"\"x\"\"\"");
    }
}
