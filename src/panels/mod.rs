//! Side, top and bottom panels. Each reads a [`crate::state::view::AppView`] and
//! pushes [`crate::Command`]s; view-only settings (what to draw) are edited
//! in place through a [`crate::state::view::ViewState`]. No panel sees the app.

pub mod menu;
pub mod plots;
pub mod replay;
pub mod run_bar;
pub mod scene;
pub mod solver;
pub mod story;
pub mod study_file;
pub mod tip;
mod typed;
mod widgets;
