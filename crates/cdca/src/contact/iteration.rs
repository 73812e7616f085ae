//! The contact iteration (SPEC §5): solve, update every face point's state
//! by the return mapping, repeat until no state changes and the
//! displacement settles. Points that flip state too often are frozen in
//! their latest state and counted, so the loop always ends with an explicit
//! status.

use crate::contact::law::{ContactState, FaceState, contact_system, gaps, update_point};
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::solvers::linear::{LinearInfo, LinearSolver};

/// Settings of the contact iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactParams {
    /// Converged when `‖Δu‖ ≤ tolerance ‖u‖` and no state changed.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// State changes after which a point is frozen (stick–slip cycling).
    pub max_flips: u32,
}

impl ContactParams {
    /// Contact iterations allowed (at least one).
    pub fn max_contact_iterations(&self) -> usize {
        self.max_iterations.max(1)
    }
}

impl Default for ContactParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-8,
            max_iterations: 50,
            max_flips: 4,
        }
    }
}

/// How the contact iteration ended.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactInfo {
    pub iterations: usize,
    /// True only when every test passed: the last linear solve converged,
    /// no state changed, the displacement settled (with slip points), and
    /// no frozen point breaks the contact law at the final displacement.
    pub converged: bool,
    /// Relative displacement change of the last iteration.
    pub residual: f64,
    /// Points frozen for cycling.
    pub cycling: usize,
    /// Frozen points whose kept state is not the one the return mapping
    /// gives at the final displacement (they break the stick/slip rule).
    pub violating: usize,
    /// Linear iterations summed over the contact iterations.
    pub linear_iterations: usize,
    /// The last linear solve.
    pub last: LinearInfo,
}

/// Solves with contact from the committed states of the last converged
/// step; returns the new states. `u` is the starting guess and the result.
pub fn solve_with_contact(
    x: &Xfem,
    f_ext: &[f64],
    committed: &[FaceState],
    u: &mut Vec<f64>,
    solver: &mut dyn LinearSolver,
    params: ContactParams,
) -> Result<(Vec<FaceState>, ContactInfo), SolveError> {
    solve_with_contact_from(
        x,
        f_ext,
        committed,
        committed.to_vec(),
        &mut None,
        u,
        solver,
        params,
    )
}

/// [`solve_with_contact`] with the iteration started from the states
/// `initial` (a guess of which points are open, stuck or slipping) instead
/// of the committed ones; the slip history is still `committed`'s.
///
/// `factored` holds the contact states (open, stick, slip per point) that
/// `solver`'s current matrix was built with on this discretisation, or
/// `None` when it has none or they are unknown; it is kept up to date.
/// The matrix `K + k_N n⊗n (+ k_T t⊗t)` depends on nothing else (not on the
/// load), so a solve whose states match it is not refactorised: the λ_cr
/// search's trials mostly start with the states the last trial ended with
/// (of 231 factorisations in a 40-step growth run, 123 were these).
pub fn solve_with_contact_from(
    x: &Xfem,
    f_ext: &[f64],
    committed: &[FaceState],
    initial: Vec<FaceState>,
    factored: &mut Option<Vec<ContactState>>,
    u: &mut Vec<f64>,
    solver: &mut dyn LinearSolver,
    params: ContactParams,
) -> Result<(Vec<FaceState>, ContactInfo), SolveError> {
    let n = x.faces.len();
    assert_eq!(initial.len(), n, "one initial state per face point");
    let mut states = initial;
    let mut tracker = FlipTracker::new(n);
    let mut info = ContactInfo::default();
    for it in 1..=params.max_contact_iterations() {
        let mut f = f_ext.to_vec();
        let blocks = contact_system(x, &states, committed, &mut f);
        let kinds: Vec<ContactState> = states.iter().map(|s| s.state).collect();
        let matrix_changed = factored.as_ref() != Some(&kinds);
        // unknown until the solve below has succeeded
        *factored = None;
        let before = u.clone();
        let lin = solver.solve(x, &blocks, &f, u, matrix_changed)?;
        *factored = Some(kinds);
        info.linear_iterations += lin.iterations;
        let linear_converged = lin.converged;
        info.last = lin;
        let update = update_states(x, u, committed, &mut states, &mut tracker, params);
        info.iterations = it;
        info.residual = relative_change(u, &before);
        info.violating = update.violating;
        if !info.residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("contact iteration {it}"),
            });
        }
        // an unconverged linear solve ends the iteration: states updated
        // from it mean little, and the status says so
        if !linear_converged {
            break;
        }
        if settled(&update, &states, info.residual, params) {
            info.converged = update.violating == 0;
            break;
        }
    }
    info.cycling = tracker.frozen();
    Ok((states, info))
}

/// Per point: how often it changed state, and whether it is frozen.
#[derive(Clone, Debug, Default)]
pub struct FlipTracker {
    flips: Vec<u32>,
    frozen: Vec<bool>,
}

impl FlipTracker {
    pub fn new(n: usize) -> Self {
        Self {
            flips: vec![0; n],
            frozen: vec![false; n],
        }
    }

    /// Number of frozen (cycling) points.
    pub fn frozen(&self) -> usize {
        self.frozen.iter().filter(|&&f| f).count()
    }
}

/// What one state update found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StateUpdate {
    /// Points whose state changed.
    pub changed: usize,
    /// Frozen points whose kept state differs from the return mapping's.
    pub violating: usize,
}

/// Whether the contact iteration has settled after `update`: no state
/// changed, and (when friction follows the iterate at slip points) the
/// displacement changed by at most the tolerance.
pub fn settled(
    update: &StateUpdate,
    states: &[FaceState],
    relative_change: f64,
    params: ContactParams,
) -> bool {
    update.changed == 0 && (!any_slip(states) || relative_change <= params.tolerance)
}

/// Relative size of a frozen point's departure from the contact law below
/// which it still counts as obeying it: a normal gap of this fraction of
/// the crack's largest jump, or a tangential traction within this fraction
/// of the Coulomb limit.
pub const FROZEN_TOLERANCE: f64 = 1e-2;

/// Updates every face point's state from the displacement `u` by the
/// return mapping.
///
/// Points that changed more than `max_flips` times are frozen in their
/// latest state (keeping them closed or bonded instead was tried: on kinked
/// wing cracks it left pieces bonded under shear tractions 40 times their
/// Coulomb limit, or kept the iteration from settling). A frozen point
/// counts as violating when its
/// kept state is not the return mapping's and the difference is more than
/// [`FROZEN_TOLERANCE`]: a normal gap beyond that fraction of its crack's
/// largest jump, or a trial tangential traction beyond that fraction of the
/// Coulomb limit.
///
/// Slivers at tips ([`FacePoint::follows`](crate::discretisation::xfem::FacePoint::follows))
/// take the state of the point they follow.
pub fn update_states(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    states: &mut [FaceState],
    tracker: &mut FlipTracker,
    params: ContactParams,
) -> StateUpdate {
    let gaps_all: Vec<(f64, f64)> = x.faces.iter().map(|fp| gaps(x, fp, u)).collect();
    let mut jump_scale = vec![0.0_f64; x.funcs.cracks.len()];
    for (fp, &(gn, gt)) in x.faces.iter().zip(&gaps_all) {
        jump_scale[fp.crack] = jump_scale[fp.crack].max(gn.hypot(gt));
    }
    let mut update = StateUpdate::default();
    for i in 0..states.len() {
        let fp = &x.faces[i];
        if fp.follows.is_some() {
            continue;
        }
        let crack = &x.funcs.cracks[fp.crack];
        let (gn, gt) = gaps_all[i];
        let new = update_point(crack, committed[i].slip, gn, gt);
        if tracker.frozen[i] {
            states[i] = forced(states[i].state, crack, committed[i].slip, gn, gt);
            let kept = states[i].state;
            let breaks = match (kept, new.state) {
                (a, b) if a == b => false,
                (ContactState::Open, _) | (_, ContactState::Open) => {
                    gn.abs() > FROZEN_TOLERANCE * jump_scale[fp.crack]
                }
                _ => {
                    let limit = crack.friction * new.p_n.abs() + crack.cohesion;
                    let trial = crack.kt * (gt - committed[i].slip);
                    (trial.abs() - limit).abs() > FROZEN_TOLERANCE * limit.max(trial.abs())
                }
            };
            update.violating += usize::from(breaks);
            continue;
        }
        if new.state != states[i].state {
            update.changed += 1;
            tracker.flips[i] += 1;
            if tracker.flips[i] > params.max_flips {
                tracker.frozen[i] = true;
            }
        }
        states[i] = new;
    }
    // slivers at tips take their neighbour's state and traction
    for (i, fp) in x.faces.iter().enumerate() {
        if let Some(j) = fp.follows {
            let (g_n, g_t) = gaps(x, fp, u);
            states[i] = FaceState {
                g_n,
                g_t,
                ..states[j]
            };
        }
    }
    update
}

/// `‖a − b‖ / ‖a‖` (or `‖a − b‖` when a = 0): the contact iteration's
/// convergence measure.
pub fn relative_change(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt();
    let n: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 0.0 { d / n } else { d }
}

/// Whether any point slips (its friction force then follows the iterate).
pub fn any_slip(states: &[FaceState]) -> bool {
    states.iter().any(|s| s.state == ContactState::Slip)
}

/// The state of a frozen point: its kind is kept, its tractions follow the
/// gaps.
fn forced(
    kind: ContactState,
    crack: &crate::geometry::cracks::Crack,
    slip: f64,
    gn: f64,
    gt: f64,
) -> FaceState {
    let free = update_point(crack, slip, gn, gt);
    match kind {
        ContactState::Open => FaceState {
            state: ContactState::Open,
            p_n: 0.0,
            p_t: 0.0,
            ..free
        },
        ContactState::Stick => FaceState {
            state: ContactState::Stick,
            slip,
            g_n: gn,
            g_t: gt,
            p_n: crack.kn * gn,
            p_t: crack.kt * (gt - slip),
        },
        ContactState::Slip => {
            let p_n = crack.kn * gn.min(0.0);
            let trial = crack.kt * (gt - slip);
            let p_t = (crack.friction * p_n.abs() + crack.cohesion) * trial.signum();
            FaceState {
                state: ContactState::Slip,
                slip: gt - p_t / crack.kt,
                g_n: gn,
                g_t: gt,
                p_n,
                p_t,
            }
        }
    }
}
