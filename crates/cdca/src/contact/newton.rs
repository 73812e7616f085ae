//! The contact iteration's semismooth Newton step, where the linear solver
//! keeps a factor (the direct solver; SPEC §5 leaves the algorithm free).
//!
//! With every point's state held (open, stick, slip and its direction, and
//! whether the cohesion's cap `min(c_c, |p_N|)` is reached), the penalty
//! law is linear in the displacement: at a slipping point
//! `p_T = s (a + b g_N)`, with `a = c_c`, `b = −μ k_N` where
//! `k_N |g_N| ≥ c_c` and `a = 0`, `b = −(μ + 1) k_N` below. Its friction
//! force `−w p_T J_T` then puts the non-symmetric term
//! `U Vᵀ = Σ_slip w s b J_T J_Nᵀ` into the tangent, `(A + U Vᵀ) u* = f₀`,
//! where `A` (the bulk plus `k_N n⊗n` at closed and `k_T t⊗t` at stuck
//! points) is the symmetric matrix the solver factorised and `f₀` holds
//! the load and the constant friction forces `−w s a J_T`.
//!
//! The contact system solved with the slip points' tractions from the
//! iterate, `g = A⁻¹ (f₀ − U g_N⁰)` (`g_N⁰` the slip points' normal gaps
//! there), gives the Newton solution through the slip points' normal gaps
//! alone: with `e = Vᵀ u* − g_N⁰`,
//!
//! `(I + Vᵀ A⁻¹ U) e = Vᵀ g − g_N⁰`,   `u* = g − A⁻¹ U e`,
//!
//! a system of one unknown per slipping point, solved by GMRES with one
//! solve through the factor per iteration, on the part of the factor the
//! faces reach ([`LinearSolver::solve_on`]), and one whole solve for
//! `A⁻¹ U e`. Nothing dense of the slip points' size is formed: a step
//! costs about the same whatever their number (10–25 Krylov iterations
//! on the held-out pairs, to [`KRYLOV_TOLERANCE`]; to
//! [`LOOSE_KRYLOV_TOLERANCE`], 8–12, while many states still change). A
//! loose step whose law holds is taken on to the tight tolerance from its
//! own Krylov space (`contact::krylov`), not solved anew.
//!
//! The iteration has converged when the law holds at the solution: the
//! force by which the Coulomb law there differs from the linearised one
//! (`law_force`, the whole residual of the equilibrium) is within the
//! contact tolerance of the load. Where it is not, the next iteration
//! builds the system of the states the solution maps to (a primal–dual
//! active-set step: Hintermüller, Ito & Kunisch 2002; Hüeber, Stadler &
//! Wohlmuth 2008).

use crate::contact::krylov::{Gmres, Solved};
use crate::contact::law::{ContactState, FaceState, jump_operators};
use crate::contact::limit_newton::by_dof;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::solvers::forward::SparseColumn;
use crate::solvers::linear::LinearSolver;

/// Relative residual GMRES solves the slip points' system to where the
/// step may end the iteration: far below the contact tolerance (1e-8),
/// above round-off.
pub const KRYLOV_TOLERANCE: f64 = 1e-11;

/// Relative residual of a step taken while many states still change, and
/// of the first step from the states a contact solve starts with (an
/// inexact Newton step: the next iteration solves its own system anew, so
/// only the states this step maps to depend on it; a step whose law holds
/// goes on to [`KRYLOV_TOLERANCE`] from the same Krylov space, so a loose
/// start costs nothing where the start was right).
pub const LOOSE_KRYLOV_TOLERANCE: f64 = 1e-4;

/// The Newton solution on the faces and how its slip system was solved.
pub(crate) struct NewtonStep {
    /// `u*` on the faces' DOFs (the others as `g` had them).
    pub u: Vec<f64>,
    /// The forces to add to the system's right-hand side for `u*`
    /// everywhere (`−U e`, and the guessed tractions put right), by DOF.
    pub correction: SparseColumn,
    /// Solves through the factor it took (GMRES iterations; slip points
    /// where the system is formed).
    pub solves: usize,
    /// The slip system's final relative residual (0 without slip points).
    pub residual: f64,
}

/// The force by which the law at `u` differs from the law linearised at
/// `states` (the system `u` solves): `Σ w ([[p]] − [[p]]_S)·J`, with the
/// face tractions the Coulomb law gives at `u` (`mapped`), by free DOF.
/// Where `u` solves that system, this is the whole residual of the
/// equilibrium `K u + F_contact(u) − f`. Zero where every point keeps its
/// state; a point whose state changes with its traction unchanged (a slip
/// direction flipping at a friction limit of nought, a point opening at a
/// gap of nought) adds nothing.
pub(crate) fn law_force(
    x: &Xfem,
    states: &[FaceState],
    mapped: &[FaceState],
    committed: &[FaceState],
) -> Vec<f64> {
    let mut r = vec![0.0; x.n_free()];
    for (i, fp) in x.faces.iter().enumerate() {
        if fp.follows.is_some() {
            continue;
        }
        let (st, now) = (&states[i], &mapped[i]);
        let crack = &x.funcs.cracks[fp.crack];
        // the linearised law's traction at `now`'s gaps
        let (p_n, p_t) = match st.state {
            ContactState::Open => (0.0, 0.0),
            ContactState::Stick => (crack.kn * now.g_n, crack.kt * (now.g_t - committed[i].slip)),
            ContactState::Slip => {
                let (a, b) = slip_line(x, i, st.g_n);
                (crack.kn * now.g_n, st.p_t.signum() * (a + b * now.g_n))
            }
        };
        let (dn, dt) = (now.p_n - p_n, now.p_t - p_t);
        if dn == 0.0 && dt == 0.0 {
            continue;
        }
        let (jn, jt) = jump_operators(fp);
        for (a, &d) in x.enriched[fp.slot].dofs.iter().enumerate() {
            if d != FIXED {
                r[d as usize] += fp.w * (dn * jn[a] + dt * jt[a]);
            }
        }
    }
    r
}

/// The Euclidean norm.
pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// The friction limit of face point `i` as a line in its normal gap,
/// `τ_y = a + b g_N`, on the branch its gap `g_n` is on
/// ([`coulomb_limit`](crate::contact::law::coulomb_limit)): `a = c_c`,
/// `b = −μ k_N` where `k_N |g_N| ≥ c_c`, `a = 0`, `b = −(μ + 1) k_N` on the
/// cohesion's rising branch, and nought where the point is open.
fn slip_line(x: &Xfem, i: usize, g_n: f64) -> (f64, f64) {
    let crack = &x.funcs.cracks[x.faces[i].crack];
    if cohesive(x, i, g_n) {
        (0.0, -(crack.friction + 1.0) * crack.kn)
    } else if g_n < 0.0 {
        (crack.cohesion, -crack.friction * crack.kn)
    } else {
        (0.0, 0.0)
    }
}

/// Whether a closed point's friction limit is on the cohesion's rising
/// branch (`k_N |g_N| < c_c`: limit `(μ + 1) k_N |g_N|`).
pub(crate) fn cohesive(x: &Xfem, i: usize, g_n: f64) -> bool {
    let crack = &x.funcs.cracks[x.faces[i].crack];
    g_n < 0.0 && crack.kn * -g_n < crack.cohesion
}

/// The Newton solution `u*` of the law linearised at `states` (those the
/// solver's current matrix and the system whose solution is `g` were built
/// with), on the DOFs `faces` (those of every element holding a face
/// point: all that the states read), from `g` there; `None` when the
/// solver keeps no factor or GMRES does not reach `tolerance` in as many
/// iterations as there are slip points (it must, in exact arithmetic).
/// `krylov` holds the slip system's GMRES solve (`None`: none started):
/// a second call with the same states and `g` and a tighter tolerance
/// goes on from the first one's iterations.
pub(crate) fn newton_step(
    x: &Xfem,
    states: &[FaceState],
    g: &[f64],
    faces: &[usize],
    solver: &dyn LinearSolver,
    tolerance: f64,
    krylov: &mut Option<Gmres>,
) -> Option<NewtonStep> {
    // per slipping point: U's column, V's column and g_N⁰
    let mut u_cols: Vec<SparseColumn> = Vec::new();
    let mut v_cols: Vec<SparseColumn> = Vec::new();
    let mut g0: Vec<f64> = Vec::new();
    // forces the system of `g` carried that the law's constant part does
    // not (a guessed state whose traction is not its limit): put right by
    // one more solve
    let mut mismatch: SparseColumn = Vec::new();
    for (i, (fp, st)) in x.faces.iter().zip(states).enumerate() {
        if fp.follows.is_some() || st.state != ContactState::Slip {
            continue;
        }
        let s = st.p_t.signum();
        let (a, b) = slip_line(x, i, st.g_n);
        let (jn, jt) = jump_operators(fp);
        if b == 0.0 || st.p_t == 0.0 {
            // p_T = s a does not move with the gaps
            let excess = st.p_t - s * a;
            if excess != 0.0 {
                mismatch.extend(by_dof(x, fp, &jt, fp.w * excess));
            }
            continue;
        }
        u_cols.push(by_dof(x, fp, &jt, fp.w * s * b));
        v_cols.push(by_dof(x, fp, &jn, 1.0));
        // the normal gap at which the law's traction is the system's
        g0.push((st.p_t - s * a) / (s * b));
    }
    let mut base = g.to_vec();
    let mut solves = 0;
    if !mismatch.is_empty() {
        let fix = solver.solve_on(&mismatch, faces)?;
        solves += 1;
        for &d in faces {
            base[d] += fix[d];
        }
    }
    if u_cols.is_empty() {
        return Some(NewtonStep {
            u: base,
            correction: mismatch,
            solves,
            residual: 0.0,
        });
    }
    let m = u_cols.len();
    let dot = |col: &SparseColumn, v: &[f64]| col.iter().map(|&(d, a)| a * v[d]).sum::<f64>();
    let rhs: Vec<f64> = v_cols
        .iter()
        .zip(&g0)
        .map(|(c, g0)| dot(c, &base) - g0)
        .collect();
    // U v as a sparse vector by DOF
    let spread = |v: &[f64]| -> SparseColumn {
        u_cols
            .iter()
            .zip(v)
            .flat_map(|(col, &c)| col.iter().map(move |&(d, a)| (d, a * c)))
            .collect()
    };
    let mut dofs: Vec<usize> = v_cols.iter().flatten().map(|&(d, _)| d).collect();
    dofs.sort_unstable();
    dofs.dedup();
    // the operator v ↦ v + Vᵀ A⁻¹ U v, on the faces' part of the factor
    let mut apply = |v: &[f64]| -> Option<Vec<f64>> {
        let w = solver.solve_on(&spread(v), &dofs)?;
        Some(
            v_cols
                .iter()
                .zip(v)
                .map(|(col, &c)| c + dot(col, &w))
                .collect(),
        )
    };
    let Solved {
        e,
        residual,
        iterations,
    } = if m <= DENSE_SLIP {
        dense_solve(solver, &v_cols, &u_cols, &rhs)?
    } else {
        krylov.get_or_insert_with(|| Gmres::new(&rhs)).solve(
            &mut apply,
            m.min(MAX_KRYLOV),
            tolerance,
        )?
    };
    // u* = g − A⁻¹ U e
    let pull: SparseColumn = spread(&e).into_iter().map(|(d, a)| (d, -a)).collect();
    let moved = solver.solve_on(&pull, faces)?;
    solves += iterations + 1;
    for &d in faces {
        base[d] += moved[d];
    }
    mismatch.extend(pull);
    Some(NewtonStep {
        u: base,
        correction: mismatch,
        solves,
        residual,
    })
}

/// Slip points up to which the slip system `I + Vᵀ A⁻¹ U` is formed and
/// factorised densely instead of solved by GMRES: its `2m` forward solves
/// on the part of the factor the faces reach cost less than GMRES's 10–25
/// solves there (measured on the bundled pairs, 5–40 slip points).
pub const DENSE_SLIP: usize = 48;

/// The slip system `(I + Vᵀ A⁻¹ U) e = rhs` formed ([`LinearSolver::coupling`])
/// and solved by LU: `e`, its relative residual, and the solves it took
/// (counted as one per forward-solved column pair).
fn dense_solve(
    solver: &dyn LinearSolver,
    v_cols: &[SparseColumn],
    u_cols: &[SparseColumn],
    rhs: &[f64],
) -> Option<Solved> {
    let m = v_cols.len();
    let coupling = solver.coupling(v_cols, u_cols)?;
    let a = nalgebra::DMatrix::identity(m, m) + coupling;
    let b = nalgebra::DVector::from_column_slice(rhs);
    let e = a.clone().lu().solve(&b)?;
    let residual = norm((&a * &e - &b).as_slice()) / norm(rhs).max(f64::MIN_POSITIVE);
    let e: Vec<f64> = e.iter().copied().collect();
    e.iter().all(|v| v.is_finite()).then_some(Solved {
        e,
        residual,
        iterations: m,
    })
}

/// GMRES iterations at most per Newton step.
pub const MAX_KRYLOV: usize = 300;
