//! Everything that touches the file system or native dialogs, so the web
//! build has one module to replace.
//!
//! In the browser, files are read asynchronously: [`open_scene_dialog`]
//! starts an `rfd::AsyncFileDialog` and returns `Ok(None)`, and
//! [`read_dropped_later`] starts reading a dropped file. Their results
//! queue up here until the app takes them with [`take_opened`] (the web
//! wrapper in `web.rs` does so every frame). Saving is a download of a
//! `Blob` through a temporary `<a download>` link, which is synchronous.

/// Whether the workbench runs in a browser (WebAssembly): what the
/// Study tab's time estimate allows for.
pub const IN_BROWSER: bool = cfg!(target_arch = "wasm32");

/// A file the user picked: its name (for messages) and its text.
pub struct OpenedFile {
    pub name: String,
    pub text: String,
}

/// What a file dialog came back with.
pub enum Picked<T> {
    Chosen(T),
    /// The user closed the dialog.
    Cancelled,
    /// No dialog could open (natively: no desktop portal and no zenity, so
    /// rfd returns at once with nothing): the app asks for a path instead.
    NoDialog,
}

/// A dialog that came back empty sooner than this never opened, s: no one
/// closes a file dialog this fast (without a dialog service rfd returns in
/// well under a millisecond).
#[cfg(not(target_arch = "wasm32"))]
const NO_DIALOG_SECONDS: f64 = 0.15;

/// `Cancelled`, or `NoDialog` when the dialog started at `start` came back
/// too soon to have been shown.
#[cfg(not(target_arch = "wasm32"))]
fn nothing_picked<T>(start: web_time::Instant) -> Picked<T> {
    if start.elapsed().as_secs_f64() < NO_DIALOG_SECONDS {
        Picked::NoDialog
    } else {
        Picked::Cancelled
    }
}

/// Copies a scene link's fragment (`scene=…`) to the clipboard; returns
/// what to tell the user.
#[cfg(not(target_arch = "wasm32"))]
pub fn share_link(ctx: &egui::Context, fragment: &str) -> String {
    ctx.copy_text(format!("#{fragment}"));
    format!(
        "Link to the scene as drawn (not the run) copied to the clipboard ({} characters): \
         append it to the web workbench's address, or open it here with cdca-workbench \
         --link",
        fragment.len() + 1
    )
}

/// Takes a stale scene link out of the page address: natively there is
/// none.
#[cfg(not(target_arch = "wasm32"))]
pub fn clear_link() {}

/// Asks for a scene file and reads it. `Ok(None)` when the user cancels.
#[cfg(not(target_arch = "wasm32"))]
pub fn open_scene_dialog(last: Option<&std::path::Path>) -> Result<Picked<OpenedFile>, String> {
    let start = web_time::Instant::now();
    let mut dialog = rfd::FileDialog::new();
    if let Some(d) = start_folder(last) {
        dialog = dialog.set_directory(d);
    }
    let Some(path) = dialog
        .set_title("Open scene")
        .add_filter("Scene (JSON)", &["json"])
        .pick_file()
    else {
        return Ok(nothing_picked(start));
    };
    read_text(&path).map(Picked::Chosen)
}

/// Writes `bytes` to `path` (typed in where no dialog could open); returns
/// where it went.
#[cfg(not(target_arch = "wasm32"))]
pub fn write_file(path: &str, bytes: &[u8]) -> Result<String, String> {
    std::fs::write(path, bytes).map_err(|e| format!("cannot write {path}: {e}"))?;
    Ok(path.to_owned())
}

/// Where a typed-in path starts: the default name in the folder last saved
/// to or opened from, else in the user's documents folder (never the
/// program's working folder, which is often its checkout).
#[cfg(not(target_arch = "wasm32"))]
pub fn default_path(name: &str, last: Option<&std::path::Path>) -> String {
    start_folder(last).map_or_else(|| name.to_owned(), |d| d.join(name).display().to_string())
}

/// The folder dialogs and typed paths start in: `last`, or the user's
/// documents folder (`~/Documents`, else the home folder).
#[cfg(not(target_arch = "wasm32"))]
pub fn start_folder(last: Option<&std::path::Path>) -> Option<std::path::PathBuf> {
    if let Some(d) = last.filter(|d| d.is_dir()) {
        return Some(d.to_owned());
    }
    let home = std::env::var_os("HOME").or_else(|| std::env::var_os("USERPROFILE"))?;
    let home = std::path::PathBuf::from(home);
    let documents = home.join("Documents");
    Some(if documents.is_dir() { documents } else { home })
}

/// Reads a dropped or picked file as text.
#[cfg(not(target_arch = "wasm32"))]
pub fn read_text(path: &std::path::Path) -> Result<OpenedFile, String> {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    Ok(OpenedFile { name, text })
}

/// Reads a file dropped on the window.
#[cfg(not(target_arch = "wasm32"))]
pub fn read_dropped(file: &egui::DroppedFileHandle) -> Result<OpenedFile, String> {
    let path = file.path();
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let bytes = file
        .bytes()
        .map_err(|e| format!("cannot read {name}: {e}"))?;
    Ok(OpenedFile {
        name,
        text: String::from_utf8_lossy(&bytes).into_owned(),
    })
}

/// Asks where to save and writes `bytes`; returns where it went, `Ok(None)`
/// when the user cancels.
#[cfg(not(target_arch = "wasm32"))]
pub fn save_dialog(
    default_name: &str,
    filter: (&str, &str),
    bytes: &[u8],
    last: Option<&std::path::Path>,
) -> Result<Picked<String>, String> {
    let start = web_time::Instant::now();
    let mut dialog = rfd::FileDialog::new();
    if let Some(d) = start_folder(last) {
        dialog = dialog.set_directory(d);
    }
    let Some(path) = dialog
        .set_title("Save")
        .set_file_name(default_name)
        .add_filter(filter.0, &[filter.1])
        .save_file()
    else {
        return Ok(nothing_picked(start));
    };
    std::fs::write(&path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(Picked::Chosen(path.display().to_string()))
}

#[cfg(target_arch = "wasm32")]
pub use web::{read_dropped_later, set_repaint_context, take_opened};

/// Starts the browser's file picker; the file arrives through
/// [`take_opened`] a few frames later. Always `Ok(None)` now.
/// Puts a scene link into the page address (its fragment: no reload) and
/// copies the address to the clipboard; returns what to tell the user.
#[cfg(target_arch = "wasm32")]
pub fn share_link(ctx: &egui::Context, fragment: &str) -> String {
    let Some(location) = web_sys::window().map(|w| w.location()) else {
        return "no page address to put the link in".to_owned();
    };
    let _ = location.set_hash(fragment);
    let href = location.href().unwrap_or_default();
    ctx.copy_text(href.clone());
    format!(
        "Link to the scene as drawn (not the run) copied to the clipboard ({} characters); \
         the page address opens this scene until it is edited or reset",
        href.len()
    )
}

/// Takes a stale scene link out of the page address: an empty fragment,
/// no reload (the address keeps a bare `#`).
#[cfg(target_arch = "wasm32")]
pub fn clear_link() {
    if let Some(location) = web_sys::window().map(|w| w.location()) {
        let _ = location.set_hash("");
    }
}

/// The browser has no file system to write a typed-in path to (its
/// downloads always work, so no path is asked for).
#[cfg(target_arch = "wasm32")]
pub fn write_file(path: &str, _bytes: &[u8]) -> Result<String, String> {
    Err(format!(
        "cannot write {path}: the browser has no file system"
    ))
}

/// The browser has no file system to read a typed-in path from.
#[cfg(target_arch = "wasm32")]
pub fn read_text(path: &std::path::Path) -> Result<OpenedFile, String> {
    Err(format!(
        "cannot read {}: the browser has no file system",
        path.display()
    ))
}

/// Where a typed-in path starts: the default name.
#[cfg(target_arch = "wasm32")]
pub fn default_path(name: &str, _last: Option<&std::path::Path>) -> String {
    name.to_owned()
}

// the native dialog's signature: it can fail, this one cannot
#[cfg(target_arch = "wasm32")]
#[allow(clippy::unnecessary_wraps)]
pub fn open_scene_dialog(_last: Option<&std::path::Path>) -> Result<Picked<OpenedFile>, String> {
    wasm_bindgen_futures::spawn_local(async {
        let picked = rfd::AsyncFileDialog::new()
            .set_title("Open scene")
            .add_filter("Scene (JSON)", &["json"])
            .pick_file()
            .await;
        if let Some(file) = picked {
            let bytes = file.read().await;
            web::finish(Ok(OpenedFile {
                name: file.file_name(),
                text: String::from_utf8_lossy(&bytes).into_owned(),
            }));
        }
    });
    Ok(Picked::Cancelled)
}

/// Dropped files can only be read asynchronously in the browser: the web
/// wrapper takes them out of the input before the app sees them and calls
/// [`read_dropped_later`]. Reaching this is a bug, reported as an error.
#[cfg(target_arch = "wasm32")]
pub fn read_dropped(file: &egui::DroppedFileHandle) -> Result<OpenedFile, String> {
    Err(format!(
        "cannot read {} synchronously in the browser",
        file.path().display()
    ))
}

/// Offers `bytes` as a download named `default_name` (the browser decides
/// where it goes); returns that name.
#[cfg(target_arch = "wasm32")]
pub fn save_dialog(
    default_name: &str,
    filter: (&str, &str),
    bytes: &[u8],
    _last: Option<&std::path::Path>,
) -> Result<Picked<String>, String> {
    web::download(default_name, mime_type(filter.1), bytes)
        .map_err(|e| format!("cannot download {default_name}: {e}"))?;
    Ok(Picked::Chosen(format!("{default_name} (downloaded)")))
}

/// The MIME type for a file extension the app exports.
#[cfg(target_arch = "wasm32")]
fn mime_type(extension: &str) -> &'static str {
    match extension {
        "json" => "application/json",
        "csv" => "text/csv",
        "png" => "image/png",
        "vtu" => "application/xml",
        _ => "application/octet-stream",
    }
}

/// The browser half: the queue of files read asynchronously, and downloads.
#[cfg(target_arch = "wasm32")]
mod web {
    use std::cell::RefCell;

    use wasm_bindgen::{JsCast as _, JsValue};

    use super::OpenedFile;

    thread_local! {
        /// Files read (or failed) since the app last looked.
        static OPENED: RefCell<Vec<Result<OpenedFile, String>>> = const { RefCell::new(Vec::new()) };
        /// Woken when a file arrives, so an idle app notices it.
        static REPAINT: RefCell<Option<egui::Context>> = const { RefCell::new(None) };
    }

    /// Lets finished reads wake the app.
    pub fn set_repaint_context(ctx: egui::Context) {
        REPAINT.with(|r| *r.borrow_mut() = Some(ctx));
    }

    /// Files read since the last call, oldest first.
    pub fn take_opened() -> Vec<Result<OpenedFile, String>> {
        OPENED.with(|o| std::mem::take(&mut *o.borrow_mut()))
    }

    pub(super) fn finish(result: Result<OpenedFile, String>) {
        OPENED.with(|o| o.borrow_mut().push(result));
        REPAINT.with(|r| {
            if let Some(ctx) = r.borrow().as_ref() {
                ctx.request_repaint();
            }
        });
    }

    /// Starts reading a file dropped on the page; see [`take_opened`].
    pub fn read_dropped_later(file: egui::DroppedFileHandle) {
        wasm_bindgen_futures::spawn_local(async move {
            let name = file.path().display().to_string();
            let result = file
                .bytes_async()
                .await
                .map(|bytes| OpenedFile {
                    name: name.clone(),
                    text: String::from_utf8_lossy(&bytes).into_owned(),
                })
                .map_err(|e| format!("cannot read {name}: {e}"));
            finish(result);
        });
    }

    /// Downloads `bytes` as `name`: a `Blob`, an object URL, and a click on
    /// a temporary `<a download>`.
    pub(super) fn download(name: &str, mime: &str, bytes: &[u8]) -> Result<(), String> {
        let js = |e: JsValue| format!("{e:?}");
        let document = web_sys::window()
            .and_then(|w| w.document())
            .ok_or("no document")?;
        let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes));
        let options = web_sys::BlobPropertyBag::new();
        options.set_type(mime);
        let blob =
            web_sys::Blob::new_with_u8_array_sequence_and_options(&parts, &options).map_err(js)?;
        let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(js)?;
        let anchor: web_sys::HtmlAnchorElement = document
            .create_element("a")
            .map_err(js)?
            .dyn_into()
            .map_err(|_| "not an anchor element")?;
        anchor.set_href(&url);
        anchor.set_download(name);
        anchor.click();
        // Give the browser a moment to start the download before the URL
        // goes away.
        let revoke = wasm_bindgen::closure::Closure::once_into_js(move || {
            let _ = web_sys::Url::revoke_object_url(&url);
        });
        web_sys::window()
            .ok_or("no window")?
            .set_timeout_with_callback_and_timeout_and_arguments_0(revoke.unchecked_ref(), 1000)
            .map_err(js)?;
        Ok(())
    }
}
