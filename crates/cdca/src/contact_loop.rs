//! The contact iteration (SPEC §5): solve, update every face point's state
//! by the return mapping, repeat until no state changes and the
//! displacement settles. Points that flip state too often are frozen in
//! their latest state and counted, so the loop always ends with an explicit
//! status.

use crate::contact::{FaceState, contact_system, gaps, update_point};
use crate::error::SolveError;
use crate::simulation::ContactState;
use crate::solver::{LinearInfo, LinearSolver};
use crate::xfem::Xfem;

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
    pub converged: bool,
    /// Relative displacement change of the last iteration.
    pub residual: f64,
    /// Points frozen for cycling.
    pub cycling: usize,
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
    let n = x.faces.len();
    let mut states: Vec<FaceState> = committed.to_vec();
    let mut tracker = FlipTracker::new(n);
    let mut info = ContactInfo::default();
    let mut kinds: Vec<ContactState> = Vec::new();
    for it in 1..=params.max_contact_iterations() {
        let mut f = f_ext.to_vec();
        let blocks = contact_system(x, &states, committed, &mut f);
        let new_kinds: Vec<ContactState> = states.iter().map(|s| s.state).collect();
        let matrix_changed = it == 1 || new_kinds != kinds;
        kinds = new_kinds;
        let before = u.clone();
        let lin = solver.solve(x, &blocks, &f, u, matrix_changed)?;
        info.linear_iterations += lin.iterations;
        info.last = lin;
        let changed = update_states(x, u, committed, &mut states, &mut tracker, params);
        info.iterations = it;
        info.residual = relative_change(u, &before);
        if !info.residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("contact iteration {it}"),
            });
        }
        // with no state change and no slip point the system solved was the
        // final one: converged; slip friction needs the displacement to settle
        if changed == 0 && (!any_slip(&states) || info.residual <= params.tolerance) {
            info.converged = true;
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

/// Updates every face point's state from the displacement `u` by the
/// return mapping; returns how many points changed state. Points that
/// changed more than `max_flips` times are frozen in their latest state.
pub fn update_states(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    states: &mut [FaceState],
    tracker: &mut FlipTracker,
    params: ContactParams,
) -> usize {
    let mut changed = 0;
    for i in 0..states.len() {
        let fp = &x.faces[i];
        let crack = &x.funcs.cracks[fp.crack];
        let (gn, gt) = gaps(x, fp, u);
        if tracker.frozen[i] {
            states[i] = forced(states[i].state, crack, committed[i].slip, gn, gt);
            continue;
        }
        let new = update_point(crack, committed[i].slip, gn, gt);
        if new.state != states[i].state {
            changed += 1;
            tracker.flips[i] += 1;
            if tracker.flips[i] > params.max_flips {
                tracker.frozen[i] = true;
            }
        }
        states[i] = new;
    }
    changed
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
    crack: &crate::cracks::Crack,
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
