//! The one job slot: the solve, a relaxation, a growth run, the solver
//! race and a parameter study are long work the app runs one at a time.
//! A job asked for while another holds the slot waits, and the banner says
//! so ([`Waiting`]): it starts when the running one ends, or at once if
//! the user cancels the running one, or never if the user drops it.

use crate::run::RunMode;
use crate::state::command::Command;

/// The long work that holds the slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Job {
    /// Solve, Step or Relax: the runner's relaxation (a direct solve too).
    Solve,
    /// Run growth or Grow one step.
    Growth,
    /// Compare solvers.
    Race,
    /// Run study.
    Study,
}

impl Job {
    /// The job of a runner in `mode`, if it runs one.
    pub fn of_run(mode: RunMode) -> Option<Self> {
        match mode {
            RunMode::Paused => None,
            RunMode::Relaxing | RunMode::SolvingDrag => Some(Self::Solve),
            RunMode::Growing | RunMode::GrowingOne => Some(Self::Growth),
        }
    }

    /// The job a command starts, if it starts one.
    pub fn of_command(cmd: &Command) -> Option<Self> {
        match cmd {
            Command::Solve | Command::Step | Command::Relax => Some(Self::Solve),
            Command::GrowOne | Command::RunGrowth => Some(Self::Growth),
            Command::CompareSolvers { .. } => Some(Self::Race),
            Command::RunStudy(_) | Command::RunStudyFile(_) => Some(Self::Study),
            _ => None,
        }
    }

    /// The job in words, as in "the solver race is running".
    pub fn name(self) -> &'static str {
        match self {
            Self::Solve => "the solve",
            Self::Growth => "the growth run",
            Self::Race => "the solver race",
            Self::Study => "the study",
        }
    }

    /// What the button that starts the job does, in words.
    pub fn start_words(self) -> &'static str {
        match self {
            Self::Solve => "solve",
            Self::Growth => "grow",
            Self::Race => "race the solvers",
            Self::Study => "run the study",
        }
    }
}

/// A job asked for while another ran: it starts when that one ends, or
/// when the user cancels it.
#[derive(Clone, Debug)]
pub struct Waiting {
    /// The job holding the slot when this one was asked for.
    pub running: Job,
    /// The command that starts the job asked for.
    pub command: Command,
}

impl Waiting {
    /// The job asked for.
    pub fn job(&self) -> Option<Job> {
        Job::of_command(&self.command)
    }

    fn wanted(&self) -> &'static str {
        self.job().map_or("start this", Job::start_words)
    }

    /// What the banner says.
    pub fn text(&self) -> String {
        format!(
            "{} is running, and one job runs at a time: the workbench will {} when it ends.",
            capitalised(self.running.name()),
            self.wanted()
        )
    }

    /// The label of the button that cancels the running job and starts
    /// the one asked for.
    pub fn confirm_label(&self) -> String {
        format!("Cancel {} and {} now", self.running.name(), self.wanted())
    }

    /// The label of the button that drops the job asked for.
    pub fn drop_label(&self) -> String {
        format!("Don't {}", self.wanted())
    }
}

/// `s` with its first letter in upper case.
pub fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_banner_names_both_jobs() {
        let w = Waiting {
            running: Job::Race,
            command: Command::RunGrowth,
        };
        assert_eq!(
            w.text(),
            "The solver race is running, and one job runs at a time: the workbench will grow \
             when it ends."
        );
        assert_eq!(w.confirm_label(), "Cancel the solver race and grow now");
        assert_eq!(w.drop_label(), "Don't grow");
    }
}
