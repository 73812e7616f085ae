//! The run protocol: what the UI asks of the host that holds the
//! simulation ([`Request`]), and what the host posts back ([`Post`]),
//! whatever carries them (`run::link`: in-process, or a thread of its
//! own). The UI never holds a simulation; it shows the host's posts.

use cdca::scene::{SceneFile, SolverKind};
use cdca::{CriterionCurve, Scene};

use crate::results::field::{FieldKey, FieldSamples};
use crate::results::solution::SolutionView;
use crate::run::RunMode;

/// What the UI asks of the host. Each is handled in the order sent.
#[derive(Clone, Debug)]
pub enum Request {
    /// The scene was edited: forget the simulation (kept as the spare
    /// whose discretisation the next build reuses) and check the scene.
    Invalidate(Box<SceneFile>),
    /// Build a simulation of the scene (nothing solved yet).
    Rebuild(Box<SceneFile>),
    /// An edit during a drag that the solves follow: check the scene only.
    EditDuringDrag(Box<SceneFile>),
    /// Start the solve of the dragged scene, if the last one has ended.
    FollowDrag,
    /// The drag ended: its last solve stands as Solve's.
    CheckAfterDrag,
    /// Another scene is opened: forget the last solve's contact verdict.
    ForgetContact,
    /// Keep the run on screen under this id (for Undo), and forget it here.
    TakeRun(u64),
    /// Bring back the run kept under this id, with the edited scene.
    RestoreRun(u64, Box<SceneFile>),
    /// The UI dropped the run kept under this id.
    ForgetRun(u64),
    /// Solve from `cdca solve`'s start; a grown run on screen is kept
    /// under the id given.
    Solve {
        keep: Option<u64>,
    },
    /// One relaxation sweep.
    Step,
    /// Relax to convergence.
    Relax,
    /// Grow (`one`: one step, then the solve of the grown cracks).
    StartGrowth {
        one: bool,
    },
    Pause,
    /// Sweeps per call (None: as many as fit).
    SetPace(Option<usize>),
    SetAccelerateGrowth(bool),
    /// Calls that would overrun a frame wait for the work between frames
    /// (the in-process host in a browser's frames).
    LeaveLongCalls(bool),
    /// The field the canvas wants (its version is the host's choice).
    WantField(Option<FieldKey>),
    /// The displacement and stress fields as a VTU file, if solved.
    ExportFields,
}

/// What the host posts back.
pub enum Post {
    Shown(Box<Shown>),
    /// The answer to [`Request::ExportFields`].
    Fields(Result<String, String>),
}

/// What the UI shows of the host's simulation and run, as of the
/// requests it has handled. (Independent flags, so bools.)
#[allow(clippy::struct_excessive_bools)]
#[derive(Clone, Default)]
pub struct Shown {
    /// Requests handled so far.
    pub handled: u64,
    pub view: SolutionView,
    /// The view holds a growth step's solve at the load it records (λ_cr,
    /// or the load increment's λ), before the tips move on.
    pub at_step_load: bool,
    /// A growth run advanced: the replay records this post.
    pub growing: bool,
    /// A field completed since the last post.
    pub field: Option<FieldSamples>,
    /// The fraction of a field being sampled, if one is.
    pub field_progress: Option<f32>,
    /// The host has the field `want_field` asked for, or has nothing to
    /// sample.
    pub field_done: bool,
    pub mode: RunMode,
    /// A run or the check from bonded faces goes on.
    pub checking_second_start: bool,
    /// The simulated scene, when it changed since the last post.
    pub scene: Option<Scene>,
    /// A simulation exists.
    pub has_sim: bool,
    /// The simulation has growth steps.
    pub grown: bool,
    /// Growth on this simulation is (or will be) set up for.
    pub growth_solver: Option<SolverKind>,
    /// Quadrature points still to integrate.
    pub points_to_integrate: Option<usize>,
    /// Each tip's criterion curve (empty unless the view is solved), when
    /// the view changed since the last post.
    pub curves: Option<Vec<Option<CriterionCurve>>>,
    pub last_solve_seconds: Option<f64>,
    pub last_solve_elements: usize,
    pub last_build_seconds: f64,
    /// An error since the last post (a run that failed, a build).
    pub error: Option<String>,
}
