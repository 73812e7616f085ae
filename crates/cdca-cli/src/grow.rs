//! `cdca grow SCENE [--csv DIR]`: runs crack growth (SPEC §9) to its end and
//! prints the `GrowReport` as JSON; with `--csv` also writes the history and
//! the crack paths as CSV.

use std::path::{Path, PathBuf};

use cdca::SolveError;
use cdca::report::GrowReport;
use cdca::scene::IntactRock;

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
    // under "nucleate" the rock past its strength starts cracks, which
    // the report lists (`nucleated`)
    let model = sim.scene().growth.intact_rock;
    if let Some(s) = report
        .steps
        .iter()
        .filter(|_| model == IntactRock::Ignore)
        .find(|s| s.intact_rock.is_some_and(|r| r.utilisation >= 1.0))
    {
        let when = format!("from step {} (λ = {:.3})", s.step, s.load_factor);
        output::note_intact_rock(&when, s.intact_rock.as_ref(), model);
    }
    if let Some(limit) = &report.start_limit {
        eprintln!(
            "cdca: note: growth stopped `unstable`: {} (`start_limit`)",
            limit.reason
        );
    }
    if let Some(s) = &report.strength {
        eprintln!("cdca: note: {} (`strength`)", s.note);
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
