//! A path typed in where no file dialog can open (a Linux desktop without
//! a file-dialog portal or zenity): File ▸ Save and Open say so and show a
//! path field instead of doing nothing.

/// What the typed path is for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PromptAction {
    /// Write these bytes there.
    Save { bytes: Vec<u8> },
    /// Write the scene there as it stands when the path is used (a growth
    /// run may have gone on since Save was chosen).
    SaveScene,
    /// Open the scene file there.
    Open,
}

/// The path field shown above the canvas.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PathPrompt {
    pub action: PromptAction,
    /// The path as typed so far.
    pub path: String,
}

impl PathPrompt {
    /// What the banner says.
    pub fn text(&self) -> &'static str {
        match self.action {
            PromptAction::Save { .. } => {
                "No file dialog could open here (no desktop file-dialog portal or zenity). \
                 Type the path to save to:"
            }
            PromptAction::SaveScene => {
                "No file dialog could open here (no desktop file-dialog portal or zenity). \
                 Type the path to save to (the scene is written as it stands when you press \
                 Save here, with the growth steps done by then):"
            }
            PromptAction::Open => {
                "No file dialog could open here (no desktop file-dialog portal or zenity). \
                 Type the path of the scene file to open:"
            }
        }
    }

    /// The label of the button that uses the path.
    pub fn button(&self) -> &'static str {
        match self.action {
            PromptAction::Save { .. } | PromptAction::SaveScene => "Save here",
            PromptAction::Open => "Open this file",
        }
    }
}
