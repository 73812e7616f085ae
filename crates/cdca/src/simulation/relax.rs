//! The relaxation driver: a resumable solve with contact that runs a few
//! sweeps per call, so that the workbench can animate the automaton and the
//! contact states settling without freezing a frame.

use super::job::{KeptRelaxation, RelaxJob, kinds};
use super::state::Simulation;
use crate::contact::iteration::{
    ContactInfo, FlipTracker, relative_change, settled, update_states,
};
use crate::contact::law::{ContactState, FaceState, contact_system};
use crate::error::SolveError;
use crate::solvers::linear::LinearInfo;
use crate::solvers::relaxation::{RelaxStatus, Relaxation, ResidualSample};

/// Relative residual below which the automaton updates contact states
/// inside its sweeps.
pub const IN_SWEEP_CONTACT_RESIDUAL: f64 = 1e-3;

impl Simulation {
    /// Starts (or restarts) a resumable solve from the current displacement
    /// with the scene's solver. The setup (cells, factorisations) happens at
    /// the first [`relax`](Self::relax) call, which reports its errors.
    pub fn start_relaxation(&mut self) {
        self.scratch.residual.clear();
        self.scratch.job = None;
    }

    /// A job for the contact system of `states`, to be set up by the next
    /// [`relax`](Self::relax) call (see [`set_up`](Self::set_up)).
    fn new_job(
        &self,
        states: Vec<FaceState>,
        tracker: FlipTracker,
        contact_iterations: usize,
        done_iterations: usize,
        done_seconds: f64,
    ) -> RelaxJob {
        let x = &self.scratch.xfem;
        let mut f: Vec<f64> = self
            .scratch
            .f_ext
            .iter()
            .map(|v| v * self.state.lambda)
            .collect();
        let blocks = contact_system(x, &states, &self.state.faces, &mut f);
        RelaxJob {
            relaxation: None,
            f,
            blocks,
            kinds: kinds(&states),
            states,
            tracker,
            contact_iterations,
            done_iterations,
            done_seconds,
            start_u: self.state.u.clone(),
            // later contact iterations do not repeat the iteration-0 sample
            copied: usize::from(done_iterations > 0),
        }
    }

    /// The job's relaxation: the kept one restarted if its contact states
    /// match (no new factorisation or setup), else a new one.
    fn set_up(&mut self, job: &RelaxJob) -> Result<Relaxation, SolveError> {
        if let Some(kept) = self.scratch.kept.take()
            && kept.kinds == job.kinds
        {
            let mut relaxation = kept.relaxation;
            relaxation.reset(&job.f, &job.start_u)?;
            return Ok(relaxation);
        }
        let spec = &self.model.scene.solver;
        Relaxation::new(
            spec.kind,
            spec,
            &self.scratch.xfem,
            &job.blocks,
            &job.f,
            &job.start_u,
        )
    }

    /// Keeps a finished or replaced job's relaxation (set up for the
    /// contact states `kinds`) for reuse.
    fn keep(&mut self, kinds: Vec<ContactState>, relaxation: Option<Relaxation>) {
        if let Some(relaxation) = relaxation {
            self.scratch.kept = Some(KeptRelaxation { kinds, relaxation });
        }
    }

    /// Runs at most `max_iterations` sweeps (or iterations) of the solve
    /// started by [`start_relaxation`](Self::start_relaxation) (started now
    /// if none is under way); cheap enough to call once per frame. When the
    /// linear solve converges, the contact states are updated and, if any
    /// changed, the relaxation continues on the new contact system.
    ///
    /// A call sets up at most one linear solver (a factorisation, cells or
    /// a multigrid hierarchy): a new contact iteration's is set up by the
    /// next call, or not at all when the last one's contact states match
    /// (open, stick or slip at every point): the matrix is then the same,
    /// and only the right-hand side changes.
    ///
    /// The solve ends (`finished`) when the contact states settle, or at a
    /// cap: `solver.max_iterations` sweeps in one contact iteration, or
    /// `solver.max_contact_iterations` contact iterations. `converged` is
    /// true only when it ended with every test passed; a capped solve ends
    /// with `converged: false`, its state is shown but growth does not go on
    /// from it. The tips are evaluated either way.
    pub fn relax(&mut self, max_iterations: usize) -> Result<RelaxStatus, SolveError> {
        if self.scratch.job.is_none() {
            self.scratch.xfem.integrate(usize::MAX);
            self.scratch.residual.clear();
            let fresh = FlipTracker::new(self.state.faces.len());
            let initial = self.initial_contact_states();
            self.scratch.job = Some(self.new_job(initial, fresh, 0, 0, 0.0));
        }
        let Some(mut job) = self.scratch.job.take() else {
            unreachable!("a job was just started")
        };
        let relaxation = match job.relaxation.take() {
            Some(r) => r,
            None => self.set_up(&job)?,
        };
        let relaxation = job.relaxation.insert(relaxation);
        let cap = self.model.scene.solver.max_iterations.max(1);
        let left = cap.saturating_sub(relaxation.status().iterations).max(1);
        let status = relaxation.run(
            &self.scratch.xfem,
            &job.blocks,
            max_iterations.min(left),
            &mut |_| {},
        )?;
        self.state.u.copy_from_slice(relaxation.u());
        self.copy_history(&mut job);
        let iterations = job.done_iterations + status.iterations;
        if !status.converged {
            if status.iterations >= cap {
                // the linear solve hit its cap: end, unconverged
                let du = relative_change(&self.state.u, &job.start_u);
                return Ok(self.finish(job, status, false, du, 0));
            }
            let job = self.contact_inside_sweeps(job, status, iterations);
            self.scratch.job = Some(job);
            return Ok(RelaxStatus {
                iterations,
                ..status
            });
        }
        // the linear solve converged: the contact iteration
        let params = self.contact_params();
        let committed = self.state.faces.clone();
        let update = update_states(
            &self.scratch.xfem,
            &self.state.u,
            &committed,
            &mut job.states,
            &mut job.tracker,
            params,
        );
        let du = relative_change(&self.state.u, &job.start_u);
        job.contact_iterations += 1;
        if settled(&update, &job.states, du, params) {
            return Ok(self.finish(job, status, update.violating == 0, du, update.violating));
        }
        if job.contact_iterations >= params.max_contact_iterations() {
            return Ok(self.finish(job, status, false, du, update.violating));
        }
        let seconds = job.seconds();
        let next = self.new_job(
            job.states,
            job.tracker,
            job.contact_iterations,
            iterations,
            seconds,
        );
        self.keep(job.kinds, job.relaxation);
        // set up by the next call: at most one setup per call
        self.scratch.job = Some(next);
        Ok(RelaxStatus {
            iterations,
            residual: status.residual,
            converged: false,
            finished: false,
        })
    }

    /// Appends the samples of the job's relaxation not yet copied to the
    /// cumulative residual history.
    fn copy_history(&mut self, job: &mut RelaxJob) {
        let (iterations, seconds) = (job.done_iterations, job.done_seconds);
        let history = job.relaxation().history();
        self.scratch
            .residual
            .extend(
                history[job.copied.min(history.len())..]
                    .iter()
                    .map(|s| ResidualSample {
                        iteration: s.iteration + iterations,
                        seconds: s.seconds + seconds,
                        residual: s.residual,
                    }),
            );
        job.copied = history.len();
    }

    /// Ends the solve: commits the contact states, records how the contact
    /// iteration ended, evaluates the tips.
    fn finish(
        &mut self,
        job: RelaxJob,
        status: RelaxStatus,
        converged: bool,
        du: f64,
        violating: usize,
    ) -> RelaxStatus {
        let iterations = job.done_iterations + status.iterations;
        self.scratch.contact = ContactInfo {
            iterations: job.contact_iterations.max(1),
            converged: converged && status.converged,
            residual: du,
            cycling: job.tracker.frozen(),
            violating,
            linear_iterations: iterations,
            last: LinearInfo {
                iterations: status.iterations,
                residual: status.residual,
                converged: status.converged,
                history: job
                    .relaxation()
                    .history()
                    .iter()
                    .map(|s| s.residual)
                    .collect(),
            },
        };
        self.state.faces = job.states;
        self.keep(job.kinds, job.relaxation);
        self.state.solved = true;
        self.evaluate();
        RelaxStatus {
            iterations,
            residual: status.residual,
            converged: self.scratch.contact.converged,
            finished: true,
        }
    }

    /// The paper's automaton updates the contact states inside its sweeps
    /// (steps 1–9): once the iterate means something (relative residual
    /// below [`IN_SWEEP_CONTACT_RESIDUAL`]), every chunk of sweeps
    /// re-evaluates the face states by the return mapping and, if any
    /// changed, continues on the new contact system from the current
    /// displacement. Points that keep flipping are frozen as in the outer
    /// loop. Other solvers keep the outer contact iteration.
    fn contact_inside_sweeps(
        &mut self,
        job: RelaxJob,
        status: RelaxStatus,
        total: usize,
    ) -> RelaxJob {
        let automaton = self.model.scene.solver.kind == crate::scene::SolverKind::Automaton;
        if !automaton || job.states.is_empty() || status.residual > IN_SWEEP_CONTACT_RESIDUAL {
            return job;
        }
        let mut states = job.states.clone();
        let mut tracker = job.tracker.clone();
        let update = update_states(
            &self.scratch.xfem,
            &self.state.u,
            &self.state.faces,
            &mut states,
            &mut tracker,
            self.contact_params(),
        );
        if update.changed == 0 {
            return job;
        }
        let next = self.new_job(
            states,
            tracker,
            job.contact_iterations + 1,
            total,
            job.seconds(),
        );
        self.keep(job.kinds, job.relaxation);
        next
    }

    /// Residual samples of the current relaxation.
    pub fn residual_history(&self) -> &[ResidualSample] {
        &self.scratch.residual
    }
}
