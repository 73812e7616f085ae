//! How requests reach the [`Host`] and its posts come back: in-process
//! (the UI's frames advance the host in slices within their deadline: the
//! UI tests, and the browser's page), or on a thread of its own
//! (natively), which works through the run and posts what it shows. Both
//! carry the same [`Request`]s and [`Post`]s; results never depend on how
//! the work is sliced, so they are the bits of `cdca grow`'s.

use std::sync::mpsc::{self, Receiver, Sender, TryRecvError};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

use web_time::{Duration, Instant};

use crate::run::host::Host;
use crate::run::protocol::{Post, Request};

/// The host thread's pieces of work between looks at its requests: as long
/// as a frame slice was, so that a request waits at most about this long.
const PIECE: Duration = Duration::from_millis(12);

/// Least time between two posts while a run goes on without an event
/// (a step, a step's load, a field, the end): the UI repaints when a post
/// comes, at most this often (10 Hz for the residual and progress), not
/// continuously, so that painting takes little from the host on a 2-core
/// machine. (Painted in software, as under Xvfb, a frame of the workbench
/// took about 30 ms of CPU: at 25 frames a second the growth thread had
/// 40% of a core, and Run growth took 2.7 times as long as `cdca grow`.)
pub const POST_INTERVAL: Duration = Duration::from_millis(100);

/// A run paced by the user (sweeps per call) is watched a call per frame:
/// the host thread waits this long between calls.
const PACED_CALL: Duration = Duration::from_millis(16);

/// The link to the host.
pub enum Link {
    /// The host advances in the UI's frames.
    InProcess(Box<InProcess>),
    /// The host works on a thread of its own.
    Thread(HostThread),
}

impl Link {
    /// A host in-process.
    pub fn in_process() -> Self {
        Self::InProcess(Box::default())
    }

    /// A host on a thread of its own.
    pub fn thread() -> Self {
        Self::Thread(HostThread::start())
    }

    pub fn send(&mut self, request: Request) {
        match self {
            Self::InProcess(p) => {
                if let Some(post) = p.host.handle(request) {
                    p.posts.push(post);
                }
                p.dirty = true;
            }
            Self::Thread(t) => {
                // the thread ends only when the link is dropped
                let _ = t.requests.send(request);
            }
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
            Self::Thread(t) => t.posts.try_iter().collect(),
        }
    }

    /// Natively, waits for the next post of the host thread (in-process:
    /// the posts waiting).
    pub fn wait_post(&mut self) -> Option<Post> {
        match self {
            Self::InProcess(p) => p.posts.pop(),
            Self::Thread(t) => t.posts.recv().ok(),
        }
    }

    /// The host works elsewhere than in the UI's frames.
    pub fn is_away(&self) -> bool {
        matches!(self, Self::Thread(_))
    }

    /// Repaints the UI when the host thread posts.
    pub fn set_waker(&mut self, ctx: &egui::Context) {
        if let Self::Thread(t) = self {
            let mut w = t.waker.lock().unwrap_or_else(PoisonError::into_inner);
            if w.is_none() {
                *w = Some(ctx.clone());
            }
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

/// The host thread, seen from the UI: requests go, posts come. Dropping
/// it ends the thread after its piece under way.
pub struct HostThread {
    requests: Sender<Request>,
    posts: Receiver<Post>,
    waker: Arc<Mutex<Option<egui::Context>>>,
    _handle: JoinHandle<()>,
}

impl HostThread {
    fn start() -> Self {
        let (requests, inbox) = mpsc::channel();
        let (outbox, posts) = mpsc::channel();
        let waker = Arc::new(Mutex::new(None));
        let thread = Worker {
            host: Host::default(),
            inbox,
            outbox,
            waker: Arc::clone(&waker),
        };
        let handle = std::thread::Builder::new()
            .name("cdca-host".to_owned())
            .spawn(move || thread.work())
            .expect("a thread for the host");
        Self {
            requests,
            posts,
            waker,
            _handle: handle,
        }
    }
}

/// The thread's side.
struct Worker {
    host: Host,
    inbox: Receiver<Request>,
    outbox: Sender<Post>,
    waker: Arc<Mutex<Option<egui::Context>>>,
}

impl Worker {
    /// Requests as they come (waiting for one while there is no work),
    /// pieces of work between them, and a post after the requests, after
    /// each piece that reached a step's load, recorded a step, completed a
    /// field or ended the run, and otherwise at most every
    /// [`POST_INTERVAL`].
    fn work(mut self) {
        let mut posted = Instant::now();
        loop {
            let mut handled = false;
            loop {
                let request = if handled || self.host.is_busy() {
                    match self.inbox.try_recv() {
                        Ok(r) => r,
                        Err(TryRecvError::Empty) => break,
                        Err(TryRecvError::Disconnected) => return,
                    }
                } else {
                    match self.inbox.recv() {
                        Ok(r) => r,
                        Err(_) => return,
                    }
                };
                if let Some(post) = self.host.handle(request) {
                    self.post(post);
                }
                handled = true;
            }
            let mut event = false;
            if self.host.is_busy() {
                let (steps, running) = (self.host.steps(), self.host.is_running());
                self.host.advance(Instant::now() + PIECE);
                event = self.host.at_event()
                    || self.host.steps() != steps
                    || running != self.host.is_running()
                    || !self.host.is_busy()
                    || self.host.is_paced();
            }
            if handled || event || (self.host.is_busy() && posted.elapsed() >= POST_INTERVAL) {
                posted = Instant::now();
                let shown = self.host.shown();
                self.post(Post::Shown(Box::new(shown)));
            }
            if self.host.is_paced() && self.host.is_busy() {
                std::thread::sleep(PACED_CALL);
            }
        }
    }

    fn post(&self, post: Post) {
        // the receiver is gone only when the UI dropped the link, and then
        // the next look at the requests ends the thread
        let _ = self.outbox.send(post);
        if let Some(ctx) = &*self.waker.lock().unwrap_or_else(PoisonError::into_inner) {
            ctx.request_repaint();
        }
    }
}

/// The least time between two UI frames while the host thread works and no
/// input comes (`WorkbenchApp::calm_frames`).
pub const CALM_FRAME: Duration = Duration::from_millis(100);

/// Waits, on the UI thread, until [`CALM_FRAME`] after `last` (when its
/// last frame began).
pub fn wait_for_calm(last: Instant) {
    if let Some(left) = CALM_FRAME.checked_sub(last.elapsed()) {
        std::thread::sleep(left);
    }
}
