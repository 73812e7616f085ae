//! Everything that touches the file system or native dialogs, so the web
//! build has one module to replace. On the web these report that the action
//! is not available yet (a later task wires `rfd::AsyncFileDialog`).

/// A file the user picked: its name (for messages) and its text.
pub struct OpenedFile {
    pub name: String,
    pub text: String,
}

/// Asks for a scene file and reads it. `Ok(None)` when the user cancels.
#[cfg(not(target_arch = "wasm32"))]
pub fn open_scene_dialog() -> Result<Option<OpenedFile>, String> {
    let Some(path) = rfd::FileDialog::new()
        .set_title("Open scene")
        .add_filter("Scene (JSON)", &["json"])
        .pick_file()
    else {
        return Ok(None);
    };
    read_text(&path).map(Some)
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
) -> Result<Option<String>, String> {
    let Some(path) = rfd::FileDialog::new()
        .set_title("Save")
        .set_file_name(default_name)
        .add_filter(filter.0, &[filter.1])
        .save_file()
    else {
        return Ok(None);
    };
    std::fs::write(&path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(Some(path.display().to_string()))
}

#[cfg(target_arch = "wasm32")]
pub fn open_scene_dialog() -> Result<Option<OpenedFile>, String> {
    Err(
        "opening files is not available in the browser yet; drop a scene file on the window"
            .to_owned(),
    )
}

#[cfg(target_arch = "wasm32")]
pub fn read_text(_path: &std::path::Path) -> Result<OpenedFile, String> {
    Err("no file system in the browser".to_owned())
}

#[cfg(target_arch = "wasm32")]
pub fn read_dropped(_file: &egui::DroppedFileHandle) -> Result<OpenedFile, String> {
    Err("reading dropped files is not available in the browser yet".to_owned())
}

#[cfg(target_arch = "wasm32")]
pub fn save_dialog(
    _default_name: &str,
    _filter: (&str, &str),
    _bytes: &[u8],
) -> Result<Option<String>, String> {
    Err("saving files is not available in the browser yet".to_owned())
}
