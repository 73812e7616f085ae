//! How requests reach the [`Host`] and its posts come back: in-process
//! (the UI's frames advance the host in slices within their deadline: the
//! UI tests, and a page that cannot start a Web Worker), on a thread of
//! its own (natively, `run::thread`) or in a Web Worker (a browser,
//! `run::worker`), which work through the run and post what it shows. All
//! carry the same [`Request`]s and [`Post`]s; results never depend on how
//! the work is sliced, so they are the bits of `cdca grow`'s.

#[cfg(not(target_arch = "wasm32"))]
use std::sync::PoisonError;

use web_time::{Duration, Instant};

use crate::run::host::Host;
use crate::run::protocol::{Post, Request};
#[cfg(not(target_arch = "wasm32"))]
use crate::run::thread::HostThread;

/// The link to the host.
pub enum Link {
    /// The host advances in the UI's frames.
    InProcess(Box<InProcess>),
    /// The host works on a thread of its own (native).
    #[cfg(not(target_arch = "wasm32"))]
    Thread(HostThread),
    /// The host works in a Web Worker (a browser).
    #[cfg(target_arch = "wasm32")]
    Worker(crate::run::worker::WorkerLink),
}

impl Link {
    /// A host in-process.
    pub fn in_process() -> Self {
        Self::InProcess(Box::default())
    }

    /// A host away from the UI's thread: on a thread of its own natively,
    /// in a Web Worker in a browser (which fails where the page cannot
    /// start one: then why).
    #[cfg_attr(not(target_arch = "wasm32"), allow(clippy::unnecessary_wraps))]
    pub fn away() -> Result<Self, String> {
        #[cfg(not(target_arch = "wasm32"))]
        return Ok(Self::Thread(HostThread::start()));
        #[cfg(target_arch = "wasm32")]
        return crate::run::worker::WorkerLink::start().map(Self::Worker);
    }

    pub fn send(&mut self, request: Request) {
        match self {
            Self::InProcess(p) => {
                if let Some(post) = p.host.handle(request) {
                    p.posts.push(post);
                }
                p.dirty = true;
            }
            #[cfg(not(target_arch = "wasm32"))]
            Self::Thread(t) => {
                // the thread ends only when the link is dropped
                let _ = t.requests.send(request);
            }
            #[cfg(target_arch = "wasm32")]
            Self::Worker(w) => w.send(&request),
        }
    }

    /// The posts come since the last call, in order. In-process, the host
    /// first works until `deadline`, if given and it has work.
    pub fn posts(&mut self, deadline: Option<Instant>) -> Vec<Post> {
        match self {
            Self::InProcess(p) => {
                if let Some(deadline) = deadline.filter(|_| p.host.is_busy()) {
                    p.host.advance(deadline);
                    p.dirty = true;
                }
                if std::mem::take(&mut p.dirty) {
                    let shown = p.host.shown();
                    p.posts.push(Post::Shown(Box::new(shown)));
                }
                std::mem::take(&mut p.posts)
            }
            #[cfg(not(target_arch = "wasm32"))]
            Self::Thread(t) => t.posts.try_iter().collect(),
            #[cfg(target_arch = "wasm32")]
            Self::Worker(w) => w.posts(),
        }
    }

    /// The host works elsewhere than in the UI's frames.
    pub fn is_away(&self) -> bool {
        !matches!(self, Self::InProcess(_))
    }

    /// Repaints the UI when the host posts from elsewhere.
    pub fn set_waker(&mut self, ctx: &egui::Context) {
        match self {
            Self::InProcess(_) => {}
            #[cfg(not(target_arch = "wasm32"))]
            Self::Thread(t) => {
                let mut w = t.waker.lock().unwrap_or_else(PoisonError::into_inner);
                if w.is_none() {
                    *w = Some(ctx.clone());
                }
            }
            #[cfg(target_arch = "wasm32")]
            Self::Worker(w) => w.set_waker(ctx),
        }
    }
}

/// The host in-process, and what it posted that the UI has not taken.
#[derive(Default)]
pub struct InProcess {
    host: Host,
    posts: Vec<Post>,
    /// The host changed since its last post.
    dirty: bool,
}

/// The least time between two UI frames while the host works away and no
/// input comes (`WorkbenchApp::calm_frames`).
pub const CALM_FRAME: Duration = Duration::from_millis(100);

/// Natively, waits on the UI thread until [`CALM_FRAME`] after `last`
/// (when its last frame began). A browser's page cannot wait: it paints
/// when the worker posts.
pub fn wait_for_calm(last: Instant) {
    #[cfg(not(target_arch = "wasm32"))]
    if let Some(left) = CALM_FRAME.checked_sub(last.elapsed()) {
        std::thread::sleep(left);
    }
    #[cfg(target_arch = "wasm32")]
    let _ = (last, CALM_FRAME);
}
