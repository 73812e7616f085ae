//! Times the run the command line started (`cdca-workbench SCENE --run grow
//! --time-run`): the wall time from the frame that starts it to the frame
//! it ends in, and the frames meanwhile (CPU time of logic and UI, and the
//! interval between frames), and the host's own time meanwhile (how much
//! of the wall time it worked), summed up in one line for a script
//! (docs/benchmarks.md, "Run growth in the workbench against cdca grow").

use web_time::Instant;

/// The run's start and its frames.
#[derive(Debug, Default)]
pub struct RunTimer {
    start: Option<Instant>,
    /// The host's own time at the start, s (`Runner::host_seconds`).
    host_start: f64,
    /// Frame CPU time, s.
    cpu: Vec<f64>,
    /// Interval since the previous frame, s.
    interval: Vec<f64>,
    done: bool,
}

impl RunTimer {
    /// The run starts now (its command is applied in this frame); the
    /// host has worked `host_seconds` so far.
    pub fn start(&mut self, host_seconds: f64) {
        if self.start.is_none() {
            self.start = Some(Instant::now());
            self.host_start = host_seconds;
        }
    }

    /// Timing, not yet ended.
    pub fn is_timing(&self) -> bool {
        self.start.is_some() && !self.done
    }

    /// A frame of the run.
    pub fn record(&mut self, cpu: f64, interval: f64) {
        if self.is_timing() {
            self.cpu.push(cpu);
            self.interval.push(interval);
        }
    }

    /// The run has ended, the host having worked `host_seconds` in all: the
    /// summary line, once.
    pub fn finish(&mut self, steps: usize, load_factor: f64, host_seconds: f64) -> Option<String> {
        let start = self.start.filter(|_| !self.done)?;
        self.done = true;
        let wall = start.elapsed().as_secs_f64();
        let ms = |v: f64| v * 1e3;
        let (cpu_mean, cpu_p95, cpu_max) = stats(&mut self.cpu);
        let (dt_mean, dt_p95, dt_max) = stats(&mut self.interval);
        Some(format!(
            "run wall {wall:.3} s; {steps} growth steps, last λ {load_factor}; {} frames: \
             CPU mean {:.1} ms, p95 {:.1} ms, max {:.1} ms; interval mean {:.1} ms, p95 {:.1} \
             ms, max {:.1} ms; host {:.3} s",
            self.cpu.len(),
            ms(cpu_mean),
            ms(cpu_p95),
            ms(cpu_max),
            ms(dt_mean),
            ms(dt_p95),
            ms(dt_max),
            host_seconds - self.host_start,
        ))
    }
}

/// Mean, 95th percentile and maximum of `v` (sorted in place); zeros when
/// empty.
fn stats(v: &mut [f64]) -> (f64, f64, f64) {
    if v.is_empty() {
        return (0.0, 0.0, 0.0);
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    let mean = v.iter().sum::<f64>() / n as f64;
    (mean, v[(n * 95 / 100).min(n - 1)], v[n - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_gives_the_mean_p95_and_max_of_the_runs_frames() {
        let mut t = RunTimer::default();
        t.record(1.0, 1.0);
        assert!(t.finish(0, 0.0, 0.0).is_none(), "nothing started");
        t.start(1.25);
        for k in 1..=100 {
            t.record(f64::from(k) * 1e-3, 0.0);
        }
        let line = t.finish(3, 0.5, 3.0).unwrap_or_default();
        assert!(
            line.contains("3 growth steps, last λ 0.5; 100 frames: CPU mean 50.5 ms, p95 96.0 ms, max 100.0 ms"),
            "{line}"
        );
        assert!(
            line.ends_with("; host 1.750 s"),
            "the host's time in the run: {line}"
        );
        assert!(t.finish(3, 0.5, 3.0).is_none(), "once");
    }
}
