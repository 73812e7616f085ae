//! The CLI's error: what went wrong, and which exit code says so.

use std::fmt;

use cdca::SolveError;

/// A failure of a subcommand, shown as one line on stderr.
#[derive(Debug)]
pub enum CliError {
    /// Bad input: arguments, an unreadable or invalid scene, an unwritable
    /// output path. Exit code 2.
    Input(String),
    /// The solver could not produce a trustworthy answer, or the report could
    /// not be written. Exit code 1.
    Failure(String),
}

impl CliError {
    pub fn exit_code(&self) -> u8 {
        match self {
            Self::Input(_) => 2,
            Self::Failure(_) => 1,
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Input(m) | Self::Failure(m) => f.write_str(m),
        }
    }
}

impl From<SolveError> for CliError {
    fn from(e: SolveError) -> Self {
        match e {
            SolveError::Scene(_) => Self::Input(e.to_string()),
            _ => Self::Failure(e.to_string()),
        }
    }
}
