//! The solve at the current load, resumable: the contact iteration
//! ([`ContactSolve`]) around the scene's linear solver, or the automaton
//! with the contact states updated in its sweeps ([`InSweep`],
//! `solver.contact_update: "in_sweep"`), a slice at a time, so that the
//! workbench can animate the automaton and the contact states settling
//! without freezing a frame. [`Simulation::solve`] runs the same slices to
//! the end.

use web_time::Instant;

use super::job::Job;
use super::state::Simulation;
use crate::contact::in_sweep::InSweep;
use crate::contact::iteration::ContactSolve;
use crate::error::SolveError;
use crate::scene::ContactUpdate;
use crate::solvers::relaxation::{RelaxStatus, ResidualSample};

impl Simulation {
    /// Starts (or restarts) a resumable solve from the current displacement
    /// with the scene's solver. The contact iteration starts at the first
    /// [`relax`](Self::relax) call. A load-controlled growth step under way
    /// starts again at its next call (as after [`solve`](Self::solve), which
    /// is this solve run to its end).
    pub fn start_relaxation(&mut self) {
        self.scratch.growth_start = None;
        self.scratch.residual.clear();
        self.scratch.job = None;
    }

    /// Advances the solve started by
    /// [`start_relaxation`](Self::start_relaxation) (started now if none is
    /// under way) by one chunk of what the discretisation still lacks (the
    /// element stiffness of a new simulation, the direct solver's pattern,
    /// a free tip's interaction-integral domain),
    /// one linear-solver setup (a factorisation, cells or a multigrid
    /// hierarchy) or at most `max_iterations` sweeps or iterations; cheap
    /// enough to call once per frame. A setup is done
    /// only when the contact states differ from those the solver's matrix
    /// was built with: the matrix is then new; otherwise only the
    /// right-hand side changes.
    ///
    /// The contact states are updated when a linear solve has finished
    /// ([`ContactSolve`]), or with `solver.contact_update: "in_sweep"` at
    /// each cell visit of the automaton ([`InSweep`]; then
    /// [`contact_points`](Self::contact_points) shows them changing
    /// between slices), never at a slice's end, so the answer does not
    /// depend on `max_iterations`. The solve ends (`finished`)
    /// when the contact states settle, or at a cap:
    /// `solver.max_iterations` sweeps in one linear solve (in all, in
    /// sweep), or `solver.max_contact_iterations` contact iterations. `converged` is
    /// true only when it ended with every test passed; a capped solve ends
    /// with `converged: false`, its state is shown but growth does not go on
    /// from it. The tips are evaluated either way.
    pub fn relax(&mut self, max_iterations: usize) -> Result<RelaxStatus, SolveError> {
        let clock = Instant::now();
        let before = (
            self.scratch.work.build_seconds,
            self.scratch.work.evaluate_seconds,
        );
        let status = self.relax_slice(max_iterations);
        // the slice's build and evaluation are counted as such
        let w = &mut self.scratch.work;
        w.solve_seconds += clock.elapsed().as_secs_f64()
            - (w.build_seconds - before.0)
            - (w.evaluate_seconds - before.1);
        status
    }

    /// One slice of [`relax`](Self::relax), its time counted there.
    fn relax_slice(&mut self, max_iterations: usize) -> Result<RelaxStatus, SolveError> {
        if self.scratch.job.is_none() {
            // a new simulation's element stiffness (and, for the direct
            // solver, its pattern), one chunk per call
            if !self.prepare_chunk()? {
                return Ok(RelaxStatus {
                    iterations: 0,
                    residual: 1.0,
                    converged: false,
                    finished: false,
                });
            }
            self.scratch.residual.clear();
            let load = self
                .scratch
                .f_ext
                .iter()
                .map(|v| v * self.state.lambda)
                .collect();
            let initial = self.initial_contact_states();
            let params = self.contact_params();
            self.scratch.job = Some(match self.model.scene.solver.contact_update {
                ContactUpdate::Outer => {
                    Job::Outer(Box::new(ContactSolve::new(load, initial, params)))
                }
                ContactUpdate::InSweep => Job::InSweep(Box::new(InSweep::new(
                    load,
                    initial,
                    self.in_sweep_params(),
                ))),
            });
        }
        let scratch = &mut self.scratch;
        let status = match scratch.job.as_mut() {
            Some(Job::Outer(job)) => job.advance(
                &scratch.xfem,
                &self.state.faces,
                &mut scratch.factored,
                &mut self.state.u,
                scratch.solver.as_mut(),
                max_iterations,
            )?,
            Some(Job::InSweep(job)) => job.run(
                &scratch.xfem,
                &self.state.faces,
                &mut self.state.u,
                max_iterations,
            )?,
            None => unreachable!("a contact iteration was just started"),
        };
        if status.finished {
            self.finish();
        }
        Ok(status)
    }

    /// Ends the solve: commits the contact states, keeps how the contact
    /// iteration ended and its residual history, evaluates the tips.
    fn finish(&mut self) {
        let Some(job) = self.scratch.job.take() else {
            return;
        };
        let reached = job.into_reached();
        let w = &mut self.scratch.work;
        w.solves += 1;
        w.contact_iterations += reached.info.iterations;
        w.linear_iterations += reached.info.linear_iterations;
        w.newton_fallbacks += usize::from(reached.info.newton_fallback);
        self.scratch.residual = reached.history;
        self.state.faces = reached.states;
        self.scratch.contact = reached.info;
        self.state.solved = true;
        let clock = Instant::now();
        self.evaluate();
        self.read_rock();
        self.scratch.work.evaluate_seconds += clock.elapsed().as_secs_f64();
    }

    /// Residual samples of the current (or last) solve, all its contact
    /// iterations' linear solves in turn.
    pub fn residual_history(&self) -> &[ResidualSample] {
        self.scratch
            .job
            .as_ref()
            .map_or(&self.scratch.residual, |j| &j.reached().history)
    }
}
