//! The simulation, the run in progress on it (a [`Task`]), and the copies
//! of its state that the UI shows: the solution view and the sampled
//! field. Its state changes only through the methods the app's commands
//! call, and through its run advancing.

use cdca::report::OtherSolutionReport;
use cdca::scene::{ContactUpdate, SceneFile, SolverKind};
use cdca::{CriterionCurve, Scene, Simulation, SolveError};
use web_time::Instant;

use crate::results::field::{FieldKey, FieldSampler, FieldSamples, LIVE_FIELD_INTERVAL};
use crate::results::replay::Replay;
use crate::results::solution::{SecondStart, SolutionView};
use crate::run::grower::{Grower, Update};
use crate::run::pacer::Pacer;
use crate::run::task::{Progress, Task};
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

/// The simulation and everything derived from it. (Independent flags,
/// so bools.)
#[allow(clippy::struct_excessive_bools)]
pub struct Runner {
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
    /// `start_relaxation` was called on the current simulation.
    relaxation_started: bool,
    /// Sweeps per call of relaxation and growth.
    pacer: Pacer,
    view: SolutionView,
    field: FieldSampler,
    /// The growth run's steps, for the replay.
    replay: Replay,
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
    /// The solution version the canvas's field shows (or is sampling).
    field_version: u64,
    /// When the field last moved to a newer version.
    field_moved_at: Option<Instant>,
    /// The field moves to the latest version at the next frame, however
    /// recent the last move: a growth step's solve at the load it records
    /// (λ_cr, or the load increment's λ), shown before its tips are
    /// extended.
    show_now: bool,
    /// The field the canvas wants ([`want_field`](Self::want_field)).
    field_wanted: Option<FieldKey>,
    /// Natively, the growth thread while it has the simulation (`sim` is
    /// then `None` and `run` a copy of the run it advances).
    grower: Option<Grower>,
    /// Growth runs on a thread (`Grower`): natively (in a browser there
    /// is none, `io::IN_BROWSER`).
    growth_thread: bool,
    /// Repaints the UI when the growth thread has an update.
    waker: Option<egui::Context>,
    /// Each tip's criterion curve, from the growth thread's last solved
    /// update (the inspector's curve while the thread has the simulation).
    curves: Vec<Option<CriterionCurve>>,
    /// The error of a run that ended on the growth thread while the UI
    /// took the simulation back, shown at the next frame.
    ended_error: Option<String>,
}

/// A run's simulation and what the UI showed of it, kept by Undo
/// ([`Runner::take_run`], [`Runner::restore_run`]).
pub struct KeptRun {
    sim: Simulation,
    view: SolutionView,
    field: Option<FieldSamples>,
    replay: Replay,
    growth_ready: bool,
}

impl KeptRun {
    /// Growth steps done, as the status prints them.
    pub fn steps(&self) -> usize {
        self.view.steps_done
    }
}

impl Default for Runner {
    fn default() -> Self {
        Self {
            checked: Err("no scene yet".to_owned()),
            sim: None,
            run: None,
            second_start: None,
            check_second_start: false,
            spare: None,
            relaxation_started: false,
            pacer: Pacer::default(),
            view: SolutionView::default(),
            field: FieldSampler::default(),
            replay: Replay::default(),
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
            grower: None,
            growth_thread: true,
            waker: None,
            curves: Vec::new(),
            ended_error: None,
        }
    }
}

/// Full solves faster than this are redone automatically after an edit.
pub const QUICK_SOLVE_SECONDS: f64 = 0.25;

/// Largest mesh the workbench solves with the direct solver, in elements
/// (400 × 400). Its numeric factorisation runs in slices across frames,
/// but the stiffness pattern and its symbolic analysis are one piece each,
/// which holds the window still, and the whole solve takes natively 1.3 s
/// and 0.45 GB at 300 × 300,
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

impl Runner {
    // --- what the UI reads ----------------------------------------------

    /// The simulation, unless the growth thread has it (see
    /// [`park`](Self::park)).
    pub fn simulation(&self) -> Option<&Simulation> {
        self.sim.as_ref()
    }

    /// The scene simulated (the growth thread's while it has the
    /// simulation).
    pub fn scene(&self) -> Option<&Scene> {
        if let Some(g) = &self.grower {
            return Some(g.scene());
        }
        self.sim.as_ref().map(Simulation::scene)
    }

    /// σ_θθ and τ_rθ around tip `tip` of the state shown.
    pub fn criterion_curve(&self, tip: usize) -> Option<CriterionCurve> {
        match &self.sim {
            Some(sim) => sim.criterion_curve(tip),
            None => self.curves.get(tip).cloned().flatten(),
        }
    }

    /// Natively, whether growth runs on a thread of its own (default) or
    /// in frame slices as in the browser.
    pub fn set_growth_thread(&mut self, on: bool) {
        self.growth_thread = on;
    }

    /// The field the canvas wants whenever the state has one (its
    /// version aside): natively the growth thread samples it at each
    /// step's load.
    pub fn want_field(&mut self, key: Option<FieldKey>) {
        self.field_wanted = key;
        if let Some(g) = &self.grower {
            g.want_field(key);
        }
    }

    /// The error of a run that ended while the UI took the simulation
    /// back from the growth thread, once.
    pub fn take_error(&mut self) -> Option<String> {
        self.ended_error.take()
    }

    /// What the UI shows of the simulation.
    pub fn view(&self) -> &SolutionView {
        &self.view
    }

    /// The sampled field of the canvas.
    /// The run's steps as stored for the replay.
    pub fn replay(&self) -> &Replay {
        &self.replay
    }

    pub fn field(&self) -> &FieldSampler {
        &self.field
    }

    pub fn mode(&self) -> RunMode {
        self.run.as_ref().map_or(RunMode::Paused, Run::mode)
    }

    /// A run is in progress.
    pub fn is_running(&self) -> bool {
        self.run.is_some()
    }

    /// The edited scene differs from the simulated one.
    pub fn is_stale(&self) -> bool {
        self.stale
    }

    /// Wall time of the last full solve, s.
    pub fn last_solve_seconds(&self) -> Option<f64> {
        self.last_solve_seconds
    }

    /// Wall time of the last discretisation build, s.
    pub fn last_build_seconds(&self) -> f64 {
        self.last_build_seconds
    }

    /// Sweeps per frame while relaxing or growing (None: as many as the
    /// frame budget allows).
    pub fn pace(&self) -> Option<usize> {
        self.pacer.fixed()
    }

    /// Growth with the automaton runs the multigrid-accelerated automaton.
    pub fn accelerate_growth(&self) -> bool {
        self.accelerate_growth
    }

    fn solver_kind(&self) -> SolverKind {
        self.sim
            .as_ref()
            .map_or(SolverKind::Direct, |s| s.scene().solver.kind)
    }

    /// Whether a re-solve of `scene` after an edit is cheap enough to do
    /// unasked: the direct solver, the last build and solve was quick, and
    /// the mesh has at most four times the elements of that solve's (or of
    /// 80 × 80; before any solve, meshes up to 80 × 80). A direct solve grows
    /// faster than the mesh (200² → 400² took 5.9 times as long), so a mesh
    /// refined tenfold in the panel waits for Solve instead of holding the
    /// window still.
    pub fn solve_is_quick(&self, scene: &SceneFile) -> bool {
        const SMALL: usize = 6400;
        let n = scene.mesh.nx.saturating_mul(scene.mesh.ny);
        scene.solver.kind == SolverKind::Direct
            && self.last_solve_seconds.map_or(n <= SMALL, |s| {
                s + self.last_build_seconds < QUICK_SOLVE_SECONDS
                    && n <= 4 * self.last_solve_elements.max(SMALL)
            })
    }

    /// The solver growth uses (or will use) on this simulation, or on a
    /// simulation of `scene` when none is built yet.
    pub fn growth_solver_kind(&self, scene: &SceneFile) -> SolverKind {
        if let Some(g) = &self.grower {
            return g.scene().solver.kind;
        }
        match &self.sim {
            Some(sim) if self.growth_ready || !sim.history().is_empty() => sim.scene().solver.kind,
            Some(sim) => growth_solver(&sim.scene().solver, self.accelerate_growth).kind,
            None => growth_solver(&scene.solver, self.accelerate_growth).kind,
        }
    }

    // --- what the commands change ---------------------------------------

    /// Forgets the simulation after an edit: `scene` is only checked
    /// (cheap; `Scene::try_from`); the discretisation is built when solver
    /// work is asked for.
    pub fn invalidate(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.park();
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
        self.replay.clear();
        // a reopened run's steps count before anything is solved, as
        // `Simulation::steps_done` counts them once it is built
        // and their events (`growth.resume.history`), as
        // `Simulation::earlier` holds them once it is built (which names a
        // bad entry)
        let resume = scene.growth.resume.as_ref();
        self.view.steps_done = resume.map_or(0, |r| r.steps);
        self.view.earlier = resume
            .and_then(|r| cdca::report::StepEvents::read(r, scene.cracks.len()).ok())
            .unwrap_or_default();
        self.field.clear();
        self.check(scene)
    }

    /// Marks the simulation stale for the edited `scene` and checks it
    /// (cheap; `Scene::try_from`).
    fn check(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.stale = true;
        self.checked = interactive_mesh(scene)
            .and_then(|()| Scene::try_from(scene.clone()).map_err(|e| e.to_string()));
        self.checked.as_ref().map(|_| ()).map_err(Clone::clone)
    }

    /// Whether an edit during a drag can leave the solution shown for
    /// [`edit_during_drag`](Self::edit_during_drag): no run goes on but a
    /// drag's solve or the check of the last Solve from bonded faces.
    pub fn can_follow_drag(&self) -> bool {
        self.run.is_none() || self.is_previewing() || self.second_start.is_some()
    }

    /// An edit during a drag that the solves follow
    /// ([`follow_drag`](Self::follow_drag); see
    /// [`can_follow_drag`](Self::can_follow_drag)): the scene is only
    /// checked; a solve of an earlier position goes on, and the view and
    /// the field keep showing the last solved one. An invalid scene waits
    /// for the release, which says why.
    pub fn edit_during_drag(&mut self, scene: &SceneFile) {
        self.park();
        if self.second_start.is_some() {
            // the check of the solve before the drag no longer applies
            self.drop_second_start();
            self.run = None;
        }
        let _ = self.check(scene);
    }

    /// Starts the solve of the dragged scene when the last one has ended
    /// and its field is shown, if the scene changed since and is valid
    /// (an invalid one waits for the release, which says why). The
    /// simulation is built on the last one's discretisation
    /// (`Simulation::with_scene`), solved as Solve solves it but for the
    /// check from bonded faces, and replaces the view and the field when
    /// it ends. Returns whether a solve started.
    pub fn follow_drag(&mut self) -> Result<bool, String> {
        self.park();
        if !self.stale || self.run.is_some() || self.field.progress().is_some() {
            return Ok(false);
        }
        let Ok(scene) = self.checked.clone() else {
            return Ok(false);
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
        Ok(true)
    }

    /// The run under way solves a dragged scene (see
    /// [`follow_drag`](Self::follow_drag)).
    pub fn is_previewing(&self) -> bool {
        self.run == Some(Run::DragSolve)
    }

    /// After a drag whose last position is solved, or being solved
    /// ([`follow_drag`](Self::follow_drag)): that solve stands as Solve's
    /// (the same fresh start), and its check from bonded faces runs when
    /// it has ended.
    pub fn check_after_drag(&mut self) {
        self.park();
        self.check_second_start = true;
        if !self.is_previewing() && self.start_second_start() {
            // the run goes on for the check alone
            self.run = Some(Run::Relax);
        }
    }

    /// The edited scene as last checked by [`invalidate`](Self::invalidate),
    /// or why it is invalid.
    pub fn checked(&self) -> Result<&Scene, String> {
        self.checked.as_ref().map_err(Clone::clone)
    }

    /// Another scene is opened: the last solve's contact verdict (see
    /// [`SolutionView::all_faces_open`]) no longer applies.
    pub fn forget_contact(&mut self) {
        self.view.forget_contact();
    }

    /// The run on screen (growth steps done), moved out for Undo before
    /// Open, Reset or an edit replaces it; `None` without one. The kept
    /// simulation's factor is freed (the next solve factorises again).
    pub fn take_run(&mut self) -> Option<KeptRun> {
        self.park();
        if self.stale || self.view.history.is_empty() {
            return None;
        }
        let mut sim = self.sim.take()?;
        if !sim.is_relaxing() {
            sim.release_solver();
        }
        let replay = std::mem::take(&mut self.replay);
        Some(self.keep(sim, replay))
    }

    /// `sim` with what the UI shows of it and the run's `replay`; the run
    /// on it stops.
    fn keep(&mut self, sim: Simulation, replay: Replay) -> KeptRun {
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
        KeptRun {
            sim,
            view: self.view.clone(),
            field: self.field.current().cloned(),
            replay,
            growth_ready: self.growth_ready,
        }
    }

    /// Brings back a run [`take_run`](Self::take_run) kept, as it was on
    /// screen, with `scene` (the edited scene it was run from) as the
    /// edited scene. What was on screen is dropped: take it first.
    pub fn restore_run(&mut self, kept: KeptRun, scene: &SceneFile) {
        self.park();
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
        self.relaxation_started = false;
        self.pacer.restart();
        self.curves.clear();
        // caches key on the version: the restored view is the newest
        let version = self.view.version + 1;
        self.view = kept.view;
        self.view.version = version;
        self.field.clear();
        if let Some(mut field) = kept.field {
            field.key.version = version;
            self.field.show(field);
        }
        self.replay = kept.replay;
        self.growth_ready = kept.growth_ready;
        self.sim = Some(kept.sim);
        // a kept run's scene was valid when it ran
        let _ = self.check(scene);
        self.stale = false;
    }

    /// Builds a simulation of `scene` (checked; nothing solved yet).
    pub fn rebuild(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.park();
        self.invalidate(scene)?;
        let valid = self.checked()?.clone();
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
        Ok(())
    }

    /// Solves now, in slices across frames: the direct solver one contact
    /// iteration (one factorisation) at a time at most, the iterative ones
    /// animated. The solve starts from the state `cdca solve` starts from
    /// on the same scene ([`fresh_start`](Self::fresh_start)), so that its
    /// contact states and K do not depend on what ran before.
    ///
    /// After growth, the grown scene is solved on a simulation of its own
    /// (its discretisation built anew: the run's cannot be both reused and
    /// kept), and the run's simulation is returned, as it was on screen,
    /// for Undo.
    pub fn solve(&mut self) -> Result<Option<KeptRun>, String> {
        self.park();
        let kept = self.fresh_start()?;
        self.drop_second_start();
        self.check_second_start = true;
        // the direct solve too runs as a relaxation, one contact iteration
        // (one factorisation) per slice at most, so that no frame holds a
        // whole solve (in a browser 0.2 s at 60 × 60)
        if self.solver_kind() == SolverKind::Direct && self.sim.is_some() {
            self.direct_solve = Some(0.0);
        }
        self.relaxation_started = false;
        self.relax();
        Ok(kept)
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
    /// and the run's simulation is returned (see [`solve`](Self::solve)).
    fn fresh_start(&mut self) -> Result<Option<KeptRun>, String> {
        let Some(sim) = self.sim.as_ref() else {
            return Ok(None);
        };
        let touched = sim.is_solved()
            || sim.is_relaxing()
            || self.relaxation_started
            || self.growth_ready
            || !sim.history().is_empty();
        if !touched {
            return Ok(None);
        }
        let edited = self.checked()?.clone();
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
        let old = self.sim.take();
        let (old, kept) = match old {
            Some(mut sim) if run => {
                sim.release_solver();
                let replay = self.replay.clone();
                (None, Some(self.keep(sim, replay)))
            }
            old => (old, None),
        };
        self.build(old, scene)?;
        if grown {
            // the run's steps stay in the plots
            self.view.earlier = self.view.history.clone();
        }
        self.growth_ready = false;
        self.relaxation_started = false;
        self.refresh(false, None);
        Ok(kept)
    }

    /// One sweep of the current relaxation (starting one if needed).
    pub fn step(&mut self) -> Result<(), String> {
        self.park();
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
    pub fn relax(&mut self) {
        self.park();
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
    pub fn start_growth(&mut self, one: bool) -> Result<(), String> {
        self.park();
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
    pub fn pause(&mut self) {
        self.park();
        self.drop_second_start();
        self.run = None;
        self.direct_solve = None;
    }

    /// Sweeps per frame while relaxing or growing (None: as many as the
    /// frame budget allows).
    pub fn set_pace(&mut self, pace: Option<usize>) {
        self.park();
        self.pacer.set_fixed(pace);
    }

    /// In a browser's frames while the job also works between frames: a
    /// growth call that would overrun the frame waits for that work
    /// ([`Pacer::set_leave_long`]).
    pub fn leave_long_calls(&mut self, on: bool) {
        self.pacer.set_leave_long(on);
    }

    /// Growth with the automaton runs its multigrid-accelerated form (from
    /// the next growth run).
    pub fn set_accelerate_growth(&mut self, on: bool) {
        self.accelerate_growth = on;
    }

    // --- the field ------------------------------------------------------

    /// The solution version the canvas's field should show: the latest
    /// when paused; while a run goes on, the latest at most every
    /// [`LIVE_FIELD_INTERVAL`] and only once the previous field is complete,
    /// so that sampling takes a small share of the frames; during the
    /// final solve after growth, the last solved one until it is solved.
    pub fn field_version(&mut self) -> u64 {
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

    /// The field of a growth step's load waits to be shown (see
    /// [`field_version`](Self::field_version)).
    pub fn field_due_now(&self) -> bool {
        self.show_now
    }

    fn refresh(&mut self, solved: bool, relax: Option<cdca::RelaxStatus>) {
        if let Some(sim) = &self.sim {
            self.view.refresh(sim, solved, relax);
        }
    }
}

/// The field task: samples the field `key` of the runner's current state.
/// Finished when there is nothing (more) to sample; the job waits until
/// then, so that what is shown is consistent. While a dragged scene is
/// being solved, the last solved position's field stays.
pub struct FieldTask<'a> {
    runner: &'a mut Runner,
    key: Option<FieldKey>,
}

impl<'a> FieldTask<'a> {
    /// The sampling of `key` (None: nothing wanted) on `runner`'s state.
    pub fn new(runner: &'a mut Runner, key: Option<FieldKey>) -> Self {
        Self { runner, key }
    }
}

impl Task for FieldTask<'_> {
    fn advance(&mut self, deadline: Instant) -> Result<Progress, String> {
        let r = &mut *self.runner;
        if r.grower.is_some() {
            // the growth thread samples it (`want_field`)
            return Ok(Progress::Finished);
        }
        Ok(match (&r.sim, self.key) {
            // (a dragged scene's simulation is sampled once solved)
            (Some(sim), Some(key)) if r.view.has_field() && !r.is_previewing() => {
                if r.field.advance(sim, key, deadline) {
                    Progress::Finished
                } else {
                    Progress::Working
                }
            }
            _ => Progress::Finished,
        })
    }
}

impl Runner {
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
    fn advance_second_start(&mut self, deadline: Instant) -> Progress {
        let Some((other, _)) = self.second_start.as_mut() else {
            return Progress::Finished;
        };
        loop {
            let start = Instant::now();
            let n = self.pacer.sweeps();
            match other.relax(n) {
                Ok(s) if !s.finished => {
                    if !self.pacer.another_fits(start, n, deadline) {
                        return Progress::Working;
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
                    return Progress::Finished;
                }
            }
        }
    }
}

impl Task for Runner {
    /// The run in progress until `deadline`; the view is refreshed after
    /// the slice. When the solve of the final cracks finds the specimen
    /// split (no stiffness against a piece's rigid motion), the run ends
    /// showing the last solved state.
    fn advance(&mut self, deadline: Instant) -> Result<Progress, String> {
        if self.second_start.is_some() {
            return Ok(self.advance_second_start(deadline));
        }
        if let Some(progress) = self.advance_thread() {
            return progress;
        }
        let (Some(sim), Some(run)) = (self.sim.as_mut(), self.run.as_mut()) else {
            self.run = None;
            return Ok(Progress::Finished);
        };
        let start = Instant::now();
        let result = run.advance(sim, &mut self.pacer, deadline);
        if let Some(t) = self.direct_solve.as_mut() {
            *t += start.elapsed().as_secs_f64();
        }
        self.after_slice(result)
    }
}

impl Runner {
    /// After a slice of the run (on the UI's thread, or the last piece of
    /// the growth thread's): the view refreshed, the replay's step
    /// recorded, and the end of the run, or its error, dealt with.
    fn after_slice(&mut self, result: Result<Slice, SolveError>) -> Result<Progress, String> {
        let (Some(sim), Some(run)) = (self.sim.as_ref(), self.run.as_ref()) else {
            self.run = None;
            return Ok(Progress::Finished);
        };
        let final_solve = run.in_final_solve();
        let drag_solve = *run == Run::DragSolve;
        let elements = sim.scene().mesh.nx * sim.scene().mesh.ny;
        let free_piece = sim.free_piece();
        if matches!(run, Run::Grow(_)) {
            // a later Relax starts its own relaxation
            self.relaxation_started = false;
            // the field of the step's load (λ_cr, or the load increment's
            // λ) is sampled before the tips move on: after a split it is
            // the field kept, at the λ printed
            self.show_now |= sim.at_step_load();
        }
        let solved = sim.is_solved();
        let growing = matches!(run, Run::Grow(_));
        let at_step_load = sim.at_step_load();
        match result {
            Ok(slice) => {
                // a drag's solve is shown when it ends
                if !drag_solve || slice.progress == Progress::Finished {
                    self.refresh(solved, slice.status);
                }
                if growing {
                    self.replay
                        .record(&self.view, at_step_load, self.field.current());
                }
                if slice.progress == Progress::Finished {
                    if let Some(t) = self.direct_solve.take() {
                        self.last_solve_seconds = Some(t);
                        self.last_solve_elements = elements;
                    }
                    if self.start_second_start() {
                        // the run goes on for the check alone
                        self.run = Some(Run::Relax);
                        return Ok(Progress::Working);
                    }
                    self.run = None;
                }
                Ok(slice.progress)
            }
            Err(SolveError::NotPositiveDefinite { .. }) if final_solve || free_piece.is_some() => {
                let piece = free_piece;
                self.refresh(false, None);
                self.view.mark_split();
                self.view.free_piece = piece;
                self.run = None;
                self.direct_solve = None;
                Ok(Progress::Finished)
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

/// Natively, growth on a thread of its own ([`Grower`]).
impl Runner {
    /// Growth goes to the thread: a growth run without a fixed pace (a
    /// pace set by the user is watched a call per frame, as in the
    /// browser).
    fn wants_thread(&self) -> bool {
        self.growth_thread
            && matches!(self.run, Some(Run::Grow(_)))
            && self.sim.is_some()
            && self.pacer.fixed().is_none()
    }

    /// This frame's part of a growth run on the thread (`None`: no
    /// growth for the thread): starts the thread, or shows its updates in
    /// order (a frame ends with an update carrying a step's field, so
    /// that every step's field is shown), and once it has ended, takes
    /// the simulation back and ends the run as a slice would.
    fn advance_thread(&mut self) -> Option<Result<Progress, String>> {
        if self.grower.is_none() {
            if !self.wants_thread() {
                return None;
            }
            let (Some(sim), Some(run)) = (self.sim.take(), self.run.clone()) else {
                return None;
            };
            // a later Relax starts its own relaxation
            self.relaxation_started = false;
            self.grower = Some(Grower::start(
                sim,
                run,
                self.pacer.clone(),
                self.view.clone(),
                self.field_wanted,
                self.waker.clone(),
            ));
            return Some(Ok(Progress::Working));
        }
        loop {
            match self.grower.as_ref()?.next_update() {
                Ok(Some(u)) => {
                    let shown = u.at_step_load && u.field.is_some();
                    self.show_update(u);
                    if shown {
                        return Some(Ok(Progress::Working));
                    }
                }
                Ok(None) => return Some(Ok(Progress::Working)),
                Err(()) => break,
            }
        }
        Some(self.take_back().unwrap_or(Ok(Progress::Working)))
    }

    /// What the growth thread sent, shown as a slice's result is: the
    /// view, the field and the curves; the replay records it.
    fn show_update(&mut self, u: Update) {
        self.view = u.view;
        self.curves = u.curves;
        if let Some(field) = u.field {
            self.field.show(field);
        }
        self.replay
            .record(&self.view, u.at_step_load, self.field.current());
    }

    /// Takes the simulation back from the growth thread: waits for its
    /// piece under way (it stops when asked, or has ended), shows its
    /// last updates, and puts the simulation, the run and the pacer back;
    /// if the run had ended there, ends it as a slice would. `None`: no
    /// thread, or it was stopped before the run's end.
    fn take_back(&mut self) -> Option<Result<Progress, String>> {
        let g = self.grower.take()?;
        g.stop();
        let (returned, updates) = g.join();
        for u in updates {
            self.show_update(u);
        }
        self.sim = Some(returned.sim);
        self.run = Some(returned.run);
        self.pacer = returned.pacer;
        self.curves.clear();
        returned.end.map(|end| self.after_slice(end))
    }
}

impl Runner {
    /// The growth thread has the simulation: the UI need not repaint but
    /// when it sends an update (it repaints the UI through `waker`, the
    /// app's context).
    pub fn grows_on_thread(&mut self, waker: &egui::Context) -> bool {
        if self.waker.is_none() {
            self.waker = Some(waker.clone());
        }
        self.grower.is_some()
    }

    /// Natively, takes the simulation back from the growth thread, if it
    /// has it, for whatever comes next (an edit, Pause, Save, an export):
    /// the run stands where the thread stopped and goes on at the next
    /// frame unless changed. Its error, if it ended in one, is kept for
    /// [`take_error`](Self::take_error). Nothing in a browser.
    pub fn park(&mut self) {
        if let Some(Err(e)) = self.take_back() {
            self.ended_error = Some(e);
        }
    }
}
