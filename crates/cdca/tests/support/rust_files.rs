//! Listing a source tree, for the layout tests of the solver crate and of
//! the workbench (included by path in both).

use std::fs;
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, in sorted order, appended to `out`.
pub fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .expect("readable source directory")
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}
