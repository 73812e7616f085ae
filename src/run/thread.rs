//! Natively, the host on a thread of its own (`Link::away`): it handles
//! requests as they come, works through the run between them in pieces
//! (`Host::work_piece`), and posts what the UI shows. Dropping the UI's side ends
//! the thread.

use std::sync::mpsc::{self, Receiver, Sender, TryRecvError};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

use web_time::Instant;

use crate::run::host::Host;
use crate::run::protocol::{PACED_CALL, POST_INTERVAL, Post, Request};

/// The host thread, seen from the UI: requests go, posts come. Dropping
/// it ends the thread after its piece under way.
pub struct HostThread {
    pub(crate) requests: Sender<Request>,
    pub(crate) posts: Receiver<Post>,
    pub(crate) waker: Arc<Mutex<Option<egui::Context>>>,
    _handle: JoinHandle<()>,
}

impl HostThread {
    pub fn start() -> Self {
        let (requests, inbox) = mpsc::channel();
        let (outbox, posts) = mpsc::channel();
        let waker = Arc::new(Mutex::new(None));
        let thread = ThreadSide {
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
struct ThreadSide {
    host: Host,
    inbox: Receiver<Request>,
    outbox: Sender<Post>,
    waker: Arc<Mutex<Option<egui::Context>>>,
}

impl ThreadSide {
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
            let event = self.host.is_busy() && self.host.work_piece();
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
