//! The contact iteration's settings, outcome and bookkeeping, shared by
//! the outer loop ([`ContactSolve`](crate::contact::iteration::ContactSolve))
//! and the in-sweep rule ([`InSweep`](crate::contact::in_sweep::InSweep)):
//! [`ContactParams`], [`ContactInfo`], where an iteration stands
//! ([`Reached`]), the stick–slip cycling guard ([`FlipTracker`]) and the
//! convergence measure ([`relative_change`]).

use crate::contact::law::FaceState;
use crate::scene::SolverSpec;
use crate::solvers::linear::LinearInfo;
use crate::solvers::relaxation::ResidualSample;

/// Settings of the contact iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactParams {
    /// Converged when `‖Δu‖ ≤ tolerance ‖u‖` and no state changed.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// State changes after which a point counts as cycling (frozen by the
    /// in-sweep rule; damped, and reported if the iteration does not
    /// settle, by [`ContactSolve`](crate::contact::iteration::ContactSolve)).
    pub max_flips: u32,
    /// Semismooth Newton steps where the solver keeps a factor
    /// ([`newton`](crate::contact::newton)); `false` keeps the damped
    /// fixed point for every solver (the steps' reference in tests).
    pub newton: bool,
}

impl ContactParams {
    /// Contact iterations allowed (at least one).
    pub fn max_contact_iterations(&self) -> usize {
        self.max_iterations.max(1)
    }
}

impl Default for ContactParams {
    /// The scene file's defaults (`solver.contact_tolerance`,
    /// `solver.max_contact_iterations`), four flips, Newton steps.
    fn default() -> Self {
        let s = SolverSpec::default();
        Self {
            tolerance: s.contact_tolerance,
            max_iterations: s.max_contact_iterations,
            max_flips: 4,
            newton: true,
        }
    }
}

/// How the contact iteration ended.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactInfo {
    pub iterations: usize,
    /// True only when every test passed: the last linear solve converged,
    /// no state changed, the displacement settled (with slip points), and
    /// no frozen point breaks the contact law at the final displacement
    /// ([`ContactSolve`](crate::contact::iteration::ContactSolve) freezes none: every point is in its Coulomb state).
    pub converged: bool,
    /// Relative displacement change of the last iteration ([`ContactSolve`](crate::contact::iteration::ContactSolve)
    /// at an inner solution: the smaller of the change since the last
    /// inner solution and the relative change of the slip points' friction
    /// limits).
    pub residual: f64,
    /// Ended at `max_iterations` without settling (states changing, or
    /// with slip the displacement still moving).
    pub capped: bool,
    /// Points frozen for cycling (the in-sweep rule), or, when
    /// [`ContactSolve`](crate::contact::iteration::ContactSolve) ends capped, those that changed state more than
    /// `max_flips` times.
    pub cycling: usize,
    /// Frozen points whose kept state is not the one the return mapping
    /// gives at the final displacement (they break the stick/slip rule).
    pub violating: usize,
    /// [`ContactSolve`](crate::contact::iteration::ContactSolve): points the last iteration left unsettled, those
    /// whose state it changed or, when none changed, those not in their
    /// Coulomb state at the solution (0 once converged).
    pub unsettled: usize,
    /// Linear iterations summed over the contact iterations.
    pub linear_iterations: usize,
    /// [`ContactSolve`](crate::contact::iteration::ContactSolve): contact
    /// iterations taken on a solve of the faces' rows alone (the fixed
    /// point's that changed a state, every Newton step's but those where no
    /// point slips).
    pub face_solves: usize,
    /// The last linear solve.
    pub last: LinearInfo,
    /// The Newton steps (a solver with a factor) cycled or did not
    /// converge within [`MAX_NEWTON_STEPS`](crate::contact::iteration::MAX_NEWTON_STEPS),
    /// and the damped fixed point finished the solve.
    pub newton_fallback: bool,
}

/// Where a contact iteration stands, the outer loop's ([`ContactSolve`](crate::contact::iteration::ContactSolve))
/// or the in-sweep rule's
/// ([`InSweep`](crate::contact::in_sweep::InSweep)): the contact states,
/// how it went, whether it ended, the residual samples so far, and the
/// flip counts of the stick–slip cycling guard.
#[derive(Clone, Debug, Default)]
pub struct Reached {
    /// The states as they are now (the result once finished).
    pub states: Vec<FaceState>,
    /// How it went so far (how it ended, once finished).
    pub info: ContactInfo,
    pub finished: bool,
    /// Relative residual samples, iterations and times from the start.
    pub history: Vec<ResidualSample>,
    /// How often each point changed state, and which are frozen.
    pub tracker: FlipTracker,
}

impl Reached {
    /// The start: the states `initial`, nothing done.
    pub fn new(initial: Vec<FaceState>) -> Self {
        Self {
            tracker: FlipTracker::new(initial.len()),
            states: initial,
            ..Self::default()
        }
    }

    /// Whether the iteration has ended; `committed` must hold one state per
    /// face point (the caller's slip history of this discretisation).
    pub(crate) fn ended(&self, committed: &[FaceState]) -> bool {
        assert_eq!(
            self.states.len(),
            committed.len(),
            "one state per face point"
        );
        self.finished
    }
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

    /// Whether point `i` is frozen.
    pub fn is_frozen(&self, i: usize) -> bool {
        self.frozen[i]
    }

    /// Counts a state change of point `i`, freezing it once it has changed
    /// more than `max_flips` times.
    pub fn flip(&mut self, i: usize, max_flips: u32) {
        self.flips[i] += 1;
        if self.flips[i] > max_flips {
            self.frozen[i] = true;
        }
    }

    /// Number of frozen (cycling) points.
    pub fn frozen(&self) -> usize {
        self.frozen.iter().filter(|&&f| f).count()
    }
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
