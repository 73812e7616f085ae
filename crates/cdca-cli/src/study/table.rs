//! The study's table on disk: the rows a stopped run left (kept, not
//! run again), rows appended whole as their points finish, and, when every
//! point of the run is there, the file rewritten in point order.
//!
//! A row is written with one `write` of its whole line to a file opened
//! for appending; a line cut short all the same (a full disk) has no line
//! break, and the next run cuts it off before it appends.

use std::collections::{BTreeMap, BTreeSet};
use std::fs::{File, OpenOptions};
use std::io::Write as _;
use std::path::{Path, PathBuf};

use cdca::study::row::row_key;
use cdca::study::{Point, Row, Study};

use crate::error::CliError;

/// The table being written.
pub struct Output {
    path: PathBuf,
    file: File,
    header: String,
    hash: String,
    /// The points of this run (its shard).
    wanted: BTreeSet<usize>,
    /// Point → its line, those on disk.
    rows: BTreeMap<usize, String>,
}

impl Output {
    /// Opens `path` for the `points` of `study`: reads the rows already
    /// there, checking that they are this study's and this run's; creates
    /// the file with its header when it does not exist. Nothing is run
    /// before this has succeeded, and a file of another study is left as
    /// it is.
    pub fn open(path: &Path, study: &Study, points: &[&Point]) -> Result<Self, CliError> {
        let failed = |what: &str, e: &dyn std::fmt::Display| {
            CliError::Input(format!("cannot {what} `{}`: {e}", path.display()))
        };
        let header = study.header();
        let hash = study.short_hash().to_owned();
        let wanted: BTreeSet<usize> = points.iter().map(|p| p.id).collect();
        let mut rows = BTreeMap::new();
        match std::fs::metadata(path) {
            Ok(m) if !m.is_file() => return Err(failed("write", &"not a regular file")),
            Ok(_) => {
                let text = std::fs::read_to_string(path).map_err(|e| failed("read", &e))?;
                let whole = text.rfind('\n').map_or(0, |i| i + 1);
                if !text.is_empty() {
                    read_rows(path, &text[..whole], &header, &hash, &wanted, &mut rows)?;
                }
                if whole < text.len() {
                    // a line cut short: not a row
                    let f = OpenOptions::new()
                        .write(true)
                        .open(path)
                        .map_err(|e| failed("write", &e))?;
                    f.set_len(whole as u64).map_err(|e| failed("write", &e))?;
                    eprintln!(
                        "cdca: note: `{}` ended in a line cut short; it was cut off",
                        path.display()
                    );
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(failed("read", &e)),
        }
        let mut file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(|e| failed("write", &e))?;
        if file.metadata().map_err(|e| failed("read", &e))?.len() == 0 {
            file.write_all(header.as_bytes())
                .map_err(|e| failed("write", &e))?;
        }
        Ok(Self {
            path: path.to_owned(),
            file,
            header,
            hash,
            wanted,
            rows,
        })
    }

    /// Rows on disk.
    pub fn done(&self) -> usize {
        self.rows.len()
    }

    pub fn has(&self, id: usize) -> bool {
        self.rows.contains_key(&id)
    }

    /// Appends `row`, whole.
    pub fn append(&mut self, row: &Row) -> Result<(), CliError> {
        let line = row.csv(&self.hash);
        self.file
            .write_all(line.as_bytes())
            .and_then(|()| self.file.flush())
            .map_err(|e| CliError::Input(format!("cannot write `{}`: {e}", self.path.display())))?;
        self.rows.insert(row.point, line);
        Ok(())
    }

    /// When every point of the run has its row: the file rewritten in
    /// point order (through a file beside it, renamed over it). Returns
    /// the rows on disk.
    pub fn finish(self) -> Result<usize, CliError> {
        if self.wanted.iter().all(|id| self.rows.contains_key(id)) {
            write_sorted(&self.path, &self.header, &self.rows)?;
        }
        Ok(self.rows.len())
    }
}

/// Reads the rows of `text` (whole lines), checking the header, the
/// study and the points, into `rows`.
fn read_rows(
    path: &Path,
    text: &str,
    header: &str,
    hash: &str,
    wanted: &BTreeSet<usize>,
    rows: &mut BTreeMap<usize, String>,
) -> Result<(), CliError> {
    let bad = |why: String| CliError::Input(format!("`{}`: {why}", path.display()));
    let mut lines = text.split_inclusive('\n');
    if lines.next().is_some_and(|first| first != header) {
        return Err(bad(
            "its columns are not this study's (another study's table?): choose another --out"
                .to_owned(),
        ));
    }
    for (i, line) in lines.enumerate() {
        let (id, study) =
            row_key(line).ok_or_else(|| bad(format!("line {} is not a row", i + 2)))?;
        if study != hash {
            return Err(bad(format!(
                "line {} is a row of study {study}, this study is {hash} (the study file \
                 changed?): choose another --out",
                i + 2
            )));
        }
        if !wanted.contains(&id) {
            return Err(bad(format!(
                "line {}: point {id} is not one of this run's points (another shard's table?)",
                i + 2
            )));
        }
        if rows.insert(id, line.to_owned()).is_some() {
            return Err(bad(format!("line {}: point {id} twice", i + 2)));
        }
    }
    Ok(())
}

/// `header` and the rows in point order, written to `path` through a
/// file beside it.
pub fn write_sorted(
    path: &Path,
    header: &str,
    rows: &BTreeMap<usize, String>,
) -> Result<(), CliError> {
    let failed =
        |e: std::io::Error| CliError::Input(format!("cannot write `{}`: {e}", path.display()));
    let mut text = header.to_owned();
    for line in rows.values() {
        text.push_str(line);
    }
    let mut temp = path.as_os_str().to_owned();
    temp.push(".part");
    let temp = PathBuf::from(temp);
    std::fs::write(&temp, text).map_err(failed)?;
    std::fs::rename(&temp, path).map_err(failed)
}
