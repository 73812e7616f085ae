//! The host: the simulation, the run in progress on it, the field sampled
//! from it, and the runs kept for Undo. It changes only through the
//! [`Request`]s it handles and through its run advancing
//! ([`Host::advance`]), and tells the UI what to show in [`Post`]s. The UI
//! reaches it through a link (`run::link`): in-process, or on a thread of
//! its own.

use std::cell::Cell;
use std::collections::HashMap;

use cdca::report::OtherSolutionReport;
use cdca::scene::{ContactUpdate, SceneFile, SolverKind};
use cdca::{Scene, Simulation, SolveError};
use web_time::Instant;

use crate::results::field::{FieldKey, FieldSampler, FieldSamples, LIVE_FIELD_INTERVAL};
use crate::results::solution::{SecondStart, SolutionView};
use crate::run::pacer::Pacer;
use crate::run::protocol::{PIECE, Post, Request, Shown};
use crate::run::task::Progress;
use crate::run::{Run, RunMode, Slice};

/// Relative residual to which iterative solvers solve in growth: the
/// criterion needs the SIFs and the kink angle, and on the default scene
/// this tolerance gives K_I and K_II within 1e-6 relative of the direct
/// solution and the same angles to 0.001° (automaton and multigrid-CG,
/// measured with `cdca solve`); the contact tolerance (1e-8) is not
/// reachable with a looser linear solve.
pub const GROWTH_TOLERANCE: f64 = 1e-8;

/// The solver settings used in growth: iterative solvers at
/// [`GROWTH_TOLERANCE`]; with `accelerate`, the plain automaton replaced by
/// its multigrid-accelerated form (CG with the automaton's sweeps as
/// smoother and a coarse-grid correction), unless the scene asks for the
/// paper's in-sweep contact, a rule of the automaton's own cell visits.
pub fn growth_solver(spec: &cdca::scene::SolverSpec, accelerate: bool) -> cdca::scene::SolverSpec {
    let mut spec = spec.clone();
    if spec.kind != SolverKind::Direct {
        spec.tolerance = GROWTH_TOLERANCE;
    }
    if accelerate
        && spec.kind == SolverKind::Automaton
        && spec.contact_update == ContactUpdate::Outer
    {
        spec.kind = SolverKind::Multigrid;
    }
    spec
}

/// Largest mesh the workbench solves with the direct solver, in elements
/// (400 × 400). Its numeric factorisation runs in slices,
/// but the stiffness pattern and its symbolic analysis are one piece each,
/// which holds the host still (and, in-process, the window), and the whole
/// solve takes natively 1.3 s and 0.45 GB at 300 × 300,
/// 3.3 s and 0.8 GB at 400 × 400, 26 s and 4.7 GB at 800 × 800 (more than
/// a browser tab can have). The iterative solvers work in slices and show
/// their progress.
pub const DIRECT_MAX_ELEMENTS: usize = 160_000;

/// Largest mesh the workbench takes with any solver, in elements (800 ×
/// 800: 1.1 GB with multigrid-CG, within a browser tab's 4 GB). The
/// command line takes up to [`cdca::scene::MAX_ELEMENTS`].
pub const MAX_ELEMENTS: usize = 640_000;

/// Refuses, before any work, a mesh the workbench cannot solve without
/// holding the window still or running out of memory, naming the limit and
/// the way round it.
pub fn interactive_mesh(scene: &SceneFile) -> Result<(), String> {
    let (nx, ny) = (scene.mesh.nx, scene.mesh.ny);
    let n = nx.saturating_mul(ny);
    let field = format!("scene field `mesh` = {nx} × {ny} ({n} elements)");
    if n > MAX_ELEMENTS {
        Err(format!(
            "{field}: the workbench takes up to {MAX_ELEMENTS} elements (800 × 800, \
             about 1.1 GB with multigrid-CG); run finer meshes with `cdca solve` or \
             `cdca grow` from the command line"
        ))
    } else if scene.solver.kind == SolverKind::Direct && n > DIRECT_MAX_ELEMENTS {
        Err(format!(
            "{field}: the direct solver analyses the whole mesh's pattern in one piece, \
             which would hold the window still (a solve at 400 × 400 takes 3.3 s and \
             0.8 GB); it is offered up to \
             {DIRECT_MAX_ELEMENTS} elements. Choose multigrid-CG, which solves in slices \
             and shows its progress, or use the command line"
        ))
    } else {
        Ok(())
    }
}

/// `scene` checked as the workbench takes it (cheap; `Scene::try_from`).
pub fn check(scene: &SceneFile) -> Result<Scene, String> {
    interactive_mesh(scene).and_then(|()| Scene::try_from(scene.clone()).map_err(|e| e.to_string()))
}

thread_local! {
    /// Requests handled and slices advanced by a host on this thread.
    static HOST_CALLS: Cell<u64> = const { Cell::new(0) };
}

/// Requests handled and slices advanced by a host on the calling thread
/// (on a page, that page's): the UI's thread makes none when its host
/// runs elsewhere.
pub fn host_calls_on_this_thread() -> u64 {
    HOST_CALLS.with(Cell::get)
}

fn count_call() {
    HOST_CALLS.with(|c| c.set(c.get() + 1));
}

/// A run kept for Undo: its simulation and what was shown of it.
struct KeptSim {
    sim: Simulation,
    view: SolutionView,
    field: Option<FieldSamples>,
    growth_ready: bool,
}

/// The simulation and everything derived from it. (Independent flags,
/// so bools.)
#[allow(clippy::struct_excessive_bools)]
pub struct Host {
    /// The edited scene, checked, or why it is invalid.
    checked: Result<Scene, String>,
    sim: Option<Simulation>,
    /// The run in progress (None: paused).
    run: Option<Run>,
    /// After Solve, the same problem from bonded faces, and the first
    /// solve's report: where faces close, Coulomb friction need not have
    /// one solution, and the app says when it has another.
    second_start: Option<(Simulation, cdca::report::SolveReport)>,
    /// The solve under way was started by Solve: check it from bonded
    /// faces when it ends converged with faces closed.
    check_second_start: bool,
    /// The simulation an edit invalidated, kept until the next build: its
    /// discretisation is reused when the edit left it unchanged
    /// (`Simulation::with_scene`: a load, the faces' friction, the solver);
    /// its solver's factor is freed when it becomes the spare.
    spare: Option<Simulation>,
    /// Runs kept for Undo, by the UI's id.
    kept: HashMap<u64, KeptSim>,
    /// `start_relaxation` was called on the current simulation.
    relaxation_started: bool,
    /// Sweeps per call of relaxation and growth.
    pacer: Pacer,
    view: SolutionView,
    field: FieldSampler,
    /// The edited scene differs from the simulated one.
    stale: bool,
    /// Wall time of the last full solve, s (for a direct solve run in
    /// slices, the time of its slices).
    last_solve_seconds: Option<f64>,
    /// The direct solve in progress: the time its slices took so far, s.
    direct_solve: Option<f64>,
    /// Elements of the mesh of that solve.
    last_solve_elements: usize,
    /// Wall time of the last build (`Simulation::new` or `with_scene`), s.
    last_build_seconds: f64,
    /// Growth with the automaton runs the multigrid-accelerated automaton.
    accelerate_growth: bool,
    /// The growth solver settings were applied to the current simulation.
    growth_ready: bool,
    /// The solution version the field shows (or is sampling).
    field_version: u64,
    /// When the field last moved to a newer version.
    field_moved_at: Option<Instant>,
    /// The field moves to the latest version at once, however recent the
    /// last move: a growth step's solve at the load it records (λ_cr, or
    /// the load increment's λ), shown before its tips are extended.
    show_now: bool,
    /// The field the UI wants (its version aside).
    field_wanted: Option<FieldKey>,
    // --- what the next post carries --------------------------------------
    handled: u64,
    /// The last slice ended at a growth step's load.
    at_step_load: bool,
    /// A growth run advanced since the last post.
    growing: bool,
    /// A field completed since the last post.
    new_field: bool,
    /// The simulated scene may have changed since the last post.
    scene_changed: bool,
    /// The view version whose criterion curves were last posted.
    curves_version: Option<u64>,
    error: Option<String>,
    /// Time spent handling requests, advancing and making posts, s.
    busy_seconds: f64,
}

impl Default for Host {
    fn default() -> Self {
        Self {
            checked: Err("no scene yet".to_owned()),
            sim: None,
            run: None,
            second_start: None,
            check_second_start: false,
            spare: None,
            kept: HashMap::new(),
            relaxation_started: false,
            pacer: Pacer::default(),
            view: SolutionView::default(),
            field: FieldSampler::default(),
            stale: false,
            last_solve_seconds: None,
            direct_solve: None,
            last_solve_elements: 0,
            last_build_seconds: 0.0,
            accelerate_growth: true,
            growth_ready: false,
            field_version: 0,
            field_moved_at: None,
            show_now: false,
            field_wanted: None,
            handled: 0,
            at_step_load: false,
            growing: false,
            new_field: false,
            scene_changed: true,
            curves_version: None,
            error: None,
            busy_seconds: 0.0,
        }
    }
}

impl Host {
    // --- the protocol ----------------------------------------------------

    /// Handles `request`; the answer to [`Request::ExportFields`] is
    /// returned, every other change shows in the next [`shown`](Self::shown).
    pub fn handle(&mut self, request: Request) -> Option<Post> {
        let start = Instant::now();
        let post = self.handle_timed(request);
        self.busy_seconds += start.elapsed().as_secs_f64();
        post
    }

    fn handle_timed(&mut self, request: Request) -> Option<Post> {
        count_call();
        self.handled += 1;
        let result = match request {
            Request::Invalidate(scene) => {
                self.invalidate(&scene);
                Ok(())
            }
            Request::Rebuild(scene) => self.rebuild(&scene),
            Request::EditDuringDrag(scene) => {
                self.edit_during_drag(&scene);
                Ok(())
            }
            Request::FollowDrag => self.follow_drag(),
            Request::CheckAfterDrag => {
                self.check_after_drag();
                Ok(())
            }
            Request::ForgetContact => {
                self.view.forget_contact();
                Ok(())
            }
            Request::TakeRun(id) => {
                self.take_run(id);
                Ok(())
            }
            Request::RestoreRun(id, scene) => {
                self.restore_run(id, &scene);
                Ok(())
            }
            Request::ForgetRun(id) => {
                self.kept.remove(&id);
                Ok(())
            }
            Request::Solve { keep } => self.solve(keep),
            Request::Step => self.step(),
            Request::Relax => {
                self.relax();
                Ok(())
            }
            Request::StartGrowth { one } => self.start_growth(one),
            Request::Pause => {
                self.pause();
                Ok(())
            }
            Request::SetPace(pace) => {
                self.pacer.set_fixed(pace);
                Ok(())
            }
            Request::SetAccelerateGrowth(on) => {
                self.accelerate_growth = on;
                Ok(())
            }
            Request::LeaveLongCalls(on) => {
                self.pacer.set_leave_long(on);
                Ok(())
            }
            Request::WantField(key) => {
                self.field_wanted = key;
                Ok(())
            }
            Request::ExportFields => return Some(Post::Fields(self.fields_vtu())),
        };
        if let Err(e) = result {
            self.error = Some(e);
        }
        None
    }

    /// What the UI shows now; what it carries once (a new field, the
    /// scene, an error) is not carried again.
    pub fn shown(&mut self) -> Shown {
        let start = Instant::now();
        let mut shown = self.shown_now();
        self.busy_seconds += start.elapsed().as_secs_f64();
        shown.host_seconds = self.busy_seconds;
        shown
    }

    fn shown_now(&mut self) -> Shown {
        let sim = self.sim.as_ref();
        let solved = self.view.solved;
        Shown {
            handled: self.handled,
            view: self.view.clone(),
            at_step_load: std::mem::take(&mut self.at_step_load),
            growing: std::mem::take(&mut self.growing),
            field: if std::mem::take(&mut self.new_field) {
                self.field.current().cloned()
            } else {
                None
            },
            field_progress: self.field.progress(),
            field_done: !self.field_pending(),
            mode: self.run.as_ref().map_or(RunMode::Paused, Run::mode),
            checking_second_start: self.second_start.is_some(),
            scene: if std::mem::take(&mut self.scene_changed) {
                sim.map(|s| s.scene().clone())
            } else {
                None
            },
            has_sim: sim.is_some(),
            grown: sim.is_some_and(|s| !s.history().is_empty()),
            growth_solver: sim.map(|sim| {
                if self.growth_ready || !sim.history().is_empty() {
                    sim.scene().solver.kind
                } else {
                    growth_solver(&sim.scene().solver, self.accelerate_growth).kind
                }
            }),
            points_to_integrate: sim.map(|s| s.xfem().points_to_integrate()),
            curves: (self.curves_version != Some(self.view.version)).then(|| {
                self.curves_version = Some(self.view.version);
                match sim {
                    Some(sim) if solved => (0..self.view.tips.len())
                        .map(|t| sim.criterion_curve(t))
                        .collect(),
                    _ => Vec::new(),
                }
            }),
            last_solve_seconds: self.last_solve_seconds,
            last_solve_elements: self.last_solve_elements,
            last_build_seconds: self.last_build_seconds,
            error: self.error.take(),
            host_seconds: 0.0,
        }
    }

    /// Work is left: a run, the check from bonded faces, or a field to
    /// sample.
    pub fn is_busy(&self) -> bool {
        self.run.is_some() || self.second_start.is_some() || self.field_pending()
    }

    /// A run or the check from bonded faces goes on.
    fn is_running(&self) -> bool {
        self.run.is_some() || self.second_start.is_some()
    }

    /// Growth steps of the simulation.
    fn steps(&self) -> usize {
        self.sim.as_ref().map_or(0, |s| s.history().len())
    }

    /// Sweeps per call are fixed by the user (the run is watched a call at
    /// a time).
    pub fn is_paced(&self) -> bool {
        self.pacer.fixed().is_some()
    }

    /// A piece of [`PIECE`] of the work, for a host away from the UI
    /// (a thread, a worker); whether it is worth a post at once: it
    /// reached a step's load, recorded a step, completed a field, started
    /// or ended the run, or the run is paced (watched a call at a time).
    pub fn work_piece(&mut self) -> bool {
        let (steps, running) = (self.steps(), self.is_running());
        self.advance(Instant::now() + PIECE);
        self.at_step_load
            || self.new_field
            || self.steps() != steps
            || running != self.is_running()
            || !self.is_busy()
            || self.is_paced()
    }

    /// The work until about `deadline`: the field the UI wants first (a run
    /// waits until it is complete, so that what is shown is consistent),
    /// then the run in progress, then, at a growth step's load, that
    /// step's field at once, before its tips move on.
    pub fn advance(&mut self, deadline: Instant) {
        count_call();
        let start = Instant::now();
        if self.advance_field(deadline) {
            self.advance_run(deadline);
            if self.show_now {
                self.advance_field(deadline);
            }
        }
        self.busy_seconds += start.elapsed().as_secs_f64();
    }

    // --- the commands ----------------------------------------------------

    /// Forgets the simulation after an edit: `scene` is only checked
    /// (cheap; `Scene::try_from`); the discretisation is built when solver
    /// work is asked for.
    fn invalidate(&mut self, scene: &SceneFile) {
        self.drop_second_start();
        if let Some(mut sim) = self.sim.take() {
            // kept for its discretisation only: its factor is freed now
            sim.release_solver();
            self.spare = Some(sim);
        }
        self.run = None;
        self.direct_solve = None;
        self.relaxation_started = false;
        self.growth_ready = false;
        self.view.clear();
        // a reopened run's steps count before anything is solved, as
        // `Simulation::steps_done` counts them once it is built, and their
        // events (`growth.resume.history`), as `Simulation::earlier` holds
        // them once it is built (which names a bad entry)
        let resume = scene.growth.resume.as_ref();
        self.view.steps_done = resume.map_or(0, |r| r.steps);
        self.view.earlier = resume
            .and_then(|r| cdca::report::StepEvents::read(r, scene.cracks.len()).ok())
            .unwrap_or_default();
        self.field.clear();
        self.scene_changed = true;
        self.check(scene);
    }

    /// Marks the simulation stale for the edited `scene` and checks it.
    fn check(&mut self, scene: &SceneFile) {
        self.stale = true;
        self.checked = check(scene);
    }

    /// An edit during a drag that the solves follow: the scene is only
    /// checked; a solve of an earlier position goes on, and the view and
    /// the field keep showing the last solved one.
    fn edit_during_drag(&mut self, scene: &SceneFile) {
        if self.second_start.is_some() {
            // the check of the solve before the drag no longer applies
            self.drop_second_start();
            self.run = None;
        }
        self.check(scene);
    }

    /// Starts the solve of the dragged scene when the last one has ended
    /// and its field is shown, if the scene changed since and is valid
    /// (an invalid one waits for the release, which says why). The
    /// simulation is built on the last one's discretisation
    /// (`Simulation::with_scene`), solved as Solve solves it but for the
    /// check from bonded faces, and replaces the view and the field when
    /// it ends.
    fn follow_drag(&mut self) -> Result<(), String> {
        if !self.stale || self.run.is_some() || self.field.progress().is_some() {
            return Ok(());
        }
        let Ok(scene) = self.checked.clone() else {
            return Ok(());
        };
        // its factor goes on as the storage of the new one's first
        // factorisation (redone only where the values changed)
        let old = self.sim.take().or_else(|| self.spare.take());
        self.build(old, scene)?;
        self.stale = false;
        self.relaxation_started = false;
        self.pacer.restart();
        self.start_relaxation();
        self.direct_solve = (self.solver_kind() == SolverKind::Direct).then_some(0.0);
        self.run = Some(Run::DragSolve);
        Ok(())
    }

    fn is_previewing(&self) -> bool {
        self.run == Some(Run::DragSolve)
    }

    /// After a drag whose last position is solved, or being solved: that
    /// solve stands as Solve's (the same fresh start), and its check from
    /// bonded faces runs when it has ended.
    fn check_after_drag(&mut self) {
        self.check_second_start = true;
        if !self.is_previewing() && self.start_second_start() {
            // the run goes on for the check alone
            self.run = Some(Run::Relax);
        }
    }

    /// Keeps the run on screen under `id` for Undo (the UI kept what it
    /// showed of it); the kept simulation's factor is freed.
    fn take_run(&mut self, id: u64) {
        if self.stale || self.view.history.is_empty() {
            return;
        }
        let Some(mut sim) = self.sim.take() else {
            return;
        };
        if !sim.is_relaxing() {
            sim.release_solver();
        }
        self.scene_changed = true;
        self.keep(id, sim);
    }

    /// Keeps `sim` under `id` with what is shown of it; the run on it stops.
    fn keep(&mut self, id: u64, sim: Simulation) {
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
        let kept = KeptSim {
            sim,
            view: self.view.clone(),
            field: self.field.current().cloned(),
            growth_ready: self.growth_ready,
        };
        self.kept.insert(id, kept);
    }

    /// Brings back the run kept under `id`, as it was on screen, with
    /// `scene` (the edited scene it was run from) as the edited scene.
    fn restore_run(&mut self, id: u64, scene: &SceneFile) {
        let Some(kept) = self.kept.remove(&id) else {
            self.invalidate(scene);
            return;
        };
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
        self.relaxation_started = false;
        self.pacer.restart();
        // caches key on the version: the restored view is the newest
        let version = self.view.version + 1;
        self.view = kept.view;
        self.view.version = version;
        self.field.clear();
        if let Some(mut field) = kept.field {
            field.key.version = version;
            self.field.show(field);
            self.field_version = version;
        }
        self.growth_ready = kept.growth_ready;
        self.sim = Some(kept.sim);
        self.scene_changed = true;
        // a kept run's scene was valid when it ran
        self.check(scene);
        self.stale = false;
    }

    /// Builds a simulation of `scene` (checked; nothing solved yet).
    fn rebuild(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.invalidate(scene);
        let valid = self.checked.clone()?;
        let old = self.spare.take();
        self.build(old, valid)?;
        self.pacer.restart();
        self.stale = false;
        Ok(())
    }

    /// Makes the simulation of `scene`, on `old`'s discretisation where
    /// the scene leaves it unchanged (`Simulation::with_scene`), and times
    /// that build.
    fn build(&mut self, old: Option<Simulation>, scene: Scene) -> Result<(), String> {
        let start = Instant::now();
        let sim = match old {
            Some(old) => old.with_scene(scene),
            None => Simulation::new(scene),
        }
        .map_err(|e| e.to_string())?;
        self.last_build_seconds = start.elapsed().as_secs_f64();
        self.sim = Some(sim);
        self.scene_changed = true;
        Ok(())
    }

    fn solver_kind(&self) -> SolverKind {
        self.sim
            .as_ref()
            .map_or(SolverKind::Direct, |s| s.scene().solver.kind)
    }

    /// Solves now, in slices: the direct solver one contact iteration (one
    /// factorisation) at a time at most, the iterative ones animated. The
    /// solve starts from the state `cdca solve` starts from on the same
    /// scene ([`fresh_start`](Self::fresh_start)), so that its contact
    /// states and K do not depend on what ran before.
    ///
    /// After growth, the grown scene is solved on a simulation of its own
    /// (its discretisation built anew: the run's cannot be both reused and
    /// kept), and the run's simulation is kept under `keep`, for Undo.
    fn solve(&mut self, keep: Option<u64>) -> Result<(), String> {
        self.fresh_start(keep)?;
        self.drop_second_start();
        self.check_second_start = true;
        // the direct solve too runs as a relaxation, one contact iteration
        // (one factorisation) per slice at most
        if self.solver_kind() == SolverKind::Direct && self.sim.is_some() {
            self.direct_solve = Some(0.0);
        }
        self.relaxation_started = false;
        self.relax();
        Ok(())
    }

    /// Rebuilds the simulation from its scene unless it is untouched since
    /// its build: u = 0 and the contact states of the scene file (every
    /// face open, or `growth.resume`'s), as `cdca solve` starts. A solve
    /// warm-started from a solved state carries that state's slip into its
    /// own: on the default scene after the race, Solve used to end with
    /// 12 stick and 17 slip points instead of 29 slip, and then not
    /// converge. The discretisation is kept (`Simulation::with_scene`)
    /// unless growth changed the cracks; after growth the grown scene (as
    /// File ▸ Save writes it) is solved, with the panel's solver settings,
    /// and the run's simulation is kept under `keep` (see
    /// [`solve`](Self::solve)).
    fn fresh_start(&mut self, keep: Option<u64>) -> Result<(), String> {
        let Some(sim) = self.sim.as_ref() else {
            return Ok(());
        };
        let touched = sim.is_solved()
            || sim.is_relaxing()
            || self.relaxation_started
            || self.growth_ready
            || !sim.history().is_empty();
        if !touched {
            return Ok(());
        }
        let edited = self.checked.clone()?;
        let run = !sim.history().is_empty();
        // (a solve after a solve after growth solves the grown scene again)
        let grown = run || !self.view.earlier.is_empty();
        let scene = if grown {
            sim.scene()
                .edit(|s| s.solver = edited.solver.clone())
                .map_err(|e| e.to_string())?
        } else {
            edited
        };
        let old = match self.sim.take() {
            Some(mut sim) if run => {
                sim.release_solver();
                if let Some(id) = keep {
                    self.keep(id, sim);
                }
                None
            }
            old => old,
        };
        self.build(old, scene)?;
        if grown {
            // the run's steps stay in the plots
            self.view.earlier = self.view.history.clone();
        }
        self.growth_ready = false;
        self.relaxation_started = false;
        self.refresh(false, None);
        Ok(())
    }

    /// One sweep of the current relaxation (starting one if needed).
    fn step(&mut self) -> Result<(), String> {
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
        self.start_relaxation();
        let Some(sim) = self.sim.as_mut() else {
            return Ok(());
        };
        // a new simulation first integrates its elements (no sweep yet):
        // Step goes on to its one sweep
        let mut result = sim.relax(1);
        while result.as_ref().is_ok_and(|r| !r.finished) && !sim.is_relaxing() {
            result = sim.relax(1);
        }
        let solved = sim.is_solved();
        self.refresh(solved, result.as_ref().ok().copied());
        result.map(|_| ()).map_err(|e| e.to_string())
    }

    /// Relaxes until converged, animated: the current relaxation goes on
    /// (one is started if none was).
    fn relax(&mut self) {
        self.start_relaxation();
        if self.sim.is_some() {
            self.run = Some(Run::Relax);
        }
    }

    fn start_relaxation(&mut self) {
        if let Some(sim) = self.sim.as_mut()
            && !self.relaxation_started
        {
            sim.start_relaxation();
            self.relaxation_started = true;
        }
    }

    /// Starts growth (`one`: a single step, then the solve of the grown
    /// cracks): before the first step, the simulation is rebuilt unloaded
    /// with the growth solver settings ([`growth_solver`]), so that the
    /// load ramps up from zero as in `cdca grow` (a state solved at full
    /// load carries its friction history into the first, lower, load
    /// increment, where the contact iteration then fails to settle).
    fn start_growth(&mut self, one: bool) -> Result<(), String> {
        self.drop_second_start();
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
                // the same discretisation, started afresh with the growth
                // solver
                let old = self.sim.take();
                self.build(old, scene)?;
                self.relaxation_started = false;
                self.refresh(false, None);
            }
        }
        self.growth_ready = true;
        self.direct_solve = None;
        let steps = self.sim.as_ref().map_or(0, |s| s.history().len());
        self.run = Some(Run::grow(one.then_some(steps)));
        Ok(())
    }

    /// Stops the run in progress where it is (it can go on later; a direct
    /// solve starts again at the next Solve).
    fn pause(&mut self) {
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
    }

    /// The fields of the solution as a VTU file (ParaView).
    fn fields_vtu(&self) -> Result<String, String> {
        match self
            .sim
            .as_ref()
            .filter(|_| self.view.solved && !self.stale)
        {
            None => Err("solve the scene before exporting its fields".to_owned()),
            Some(sim) => Ok(crate::results::export::fields_vtu(
                sim.scene(),
                |p| sim.displacement_at(p),
                |p| sim.stress_at(p),
            )),
        }
    }

    fn refresh(&mut self, solved: bool, relax: Option<cdca::RelaxStatus>) {
        if let Some(sim) = &self.sim {
            self.view.refresh(sim, solved, relax);
        }
    }
}

/// The field.
impl Host {
    /// The solution version the field should show: the latest when
    /// paused; while a run goes on, the latest at most every
    /// [`LIVE_FIELD_INTERVAL`] and only once the previous field is complete,
    /// so that sampling takes a small share of the work; during the final
    /// solve after growth, the last solved one until it is solved.
    fn field_version(&mut self) -> u64 {
        let now = Instant::now();
        let due = self.run.is_none()
            || std::mem::take(&mut self.show_now)
            || (self.field.progress().is_none()
                && !self.run.as_ref().is_some_and(Run::in_final_solve)
                && self
                    .field_moved_at
                    .is_none_or(|t| (now - t).as_secs_f64() >= LIVE_FIELD_INTERVAL));
        if due && self.field_version != self.view.version {
            self.field_version = self.view.version;
            self.field_moved_at = Some(now);
        }
        self.field_version
    }

    /// The field wanted, at the version it should show, when the state has
    /// one to sample. While a dragged scene is being solved, the last
    /// solved position's field stays.
    fn field_key(&mut self) -> Option<FieldKey> {
        let key = self.field_wanted?;
        let version = self.field_version();
        self.has_field_to_sample()
            .then_some(FieldKey { version, ..key })
    }

    /// The state has a field to sample: a solution or a live iterate, but
    /// not a dragged scene's solve under way (the last solved position's
    /// field stays).
    fn has_field_to_sample(&self) -> bool {
        self.sim.is_some() && self.view.has_field() && !self.is_previewing()
    }

    /// A field is wanted and not yet sampled.
    fn field_pending(&self) -> bool {
        let Some(key) = self.field_wanted else {
            return false;
        };
        self.has_field_to_sample()
            && !self.field.is_current(&FieldKey {
                version: self.view.version,
                ..key
            })
            && (self.run.is_none() || self.field.progress().is_some() || self.show_now)
    }

    /// Samples the field wanted until `deadline`; true when it is complete
    /// (or nothing is to be sampled).
    fn advance_field(&mut self, deadline: Instant) -> bool {
        let Some(key) = self.field_key() else {
            return true;
        };
        let Some(sim) = self.sim.as_ref() else {
            return true;
        };
        if self.field.is_current(&key) {
            return true;
        }
        let done = self.field.advance(sim, key, deadline);
        self.new_field |= done;
        done
    }
}

/// The run.
impl Host {
    /// Forgets the check for another solution (a new solve, an edit, a
    /// pause, growth): what it would say no longer belongs to what is shown.
    fn drop_second_start(&mut self) {
        self.second_start = None;
        self.check_second_start = false;
        self.view.other_solution = None;
        self.view.second_start = SecondStart::NotRun;
    }

    /// After Solve has ended converged with faces closed: starts the same
    /// problem from bonded faces (the run goes on until it ends). Returns
    /// whether it started.
    fn start_second_start(&mut self) -> bool {
        let Some(sim) = self.sim.as_ref() else {
            return false;
        };
        let first = sim.report(0.0);
        let check = std::mem::take(&mut self.check_second_start)
            && OtherSolutionReport::worth_checking(&first);
        let Some(other) = check.then(|| sim.bonded_start().ok()).flatten() else {
            return false;
        };
        self.second_start = Some((other, first));
        self.view.second_start = SecondStart::Running;
        true
    }

    /// The solve from bonded faces until `deadline`; at its end the view
    /// says whether it found another solution, and the run ends. A solve
    /// that fails or does not converge says nothing about the first: no
    /// other solution is reported.
    fn advance_second_start(&mut self, deadline: Instant) {
        let Some((other, _)) = self.second_start.as_mut() else {
            return;
        };
        loop {
            let start = Instant::now();
            let n = self.pacer.sweeps();
            match other.relax(n) {
                Ok(s) if !s.finished => {
                    if !self.pacer.another_fits(start, n, deadline) {
                        return;
                    }
                }
                result => {
                    let (other, first) = self.second_start.take().expect("checked above");
                    self.view.other_solution = result
                        .ok()
                        .and_then(|_| {
                            OtherSolutionReport::between(&first, &other.report(0.0), "bonded")
                        })
                        .map(|o| o.sentence(&first.contact));
                    self.view.second_start = SecondStart::Done;
                    self.run = None;
                    return;
                }
            }
        }
    }

    /// The run in progress until `deadline`; the view is refreshed after
    /// the slice.
    fn advance_run(&mut self, deadline: Instant) {
        if self.second_start.is_some() {
            self.advance_second_start(deadline);
            return;
        }
        let (Some(sim), Some(run)) = (self.sim.as_mut(), self.run.as_mut()) else {
            self.run = None;
            return;
        };
        let start = Instant::now();
        let result = run.advance(sim, &mut self.pacer, deadline);
        if let Some(t) = self.direct_solve.as_mut() {
            *t += start.elapsed().as_secs_f64();
        }
        if let Err(e) = self.after_slice(result) {
            self.error = Some(e);
        }
    }

    /// After a slice of the run: the view refreshed, and the end of the
    /// run, or its error, dealt with. When the solve of the final cracks
    /// finds the specimen split (no stiffness against a piece's rigid
    /// motion), the run ends showing the last solved state.
    fn after_slice(&mut self, result: Result<Slice, SolveError>) -> Result<(), String> {
        let (Some(sim), Some(run)) = (self.sim.as_ref(), self.run.as_ref()) else {
            self.run = None;
            return Ok(());
        };
        let final_solve = run.in_final_solve();
        let drag_solve = *run == Run::DragSolve;
        let elements = sim.scene().mesh.nx * sim.scene().mesh.ny;
        let free_piece = sim.free_piece();
        let growing = matches!(run, Run::Grow(_));
        let at_step_load = sim.at_step_load();
        if growing {
            // a later Relax starts its own relaxation
            self.relaxation_started = false;
            // the field of the step's load (λ_cr, or the load increment's
            // λ) is sampled before the tips move on: after a split it is
            // the field kept, at the λ printed
            self.show_now |= at_step_load;
            self.at_step_load = at_step_load;
            self.growing = true;
            self.scene_changed = true;
        }
        let solved = sim.is_solved();
        match result {
            Ok(slice) => {
                // a drag's solve is shown when it ends
                if !drag_solve || slice.progress == Progress::Finished {
                    self.refresh(solved, slice.status);
                }
                if slice.progress == Progress::Finished {
                    if let Some(t) = self.direct_solve.take() {
                        self.last_solve_seconds = Some(t);
                        self.last_solve_elements = elements;
                    }
                    self.run = None;
                    if self.start_second_start() {
                        // the run goes on for the check alone
                        self.run = Some(Run::Relax);
                    }
                }
                Ok(())
            }
            Err(SolveError::NotPositiveDefinite { .. }) if final_solve || free_piece.is_some() => {
                self.refresh(false, None);
                self.view.mark_split();
                self.view.free_piece = free_piece;
                self.run = None;
                self.direct_solve = None;
                Ok(())
            }
            Err(e) => {
                self.refresh(solved, None);
                self.run = None;
                self.direct_solve = None;
                Err(e.to_string())
            }
        }
    }
}
