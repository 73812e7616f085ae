//! The scene contract (SPEC §10): the JSON scene file as a serde type, and
//! its validation before any work ("parse, don't validate": every value is
//! checked on load and a bad one is named with its field).
//!
//! The bottom of the crate: uses only [`error`](crate::error); everything
//! else reads scenes.

mod file;
mod param;
mod resume;
mod validate;

pub use file::{
    ArcSpec, Boundary, ContactUpdate, CrackSpec, CriterionKind, CriterionSpec, Fix, GrowthControl,
    GrowthSpec, Material, MeshSpec, Ordering, Plane, PointSupport, Sampling, Scene, ShearStrength,
    SideBc, SolverKind, SolverSpec, Specimen,
};
pub use resume::Resume;
pub use validate::MAX_ELEMENTS;
