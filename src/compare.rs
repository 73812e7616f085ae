//! Error against run time of each solver on the current scene. The direct
//! solver runs first and gives the reference displacement at probe points;
//! each iterative solver then relaxes in budgeted chunks across frames and
//! records its error at the probes against its accumulated run time.

use cdca::scene::SolverKind;
use cdca::{Scene, Simulation};
use egui_plot::PlotPoint;
use web_time::{Duration, Instant};

/// One solver's curve.
pub struct CompareRun {
    pub kind: SolverKind,
    /// x = run time (s), y = log10 of the relative displacement error.
    pub points: Vec<PlotPoint>,
    pub seconds: f64,
    pub iterations: usize,
    pub done: bool,
    pub error: Option<String>,
}

/// The comparison in progress (or finished).
pub struct Comparison {
    scene: Scene,
    pub runs: Vec<CompareRun>,
    current: usize,
    sim: Option<Simulation>,
    probes: Vec<[f64; 2]>,
    reference: Option<Vec<[f64; 2]>>,
    /// Wall time after which an iterative solver is stopped, s.
    pub time_limit: f64,
}

/// Probes per side of the probe grid.
const PROBES: usize = 8;
/// Relative error at which a run is complete.
const ERROR_FLOOR: f64 = 1e-12;

pub fn solver_name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Direct => "Direct (sparse Cholesky)",
        SolverKind::Automaton => "Automaton (block Gauss–Seidel)",
        SolverKind::Cg => "CG + automaton sweep",
        SolverKind::Multigrid => "CG + sweeps + coarse grid",
    }
}

impl Comparison {
    /// Compares `kinds` on `scene`; the direct solver is always run first
    /// as the reference.
    pub fn new(scene: &Scene, kinds: &[SolverKind]) -> Self {
        let mut order = vec![SolverKind::Direct];
        order.extend(kinds.iter().copied().filter(|k| *k != SolverKind::Direct));
        let (w, h) = (scene.specimen.width, scene.specimen.height);
        let probes = (0..PROBES * PROBES)
            .map(|k| {
                let (i, j) = (k % PROBES, k / PROBES);
                [
                    w * (i as f64 + 0.53) / PROBES as f64,
                    h * (j as f64 + 0.47) / PROBES as f64,
                ]
            })
            .collect();
        Self {
            scene: scene.clone(),
            runs: order
                .into_iter()
                .map(|kind| CompareRun {
                    kind,
                    points: Vec::new(),
                    seconds: 0.0,
                    iterations: 0,
                    done: false,
                    error: None,
                })
                .collect(),
            current: 0,
            sim: None,
            probes,
            reference: None,
            time_limit: 10.0,
        }
    }

    pub fn finished(&self) -> bool {
        self.current >= self.runs.len()
    }

    /// Which run is going, for the progress line.
    pub fn status(&self) -> Option<(SolverKind, f64)> {
        self.runs.get(self.current).map(|r| (r.kind, r.seconds))
    }

    /// Works on the comparison until `deadline`.
    pub fn tick(&mut self, deadline: Instant) {
        while !self.finished() && Instant::now() < deadline {
            if let Err(e) = self.advance(deadline) {
                let run = &mut self.runs[self.current];
                run.error = Some(e);
                run.done = true;
            }
            if self.runs[self.current].done {
                self.sim = None;
                self.current += 1;
            }
        }
    }

    fn advance(&mut self, deadline: Instant) -> Result<(), String> {
        let run = &mut self.runs[self.current];
        if self.sim.is_none() {
            let mut scene = self.scene.clone();
            scene.solver.kind = run.kind;
            let mut sim = Simulation::new(scene).map_err(|e| e.to_string())?;
            sim.start_relaxation();
            self.sim = Some(sim);
        }
        let Some(sim) = self.sim.as_mut() else {
            return Ok(());
        };
        let remaining = deadline
            .saturating_duration_since(Instant::now())
            .max(Duration::from_millis(1));
        let n = estimate_sweeps(run, remaining);
        let t0 = Instant::now();
        let status = sim.relax(n).map_err(|e| e.to_string())?;
        run.seconds += t0.elapsed().as_secs_f64();
        run.iterations = status.iterations;
        let u: Vec<[f64; 2]> = self
            .probes
            .iter()
            .map(|&p| sim.displacement_at(p).unwrap_or([0.0; 2]))
            .collect();
        match &self.reference {
            None => {
                run.points
                    .push(PlotPoint::new(run.seconds, ERROR_FLOOR.log10()));
                self.reference = Some(u);
                run.done = true;
            }
            Some(reference) => {
                let e = relative_error(&u, reference).max(ERROR_FLOOR);
                run.points.push(PlotPoint::new(run.seconds, e.log10()));
                run.done = status.converged || e <= ERROR_FLOOR || run.seconds > self.time_limit;
            }
        }
        Ok(())
    }
}

/// Sweeps for the next call, so a call takes about a third of `remaining`.
fn estimate_sweeps(run: &CompareRun, remaining: Duration) -> usize {
    if run.iterations == 0 || run.seconds <= 0.0 {
        return 1;
    }
    let per_sweep = run.seconds / run.iterations as f64;
    ((remaining.as_secs_f64() / 3.0 / per_sweep) as usize).clamp(1, 10_000)
}

/// ‖u − r‖ / ‖r‖ over the probes.
pub fn relative_error(u: &[[f64; 2]], reference: &[[f64; 2]]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (a, b) in u.iter().zip(reference) {
        num += (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
        den += b[0] * b[0] + b[1] * b[1];
    }
    if den > 0.0 {
        (num / den).sqrt()
    } else {
        num.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::default_scene;

    #[test]
    fn direct_runs_first_and_once() {
        let c = Comparison::new(
            &default_scene(),
            &[SolverKind::Automaton, SolverKind::Direct, SolverKind::Cg],
        );
        let kinds: Vec<SolverKind> = c.runs.iter().map(|r| r.kind).collect();
        assert_eq!(
            kinds,
            vec![SolverKind::Direct, SolverKind::Automaton, SolverKind::Cg]
        );
    }

    #[test]
    fn relative_error_is_zero_on_the_reference_and_scales() {
        let r = [[1.0, 0.0], [0.0, 1.0]];
        assert_eq!(relative_error(&r, &r), 0.0);
        let u = [[1.1, 0.0], [0.0, 1.1]];
        assert!((relative_error(&u, &r) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn probes_stay_inside_the_specimen() {
        let s = default_scene();
        let c = Comparison::new(&s, &[]);
        assert_eq!(c.probes.len(), PROBES * PROBES);
        assert!(c.probes.iter().all(|p| p[0] > 0.0
            && p[0] < s.specimen.width
            && p[1] > 0.0
            && p[1] < s.specimen.height));
    }
}
