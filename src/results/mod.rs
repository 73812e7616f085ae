//! **What a run leaves**: the view of a solution the panels read, the
//! sampled field the canvas draws, the replay of a run's steps, its story
//! and the files exported from it. Uses `files` and `style`.
//!
//! - `solution`: the view of the simulation's state (`SolutionView`);
//! - `field`: the sampled stress and displacement fields;
//! - `replay`: a growth run's steps, to be shown again;
//! - `story`: a run told in a few sentences;
//! - `export`: CSV and VTU files of a solution.

pub(crate) mod export;
pub(crate) mod field;
pub(crate) mod replay;
pub(crate) mod solution;
pub mod story;
