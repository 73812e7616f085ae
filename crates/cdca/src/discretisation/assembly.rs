//! Extra element blocks (contact) added to `K = Σ_e K_e`; the operator is
//! applied element by element in [`crate::solvers::element_op`] and
//! assembled sparse in [`crate::solvers::direct`].

use nalgebra::DMatrix;

/// Extra stiffness on one enriched element (contact), in that element's DOF
/// layout.
#[derive(Clone, Debug, PartialEq)]
pub struct ElementBlock {
    /// Index into [`Xfem::enriched`](crate::discretisation::xfem::Xfem::enriched).
    pub slot: usize,
    pub k: DMatrix<f64>,
}
