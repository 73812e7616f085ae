//! Drives the solver inside the frame budget: the run mode, the
//! simulation, and the copies of its state that the UI shows.

use cdca::scene::SolverKind;
use cdca::{Scene, Simulation};
use web_time::{Duration, Instant};

use crate::field::{FieldKey, FieldSampler};
use crate::solution::SolutionView;

/// What the solver does in the coming frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RunMode {
    #[default]
    Paused,
    /// Relaxation sweeps each frame until converged.
    Relaxing,
    /// Growth steps each frame until the run ends.
    Growing,
}

/// The simulation and everything derived from it.
#[derive(Default)]
pub struct Runner {
    sim: Option<Simulation>,
    pub mode: RunMode,
    /// `start_relaxation` was called on the current simulation.
    relaxation_started: bool,
    /// Sweeps per `relax` call, adapted to fill the budget.
    sweeps_per_call: usize,
    pub view: SolutionView,
    pub field: FieldSampler,
    /// The edited scene differs from the simulated one.
    pub stale: bool,
    /// Wall time of the last full solve, s.
    pub last_solve_seconds: Option<f64>,
    /// Wall time of the last `Simulation::new`, s.
    pub last_build_seconds: f64,
    /// Solver time spent in the last frame, s.
    pub frame_solver_seconds: f64,
}

/// Full solves faster than this are redone automatically after an edit.
pub const QUICK_SOLVE_SECONDS: f64 = 0.25;

impl Runner {
    /// Forgets the simulation after an edit: `scene` is only validated
    /// (cheap); the discretisation is built when solver work is asked for.
    pub fn invalidate(&mut self, scene: &Scene) -> Result<(), String> {
        self.sim = None;
        self.mode = RunMode::Paused;
        self.relaxation_started = false;
        self.view.clear();
        self.field.clear();
        self.stale = true;
        scene.validate().map_err(|e| e.to_string())
    }

    /// Builds a simulation of `scene` (validated; nothing solved yet).
    pub fn rebuild(&mut self, scene: &Scene) -> Result<(), String> {
        self.invalidate(scene)?;
        let start = Instant::now();
        let sim = Simulation::new(scene.clone()).map_err(|e| e.to_string())?;
        self.last_build_seconds = start.elapsed().as_secs_f64();
        self.sim = Some(sim);
        self.sweeps_per_call = 1;
        self.stale = false;
        Ok(())
    }

    pub fn simulation(&self) -> Option<&Simulation> {
        self.sim.as_ref()
    }

    fn solver_kind(&self) -> SolverKind {
        self.sim
            .as_ref()
            .map_or(SolverKind::Direct, |s| s.scene().solver.kind)
    }

    /// Whether a re-solve of `scene` after an edit is cheap enough to do
    /// unasked: the direct solver, and the last build and solve was quick
    /// (before any, meshes up to 80 × 80).
    pub fn solve_is_quick(&self, scene: &Scene) -> bool {
        scene.solver.kind == SolverKind::Direct
            && self
                .last_solve_seconds
                .map_or(scene.mesh.nx * scene.mesh.ny <= 6400, |s| {
                    s + self.last_build_seconds < QUICK_SOLVE_SECONDS
                })
    }

    /// Solves now: the direct solver in one call, iterative ones animated.
    pub fn solve(&mut self) -> Result<(), String> {
        if self.solver_kind() != SolverKind::Direct {
            self.relaxation_started = false;
            self.mode = RunMode::Relaxing;
            return Ok(());
        }
        let Some(sim) = self.sim.as_mut() else {
            return Ok(());
        };
        self.mode = RunMode::Paused;
        let start = Instant::now();
        let result = sim.solve();
        self.last_solve_seconds = Some(start.elapsed().as_secs_f64());
        self.refresh(true, None);
        result.map(|_| ()).map_err(|e| e.to_string())
    }

    /// One sweep of the current relaxation (starting one if needed).
    pub fn step(&mut self) -> Result<(), String> {
        self.mode = RunMode::Paused;
        self.relax_chunk(1).map(|_| ())
    }

    /// One whole growth step (a button press).
    pub fn grow_one(&mut self) -> Result<(), String> {
        self.mode = RunMode::Paused;
        let Some(sim) = self.sim.as_mut() else {
            return Ok(());
        };
        let result = if sim.growth_finished().is_some() {
            Ok(())
        } else {
            // the step, then the re-solve of the grown cracks at the same
            // load (SPEC §9), so that the field of the new geometry shows
            sim.grow_step()
                .and_then(|_| {
                    if sim.is_solved() {
                        Ok(())
                    } else {
                        sim.solve().map(|_| ())
                    }
                })
                .map_err(|e| e.to_string())
        };
        self.relaxation_started = false;
        self.refresh(true, None);
        result
    }

    /// Runs `n` sweeps; returns whether the relaxation converged.
    fn relax_chunk(&mut self, n: usize) -> Result<bool, String> {
        let Some(sim) = self.sim.as_mut() else {
            return Ok(true);
        };
        if !self.relaxation_started {
            sim.start_relaxation();
            self.relaxation_started = true;
        }
        let result = sim.relax(n);
        let status = result.as_ref().ok().copied();
        self.refresh(true, status);
        let status = result.map_err(|e| e.to_string())?;
        Ok(status.converged)
    }

    /// Growth until `deadline`, in resumable chunks (a few solver sweeps or
    /// one contact iteration each; the chunk that completes a step also
    /// extends the tips and rebuilds the discretisation); returns whether
    /// the run ended.
    fn grow_chunk(&mut self, deadline: Instant) -> Result<bool, String> {
        let Some(sim) = self.sim.as_mut() else {
            return Ok(true);
        };
        let mut result = Ok(false);
        loop {
            if sim.growth_finished().is_some() {
                result = Ok(true);
                break;
            }
            if let Err(e) = sim.advance_growth(self.sweeps_per_call.max(1)) {
                result = Err(e.to_string());
                break;
            }
            if Instant::now() >= deadline {
                break;
            }
        }
        let finished = sim.growth_finished().is_some();
        self.relaxation_started = false;
        // the view follows solved states; while a grown geometry is being
        // solved it keeps showing the last converged field
        let solved = sim.is_solved();
        if solved || finished || result.is_err() {
            self.refresh(solved, None);
        }
        result.map(|done| done || finished)
    }

    fn refresh(&mut self, solved: bool, relax: Option<cdca::RelaxStatus>) {
        if let Some(sim) = &self.sim {
            self.view.refresh(sim, solved, relax);
        }
    }

    /// The frame's share of work within `budget`: either sampling the field
    /// of the current state (so what is shown is consistent), or solver work
    /// in the run mode, never both: one growth step can take most of a
    /// frame by itself. Returns an error to show.
    pub fn tick(&mut self, budget: Duration, field_key: Option<FieldKey>) -> Result<(), String> {
        let start = Instant::now();
        let deadline = start + budget;
        self.frame_solver_seconds = 0.0;
        if let (Some(sim), Some(key)) = (&self.sim, field_key)
            && self.view.solved
            && !self.field.is_current(&key)
        {
            self.field.work(sim, key, deadline);
            self.frame_solver_seconds = start.elapsed().as_secs_f64();
            return Ok(());
        }
        if Instant::now() >= deadline {
            return Ok(());
        }
        let outcome = match self.mode {
            RunMode::Paused => Ok(false),
            RunMode::Relaxing => self.relax_for(deadline),
            RunMode::Growing => self.grow_chunk(deadline),
        };
        self.frame_solver_seconds = start.elapsed().as_secs_f64();
        match outcome {
            Ok(false) => Ok(()),
            Ok(true) => {
                self.mode = RunMode::Paused;
                Ok(())
            }
            Err(e) => {
                self.mode = RunMode::Paused;
                Err(e)
            }
        }
    }

    /// Relaxation sweeps until `deadline`, adapting the sweeps per call so
    /// that one call takes about a quarter of the remaining budget.
    fn relax_for(&mut self, deadline: Instant) -> Result<bool, String> {
        loop {
            let t0 = Instant::now();
            let n = self.sweeps_per_call.max(1);
            if self.relax_chunk(n)? {
                return Ok(true);
            }
            let per_sweep = t0.elapsed().as_secs_f64() / n as f64;
            let now = Instant::now();
            if now >= deadline {
                self.sweeps_per_call = (n / 2).max(1);
                return Ok(false);
            }
            let left = (deadline - now).as_secs_f64();
            self.sweeps_per_call = ((0.25 * left / per_sweep.max(1e-7)) as usize).clamp(1, 10_000);
        }
    }
}
