//! Critical control (SPEC §9): before each growth step, the load factor
//! λ_cr at which the most critical free tip just meets its criterion, by
//! the bracketing root search of [`Search`] through the contact solve;
//! resumable, one trial solve at a time. See `search.rs` for which
//! committed states each trial starts from.

use web_time::Instant;

use super::search::{CriticalRun, MAX_UNSOLVED, Next, Search, Snapshot};
use super::state::Simulation;
use crate::contact::iteration::states_at_scaled_load;
use crate::contact::law::FaceState;
use crate::report::{GrowthStepReport, WorkReport};

impl Simulation {
    /// Largest utilisation over the free tips and the kinks of the last
    /// solve, and the intact rock's sites (0 with none).
    pub(super) fn utilisation(&self) -> f64 {
        self.scratch
            .utilisation
            .iter()
            .chain(&self.scratch.kink_utilisation)
            .copied()
            .fold(self.rock_utilisation(), f64::max)
    }

    /// Starts a critical-control step: the first trial at the last step's
    /// λ_cr (warm start; `growth.resume.load_factor` in a scene saved
    /// mid-run), or at the scene's load (λ = 1) at the first step.
    pub(super) fn begin_critical(&mut self) {
        let g = &self.model.scene.growth;
        let resumed = self.state.steps_before > 0 && self.state.lambda > 0.0;
        let warm = self
            .state
            .history
            .last()
            .map_or(if resumed { self.state.lambda } else { 1.0 }, |s| {
                s.load_factor
            });
        // every step starts from what the scene carries (`growth.resume`):
        // no displacement, the contact states as they are
        self.state.u.fill(0.0);
        self.scratch.work = WorkReport::default();
        let first = warm.min(g.max_load_factor);
        self.scratch.critical = Some(CriticalRun {
            search: Search::new(g.max_load_factor),
            base_faces: vec![FaceState::default(); self.state.faces.len()],
            best: None,
            unsolved: Vec::new(),
            cold_trials: Vec::new(),
            scaled: Vec::new(),
            cold: false,
            start: Instant::now(),
            ended: None,
        });
        self.start_trial(first);
    }

    /// Sets up the trial solve at `lambda` from the committed states.
    fn start_trial(&mut self, lambda: f64) {
        let Some(run) = &self.scratch.critical else {
            return;
        };
        // the states just solved (this step's last trial, or the last
        // step's λ_cr carried over to the grown cracks) start the next
        // trial's contact iteration; its slip history is `base_faces`
        let solved = std::mem::replace(&mut self.state.faces, run.base_faces.clone());
        self.scratch.contact_guess = Some(solved);
        if self.state.lambda > 0.0 {
            let s = lambda / self.state.lambda;
            self.state.u.iter_mut().for_each(|v| *v *= s);
        }
        self.state.lambda = lambda;
        self.state.solved = false;
        self.scratch.job = None;
        self.scratch.residual.clear();
    }

    /// Whether the λ_cr search of the step in progress has ended: the state
    /// is the solve at λ_cr, and the next
    /// [`advance_growth`](Self::advance_growth) call extends the tips.
    pub fn at_critical_load(&self) -> bool {
        self.scratch
            .critical
            .as_ref()
            .is_some_and(|r| r.ended.is_some())
    }

    /// After a trial solve (the state is solved at the trial's λ): the next
    /// trial; or, when the search ends, the state of λ_cr restored (the
    /// caller may show it) and `None`; or, the call after that, the step
    /// finished (tips extended at λ_cr and recorded).
    pub(super) fn trial_done(&mut self) -> Option<GrowthStepReport> {
        let mut run = self.scratch.critical.take()?;
        let seconds = run.start.elapsed().as_secs_f64();
        let report = self.report(seconds);
        if let Some(next) = run.ended {
            return Some(self.finish_growth_step(&report, &run.trials(), next != Next::Failed));
        }
        let (lambda, u) = (self.state.lambda, self.utilisation());
        if !report.converged() && !run.cold {
            // the warm start (the last trial's contact states and
            // displacement) only speeds the contact iteration up; a trial
            // that does not settle from it is solved once more from a cold
            // start (no displacement, no guessed states), as a fresh solve
            // of the scene at that load would be
            run.cold = true;
            run.cold_trials.push(lambda);
            self.scratch.critical = Some(run);
            self.start_trial(lambda);
            self.scratch.contact_guess = None;
            self.state.u.fill(0.0);
            return None;
        }
        run.cold = false;
        if !report.converged() {
            // a solve that does not converge says nothing about U(λ): move
            // away from it (near a split the contact iteration can cycle at
            // one load and settle at another), a few times per step
            let next = (run.unsolved.len() < MAX_UNSOLVED)
                .then(|| run.search.unsolved(lambda))
                .flatten();
            run.unsolved.push(lambda);
            let Some(next) = next else {
                return Some(self.finish_growth_step(&report, &run.trials(), true));
            };
            // the next trial starts from the lowest converged one above
            let guess = run.best.as_ref().map(|b| b.faces.clone());
            self.scratch.critical = Some(run);
            self.start_trial(next);
            if guess.is_some() {
                self.scratch.contact_guess = guess;
            }
            return None;
        }
        if u >= 1.0 && run.best.as_ref().is_none_or(|b| lambda < b.lambda) {
            run.best = Some(self.snapshot());
        }
        match run.search.record(lambda, u) {
            Next::Trial(next) => {
                let scaled = self.scale_solved(next, &run.base_faces);
                if scaled {
                    run.scaled.push(next);
                }
                self.scratch.critical = Some(run);
                if !scaled {
                    self.start_trial(next);
                }
                None
            }
            Next::Exceeded => Some(self.finish_growth_step(&report, &run.trials(), true)),
            next => {
                if let Some(best) = run.best.take() {
                    self.restore(best);
                }
                run.ended = Some(next);
                self.scratch.critical = Some(run);
                None
            }
        }
    }

    /// The trial at `lambda` without a solve, when the scene scales: the
    /// solved state (a converged trial) times `lambda / λ`, its contact
    /// states checked at the scaled displacement
    /// ([`states_at_scaled_load`]), the tips evaluated on it. False (the
    /// state untouched) when a face has cohesion or a state would change;
    /// the trial is then solved.
    fn scale_solved(&mut self, lambda: f64, committed: &[FaceState]) -> bool {
        let (x, from) = (&self.scratch.xfem, self.state.lambda);
        if !(self.state.solved && from > 0.0 && lambda > 0.0) {
            return false;
        }
        let s = lambda / from;
        let u: Vec<f64> = self.state.u.iter().map(|v| v * s).collect();
        let Some(faces) = states_at_scaled_load(x, &u, committed, &self.state.faces) else {
            return false;
        };
        self.state.u = u;
        self.state.faces = faces;
        self.state.lambda = lambda;
        self.evaluate();
        true
    }

    fn snapshot(&self) -> Snapshot {
        Snapshot {
            lambda: self.state.lambda,
            u: self.state.u.clone(),
            faces: self.state.faces.clone(),
            tips: self.scratch.tips.clone(),
            circles: self.scratch.circles.clone(),
            tip_faces: self.scratch.tip_faces.clone(),
            utilisation: self.scratch.utilisation.clone(),
            kinks: self.scratch.kinks.clone(),
            kink_utilisation: self.scratch.kink_utilisation.clone(),
            rock: self.scratch.rock.clone(),
            contact: self.scratch.contact.clone(),
            residual: self.scratch.residual.clone(),
        }
    }

    fn restore(&mut self, s: Snapshot) {
        self.state.lambda = s.lambda;
        self.state.u = s.u;
        self.state.faces = s.faces;
        self.state.solved = true;
        self.scratch.tips = s.tips;
        self.scratch.circles = s.circles;
        self.scratch.tip_faces = s.tip_faces;
        self.scratch.utilisation = s.utilisation;
        self.scratch.kinks = s.kinks;
        self.scratch.kink_utilisation = s.kink_utilisation;
        self.scratch.rock = s.rock;
        self.scratch.contact = s.contact;
        self.scratch.residual = s.residual;
        self.scratch.job = None;
    }
}
