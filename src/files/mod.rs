//! **Files**: the scenes and files the user opens, saves and shares. Uses
//! nothing of the workbench.
//!
//! - `scenes`: the bundled scenes and the default one;
//! - `io`: open, save and download, native and in a browser;
//! - `link`: a scene carried in a link's fragment;
//! - `path_prompt`: the typed path where no file dialog is.

pub(crate) mod io;
pub mod link;
pub(crate) mod path_prompt;
pub mod scenes;
