//! Studies of many scenes (issue 55): a study file holds a base scene and
//! axes, each point of the study is the base scene with one value of every
//! axis, and each point's growth run becomes one CSV row. The CLI
//! (`cdca study`) and the workbench's Study tab read the same file through
//! this module; they do the files, the threads and the drawing.
//!
//! - [`file`](mod@file): the study file's serde types (unknown fields are errors);
//! - [`axis`]: an axis's values (listed, a range, a seeded random sample);
//! - [`flaws`]: the flaws generator (one flaw, or a pair in one of five
//!   layouts, centred as the held-out pairs were);
//! - [`random`]: the seeded generator (SplitMix64) that fixes random points
//!   before any run;
//! - [`plan`]: [`Study`], the checked file and its points (grid, zip or a
//!   joint random sample), and each point's scene;
//! - [`row`]: one point's growth report as a CSV row, and the table read
//!   back;
//! - [`summary`]: a finished table summed up per layout (the held-out
//!   pairs' table in `docs/fracture-model.md`).
//!
//! The format is documented in `docs/studies.md`.

pub mod axis;
pub mod error;
pub mod file;
pub mod flaws;
pub mod plan;
pub mod random;
pub mod row;
pub mod summary;

pub use axis::{Axis, Input, Point};
pub use error::StudyError;
pub use file::{Combine, RunKind, StudyFile};
pub use flaws::{Flaws, Layout};
pub use plan::Study;
pub use row::{Row, Table};
