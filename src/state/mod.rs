//! **What the user asks for**: the commands the panels and the canvas
//! send, the app's state they read (`AppView`), the edit in progress, the
//! job slot, undo, the layout and the settings kept between sessions. Uses
//! the parts below (studies, runs, results, plots, files, style).
//!
//! - `command`: every command the UI sends;
//! - `view`: what the panels read of the app (`AppView`);
//! - `edit`: the crack being drawn or moved;
//! - `job`: the one job slot;
//! - `undo`: the undo stack;
//! - `layout`: the panels' layout;
//! - `settings`: what the canvas shows (`ViewSettings`);
//! - `persist`: the settings kept between sessions;
//! - `frame_stats`: frame times.

pub mod command;
pub(crate) mod edit;
pub(crate) mod frame_stats;
pub mod job;
pub mod layout;
pub(crate) mod persist;
pub(crate) mod settings;
pub(crate) mod undo;
pub(crate) mod view;
