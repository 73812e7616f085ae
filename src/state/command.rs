//! What the UI asks for. Panels and the canvas read the app's state and push
//! commands; the app applies them once per frame, before any solver work.

use cdca::scene::SceneFile;

use crate::plots::plot_tab::PlotTab;
use crate::study::StudySetup;

/// How a plot is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlotFormat {
    /// The numbers, one row per point.
    Csv,
    /// The picture, for slides.
    Svg,
}

/// Files the workbench can write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Export {
    /// The scene as JSON.
    Scene,
    /// Crack polylines as CSV.
    CrackPaths,
    /// Growth history as CSV.
    History,
    /// Mesh with displacement and stresses as a VTK unstructured grid.
    Fields,
    /// The canvas as a PNG image.
    CanvasPng,
    /// The solver race as CSV (the columns of `cdca bench`).
    Race,
    /// The parameter study as CSV.
    Study,
    /// A study file's run as CSV (the columns of `cdca study`).
    StudyTable,
    /// Figure `index` of a plot tab, as CSV or SVG.
    Plot {
        tab: PlotTab,
        index: usize,
        format: PlotFormat,
    },
}

/// One request from the UI.
#[derive(Clone, Debug)]
pub enum Command {
    /// Replace the scene being edited. `ongoing` is true while a drag is in
    /// progress: consecutive ongoing edits form one undo step and the
    /// re-solve waits until the drag ends.
    SetScene {
        scene: Box<SceneFile>,
        ongoing: bool,
    },
    /// Add a drawn crack to the scene, with the contact law (friction,
    /// cohesion, joint stiffness) of the last edited crack, and say so.
    AddCrack(Box<cdca::scene::CrackSpec>),
    /// A drag of scene edits ended: the next edit is a new undo step, and
    /// the scene may be re-solved.
    EndDrag,
    /// Parse a scene file's text and open it; on error the current scene
    /// and its results stay untouched and the error is shown.
    OpenSceneText {
        source: String,
        text: String,
    },
    /// Open bundled scene `i` of [`crate::files::scenes::BUNDLED`].
    OpenBundled(usize),
    /// Open the scene a shared link carries (`#scene=…`); a link without a
    /// valid scene opens the default scene and says why.
    OpenLink(String),
    /// Put the scene (as File ▸ Save would write it) into a link: in the
    /// browser the page address, copied to the clipboard.
    CopyLink,
    /// Ask for a file to open (native dialog).
    OpenDialog,
    /// Ask for a path and write a file.
    Export(Export),
    Undo,
    Redo,
    /// Solve the current scene now (direct: one call; iterative: relax).
    Solve,
    /// One sweep of the iterative solver.
    Step,
    /// Relax to convergence, animated.
    Relax,
    /// One growth step.
    GrowOne,
    /// Grow until the run ends, animated.
    RunGrowth,
    Pause,
    /// Back to the scene's initial cracks, no solution.
    Reset,
    /// Race every solver on the current scene from a cold start and record
    /// error against run time, each iterative run capped at `time_cap` s.
    CompareSolvers {
        time_cap: f64,
    },
    /// Stop the solver race; the runs done so far stay.
    CancelRace,
    /// Sweeps per frame while relaxing or growing (None: as many as the
    /// frame budget allows).
    SetPace(Option<usize>),
    /// Show the run as it stood after this growth step (None: as it
    /// stands now).
    Replay(Option<usize>),
    /// Show this plot tab.
    ShowPlot(PlotTab),
    /// Growth with the automaton runs its multigrid-accelerated form
    /// (applies from the next growth run).
    SetAccelerateGrowth(bool),
    /// Run a parameter study on the current scene.
    RunStudy(StudySetup),
    /// Read a study file's text (bundled, opened or dropped); on error the
    /// study read before stays and the error is shown.
    OpenStudy {
        source: String,
        text: String,
    },
    /// Run the study file read, as the Study tab's setup says (first steps,
    /// or the first points grown to the end).
    RunStudyFile(crate::study::file::StudyFileSetup),
    CancelStudy,
    /// Inspect tip `i` of the current solution's tips (None: close).
    SelectTip(Option<usize>),
    DismissMessage,
    /// A value typed into the Scene panel is not taken: show why (the
    /// scene stays as it was).
    Refuse(String),
    /// Use the path typed where no file dialog could open.
    UseTypedPath,
    /// Close the path field without saving or opening.
    CancelTypedPath,
    /// Stop the job holding the slot (see [`crate::state::job::Job`]).
    CancelJob,
    /// Cancel the running job and start the one that waits for the slot.
    StartWaiting,
    /// Forget the job that waits for the slot.
    DropWaiting,
}
