//! What survives a restart: the last scene and the view settings. A small
//! `#[serde(default)]` struct, so older or newer saves still load.

use serde::{Deserialize, Serialize};

use crate::state::layout::LayoutSettings;
use crate::state::settings::ViewSettings;

/// Saved as JSON through eframe's storage under [`STORAGE_KEY`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Persisted {
    /// The scene being edited, as scene-file JSON.
    pub scene_json: Option<String>,
    /// Where it came from (file name or bundled title).
    pub scene_source: String,
    pub view: ViewSettings,
    /// Which side panels show, and the text size.
    pub layout: LayoutSettings,
}

/// Key of the saved state in eframe's storage.
pub const STORAGE_KEY: &str = "cdca-workbench";

impl Persisted {
    /// The saved state, or the default when there is none or it does not parse.
    pub fn load(storage: Option<&dyn eframe::Storage>) -> Self {
        storage
            .and_then(|s| s.get_string(STORAGE_KEY))
            .and_then(|text| serde_json::from_str(&text).ok())
            .unwrap_or_default()
    }

    pub fn store(&self, storage: &mut dyn eframe::Storage) {
        if let Ok(text) = serde_json::to_string(self) {
            storage.set_string(STORAGE_KEY, text);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_fields_take_defaults() {
        let p: Persisted = serde_json::from_str(r#"{"scene_source": "x"}"#).unwrap_or_default();
        assert_eq!(p.scene_source, "x");
        assert_eq!(p.view, ViewSettings::default());
        assert!(p.scene_json.is_none());
    }
}
