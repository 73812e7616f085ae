//! The CDCA workbench: an egui application on top of the headless `cdca`
//! solver crate. `main.rs` is a thin native (and web) wrapper around
//! [`WorkbenchApp`].

pub mod app;
mod apply;
mod canvas;
pub mod command;
mod compare;
mod edit;
mod export;
mod field;
mod io;
mod panels;
mod persist;
mod runner;
pub mod scenes;
mod solution;
mod units;
#[cfg(target_arch = "wasm32")]
pub mod web;

pub use app::{Options, WorkbenchApp};
pub use command::Command;
pub use runner::RunMode;
