//! `cdca`: the command-line face of the solver (SPEC §11).
//!
//! Every subcommand exits 0 on success. On failure it prints one line
//! `cdca: <message>` on stderr and exits 2 for bad input (arguments, scene
//! file, output directory) or 1 when the solver fails. Each subcommand lives
//! in its own module with an `Args` struct and a `run` function.

mod bench;
mod error;
mod grow;
mod output;
mod scene_file;
mod solve;
mod study;
mod svg;
mod sweep;
mod validate;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::error::CliError;

/// Crack growth in brittle rock with the continuous–discontinuous cellular
/// automaton method.
#[derive(Debug, Parser)]
#[command(name = "cdca", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Check a scene file; prints nothing when it is valid.
    Validate(validate::Args),
    /// Solve a scene at full load (no growth) and print the report as JSON.
    Solve(solve::Args),
    /// Grow the cracks of a scene (SPEC §9) and print the history as JSON.
    Grow(grow::Args),
    /// The first critical-growth step (angle, mode, λ_cr, K_I, K_II) for
    /// each value of one scene parameter; a table, and CSV with `--csv`.
    Sweep(sweep::Args),
    /// Error against run time of every solver (CSV, SVG and a table).
    Bench(bench::Args),
    /// Every point of a study file grown as `cdca grow` grows it, one CSV
    /// row each, on every core; resumable, in shards, merged.
    Study(study::Args),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(), // --help, --version
        Err(e) => return report(&CliError::Input(usage_message(&e))),
    };
    let result = match cli.command {
        Command::Validate(args) => validate::run(&args),
        Command::Solve(args) => solve::run(&args),
        Command::Grow(args) => grow::run(&args),
        Command::Sweep(args) => sweep::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Study(args) => study::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => report(&e),
    }
}

/// Prints the error as one line on stderr and returns its exit code.
fn report(error: &CliError) -> ExitCode {
    let message = error.to_string().replace(['\n', '\r'], " ");
    eprintln!("cdca: {}", message.trim());
    ExitCode::from(error.exit_code())
}

/// The first paragraph of clap's message, on one line and without its
/// `error: ` prefix, plus a pointer to `--help`.
fn usage_message(e: &clap::Error) -> String {
    if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        let cli = <Cli as clap::CommandFactory>::command();
        let names: Vec<&str> = cli.get_subcommands().map(clap::Command::get_name).collect();
        return format!(
            "missing subcommand: one of {} (see `cdca --help`)",
            names.join(", ")
        );
    }
    let rendered = e.render().to_string();
    let first = rendered.trim().split("\n\n").next().unwrap_or_default();
    let words: Vec<&str> = first.split_whitespace().collect();
    let message = words.join(" ");
    format!(
        "{} (see `cdca --help`)",
        message.trim_start_matches("error:").trim()
    )
}
