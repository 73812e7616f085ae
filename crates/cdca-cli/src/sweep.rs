//! `cdca sweep SCENE --param PATH --values a,b,c [--csv FILE]`: the first
//! critical-growth step of the scene for each value of one parameter
//! (`cdca::initiation`); prints a table and optionally writes it as CSV.

use std::fmt::Write as _;
use std::path::PathBuf;

use crate::error::CliError;
use crate::scene_file;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (JSON, SPEC §10).
    scene: PathBuf,
    /// Dotted path of a numeric scene field: `cracks.0.friction`,
    /// `boundary.right.normal`, `criterion.r0`.
    #[arg(long, value_name = "PATH")]
    param: String,
    /// Comma-separated values of the parameter.
    #[arg(
        long,
        value_name = "A,B,C",
        value_delimiter = ',',
        required = true,
        allow_hyphen_values = true
    )]
    values: Vec<f64>,
    /// Also write the table as CSV to this file.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let scene = scene_file::load(&args.scene)?;
    // every value checked before any work
    let scenes = args
        .values
        .iter()
        .map(|&v| scene.with_param(&args.param, v))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| CliError::Input(e.to_string()))?;
    let mut csv = format!("{},angle_deg,mode,lambda_cr,k1,k2,converged\n", args.param);
    let mut table = format!(
        "{:>14} {:>10} {:>8} {:>12} {:>12} {:>12} {:>9}\n",
        args.param, "angle_deg", "mode", "lambda_cr", "K_I", "K_II", "converged"
    );
    let mut failed = Vec::new();
    for (v, s) in args.values.iter().zip(&scenes) {
        let i = cdca::initiation(s)?;
        let mode = i.mode.name();
        let _ = writeln!(
            csv,
            "{v},{},{mode},{},{},{},{}",
            i.angle_deg, i.lambda_cr, i.k1, i.k2, i.converged
        );
        let _ = writeln!(
            table,
            "{v:>14} {:>10.2} {mode:>8} {:>12.5} {:>12.4e} {:>12.4e} {:>9}",
            i.angle_deg, i.lambda_cr, i.k1, i.k2, i.converged
        );
        if !i.converged {
            failed.push(*v);
        }
    }
    print!("{table}");
    if let Some(path) = &args.csv {
        std::fs::write(path, csv)
            .map_err(|e| CliError::Input(format!("cannot write `{}`: {e}", path.display())))?;
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::Failure(format!(
            "{} = {failed:?}: a solve or the λ_cr search did not converge",
            args.param
        )))
    }
}
