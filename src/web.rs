//! The browser wrapper around [`WorkbenchApp`]: files the browser reads
//! asynchronously (picked in the open dialog or dropped on the page) reach
//! the app as commands, and solve and frame times go to the console so the
//! browser build can be compared with the native one.
//!
//! Everything else is the same app: the same per-frame solver budget, the
//! same persistence (eframe keeps it in the page's local storage).

use wasm_bindgen::JsValue;
use web_time::{Duration, Instant};

use crate::app::WorkbenchApp;
use crate::command::Command;
use crate::io;
use crate::view::Message;

/// How often frame statistics are logged while the app is busy.
const REPORT_EVERY: Duration = Duration::from_secs(2);

/// [`WorkbenchApp`] as the web runner sees it.
pub struct WebApp {
    app: WorkbenchApp,
    /// What was last logged, to log only changes.
    logged_solve: Option<f64>,
    logged_growth_steps: usize,
    /// A job (solve, growth, race, study) ran at the last frame.
    job_was_running: bool,
    next_report: Instant,
    /// The page asked for test hooks (`?cdca_test`): the widgets and the
    /// app's state are published on `window` each frame.
    test_hooks: bool,
}

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
        let mut app = WorkbenchApp::from_creation_context(cc);
        // a shared link (`#scene=…`, src/link.rs) opens its scene, solved
        let hash = web_sys::window()
            .and_then(|w| w.location().hash().ok())
            .unwrap_or_default();
        if hash.contains("scene=") {
            app.push(Command::OpenLink(hash));
        }
        Self {
            app,
            logged_solve: None,
            logged_growth_steps: 0,
            job_was_running: false,
            next_report: Instant::now() + REPORT_EVERY,
            test_hooks,
        }
    }

    /// For the browser test: what it asserts on, as `window.cdcaState`.
    fn state_to_page(&self) {
        let state = js_sys::Object::new();
        let set = |key: &str, value: JsValue| {
            let _ = js_sys::Reflect::set(&state, &key.into(), &value);
        };
        set("sceneName", self.app.scene().name.as_str().into());
        set("solved", self.app.is_solved().into());
        set("fieldShown", self.app.field_is_shown().into());
        // Sub-cells of the shown field with a finite stress (0: nothing
        // coloured, e.g. a field sampled before a solve).
        let finite = self.app.runner.field().current().map_or(0, |f| {
            f.samples.iter().filter(|s| s.stress[0].is_finite()).count()
        });
        set("fieldFinite", (finite as f64).into());
        set("growthSteps", (self.app.growth_steps() as f64).into());
        set(
            "residualSamples",
            (self.app.residual_samples() as f64).into(),
        );
        set("runMode", format!("{:?}", self.app.run_mode()).into());
        let crack_points: usize = self.app.simulated_cracks().iter().map(Vec::len).sum();
        set("crackPoints", (crack_points as f64).into());
        set(
            "message",
            match self.app.message() {
                Some(Message::Error(e)) => format!("error: {e}").into(),
                Some(Message::Info(i)) => i.as_str().into(),
                None => JsValue::NULL,
            },
        );
        set_on_window("cdcaState", &state);
    }

    fn take_opened_files(&mut self) {
        for result in io::take_opened() {
            match result {
                Ok(file) => self.app.push(Command::OpenSceneText {
                    source: file.name,
                    text: file.text,
                }),
                Err(e) => self.app.message = Some(Message::Error(e)),
            }
        }
    }

    /// Solve, growth and frame times to the console (`log` → `console.*`).
    fn log_timings(&mut self) {
        let runner = &self.app.runner;
        let solve = runner.last_solve_seconds();
        if solve.is_some() && solve != self.logged_solve {
            self.logged_solve = solve;
            log::info!(
                "timing: build {:.1} ms, direct solve {:.1} ms",
                runner.last_build_seconds() * 1e3,
                solve.unwrap_or_default() * 1e3
            );
        }
        let steps = self.app.growth_steps();
        let stats = self.app.frame_stats();
        if steps != self.logged_growth_steps {
            self.logged_growth_steps = steps;
            log::info!(
                "timing: growth steps {steps}, last frame {:.1} ms",
                stats.last() * 1e3
            );
        }
        // a job's frames are counted from its start, and reported at its end
        let running = self.app.running_job().is_some();
        let ended = self.job_was_running && !running;
        if running && !self.job_was_running {
            self.app.frame_stats.clear();
        }
        self.job_was_running = running;
        let stats = self.app.frame_stats();
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
        self.take_opened_files();
        eframe::App::logic(&mut self.app, ctx, frame);
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        eframe::App::ui(&mut self.app, ui, frame);
        self.log_timings();
        if self.test_hooks {
            self.state_to_page();
        }
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::App::save(&mut self.app, storage);
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
