//! **How work runs**: the host's simulation and its runs, advanced in
//! slices, in the UI's frames or on a thread of its own, behind one run
//! protocol. Uses `results` (what a run leaves: view, field, replay) and
//! nothing above it.
//!
//! - `task`: long work done a slice at a time (the `Task` trait);
//! - `pacer`: sizes solver calls to a slice's deadline;
//! - `protocol`: the requests the UI sends and the posts the host sends back;
//! - `host`: the simulation, its view and field, and the runs on it;
//! - `link`: how requests and posts travel: in-process, or away
//!   (`thread` natively, `worker`, a Web Worker, in a browser);
//! - `runner`: the UI's side: sends requests, keeps what the host posts;
//! - `timer`: times a run started from the command line;
//! - this file: the runs themselves (`RunMode`, `Run`).
//!
//! The runs of the host's simulation, advanced until a deadline in calls
//! sized by the [`Pacer`]: relaxation to convergence, and growth, which
//! ends with the solve of the final cracks at the last step's load factor.

pub mod host;
pub mod link;
pub mod pacer;
pub mod protocol;
pub mod runner;
pub mod task;
#[cfg(not(target_arch = "wasm32"))]
pub mod thread;
pub mod timer;
#[cfg(target_arch = "wasm32")]
pub mod worker;

use cdca::scene::SolverKind;
use cdca::{RelaxStatus, Simulation, SolveError};
use web_time::Instant;

use crate::run::pacer::Pacer;
use crate::run::task::Progress;

/// What the solver does in the coming frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum RunMode {
    #[default]
    Paused,
    /// Relaxation sweeps each frame until converged.
    Relaxing,
    /// A dragged scene is solved (its solution shows when it ends; the
    /// panels stay as they are, as paused).
    SolvingDrag,
    /// Growth steps each frame until the run ends.
    Growing,
    /// One growth step, then the solve of the grown cracks, then pause.
    GrowingOne,
}

/// A run in progress.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Run {
    /// The relaxation started on the simulation, until it finishes.
    Relax,
    /// The solve of a dragged scene
    /// ([`Runner::follow_drag`](crate::run::runner::Runner::follow_drag)),
    /// shown when it ends.
    DragSolve,
    Grow(Growth),
}

/// A growth run: steps until growth ends (or, for Grow one step, until
/// one more step is recorded), then the final solve.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Growth {
    /// Grow one step: the number of steps recorded when it was asked for;
    /// the run ends once one more is recorded and the grown cracks are
    /// solved (counted from the click, not per frame: a step completing
    /// at a frame's end used to let the run go on to the end of growth).
    one_step_after: Option<usize>,
    /// Growth has ended and the final cracks are being solved at the last
    /// step's load factor ([`Simulation::start_final_solve`]).
    final_solve: bool,
}

/// What a slice of a run did: where the run stands, and the status of the
/// relaxation (or final solve) it advanced, if any.
pub struct Slice {
    pub progress: Progress,
    pub status: Option<RelaxStatus>,
}

impl Run {
    /// Growth until it ends; `one_step_after`: see [`Growth`].
    pub fn grow(one_step_after: Option<usize>) -> Self {
        Self::Grow(Growth {
            one_step_after,
            final_solve: false,
        })
    }

    pub fn mode(&self) -> RunMode {
        match self {
            Self::Relax => RunMode::Relaxing,
            Self::DragSolve => RunMode::SolvingDrag,
            Self::Grow(g) if g.one_step_after.is_some() => RunMode::GrowingOne,
            Self::Grow(_) => RunMode::Growing,
        }
    }

    /// The final solve after growth is under way: the field shown stays
    /// the last solved one until it is solved.
    pub fn in_final_solve(&self) -> bool {
        matches!(self, Self::Grow(g) if g.final_solve)
    }

    /// Works on `sim` until about `deadline`.
    pub fn advance(
        &mut self,
        sim: &mut Simulation,
        pacer: &mut Pacer,
        deadline: Instant,
    ) -> Result<Slice, SolveError> {
        match self {
            Self::Relax | Self::DragSolve => relax(sim, pacer, deadline),
            Self::Grow(g) => g.advance(sim, pacer, deadline),
        }
    }
}

/// Relaxation sweeps until the relaxation finishes (converged or capped)
/// or the frame is used.
fn relax(sim: &mut Simulation, pacer: &mut Pacer, deadline: Instant) -> Result<Slice, SolveError> {
    loop {
        let start = Instant::now();
        let n = pacer.sweeps();
        let status = sim.relax(n)?;
        if status.finished {
            return Ok(Slice {
                progress: Progress::Finished,
                status: Some(status),
            });
        }
        if !pacer.another_fits(start, n, deadline) {
            return Ok(Slice {
                progress: Progress::Working,
                status: Some(status),
            });
        }
    }
}

impl Growth {
    /// Growth in resumable chunks ([`Simulation::advance_growth`]: a few
    /// solver sweeps, one contact iteration, a piece of a rebuild, or the
    /// extension of the tips), stopping early when a step has solved at
    /// the load it records, λ_cr or the load increment's
    /// ([`Simulation::at_step_load`]: its field is shown before the tips
    /// move on). Once
    /// growth has ended, the final cracks are solved at the last step's
    /// load factor ([`Simulation::start_final_solve`]), so that the state
    /// shown at the end is solved at the load the history prints; nothing
    /// is left to solve when the last step grew nothing (its state is that
    /// solve).
    fn advance(
        &mut self,
        sim: &mut Simulation,
        pacer: &mut Pacer,
        deadline: Instant,
    ) -> Result<Slice, SolveError> {
        let mut status = None;
        loop {
            if !pacer.may_start(deadline) {
                return Ok(Slice {
                    progress: Progress::Working,
                    status,
                });
            }
            let start = Instant::now();
            let n = pacer.sweeps();
            if self.final_solve {
                let s = sim.relax(n)?;
                status = Some(s);
                if s.finished {
                    return Ok(Slice {
                        progress: Progress::Finished,
                        status,
                    });
                }
            } else if sim.growth_finished().is_some() {
                if sim.is_solved() || sim.start_final_solve().is_none() {
                    return Ok(Slice {
                        progress: Progress::Finished,
                        status,
                    });
                }
                self.final_solve = true;
                continue;
            } else {
                let preparing = sim.rebuild_progress().is_some();
                let report = sim.advance_growth(n)?;
                let one_done = self
                    .one_step_after
                    .is_some_and(|from| sim.history().len() > from);
                if one_done && report.is_none() && sim.is_solved() {
                    return Ok(Slice {
                        progress: Progress::Finished,
                        status,
                    });
                }
                if sim.at_step_load() {
                    // the step's solved state is shown before its tips move
                    return Ok(Slice {
                        progress: Progress::Working,
                        status,
                    });
                }
                // a new discretisation is ready: the direct solver's next
                // calls factorise it, a slice each (`FACTOR_SLICE_FLOPS`),
                // so they open a frame unless one fits in what is left of
                // this one
                if preparing
                    && sim.rebuild_progress().is_none()
                    && sim.scene().solver.kind == SolverKind::Direct
                    && pacer.defer_long_call(deadline)
                {
                    return Ok(Slice {
                        progress: Progress::Working,
                        status,
                    });
                }
            }
            if !pacer.another_fits(start, n, deadline) {
                return Ok(Slice {
                    progress: Progress::Working,
                    status,
                });
            }
        }
    }
}
