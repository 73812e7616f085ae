//! The CDCA workbench: an egui application on top of the headless `cdca`
//! solver crate. `main.rs` is a thin native (and web) wrapper around
//! [`WorkbenchApp`].

pub mod app;
mod apply;
mod canvas;
pub mod command;
pub mod compare;
mod contrast;
mod edit;
mod export;
mod field;
mod figure;
mod figures;
mod frame_stats;
mod grower;
mod io;
pub mod job;
pub mod layout;
pub mod link;
mod pacer;
mod panels;
mod path_prompt;
mod persist;
mod plot_tab;
mod replay;
mod restore;
mod run;
mod run_timer;
mod runner;
pub mod scenes;
mod solution;
pub mod story;
pub mod study;
pub mod study_file;
mod study_map;
mod task;
mod typed;
mod undo;
mod units;
mod view;
#[cfg(target_arch = "wasm32")]
pub mod web;
#[cfg(target_arch = "wasm32")]
mod web_work;

pub use app::{Options, StartRun, WorkbenchApp};
pub use command::Command;
pub use plot_tab::PlotTab;
pub use run::RunMode;
