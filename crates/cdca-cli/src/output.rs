//! Writing reports to stdout.

use std::io::Write;

use serde::Serialize;

use crate::error::CliError;

/// Prints `value` as pretty JSON followed by a newline.
pub fn print_json(value: &impl Serialize) -> Result<(), CliError> {
    let failed =
        |e: &dyn std::fmt::Display| CliError::Failure(format!("cannot write the report: {e}"));
    let mut out = std::io::stdout().lock();
    serde_json::to_writer_pretty(&mut out, value).map_err(|e| failed(&e))?;
    writeln!(out)
        .and_then(|()| out.flush())
        .map_err(|e| failed(&e))
}
