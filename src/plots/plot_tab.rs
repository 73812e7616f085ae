//! Which plot the bottom panel shows: named by commands, the view, the
//! figures and the panels alike, so it sits below all of them.

use cdca::scene::SceneFile;

/// Which plot the bottom panel shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PlotTab {
    #[default]
    ResidualBySweep,
    ResidualByTime,
    Sifs,
    Angles,
    LoadFactor,
    SolverComparison,
    /// A parameter study: kink angle and mode against one parameter.
    Study,
    /// A study file's run (shown in the Study tab): its map per layout, or
    /// its plots over one axis.
    StudyMap,
}

impl PlotTab {
    /// The tabs the plot panel shows, in order (a study file's map shows in
    /// the Study tab).
    pub const TABS: [Self; 7] = [
        Self::ResidualBySweep,
        Self::ResidualByTime,
        Self::Sifs,
        Self::Angles,
        Self::LoadFactor,
        Self::SolverComparison,
        Self::Study,
    ];

    /// The tab's name on screen.
    pub fn label(self) -> &'static str {
        match self {
            Self::ResidualBySweep => "Residual / sweeps",
            Self::ResidualByTime => "Residual / time",
            Self::Sifs => "K_I, K_II",
            Self::Angles => "Angles",
            Self::LoadFactor => "Load factor",
            Self::SolverComparison => "Solver race",
            Self::Study | Self::StudyMap => "Study",
        }
    }

    /// The tab a command line names (`--plot`): residual, residual-time,
    /// k, angles, load, race or study.
    pub fn from_arg(name: &str) -> Option<Self> {
        Some(match name {
            "residual" => Self::ResidualBySweep,
            "residual-time" => Self::ResidualByTime,
            "k" => Self::Sifs,
            "angles" => Self::Angles,
            "load" => Self::LoadFactor,
            "race" => Self::SolverComparison,
            "study" => Self::Study,
            _ => return None,
        })
    }

    /// The plot that has something to show for `scene` before any run: the
    /// residual for an iterative solver, the SIFs for the direct one.
    pub fn fitting(scene: &SceneFile) -> Self {
        if scene.solver.kind == cdca::scene::SolverKind::Direct {
            Self::Sifs
        } else {
            Self::ResidualBySweep
        }
    }
}
