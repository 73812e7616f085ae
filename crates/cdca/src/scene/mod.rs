//! The scene contract (SPEC §10): the JSON scene file as a serde type
//! ([`SceneFile`], any values) and the valid scene ([`Scene`]), into which a
//! file converts once, through `TryFrom`, checking every value and naming a
//! bad one with its field ("parse, don't validate": nothing downstream checks
//! a scene again).
//!
//! The bottom of the crate: uses only [`error`](crate::error); everything
//! else reads scenes.

mod criterion;
mod file;
mod param;
mod resume;
mod valid;
mod validate;

pub use criterion::{Criterion, CriterionFields};
pub use file::{
    ArcSpec, Boundary, ContactUpdate, CrackSpec, CriterionKind, CriterionSpec, DIRECT_TOLERANCE,
    Fix, GrowthControl, GrowthSpec, IntactRock, Material, MeshSpec, Ordering, Plane, PointSupport,
    Sampling, SceneFile, ShearStrength, SideBc, SolverKind, SolverSpec, Specimen,
};
pub use param::json_number;
pub use resume::{Lineage, Part, Resume, RockStarts};
pub use valid::Scene;
pub(crate) use validate::fmt_point;
pub use validate::{MAX_ELEMENTS, MIN_END_SEGMENT};
