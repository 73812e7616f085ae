//! The CDCA workbench: an egui application on top of the headless `cdca`
//! solver crate. `main.rs` is a thin native (and web) wrapper around
//! [`WorkbenchApp`].
//!
//! Its parts, bottom to top; each uses only the parts below it
//! (`tests/layout.rs` checks it):
//!
//! - `style`: how numbers and colours read;
//! - `files`: scenes and files opened, saved and shared;
//! - `results`: what a run leaves (solution view, field, replay, story,
//!   exports);
//! - `run`: how work runs (the host of the simulation, its runs, the run
//!   protocol and its links, the UI's runner);
//! - `plots`: the figures of a solve and a run;
//! - `study`: studies and the solver race, and their plots;
//! - `state`: what the user asks for (commands, the app's view, edits,
//!   the job slot, undo, layout and settings);
//! - `canvas`: the specimen drawn;
//! - `panels`: the panels, menus and bars;
//! - `app`: the frame loop, commands applied, the browser's wrapper.

pub mod app;
mod canvas;
pub mod files;
mod panels;
mod plots;
pub mod results;
mod run;
pub mod state;
pub mod study;
mod style;

pub use app::{Options, StartRun, WorkbenchApp};
pub use plots::plot_tab::PlotTab;
pub use run::RunMode;
pub use run::host::host_calls_on_this_thread;
#[cfg(target_arch = "wasm32")]
pub use run::worker::serve as serve_worker;
pub use state::command::Command;
