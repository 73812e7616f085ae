//! Writing reports to stdout.

use std::io::Write;

use cdca::report::IntactRockReport;
use cdca::scene::IntactRock;
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

/// Notes on stderr that the rock away from the cracks is past its own
/// strength `when` (e.g. "at full load"): the tip criterion does not check
/// it, so a user reading only the cracks would not know.
pub fn note_intact_rock(when: &str, r: Option<&IntactRockReport>, model: IntactRock) {
    if let Some(r) = r.filter(|r| r.utilisation >= 1.0) {
        let why = match model {
            IntactRock::Ignore => {
                "the paper's model (growth.intact_rock = \"ignore\") does not let it fail"
            }
            IntactRock::Nucleate => "growth would start a crack there",
        };
        eprintln!(
            "cdca: note: {when} the rock away from the cracks is past its Mohr–Coulomb \
             strength (median utilisation {:.2}, σ_c = {:.1} MPa); {why}",
            r.utilisation,
            r.ucs / 1e6
        );
    }
}
