//! Displacement, displacement gradient and stress at any point, enrichment
//! included.

use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{REGULAR, Xfem};
use crate::geometry::plane::P2;

/// The solution field of one discretisation.
pub struct Field<'a> {
    pub xfem: &'a Xfem,
    /// Free-DOF displacement vector.
    pub u: &'a [f64],
}

/// Displacement and its gradient `[[∂ux/∂x, ∂ux/∂y], [∂uy/∂x, ∂uy/∂y]]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointValue {
    pub u: P2,
    pub grad: [[f64; 2]; 2],
}

/// The shape functions (enrichment included) of one discretisation at a
/// list of points, with their DOFs: all a field's value at those points
/// needs besides the displacement, so that a field read at the same points
/// after every solve on one discretisation evaluates them once
/// ([`Field::at_point`]).
#[derive(Clone, Debug, Default)]
pub struct PointBasis {
    vals: Vec<f64>,
    grads: Vec<P2>,
    dofs: Vec<u32>,
    /// Start of each point's functions in `vals`, and the end of the last.
    starts: Vec<usize>,
    /// One point's functions, as [`Xfem::eval_element`] gives them.
    scratch: (Vec<f64>, Vec<P2>, Vec<u32>),
}

impl PointBasis {
    /// Room for `points` more points of element `e` of `xfem`.
    pub fn reserve(&mut self, xfem: &Xfem, e: usize, points: usize) {
        let slot = xfem.slot[e];
        let functions = if slot == REGULAR {
            4
        } else {
            xfem.enriched[slot as usize].dofs.len() / 2
        };
        self.vals.reserve(points * functions);
        self.grads.reserve(points * functions);
        self.dofs.reserve(2 * points * functions);
        self.starts.reserve(points + 1);
    }

    /// Adds the point `x` of element `e` of `xfem`.
    pub fn push(&mut self, xfem: &Xfem, e: usize, x: P2) {
        let (vals, grads, dofs) = &mut self.scratch;
        xfem.eval_element(e, x, vals, grads, dofs);
        if self.starts.is_empty() {
            self.starts.push(0);
        }
        self.vals.extend_from_slice(vals);
        self.grads.extend_from_slice(grads);
        self.dofs.extend_from_slice(dofs);
        self.starts.push(self.vals.len());
    }

    /// Drops the room left over and the scratch (once every point is in).
    pub fn shrink_to_fit(&mut self) {
        self.vals.shrink_to_fit();
        self.grads.shrink_to_fit();
        self.dofs.shrink_to_fit();
        self.starts.shrink_to_fit();
        self.scratch = Default::default();
    }
}

impl Field<'_> {
    /// Value in element `e` at `x` (x may lie on the element's boundary).
    pub fn in_element(&self, e: usize, x: P2) -> PointValue {
        let (mut vals, mut grads, mut dofs) = (Vec::new(), Vec::new(), Vec::new());
        self.xfem
            .eval_element(e, x, &mut vals, &mut grads, &mut dofs);
        self.combine(&vals, &grads, &dofs)
    }

    /// Value at point `i` of `basis` (made on this field's discretisation):
    /// the same as [`in_element`](Self::in_element) there.
    pub fn at_point(&self, basis: &PointBasis, i: usize) -> PointValue {
        let (a, b) = (basis.starts[i], basis.starts[i + 1]);
        self.combine(
            &basis.vals[a..b],
            &basis.grads[a..b],
            &basis.dofs[2 * a..2 * b],
        )
    }

    /// `Σ N_s u_s` and its gradient over scalar functions `vals` (gradients
    /// `grads`) with two DOFs each, `dofs`.
    fn combine(&self, vals: &[f64], grads: &[P2], dofs: &[u32]) -> PointValue {
        let mut out = PointValue::default();
        for (s, (&v, g)) in vals.iter().zip(grads).enumerate() {
            for c in 0..2 {
                let d = dofs[2 * s + c];
                if d == FIXED {
                    continue;
                }
                let a = self.u[d as usize];
                out.u[c] += v * a;
                out.grad[c][0] += g.x * a;
                out.grad[c][1] += g.y * a;
            }
        }
        out
    }

    /// Value at `x`, or `None` outside the specimen.
    pub fn at(&self, x: P2) -> Option<PointValue> {
        self.xfem.mesh.element_at(x).map(|e| self.in_element(e, x))
    }

    /// Stress `[σxx, σyy, τxy]` from a displacement gradient, Pa.
    pub fn stress(&self, v: &PointValue) -> [f64; 3] {
        let eps = nalgebra::Vector3::new(v.grad[0][0], v.grad[1][1], v.grad[0][1] + v.grad[1][0]);
        let s = self.xfem.elastic.d * eps;
        [s[0], s[1], s[2]]
    }

    /// Stress at `x`, or `None` outside the specimen.
    pub fn stress_at(&self, x: P2) -> Option<[f64; 3]> {
        self.at(x).map(|v| self.stress(&v))
    }

    /// Stress at `x` averaged over every element whose closed box holds it:
    /// on an element edge or corner the (discontinuous) stresses of the
    /// elements meeting there are averaged, so that sampling does not depend
    /// on how a tie is broken.
    pub fn stress_averaged_at(&self, x: P2) -> Option<[f64; 3]> {
        let m = &self.xfem.mesh;
        self.xfem.mesh.element_at(x)?;
        let tol = 1e-9 * m.h();
        let mut sum = [0.0; 3];
        let mut n = 0.0;
        for e in m.elements_in_box(x, x, tol) {
            let (lo, hi) = m.element_box(e);
            if x.x < lo.x - tol || x.x > hi.x + tol || x.y < lo.y - tol || x.y > hi.y + tol {
                continue;
            }
            let s = self.stress(&self.in_element(e, x));
            for k in 0..3 {
                sum[k] += s[k];
            }
            n += 1.0;
        }
        (n > 0.0).then(|| sum.map(|v| v / n))
    }
}
