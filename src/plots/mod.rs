//! **Plots**: the figures of a solve and a run (residual, K, angles, load
//! factor) and the figure primitives every plot uses. Read data from
//! `results`; know nothing of studies or the runner.
//!
//! - `figure`: a figure's data (curves, points, axes) and its drawing;
//! - `figures`: the figures of a solve and a run;
//! - `plot_tab`: the plot tabs.

pub mod figure;
pub mod figures;
pub mod plot_tab;
