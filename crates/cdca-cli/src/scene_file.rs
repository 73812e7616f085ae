//! Reading a scene file: the library has no file system, the CLI does.

use std::path::Path;

use cdca::Scene;

use crate::error::CliError;

/// Reads, parses and validates the scene at `path` (its cracks too:
/// [`cdca::check_cracks`]). Every problem is an
/// input error naming the file and, for a bad scene, the field and value.
pub fn load(path: &Path) -> Result<Scene, CliError> {
    let shown = path.display();
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::Input(format!("cannot read `{shown}`: {e}")))?;
    let scene = Scene::from_json(&text).map_err(|e| CliError::Input(format!("{shown}: {e}")))?;
    cdca::check_cracks(&scene).map_err(|e| CliError::Input(format!("{shown}: {e}")))?;
    Ok(scene)
}
