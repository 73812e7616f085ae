//! The enriched discretisation (SPEC §3–4, §10): material law, supports and
//! side loads, which nodes are enriched and how (Heaviside, tip, junction),
//! the one DOF map, quadrature of plain, cut and tip elements, element
//! stiffnesses and crack-face points, the stiffness pattern, and the field
//! (displacement, stress) at any point.
//!
//! [`model::Model`] is the immutable part of a scene (mesh, material,
//! supports); [`xfem::Xfem`] is the discretisation of one crack
//! configuration. Uses geometry and the scene types; knows nothing of
//! solvers, contact states or fracture.

pub mod assembly;
pub mod boundary;
pub mod dofs;
pub mod enrichment;
pub mod field;
pub mod loads;
pub mod material;
pub mod model;
pub mod pattern;
pub mod quadrature;
pub mod subdivision;
pub mod xfem;
