//! `cdca grow SCENE [--csv DIR]`: runs crack growth (SPEC §9) to its end and
//! prints the `GrowReport` as JSON; with `--csv` also writes the history and
//! the crack paths as CSV.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use cdca::Simulation;
use cdca::report::{GrowReport, GrowthStepReport, Mode};

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
    let scene = scene_file::load(&args.scene)?;
    let mut sim = Simulation::new(scene)?;
    let outcome = loop {
        if let Some(outcome) = sim.growth_finished() {
            break outcome;
        }
        sim.grow_step()?;
    };
    let report = GrowReport {
        steps: sim.history().to_vec(),
        outcome,
        cracks: sim.cracks(),
    };
    if let Some(dir) = &args.csv {
        write_csv(dir, &report)?;
    }
    output::print_json(&report)?;
    // the report is printed either way; growth stopped on an unconverged
    // solve exits 1
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
        ("history.csv", history_csv(&report.steps)),
        ("cracks.csv", cracks_csv(&report.cracks)),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| failed(&path, e))?;
    }
    Ok(())
}

/// One row per grown tip per step.
fn history_csv(steps: &[GrowthStepReport]) -> String {
    let mut csv = String::from("step,load_factor,crack,tip,x,y,mode,angle_deg,k1,k2\n");
    for step in steps {
        for g in &step.grown {
            let mode = match g.mode {
                Mode::Tension => "tension",
                Mode::Shear => "shear",
                Mode::None => "none",
            };
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{mode},{},{},{}",
                step.step, step.load_factor, g.crack, g.tip, g.x, g.y, g.angle_deg, g.k1, g.k2
            );
        }
    }
    csv
}

/// One row per crack vertex.
fn cracks_csv(cracks: &[Vec<[f64; 2]>]) -> String {
    let mut csv = String::from("crack,point,x,y\n");
    for (c, points) in cracks.iter().enumerate() {
        for (k, [x, y]) in points.iter().enumerate() {
            let _ = writeln!(csv, "{c},{k},{x},{y}");
        }
    }
    csv
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdca::report::GrownTip;

    #[test]
    fn history_has_one_row_per_grown_tip() {
        let tip = |crack, tip, mode| GrownTip {
            crack,
            tip,
            x: 0.125,
            y: 0.5,
            mode,
            angle_deg: -70.5,
            k1: 1.5e6,
            k2: -2e5,
        };
        let steps = [
            GrowthStepReport {
                step: 0,
                load_factor: 0.1,
                ..Default::default()
            },
            GrowthStepReport {
                step: 1,
                load_factor: 0.2,
                grown: vec![tip(0, 1, Mode::Tension), tip(1, 0, Mode::Shear)],
                ..Default::default()
            },
        ];
        assert_eq!(
            history_csv(&steps),
            "step,load_factor,crack,tip,x,y,mode,angle_deg,k1,k2\n\
             1,0.2,0,1,0.125,0.5,tension,-70.5,1500000,-200000\n\
             1,0.2,1,0,0.125,0.5,shear,-70.5,1500000,-200000\n"
        );
    }

    #[test]
    fn cracks_list_every_vertex() {
        let cracks = vec![vec![[0.0, 1.0], [0.5, 1.25]], vec![[0.1, 0.2]]];
        assert_eq!(
            cracks_csv(&cracks),
            "crack,point,x,y\n0,0,0,1\n0,1,0.5,1.25\n1,0,0.1,0.2\n"
        );
    }
}
