//! The points run on a thread pool (rayon: the workspace's pool, with
//! work handed out in order), their rows handed back on this thread in the
//! order they finish, with a progress bar on stderr (indicatif: points
//! done, time gone and time left; drawn only on a terminal).

use std::sync::atomic::{AtomicBool, Ordering};

use cdca::study::{Point, Row, Study};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::iter::{ParallelBridge, ParallelIterator};

use crate::error::CliError;

/// Runs `pending` on `jobs` threads, each row given to `sink` as it
/// finishes. Points are taken in order (a shared queue: `par_bridge`), so
/// the rows come nearly in order. When `sink` fails, no point starts
/// after it and the error is returned once the running ones end.
pub fn run(
    study: &Study,
    pending: Vec<&Point>,
    jobs: usize,
    mut sink: impl FnMut(Row) -> Result<(), CliError>,
) -> Result<(), CliError> {
    if pending.is_empty() {
        return Ok(());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| CliError::Failure(format!("cannot start {jobs} threads: {e}")))?;
    let bar = ProgressBar::new(pending.len() as u64);
    if let Ok(style) = ProgressStyle::with_template(
        "{bar:30} {pos}/{len} points, {elapsed_precise} gone, {eta_precise} left",
    ) {
        bar.set_style(style);
    }
    let stop = AtomicBool::new(false);
    let (tx, rx) = std::sync::mpsc::channel::<Row>();
    let result = std::thread::scope(|scope| {
        let stop = &stop;
        scope.spawn(move || {
            pool.install(|| {
                pending
                    .into_iter()
                    .par_bridge()
                    .for_each_with(tx, |tx, point| {
                        if !stop.load(Ordering::Relaxed) {
                            // the receiver is gone only after an error
                            let _ = tx.send(study.run_point(point));
                        }
                    });
            });
        });
        let mut result = Ok(());
        for row in rx {
            if result.is_ok() {
                result = sink(row);
                if result.is_err() {
                    stop.store(true, Ordering::Relaxed);
                }
            }
            bar.inc(1);
        }
        result
    });
    bar.finish_and_clear();
    result
}
