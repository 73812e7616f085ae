//! **Style**: how numbers and colours read on screen. Uses nothing of the
//! workbench.
//!
//! - `units`: numbers with their units, to significant digits;
//! - `contrast`: colours legible on the theme's canvas.

pub mod contrast;
pub mod units;
