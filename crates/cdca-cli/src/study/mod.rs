//! `cdca study STUDY.json`: every point of a study (`cdca::study`) grown
//! as `cdca grow` grows its scene, one CSV row each, on every core;
//! resumable, in shards (`--shard i/n`) joined by `--merge`, summed up per
//! layout on stdout, and drawn as a map (`--map FILE.svg`).
//!
//! - `table.rs`: the CSV file: the rows already there (resume), rows
//!   appended whole, the file rewritten in point order at the end;
//! - `pool.rs`: the runs on a thread pool, rows back in the order they
//!   finish, the progress bar;
//! - `merge.rs`: shards' tables joined into the single run's;
//! - `map.rs`: the map figure (SVG) over two numeric axes, per layout.

mod map;
mod merge;
mod pool;
mod table;

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use cdca::study::{Study, Table};

use crate::error::CliError;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Study file (JSON; docs/studies.md).
    study: PathBuf,
    /// The table (CSV) to write, or to resume: its finished rows are kept
    /// [default: STUDY's name with .csv, in the current folder; with
    /// --shard i/n, .shard-i-of-n.csv].
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Points run at once [default: the machine's cores].
    #[arg(long, value_name = "N")]
    jobs: Option<usize>,
    /// Run shard I of N only (1-based): points I, I+N, I+2N, …
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
    /// Threads each run's element integration may use [default: cores /
    /// jobs, at least 1]; the rest of a run uses one.
    #[arg(long, value_name = "N")]
    solver_threads: Option<usize>,
    /// Join these shards' tables into the single run's table (--out); runs
    /// nothing.
    #[arg(long, value_name = "FILE", num_args = 1.., conflicts_with_all = ["shard", "point"])]
    merge: Vec<PathBuf>,
    /// Print point K's scene (JSON, as `cdca grow` reads it) and exit.
    #[arg(long, value_name = "K", conflicts_with = "shard")]
    point: Option<usize>,
    /// Also draw the finished table as a map over its first two numeric
    /// axes, one panel per layout (SVG).
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
}

pub fn run(args: &Args) -> Result<(), CliError> {
    let study = read(&args.study)?;
    if let Some(k) = args.point {
        return print_point(&args.study, &study, k);
    }
    let shard = match &args.shard {
        Some(text) => Some(
            parse_shard(text)
                .map_err(|e| CliError::Input(format!("{}: {e}", args.study.display())))?,
        ),
        None => None,
    };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| default_out(&args.study, shard));
    let started = Instant::now();
    let (rows, resumed, ran) = if args.merge.is_empty() {
        let jobs = args.jobs.unwrap_or_else(cores);
        if jobs == 0 {
            return Err(CliError::Input(format!(
                "{}: --jobs 0: at least one job",
                args.study.display()
            )));
        }
        let threads = args.solver_threads.unwrap_or((cores() / jobs).max(1));
        cdca::discretisation::xfem::set_integration_threads(threads);
        let (i, n) = shard.unwrap_or((1, 1));
        let points: Vec<_> = study.shard(i, n).collect();
        let mut file = table::Output::open(&out, &study, &points)?;
        let resumed = file.done();
        let pending: Vec<_> = points.into_iter().filter(|p| !file.has(p.id)).collect();
        let ran = pending.len();
        pool::run(&study, pending, jobs, |row| file.append(&row))?;
        (file.finish()?, resumed, ran)
    } else {
        let rows = merge::merge(&args.merge, &out, &study)?;
        (rows, 0, 0)
    };
    let text = std::fs::read_to_string(&out)
        .map_err(|e| CliError::Input(format!("cannot read `{}`: {e}", out.display())))?;
    let table =
        Table::parse(&text).map_err(|e| CliError::Failure(format!("{}: {e}", out.display())))?;
    if let Some(path) = &args.map {
        let svg = map::draw(&table, &study).map_err(|e| CliError::Input(format!("--map: {e}")))?;
        std::fs::write(path, svg)
            .map_err(|e| CliError::Input(format!("cannot write `{}`: {e}", path.display())))?;
    }
    report(&study, &out, &table, rows, resumed, ran, started);
    Ok(())
}

/// Reads and checks the study file; the scene file it names is read
/// relative to it. Every problem names the file.
fn read(path: &Path) -> Result<Study, CliError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| CliError::Input(format!("cannot read `{}`: {e}", path.display())))?;
    let dir = path.parent().unwrap_or(Path::new("."));
    Study::parse(&text, |scene| {
        std::fs::read_to_string(dir.join(scene))
            .map_err(|e| format!("cannot read `{}`: {e}", dir.join(scene).display()))
    })
    .map_err(|e| CliError::Input(format!("{}: {e}", path.display())))
}

/// `--point K`: the point's scene as JSON on stdout.
fn print_point(path: &Path, study: &Study, k: usize) -> Result<(), CliError> {
    let point = study.point(k).ok_or_else(|| {
        CliError::Input(format!(
            "--point {k}: {} has points 1 to {}",
            path.display(),
            study.points().len()
        ))
    })?;
    let scene = study
        .scene(point)
        .map_err(|e| CliError::Input(format!("{}: point {k}: {e}", path.display())))?;
    crate::output::print_json(&scene)
}

/// `I/N` with 1 ≤ I ≤ N.
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let bad = |why: &str| format!("--shard {text}: {why}");
    let (i, n) = text
        .split_once('/')
        .ok_or_else(|| bad("expects I/N, as 2/4"))?;
    let (i, n): (usize, usize) = (
        i.trim()
            .parse()
            .map_err(|_| bad("I is not a whole number"))?,
        n.trim()
            .parse()
            .map_err(|_| bad("N is not a whole number"))?,
    );
    if n == 0 || i == 0 || i > n {
        return Err(bad(&format!(
            "the shard must be 1 to N (N ≥ 1), here {i} of {n}"
        )));
    }
    Ok((i, n))
}

/// `STEM.csv`, or `STEM.shard-I-of-N.csv`, in the current folder.
fn default_out(study: &Path, shard: Option<(usize, usize)>) -> PathBuf {
    let stem = study
        .file_stem()
        .map_or("study".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from(match shard {
        Some((i, n)) => format!("{stem}.shard-{i}-of-{n}.csv"),
        None => format!("{stem}.csv"),
    })
}

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// What was done, on stdout: the study, the table, and its summary per
/// layout (Markdown); points that did not converge or were invalid are
/// noted on stderr.
fn report(
    study: &Study,
    out: &Path,
    table: &Table,
    rows: usize,
    resumed: usize,
    ran: usize,
    started: Instant,
) {
    let mut text = format!(
        "study `{}` (sha256 {}): {} points; {} rows in `{}` ({resumed} resumed, {ran} run in {:.1} s)\n\n{}",
        study.name,
        study.hash,
        study.points().len(),
        rows,
        out.display(),
        started.elapsed().as_secs_f64(),
        cdca::study::summary::HEADER
    );
    for (_, row) in cdca::study::summary::by_layout(table) {
        text.push_str(&row);
    }
    if table.column("link_joins").is_some() {
        text.push('\n');
        text.push_str(cdca::study::summary::KIND_HEADER);
        for (_, row) in cdca::study::summary::by_crack_kind(table) {
            text.push_str(&row);
        }
    }
    // the table is on disk: a closed stdout (`| head`) loses the summary only
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
    let points = |pick: &dyn Fn(usize) -> bool| -> Vec<String> {
        (0..table.rows.len())
            .filter(|&r| pick(r))
            .map(|r| table.cell(r, "point").to_owned())
            .collect()
    };
    let invalid = points(&|r| table.cell(r, "outcome") == "invalid");
    let unconverged = points(&|r| table.cell(r, "every_step_converged") == "false");
    if !invalid.is_empty() {
        eprintln!(
            "cdca: note: points {} are invalid: their scene refused the values (column `error`)",
            invalid.join(", ")
        );
    }
    if !unconverged.is_empty() {
        eprintln!(
            "cdca: note: points {} have a step that did not converge (`every_step_converged`)",
            unconverged.join(", ")
        );
    }
}
