//! Geometry, step 0 of the method (SPEC §1–2): plane geometry on points,
//! the structured Q4 mesh, and the cracks as explicit polylines with their
//! level sets `φ` (signed distance) and `ψ` (along each tip) and the kind of
//! each tip (free, on the boundary, at a junction).
//!
//! Uses only the scene types; knows nothing of DOFs or solvers.

pub mod cracks;
pub mod mesh;
pub mod plane;
