//! `cdca solve SCENE`: one solve at full load, no growth, and where faces
//! close the same problem from bonded faces
//! ([`Simulation::solve_scene`](cdca::Simulation::solve_scene)); prints the
//! `SolveReport` as JSON.

use std::path::PathBuf;
use std::time::Instant;

use crate::error::CliError;
use crate::{output, scene_file};

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (JSON, SPEC §10).
    scene: PathBuf,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let started = Instant::now();
    // The scene is validated here, before any solve.
    let sim = scene_file::simulation(&args.scene)?;
    let intact_rock = sim.scene().growth.intact_rock;
    let report = sim.solve_scene(started)?;
    output::print_json(&report)?;
    output::note_intact_rock("at full load", report.intact_rock.as_ref(), intact_rock);
    if let Some(o) = &report.other_solution {
        eprintln!("cdca: note: {}", o.sentence(&report.contact));
    }
    // the report is printed either way; an unconverged solve exits 1
    match report.failure() {
        Some(why) => Err(CliError::Failure(why)),
        None => Ok(()),
    }
}
