//! The narrow interface between the app and its panels. Panels never see
//! [`crate::WorkbenchApp`]: they read an [`AppView`] (a read-only snapshot
//! of what they show), edit how things are shown in place through a
//! [`ViewState`], and push [`crate::Command`]s for everything else.

use cdca::CriterionCurve;
use cdca::scene::SceneFile;
use cdca::scene::SolverKind;

use crate::plots::plot_tab::PlotTab;
use crate::results::solution::SolutionView;
use crate::run::RunMode;
use crate::state::edit::Editor;
use crate::state::job::Job;
use crate::state::layout::Layout;
use crate::state::settings::ViewSettings;
use crate::study::file::{FileStudy, LoadedStudy, StudyFileSetup};
use crate::study::race::Race;
use crate::study::{Study, StudySetup};

/// A message shown above the canvas until dismissed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Message {
    Error(String),
    Info(String),
}

/// The solver's progress as the panels show it.
#[derive(Clone, Copy, Debug, Default)]
#[allow(clippy::struct_excessive_bools)]
pub struct RunStatus {
    pub mode: RunMode,
    /// The edited scene differs from the simulated one.
    pub stale: bool,
    /// Fraction of the field sampled, while sampling goes on.
    pub field_progress: Option<f32>,
    /// Wall time of the last full solve, s.
    pub last_solve_seconds: Option<f64>,
    /// Wall time of the last discretisation build, s.
    pub last_build_seconds: f64,
    /// Sweeps per frame (None: as many as the budget allows).
    pub pace: Option<usize>,
    /// Growth with the automaton runs its multigrid-accelerated form.
    pub accelerate_growth: bool,
    /// The solver growth uses on the current simulation.
    pub growth_solver: SolverKind,
    /// The job holding the slot, if one runs.
    pub job: Option<Job>,
    /// A drag of the scene (a crack end, a slider) is under way.
    pub dragging: bool,
    /// An edit is re-solved by itself when it ends (the solve is quick).
    pub solves_on_release: bool,
}

/// What the panels read.
pub struct AppView<'a> {
    pub scene: &'a SceneFile,
    /// Where the scene came from (file name or bundled title).
    pub scene_source: &'a str,
    /// The scene differs from the one opened (edited, or grown).
    pub scene_edited: bool,
    pub solution: &'a SolutionView,
    pub run: RunStatus,
    pub can_undo: bool,
    pub can_redo: bool,
    /// The solver race, running or finished.
    pub race: Option<&'a Race>,
    /// The parameter study, running or finished.
    pub study: Option<&'a Study>,
    /// The study file read (Study tab, *Study file*), and its run.
    pub loaded_study: Option<&'a LoadedStudy>,
    pub file_study: Option<&'a FileStudy>,
    pub selected_tip: Option<usize>,
    /// The plot tab shown.
    pub plot_tab: PlotTab,
    /// The growth step the canvas replays, when it replays one.
    pub replayed: Option<&'a crate::results::replay::Snapshot>,
    /// σ_θθ and τ_rθ around the selected tip, when available.
    pub tip_curve: Option<&'a CriterionCurve>,
    /// The deformation magnification the canvas used last frame.
    pub deform_scale_used: f64,
}

/// What the panels may change in place: how things are shown, never the
/// scene or the solver.
pub struct ViewState<'a> {
    pub settings: &'a mut ViewSettings,
    /// Tool, selection and crack being drawn.
    pub editor: &'a mut Editor,
    /// Fit the specimen to the canvas next frame.
    pub fit_requested: &'a mut bool,
    /// Time cap of one iterative solver in the race, s.
    pub race_time_cap: &'a mut f64,
    /// The parameter study to run next.
    pub study_setup: &'a mut StudySetup,
    /// How the Study tab runs a study file.
    pub study_file_setup: &'a mut StudyFileSetup,
    /// Which side panels show, and the text size.
    pub layout: &'a mut Layout,
}
