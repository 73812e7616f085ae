//! What the canvas shows: the field, the layers and the deformation, as
//! the user set them (kept between sessions by `persist`).

use serde::{Deserialize, Serialize};

use crate::results::field::FieldKind;

/// How the specimen is shown (persisted). Independent switches, so bools.
#[allow(clippy::struct_excessive_bools)]
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct ViewSettings {
    pub field: FieldKind,
    pub show_mesh: bool,
    pub show_loads: bool,
    pub show_contact: bool,
    pub show_traction_arrows: bool,
    pub deformed: bool,
    /// Deformation magnification; `None` picks one so the largest
    /// displacement shows as 5 % of the specimen.
    pub deform_scale: Option<f64>,
    /// Colour range from the 1st–99th percentiles instead of min–max.
    pub clip_range: bool,
    /// Field samples per element side.
    pub samples_per_cell: usize,
    /// Frame-time overlay.
    pub frame_overlay: bool,
}

impl Default for ViewSettings {
    fn default() -> Self {
        Self {
            field: FieldKind::default(),
            show_mesh: false,
            show_loads: true,
            show_contact: true,
            show_traction_arrows: true,
            deformed: false,
            deform_scale: None,
            clip_range: true,
            samples_per_cell: 2,
            frame_overlay: false,
        }
    }
}
