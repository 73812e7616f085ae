//! `cdca grow SCENE [--csv DIR]`: runs crack growth (SPEC §9) to its end and
//! prints the `GrowReport` as JSON; with `--csv` also writes the history and
//! the crack paths as CSV.

use std::path::{Path, PathBuf};

use cdca::SolveError;
use cdca::report::GrowReport;

use crate::error::CliError;
use crate::{output, scene_file};

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (JSON, SPEC §10).
    scene: PathBuf,
    /// Also write `history.csv` and `cracks.csv` into this directory
    /// (created if missing).
    #[arg(long, value_name = "DIR")]
    csv: Option<PathBuf>,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let mut sim = scene_file::simulation(&args.scene)?;
    let (report, failed) = sim.grow_to_end();
    if let Some(dir) = &args.csv {
        write_csv(dir, &report)?;
    }
    output::print_json(&report)?;
    if let Some(cap) = &report.load_cap {
        eprintln!("cdca: note: growth {} (`load_cap`)", cap.reason);
    }
    if let Some(s) = report
        .steps
        .iter()
        .find(|s| s.intact_rock.is_some_and(|r| r.utilisation >= 1.0))
    {
        let when = format!("from step {} (λ = {:.3})", s.step, s.load_factor);
        output::note_intact_rock(&when, s.intact_rock.as_ref());
    }
    for s in report
        .steps
        .iter()
        .filter(|s| !s.unsolved_trials.is_empty())
    {
        let at: Vec<String> = s
            .unsolved_trials
            .iter()
            .map(|l| format!("{l:.4}"))
            .collect();
        eprintln!(
            "cdca: note: step {}: the λ_cr search moved away from trials whose solve did \
             not converge, at λ = {} (`unsolved_trials`)",
            s.step,
            at.join(", ")
        );
    }
    // the report is printed either way; growth stopped on an unconverged
    // solve exits 1, on an error with that error's code
    if let Some(e) = failed {
        let m = format!(
            "{}; growth stopped",
            report.error.as_deref().unwrap_or_default()
        );
        return Err(match e {
            SolveError::Scene(_) => CliError::Input(m),
            _ => CliError::Failure(m),
        });
    }
    match report.steps.iter().find(|s| !s.converged) {
        Some(s) => Err(CliError::Failure(format!(
            "step {} did not converge: {}; growth stopped",
            s.step,
            s.failure.as_deref().unwrap_or("no reason recorded")
        ))),
        None => Ok(()),
    }
}

fn write_csv(dir: &Path, report: &GrowReport) -> Result<(), CliError> {
    let failed = |path: &Path, e: std::io::Error| {
        CliError::Input(format!("cannot write `{}`: {e}", path.display()))
    };
    std::fs::create_dir_all(dir).map_err(|e| failed(dir, e))?;
    for (name, text) in [
        ("history.csv", cdca::csv::growth_history(&report.steps)),
        ("cracks.csv", cdca::csv::crack_paths(&report.cracks)),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| failed(&path, e))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdca::Simulation;
    use cdca::report::{GrowthStepReport, Outcome};

    /// `Simulation::grow_to_end` with the step injected: growth steps by
    /// `step` until the run ends or a step fails, and the run's report.
    fn grow(
        sim: &mut Simulation,
        mut step: impl FnMut(&mut Simulation) -> Result<(), SolveError>,
    ) -> (GrowReport, Option<SolveError>) {
        let mut failed = None;
        let outcome = loop {
            if let Some(outcome) = sim.growth_finished() {
                break outcome;
            }
            if let Err(e) = step(sim) {
                failed = Some(e);
                break Outcome::Error;
            }
        };
        (sim.grow_report(outcome, failed.as_ref()), failed)
    }

    /// A step that fails ends growth with the steps before it in the
    /// report: the first two steps of the bundled single flaw (40 × 40),
    /// equal to those of an uninterrupted run (time aside), outcome
    /// `error`, and the message naming step 3; the error is handed back
    /// for the exit code.
    #[test]
    fn a_failing_step_keeps_the_steps_before_it() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/scenes/specimen_single_flaw.json"
        );
        let text = std::fs::read_to_string(path).expect("bundled scene");
        let mut file = cdca::Scene::from_json(&text).expect("valid").into_file();
        file.mesh.nx = 40;
        file.mesh.ny = 40;
        file.growth.max_steps = 3;
        let scene = cdca::Scene::try_from(file).expect("valid");
        let untimed = |steps: &[GrowthStepReport]| -> Vec<GrowthStepReport> {
            steps
                .iter()
                .map(|s| GrowthStepReport {
                    seconds: 0.0,
                    ..s.clone()
                })
                .collect()
        };
        let mut sim = Simulation::new(scene.clone()).expect("solvable");
        let (reference, failed) = grow(&mut sim, |sim| sim.grow_step().map(drop));
        assert!(failed.is_none() && reference.error.is_none());
        assert_eq!(
            (reference.outcome, reference.steps.len()),
            (Outcome::MaxSteps, 3)
        );

        let mut sim = Simulation::new(scene).expect("solvable");
        let (report, failed) = grow(&mut sim, |sim| {
            if sim.history().len() == 2 {
                Err(SolveError::NotPositiveDefinite {
                    dofs: 7,
                    detail: "NonPositivePivot { index: 6 }".to_owned(),
                })
            } else {
                sim.grow_step().map(drop)
            }
        });
        assert!(matches!(
            failed,
            Some(SolveError::NotPositiveDefinite { dofs: 7, .. })
        ));
        assert_eq!(report.outcome, Outcome::Error);
        assert_eq!(untimed(&report.steps), untimed(&reference.steps[..2]));
        let json = serde_json::to_value(&report).expect("JSON");
        assert_eq!(json["outcome"], "error");
        assert_eq!(json["steps"].as_array().map(Vec::len), Some(2));
        assert_eq!(
            json["error"],
            "step 3: stiffness matrix is not positive definite (7 DOFs): \
             NonPositivePivot { index: 6 }"
        );
        // a run that ends normally has no `error` field
        let json = serde_json::to_value(&reference).expect("JSON");
        assert!(json.get("error").is_none());
    }
}
