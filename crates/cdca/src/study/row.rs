//! One point's growth report as one CSV row, and a study's table read
//! back (to resume, merge, sum up and draw it).
//!
//! Columns: `point`, `study` (the hash's first 16 hex digits), one per
//! axis (named by its field), then
//!
//! | column | from the run's [`GrowReport`] |
//! | --- | --- |
//! | `outcome` | `outcome` (`invalid`: the scene refused the point's values or geometry) |
//! | `steps` | growth steps recorded |
//! | `every_step_converged` | every step's `converged` |
//! | `peak_step`, `peak_load_factor`, `peak_stress_pa` | `strength`: the peak of λ over the steps that grew something, and λ times the reference stress |
//! | `intact_load_factor`, `strength_ratio` | `strength`: where the uncracked specimen's rock fails, and the peak over it (empty when absent) |
//! | `link_step`, `link_load_factor`, `link_joins` | `coalescence`: the first link between two flaws and what it joins (`wing–secondary`, …) |
//! | `wings` | flaw ends whose first growth was in tension |
//! | `secondary_cracks` | cracks started at kinks (`started`), and flaw ends whose first growth was in shear |
//! | `intact_rock_cracks` | cracks started in the intact rock (`nucleated`) |
//! | `error` | why a point is `invalid` or ended with `error` |
//! | `seconds` | wall time of the point (its scene, its simulation, its run) |
//!
//! Numbers in Rust's shortest round-trip form: apart from `seconds`, a
//! row is a function of the report alone, and equals to the bit the row of
//! `cdca grow` on the point's scene.

use std::fmt::Write as _;

use super::axis::{Input, Point};
use crate::report::{CoalescenceReport, GrowReport, Mode, Outcome, StrengthReport};

/// The columns after the inputs.
pub const RESULT_COLUMNS: [&str; 16] = [
    "outcome",
    "steps",
    "every_step_converged",
    "peak_step",
    "peak_load_factor",
    "peak_stress_pa",
    "intact_load_factor",
    "strength_ratio",
    "link_step",
    "link_load_factor",
    "link_joins",
    "wings",
    "secondary_cracks",
    "intact_rock_cracks",
    "error",
    "seconds",
];

/// The header line for axes named `fields` (CSV-quoted already).
pub(crate) fn header(fields: &[String]) -> String {
    let mut columns = vec!["point".to_owned(), "study".to_owned()];
    columns.extend(fields.iter().cloned());
    columns.extend(RESULT_COLUMNS.iter().map(|c| (*c).to_owned()));
    format!("{}\n", columns.join(","))
}

/// What a growth run gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub steps: usize,
    pub every_step_converged: bool,
    pub strength: Option<StrengthReport>,
    pub link: Option<CoalescenceReport>,
    pub wings: usize,
    pub secondary_cracks: usize,
    pub intact_rock_cracks: usize,
}

/// One point's row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub point: usize,
    pub inputs: Vec<Input>,
    /// The run's outcome as reports spell it, or `invalid`.
    pub outcome: String,
    /// `None` for an `invalid` point, or one whose simulation could not be
    /// made.
    pub run: Option<Run>,
    pub error: Option<String>,
    pub seconds: f64,
}

impl Row {
    /// The row of a finished run of a scene with `drawn` cracks as drawn.
    pub fn of_report(point: &Point, report: &GrowReport, drawn: usize) -> Self {
        let (mut wings, mut secondary, mut intact) = (0, 0, 0);
        let mut seen: Vec<(usize, usize)> = Vec::new();
        for s in &report.steps {
            for g in s.grown.iter().filter(|g| g.crack < drawn) {
                if !seen.contains(&(g.crack, g.tip)) {
                    seen.push((g.crack, g.tip));
                    match g.mode {
                        Mode::Tension => wings += 1,
                        Mode::Shear => secondary += 1,
                        Mode::None => {}
                    }
                }
            }
            secondary += s.started.len();
            intact += s.nucleated.len();
        }
        Self {
            point: point.id,
            inputs: point.inputs.clone(),
            outcome: outcome_name(report.outcome).to_owned(),
            run: Some(Run {
                steps: report.steps.len(),
                every_step_converged: report.steps.iter().all(|s| s.converged),
                strength: report.strength.clone(),
                link: report.coalescence.clone(),
                wings,
                secondary_cracks: secondary,
                intact_rock_cracks: intact,
            }),
            error: report.error.clone(),
            seconds: 0.0,
        }
    }

    /// A point whose scene refused its values or geometry.
    pub fn invalid(point: &Point, why: &str) -> Self {
        Self {
            point: point.id,
            inputs: point.inputs.clone(),
            outcome: "invalid".to_owned(),
            run: None,
            error: Some(why.to_owned()),
            seconds: 0.0,
        }
    }

    /// A point whose simulation could not be made (outcome `error`).
    pub fn failed(point: &Point, why: &str) -> Self {
        Self {
            outcome: outcome_name(Outcome::Error).to_owned(),
            ..Self::invalid(point, why)
        }
    }

    /// The row as one CSV line (with its line break), `study` being the
    /// study's short hash. A message's line breaks become spaces, so that
    /// a row is one line.
    pub fn csv(&self, study: &str) -> String {
        let mut out = format!("{},{study}", self.point);
        for input in &self.inputs {
            let _ = write!(out, ",{}", input.csv());
        }
        let opt = |x: Option<f64>| x.map(|v| v.to_string()).unwrap_or_default();
        let _ = write!(out, ",{}", self.outcome);
        match &self.run {
            None => out.push_str(",,,,,,,,,,,,,"),
            Some(r) => {
                let s = r.strength.as_ref();
                let l = r.link.as_ref();
                let _ = write!(
                    out,
                    ",{},{},{},{},{},{},{},{},{},{},{},{},{}",
                    r.steps,
                    r.every_step_converged,
                    s.map(|s| s.peak_step.to_string()).unwrap_or_default(),
                    opt(s.map(|s| s.peak_load_factor)),
                    opt(s.map(|s| s.peak_stress)),
                    opt(s.and_then(|s| s.intact_load_factor)),
                    opt(s.and_then(|s| s.ratio)),
                    l.map(|l| l.step.to_string()).unwrap_or_default(),
                    opt(l.map(|l| l.load_factor)),
                    l.map(|l| crate::csv::field(&l.category))
                        .unwrap_or_default(),
                    r.wings,
                    r.secondary_cracks,
                    r.intact_rock_cracks,
                );
            }
        }
        let error = self
            .error
            .as_deref()
            .unwrap_or_default()
            .replace(['\n', '\r'], " ");
        let _ = writeln!(out, ",{},{:.3}", crate::csv::field(&error), self.seconds);
        out
    }
}

/// An outcome as reports spell it (`max_steps`, `not_converged`).
pub fn outcome_name(o: Outcome) -> &'static str {
    match o {
        Outcome::Completed => "completed",
        Outcome::Unstable => "unstable",
        Outcome::Through => "through",
        Outcome::MaxSteps => "max_steps",
        Outcome::NotConverged => "not_converged",
        Outcome::Error => "error",
    }
}

/// The point number and the study's short hash of a row, its first two
/// cells; `None` for a line that is not a row (the header, a fragment).
pub fn row_key(line: &str) -> Option<(usize, &str)> {
    let mut cells = line.splitn(3, ',');
    let point = cells.next()?.parse().ok()?;
    let study = cells.next()?;
    cells.next()?;
    Some((point, study))
}

/// A line without its last cell (`seconds`): rows compared "seconds
/// aside".
pub fn without_seconds(line: &str) -> &str {
    line.trim_end_matches(['\n', '\r'])
        .rsplit_once(',')
        .map_or(line, |(head, _)| head)
}

/// A study's table read back: its columns and, per row, its cells.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    pub columns: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads CSV text: a header line, then one row a line (cells quoted
    /// where they hold a comma or a quote). A line with another number of
    /// cells than the header is an error naming it (1-based).
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut lines = text.lines();
        let columns = split(lines.next().ok_or("no header line")?);
        let mut rows = Vec::new();
        for (i, line) in lines.enumerate() {
            let cells = split(line);
            if cells.len() != columns.len() {
                return Err(format!(
                    "line {}: {} cells, the header has {}",
                    i + 2,
                    cells.len(),
                    columns.len()
                ));
            }
            rows.push(cells);
        }
        Ok(Self { columns, rows })
    }

    /// The index of the column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// Row `r`'s cell in column `name` (`""` when there is no such column).
    pub fn cell(&self, r: usize, name: &str) -> &str {
        self.column(name)
            .and_then(|c| self.rows.get(r).and_then(|row| row.get(c)))
            .map_or("", String::as_str)
    }
}

/// The cells of one CSV line (RFC 4180 quoting).
fn split(line: &str) -> Vec<String> {
    let mut cells = Vec::new();
    let mut cell = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => cells.push(std::mem::take(&mut cell)),
            (c, _) => cell.push(c),
        }
    }
    cells.push(cell);
    cells
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{GrownTip, GrowthStepReport, NucleatedCrack, StartedCrack};

    fn step(step: usize, grown: &[(usize, usize, Mode)], started: usize) -> GrowthStepReport {
        GrowthStepReport {
            step,
            load_factor: 0.5 + step as f64 / 10.0,
            converged: true,
            grown: grown
                .iter()
                .map(|&(crack, tip, mode)| GrownTip {
                    crack,
                    tip,
                    mode,
                    ..GrownTip::default()
                })
                .collect(),
            started: vec![StartedCrack::default(); started],
            ..GrowthStepReport::default()
        }
    }

    /// Wings and secondary cracks are counted as the lineage names them:
    /// a flaw end's first growth names it (tension: a wing; shear: a
    /// secondary crack), later growth of that end and of cracks that are
    /// not flaws (index ≥ drawn) does not count again, and each crack
    /// started at a kink is one secondary crack; cracks started in the
    /// intact rock are counted apart.
    #[test]
    fn a_report_makes_a_row_with_its_counts() {
        let mut report = GrowReport {
            steps: vec![
                step(1, &[(0, 0, Mode::Tension), (0, 1, Mode::Tension)], 0),
                step(2, &[(0, 0, Mode::Shear), (1, 1, Mode::Shear)], 1),
                step(3, &[(2, 1, Mode::Tension)], 0),
            ],
            outcome: Outcome::Through,
            coalescence: Some(CoalescenceReport {
                step: 3,
                load_factor: 0.8,
                category: "wing–secondary".to_owned(),
                flaws: [0, 1],
            }),
            strength: Some(StrengthReport {
                peak_step: 3,
                peak_load_factor: 0.8,
                reference_stress: 1e8,
                peak_stress: 8e7,
                ..StrengthReport::default()
            }),
            ..GrowReport::default()
        };
        report.steps[2].nucleated = vec![NucleatedCrack::default()];
        report.steps[1].converged = false;
        let point = Point {
            id: 7,
            inputs: vec![
                Input::Number(0.25),
                Input::Json(serde_json::Value::from("a, b")),
            ],
        };
        let row = Row::of_report(&point, &report, 2);
        let run = row.run.as_ref().expect("a run");
        assert_eq!(
            (run.wings, run.secondary_cracks, run.intact_rock_cracks),
            (2, 2, 1)
        );
        assert_eq!(
            row.csv("abc"),
            "7,abc,0.25,\"a, b\",through,3,false,3,0.8,80000000,,,3,0.8,wing–secondary,2,2,1,,0.000\n"
        );
        let header = header(&["x".to_owned(), "y".to_owned()]);
        let table = Table::parse(&format!("{header}{}", row.csv("abc"))).expect("parses");
        assert_eq!(table.cell(0, "y"), "a, b");
        assert_eq!(table.cell(0, "link_joins"), "wing–secondary");
        assert_eq!(table.cell(0, "seconds"), "0.000");
        assert_eq!(row_key(&row.csv("abc")), Some((7, "abc")));
        assert_eq!(row_key(&header), None);
        assert!(without_seconds(&row.csv("abc")).ends_with(",2,2,1,"));
    }

    /// An invalid point has its inputs, the outcome `invalid`, the reason
    /// (on one line) and empty results, as many cells as the header.
    #[test]
    fn an_invalid_point_keeps_its_inputs_and_reason() {
        let point = Point {
            id: 2,
            inputs: vec![Input::Number(-1.0)],
        };
        let row = Row::invalid(&point, "scene field `x` = -1:\nmust be ≥ 0");
        let line = row.csv("h");
        let header = header(&["x".to_owned()]);
        let table = Table::parse(&format!("{header}{line}")).expect("same cells as the header");
        assert_eq!(table.cell(0, "outcome"), "invalid");
        assert_eq!(table.cell(0, "error"), "scene field `x` = -1: must be ≥ 0");
        assert_eq!(table.cell(0, "steps"), "");
        assert_eq!(Row::failed(&point, "x").outcome, "error");
    }
}
