//! Side, top and bottom panels. Each reads the app's state and pushes
//! [`crate::Command`]s; view-only settings (what to draw) are edited in place.

mod frame_stats;
pub mod menu;
pub mod plots;
pub mod scene;
pub mod solver;
pub mod tip;
mod widgets;

pub use frame_stats::FrameStats;
pub use plots::PlotTab;
