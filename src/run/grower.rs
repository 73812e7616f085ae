//! Natively, a growth run works on a thread of its own (issue 56, "No
//! waiting"): run in frame slices, the solver had 12 ms of each frame and
//! Run growth took 2.3–6.7 times as long as `cdca grow`. The thread owns
//! the simulation and its run while they grow, advances the run exactly as
//! the frame slices do ([`Run::advance`], pieces of [`PIECE`]), and sends
//! the UI what it shows after each piece worth showing: the refreshed
//! [`SolutionView`], the tips' criterion curves, and at each step's load
//! (and every [`LIVE_FIELD_INTERVAL`] while the solve goes on) the sampled
//! field, which the UI samples in slices when it has the simulation. When
//! the run ends, or the UI stops it to pause, edit or save, the
//! simulation, its run and the pacer come back
//! ([`Returned`]), and whatever comes next (the end of the run, Solve,
//! Save with `growth.resume`) works on them as after a sliced run. Results
//! never depend on how the run is sliced, so they are the bits of the
//! sliced run and of `cdca grow`. In the browser the run stays sliced.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender, TryRecvError};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

use cdca::{CriterionCurve, Scene, Simulation, SolveError};
use web_time::{Duration, Instant};

use crate::results::field::{FieldKey, FieldSampler, FieldSamples, LIVE_FIELD_INTERVAL};
use crate::results::solution::SolutionView;
use crate::run::pacer::Pacer;
use crate::run::task::Progress;
use crate::run::{Run, Slice};

/// The simulation can move to the growth thread (its linear solver is a
/// `Box<dyn LinearSolver>`, a `Send` trait).
const _: () = {
    const fn send<T: Send>() {}
    send::<Simulation>();
};

/// The thread's pieces of work between checks of the stop flag, s: as long
/// as a frame slice was, so that a pause waits at most about this long.
const PIECE: Duration = Duration::from_millis(12);

/// Least time between two updates without a step's event, and the
/// longest the UI waits to show one, s: the UI repaints when an update
/// comes, at most this often (10 Hz for the residual and progress; each
/// step's field is shown for a frame), not continuously, so that painting
/// takes little from the solver on a 2-core machine. (Painted in software,
/// as under Xvfb, a frame of the workbench took about 30 ms of CPU: at
/// 25 frames a second the growth thread had 40% of a core, and Run growth
/// took 2.7 times as long as `cdca grow`.)
const UPDATE_INTERVAL: Duration = Duration::from_millis(100);

/// The least time between two UI frames while the thread grows and no
/// input comes (`WorkbenchApp::calm_frames`).
pub const CALM_FRAME: Duration = Duration::from_millis(100);

/// Waits, on the UI thread, until [`CALM_FRAME`] after `last` (when its
/// last frame began).
pub fn wait_for_calm(last: Instant) {
    if let Some(left) = CALM_FRAME.checked_sub(last.elapsed()) {
        std::thread::sleep(left);
    }
}

/// What the UI shows after a piece of the run.
pub struct Update {
    pub view: SolutionView,
    /// The piece ended at a step's load (λ_cr, or the load increment's λ):
    /// `view` holds its solve, before the tips move on.
    pub at_step_load: bool,
    /// The field of `view`'s state, when sampled with this update.
    pub field: Option<FieldSamples>,
    /// Each tip's criterion curve, when `view` is solved.
    pub curves: Vec<Option<CriterionCurve>>,
}

/// What comes back when the thread ends.
pub struct Returned {
    pub sim: Simulation,
    pub run: Run,
    pub pacer: Pacer,
    /// How the run's last piece ended (`None`: stopped before its end).
    pub end: Option<Result<Slice, SolveError>>,
}

/// The growth thread, seen from the UI.
pub struct Grower {
    updates: Receiver<Update>,
    stop: Arc<AtomicBool>,
    /// The field the canvas wants (coarse while running; `None`: none).
    key: Arc<Mutex<Option<FieldKey>>>,
    handle: JoinHandle<Returned>,
    /// Stops the thread when the grower is dropped unjoined (the window
    /// closed, a test ended).
    _stop_on_drop: StopOnDrop,
    /// The scene simulated when the thread started (mesh and specimen do
    /// not change while it grows).
    scene: Scene,
}

impl Grower {
    /// Starts growing `sim` on a thread: `run` goes on from where it
    /// stands; `view` is the runner's (its version counter and earlier
    /// steps go on).
    pub fn start(
        sim: Simulation,
        run: Run,
        pacer: Pacer,
        view: SolutionView,
        key: Option<FieldKey>,
        waker: Option<egui::Context>,
    ) -> Self {
        let (tx, updates) = mpsc::channel();
        let stop = Arc::new(AtomicBool::new(false));
        let key = Arc::new(Mutex::new(key));
        let scene = sim.scene().clone();
        let thread = Thread {
            sim,
            run,
            pacer,
            view,
            stop: Arc::clone(&stop),
            key: Arc::clone(&key),
            tx,
            waker,
        };
        let handle = std::thread::spawn(move || thread.grow());
        Self {
            updates,
            _stop_on_drop: StopOnDrop(Arc::clone(&stop)),
            stop,
            key,
            handle,
            scene,
        }
    }

    /// The scene simulated.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The field the canvas wants from now on.
    pub fn want_field(&self, key: Option<FieldKey>) {
        *self.key.lock().unwrap_or_else(PoisonError::into_inner) = key;
    }

    /// The next update, if one has come; `Err(())` once the thread has
    /// ended and every update is taken.
    pub fn next_update(&self) -> Result<Option<Update>, ()> {
        match self.updates.try_recv() {
            Ok(u) => Ok(Some(u)),
            Err(TryRecvError::Empty) => Ok(None),
            Err(TryRecvError::Disconnected) => Err(()),
        }
    }

    /// Asks the thread to stop after its piece under way.
    pub fn stop(&self) {
        self.stop.store(true, Ordering::Relaxed);
    }

    /// Waits for the thread's end and takes back what it grew, and the
    /// updates not yet taken, in order. A panic on the thread (a bug) goes
    /// on here.
    pub fn join(self) -> (Returned, Vec<Update>) {
        match self.handle.join() {
            Ok(r) => (r, self.updates.try_iter().collect()),
            Err(panic) => std::panic::resume_unwind(panic),
        }
    }
}

struct StopOnDrop(Arc<AtomicBool>);

impl Drop for StopOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// The thread's side.
struct Thread {
    sim: Simulation,
    run: Run,
    pacer: Pacer,
    view: SolutionView,
    stop: Arc<AtomicBool>,
    key: Arc<Mutex<Option<FieldKey>>>,
    tx: Sender<Update>,
    /// Repaints the UI when an update is sent.
    waker: Option<egui::Context>,
}

impl Thread {
    /// Pieces of the run until it ends, fails or is stopped; an update
    /// after each piece that reached a step's load, recorded a step or
    /// ended the run, and otherwise at most every [`UPDATE_INTERVAL`].
    fn grow(mut self) -> Returned {
        let mut sent = Instant::now();
        let mut field_at: Option<Instant> = None;
        let mut steps = self.sim.history().len();
        let end = loop {
            if self.stop.load(Ordering::Relaxed) {
                break None;
            }
            let result = self
                .run
                .advance(&mut self.sim, &mut self.pacer, Instant::now() + PIECE);
            let Ok(slice) = &result else {
                break Some(result);
            };
            let finished = slice.progress == Progress::Finished;
            let at_step_load = self.sim.at_step_load();
            let stepped = self.sim.history().len() != steps;
            let now = Instant::now();
            if at_step_load || stepped || finished || now - sent >= UPDATE_INTERVAL {
                steps = self.sim.history().len();
                sent = now;
                let solved = self.sim.is_solved();
                self.view.refresh(&self.sim, solved, slice.status);
                let live = field_at.is_none_or(|t| (now - t).as_secs_f64() >= LIVE_FIELD_INTERVAL)
                    && !self.run.in_final_solve();
                let field = if at_step_load || live {
                    self.field()
                } else {
                    None
                };
                if field.is_some() {
                    field_at = Some(now);
                }
                self.send(at_step_load, field);
            }
            if finished {
                break Some(result);
            }
        };
        Returned {
            sim: self.sim,
            run: self.run,
            pacer: self.pacer,
            end,
        }
    }

    /// The view (refreshed) sent with `field` and the tips' curves.
    fn send(&self, at_step_load: bool, field: Option<FieldSamples>) {
        let curves = if self.view.solved {
            (0..self.view.tips.len())
                .map(|t| self.sim.criterion_curve(t))
                .collect()
        } else {
            Vec::new()
        };
        // the receiver is gone only when the UI dropped the grower, which
        // stops the thread
        let _ = self.tx.send(Update {
            view: self.view.clone(),
            at_step_load,
            field,
            curves,
        });
        if let Some(ctx) = &self.waker {
            ctx.request_repaint_after(UPDATE_INTERVAL);
        }
    }

    /// The field the canvas wants, sampled whole from the state the view
    /// was refreshed from (it carries the view's version).
    fn field(&self) -> Option<FieldSamples> {
        let key = (*self.key.lock().unwrap_or_else(PoisonError::into_inner))?;
        self.view.has_field().then(|| {
            FieldSampler::sampled(
                &self.sim,
                FieldKey {
                    version: self.view.version,
                    ..key
                },
            )
        })
    }
}
