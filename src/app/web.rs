//! The browser wrapper around [`WorkbenchApp`]: files the browser reads
//! asynchronously (picked in the open dialog or dropped on the page) reach
//! the app as commands, and solve and frame times go to the console so the
//! browser build can be compared with the native one.
//!
//! Everything else is the same app: the same per-frame solver budget, the
//! same persistence (eframe keeps it in the page's local storage). What
//! the browser adds is a running job's work between frames
//! ([`BetweenFrames`]); the app is shared with those tasks, hence the
//! `Rc<RefCell<…>>`.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use wasm_bindgen::JsValue;
use web_time::{Duration, Instant};

use crate::app::WorkbenchApp;
use crate::app::web_work::BetweenFrames;
use crate::files::io;
use crate::results::field::{FieldKey, FieldScale};
use crate::state::command::Command;
use crate::state::view::Message;

/// How often frame statistics are logged while the app is busy.
const REPORT_EVERY: Duration = Duration::from_secs(2);

/// [`WorkbenchApp`] as the web runner sees it.
pub struct WebApp {
    app: Rc<RefCell<WorkbenchApp>>,
    between: Rc<BetweenFrames>,
    /// What was last logged, to log only changes.
    logged_solve: Option<f64>,
    logged_growth_steps: usize,
    /// A job (solve, growth, race, study) ran at the last frame.
    job_was_running: bool,
    next_report: Instant,
    /// The page asked for test hooks (`?cdca_test`): the widgets and the
    /// app's state are published on `window` each frame.
    test_hooks: bool,
    /// When the first frame was laid out and the first field shown, ms
    /// since the page's navigation began (`performance.now()`).
    first_frame_ms: Option<f64>,
    first_field_ms: Option<f64>,
    /// The page asked for continuous repaint (`?cdca_continuous`): every
    /// frame asks for the next, idle or not, so that the browser test
    /// compares frame intervals during a run with those of an idle page
    /// that paints as often (issue 63's decision).
    continuous: bool,
    /// The shown field's scale and what it was worked out for (the field's
    /// key and load factor): once per field, not every frame (it sorts
    /// every sample's stresses).
    field_scale: Cell<Option<ScaleOf>>,
}

/// A field's key, its load factor's bits, and its scale.
type ScaleOf = (FieldKey, u64, Option<FieldScale>);

impl WebApp {
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        io::set_repaint_context(cc.egui_ctx.clone());
        let test_hooks = page_query().contains("cdca_test");
        log::info!(
            "CDCA workbench starting (WebAssembly{})",
            if test_hooks { ", test hooks" } else { "" }
        );
        if test_hooks {
            cc.egui_ctx.enable_accesskit();
            cc.egui_ctx.add_plugin(WidgetsToPage);
        }
        // `?cdca_no_worker`: the host on the page, as where no Web Worker
        // can start (the fallback, tested to the same answer)
        let mut app =
            WorkbenchApp::from_creation_context(cc, !page_query().contains("cdca_no_worker"));
        // a shared link (`#scene=…`, src/files/link.rs) opens its scene, solved
        let hash = web_sys::window()
            .and_then(|w| w.location().hash().ok())
            .unwrap_or_default();
        if hash.contains("scene=") {
            app.push(Command::OpenLink(hash));
        }
        let app = Rc::new(RefCell::new(app));
        // `?cdca_frames_only`: the job in the frames only, as before the
        // work between frames, to measure what that gains
        let between = BetweenFrames::new(&app, cc.egui_ctx.clone());
        if page_query().contains("cdca_frames_only") {
            between.disable();
        }
        // jobs on the page (the race, a study; the host's runs without a
        // worker) also work between frames
        app.borrow_mut().works_between_frames = between.enabled();
        Self {
            between,
            app,
            logged_solve: None,
            logged_growth_steps: 0,
            job_was_running: false,
            next_report: Instant::now() + REPORT_EVERY,
            test_hooks,
            first_frame_ms: None,
            first_field_ms: None,
            continuous: page_query().contains("cdca_continuous"),
            field_scale: Cell::new(None),
        }
    }

    /// [`WorkbenchApp::shown_field_scale`], worked out again only when the
    /// field shown changes.
    fn shown_field_scale(&self, app: &WorkbenchApp) -> Option<FieldScale> {
        let shown = app
            .runner
            .field()
            .current()
            .map(|f| (f.key, f.load_factor.to_bits()))?;
        if let Some((key, bits, scale)) = self.field_scale.get()
            && (key, bits) == shown
        {
            return scale;
        }
        let scale = app.shown_field_scale();
        self.field_scale.set(Some((shown.0, shown.1, scale)));
        scale
    }

    /// For the browser test: what it asserts on, as `window.cdcaState`;
    /// rectangles in CSS pixels, as `window.cdcaWidgets`.
    fn state_to_page(&self, zoom: f64) {
        let app = self.app.borrow();
        let state = js_sys::Object::new();
        let set = |key: &str, value: JsValue| {
            let _ = js_sys::Reflect::set(&state, &key.into(), &value);
        };
        set("sceneName", app.scene().name.as_str().into());
        // Whether the solver runs on a Web Worker, off the page's thread
        // (issue 63), and how many requests and slices the page's own host
        // has handled (none while the worker has the host).
        set("worker", app.runner.is_away().into());
        set(
            "hostCallsOnPage",
            (crate::run::host::host_calls_on_this_thread() as f64).into(),
        );
        set("hostSeconds", app.runner.host_seconds().into());
        set("solved", app.is_solved().into());
        set("fieldShown", app.field_is_shown().into());
        // Sub-cells of the shown field with a finite stress (0: nothing
        // coloured, e.g. a field sampled before a solve).
        let finite = app.runner.field().current().map_or(0, |f| {
            f.samples.iter().filter(|s| s.stress[0].is_finite()).count()
        });
        set("fieldFinite", (finite as f64).into());
        // The shown field's stresses against the load (issue 63): `ok`
        // false for a field of zeros or a working vector's spikes
        // (`FieldScale::is_a_field`); null without a field.
        set(
            "fieldScale",
            self.shown_field_scale(&app).map_or(JsValue::NULL, |f| {
                let o = js_sys::Object::new();
                for (key, value) in [
                    ("peak", JsValue::from(f.peak)),
                    ("p99", JsValue::from(f.p99)),
                    ("load", JsValue::from(f.load)),
                    ("ok", JsValue::from(f.is_a_field())),
                ] {
                    let _ = js_sys::Reflect::set(&o, &JsValue::from_str(key), &value);
                }
                o.into()
            }),
        );
        set("growthSteps", (app.growth_steps() as f64).into());
        // each step's load factor, to set beside `cdca grow`'s (issue 63)
        set(
            "stepLoads",
            js_sys::Array::from_iter(
                app.growth_history()
                    .iter()
                    .map(|s| JsValue::from(s.load_factor)),
            )
            .into(),
        );
        set("residualSamples", (app.residual_samples() as f64).into());
        set("runMode", format!("{:?}", app.run_mode()).into());
        let crack_points: usize = app.simulated_cracks().iter().map(Vec::len).sum();
        set("crackPoints", (crack_points as f64).into());
        let view = app.runner.view();
        set("loadFactor", view.load_factor.into());
        // The growth steps' work (`GrowthStepReport::work`), summed: build,
        // solve and evaluation seconds, to set beside `cdca grow`'s (issue
        // 64). Their `seconds` are wall times, which here hold the frames
        // painted between a step's slices.
        let work = app
            .growth_history()
            .iter()
            .fold([0.0; 3], |[b, s, e], step| {
                let w = &step.work;
                [
                    b + w.build_seconds,
                    s + w.solve_seconds,
                    e + w.evaluate_seconds,
                ]
            });
        set(
            "growthWork",
            js_sys::Array::from_iter(work.map(JsValue::from)).into(),
        );
        let ms = |t: Option<f64>| t.map_or(JsValue::NULL, JsValue::from);
        set("firstFrameMs", ms(self.first_frame_ms));
        set("firstFieldMs", ms(self.first_field_ms));
        // the specimen and the keys drawn on the canvas, for the layout
        // test (issue 56): how large the specimen shows, and that no key
        // covers another
        set("specimen", rect_to_page(app.specimen_rect(), zoom).into());
        let keys = js_sys::Array::new();
        let (key, legend) = app.canvas_keys();
        let named = [("key", key), ("colour legend", legend)]
            .into_iter()
            .filter_map(|(name, r)| r.map(|r| (name, r)))
            .chain(
                app.canvas
                    .load_label_rects
                    .iter()
                    .map(|&r| ("load label", r)),
            );
        for (name, r) in named {
            let k = rect_to_page(r, zoom);
            let _ = js_sys::Reflect::set(&k, &"name".into(), &name.into());
            keys.push(&k);
        }
        set("keys", keys.into());
        // the story and the plot below the canvas, for the layout test
        // after a run (issue 65): whole in the window, off the canvas
        let [story, plot] = app.story_and_plot;
        let rect =
            |r: Option<egui::Rect>| r.map_or(JsValue::NULL, |r| rect_to_page(r, zoom).into());
        set("story", rect(story));
        set("plot", rect(plot));
        set("outcome", app.runner.view().outcome.is_some().into());
        set(
            "message",
            match app.message() {
                Some(Message::Error(e)) => format!("error: {e}").into(),
                Some(Message::Info(i)) => i.as_str().into(),
                None => JsValue::NULL,
            },
        );
        set_on_window("cdcaState", &state);
    }

    fn take_opened_files(app: &mut WorkbenchApp) {
        for result in io::take_opened() {
            match result {
                Ok(file) => app.push(Command::OpenSceneText {
                    source: file.name,
                    text: file.text,
                }),
                Err(e) => app.message = Some(Message::Error(e)),
            }
        }
    }

    /// When the first frame was laid out and the first field shown (as
    /// natively with `CDCA_STARTUP_REPORT`), to the console and, with the
    /// test hooks, to the page: `scripts/test-web.sh` times the browser's
    /// first frame from it.
    fn note_startup(&mut self) {
        let now = || {
            web_sys::window()
                .and_then(|w| w.performance())
                .map_or(0.0, |p| p.now())
        };
        if self.first_frame_ms.is_none() {
            let t = now();
            self.first_frame_ms = Some(t);
            log::info!("timing: first frame {t:.0} ms after navigation");
        }
        if self.first_field_ms.is_none() && self.app.borrow().runner.field().current().is_some() {
            let t = now();
            self.first_field_ms = Some(t);
            log::info!("timing: first field {t:.0} ms after navigation");
        }
    }

    /// Solve, growth and frame times to the console (`log` → `console.*`).
    fn log_timings(&mut self) {
        let mut app = self.app.borrow_mut();
        let runner = &app.runner;
        let solve = runner.last_solve_seconds();
        if solve.is_some() && solve != self.logged_solve {
            self.logged_solve = solve;
            log::info!(
                "timing: build {:.1} ms, direct solve {:.1} ms",
                runner.last_build_seconds() * 1e3,
                solve.unwrap_or_default() * 1e3
            );
        }
        let steps = app.growth_steps();
        let stats = app.frame_stats();
        if steps != self.logged_growth_steps {
            self.logged_growth_steps = steps;
            log::info!(
                "timing: growth steps {steps}, last frame {:.1} ms",
                stats.last() * 1e3
            );
        }
        // a job's frames are counted from its start, and reported at its end
        let running = app.running_job().is_some();
        let ended = self.job_was_running && !running;
        if running && !self.job_was_running {
            app.frame_stats.clear();
            self.between.take_stats();
        }
        self.job_was_running = running;
        let stats = app.frame_stats();
        let now = Instant::now();
        if (now >= self.next_report || ended) && !stats.is_empty() {
            self.next_report = now + REPORT_EVERY;
            log::info!(
                "timing: frames {} mean {:.1} ms p95 {:.1} ms max {:.1} ms, solver {:.1} ms/frame, interval {:.1} ms",
                stats.len(),
                stats.mean() * 1e3,
                stats.p95() * 1e3,
                stats.max() * 1e3,
                stats.mean_solver() * 1e3,
                stats.mean_interval() * 1e3
            );
            let work = self.between.take_stats();
            if work.tasks > 0 {
                log::info!(
                    "timing: between frames {} tasks, {:.0} ms of work",
                    work.tasks,
                    work.worked * 1e3
                );
            }
        }
    }
}

impl eframe::App for WebApp {
    /// Dropped files can only be read asynchronously here: start reading
    /// them, so the app (which reads them synchronously natively) never
    /// sees them; they come back through [`io::take_opened`].
    fn raw_input_hook(&mut self, _ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        for file in raw_input.dropped_files.drain(..) {
            io::read_dropped_later(file);
        }
    }

    fn logic(&mut self, ctx: &egui::Context, frame: &mut eframe::Frame) {
        let mut app = self.app.borrow_mut();
        Self::take_opened_files(&mut app);
        eframe::App::logic(&mut *app, ctx, frame);
        if app.job_on_page() {
            self.between.start();
        }
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        eframe::App::ui(&mut *self.app.borrow_mut(), ui, frame);
        self.note_startup();
        self.log_timings();
        if self.test_hooks {
            self.state_to_page(f64::from(ui.ctx().zoom_factor()));
        }
        if self.continuous {
            ui.ctx().request_repaint();
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::App::save(&mut *self.app.borrow_mut(), storage);
    }
}

/// Publishes every labelled widget (from egui's AccessKit tree) as
/// `window.cdcaWidgets = [{ label, role, x, y, w, h, disabled }]` in CSS
/// pixels, so the browser test can click buttons by their label as the
/// egui_kittest tests do natively.
struct WidgetsToPage;

impl egui::Plugin for WidgetsToPage {
    fn debug_name(&self) -> &'static str {
        "cdca widgets to page"
    }

    fn output_hook(&mut self, ctx: &egui::Context, output: &mut egui::FullOutput) {
        let Some(update) = output.platform_output.accesskit_update.take() else {
            return;
        };
        let zoom = f64::from(ctx.zoom_factor());
        let widgets = js_sys::Array::new();
        for (_, node) in &update.nodes {
            let (Some(label), Some(b)) = (node.label(), node.bounds()) else {
                continue;
            };
            let w = js_sys::Object::new();
            let set = |key: &str, value: JsValue| {
                let _ = js_sys::Reflect::set(&w, &key.into(), &value);
            };
            set("label", label.into());
            set("role", format!("{:?}", node.role()).into());
            set("x", (b.x0 * zoom).into());
            set("y", (b.y0 * zoom).into());
            set("w", ((b.x1 - b.x0) * zoom).into());
            set("h", ((b.y1 - b.y0) * zoom).into());
            set("disabled", node.is_disabled().into());
            widgets.push(&w);
        }
        set_on_window("cdcaWidgets", &widgets);
    }
}

/// `{ x, y, w, h }` in CSS pixels of a rectangle in points.
fn rect_to_page(r: egui::Rect, zoom: f64) -> js_sys::Object {
    let o = js_sys::Object::new();
    for (key, value) in [
        ("x", r.min.x),
        ("y", r.min.y),
        ("w", r.width()),
        ("h", r.height()),
    ] {
        let _ = js_sys::Reflect::set(&o, &key.into(), &(f64::from(value) * zoom).into());
    }
    o
}

fn set_on_window(key: &str, value: &JsValue) {
    if let Some(window) = web_sys::window() {
        let _ = js_sys::Reflect::set(&window, &key.into(), value);
    }
}

/// The page address's query string (`?…`), empty if none.
fn page_query() -> String {
    web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default()
}
