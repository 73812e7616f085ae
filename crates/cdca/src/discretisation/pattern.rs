//! The sparsity pattern (lower triangle) of one discretisation's stiffness
//! and its symbolic Cholesky factorisation (AMD ordering, elimination
//! tree), computed once and reused for every numeric factorisation on that
//! discretisation: contact blocks live on enriched elements, whose DOFs are
//! already coupled, so they never change the pattern.
//!
//! The discretisation owns it ([`Xfem::pattern`](crate::discretisation::xfem::Xfem::pattern));
//! the direct solver fills it ([`Factor`](crate::solvers::direct::Factor)).

use faer::Side;
use faer::sparse::linalg::solvers::SymbolicLlt;
use faer::sparse::{SparseColMat, Triplet};

use crate::discretisation::dofs::FIXED;
use crate::error::SolveError;

/// Pattern and symbolic factorisation of a stiffness matrix.
#[derive(Clone, Debug)]
pub struct Pattern {
    mat: SparseColMat<usize, f64>,
    symbolic: SymbolicLlt<usize>,
}

impl Pattern {
    /// The pattern of `n` free DOFs coupled element by element:
    /// `elements` calls its argument once with each element's DOF list
    /// ([`FIXED`] entries are skipped).
    pub fn new(
        n: usize,
        capacity: usize,
        elements: impl FnOnce(&mut dyn FnMut(&[u32])),
    ) -> Result<Self, SolveError> {
        let mut trip: Vec<Triplet<usize, usize, f64>> = Vec::with_capacity(capacity);
        elements(&mut |dofs: &[u32]| {
            for &dj in dofs.iter().filter(|&&d| d != FIXED) {
                for &di in dofs.iter().filter(|&&d| d != FIXED && d >= dj) {
                    trip.push(Triplet::new(di as usize, dj as usize, 0.0));
                }
            }
        });
        let not_pd = |detail: String| SolveError::NotPositiveDefinite { dofs: n, detail };
        let mat = SparseColMat::try_new_from_triplets(n, n, &trip)
            .map_err(|e| not_pd(format!("{e:?}")))?;
        let symbolic = SymbolicLlt::try_new(mat.symbolic(), Side::Lower)
            .map_err(|e| not_pd(format!("{e:?}")))?;
        Ok(Self { mat, symbolic })
    }

    /// The lower-triangle matrix with every stored value 0.
    pub fn matrix(&self) -> &SparseColMat<usize, f64> {
        &self.mat
    }

    /// The symbolic Cholesky factorisation of the pattern.
    pub fn symbolic(&self) -> &SymbolicLlt<usize> {
        &self.symbolic
    }
}
