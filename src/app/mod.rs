//! **The app**: the frame loop that applies the user's commands to the
//! state and runs the job's work, the panels' and the canvas's frame, and
//! the browser's wrapper. Uses every part below it.
//!
//! - this file: `WorkbenchApp`, its state, layout, and the per-frame
//!   logic that applies the UI's commands and runs solver work inside the
//!   frame budget;
//! - `apply`: what each command does;
//! - `restore`: undo and redo applied;
//! - `web`, `web_work`: the page around the app in a browser, and the
//!   job's work between frames there.

mod apply;
mod restore;
#[cfg(target_arch = "wasm32")]
pub mod web;
#[cfg(target_arch = "wasm32")]
mod web_work;

use std::sync::{Arc, Mutex};

use cdca::CriterionCurve;
use cdca::scene::SceneFile;
use cdca::scene::SolverKind;
use egui::Ui;
use web_time::{Duration, Instant};

pub use crate::canvas::{CANVAS_LABEL, SECONDARY_COLOR, SECONDARY_KEY};
use crate::canvas::{Canvas, CanvasInput};
use crate::files::path_prompt::PathPrompt;
use crate::files::scenes;
use crate::panels;
use crate::plots::plot_tab::PlotTab;
use crate::results::field::{FieldKey, FieldKind};
use crate::run::RunMode;
use crate::run::link::Link;
use crate::run::runner::Runner;
use crate::run::task::Task;
use crate::run::timer::RunTimer;
use crate::state::command::Command;
use crate::state::edit::Editor;
use crate::state::frame_stats::FrameStats;
use crate::state::job::{Job, Waiting};
use crate::state::layout::Layout;
use crate::state::persist::Persisted;
use crate::state::settings::ViewSettings;
use crate::state::undo::UndoStack;
pub use crate::state::view::Message;
use crate::state::view::{AppView, RunStatus, ViewState};
use crate::study::file::{FileStudy, LoadedStudy, StudyFileSetup};
use crate::study::race::{self, Race};
use crate::study::{Study, StudySetup};

/// Most solver work per frame (the rest of a 60 Hz frame is left to
/// drawing).
pub const FRAME_BUDGET: Duration = Duration::from_millis(12);

/// The app's CPU time per frame aimed at: a frame's solver work gets what
/// the rest of the last frame (commands, UI) left of it, at most
/// [`FRAME_BUDGET`] and at least [`MIN_SOLVER_BUDGET`]. Natively the UI
/// takes 1–2 ms, so the solver gets its 12 ms; in a browser it takes 4–5 ms,
/// which a fixed 12 ms budget pushed to 17.5 ms at the 95th percentile.
pub const FRAME_TARGET: Duration = Duration::from_millis(15);

/// Least solver work per frame, however long the UI took.
pub const MIN_SOLVER_BUDGET: Duration = Duration::from_millis(4);

/// Height the canvas (with the replay bar above it) keeps whatever the
/// plot panel needs, points: a fifth of the window, from 110 on a phone's
/// 640 points to 150 from 750 points up (at 360 × 640 the story, the tabs
/// and a whole plot leave no more).
fn min_canvas_height(window: f32) -> f32 {
    (0.2 * window).clamp(110.0, 150.0)
}

/// The solver's budget in a frame after one whose work besides the
/// solver's took `rest` (see [`FRAME_TARGET`]).
pub fn solver_budget(rest: Duration) -> Duration {
    FRAME_TARGET
        .saturating_sub(rest)
        .clamp(MIN_SOLVER_BUDGET, FRAME_BUDGET)
}

/// How the app starts. (Independent flags, so bools.)
#[derive(Clone, Debug)]
#[allow(clippy::struct_excessive_bools)]
pub struct Options {
    /// Solve the first scene in the first frame.
    pub solve_on_start: bool,
    /// Re-solve after an edit when the solve is quick.
    pub auto_solve: bool,
    /// The scene to start on (None: the default scene).
    pub scene: Option<SceneFile>,
    /// Where that scene came from.
    pub scene_source: String,
    pub view: ViewSettings,
    /// A run to start after the first solve (command line `--run`).
    pub start_run: Option<StartRun>,
    /// Native file dialogs are tried (false: Save and Open ask for a path
    /// at once, as where no dialog service exists).
    pub file_dialogs: bool,
    /// Time the command line's run (`--time-run`): when it ends, print its
    /// wall time and frame times (stderr) and close the window.
    pub time_run: bool,
    /// The simulation's host works away from the UI's thread: on a thread
    /// of its own natively, in a Web Worker in a browser (the app's
    /// launch); false: in-process, advanced in the frames (the UI tests,
    /// which call the host's handler in-process; a page asked for
    /// `?cdca_no_worker`).
    pub host_thread: bool,
    /// The plot tab shown whatever runs (command line `--plot`, for
    /// screenshots); the user can still pick another.
    pub plot: Option<PlotTab>,
}

/// A run the app starts by itself (`cdca-workbench SCENE --run relax|grow`,
/// `--study PATH FROM TO COUNT`).
#[derive(Clone, Debug, PartialEq)]
pub enum StartRun {
    /// Relax with the scene's solver (the direct solver solves at once).
    Relax,
    /// Run growth until the run ends.
    Grow,
    /// Race the solvers (Compare solvers).
    Compare,
    /// Run a parameter study (the Study tab's Run study).
    Study(crate::study::StudySetup),
    /// Read a study file and run its first steps (the Study tab's *Study
    /// file*).
    StudyFile { source: String, text: String },
}

impl Default for Options {
    fn default() -> Self {
        Self {
            solve_on_start: true,
            auto_solve: true,
            scene: None,
            scene_source: scenes::DEFAULT_TITLE.to_owned(),
            view: ViewSettings::default(),
            start_run: None,
            file_dialogs: true,
            time_run: false,
            host_thread: false,
            plot: None,
        }
    }
}

/// σ_θθ and τ_rθ around the inspected tip, for the solution `version`.
pub struct TipCurve {
    pub tip: usize,
    pub version: u64,
    pub curve: Option<CriterionCurve>,
}

/// The whole application. (Independent flags, so bools.)
#[allow(clippy::struct_excessive_bools)]
pub struct WorkbenchApp {
    pub(crate) scene: SceneFile,
    pub(crate) scene_source: String,
    pub(crate) runner: Runner,
    pub(crate) undo: UndoStack,
    pub(crate) editor: Editor,
    pub(crate) canvas: Canvas,
    pub(crate) settings: ViewSettings,
    /// Which side panels show, and the text size.
    pub(crate) layout: Layout,
    pub(crate) commands: Vec<Command>,
    pub(crate) message: Option<Message>,
    pub(crate) selected_tip: Option<usize>,
    /// The user chose no tip in the inspector: no tip is picked for them
    /// until they open another scene (see [`Self::refresh_tip_curve`]).
    pub(crate) no_tip_wanted: bool,
    pub(crate) tip_curve: Option<TipCurve>,
    pub(crate) plot_tab: PlotTab,
    pub(crate) race: Option<Race>,
    pub(crate) race_time_cap: f64,
    pub(crate) study: Option<Study>,
    pub(crate) study_setup: StudySetup,
    /// The study file read (Study tab, *Study file*), its run, and how
    /// to run it.
    pub(crate) loaded_study: Option<LoadedStudy>,
    pub(crate) file_study: Option<FileStudy>,
    pub(crate) study_file_setup: StudyFileSetup,
    pub(crate) options: Options,
    pub(crate) started: bool,
    /// A job asked for while another held the slot: it starts when the
    /// slot frees, or at once if the user cancels the running job.
    pub(crate) waiting: Option<Waiting>,
    /// The path field shown where no file dialog could open.
    pub(crate) path_prompt: Option<PathPrompt>,
    /// The scene link the page address holds (the browser's).
    pub(crate) address: crate::files::link::Address,
    /// The folder last saved to or opened from: where the next Save and
    /// Open start.
    pub(crate) last_folder: Option<std::path::PathBuf>,
    /// The growth step the canvas replays (None: the state now).
    pub(crate) replay_step: Option<usize>,
    /// What the plot panel showed besides its plot last frame (the story,
    /// the tabs, the legend, the notes), points: the panel keeps room for
    /// them and a whole plot.
    plots_overhead: f32,
    /// Where the story and the plot showed last frame, points (for the
    /// browser's layout test: `window.cdcaState`).
    pub(crate) story_and_plot: [Option<egui::Rect>; 2],
    /// The first frame has been laid out (the start-up work waits for it).
    painted_once: bool,
    /// The first frame and the first field were reported (see
    /// `STARTUP_REPORT`).
    startup_reported: (bool, bool),
    /// The scene as last opened (the default file name says `_edited` once
    /// the scene differs from it).
    pub(crate) opened_scene: SceneFile,
    /// The crack the last edit changed (a drawn crack takes its contact
    /// law).
    pub(crate) last_edited_crack: Option<usize>,
    /// A drag of the scene is under way (its edits are `ongoing`).
    pub(crate) dragging: bool,
    /// The drag's edits were solved as it went
    /// ([`Runner::follow_drag`](crate::run::runner::Runner::follow_drag)).
    pub(crate) drag_followed: bool,
    /// A job the command line asked for, started once the first solve has
    /// freed the slot.
    pub(crate) queued: Option<Command>,
    pub(crate) frame_stats: FrameStats,
    /// A running job also advances between frames, and that loop repaints
    /// (the browser wrapper's `web_work`): the app then does not ask for a
    /// frame after every frame while a job runs.
    pub(crate) works_between_frames: bool,
    /// The command line's run, timed (`--time-run`).
    run_timer: RunTimer,
    frame_start: Option<Instant>,
    /// When the last frame began, as eframe runs it (see `calm_frames`).
    last_frame: Option<Instant>,
    /// Time the frame's tasks took, s.
    frame_solver_seconds: f64,
    /// A canvas screenshot on its way (PNG export).
    pub(crate) screenshot: Arc<Mutex<Option<Arc<egui::ColorImage>>>>,
    pub(crate) screenshot_rect: Option<egui::Rect>,
}

impl WorkbenchApp {
    pub fn new(options: Options) -> Self {
        let scene = options.scene.clone().unwrap_or_else(scenes::default_scene);
        let plot_tab = options.plot.unwrap_or_else(|| PlotTab::fitting(&scene));
        let opened_scene = scene.clone();
        // where no worker can start, the host works in the page's frames
        let (link, no_worker) = if options.host_thread {
            match Link::away() {
                Ok(link) => (link, None),
                Err(e) => (Link::in_process(), Some(e)),
            }
        } else {
            (Link::in_process(), None)
        };
        let mut runner = Runner::new(link);
        let message = runner
            .invalidate(&scene)
            .err()
            .or(no_worker.map(|e| {
                format!(
                    "The solver runs on the page (the page could not start a Web Worker: {e}): \
                     the page may stutter while it works."
                )
            }))
            .map(Message::Error);
        Self {
            scene_source: options.scene_source.clone(),
            scene,
            runner,
            undo: UndoStack::default(),
            editor: Editor::default(),
            canvas: Canvas::default(),
            settings: options.view.clone(),
            layout: Layout::default(),
            commands: Vec::new(),
            message,
            selected_tip: None,
            no_tip_wanted: false,
            tip_curve: None,
            plot_tab,
            race: None,
            race_time_cap: race::DEFAULT_TIME_CAP,
            study: None,
            study_setup: StudySetup::default(),
            loaded_study: None,
            file_study: None,
            study_file_setup: StudyFileSetup::default(),
            options,
            started: false,
            waiting: None,
            path_prompt: None,
            address: crate::files::link::Address::default(),
            last_folder: None,
            replay_step: None,
            plots_overhead: 60.0,
            painted_once: false,
            startup_reported: (false, false),
            opened_scene,
            last_edited_crack: None,
            dragging: false,
            drag_followed: false,
            queued: None,
            frame_stats: FrameStats::default(),
            works_between_frames: false,
            run_timer: RunTimer::default(),
            frame_start: None,
            last_frame: None,
            frame_solver_seconds: 0.0,
            screenshot: Arc::default(),
            screenshot_rect: None,
            story_and_plot: [None, None],
        }
    }

    /// The web entry: restores the last scene and view settings; the host
    /// in a Web Worker with `host_thread` (else on the page).
    pub fn from_creation_context(cc: &eframe::CreationContext<'_>, host_thread: bool) -> Self {
        Self::launch(cc, None, None, false, None, host_thread)
    }

    /// The entry from the command line: opens `scene` (source, scene)
    /// instead of the saved one when given, restores the view settings, and
    /// starts `run` after the first solve; the host away from the UI's
    /// thread with `host_thread` ([`Options::host_thread`]).
    pub fn launch(
        cc: &eframe::CreationContext<'_>,
        scene: Option<(String, SceneFile)>,
        run: Option<StartRun>,
        time_run: bool,
        plot: Option<PlotTab>,
        host_thread: bool,
    ) -> Self {
        cc.egui_ctx.set_fonts(fonts());
        let saved = Persisted::load(cc.storage);
        let (scene, source) = if let Some((source, scene)) = scene {
            (Some(scene), source)
        } else {
            let scene = saved
                .scene_json
                .as_deref()
                .and_then(|j| cdca::Scene::from_json(j).map(cdca::Scene::into_file).ok());
            let source = if scene.is_some() && !saved.scene_source.is_empty() {
                saved.scene_source
            } else {
                scenes::DEFAULT_TITLE.to_owned()
            };
            (scene, source)
        };
        let mut app = Self::new(Options {
            scene,
            scene_source: source,
            view: saved.view,
            start_run: run,
            time_run,
            plot,
            host_thread,
            ..Options::default()
        });
        app.layout = Layout::new(saved.layout);
        app
    }

    // --- read access for tests and panels -------------------------------

    /// Where the scene came from (the title's name): a file, a bundled
    /// scene's title, a shared link.
    pub fn scene_source(&self) -> &str {
        &self.scene_source
    }
    pub fn scene(&self) -> &SceneFile {
        &self.scene
    }
    pub fn message(&self) -> Option<&Message> {
        self.message.as_ref()
    }
    pub fn run_mode(&self) -> RunMode {
        self.runner.mode()
    }
    /// The job holding the slot, if one runs.
    pub fn running_job(&self) -> Option<Job> {
        Job::of_run(self.runner.mode())
            .or_else(|| {
                self.race
                    .as_ref()
                    .filter(|r| !r.finished())
                    .map(|_| Job::Race)
            })
            .or_else(|| {
                self.study
                    .as_ref()
                    .filter(|s| !s.finished())
                    .map(|_| Job::Study)
            })
            .or_else(|| {
                self.file_study
                    .as_ref()
                    .filter(|s| !s.finished())
                    .map(|_| Job::Study)
            })
    }
    /// The contact state of every crack-face point shown (empty before a
    /// solve).
    pub fn contact_states(&self) -> Vec<cdca::ContactState> {
        self.runner.view().contact.iter().map(|c| c.state).collect()
    }
    /// The crack-face points shown, with their cracks, positions and
    /// states (empty before a solve).
    pub fn contact_points(&self) -> &[cdca::ContactPointView] {
        &self.runner.view().contact
    }
    /// The free tips of the last solve (SIFs and criterion).
    pub fn tips(&self) -> &[cdca::report::TipReport] {
        &self.runner.view().tips
    }
    /// The growth run ended at `growth.max_load_factor`, if it did.
    pub fn load_cap(&self) -> Option<&cdca::report::LoadCapReport> {
        self.runner.view().load_cap.as_ref()
    }
    /// The job asked for while another ran, waiting for the slot.
    pub fn waiting_job(&self) -> Option<Job> {
        self.waiting.as_ref().and_then(Waiting::job)
    }
    /// Residual samples of the current relaxation.
    pub fn residual_samples(&self) -> usize {
        self.runner.view().residual_samples
    }
    /// Crack polylines as simulated (grown), empty before a solve.
    pub fn simulated_cracks(&self) -> &[Vec<[f64; 2]>] {
        &self.runner.view().cracks
    }
    /// Free tips after the last solve: (x, y) in m.
    pub fn tip_positions(&self) -> Vec<[f64; 2]> {
        self.runner.view().tips.iter().map(|t| [t.x, t.y]).collect()
    }
    /// The inspected tip and whether its σ_θθ / τ_rθ curve is available.
    pub fn inspected_tip(&self) -> Option<(usize, bool)> {
        let tip = self.selected_tip?;
        let has_curve = self
            .tip_curve
            .as_ref()
            .is_some_and(|c| c.tip == tip && c.curve.is_some());
        Some((tip, has_curve))
    }
    /// How the growth run ended, if it has.
    pub fn growth_outcome(&self) -> Option<cdca::report::Outcome> {
        self.runner.view().outcome
    }
    /// The end of the growth run as the solver panel tells it, once it
    /// has ended.
    pub fn run_story(&self) -> Option<crate::results::story::Story> {
        crate::results::story::story(self.runner.view(), &self.scene)
    }
    /// The simulated cracks as the panels name them ("Crack 1", "Crack 1 ·
    /// secondary 1", "Rock crack 3").
    pub fn crack_names(&self) -> Vec<String> {
        let v = self.runner.view();
        (0..v.cracks.len()).map(|c| v.crack_name(c)).collect()
    }
    /// The first link between two flaws in the run shown, if any.
    pub fn coalescence(&self) -> Option<&cdca::report::CoalescenceReport> {
        self.runner.view().coalescence.as_ref()
    }
    /// The specimen's strength against the intact rock's, once the run
    /// has ended.
    pub fn strength(&self) -> Option<&cdca::report::StrengthReport> {
        self.runner.view().strength.as_ref()
    }
    /// Growth steps done, as the status prints them: a reopened run's
    /// earlier steps (`growth.resume.steps`) included, so that the last
    /// step is the growth plots' last x.
    pub fn growth_steps(&self) -> usize {
        self.runner.view().steps_done
    }
    pub fn is_solved(&self) -> bool {
        self.runner.view().solved
    }
    /// Whether the last Solve was checked from bonded faces (it ended
    /// converged with faces closed), and the sentence saying it found
    /// another solution, if it did.
    pub fn second_start(&self) -> (bool, Option<&str>) {
        let v = self.runner.view();
        (
            v.second_start == crate::results::solution::SecondStart::Done,
            v.other_solution.as_deref(),
        )
    }
    /// The sampled field currently shown, if complete.
    pub fn field_is_shown(&self) -> bool {
        self.runner.field().current().is_some()
    }
    /// Fraction of the field being sampled, if one is.
    pub fn field_progress(&self) -> Option<f32> {
        self.runner.field_progress()
    }
    /// The solver race, running or finished.
    pub fn race(&self) -> Option<&Race> {
        self.race.as_ref()
    }
    /// The parameter study, running or finished.
    pub fn study(&self) -> Option<&Study> {
        self.study.as_ref()
    }

    /// The study file read in the Study tab.
    pub fn loaded_study(&self) -> Option<&LoadedStudy> {
        self.loaded_study.as_ref()
    }

    /// The study file's run, running or finished.
    pub fn file_study(&self) -> Option<&FileStudy> {
        self.file_study.as_ref()
    }

    /// How the Study tab runs a study file.
    pub fn study_file_setup(&self) -> &StudyFileSetup {
        &self.study_file_setup
    }
    /// The solution version and the number of samples of the field the
    /// canvas shows, if any.
    pub fn shown_field(&self) -> Option<(u64, usize)> {
        self.runner
            .field()
            .current()
            .map(|f| (f.key.version, f.samples.len()))
    }
    /// How large the stresses of the field the canvas shows are against
    /// the scene's largest boundary traction (`FieldScale`), if a field
    /// shows.
    pub fn shown_field_scale(&self) -> Option<crate::results::field::FieldScale> {
        use cdca::discretisation::boundary::Side;
        let traction = Side::ALL
            .iter()
            .filter_map(|side| side.traction(&self.scene.boundary))
            .map(|[x, y]| x.hypot(y))
            .fold(0.0, f64::max);
        self.runner.field().current().map(|f| f.scale(traction))
    }
    /// The load factor of the state the canvas's field was sampled from.
    pub fn shown_field_load_factor(&self) -> Option<f64> {
        self.runner.field().current().map(|f| f.load_factor)
    }
    /// The load factor λ the solver panel prints.
    pub fn load_factor(&self) -> f64 {
        self.runner.view().load_factor
    }
    /// The growth steps recorded by the current simulation.
    pub fn growth_history(&self) -> &[cdca::report::GrowthStepReport] {
        &self.runner.view().history
    }
    /// The final cracks cut the specimen through (their solve failed).
    pub fn specimen_split(&self) -> bool {
        self.runner.view().split
    }
    /// What File ▸ Save writes: the scene as simulated when a simulation
    /// of the edited scene exists (grown cracks and `growth.resume`, so
    /// that the file reopens and grows the identical next step), else the
    /// edited scene.
    pub fn scene_file(&self) -> Result<String, String> {
        let scene = match self.runner.scene() {
            Some(simulated) if !self.runner.is_stale() => simulated,
            _ => &self.scene,
        };
        scene.to_json().map_err(|e| e.to_string())
    }
    /// The link Copy link shares (its fragment, `scene=…`): the scene as
    /// drawn, never a run's state (see [`crate::files::link`]).
    pub fn scene_link(&self) -> Result<String, String> {
        let json = self.scene.to_json().map_err(|e| e.to_string())?;
        Ok(crate::files::link::to_fragment(&json))
    }
    /// Whether the page address holds a link to the scene on screen (in
    /// the browser; natively what it would hold).
    pub fn address_holds_link(&self) -> bool {
        self.address.is_held()
    }
    /// The stress samples of the field the canvas shows (σ_xx, σ_yy, τ_xy).
    pub fn shown_stresses(&self) -> Vec<[f64; 3]> {
        self.runner
            .field()
            .current()
            .map(|f| f.samples.iter().map(|s| s.stress).collect())
            .unwrap_or_default()
    }
    /// Growth steps done, residual samples of the current solve, its last
    /// residual, and the fraction of a rebuild's integration done: changes
    /// whenever the growth run advances.
    pub fn growth_progress(&self) -> (usize, usize, Option<f64>, Option<f64>) {
        let v = self.runner.view();
        (
            v.history.len(),
            v.residual_samples,
            v.last_residual.map(|r| r.residual),
            v.rebuild,
        )
    }
    /// The solver growth uses (or will use) on the current simulation.
    pub fn growth_solver(&self) -> cdca::scene::SolverKind {
        self.runner.growth_solver_kind(&self.scene)
    }
    /// Quadrature points the current simulation still has to integrate
    /// (`None` without one): 0 right after an edit that kept the
    /// discretisation (`Simulation::with_scene`).
    pub fn points_to_integrate(&self) -> Option<usize> {
        self.runner.points_to_integrate()
    }
    /// The relaxation status shown, if any.
    pub fn relax_status(&self) -> Option<cdca::RelaxStatus> {
        self.runner.view().relax
    }
    /// The plot the bottom panel shows.
    pub fn plot_tab(&self) -> PlotTab {
        self.plot_tab
    }
    pub fn frame_stats(&self) -> &FrameStats {
        &self.frame_stats
    }
    /// Where a specimen point (m) is on screen.
    pub fn screen_from_world(&self, p: [f64; 2]) -> egui::Pos2 {
        self.canvas.view.screen_from_world(p)
    }
    /// The specimen's rectangle on screen, as the canvas last drew it.
    pub fn specimen_rect(&self) -> egui::Rect {
        let s = &self.scene.specimen;
        egui::Rect::from_two_pos(
            self.screen_from_world([0.0, 0.0]),
            self.screen_from_world([s.width, s.height]),
        )
    }
    /// The canvas's key (tip markers, crack kinds) and the field's colour
    /// legend on screen, as last drawn (`None`: not drawn).
    pub fn canvas_keys(&self) -> (Option<egui::Rect>, Option<egui::Rect>) {
        (self.canvas.key_rect, self.canvas.legend_rect)
    }
    /// Which side panels show, and the text size.
    pub fn layout(&self) -> &crate::state::layout::LayoutSettings {
        &self.layout.settings
    }
    /// Shows or hides the side panels, as the menu bar's buttons do.
    pub fn toggle_panel(&mut self, scene: bool) {
        if scene {
            self.layout.toggle_scene();
        } else {
            self.layout.toggle_solver();
        }
    }
    /// Queues a command as if a panel had pushed it.
    pub fn push(&mut self, cmd: Command) {
        self.commands.push(cmd);
    }

    // --- per frame -------------------------------------------------------

    /// Applies the queued commands, then spends the frame's solver budget.
    pub fn logic(&mut self, ctx: &egui::Context) {
        self.frame_start = Some(Instant::now());
        self.layout.apply_text_scale(ctx);
        self.take_dropped_files(ctx);
        for cmd in std::mem::take(&mut self.commands) {
            let reset = matches!(cmd, Command::Reset);
            self.run_cmd(ctx, cmd);
            if self.address.went_stale(&self.scene, reset) {
                crate::files::io::clear_link();
            }
        }
        if !self.painted_once {
            // the first frame shows the scene's geometry and the controls
            // at once; the start-up work (a build, a solve, a run) begins
            // in the next frame, so that no scene leaves the window blank
            self.painted_once = true;
            ctx.all_styles_mut(crate::style::contrast::legible);
            ctx.request_repaint();
        } else if !self.started {
            self.started = true;
            if self.options.solve_on_start {
                self.run_cmd(ctx, Command::Solve);
            }
            match self.options.start_run.clone() {
                Some(StartRun::Relax) if self.scene.solver.kind != SolverKind::Direct => {
                    self.run_cmd(ctx, Command::Relax);
                }
                Some(StartRun::Relax) if !self.options.solve_on_start => {
                    self.run_cmd(ctx, Command::Solve);
                }
                Some(StartRun::Grow) => self.queued = Some(Command::RunGrowth),
                Some(StartRun::Compare) => {
                    self.queued = Some(Command::CompareSolvers {
                        time_cap: self.race_time_cap,
                    });
                }
                Some(StartRun::Study(setup)) => {
                    self.study_setup = setup.clone();
                    self.queued = Some(Command::RunStudy(setup));
                }
                Some(StartRun::StudyFile { source, text }) => {
                    self.run_cmd(ctx, Command::OpenStudy { source, text });
                    self.queued = Some(Command::RunStudyFile(self.study_file_setup.clone()));
                }
                _ => {}
            }
        }
        self.follow_drag(ctx);
        self.finish_screenshot(ctx);
        self.run_tasks();
        // the job that waited (the banner said so), or the command line's
        // run, as soon as the slot is free: in the frame the running job
        // ended, so that no frame shows the workbench idle in between
        if self.running_job().is_none()
            && let Some(cmd) = self
                .waiting
                .take()
                .map(|w| w.command)
                .or_else(|| self.queued.take())
        {
            if self.options.time_run {
                self.run_timer.start(self.runner.host_seconds());
            }
            self.run_cmd(ctx, cmd);
        }
        if self.run_timer.is_timing() && self.running_job().is_none() && self.queued.is_none() {
            let v = self.runner.view();
            let host = self.runner.host_seconds();
            if let Some(line) = self.run_timer.finish(v.history.len(), v.load_factor, host) {
                eprintln!("{line}");
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        self.refresh_tip_curve();
        // natively the host thread repaints the UI when it has something
        // to show (and the field comes with it)
        self.want_field();
        let on_thread = self.runner.works_away(ctx);
        // in a browser, a job working between frames repaints when due
        let away = on_thread || (self.works_between_frames && self.job_on_page());
        let busy = (self.running_job().is_some() && !away)
            || self.queued.is_some()
            || self.waiting.is_some()
            || (!away && !self.runner.field_done());
        if busy || !self.commands.is_empty() {
            ctx.request_repaint();
        } else if on_thread {
            ctx.request_repaint_after(Duration::from_millis(100));
        }
    }

    /// The frame's tasks within its solver budget ([`FRAME_TARGET`]): the field the canvas
    /// shows, a task like the others (the job waits until it is complete,
    /// so that what is shown is consistent and stays shown while the job
    /// runs), then the job holding the slot, if any (one at a time: see
    /// [`Job`]); after that, a growth step's field at λ_cr at once, before
    /// its tips move on.
    fn run_tasks(&mut self) {
        if let Some(e) = self.runner.take_error() {
            self.message = Some(Message::Error(e));
        }
        self.save_fields();
        let start = Instant::now();
        let rest = Duration::from_secs_f64(self.frame_stats.last_besides_solver());
        let deadline = start + solver_budget(rest);
        // a frame whose commands already took the budget (a rebuild of the
        // simulation) leaves the tasks to the next one: a rebuild and the
        // first contact iteration's factorisation then hold two frames,
        // not one for both
        if self.frame_start.is_some_and(|f| start - f >= FRAME_BUDGET) {
            self.frame_solver_seconds = 0.0;
            return;
        }
        // long growth calls wait for the work between frames, if it runs
        self.runner.leave_long_calls(self.works_between_frames);
        self.advance_tasks(deadline);
        self.frame_solver_seconds = start.elapsed().as_secs_f64();
    }

    /// The running job's work between frames, until `deadline`: the
    /// browser wrapper calls it in tasks of its own (`src/app/web_work.rs`),
    /// where software painting leaves the job a seventh of the time in
    /// frames. The same tasks in the same order as in a frame, so results
    /// do not depend on where the slices fall. Nothing without a running
    /// job.
    pub fn advance_job_until(&mut self, deadline: Instant) {
        if self.job_on_page() {
            self.runner.leave_long_calls(false);
            self.advance_tasks(deadline);
        }
    }

    /// [`Self::run_tasks`]'s work until `deadline`: the host's (in-process,
    /// the field first, then its run; on a thread, its posts), then the
    /// race's or the study's, once the field shown is complete.
    fn advance_tasks(&mut self, deadline: Instant) {
        self.want_field();
        if self.runner.advance(deadline)
            && let Some(Err(e)) = self.job_task().map(|t| t.advance(deadline))
        {
            self.message = Some(Message::Error(e));
        }
    }

    /// A job runs whose work is done on the UI's thread: the race, a study,
    /// or the host's run when the host is in-process.
    pub(crate) fn job_on_page(&self) -> bool {
        match self.running_job() {
            Some(Job::Solve | Job::Growth) => !self.runner.is_away(),
            Some(Job::Race | Job::Study) => true,
            None => false,
        }
    }

    /// The task of the race or the study holding the slot, if one runs.
    fn job_task(&mut self) -> Option<&mut dyn Task> {
        match self.running_job()? {
            Job::Solve | Job::Growth => None,
            Job::Race => self.race.as_mut().map(|r| r as &mut dyn Task),
            Job::Study => match self.file_study.as_mut().filter(|s| !s.finished()) {
                Some(s) => Some(s as &mut dyn Task),
                None => self.study.as_mut().map(|s| s as &mut dyn Task),
            },
        }
    }

    /// Stops the job holding the slot, if any: the runner's run pauses,
    /// the race and a study stop where they are (what they did stays).
    pub(crate) fn cancel_job(&mut self) {
        match self.running_job() {
            Some(Job::Solve | Job::Growth) => self.runner.pause(),
            Some(Job::Race) => {
                if let Some(r) = self.race.as_mut() {
                    r.cancel();
                }
            }
            Some(Job::Study) => {
                if let Some(s) = self.study.as_mut().filter(|s| !s.finished()) {
                    s.cancel();
                }
                if let Some(s) = self.file_study.as_mut().filter(|s| !s.finished()) {
                    s.cancel();
                }
            }
            None => {}
        }
    }

    /// Tells the host the field the canvas wants, if any: the current
    /// solution or iterate, coarse (one sample per element) while a run
    /// goes on and at the chosen resolution when it stops. The host
    /// samples it whenever the state has one (natively, on its thread, the
    /// field of each step's load whatever the view shows now).
    fn want_field(&mut self) {
        // coarse during a drag too: its solves follow the pointer
        let running = self.runner.is_running() || self.dragging;
        let s = &self.settings;
        let wanted = s.field != FieldKind::None || s.deformed;
        let Some(scene) = self.runner.scene() else {
            return;
        };
        let k = if running {
            1
        } else {
            s.samples_per_cell.clamp(1, 4)
        };
        let key = wanted.then(|| FieldKey {
            version: 0,
            cols: scene.mesh.nx * k,
            rows: scene.mesh.ny * k,
            width: scene.specimen.width,
            height: scene.specimen.height,
            with_displacement: s.deformed || s.field == FieldKind::Displacement,
        });
        self.runner.want_field(key);
    }

    /// The inspected tip's σ_θθ / τ_rθ curve, for the current solution.
    /// With none chosen, a solved scene's most loaded free tip (largest
    /// √(K_I⁺² + K_II²)) is inspected, so that the inspector shows its
    /// values and polar plot from the start.
    fn refresh_tip_curve(&mut self) {
        if self.runner.is_previewing() {
            // the simulation is a dragged scene's, not yet solved
            return;
        }
        let view = self.runner.view();
        if self.selected_tip.is_none() && !self.no_tip_wanted && view.solved {
            let load = |t: &cdca::report::TipReport| t.k1.max(0.0).hypot(t.k2);
            self.selected_tip = (0..view.tips.len())
                .max_by(|&a, &b| load(&view.tips[a]).total_cmp(&load(&view.tips[b])));
        }
        let version = self.runner.view().version;
        match self.selected_tip {
            None => self.tip_curve = None,
            Some(tip) => {
                if self
                    .tip_curve
                    .as_ref()
                    .is_some_and(|c| c.tip == tip && c.version == version)
                {
                    return;
                }
                let curve = self.runner.criterion_curve(tip);
                self.tip_curve = Some(TipCurve {
                    tip,
                    version,
                    curve,
                });
            }
        }
    }

    /// Scene files dropped on the window open like File ▸ Open.
    fn take_dropped_files(&mut self, ctx: &egui::Context) {
        for file in ctx.input(|i| i.raw.dropped_files.clone()) {
            match crate::files::io::read_dropped(&file) {
                Ok(f) => self.commands.push(Command::OpenSceneText {
                    source: f.name,
                    text: f.text,
                }),
                Err(e) => self.message = Some(Message::Error(e)),
            }
        }
    }

    /// What the panels read, and the view settings they may edit.
    fn view_parts(&mut self) -> (AppView<'_>, ViewState<'_>) {
        let run = RunStatus {
            mode: self.runner.mode(),
            stale: self.runner.is_stale(),
            field_progress: self.runner.field_progress(),
            last_solve_seconds: self.runner.last_solve_seconds(),
            last_build_seconds: self.runner.last_build_seconds(),
            pace: self.runner.pace(),
            accelerate_growth: self.runner.accelerate_growth(),
            growth_solver: self.runner.growth_solver_kind(&self.scene),
            job: self.running_job(),
            dragging: self.dragging,
            solves_on_release: self.options.auto_solve && self.runner.solve_is_quick(&self.scene),
        };
        let tip_curve = self
            .tip_curve
            .as_ref()
            .filter(|c| Some(c.tip) == self.selected_tip)
            .and_then(|c| c.curve.as_ref());
        let view = AppView {
            scene: &self.scene,
            scene_source: &self.scene_source,
            scene_edited: self.scene != self.opened_scene,
            solution: self.runner.view(),
            run,
            can_undo: self.undo.can_undo(),
            can_redo: self.undo.can_redo(),
            race: self.race.as_ref(),
            study: self.study.as_ref(),
            loaded_study: self.loaded_study.as_ref(),
            file_study: self.file_study.as_ref(),
            selected_tip: self.selected_tip,
            plot_tab: self.plot_tab,
            replayed: self
                .replay_step
                .filter(|_| !self.runner.is_running())
                .and_then(|k| self.runner.replay().at(k)),
            tip_curve,
            deform_scale_used: self.canvas.deform_scale_used,
        };
        let state = ViewState {
            settings: &mut self.settings,
            editor: &mut self.editor,
            fit_requested: &mut self.canvas.fit_requested,
            race_time_cap: &mut self.race_time_cap,
            study_setup: &mut self.study_setup,
            study_file_setup: &mut self.study_file_setup,
            layout: &mut self.layout,
        };
        (view, state)
    }

    /// Whether the replay bar shows above the canvas: after a run that
    /// stored two steps or more.
    fn replay_shown(&self) -> bool {
        !self.runner.is_running() && self.runner.replay().snapshots.len() >= 2
    }

    /// The whole UI. Panels read an `AppView` and push commands.
    pub fn ui(&mut self, ui: &mut Ui) {
        let mut cmds = Vec::new();
        egui::Panel::top("menu").show(ui, |ui| {
            let (v, mut s) = self.view_parts();
            panels::menu::menu_bar_ui(ui, &v, &mut s, &mut cmds);
        });
        egui::Panel::top("toolbar").show(ui, |ui| {
            let (v, mut s) = self.view_parts();
            panels::menu::toolbar_ui(ui, &v, &mut s, &mut cmds);
        });
        // Side panels keep their width whatever their text (see
        // `side_scroll`). Either can be hidden (menu bar); a narrow window (a
        // phone) starts with both hidden and opens one at a time, taking
        // most of the width, and shows the run bar instead.
        let window = ui.ctx().content_rect();
        let narrow = self.layout.follow_width(window.width());
        if !self.layout.settings.show_solver {
            let replay_shown = self.replay_shown();
            egui::Panel::top("run bar").show(ui, |ui| {
                let (v, _) = self.view_parts();
                panels::run_bar::run_bar_ui(ui, &v, replay_shown, &mut cmds);
            });
        }
        let side_max = if narrow {
            (window.width() - 40.0).max(200.0)
        } else {
            // at most 27 % of the window each, so that the canvas keeps
            // 46 % of it: a panel dragged wide on a large window shrinks
            // when the window does (at 1024 px: 276 px each)
            (0.27 * window.width()).clamp(240.0, 600.0)
        };
        let side_default = (0.26 * window.width()).clamp(200.0, 330.0);
        if self.layout.settings.show_scene {
            egui::Panel::left("scene")
                .resizable(true)
                .default_size(side_default)
                .size_range(200.0..=side_max)
                .show(ui, |ui| {
                    side_scroll(ui, "scene scroll", false, |ui| {
                        panels::scene::scene_ui(
                            ui,
                            &self.scene,
                            self.runner.view(),
                            &mut self.editor,
                            &mut cmds,
                        );
                    });
                });
        }
        if self.layout.settings.show_solver {
            egui::Panel::right("solver")
                .resizable(true)
                .default_size(side_default.max(240.0))
                .size_range(240.0..=side_max.max(240.0))
                .show(ui, |ui| {
                    side_scroll(ui, "solver scroll", true, |ui| {
                        let (v, s) = self.view_parts();
                        panels::solver::solver_ui(ui, &v, s.race_time_cap, &mut cmds);
                        ui.separator();
                        panels::tip::tip_ui(ui, &v, &mut cmds);
                    });
                });
        }
        // a study file's map needs its controls and a 300 px plot, and a
        // sweep its controls, table and a plot of 150 px or more: the
        // panel takes 480 px while the Study tab shows (at 1400 × 900 the
        // canvas keeps about 350)
        let study_tab = self.plot_tab == PlotTab::Study;
        let room = ui.available_rect_before_wrap().height();
        // otherwise, once a run has steps, the panel holds the story, the
        // tabs and the legend (as tall as they were last frame) and a plot
        // of MIN_PLOT_HEIGHT whole, leaving the canvas at least
        // `min_canvas_height`; where more
        // is left, the canvas keeps half the window's height and its
        // margins (the fit's, at most 2 × 41 there, and the panel's): the
        // specimen spans at least half the window (a projector at 1024 ×
        // 640 showed it 135 px high under a 300 px plot panel)
        let after_run = !self.runner.view().history.is_empty();
        // before a run the canvas comes first: a class sees the specimen
        // (at 1024 × 640 the two did not fit together)
        let whole_plot = if after_run {
            self.plots_overhead + panels::plots::MIN_PLOT_HEIGHT
        } else {
            20.0
        };
        let min_plots = if study_tab { 480.0 } else { whole_plot }
            .min(room - min_canvas_height(window.height()))
            .max(20.0);
        let max_plots = (room - 0.5 * window.height() - 110.0).max(min_plots);
        let mut overhead: Option<f32> = None;
        let mut story_and_plot = [None, None];
        egui::Panel::bottom("plots")
            .resizable(true)
            .default_size(300.0_f32.min(max_plots))
            .size_range(min_plots..=max_plots)
            .show(ui, |ui| {
                // the panel keeps its height whether it shows a plot or a hint
                ui.set_min_height(ui.available_height());
                let (v, s) = self.view_parts();
                let story = panels::story::story_ui(ui, &v);
                let plot =
                    panels::plots::plots_ui(ui, &v, s.study_setup, s.study_file_setup, &mut cmds);
                // the content's height (past the panel's edge where it
                // overflows) less the plot's
                overhead = plot.map(|p| ui.min_rect().height() - p.height());
                story_and_plot = [story, plot];
            });
        self.story_and_plot = story_and_plot;
        // a changed need lays the frame out again at once (otherwise the
        // panel settles over the next frames and the tabs move under a click)
        if let Some(o) = overhead.map(|o| o.max(0.0))
            && (o - self.plots_overhead).abs() > 0.5
        {
            self.plots_overhead = o;
            if after_run {
                ui.ctx().request_discard("the plot panel's height");
            }
        }
        egui::CentralPanel::default().show(ui, |ui| {
            panels::menu::message_ui(ui, self.message.as_ref(), &mut cmds);
            panels::menu::waiting_ui(ui, self.waiting.as_ref(), &mut cmds);
            panels::menu::path_prompt_ui(ui, self.path_prompt.as_mut(), &mut cmds);
            let replay = self.runner.replay();
            if self.replay_shown() {
                panels::replay::replay_ui(
                    ui,
                    replay,
                    self.runner.view(),
                    self.replay_step,
                    &mut cmds,
                );
            }
            // the fields, not `self.replayed()`: the canvas and the editor
            // are borrowed mutably below
            let replayed = self
                .replay_step
                .filter(|_| !self.runner.is_running())
                .and_then(|k| self.runner.replay().at(k));
            let input = match replayed {
                Some(snapshot) => CanvasInput {
                    scene: &self.scene,
                    solution: &snapshot.view,
                    field: snapshot.field.as_deref(),
                    settings: &self.settings,
                    selected_tip: None,
                },
                None => CanvasInput {
                    scene: &self.scene,
                    solution: self.runner.view(),
                    field: self.runner.field().current(),
                    settings: &self.settings,
                    selected_tip: self.selected_tip,
                },
            };
            let response = self.canvas.ui(ui, &input, &mut self.editor, &mut cmds);
            self.screenshot_rect = Some(response.rect);
            if self.settings.frame_overlay {
                panels::menu::frame_overlay_ui(ui, response.rect, &self.frame_stats);
            }
        });
        if !cmds.is_empty() {
            ui.ctx().request_repaint();
        }
        self.commands.extend(cmds);
        if let Some(start) = self.frame_start.take() {
            let dt = ui.input(|i| i.unstable_dt);
            self.frame_stats.record(
                start.elapsed().as_secs_f64(),
                self.frame_solver_seconds,
                f64::from(dt),
            );
            self.run_timer
                .record(start.elapsed().as_secs_f64(), f64::from(dt));
        }
    }

    /// Starts a PNG export of the canvas: the image arrives a frame later.
    pub(crate) fn request_canvas_png(&self, ctx: &egui::Context) {
        let slot = Arc::clone(&self.screenshot);
        ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(
            egui::ScreenshotCallback::new(move |image| {
                if let Ok(mut s) = slot.lock() {
                    *s = Some(image);
                }
            }),
        ));
    }

    fn finish_screenshot(&mut self, ctx: &egui::Context) {
        let image = self.screenshot.lock().ok().and_then(|mut s| s.take());
        let (Some(image), Some(rect)) = (image, self.screenshot_rect) else {
            return;
        };
        let cropped = image.region(&rect, Some(ctx.pixels_per_point()));
        match crate::results::export::png_bytes(&cropped) {
            Ok(bytes) => {
                let name = format!("{}.png", self.file_stem());
                self.save_bytes(&name, ("PNG image", "png"), bytes, false);
            }
            Err(e) => self.message = Some(Message::Error(e)),
        }
    }

    /// The scene differs from the one last opened.
    pub fn is_edited(&self) -> bool {
        self.scene != self.opened_scene
    }

    /// The path field shown where no file dialog could open: its text.
    pub fn typed_path(&self) -> Option<&str> {
        self.path_prompt.as_ref().map(|p| p.path.as_str())
    }
    /// The step the canvas replays, when it replays one (not while a run
    /// goes on).
    pub(crate) fn replayed(&self) -> Option<&crate::results::replay::Snapshot> {
        let step = self.replay_step.filter(|_| !self.runner.is_running())?;
        self.runner.replay().at(step)
    }
    /// The cracks the canvas draws: a replayed step's, or the state's now.
    pub fn canvas_cracks(&self) -> Vec<Vec<[f64; 2]>> {
        self.replayed().map_or_else(
            || self.runner.view().cracks.clone(),
            |s| s.view.cracks.clone(),
        )
    }
    /// The replay's marks: the step and name of each event of the run.
    pub fn replay_marks(&self) -> Vec<(usize, String)> {
        let v = self.runner.view();
        crate::results::replay::marks(&v.history, v, v.coalescence.as_ref().map(|c| c.step))
            .into_iter()
            .map(|m| (m.step, m.text))
            .collect()
    }
    /// The load factor of the field the canvas draws, and whether a field
    /// is drawn at all.
    pub fn canvas_field_load_factor(&self) -> Option<f64> {
        match self.replayed() {
            Some(s) => s.field.as_ref().map(|f| f.load_factor),
            None => self.shown_field_load_factor(),
        }
    }
    /// The steps the replay can show, in order.
    pub fn replay_steps(&self) -> Vec<usize> {
        self.runner
            .replay()
            .snapshots
            .iter()
            .map(|s| s.step)
            .collect()
    }
    /// Types `path` into the path field, when it is shown.
    pub fn set_typed_path(&mut self, path: &str) {
        if let Some(p) = self.path_prompt.as_mut() {
            path.clone_into(&mut p.path);
        }
    }
}

/// A side panel's scroll area, filling the panel: content wider than the
/// panel scrolls sideways instead of widening it; with `wrap`, text wraps
/// to the panel's width first (the Solver panel's status and words ran
/// past the window's edge, laid out as wide as the scrolled content).
fn side_scroll(ui: &mut Ui, id: &str, wrap: bool, add_contents: impl FnOnce(&mut Ui)) {
    // the panel may reach past the window's edge (its content is wider
    // than the window leaves it): wrap at what is on screen, the
    // scrollbar's width aside
    let on_screen = ui.clip_rect().right() - ui.cursor().left();
    let bar = ui.spacing().scroll.allocated_width();
    let width = ui.available_width().min(on_screen) - bar;
    egui::ScrollArea::both()
        .id_salt(id)
        .auto_shrink([false, false])
        .show(ui, |ui| {
            if wrap {
                ui.set_max_width(width);
            }
            add_contents(ui);
        });
}

/// When the process started, set by the native `main` when the
/// environment has `CDCA_STARTUP_REPORT` (scripts/first_frame.sh): the app
/// then prints when its first frame and its first solved field were laid
/// out, and closes once the field is shown.
pub static STARTUP_REPORT: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();

impl WorkbenchApp {
    fn report_startup(&mut self, ctx: &egui::Context) {
        let Some(t0) = STARTUP_REPORT.get() else {
            return;
        };
        let t = t0.elapsed().as_secs_f64();
        if !self.startup_reported.0 {
            self.startup_reported.0 = true;
            eprintln!("startup: first frame {t:.3} s");
        }
        if !self.startup_reported.1 && self.runner.field().current().is_some() {
            self.startup_reported.1 = true;
            eprintln!("startup: field {t:.3} s");
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }
}

impl WorkbenchApp {
    /// While the host works on its thread and no input comes, a frame waits
    /// until [`CALM_FRAME`](crate::run::link::CALM_FRAME) after the last one
    /// began. The app asks for 10
    /// frames a second then, but egui asks for one or two more after each
    /// update, while a grid's columns or a scroll bar settle to what it
    /// shows: painted in software (Xvfb, llvmpipe on both cores) that was
    /// about 29 frames a second at 30 ms of CPU each, taken from the
    /// host thread. Input (a click, a pointer move) is answered at once.
    /// A browser's page does not wait: it paints when the worker posts.
    fn calm_frames(&mut self, ctx: &egui::Context) {
        let quiet = ctx.input(|i| i.events.is_empty() && !i.pointer.is_moving());
        if let Some(last) = self.last_frame
            && quiet
            && self.runner.works_away(ctx)
        {
            crate::run::link::wait_for_calm(last);
        }
        self.last_frame = Some(Instant::now());
    }
}

impl eframe::App for WorkbenchApp {
    fn logic(&mut self, ctx: &egui::Context, _frame: &mut eframe::Frame) {
        self.calm_frames(ctx);
        WorkbenchApp::logic(self, ctx);
    }

    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        WorkbenchApp::ui(self, ui);
        self.report_startup(ui.ctx());
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        Persisted {
            scene_json: self.scene.to_json().ok(),
            scene_source: self.scene_source.clone(),
            view: self.settings.clone(),
            layout: self.layout.settings.clone(),
        }
        .store(storage);
    }
}

/// The app's fonts: egui's Ubuntu Light, cut to the scripts a scene name
/// or message may use (Latin-1 and Extended-A, Greek, Cyrillic, punctuation,
/// mathematical operators; `scripts/subset_font.sh`), for all
/// text (its digits are tabular, so the coordinate readouts do not jitter),
/// and egui's icons. egui's default set adds the monospace Hack and the
/// whole Ubuntu Light: without them the browser bundle is 0.6 MiB smaller.
/// Characters outside the cut are drawn as boxes.
fn fonts() -> egui::FontDefinitions {
    use egui::{FontData, FontFamily, FontTweak};
    use std::sync::Arc;
    let mut fonts = egui::FontDefinitions::empty();
    fonts.font_data.insert(
        "Ubuntu-Light".to_owned(),
        Arc::new(FontData::from_static(include_bytes!(
            "../../assets/fonts/Ubuntu-Light-derivative-CDCA.ttf"
        ))),
    );
    fonts.font_data.insert(
        "egui-icons".to_owned(),
        Arc::new(
            FontData::from_static(epaint_default_fonts::EGUI_ICONS).tweak(FontTweak {
                scale: 0.90,
                ..Default::default()
            }),
        ),
    );
    for family in [FontFamily::Proportional, FontFamily::Monospace] {
        fonts.families.insert(
            family,
            vec!["Ubuntu-Light".to_owned(), "egui-icons".to_owned()],
        );
    }
    fonts
}

#[cfg(test)]
mod tests {
    use super::{Duration, fonts, solver_budget};

    /// The solver gets what the rest of the last frame left of
    /// `FRAME_TARGET` (15 ms), within 4–12 ms.
    #[test]
    fn the_solver_budget_is_what_the_rest_of_the_frame_leaves() {
        let ms = Duration::from_millis;
        assert_eq!(solver_budget(ms(1)), ms(12));
        assert_eq!(solver_budget(ms(5)), ms(10));
        assert_eq!(solver_budget(ms(30)), ms(4));
    }

    /// Every character outside ASCII that the app's or the solver's code
    /// writes (comments aside: UI text, units, messages), and a sample of
    /// the scripts the font is cut to, has a glyph in the app's fonts, in
    /// both families.
    #[test]
    fn the_fonts_cover_every_character_the_code_writes() {
        fn chars_in(dir: &std::path::Path, out: &mut std::collections::BTreeSet<char>) {
            for entry in std::fs::read_dir(dir).expect("source dir") {
                let path = entry.expect("entry").path();
                if path.is_dir() {
                    chars_in(&path, out);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    let text = std::fs::read_to_string(&path).expect("source");
                    for line in text.lines() {
                        let code = line.split("//").next().unwrap_or("");
                        out.extend(code.chars().filter(|c| !c.is_ascii()));
                    }
                }
            }
        }
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut used = std::collections::BTreeSet::new();
        chars_in(&root.join("src"), &mut used);
        chars_in(&root.join("crates/cdca/src"), &mut used);
        assert!(used.contains(&'λ') && used.contains(&'≤'), "{used:?}");
        // and what a user may type in a scene's name or description
        used.extend("àéîõüñçßøåæœšžčłğı ΑΩαω АЯая €№™∞≈≠±".chars());
        let ctx = egui::Context::default();
        ctx.set_fonts(fonts());
        // the font atlas's first upload, not applied here: cleared, as
        // epaint's debug build refuses to drop it unapplied
        ctx.run_ui(egui::RawInput::default(), |_| {})
            .textures_delta
            .clear();
        let mut missing = Vec::new();
        ctx.fonts_mut(|f| {
            for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
                let font = egui::FontId::new(12.0, family.clone());
                missing.extend(
                    used.iter()
                        .filter(|&&c| !f.has_glyph(&font, c))
                        .map(|&c| (c, family.clone())),
                );
            }
        });
        assert!(missing.is_empty(), "no glyph for {missing:?}");
    }
}
