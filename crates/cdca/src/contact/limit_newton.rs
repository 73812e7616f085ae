//! The outer loop's friction limits by Newton's method, where the linear
//! solver keeps a factor (SPEC §5).
//!
//! With every point's state, slip direction and closure held, the inner
//! solution is affine in the slipping points' limits `τ_S`: a slipping
//! point `j` adds the force `−w_j s_j τ_j J_T,j` (`s_j` its slip
//! direction), so `∂g_N,i/∂τ_j = M_ij = J_N,iᵀ K⁻¹ (−w_j s_j J_T,j)`. The
//! limits' map `G(τ) = μ|p_N(g(τ))| + min(c_c, |p_N|)` is then affine too
//! (piecewise, in the cohesion's cap), and Newton's step on `τ_S − G_S(τ_S)`,
//!
//! `(I − D_S M_SS) Δτ_S = G_S − τ_S`, `D_i = ∂G_i/∂g_N,i = −k_N (μ + [k_N|g_N| < c_c])`,
//!
//! lands on its fixed point: one solve with those limits ends the outer
//! loop, where the Anderson mix took five to eight. `M` costs forward
//! solves of the few face vectors on the part of the factor they reach
//! ([`LinearSolver::coupling`]), not a solve of the whole system.

use nalgebra::{DMatrix, DVector};

use crate::contact::law::{ContactState, FaceState, gaps, jump_operators};
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{FacePoint, Xfem};
use crate::solvers::forward::SparseColumn;
use crate::solvers::linear::LinearSolver;

/// The limits at the fixed point of the limits' map with the current
/// states (see the module), from the inner solution `u` of the limits
/// `limits` and the plain step `target = G(limits)`; `None` when the
/// solver keeps no factor, no point slips, or the step would take a
/// slipping point's limit below zero (its closure would change: the
/// caller's mix takes over).
pub(crate) fn newton_limits(
    x: &Xfem,
    u: &[f64],
    states: &[FaceState],
    limits: &[f64],
    target: &[f64],
    solver: &dyn LinearSolver,
) -> Option<Vec<f64>> {
    let leading = |i: &usize| x.faces[*i].follows.is_none();
    let slipping: Vec<usize> = (0..states.len())
        .filter(leading)
        .filter(|&i| states[i].state == ContactState::Slip)
        .collect();
    if slipping.is_empty() {
        return None;
    }
    let g_n: Vec<f64> = x.faces.iter().map(|fp| gaps(x, fp, u).0).collect();
    let closed: Vec<usize> = (0..states.len())
        .filter(leading)
        .filter(|&i| g_n[i] < 0.0)
        .collect();
    let rows: Vec<SparseColumn> = closed
        .iter()
        .map(|&i| {
            let fp = &x.faces[i];
            by_dof(x, fp, &jump_operators(fp).0, 1.0)
        })
        .collect();
    let cols: Vec<SparseColumn> = slipping
        .iter()
        .map(|&j| {
            let fp = &x.faces[j];
            by_dof(x, fp, &jump_operators(fp).1, -fp.w * states[j].p_t.signum())
        })
        .collect();
    let m = solver.coupling(&rows, &cols)?;
    // ∂G_i/∂g_N,i at the closed points
    let slope: Vec<f64> = closed
        .iter()
        .map(|&i| {
            let crack = &x.funcs.cracks[x.faces[i].crack];
            let cohesive = crack.kn * -g_n[i] < crack.cohesion;
            -crack.kn * (crack.friction + if cohesive { 1.0 } else { 0.0 })
        })
        .collect();
    let row_of = |i: usize| closed.binary_search(&i).ok();
    let ns = slipping.len();
    let mut a = DMatrix::identity(ns, ns);
    let mut rhs = DVector::zeros(ns);
    for (k, &j) in slipping.iter().enumerate() {
        rhs[k] = target[j] - limits[j];
        if let Some(r) = row_of(j) {
            for l in 0..ns {
                a[(k, l)] -= slope[r] * m[(r, l)];
            }
        }
    }
    let step = a.lu().solve(&rhs)?;
    let moved = &m * &step;
    let mut next = target.to_vec();
    for (r, &i) in closed.iter().enumerate() {
        next[i] = (target[i] + slope[r] * moved[r]).max(0.0);
    }
    for (k, &j) in slipping.iter().enumerate() {
        let limit = limits[j] + step[k];
        if limit < 0.0 || !limit.is_finite() {
            return None;
        }
        next[j] = limit;
    }
    Some(next)
}

/// An element vector of face point `fp` (from [`jump_operators`]) times
/// `scale`, by DOF.
pub fn by_dof(x: &Xfem, fp: &FacePoint, v: &DVector<f64>, scale: f64) -> SparseColumn {
    x.enriched[fp.slot]
        .dofs
        .iter()
        .zip(v.iter())
        .filter(|&(&d, &a)| d != FIXED && a != 0.0)
        .map(|(&d, &a)| (d as usize, scale * a))
        .collect()
}
