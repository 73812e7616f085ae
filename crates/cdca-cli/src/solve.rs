//! `cdca solve SCENE`: one solve at full load, no growth; prints the
//! `SolveReport` as JSON.

use std::path::PathBuf;

use cdca::report::OtherSolutionReport;

use crate::error::CliError;
use crate::{output, scene_file};

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (JSON, SPEC §10).
    scene: PathBuf,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    // The scene is validated here, before any solve.
    let mut sim = scene_file::simulation(&args.scene)?;
    sim.set_load_factor(1.0);
    let mut report = sim.solve()?;
    // where faces close, the same problem from the opposite start: Coulomb
    // friction need not have one solution
    if OtherSolutionReport::worth_checking(&report) {
        let second = sim.bonded_start()?.solve()?;
        report.other_solution = OtherSolutionReport::between(&report, &second, "bonded");
    }
    output::print_json(&report)?;
    output::note_intact_rock(
        "at full load",
        report.intact_rock.as_ref(),
        sim.scene().growth.intact_rock,
    );
    if let Some(o) = &report.other_solution {
        eprintln!("cdca: note: {}", o.sentence(&report.contact));
    }
    // the report is printed either way; an unconverged solve exits 1
    match report.failure() {
        Some(why) => Err(CliError::Failure(why)),
        None => Ok(()),
    }
}
