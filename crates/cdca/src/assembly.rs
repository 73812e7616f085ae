//! Global sparse assembly of the operator `K = Σ_e K_e (+ contact)` and its
//! product with a vector, matrix-free.

use faer::sparse::{SparseColMat, Triplet};
use nalgebra::DMatrix;

use crate::dofs::FIXED;
use crate::xfem::{REGULAR, Xfem};

/// Extra stiffness on one enriched element (contact), in that element's DOF
/// layout.
#[derive(Clone, Debug)]
pub struct ElementBlock {
    /// Index into [`Xfem::enriched`].
    pub slot: usize,
    pub k: DMatrix<f64>,
}

/// Assembles the lower triangle of the global stiffness (free DOFs).
pub fn assemble_lower(
    x: &Xfem,
    extra: &[ElementBlock],
) -> Result<SparseColMat<usize, f64>, String> {
    let n = x.n_free();
    let mut trip: Vec<Triplet<usize, usize, f64>> = Vec::with_capacity(x.mesh.element_count() * 36);
    let mut push = |dofs: &[u32], k: &dyn Fn(usize, usize) -> f64| {
        for (j, &dj) in dofs.iter().enumerate() {
            if dj == FIXED {
                continue;
            }
            for (i, &di) in dofs.iter().enumerate() {
                if di == FIXED || di < dj {
                    continue;
                }
                let v = k(i, j);
                if v != 0.0 {
                    trip.push(Triplet::new(di as usize, dj as usize, v));
                }
            }
        }
    };
    for e in 0..x.mesh.element_count() {
        if x.slot[e] == REGULAR {
            let d = x.regular_dofs(e);
            push(&d, &|i, j| x.k0[(i, j)]);
        }
    }
    for el in &x.enriched {
        push(&el.dofs, &|i, j| el.k[(i, j)]);
    }
    for b in extra {
        let el = &x.enriched[b.slot];
        push(&el.dofs, &|i, j| b.k[(i, j)]);
    }
    SparseColMat::try_new_from_triplets(n, n, &trip).map_err(|e| format!("{e:?}"))
}

/// `y = K u` element by element (no global matrix).
pub fn apply(x: &Xfem, extra: &[ElementBlock], u: &[f64], y: &mut [f64]) {
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
