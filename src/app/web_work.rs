//! A page without the solver's Web Worker: the running job's work between
//! frames, in tasks of its own.
//!
//! In a frame the solver gets what the UI leaves of the app's 15 ms
//! (`app::solver_budget`), so that no frame is long. But where the browser
//! paints in software (no GPU, as in the headless test), each painted
//! frame then holds the main thread some 60 ms more, outside the app's
//! code (measured: a message loop in the page ran nothing for 88 ms of
//! each 88 ms frame interval, while the app's part of the frame took
//! 25 ms), so a job that runs only inside frames gets a seventh of the
//! time. Nor does `requestIdleCallback` help: with frames back to back, it
//! was called not once in 8 s of Run growth.
//!
//! So while a job runs, it advances in slices of [`SLICE`] posted through a
//! `MessageChannel` (not clamped like `setTimeout`), which leave the
//! browser free to run input and frames between any two, and the page
//! repaints every [`REPAINT_EVERY`] instead of continuously (the app leaves
//! repainting to this loop: `WorkbenchApp::works_between_frames`), as the
//! native host thread repaints when it has something to show. Same tasks,
//! same order (`WorkbenchApp::advance_job_until`), so the same results.
//! Measured on the stepped pair (docs/browser.md): Run growth in 14.6–21.2 s
//! instead of 21.9–30.4 s; a solver call that cannot be split (up to 0.2 s
//! in wasm) now also delays the frame after the task that holds it. The
//! frames leave such calls to these tasks (`Pacer::set_leave_long`), so
//! that a frame of the app holds its UI and what surely fits: its CPU p95
//! fell from 98–118 ms to 5.6–5.7 ms on that run, 7.8 ms on the default
//! scene's.
//!
//! Only for the jobs that work on the page (`WorkbenchApp::job_on_page`):
//! Compare solvers and a study, which do not go through the run protocol
//! yet, and the host's runs where no Web Worker can start (a browser
//! without module workers, a page opened from a file, a policy forbidding
//! workers) or where `?cdca_no_worker` asks for it; the browser test runs
//! Run growth so and on the worker, to the same steps and λ. Otherwise the
//! host is in its worker (`run::worker`) and the page only paints what it
//! posts.

use std::cell::{Cell, RefCell};
use std::rc::{Rc, Weak};

use wasm_bindgen::JsCast;
use wasm_bindgen::closure::Closure;
use web_time::{Duration, Instant};

use crate::app::WorkbenchApp;

/// The job's work per task: a frame due meanwhile waits at most this
/// long (plus one solver call's overrun).
const SLICE: Duration = Duration::from_millis(10);

/// How often this loop repaints the page while a job runs between frames:
/// 4 Hz, as the growth run's spinner asks (`panels::widgets::slow_spinner`).
/// (egui asks for more when a grid or a scroll area changes size with what
/// it shows: about 10 frames a second were painted during Run growth.)
const REPAINT_EVERY: Duration = Duration::from_millis(250);

/// The work done between frames since the last [`BetweenFrames::take_stats`].
#[derive(Clone, Copy, Debug, Default)]
pub struct WorkStats {
    /// Tasks that did work.
    pub tasks: u32,
    /// Time spent on the job in them, seconds.
    pub worked: f64,
}

/// Shared by the frames (which start it while a job runs) and the tasks
/// (which advance the job and post the next one while it runs).
pub struct BetweenFrames {
    app: Weak<RefCell<WorkbenchApp>>,
    ctx: egui::Context,
    /// Posting to `port2` runs a task (`port1`'s message handler).
    channel: Option<web_sys::MessageChannel>,
    /// Kept alive while `port1` may call it.
    _on_message: Closure<dyn FnMut()>,
    /// A task is posted and has not run yet.
    posted: Cell<bool>,
    /// The page asked for the job in frames only (`?cdca_frames_only`).
    disabled: Cell<bool>,
    last_repaint: Cell<Instant>,
    stats: Cell<WorkStats>,
}

impl BetweenFrames {
    pub fn new(app: &Rc<RefCell<WorkbenchApp>>, ctx: egui::Context) -> Rc<Self> {
        Rc::new_cyclic(|this: &Weak<Self>| {
            let this = this.clone();
            let on_message = Closure::<dyn FnMut()>::new(move || {
                if let Some(this) = this.upgrade() {
                    this.run();
                }
            });
            let channel = web_sys::MessageChannel::new().ok();
            if let Some(c) = &channel {
                c.port1()
                    .set_onmessage(Some(on_message.as_ref().unchecked_ref()));
            } else {
                log::info!("no MessageChannel here: the solver works within frames only");
            }
            Self {
                app: Rc::downgrade(app),
                ctx,
                channel,
                _on_message: on_message,
                posted: Cell::new(false),
                disabled: Cell::new(false),
                last_repaint: Cell::new(Instant::now()),
                stats: Cell::new(WorkStats::default()),
            }
        })
    }

    /// Leaves the job to the frames, as before this loop (to measure it).
    pub fn disable(&self) {
        self.disabled.set(true);
    }

    /// Whether a running job advances here (the app then leaves the
    /// repainting to this loop).
    pub fn enabled(&self) -> bool {
        self.channel.is_some() && !self.disabled.get()
    }

    /// Posts a task unless one is pending (each frame calls this while a
    /// job runs; a task posts the next itself while the job runs).
    pub fn start(&self) {
        if self.posted.get() || !self.enabled() {
            return;
        }
        if let Some(c) = &self.channel
            && c.port2().post_message(&wasm_bindgen::JsValue::NULL).is_ok()
        {
            self.posted.set(true);
        }
    }

    /// What the tasks did since the last call, and starts anew.
    pub fn take_stats(&self) -> WorkStats {
        self.stats.take()
    }

    fn run(&self) {
        self.posted.set(false);
        let Some(app) = self.app.upgrade() else {
            return;
        };
        // a frame never runs inside a task, but should the app be
        // borrowed, the next task will do
        let Ok(mut app) = app.try_borrow_mut() else {
            self.start();
            return;
        };
        if !app.job_on_page() {
            // the job's last state shows
            self.ctx.request_repaint();
            return;
        }
        let start = Instant::now();
        app.advance_job_until(start + SLICE);
        let mut stats = self.stats.get();
        stats.tasks += 1;
        stats.worked += start.elapsed().as_secs_f64();
        self.stats.set(stats);
        let running = app.job_on_page();
        drop(app);
        if !running || self.last_repaint.get().elapsed() >= REPAINT_EVERY {
            self.last_repaint.set(Instant::now());
            self.ctx.request_repaint();
        }
        if running {
            self.start();
        }
    }
}
