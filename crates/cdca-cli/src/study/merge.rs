//! `--merge`: shards' tables joined into the single run's (the same
//! bytes, each row's `seconds` aside): every point of the study once, in
//! point order, under the study's header.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use cdca::study::Study;
use cdca::study::row::row_key;

use super::table::write_sorted;
use crate::error::CliError;

/// Joins `files` into `out`; returns the rows written.
pub fn merge(files: &[PathBuf], out: &Path, study: &Study) -> Result<usize, CliError> {
    let header = study.header();
    let hash = study.short_hash();
    let mut rows: BTreeMap<usize, (String, &Path)> = BTreeMap::new();
    for file in files {
        let bad = |why: String| CliError::Input(format!("`{}`: {why}", file.display()));
        let text = std::fs::read_to_string(file)
            .map_err(|e| CliError::Input(format!("cannot read `{}`: {e}", file.display())))?;
        if !text.ends_with('\n') {
            return Err(bad(
                "its last line is cut short: run that shard again to finish it".to_owned(),
            ));
        }
        let mut lines = text.split_inclusive('\n');
        if lines.next() != Some(header.as_str()) {
            return Err(bad("its columns are not this study's".to_owned()));
        }
        for (i, line) in lines.enumerate() {
            let (id, study) =
                row_key(line).ok_or_else(|| bad(format!("line {} is not a row", i + 2)))?;
            if study != hash {
                return Err(bad(format!(
                    "line {} is a row of study {study}, this study is {hash}",
                    i + 2
                )));
            }
            if let Some((_, other)) = rows.insert(id, (line.to_owned(), file)) {
                return Err(bad(format!("point {id} is in `{}` too", other.display())));
            }
        }
    }
    let missing: Vec<String> = study
        .points()
        .iter()
        .filter(|p| !rows.contains_key(&p.id))
        .map(|p| p.id.to_string())
        .collect();
    if !missing.is_empty() {
        let shown = missing
            .iter()
            .take(10)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        return Err(CliError::Input(format!(
            "--merge: {} of {} points of the study have no row (points {shown}{}): finish their shards first",
            missing.len(),
            study.points().len(),
            if missing.len() > 10 { ", …" } else { "" }
        )));
    }
    let lines: BTreeMap<usize, String> = rows.into_iter().map(|(id, (l, _))| (id, l)).collect();
    write_sorted(out, &header, &lines)?;
    Ok(lines.len())
}
