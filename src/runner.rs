//! Drives the solver inside the frame budget: the run mode, the
//! simulation, and the copies of its state that the UI shows.

use cdca::scene::{SceneFile, SolverKind};
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
    /// One growth step, then the solve of the grown cracks, then pause.
    GrowingOne,
}

/// Relative residual to which iterative solvers solve in growth: the
/// criterion needs the SIFs and the kink angle, and on the default scene
/// this tolerance gives K_I and K_II within 1e-6 relative of the direct
/// solution and the same angles to 0.001° (automaton and multigrid-CG,
/// measured with `cdca solve`); the contact tolerance (1e-8) is not
/// reachable with a looser linear solve.
pub const GROWTH_TOLERANCE: f64 = 1e-8;

/// While a run goes on, the canvas's field follows the solver at most this
/// often (sampled coarsely, one sample per element), s.
pub const LIVE_FIELD_INTERVAL: f64 = 0.15;

/// The solver settings used in growth: iterative solvers at
/// [`GROWTH_TOLERANCE`]; with `accelerate`, the plain automaton replaced by
/// its multigrid-accelerated form (CG with the automaton's sweeps as
/// smoother and a coarse-grid correction).
pub fn growth_solver(spec: &cdca::scene::SolverSpec, accelerate: bool) -> cdca::scene::SolverSpec {
    let mut spec = spec.clone();
    if spec.kind != SolverKind::Direct {
        spec.tolerance = GROWTH_TOLERANCE;
    }
    if accelerate && spec.kind == SolverKind::Automaton {
        spec.kind = SolverKind::Multigrid;
    }
    spec
}

/// The simulation and everything derived from it. (Independent flags,
/// so bools.)
#[allow(clippy::struct_excessive_bools)]
pub struct Runner {
    /// The edited scene, checked (None while it is invalid).
    checked: Option<Scene>,
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
    /// Sweeps per frame while relaxing or growing (None: as many as the
    /// frame budget allows).
    pub pace: Option<usize>,
    /// Growth with the automaton runs the multigrid-accelerated automaton.
    pub accelerate_growth: bool,
    /// The growth solver settings were applied to the current simulation.
    growth_ready: bool,
    /// Growth steps recorded when Grow one step was pressed: that run ends
    /// once one more is recorded (counted from the click, not per frame: a
    /// step completing at a frame's end used to let the run go on to the
    /// end of growth).
    one_step_from: usize,
    /// The solution version the canvas's field shows (or is sampling).
    field_version: u64,
    /// When the field last moved to a newer version.
    field_moved_at: Option<Instant>,
    /// The field moves to the latest version at the next frame, however
    /// recent the last move: a growth step's solve at λ_cr, shown before
    /// its tips are extended.
    show_now: bool,
}

impl Default for Runner {
    fn default() -> Self {
        Self {
            checked: None,
            sim: None,
            mode: RunMode::Paused,
            relaxation_started: false,
            sweeps_per_call: 1,
            view: SolutionView::default(),
            field: FieldSampler::default(),
            stale: false,
            last_solve_seconds: None,
            last_build_seconds: 0.0,
            frame_solver_seconds: 0.0,
            pace: None,
            accelerate_growth: true,
            growth_ready: false,
            one_step_from: 0,
            field_version: 0,
            field_moved_at: None,
            show_now: false,
        }
    }
}

/// Full solves faster than this are redone automatically after an edit.
pub const QUICK_SOLVE_SECONDS: f64 = 0.25;

impl Runner {
    /// Forgets the simulation after an edit: `scene` is only checked
    /// (cheap; `Scene::try_from`); the discretisation is built when solver
    /// work is asked for.
    pub fn invalidate(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.checked = None;
        self.sim = None;
        self.mode = RunMode::Paused;
        self.relaxation_started = false;
        self.growth_ready = false;
        self.view.clear();
        self.field.clear();
        self.stale = true;
        self.checked = Some(Scene::try_from(scene.clone()).map_err(|e| e.to_string())?);
        Ok(())
    }

    /// Builds a simulation of `scene` (checked; nothing solved yet).
    pub fn rebuild(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.invalidate(scene)?;
        let Some(valid) = self.checked.clone() else {
            unreachable!("invalidate keeps the checked scene or fails")
        };
        let start = Instant::now();
        let sim = Simulation::new(valid).map_err(|e| e.to_string())?;
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
    pub fn solve_is_quick(&self, scene: &SceneFile) -> bool {
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

    /// Starts growth (`one`: a single step, then the solve of the grown
    /// cracks): before the first step, the simulation is rebuilt unloaded
    /// with the growth solver settings ([`growth_solver`]), so that the
    /// load ramps up from zero as in `cdca grow` (a state solved at full
    /// load carries its friction history into the first, lower, load
    /// increment, where the contact iteration then fails to settle).
    pub fn start_growth(&mut self, one: bool) -> Result<(), String> {
        let Some(sim) = self.sim.as_ref() else {
            return Ok(());
        };
        if !self.growth_ready && sim.history().is_empty() {
            let spec = growth_solver(&sim.scene().solver, self.accelerate_growth);
            if spec != sim.scene().solver || sim.is_solved() || sim.is_relaxing() {
                let scene = sim
                    .scene()
                    .edit(|s| s.solver = spec)
                    .map_err(|e| e.to_string())?;
                let start = Instant::now();
                let sim = Simulation::new(scene).map_err(|e| e.to_string())?;
                self.last_build_seconds = start.elapsed().as_secs_f64();
                self.sim = Some(sim);
                self.relaxation_started = false;
                self.refresh(false, None);
            }
        }
        self.growth_ready = true;
        self.one_step_from = self.sim.as_ref().map_or(0, |s| s.history().len());
        self.mode = if one {
            RunMode::GrowingOne
        } else {
            RunMode::Growing
        };
        Ok(())
    }

    /// The solver growth uses (or will use) on this simulation, or on a
    /// simulation of `scene` when none is built yet.
    pub fn growth_solver_kind(&self, scene: &SceneFile) -> SolverKind {
        match &self.sim {
            Some(sim) if self.growth_ready || !sim.history().is_empty() => sim.scene().solver.kind,
            Some(sim) => growth_solver(&sim.scene().solver, self.accelerate_growth).kind,
            None => growth_solver(&scene.solver, self.accelerate_growth).kind,
        }
    }

    /// Runs `n` sweeps; returns whether the relaxation has finished (converged or capped).
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
        let solved = sim.is_solved();
        self.refresh(solved, status);
        let status = result.map_err(|e| e.to_string())?;
        Ok(status.finished)
    }

    /// Growth until `deadline`, in resumable chunks (a few solver sweeps or
    /// one contact iteration each; the chunk that completes a step also
    /// extends the tips and rebuilds the discretisation); with a pace, one
    /// chunk of that many sweeps. `one`: stop after one step, once the
    /// grown cracks are solved. Returns whether the run ended.
    fn grow_chunk(&mut self, deadline: Instant, one: bool) -> Result<bool, String> {
        let Some(sim) = self.sim.as_mut() else {
            return Ok(true);
        };
        let steps = self.one_step_from;
        let n = self.pace.unwrap_or(self.sweeps_per_call).max(1);
        let mut result = Ok(false);
        loop {
            if sim.growth_finished().is_some() {
                result = Ok(true);
                break;
            }
            let t0 = Instant::now();
            match sim.advance_growth(n) {
                Err(e) => {
                    result = Err(e.to_string());
                    break;
                }
                Ok(report) => {
                    if one && report.is_none() && sim.history().len() > steps && sim.is_solved() {
                        result = Ok(true);
                        break;
                    }
                }
            }
            if sim.at_critical_load() {
                // the field of λ_cr is sampled before the tips move on
                self.show_now = true;
                break;
            }
            if self.pace.is_some() {
                break;
            }
            // no call that would overrun the frame if it took as long as
            // the last one (setup calls, e.g. a factorisation, come in
            // runs); sweeps: a call of about a quarter of the budget left
            let now = Instant::now();
            if now + (now - t0) >= deadline {
                break;
            }
            let per_sweep = (now - t0).as_secs_f64() / n as f64;
            let left = (deadline - now).as_secs_f64();
            self.sweeps_per_call = ((0.25 * left / per_sweep.max(1e-7)) as usize).clamp(1, 10_000);
        }
        let finished = sim.growth_finished().is_some();
        self.relaxation_started = false;
        let solved = sim.is_solved();
        self.refresh(solved, None);
        result.map(|done| done || finished)
    }

    /// The solution version the canvas's field should show: the latest
    /// when paused; while a run goes on, the latest at most every
    /// [`LIVE_FIELD_INTERVAL`] and only once the previous field is complete,
    /// so that sampling takes a small share of the frames.
    pub fn field_version(&mut self) -> u64 {
        let now = Instant::now();
        let due = self.mode == RunMode::Paused
            || std::mem::take(&mut self.show_now)
            || (self.field.progress().is_none()
                && self
                    .field_moved_at
                    .is_none_or(|t| (now - t).as_secs_f64() >= LIVE_FIELD_INTERVAL));
        if due && self.field_version != self.view.version {
            self.field_version = self.view.version;
            self.field_moved_at = Some(now);
        }
        self.field_version
    }

    fn refresh(&mut self, solved: bool, relax: Option<cdca::RelaxStatus>) {
        if let Some(sim) = &self.sim {
            self.view.refresh(sim, solved, relax);
        }
    }

    /// The frame's share of work within `budget`: first sampling the field
    /// of the current state (the solver waits until a field is complete, so
    /// what is shown is consistent), then solver work in the run mode with
    /// what is left. While a run goes on the field is coarse and refreshed
    /// at most every [`LIVE_FIELD_INTERVAL`], so the solver advances every
    /// frame. Returns an error to show.
    pub fn tick(&mut self, budget: Duration, field_key: Option<FieldKey>) -> Result<(), String> {
        let start = Instant::now();
        let deadline = start + budget;
        self.frame_solver_seconds = 0.0;
        if let (Some(sim), Some(key)) = (&self.sim, field_key)
            && self.view.has_field()
            && !self.field.is_current(&key)
        {
            let complete = self.field.work(sim, key, deadline);
            if !complete || self.mode == RunMode::Paused {
                self.frame_solver_seconds = start.elapsed().as_secs_f64();
                return Ok(());
            }
        }
        if self.mode == RunMode::Paused {
            return Ok(());
        }
        let outcome = match self.mode {
            RunMode::Paused => Ok(false),
            RunMode::Relaxing => self.relax_for(deadline),
            RunMode::Growing => self.grow_chunk(deadline, false),
            RunMode::GrowingOne => self.grow_chunk(deadline, true),
        };
        if let Some(key) = field_key.filter(|_| self.show_now) {
            // a growth step reached λ_cr: its field, from this frame on
            let version = self.field_version();
            if let Some(sim) = &self.sim {
                self.field.work(sim, FieldKey { version, ..key }, deadline);
            }
        }
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
    /// that one call takes about a quarter of the remaining budget; with a
    /// pace, that many sweeps.
    fn relax_for(&mut self, deadline: Instant) -> Result<bool, String> {
        if let Some(n) = self.pace {
            return self.relax_chunk(n.max(1));
        }
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
