//! Long work done a slice per frame: the runner's relaxation and growth,
//! the solver race and a parameter study. The app runs the frame's tasks
//! in one place (`WorkbenchApp::run_tasks`), after sampling the field the
//! canvas shows.

use web_time::Instant;

/// Where a task stands after a slice of work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// More to do in later frames.
    Working,
    /// Done (or stopped); nothing more to do.
    Finished,
}

/// Work advanced across frames, a slice at a time.
pub trait Task {
    /// Works until about `deadline` (calls sized by a
    /// [`Pacer`](crate::run::pacer::Pacer)); an error ends the task and is shown.
    fn advance(&mut self, deadline: Instant) -> Result<Progress, String>;
}
