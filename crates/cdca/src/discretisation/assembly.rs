//! The operator `K = Σ_e K_e (+ contact)`: contact blocks and the product
//! with a vector, matrix-free (the sparse assembly is in [`crate::solvers::direct`]).

use nalgebra::DMatrix;

use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{NOT_INTEGRATED, REGULAR, Xfem};

/// Extra stiffness on one enriched element (contact), in that element's DOF
/// layout.
#[derive(Clone, Debug, PartialEq)]
pub struct ElementBlock {
    /// Index into [`Xfem::enriched`].
    pub slot: usize,
    pub k: DMatrix<f64>,
}

/// `y = K u` element by element (no global matrix).
pub fn apply(x: &Xfem, extra: &[ElementBlock], u: &[f64], y: &mut [f64]) {
    assert!(x.is_integrated(), "{NOT_INTEGRATED}");
    y.fill(0.0);
    let get = |d: u32| if d == FIXED { 0.0 } else { u[d as usize] };
    for e in 0..x.mesh.element_count() {
        if x.slot[e] != REGULAR {
            continue;
        }
        let d = x.regular_dofs(e);
        let ue: [f64; 8] = std::array::from_fn(|i| get(d[i]));
        for i in 0..8 {
            if d[i] != FIXED {
                y[d[i] as usize] += (0..8).map(|j| x.k0[(i, j)] * ue[j]).sum::<f64>();
            }
        }
    }
    let mut add = |dofs: &[u32], k: &DMatrix<f64>| {
        let ue: Vec<f64> = dofs.iter().map(|&d| get(d)).collect();
        for (i, &di) in dofs.iter().enumerate() {
            if di != FIXED {
                y[di as usize] += (0..dofs.len()).map(|j| k[(i, j)] * ue[j]).sum::<f64>();
            }
        }
    };
    for el in &x.enriched {
        add(&el.dofs, &el.k);
    }
    for b in extra {
        add(&x.enriched[b.slot].dofs, &b.k);
    }
}
