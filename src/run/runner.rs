//! The UI's side of the run protocol: it sends the host ([`Host`]) the
//! app's commands as [`Request`]s and keeps what the host posts (the
//! solution view, the field, the criterion curves, the simulated scene),
//! so that the UI reads it at once, wherever the host works. It holds no
//! simulation. What it answers before the host has handled a request (a
//! scene's check, whether a simulation exists, the run's mode) it works
//! out as the host will; the host's next post has the last word.
//!
//! [`Host`]: crate::run::host::Host

use std::sync::mpsc::{self, Receiver, Sender};

use cdca::scene::{SceneFile, SolverKind};
use cdca::{CriterionCurve, Scene};
use web_time::Instant;

use crate::results::field::{FieldKey, FieldSampler, FieldSamples};
use crate::results::replay::Replay;
use crate::results::solution::SolutionView;
use crate::run::RunMode;
use crate::run::host::{self, growth_solver};
use crate::run::link::Link;
use crate::run::protocol::{Post, Request, Shown};

/// What the UI shows of the host's simulation, and the link to it.
pub struct Runner {
    link: Link,
    /// Requests sent (the host's posts say how many it handled).
    sent: u64,
    /// The host's last post, as the UI shows it.
    shown: Shown,
    field: FieldSampler,
    /// Each tip's criterion curve, from the host's last solved view.
    curves: Vec<Option<CriterionCurve>>,
    /// The simulated scene.
    scene: Option<Scene>,
    /// The growth run's steps, for the replay.
    replay: Replay,
    /// The edited scene, checked, or why it is invalid.
    checked: Result<Scene, String>,
    /// The edited scene differs from the simulated one.
    stale: bool,
    /// A simulation exists (as the host will have it once it has handled
    /// every request sent).
    has_sim: bool,
    /// The run's mode until the host has handled the requests sent.
    expected_mode: Option<RunMode>,
    pace: Option<usize>,
    accelerate_growth: bool,
    /// The field wanted, as last sent.
    field_wanted: Option<FieldKey>,
    /// Runs kept for Undo tell the host when they are dropped.
    next_kept: u64,
    forgotten: (Sender<u64>, Receiver<u64>),
    error: Option<String>,
    /// The host's answer to Export fields, until the app saves it.
    fields: Option<Result<String, String>>,
}

/// A run kept by Undo ([`Runner::take_run`], [`Runner::restore_run`]):
/// what the UI showed of it; the host keeps its simulation under `id`
/// until this is restored or dropped.
pub struct KeptRun {
    id: Option<u64>,
    view: SolutionView,
    field: Option<FieldSamples>,
    replay: Replay,
    forget: Sender<u64>,
}

impl KeptRun {
    /// Growth steps done, as the status prints them.
    pub fn steps(&self) -> usize {
        self.view.steps_done
    }
}

impl Drop for KeptRun {
    fn drop(&mut self) {
        if let Some(id) = self.id {
            // the runner is gone only with the host
            let _ = self.forget.send(id);
        }
    }
}

/// Full solves faster than this are redone automatically after an edit.
pub const QUICK_SOLVE_SECONDS: f64 = 0.25;

impl Runner {
    /// The runner of a host reached through `link`.
    pub fn new(link: Link) -> Self {
        Self {
            link,
            sent: 0,
            shown: Shown {
                field_done: true,
                ..Shown::default()
            },
            field: FieldSampler::default(),
            curves: Vec::new(),
            scene: None,
            replay: Replay::default(),
            checked: Err("no scene yet".to_owned()),
            stale: false,
            has_sim: false,
            expected_mode: None,
            pace: None,
            accelerate_growth: true,
            field_wanted: None,
            next_kept: 0,
            forgotten: mpsc::channel(),
            error: None,
            fields: None,
        }
    }

    fn send(&mut self, request: Request) {
        self.sent += 1;
        self.link.send(request);
    }

    /// Sends the request and, in-process, takes the host's post at once
    /// (so that what the UI reads next is the host's answer).
    fn ask(&mut self, request: Request, mode: Option<RunMode>) {
        self.send(request);
        self.expected_mode = mode;
        if !self.link.is_away() {
            self.take_posts(None);
        }
    }

    /// Takes the host's posts (in-process, after the host has worked until
    /// `deadline`, if given).
    fn take_posts(&mut self, deadline: Option<Instant>) {
        while let Ok(id) = self.forgotten.1.try_recv() {
            self.send(Request::ForgetRun(id));
        }
        for post in self.link.posts(deadline) {
            self.take(post);
        }
    }

    fn take(&mut self, post: Post) {
        match post {
            Post::Shown(shown) => self.show(*shown),
            Post::Fields(vtu) => self.fields = Some(vtu),
            Post::Failed(e) => {
                // nothing runs any more
                self.shown.mode = RunMode::Paused;
                self.shown.field_done = true;
                self.expected_mode = Some(RunMode::Paused);
                self.error = Some(e);
            }
        }
    }

    /// Shows a post of the host: the view, the field and the curves; the
    /// replay records it.
    fn show(&mut self, mut shown: Shown) {
        if let Some(field) = shown.field.take() {
            self.field.show(field);
        }
        if let Some(curves) = shown.curves.take() {
            self.curves = curves;
        }
        if let Some(scene) = shown.scene.take() {
            self.scene = Some(scene);
        }
        if let Some(e) = shown.error.take() {
            self.error = Some(e);
        }
        if shown.growing {
            self.replay
                .record(&shown.view, shown.at_step_load, self.field.current());
        }
        if shown.handled >= self.sent {
            self.expected_mode = None;
            self.has_sim = shown.has_sim;
        }
        if !shown.has_sim {
            self.scene = None;
        }
        self.shown = shown;
    }

    /// The host's work until `deadline` in-process, or its posts since the
    /// last frame; whether the field the canvas wants is complete (a job
    /// of the app waits until it is, so that what is shown is consistent).
    pub fn advance(&mut self, deadline: Instant) -> bool {
        self.take_posts(Some(deadline));
        self.shown.field_done
    }

    // --- what the UI reads ----------------------------------------------

    /// The scene simulated.
    pub fn scene(&self) -> Option<&Scene> {
        self.scene.as_ref()
    }

    /// A simulation exists (or will, once the host has built it).
    pub fn has_simulation(&self) -> bool {
        self.has_sim
    }

    /// The simulation has growth steps.
    pub fn is_grown(&self) -> bool {
        self.shown.grown
    }

    /// Quadrature points the simulation still has to integrate.
    pub fn points_to_integrate(&self) -> Option<usize> {
        self.shown.points_to_integrate
    }

    /// σ_θθ and τ_rθ around tip `tip` of the state shown.
    pub fn criterion_curve(&self, tip: usize) -> Option<CriterionCurve> {
        self.curves.get(tip).cloned().flatten()
    }

    /// The field the canvas wants whenever the state has one (its version
    /// is the host's choice).
    pub fn want_field(&mut self, key: Option<FieldKey>) {
        let key = key.map(|k| FieldKey { version: 0, ..k });
        if key != self.field_wanted {
            self.field_wanted = key;
            self.send(Request::WantField(key));
        }
    }

    /// The error of a run or a build since the last call, once.
    pub fn take_error(&mut self) -> Option<String> {
        self.error.take()
    }

    /// What the UI shows of the simulation.
    pub fn view(&self) -> &SolutionView {
        &self.shown.view
    }

    /// The run's steps as stored for the replay.
    pub fn replay(&self) -> &Replay {
        &self.replay
    }

    /// The sampled field of the canvas.
    pub fn field(&self) -> &FieldSampler {
        &self.field
    }

    /// Fraction of the field being sampled, if one is.
    pub fn field_progress(&self) -> Option<f32> {
        self.shown.field_progress
    }

    /// The host has the field the canvas wants, or nothing to sample.
    pub fn field_done(&self) -> bool {
        self.shown.field_done
    }

    pub fn mode(&self) -> RunMode {
        self.expected_mode.unwrap_or(self.shown.mode)
    }

    /// A run is in progress.
    pub fn is_running(&self) -> bool {
        self.mode() != RunMode::Paused
    }

    /// The host works away from the UI's thread (a thread of its own, a
    /// Web Worker).
    pub fn is_away(&self) -> bool {
        self.link.is_away()
    }

    /// The host works on a thread of its own and has work (a run, a field
    /// to sample): the UI need not repaint but when it posts (it repaints
    /// the UI through `waker`, the app's context).
    pub fn works_away(&mut self, waker: &egui::Context) -> bool {
        self.link.set_waker(waker);
        self.is_away() && (self.is_running() || !self.shown.field_done)
    }

    /// The edited scene differs from the simulated one.
    pub fn is_stale(&self) -> bool {
        self.stale
    }

    /// Wall time of the last full solve, s.
    pub fn last_solve_seconds(&self) -> Option<f64> {
        self.shown.last_solve_seconds
    }

    /// The host's own time so far, s ([`Shown::host_seconds`]).
    pub fn host_seconds(&self) -> f64 {
        self.shown.host_seconds
    }

    /// Wall time of the last discretisation build, s.
    pub fn last_build_seconds(&self) -> f64 {
        self.shown.last_build_seconds
    }

    /// Sweeps per frame while relaxing or growing (None: as many as the
    /// frame budget allows).
    pub fn pace(&self) -> Option<usize> {
        self.pace
    }

    /// Growth with the automaton runs the multigrid-accelerated automaton.
    pub fn accelerate_growth(&self) -> bool {
        self.accelerate_growth
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
        let s = &self.shown;
        scene.solver.kind == SolverKind::Direct
            && s.last_solve_seconds.map_or(n <= SMALL, |t| {
                t + s.last_build_seconds < QUICK_SOLVE_SECONDS
                    && n <= 4 * s.last_solve_elements.max(SMALL)
            })
    }

    /// The solver growth uses (or will use) on this simulation, or on a
    /// simulation of `scene` when none is built yet.
    pub fn growth_solver_kind(&self, scene: &SceneFile) -> SolverKind {
        match self.shown.growth_solver {
            Some(kind) if self.has_sim => kind,
            _ => growth_solver(&scene.solver, self.accelerate_growth).kind,
        }
    }

    /// The edited scene as last checked, or why it is invalid.
    pub fn checked(&self) -> Result<&Scene, String> {
        self.checked.as_ref().map_err(Clone::clone)
    }

    /// Whether an edit during a drag can leave the solution shown for
    /// [`edit_during_drag`](Self::edit_during_drag): no run goes on but a
    /// drag's solve or the check of the last Solve from bonded faces.
    pub fn can_follow_drag(&self) -> bool {
        !self.is_running() || self.is_previewing() || self.shown.checking_second_start
    }

    /// The run under way solves a dragged scene (see
    /// [`follow_drag`](Self::follow_drag)).
    pub fn is_previewing(&self) -> bool {
        self.mode() == RunMode::SolvingDrag
    }

    // --- what the commands change ---------------------------------------

    /// Marks the simulation stale for the edited `scene` and checks it.
    fn check(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.stale = true;
        self.checked = host::check(scene);
        self.checked.as_ref().map(|_| ()).map_err(Clone::clone)
    }

    /// Forgets the simulation after an edit: `scene` is only checked
    /// (cheap; `Scene::try_from`); the discretisation is built when solver
    /// work is asked for.
    pub fn invalidate(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.replay.clear();
        self.field.clear();
        self.has_sim = false;
        self.ask(
            Request::Invalidate(Box::new(scene.clone())),
            Some(RunMode::Paused),
        );
        self.check(scene)
    }

    /// An edit during a drag that the solves follow
    /// ([`follow_drag`](Self::follow_drag); see
    /// [`can_follow_drag`](Self::can_follow_drag)): the scene is only
    /// checked; a solve of an earlier position goes on, and the view and
    /// the field keep showing the last solved one. An invalid scene waits
    /// for the release, which says why.
    pub fn edit_during_drag(&mut self, scene: &SceneFile) {
        let _ = self.check(scene);
        let mode = self.shown.checking_second_start.then_some(RunMode::Paused);
        self.ask(Request::EditDuringDrag(Box::new(scene.clone())), mode);
    }

    /// Starts the solve of the dragged scene when the last one has ended
    /// and its field is shown, if the scene changed since and is valid
    /// (an invalid one waits for the release, which says why). The
    /// simulation is built on the last one's discretisation
    /// (`Simulation::with_scene`), solved as Solve solves it but for the
    /// check from bonded faces, and replaces the view and the field when
    /// it ends. Returns whether a solve started (its errors come as the
    /// host's, [`take_error`](Self::take_error)).
    pub fn follow_drag(&mut self) -> bool {
        if !self.stale
            || self.is_running()
            || self.shown.field_progress.is_some()
            || self.checked.is_err()
        {
            return false;
        }
        self.stale = false;
        self.has_sim = true;
        self.ask(Request::FollowDrag, Some(RunMode::SolvingDrag));
        true
    }

    /// After a drag whose last position is solved, or being solved
    /// ([`follow_drag`](Self::follow_drag)): that solve stands as Solve's
    /// (the same fresh start), and its check from bonded faces runs when
    /// it has ended.
    pub fn check_after_drag(&mut self) {
        self.ask(Request::CheckAfterDrag, None);
    }

    /// Another scene is opened: the last solve's contact verdict (see
    /// [`SolutionView::all_faces_open`]) no longer applies.
    pub fn forget_contact(&mut self) {
        self.ask(Request::ForgetContact, None);
    }

    /// A kept run of what is on screen with `replay`, under a new id.
    fn keep(&mut self, replay: Replay) -> (u64, KeptRun) {
        self.next_kept += 1;
        let id = self.next_kept;
        let kept = KeptRun {
            id: Some(id),
            view: self.shown.view.clone(),
            field: self.field.current().cloned(),
            replay,
            forget: self.forgotten.0.clone(),
        };
        (id, kept)
    }

    /// The run on screen (growth steps done), moved out for Undo before
    /// Open, Reset or an edit replaces it; `None` without one. The kept
    /// simulation's factor is freed (the next solve factorises again).
    pub fn take_run(&mut self) -> Option<KeptRun> {
        if self.stale || self.shown.view.history.is_empty() || !self.has_sim {
            return None;
        }
        let replay = std::mem::take(&mut self.replay);
        let (id, kept) = self.keep(replay);
        self.has_sim = false;
        self.ask(Request::TakeRun(id), Some(RunMode::Paused));
        Some(kept)
    }

    /// Brings back a run [`take_run`](Self::take_run) kept, as it was on
    /// screen, with `scene` (the edited scene it was run from) as the
    /// edited scene. What was on screen is dropped: take it first.
    pub fn restore_run(&mut self, mut kept: KeptRun, scene: &SceneFile) {
        let Some(id) = kept.id.take() else {
            return;
        };
        self.field.clear();
        if let Some(field) = kept.field.take() {
            self.field.show(field);
        }
        self.replay = std::mem::take(&mut kept.replay);
        self.curves.clear();
        self.has_sim = true;
        // a kept run's scene was valid when it ran
        let _ = self.check(scene);
        self.stale = false;
        self.ask(
            Request::RestoreRun(id, Box::new(scene.clone())),
            Some(RunMode::Paused),
        );
    }

    /// Builds a simulation of `scene` (checked; nothing solved yet).
    pub fn rebuild(&mut self, scene: &SceneFile) -> Result<(), String> {
        self.replay.clear();
        self.field.clear();
        self.check(scene)?;
        self.stale = false;
        self.has_sim = true;
        self.ask(
            Request::Rebuild(Box::new(scene.clone())),
            Some(RunMode::Paused),
        );
        Ok(())
    }

    /// Solves now, in slices: the direct solver one contact iteration (one
    /// factorisation) at a time at most, the iterative ones animated. The
    /// solve starts from the state `cdca solve` starts from on the same
    /// scene, so that its contact states and K do not depend on what ran
    /// before.
    ///
    /// After growth, the grown scene is solved on a simulation of its own,
    /// and the run is returned, as it was on screen, for Undo.
    pub fn solve(&mut self) -> Option<KeptRun> {
        // (the run's steps stay in the plots)
        let kept = (self.has_sim && self.shown.grown).then(|| self.keep(self.replay.clone()).1);
        let keep = kept.as_ref().and_then(|k| k.id);
        self.ask(Request::Solve { keep }, Some(RunMode::Relaxing));
        kept
    }

    /// One sweep of the current relaxation (starting one if needed).
    pub fn step(&mut self) {
        self.ask(Request::Step, Some(RunMode::Paused));
    }

    /// Relaxes until converged, animated: the current relaxation goes on
    /// (one is started if none was).
    pub fn relax(&mut self) {
        self.ask(Request::Relax, Some(RunMode::Relaxing));
    }

    /// Starts growth (`one`: a single step, then the solve of the grown
    /// cracks), from an unloaded rebuild before the first step.
    pub fn start_growth(&mut self, one: bool) {
        let mode = if one {
            RunMode::GrowingOne
        } else {
            RunMode::Growing
        };
        self.ask(Request::StartGrowth { one }, Some(mode));
    }

    /// Stops the run in progress where it is (it can go on later; a direct
    /// solve starts again at the next Solve).
    pub fn pause(&mut self) {
        self.ask(Request::Pause, Some(RunMode::Paused));
    }

    /// Sweeps per frame while relaxing or growing (None: as many as the
    /// frame budget allows).
    pub fn set_pace(&mut self, pace: Option<usize>) {
        self.pace = pace;
        self.ask(Request::SetPace(pace), None);
    }

    /// In a browser's frames while the job also works between frames: a
    /// growth call that would overrun the frame waits for that work
    /// (`Pacer::set_leave_long`).
    pub fn leave_long_calls(&mut self, on: bool) {
        if !self.link.is_away() {
            self.send(Request::LeaveLongCalls(on));
        }
    }

    /// Growth with the automaton runs its multigrid-accelerated form (from
    /// the next growth run).
    pub fn set_accelerate_growth(&mut self, on: bool) {
        self.accelerate_growth = on;
        self.ask(Request::SetAccelerateGrowth(on), None);
    }

    /// Asks the host for the fields of the solution as a VTU file
    /// (ParaView); [`take_fields`](Self::take_fields) has them once they
    /// come.
    pub fn request_fields(&mut self) {
        self.ask(Request::ExportFields, None);
    }

    /// The host's answer to [`request_fields`](Self::request_fields), once.
    pub fn take_fields(&mut self) -> Option<Result<String, String>> {
        self.fields.take()
    }
}
