//! The CDCA workbench: native window (and, later, the browser).

#![cfg_attr(not(debug_assertions), windows_subsystem = "windows")]

use cdca_workbench::WorkbenchApp;

#[cfg(not(target_arch = "wasm32"))]
fn main() -> eframe::Result {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("CDCA workbench")
            .with_inner_size([1400.0, 900.0])
            .with_min_inner_size([800.0, 500.0]),
        ..Default::default()
    };
    eframe::run_native(
        "cdca-workbench",
        options,
        Box::new(|cc| Ok(Box::new(WorkbenchApp::from_creation_context(cc)))),
    )
}

/// The web build (a later task adds `wasm-bindgen-futures` and `web-sys`
/// and starts an `eframe::WebRunner` on the page's canvas here).
#[cfg(target_arch = "wasm32")]
fn main() {
    let _ = WorkbenchApp::from_creation_context;
}
