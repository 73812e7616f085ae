//! Reading a scene file: the library has no file system, the CLI does.

use std::path::Path;

use cdca::{Scene, Simulation, SolveError};

use crate::error::CliError;

/// Reads, parses and validates the scene at `path` (its cracks too:
/// [`cdca::check_cracks`]). Every problem is an
/// input error naming the file and, for a bad scene, the field and value.
pub fn load(path: &Path) -> Result<Scene, CliError> {
    let scene = read(path)?;
    cdca::check_cracks(&scene).map_err(|e| input(path, &e))?;
    Ok(scene)
}

/// Reads the scene at `path` and builds its simulation, before any solve:
/// the values are checked as the file is read, and the cracks once, where
/// [`Simulation::new`] builds them (with the checks and messages of
/// [`cdca::check_cracks`]). A bad scene is an input error naming the file.
pub fn simulation(path: &Path) -> Result<Simulation, CliError> {
    Simulation::new(read(path)?).map_err(|e| match e {
        SolveError::Scene(e) => input(path, &e),
        e => e.into(),
    })
}

/// Reads, parses and validates the scene at `path` (not its cracks).
fn read(path: &Path) -> Result<Scene, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::Input(format!("cannot read `{}`: {e}", path.display())))?;
    Scene::from_json(&text).map_err(|e| input(path, &e))
}

/// An input error naming the file.
fn input(path: &Path, e: &impl std::fmt::Display) -> CliError {
    CliError::Input(format!("{}: {e}", path.display()))
}
