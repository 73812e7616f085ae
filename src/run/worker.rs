//! In a browser, the host in a Web Worker, off the page's thread (issue
//! 63): the same `.wasm` instantiated a second time by `worker.js`
//! (written by `scripts/build-web.sh`), whose `main` finds no window and
//! [`serve`]s instead of starting the app. Requests and posts cross as
//! JSON, and a field's samples as a transferred `Float32Array`, never as a
//! JS array of numbers (`protocol::wire`).
//!
//! - the page's side, [`WorkerLink`]: sends requests, keeps the posts that
//!   come, and wakes the page's frames;
//! - the worker's side, [`serve`]: handles each request as it comes, and
//!   between them advances the host in pieces (`Host::work_piece`), each a task of
//!   its own (posted through a `MessageChannel`), posting what the UI
//!   shows as the native host thread does (`link::Worker`).

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use wasm_bindgen::JsCast;
use wasm_bindgen::closure::Closure;
use web_time::Instant;

use crate::run::host::Host;
use crate::run::protocol::{PACED_CALL, POST_INTERVAL, Post, Request, wire};

/// A post as a message: `{ json, samples }`, the samples (if any) in a
/// `Float32Array` whose buffer the list returned transfers.
fn post_message(post: &Post) -> (js_sys::Object, js_sys::Array) {
    let (json, samples) = wire::post_to_message(post);
    let message = js_sys::Object::new();
    let transfer = js_sys::Array::new();
    let _ = js_sys::Reflect::set(&message, &"json".into(), &json.into());
    if let Some(samples) = samples {
        let array = js_sys::Float32Array::from(samples.as_slice());
        transfer.push(&array.buffer());
        let _ = js_sys::Reflect::set(&message, &"samples".into(), &array);
    }
    (message, transfer)
}

/// The post a message from the worker carries.
fn post_of(data: &wasm_bindgen::JsValue) -> Result<Post, String> {
    let get = |key: &str| js_sys::Reflect::get(data, &key.into()).ok();
    let json = get("json")
        .and_then(|j| j.as_string())
        .ok_or("a post of the solver without its JSON")?;
    let samples = get("samples")
        .filter(|s| s.is_instance_of::<js_sys::Float32Array>())
        .map(|s| js_sys::Float32Array::from(s).to_vec());
    wire::post_from_message(&json, samples.as_deref())
}

/// The host's worker, seen from the page.
pub struct WorkerLink {
    worker: web_sys::Worker,
    posts: Rc<RefCell<Vec<Post>>>,
    waker: Rc<RefCell<Option<egui::Context>>>,
    _on_message: Closure<dyn FnMut(web_sys::MessageEvent)>,
    _on_error: Closure<dyn FnMut(web_sys::Event)>,
}

impl WorkerLink {
    /// The worker the page started as it loaded (`window.cdcaWorker`, see
    /// `index.html`: it compiles the module while the page does), or a new
    /// one (`worker.js`, a module beside the page). Fails where the page
    /// cannot start one (no module workers, a page opened from a file, a
    /// policy forbidding workers).
    pub fn start() -> Result<Self, String> {
        let window = web_sys::window().ok_or("no window")?;
        let started = js_sys::Reflect::get(&window, &"cdcaWorker".into())
            .ok()
            .filter(|w| w.is_instance_of::<web_sys::Worker>());
        let worker = match started {
            Some(worker) => {
                let _ = js_sys::Reflect::delete_property(&window, &"cdcaWorker".into());
                worker.unchecked_into::<web_sys::Worker>()
            }
            None => {
                let options = web_sys::WorkerOptions::new();
                options.set_type(web_sys::WorkerType::Module);
                web_sys::Worker::new_with_options("./worker.js", &options)
                    .map_err(|e| format!("{e:?}"))?
            }
        };
        let posts = Rc::new(RefCell::new(Vec::new()));
        let waker: Rc<RefCell<Option<egui::Context>>> = Rc::new(RefCell::new(None));
        let wake = {
            let waker = Rc::clone(&waker);
            move || {
                if let Some(ctx) = &*waker.borrow() {
                    ctx.request_repaint();
                }
            }
        };
        let on_message = {
            let (posts, wake) = (Rc::clone(&posts), wake.clone());
            Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
                let post = post_of(&e.data()).unwrap_or_else(Post::Failed);
                posts.borrow_mut().push(post);
                wake();
            })
        };
        let on_error = {
            let posts = Rc::clone(&posts);
            Closure::<dyn FnMut(web_sys::Event)>::new(move |e: web_sys::Event| {
                // an ErrorEvent (a panic, a script error) has a message; a
                // script that failed to load, none
                let why = js_sys::Reflect::get(&e, &"message".into())
                    .ok()
                    .and_then(|m| m.as_string())
                    .unwrap_or_else(|| "its script did not load".to_owned());
                posts.borrow_mut().push(Post::Failed(format!(
                    "the solver's Web Worker stopped: {why} (reload the page to start it \
                     again, or add ?cdca_no_worker to the address to solve on the page)"
                )));
                wake();
            })
        };
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        Ok(Self {
            worker,
            posts,
            waker,
            _on_message: on_message,
            _on_error: on_error,
        })
    }

    pub fn send(&self, request: &Request) {
        let json = wire::request_to_json(request);
        if let Err(e) = self.worker.post_message(&json.into()) {
            self.posts.borrow_mut().push(Post::Failed(format!(
                "a request to the solver's worker failed: {e:?}"
            )));
        }
    }

    /// The posts come since the last call, in order.
    pub fn posts(&self) -> Vec<Post> {
        std::mem::take(&mut *self.posts.borrow_mut())
    }

    /// Repaints the page when a post comes.
    pub fn set_waker(&self, ctx: &egui::Context) {
        let mut w = self.waker.borrow_mut();
        if w.is_none() {
            *w = Some(ctx.clone());
        }
    }
}

impl Drop for WorkerLink {
    fn drop(&mut self) {
        self.worker.terminate();
    }
}

/// The worker's side: the host, and the task that advances it.
struct Served {
    host: RefCell<Host>,
    scope: web_sys::DedicatedWorkerGlobalScope,
    /// Posting to `port2` runs a piece of work (`port1`'s handler).
    channel: web_sys::MessageChannel,
    /// A piece is posted and has not run yet.
    scheduled: Cell<bool>,
    posted_at: Cell<Instant>,
}

/// Serves the host in this worker: requests from the page as they come
/// (those that came while the module loaded first, kept by `worker.js` in
/// `cdcaEarly`), the host's work between them.
pub fn serve() {
    let scope: web_sys::DedicatedWorkerGlobalScope = js_sys::global().unchecked_into();
    let Ok(channel) = web_sys::MessageChannel::new() else {
        log::error!("no MessageChannel in the worker");
        return;
    };
    let served = Rc::new(Served {
        host: RefCell::new(Host::default()),
        scope,
        channel,
        scheduled: Cell::new(false),
        posted_at: Cell::new(Instant::now()),
    });
    let work = {
        let served = Rc::clone(&served);
        Closure::<dyn FnMut()>::new(move || served.work())
    };
    served
        .channel
        .port1()
        .set_onmessage(Some(work.as_ref().unchecked_ref()));
    work.forget();
    let on_message = {
        let served = Rc::clone(&served);
        Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
            served.handle(&e.data());
        })
    };
    let early = js_sys::Reflect::get(&served.scope, &"cdcaEarly".into()).ok();
    served
        .scope
        .set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    on_message.forget();
    if let Some(early) = early.filter(js_sys::Array::is_array) {
        for data in js_sys::Array::from(&early).iter() {
            served.handle(&data);
        }
    }
}

impl Served {
    /// A request: handled at once, then what the UI shows is posted, and
    /// the work goes on.
    fn handle(&self, data: &wasm_bindgen::JsValue) {
        let request = data
            .as_string()
            .ok_or_else(|| "a request to the solver that is not JSON".to_owned())
            .and_then(|json| wire::request_from_json(&json));
        match request {
            Ok(request) => {
                let answer = self.host.borrow_mut().handle(request);
                if let Some(answer) = answer {
                    self.post(&answer);
                }
            }
            Err(e) => self.post(&Post::Failed(e)),
        }
        self.post_shown();
        self.schedule();
    }

    /// A piece of work, and a post after each piece that reached a step's
    /// load, recorded a step, completed a field or ended the run, and
    /// otherwise at most every [`POST_INTERVAL`].
    fn work(&self) {
        self.scheduled.set(false);
        let mut host = self.host.borrow_mut();
        if !host.is_busy() {
            return;
        }
        let event = host.work_piece();
        drop(host);
        if event || self.posted_at.get().elapsed() >= POST_INTERVAL {
            self.post_shown();
        }
        self.schedule();
    }

    /// Posts the next piece of work, if the host has work and none is
    /// posted: at once, or after [`PACED_CALL`] for a paced run.
    fn schedule(&self) {
        let host = self.host.borrow();
        if self.scheduled.get() || !host.is_busy() {
            return;
        }
        let posted = if host.is_paced() {
            let port = self.channel.port2();
            let next = Closure::once_into_js(move || {
                let _ = port.post_message(&wasm_bindgen::JsValue::NULL);
            });
            self.scope
                .set_timeout_with_callback_and_timeout_and_arguments_0(
                    next.unchecked_ref(),
                    i32::try_from(PACED_CALL.as_millis()).unwrap_or(i32::MAX),
                )
                .is_ok()
        } else {
            self.channel
                .port2()
                .post_message(&wasm_bindgen::JsValue::NULL)
                .is_ok()
        };
        self.scheduled.set(posted);
    }

    fn post_shown(&self) {
        self.posted_at.set(Instant::now());
        let shown = self.host.borrow_mut().shown();
        self.post(&Post::Shown(Box::new(shown)));
    }

    fn post(&self, post: &Post) {
        let (message, transfer) = post_message(post);
        if let Err(e) = self.scope.post_message_with_transfer(&message, &transfer) {
            log::error!("the worker could not post: {e:?}");
        }
    }
}
