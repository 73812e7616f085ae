//! Fracture (SPEC §7–9): stress intensity factors and T-stress by the
//! interaction integral (with the crack-face tractions), the fracture
//! criteria (the paper's comprehensive tensile-then-shear criterion, MTS),
//! the evaluation of every free tip after a solve, and the geometry of a
//! growth increment (kink, junction with another crack, exit through the
//! boundary), and the intact rock's own strength away from the cracks.
//!
//! Uses the discretisation's field and the contact face states; the growth
//! loop that drives these lives in [`simulation`](crate::Simulation).

pub mod criterion;
pub mod growth;
pub mod kinks;
pub mod rock;
pub mod sif;
pub mod sites;
pub mod tips;
