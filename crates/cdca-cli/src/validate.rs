//! `cdca validate SCENE`: checks a scene, prints nothing when it is valid.

use std::path::PathBuf;

use crate::error::CliError;
use crate::scene_file;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (JSON, SPEC §10).
    scene: PathBuf,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    scene_file::load(&args.scene).map(drop)
}
