//! The solver race: error against run time of every solver on the current
//! scene, measured as `cdca bench` measures it.
//!
//! The contact states are settled first with the direct solver, starting
//! from the scene's states; then every solver solves the same final linear
//! system `(K + K_contact) u = f` from a cold start, `u = 0`. The direct
//! solution is the reference. Each iterative solver runs in budgeted chunks
//! across frames and is sampled at checkpoints (every 25 % more
//! iterations), where the relative energy-norm error
//! `‖u − u_ref‖_K / ‖u_ref‖_K` and the largest K_I, K_II errors (relative to
//! the largest reference |K|) are measured with the solver's clock paused.
//! The clock counts setup (cells, factorisations, hierarchy) and
//! iterations. A run ends when it converges, when its energy error reaches
//! [`ENERGY_FLOOR`], or at the time cap, which counts wall time (the
//! frames' drawing and the error sampling included), so that the race takes
//! the time it announces: the solver clock alone used to end a race of 4 ×
//! 10 s after about 80 s.

use cdca::Scene;
use cdca::contact::status::ContactParams;
pub use cdca::race::Sample;
use cdca::race::{RaceSystem, Reference};
use cdca::scene::{Ordering, SolverKind, SolverSpec};
use cdca::solvers::Relaxation;
use cdca::solvers::automaton::sor_omega;
use egui_plot::PlotPoint;
use web_time::Instant;

use crate::run::pacer::Pacer;
use crate::run::task::{Progress, Task};

/// Energy error at which a run is complete (as in `cdca bench`).
pub const ENERGY_FLOOR: f64 = 1e-11;

/// Default time cap of one iterative run, s.
pub const DEFAULT_TIME_CAP: f64 = 10.0;

/// One contender: how the bench names it, its solver, ordering and ω
/// (`None`: the optimal SOR factor 2/(1 + sin(π/n)) of an n × n mesh).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Racer {
    pub name: &'static str,
    pub kind: SolverKind,
    pub ordering: Ordering,
    pub omega: Option<f64>,
}

/// The direct reference and the iterative solvers of `cdca bench`.
pub const RACERS: [Racer; 5] = [
    Racer {
        name: "direct",
        kind: SolverKind::Direct,
        ordering: Ordering::Lexicographic,
        omega: Some(1.0),
    },
    Racer {
        name: "automaton",
        kind: SolverKind::Automaton,
        ordering: Ordering::Lexicographic,
        omega: Some(1.0),
    },
    Racer {
        name: "automaton-sor",
        kind: SolverKind::Automaton,
        ordering: Ordering::RedBlack,
        omega: None,
    },
    Racer {
        name: "cg",
        kind: SolverKind::Cg,
        ordering: Ordering::Lexicographic,
        omega: Some(1.0),
    },
    Racer {
        name: "multigrid",
        kind: SolverKind::Multigrid,
        ordering: Ordering::Lexicographic,
        omega: Some(1.0),
    },
];

pub fn solver_name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Direct => "Direct (sparse Cholesky)",
        SolverKind::Automaton => "Automaton (block Gauss–Seidel)",
        SolverKind::Cg => "CG + automaton sweep",
        SolverKind::Multigrid => "CG + sweeps + coarse grid",
    }
}

impl Racer {
    /// A readable name for legends.
    pub fn label(&self) -> &'static str {
        match self.name {
            "automaton-sor" => "Automaton, four-colour SOR",
            _ => solver_name(self.kind),
        }
    }
}

/// One solver's run.
pub struct RaceRun {
    pub racer: Racer,
    pub samples: Vec<Sample>,
    pub done: bool,
    pub error: Option<String>,
    /// x = run time (s), y = log10 of the energy error.
    pub energy_points: Vec<PlotPoint>,
    /// x = run time (s), y = log10 of max(K_I, K_II error).
    pub k_points: Vec<PlotPoint>,
    /// When the run's setup began (wall clock).
    started: Option<Instant>,
}

impl RaceRun {
    fn push(&mut self, s: Sample) {
        let log = |v: f64| v.max(ENERGY_FLOOR * 1e-3).log10();
        self.energy_points
            .push(PlotPoint::new(s.seconds, log(s.energy)));
        self.k_points
            .push(PlotPoint::new(s.seconds, log(s.k1.max(s.k2))));
        self.samples.push(s);
    }

    pub fn iterations(&self) -> usize {
        self.samples.last().map_or(0, |s| s.iteration)
    }

    pub fn seconds(&self) -> f64 {
        self.samples.last().map_or(0.0, |s| s.seconds)
    }

    /// Wall time since the run's setup began, s (0 before it).
    pub fn wall_seconds(&self) -> f64 {
        self.started.map_or(0.0, |t| t.elapsed().as_secs_f64())
    }
}

/// What the next piece of work is.
enum Phase {
    /// Build the discretisation and settle the contact states.
    Settle,
    /// Solve directly for the reference.
    Reference,
    /// Set up run `i` (an iterative solver).
    Setup(usize),
    /// Run `i` is under way.
    Running(usize, Box<Relaxation>, usize),
    Finished,
}

/// The race in progress (or finished).
pub struct Race {
    scene: Scene,
    pub runs: Vec<RaceRun>,
    /// Solver time after which an iterative run is stopped, s.
    pub time_cap: f64,
    phase: Phase,
    system: Option<RaceSystem>,
    reference: Option<Reference>,
    /// Iterations per call of a run.
    pacer: Pacer,
    cancelled: bool,
}

impl Race {
    /// A race of [`RACERS`] on `scene` with `time_cap` seconds per solver.
    pub fn new(scene: &Scene, time_cap: f64) -> Self {
        Self {
            scene: scene.clone(),
            runs: RACERS
                .iter()
                .map(|&racer| RaceRun {
                    racer,
                    samples: Vec::new(),
                    done: false,
                    error: None,
                    energy_points: Vec::new(),
                    k_points: Vec::new(),
                    started: None,
                })
                .collect(),
            time_cap: time_cap.max(0.01),
            phase: Phase::Settle,
            system: None,
            reference: None,
            pacer: Pacer::default(),
            cancelled: false,
        }
    }

    pub fn finished(&self) -> bool {
        matches!(self.phase, Phase::Finished)
    }

    /// Stops the race; the runs done so far stay.
    pub fn cancel(&mut self) {
        self.phase = Phase::Finished;
        self.cancelled = true;
    }

    pub fn cancelled(&self) -> bool {
        self.cancelled
    }

    /// The iterative solvers raced.
    pub fn iterative_runs(&self) -> usize {
        self.runs.len() - 1
    }

    /// How long the race takes at most, s: every iterative solver run to
    /// its time cap of wall time (the settling and the direct reference, a
    /// fraction of a second on the default scene, left out).
    pub fn estimate_seconds(&self) -> f64 {
        self.iterative_runs() as f64 * self.time_cap
    }

    /// The run in progress and the race's overall progress in [0, 1].
    pub fn status(&self) -> Option<(&RaceRun, f32)> {
        let (i, within) = match &self.phase {
            Phase::Settle => (0, 0.0),
            Phase::Reference => (0, 0.5),
            Phase::Setup(i) => (*i, 0.0),
            Phase::Running(i, ..) => {
                let run = &self.runs[*i];
                let by_time = run.wall_seconds() / self.time_cap;
                let by_error = run.samples.last().map_or(0.0, |s| {
                    (s.energy.max(ENERGY_FLOOR).log10() / ENERGY_FLOOR.log10()).max(0.0)
                });
                (*i, by_time.max(by_error).min(1.0))
            }
            Phase::Finished => return None,
        };
        let total = (i as f64 + within) / self.runs.len() as f64;
        Some((&self.runs[i], total as f32))
    }

    /// The phase after run `i`.
    fn after(&self, i: usize) -> Phase {
        if i + 1 < self.runs.len() {
            Phase::Setup(i + 1)
        } else {
            Phase::Finished
        }
    }

    /// One piece of `phase`, and the iterations it ran.
    fn work_on(&mut self, phase: Phase) -> Result<(Phase, usize), (usize, String)> {
        match phase {
            Phase::Settle => {
                let params = ContactParams {
                    tolerance: self.scene.solver.contact_tolerance,
                    max_iterations: self.scene.solver.max_contact_iterations,
                    ..ContactParams::default()
                };
                let system =
                    RaceSystem::settle(&self.scene, params).map_err(|e| (0, e.to_string()))?;
                self.system = Some(system);
                Ok((Phase::Reference, 0))
            }
            Phase::Reference => {
                let Some(sys) = &self.system else {
                    return Ok((Phase::Settle, 0));
                };
                let spec = self.spec(&self.runs[0].racer);
                let zero = vec![0.0; sys.x.n_free()];
                let mut direct =
                    Relaxation::new(spec.kind, &spec, &sys.x, &sys.blocks, &sys.f, &zero)
                        .map_err(|e| (0, e.to_string()))?;
                direct
                    .run(&sys.x, &sys.blocks, 1, &mut |_| {})
                    .map_err(|e| (0, e.to_string()))?;
                let reference = Reference::new(&sys.x, direct.operator(), direct.u());
                let sample =
                    reference.sample(&sys.x, direct.operator(), direct.u(), 1, direct.seconds());
                self.reference = Some(reference);
                let run = &mut self.runs[0];
                run.push(sample);
                run.done = true;
                Ok((self.after(0), 0))
            }
            Phase::Setup(i) => {
                let (Some(sys), Some(reference)) = (&self.system, &self.reference) else {
                    return Ok((Phase::Settle, 0));
                };
                self.runs[i].started = Some(Instant::now());
                let spec = self.spec(&self.runs[i].racer);
                let zero = vec![0.0; sys.x.n_free()];
                let r = Relaxation::new(spec.kind, &spec, &sys.x, &sys.blocks, &sys.f, &zero)
                    .map_err(|e| (i, e.to_string()))?;
                let s = reference.sample(&sys.x, r.operator(), r.u(), 0, r.seconds());
                self.runs[i].push(s);
                Ok((Phase::Running(i, Box::new(r), 1), 0))
            }
            Phase::Running(i, mut r, next) => {
                let (Some(sys), Some(reference)) = (&self.system, &self.reference) else {
                    return Ok((Phase::Settle, 0));
                };
                let run = &mut self.runs[i];
                let n = (next - r.status().iterations).min(self.pacer.sweeps());
                let status = r
                    .run(&sys.x, &sys.blocks, n, &mut |_| {})
                    .map_err(|e| (i, e.to_string()))?;
                let capped = run.wall_seconds() > self.time_cap;
                if status.iterations < next && !status.converged && !capped {
                    return Ok((Phase::Running(i, r, next), n));
                }
                let s =
                    reference.sample(&sys.x, r.operator(), r.u(), status.iterations, r.seconds());
                run.push(s);
                if status.converged || s.energy <= ENERGY_FLOOR || capped {
                    run.done = true;
                    return Ok((self.after(i), n));
                }
                let next = (next + 1).max((next as f64 * 1.25) as usize);
                Ok((Phase::Running(i, r, next), n))
            }
            Phase::Finished => Ok((Phase::Finished, 0)),
        }
    }

    /// The solver settings of `racer` on this scene (tolerance and iteration
    /// limit out of the way: the race stops on the energy error or the cap).
    fn spec(&self, racer: &Racer) -> SolverSpec {
        let n = self.scene.mesh.nx.max(self.scene.mesh.ny);
        SolverSpec {
            kind: racer.kind,
            ordering: racer.ordering,
            omega: racer.omega.unwrap_or_else(|| sor_omega(n)),
            tolerance: 1e-14,
            max_iterations: usize::MAX,
            ..self.scene.solver.clone()
        }
    }

    /// The race as CSV, with the columns of `cdca bench`'s
    /// `error_vs_time.csv` (size: elements along x).
    pub fn to_csv(&self) -> String {
        cdca::csv::race(self.runs.iter().map(|r| cdca::csv::RaceRun {
            scene: &self.scene.name,
            size: self.scene.mesh.nx,
            solver: r.racer.name,
            samples: &r.samples,
        }))
    }
}

impl Task for Race {
    /// Works on the race until about `deadline`; each phase is one
    /// resumable piece (the setup of a solver is one piece, however long),
    /// a run's iterations go in calls sized by the pacer.
    fn advance(&mut self, deadline: Instant) -> Result<Progress, String> {
        while !self.finished() {
            let start = Instant::now();
            let phase = std::mem::replace(&mut self.phase, Phase::Finished);
            let iterations = match self.work_on(phase) {
                Ok((next, iterations)) => {
                    self.phase = next;
                    iterations
                }
                Err((i, e)) => {
                    let run = &mut self.runs[i];
                    run.error = Some(e);
                    run.done = true;
                    self.phase = if i == 0 {
                        // no reference: nothing to race against
                        for r in &mut self.runs {
                            r.done = true;
                        }
                        Phase::Finished
                    } else {
                        self.after(i)
                    };
                    0
                }
            };
            if !self.pacer.another_fits(start, iterations, deadline) {
                break;
            }
        }
        Ok(if self.finished() {
            Progress::Finished
        } else {
            Progress::Working
        })
    }
}

#[cfg(test)]
mod tests {
    use web_time::Duration;

    use super::*;
    use crate::files::scenes::default_scene;

    /// The race on a small scene runs to the end in budgeted ticks: the
    /// direct reference has zero error against itself (1e-12); every
    /// iterative run starts at u = 0, where the energy error is exactly 1
    /// (‖0 − u_ref‖_K / ‖u_ref‖_K; 1e-12), and its error never rises (each
    /// method decreases the energy norm of the error on an SPD system;
    /// 1e-9 relative slack for round-off). CG and multigrid-CG reach the
    /// 1e-11 floor in a few dozen iterations (< 0.1 s here), far inside the
    /// 0.5 s cap; the automata fall at least tenfold within it.
    #[test]
    fn a_race_on_a_small_scene_starts_cold_and_the_errors_fall() {
        let mut scene = default_scene();
        scene.mesh.nx = 14;
        scene.mesh.ny = 14;
        let mut race = Race::new(&cdca::Scene::try_from(scene).expect("valid"), 0.5);
        for _ in 0..100_000 {
            if race.finished() {
                break;
            }
            let _ = race.advance(Instant::now() + Duration::from_millis(10));
        }
        assert!(race.finished());
        assert!(race.runs[0].samples[0].energy < 1e-12);
        for run in &race.runs[1..] {
            let name = run.racer.name;
            assert!(run.error.is_none(), "{name}: {:?}", run.error);
            let e: Vec<f64> = run.samples.iter().map(|s| s.energy).collect();
            assert_eq!(run.samples[0].iteration, 0);
            assert!((e[0] - 1.0).abs() < 1e-12, "{name}: {}", e[0]);
            assert!(
                e.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-9)),
                "{name}: {e:?}"
            );
            let last = e[e.len() - 1];
            match run.racer.kind {
                SolverKind::Cg | SolverKind::Multigrid => {
                    assert!(last <= ENERGY_FLOOR, "{name}: {last:e}");
                }
                _ => assert!(last < 0.1, "{name}: {last:e}"),
            }
        }
        let csv = race.to_csv();
        let rows = race.runs.iter().map(|r| r.samples.len()).sum::<usize>();
        assert_eq!(csv.lines().count(), rows + 1);
        assert!(csv.starts_with("scene,size,solver,iteration,seconds,energy_error"));
    }

    #[test]
    fn the_sor_racer_uses_the_optimal_omega_of_the_mesh() {
        let mut scene = default_scene();
        scene.mesh.nx = 40;
        scene.mesh.ny = 40;
        let race = Race::new(&cdca::Scene::try_from(scene).expect("valid"), 1.0);
        let spec = race.spec(&RACERS[2]);
        let expected = 2.0 / (1.0 + (std::f64::consts::PI / 40.0).sin()); // Young's optimum
        assert!((spec.omega - expected).abs() < 1e-15);
        assert_eq!(spec.ordering, Ordering::RedBlack);
    }
}
