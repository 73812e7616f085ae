//! Writing reports to stdout.

use std::io::Write;

use cdca::report::IntactRockReport;
use cdca::scene::IntactRock;
use serde::Serialize;

use crate::error::CliError;

/// Prints `value` as pretty JSON followed by a newline, with every `-0.0`
/// written as `0.0` (a zero residual or length read as a negative number).
pub fn print_json(value: &impl Serialize) -> Result<(), CliError> {
    let failed =
        |e: &dyn std::fmt::Display| CliError::Failure(format!("cannot write the report: {e}"));
    let text = serde_json::to_string_pretty(value).map_err(|e| failed(&e))?;
    let mut out = std::io::stdout().lock();
    out.write_all(positive_zeros(&text).as_bytes())
        .map_err(|e| failed(&e))?;
    writeln!(out)
        .and_then(|()| out.flush())
        .map_err(|e| failed(&e))
}

/// `json` with every number `-0.0` written `0.0` (outside strings; the
/// field order as serialised).
fn positive_zeros(json: &str) -> String {
    let mut out = String::with_capacity(json.len());
    let (mut in_string, mut escaped) = (false, false);
    let bytes = json.as_bytes();
    for (i, c) in json.char_indices() {
        if in_string {
            match (escaped, c) {
                (true, _) => escaped = false,
                (false, '\\') => escaped = true,
                (false, '"') => in_string = false,
                _ => {}
            }
        } else if c == '"' {
            in_string = true;
        } else if c == '-'
            && json[i + 1..].starts_with("0.0")
            && !bytes
                .get(i + 4)
                .is_some_and(|b| b.is_ascii_digit() || matches!(b, b'e' | b'E' | b'.'))
        {
            continue;
        }
        out.push(c);
    }
    out
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `-0.0` anywhere in a report (a zero residual) is written `0.0`;
    /// other numbers, strings and the field order stay as they were.
    #[test]
    fn negative_zeros_are_written_as_zeros() {
        let text = r#"{"residual": -0.0, "k": [-0.0, -1.5, -0.05, -0.0e-3], "note": "-0.0"}"#;
        assert_eq!(
            positive_zeros(text),
            r#"{"residual": 0.0, "k": [0.0, -1.5, -0.05, -0.0e-3], "note": "-0.0"}"#
        );
    }
}
