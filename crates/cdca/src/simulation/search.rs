//! The data of critical control (SPEC §9): the bracketing search for λ_cr
//! and the step in progress (the driver is in `critical.rs`).
//!
//! Path dependence: every trial solve starts from no slip history:
//! proportional loading from zero to λ on the current cracks, in
//! one increment. The utilisation `U(λ)` (the largest over the free tips,
//! see [`assess`](crate::fracture::criterion::assess)) is then a function
//! of λ alone, whatever order the search visits it in. Carrying the slip of
//! the last accepted step instead (measured) made every λ_cr below the last
//! one an unloading path on which the stick/slip iteration did not settle
//! (the default specimen stopped `not_converged` at its second step); under
//! a monotonic proportional load the two agree. What is carried from trial
//! to trial are initial guesses only: the displacement (scaled by the load
//! ratio) for the iterative solvers, and the contact states (open, stick or
//! slip) the contact iteration starts from.
//!
//! Those guesses only speed the contact iteration up: a trial that does
//! not settle from them is solved once more from a cold start (no
//! displacement, no guessed states), as a fresh solve of the scene would
//! be (`cold_trials`). A trial that does not converge either way is not a
//! point of `U(λ)`: the search moves away from it ([`Search::unsolved`]) a
//! few times per step before it records the step unconverged.

use web_time::Instant;

use crate::contact::law::FaceState;
use crate::contact::status::ContactInfo;
use crate::fracture::criterion::{Circle, Faces};
use crate::fracture::sites::Readings;
use crate::report::{KinkReport, TipReport};
use crate::solvers::relaxation::ResidualSample;

/// Relative width of the search's final bracket: λ_cr is the lowest trial
/// load at which a tip meets its criterion, and either a trial at
/// `λ ≥ (1 − LAMBDA_TOLERANCE) λ_cr` showed none meeting it, or the tip
/// meets it to within 0.05% (`UTILISATION_BAND`).
pub const LAMBDA_TOLERANCE: f64 = 1e-3;

/// A trial whose utilisation lies in `[1, 1 + UTILISATION_BAND]` ends the
/// search at once: the tip meets its criterion to 0.05%, which for any
/// response at least as steep as `U ∝ √λ` near the root (linear
/// elasticity gives `U ∝ λ`) puts λ within [`LAMBDA_TOLERANCE`] of the root.
/// Trials aim at the middle of the band, so a near-linear response ends in
/// two or three trials instead of closing a 0.1% bracket (five to seven).
const UTILISATION_BAND: f64 = 0.5 * LAMBDA_TOLERANCE;

/// The utilisation trials aim at.
const TARGET: f64 = 1.0 + 0.5 * UTILISATION_BAND;

/// Trial solves per step before the search gives up (the step is then
/// recorded unconverged).
pub const MAX_TRIALS: usize = 60;

/// Trials per step whose solve may fail to converge before the step is
/// recorded unconverged (see [`Search::unsolved`]).
pub const MAX_UNSOLVED: usize = 3;

/// Largest factor by which one trial raises λ while no tip meets its
/// criterion.
const MAX_RAISE: f64 = 10.0;

/// Where the search goes after a trial.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Next {
    /// Solve at this λ next.
    Trial(f64),
    /// λ_cr (the bracket's upper end) found.
    Found(f64),
    /// No tip meets its criterion at the largest load factor allowed.
    Exceeded,
    /// [`MAX_TRIALS`] trials without closing the bracket.
    Failed,
}

/// The bracketing search for `U(λ) = 1`: regula falsi with the Illinois
/// modification on a bracket `[lo, hi]`, `U(lo) < 1 ≤ U(hi)`, started at
/// `lo = 0` (no load, `U = 0`). Until a trial meets the criterion, each
/// next trial raises λ by the larger of `1/U` (exact for a linear response)
/// and the secant through the last two trials below 1 (a response that
/// saturates, as friction and closure make it, otherwise creeps up by a
/// few percent a trial: 37 trials, 71 s, for a stuck tip of the stepped
/// specimen), up to [`MAX_RAISE`]. Trials aim at `U = 1 +` half the
/// [`UTILISATION_BAND`]. When the same end of the bracket moved twice in a
/// row (a curved response), the interpolated trial is nudged by half the
/// tolerance towards the other end, so that the trials land on both sides
/// and the bracket closes in a few solves.
#[derive(Clone, Debug)]
pub(super) struct Search {
    /// (λ, U) with U < 1.
    lo: (f64, f64),
    /// The `lo` before the last, for the secant while no trial reached 1.
    prev_lo: Option<(f64, f64)>,
    /// (λ, U) with U ≥ 1.
    hi: Option<(f64, f64)>,
    /// The end moved by the last trial (true: hi), and how many times in a
    /// row.
    last: Option<(bool, u32)>,
    trials: usize,
    max: f64,
}

impl Search {
    pub(super) fn new(max_load_factor: f64) -> Self {
        Self {
            lo: (0.0, 0.0),
            prev_lo: None,
            hi: None,
            last: None,
            trials: 0,
            max: max_load_factor,
        }
    }

    /// Records the utilisation `u` of the trial at `lambda` and says what
    /// comes next.
    pub(super) fn record(&mut self, lambda: f64, u: f64) -> Next {
        self.trials += 1;
        let side = u >= 1.0;
        if side {
            if self.hi.is_none_or(|h| lambda < h.0) {
                self.hi = Some((lambda, u));
            }
        } else if lambda > self.lo.0 {
            self.prev_lo = Some(self.lo).filter(|l| l.0 > 0.0);
            self.lo = (lambda, u);
        }
        self.last = Some(match self.last {
            Some((s, n)) if s == side => (s, n + 1),
            _ => (side, 1),
        });
        let Some(hi) = self.hi else {
            if lambda >= self.max {
                return Next::Exceeded;
            }
            let scale = if u > 0.0 { TARGET / u } else { MAX_RAISE };
            let secant = match self.prev_lo {
                Some((l0, u0)) if u > u0 => {
                    (lambda + (TARGET - u) * (lambda - l0) / (u - u0)) / lambda
                }
                Some(_) => MAX_RAISE,
                None => 1.0,
            };
            let raise = scale.max(secant);
            let next = lambda * raise.clamp(1.0 + LAMBDA_TOLERANCE, MAX_RAISE);
            return Next::Trial(next.min(self.max));
        };
        let w = LAMBDA_TOLERANCE * hi.0;
        if hi.0 - self.lo.0 <= w || hi.1 <= 1.0 + UTILISATION_BAND {
            return Next::Found(hi.0);
        }
        if self.trials >= MAX_TRIALS {
            return Next::Failed;
        }
        // Illinois: the end that stayed put twice or more counts half as much
        let (moved_hi, n) = self.last.unwrap_or((true, 1));
        let damp = 0.5_f64.powi(n.saturating_sub(1).min(30) as i32);
        let (mut fl, mut fh) = (self.lo.1 - TARGET, hi.1 - TARGET);
        if moved_hi {
            fl *= damp;
        } else {
            fh *= damp;
        }
        let mut next = if fh.is_finite() && fh - fl > 0.0 {
            self.lo.0 + (hi.0 - self.lo.0) * (-fl) / (fh - fl)
        } else {
            0.5 * (self.lo.0 + hi.0)
        };
        if n >= 2 {
            next += if moved_hi { -0.5 * w } else { 0.5 * w };
        }
        let next = next.clamp(self.lo.0 + 0.25 * w, hi.0 - 0.25 * w);
        Next::Trial(next)
    }

    /// A trial at `lambda` whose solve did not converge: it says nothing
    /// about `U`, so the bracket stays as it is and the next trial moves
    /// away from it, to the middle between it and the bracket's upper end
    /// (a converged solve above) when there is one, otherwise to the middle
    /// between it and the lower end. `None` when no trial is left.
    pub(super) fn unsolved(&mut self, lambda: f64) -> Option<f64> {
        self.trials += 1;
        if self.trials >= MAX_TRIALS {
            return None;
        }
        let other = match self.hi {
            Some(hi) if lambda < hi.0 => hi.0,
            _ => self.lo.0,
        };
        let next = 0.5 * (lambda + other);
        (next > 0.0 && (next - lambda).abs() > LAMBDA_TOLERANCE * lambda).then_some(next)
    }
}

/// The solved state of one trial, kept while it is the bracket's upper end.
pub(super) struct Snapshot {
    pub(super) lambda: f64,
    pub(super) u: Vec<f64>,
    pub(super) faces: Vec<FaceState>,
    pub(super) tips: Vec<TipReport>,
    pub(super) circles: Vec<Circle>,
    pub(super) tip_faces: Vec<Faces>,
    pub(super) utilisation: Vec<f64>,
    pub(super) kinks: Vec<KinkReport>,
    pub(super) kink_utilisation: Vec<f64>,
    pub(super) rock: Option<Readings>,
    pub(super) contact: ContactInfo,
    pub(super) residual: Vec<ResidualSample>,
}

/// A critical-control step in progress.
pub(super) struct CriticalRun {
    pub(super) search: Search,
    /// Committed contact states every trial starts from.
    pub(super) base_faces: Vec<FaceState>,
    /// The lowest trial so far that meets the criterion.
    pub(super) best: Option<Snapshot>,
    /// Load factors of the trials whose solve did not converge (the search
    /// moved away from them).
    pub(super) unsolved: Vec<f64>,
    /// Load factors of the trials solved again from a cold start after
    /// their warm start did not converge; `cold` while such a retry is in
    /// progress.
    pub(super) cold_trials: Vec<f64>,
    pub(super) cold: bool,
    /// Load factors of the trials taken from the last solved one by
    /// scaling, without a solve (see `Simulation::scale_solved`).
    pub(super) scaled: Vec<f64>,
    pub(super) start: Instant,
    /// The search's verdict once it has ended (the state then holds the
    /// solve at λ_cr, shown before the tips are extended).
    pub(super) ended: Option<Next>,
}

/// What a growth step's report says of its λ_cr search: when it started,
/// and the trials it stepped around or solved again from a cold start.
pub(super) struct Trials<'a> {
    pub(super) start: Instant,
    pub(super) unsolved: &'a [f64],
    pub(super) cold: &'a [f64],
    pub(super) scaled: &'a [f64],
}

impl CriticalRun {
    pub(super) fn trials(&self) -> Trials<'_> {
        Trials {
            start: self.start,
            unsolved: &self.unsolved,
            cold: &self.cold_trials,
            scaled: &self.scaled,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs the search on a known `U(λ)` and returns (λ_cr or None, trials).
    fn find(u: impl Fn(f64) -> f64, first: f64, max: f64) -> (Option<f64>, usize) {
        let mut s = Search::new(max);
        let mut lambda = first;
        for k in 1..=MAX_TRIALS + 1 {
            match s.record(lambda, u(lambda)) {
                Next::Trial(l) => lambda = l,
                Next::Found(l) => return (Some(l), k),
                Next::Exceeded | Next::Failed => return (None, k),
            }
        }
        unreachable!("the search ends within MAX_TRIALS")
    }

    /// A linear response `U = λ/2.37` is found in 2 trials from below
    /// (λ = 1) and in 2 from above (λ = 5), λ_cr within the tolerance above
    /// the root.
    #[test]
    fn linear_root_in_two_trials() {
        let root = 2.37;
        for first in [1.0, 5.0] {
            let (l, n) = find(|l| l / root, first, 100.0);
            let l = l.expect("found");
            assert!(l >= root && l <= root * (1.0 + LAMBDA_TOLERANCE), "{l}");
            assert!(n <= 2, "from {first}: {n} trials");
        }
    }

    /// Nonlinear responses (a threshold then a steep rise; a square root;
    /// a step) are bracketed to the tolerance from warm starts on either
    /// side; a response that stays below 1 up to the cap is `Exceeded`.
    #[test]
    fn nonlinear_roots_are_bracketed() {
        let cases: [(&dyn Fn(f64) -> f64, f64); 3] = [
            (
                &|l: f64| {
                    if l < 3.0 {
                        0.1 * l
                    } else {
                        0.2 + 5.0 * (l - 3.0)
                    }
                },
                3.16,
            ),
            (&|l: f64| (l / 7.0).sqrt(), 7.0),
            (&|l: f64| if l < 0.42 { 0.2 } else { 1.5 }, 0.42),
        ];
        for (u, root) in cases {
            for first in [0.01, 1.0, 50.0] {
                let (l, n) = find(u, first, 100.0);
                let l = l.expect("found");
                assert!(
                    l >= root && l <= root / (1.0 - LAMBDA_TOLERANCE),
                    "root {root} from {first}: {l} after {n} trials"
                );
                assert!(n < 40, "root {root} from {first}: {n} trials");
            }
        }
        assert_eq!(find(|l| l / 200.0, 1.0, 100.0).0, None);
    }

    /// Solves that do not converge in a band of λ (as near a split, where
    /// the contact iteration cycles) are stepped around: with a step
    /// response (`U` = 0.2 below λ = 2.37, 3 above), unsolved on
    /// (0.5, 1.5), and a first trial at 9, the regula falsi's second trial
    /// (λ = 3) and third (1.0, unsolved) lead on to 2.0 and the search ends
    /// at the root; with everything below the root unsolved it gives up
    /// after [`MAX_UNSOLVED`] of them.
    #[test]
    fn unsolved_trials_are_stepped_around() {
        let root = 2.37;
        let run = |bad: &dyn Fn(f64) -> bool| -> (Option<f64>, usize) {
            let mut s = Search::new(100.0);
            let (mut lambda, mut unsolved) = (9.0, 0);
            for _ in 0..MAX_TRIALS {
                if bad(lambda) {
                    unsolved += 1;
                    match s.unsolved(lambda).filter(|_| unsolved <= MAX_UNSOLVED) {
                        Some(next) => lambda = next,
                        None => return (None, unsolved),
                    }
                    continue;
                }
                match s.record(lambda, if lambda < root { 0.2 } else { 3.0 }) {
                    Next::Trial(l) => lambda = l,
                    Next::Found(l) => return (Some(l), unsolved),
                    Next::Exceeded | Next::Failed => return (None, unsolved),
                }
            }
            (None, unsolved)
        };
        let (l, unsolved) = run(&|l| (0.5..1.5).contains(&l));
        let l = l.expect("found around the unsolved band");
        assert!(l >= root && l <= root / (1.0 - LAMBDA_TOLERANCE), "{l}");
        assert!((1..=MAX_UNSOLVED).contains(&unsolved), "{unsolved}");
        let (l, unsolved) = run(&|l| l < root * 0.999);
        assert_eq!((l, unsolved), (None, MAX_UNSOLVED + 1));
    }

    /// A response that saturates below 1 (`U = 0.9 (1 − e^−λ)`, as a tip
    /// held by friction) reaches the cap in a few trials, not by creeping
    /// up by `1/U`; one that saturates just above 1 is still found.
    #[test]
    fn saturating_responses_end_in_few_trials() {
        let (l, n) = find(|l| 0.9 * (1.0 - (-l).exp()), 1.0, 100.0);
        assert_eq!(l, None);
        assert!(n <= 10, "{n} trials");
        let root = -(1.0 - 1.0 / 1.1_f64).ln();
        let (l, n) = find(|l| 1.1 * (1.0 - (-l).exp()), 0.5, 100.0);
        let l = l.expect("found");
        assert!(
            l >= root && l <= root / (1.0 - LAMBDA_TOLERANCE),
            "{l} vs {root}"
        );
        assert!(n < 40, "{n} trials");
    }
}
