//! A plain-data copy of what the UI shows of a [`Simulation`]: cracks, tips,
//! contact points, residual and growth histories. The UI reads only this
//! copy, so panels and the canvas never call into the solver; the runner
//! refreshes it after each piece of solver work.

use cdca::report::{
    CoalescenceReport, GrowthStepReport, IntactRockReport, LoadCapReport, Outcome, StrengthReport,
    TipReport,
};
use cdca::scene::Lineage;
use cdca::scene::SolverKind;
use cdca::{ContactPointView, ContactState, RelaxStatus, ResidualSample, Simulation};
use egui_plot::PlotPoint;

/// Longest series handed to a plot; longer histories are decimated.
const MAX_PLOT_POINTS: usize = 2000;

/// What the UI knows of the solver's state.
#[derive(Clone, Debug, Default, serde::Serialize, serde::Deserialize)]
pub struct SolutionView {
    /// Bumped every time the solver's state changes; caches key on it.
    pub version: u64,
    /// The displacement is a solution of the current cracks and load.
    pub solved: bool,
    /// A solve is under way and its iterate is a field
    /// ([`Simulation::has_live_iterate`]: an iterative solver's, after its
    /// first iteration): the canvas shows it live.
    pub live: bool,
    /// Crack polylines as simulated (grown segments included), m.
    pub cracks: Vec<Vec<[f64; 2]>>,
    /// Per crack, per segment of its polyline: part of a secondary crack
    /// (one started at a kink, or grown from a flaw's end first in shear).
    pub secondary: Vec<Vec<bool>>,
    /// Per crack: started in the intact rock (`growth.intact_rock`
    /// `"nucleate"`), drawn in a colour of its own.
    pub intact: Vec<bool>,
    /// Per crack: its [`Lineage`] (the drawn flaw it grew from), for its
    /// name ([`crack_name`](Self::crack_name)).
    pub lineage: Vec<Lineage>,
    /// Every free tip after the last solve.
    pub tips: Vec<TipReport>,
    pub contact: Vec<ContactPointView>,
    /// Residual against sweep number: x = sweep, y = log10(residual).
    #[serde(with = "plot_points")]
    pub residual_by_sweep: Vec<PlotPoint>,
    /// Residual against wall time: x = seconds, y = log10(residual).
    #[serde(with = "plot_points")]
    pub residual_by_time: Vec<PlotPoint>,
    /// Number of residual samples before decimation.
    pub residual_samples: usize,
    /// The last residual sample of the current solve.
    pub last_residual: Option<ResidualSample>,
    /// The growth steps of this simulation (the `step` of each report
    /// counts from the run a resumed scene continues).
    pub history: Vec<GrowthStepReport>,
    /// The steps of the run the simulation continues, when it was rebuilt
    /// from a grown scene in this session (Solve after growth): shown
    /// before its own steps, so that no job erases a run's plots.
    pub earlier: Vec<GrowthStepReport>,
    /// Growth steps done, a resumed run's earlier steps included
    /// ([`Simulation::steps_done`]): the number the status prints and the
    /// plots' last step.
    pub steps_done: usize,
    pub load_factor: f64,
    pub outcome: Option<Outcome>,
    /// The growth run ended at `growth.max_load_factor` (critical control):
    /// no free tip meets its criterion below it.
    pub load_cap: Option<LoadCapReport>,
    /// Load factor at which the uncracked specimen's rock fails
    /// ([`Simulation::intact_load_factor`]), once the run has a step: the
    /// intact strength line of the Load factor plot.
    pub intact_load_factor: Option<f64>,
    /// The specimen's strength against the intact rock's, once the run
    /// has ended ([`Simulation::strength`]).
    pub strength: Option<StrengthReport>,
    /// The run's first link between two flaws ([`Simulation::coalescence`]),
    /// and where its tip met the other crack, m.
    pub coalescence: Option<CoalescenceReport>,
    pub junction: Option<[f64; 2]>,
    /// The solve from bonded faces found another solution of the same
    /// frictional problem (`Simulation::bonded_start`): the sentence
    /// saying so, with both solutions' contact counts.
    pub other_solution: Option<String>,
    /// That second solve is under way, or has ended (whatever it found).
    pub second_start: SecondStart,
    /// Status of the current relaxation, if one ran.
    pub relax: Option<RelaxStatus>,
    /// The linear solver behind `relax` and the residual samples (during
    /// growth, the growth solver).
    pub solver: SolverKind,
    /// Fraction of the grown tips' elements integrated, while a growth
    /// step rebuilds the discretisation.
    pub rebuild: Option<f64>,
    /// The final cracks cut the specimen through: their solve failed (no
    /// stiffness against a piece's rigid motion), and the field shown is
    /// the last solved state, at the last step's load factor.
    pub split: bool,
    /// The piece the cracks cut off with nothing holding it, when the
    /// last solve found one (then `split`).
    pub free_piece: Option<cdca::report::FreePieceReport>,
    /// The rock away from the cracks against its strength, when solved.
    pub intact_rock: Option<IntactRockReport>,
    /// Which convergence test failed, in the solver's words
    /// ([`SolveReport::failure`](cdca::report::SolveReport::failure)), when
    /// the last solve ended without converging.
    pub failure: Option<String>,
    /// Crack-face points in contact (stick or slip) at the last solve of
    /// this scene; `None` before one, or without face points. Kept while
    /// the next solve runs, so that the panels do not flicker while a tip
    /// is dragged (see [`all_faces_open`](Self::all_faces_open)).
    pub closed_at_last_solve: Option<usize>,
}

impl SolutionView {
    /// Copies what the UI needs from `sim`. `solved` says whether the
    /// simulation holds a solution; while a solve is under way its iterate
    /// (field and contact states) is shown too.
    pub fn refresh(&mut self, sim: &Simulation, solved: bool, relax: Option<RelaxStatus>) {
        self.version += 1;
        self.solved = solved;
        self.split = false;
        self.free_piece = None;
        self.live = !solved && sim.has_live_iterate();
        self.relax = relax;
        self.failure = relax
            .filter(|r| r.finished && !r.converged)
            .and_then(|_| sim.report(0.0).failure());
        self.solver = sim.scene().solver.kind;
        self.rebuild = sim.rebuild_progress();
        self.cracks = sim.cracks();
        self.secondary = sim
            .lineage()
            .iter()
            .zip(&self.cracks)
            .map(|(l, c)| l.secondary_segments(c.len()))
            .collect();
        self.lineage = sim.lineage().to_vec();
        self.intact = self.lineage.iter().map(Lineage::is_intact).collect();
        self.load_factor = sim.load_factor();
        self.outcome = sim.growth_finished();
        self.load_cap = sim.load_cap();
        let history = sim.history();
        if self.earlier.len() + history.len() != self.history.len() {
            self.history = self.earlier.iter().chain(history).cloned().collect();
        }
        // one uncracked solve per simulation (cached), after the first step
        self.intact_load_factor = if history.is_empty() {
            None
        } else {
            sim.intact_load_factor().0
        };
        self.strength = self.outcome.and_then(|o| sim.strength(o));
        self.coalescence = sim.coalescence();
        // (the link may be in the steps of a run this scene resumes)
        self.junction = self.coalescence.as_ref().and_then(|c| {
            let link = self
                .history
                .iter()
                .find(|s| s.step == c.step)?
                .links
                .iter()
                .find(|l| l.coalescence)?;
            let crack = self.cracks.get(link.crack)?;
            if link.tip == 0 {
                crack.first().copied()
            } else {
                crack.last().copied()
            }
        });
        self.steps_done = sim.steps_done();
        let samples = sim.residual_history();
        self.residual_samples = samples.len();
        self.last_residual = samples.last().copied();
        let log = |r: f64| r.max(1e-300).log10();
        self.residual_by_sweep = decimate(samples, |s| {
            PlotPoint::new(s.iteration as f64, log(s.residual))
        });
        self.residual_by_time = decimate(samples, |s| PlotPoint::new(s.seconds, log(s.residual)));
        self.intact_rock = if solved { sim.intact_rock() } else { None };
        if solved {
            self.tips = sim.tips().to_vec();
        } else {
            self.tips.clear();
        }
        if solved || self.live {
            self.contact = sim.contact_points();
        } else {
            self.contact.clear();
        }
        // a solve with a piece held by nothing is no solution: shown split
        if solved && let Some(piece) = sim.free_piece() {
            self.free_piece = Some(piece);
            self.mark_split();
            return;
        }
        if solved {
            self.closed_at_last_solve = (!self.contact.is_empty()).then(|| {
                self.contact
                    .iter()
                    .filter(|c| c.state != ContactState::Open)
                    .count()
            });
        }
    }

    /// Crack `c` as the Scene panel and the plots name it: a drawn flaw
    /// "Crack 2"; a crack started at one of its kinks "Crack 2 · secondary
    /// 1" (numbered within the flaw, in order of starting); one started in
    /// the intact rock "Rock crack 1".
    pub fn crack_name(&self, c: usize) -> String {
        let Some(l) = self.lineage.get(c) else {
            return format!("Crack {}", c + 1);
        };
        if l.is_intact() {
            let k = self.lineage[..c].iter().filter(|o| o.is_intact()).count();
            format!("Rock crack {}", k + 1)
        } else if l.drawn == 0 {
            let k = self.lineage[..c]
                .iter()
                .filter(|o| o.drawn == 0 && !o.is_intact() && o.flaw == l.flaw)
                .count();
            format!("Crack {} · secondary {}", l.flaw + 1, k + 1)
        } else {
            format!("Crack {}", l.flaw + 1)
        }
    }

    /// The final cracks' solve found the specimen split: nothing of that
    /// failed solve is shown (no field, contact states or tips), and the
    /// canvas keeps the last solved field.
    pub fn mark_split(&mut self) {
        self.split = true;
        self.solved = false;
        self.live = false;
        self.tips.clear();
        self.contact.clear();
        self.intact_rock = None;
    }

    /// The last solve found every crack-face point open: friction,
    /// cohesion and the contact iteration's settings have nothing to act on.
    pub fn all_faces_open(&self) -> bool {
        self.closed_at_last_solve == Some(0)
    }

    /// A displacement field can be sampled: a solution, or the iterate of
    /// a solve under way.
    pub fn has_field(&self) -> bool {
        self.solved || self.live
    }

    /// Forgets the solution (the scene changed), keeping the version counter
    /// rising and the last solve's contact verdict until the next solve.
    pub fn clear(&mut self) {
        let version = self.version + 1;
        *self = Self {
            version,
            closed_at_last_solve: self.closed_at_last_solve,
            ..Self::default()
        };
    }

    /// Forgets the last solve's contact verdict too (another scene).
    pub fn forget_contact(&mut self) {
        self.closed_at_last_solve = None;
    }
}

/// Length of a polyline, m.
pub fn polyline_length(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}

/// At most `MAX_PLOT_POINTS` evenly spaced samples, always keeping the last.
fn decimate<T>(samples: &[T], f: impl Fn(&T) -> PlotPoint) -> Vec<PlotPoint> {
    let n = samples.len();
    if n <= MAX_PLOT_POINTS {
        return samples.iter().map(f).collect();
    }
    let stride = n.div_ceil(MAX_PLOT_POINTS);
    let mut out: Vec<PlotPoint> = samples.iter().step_by(stride).map(&f).collect();
    if !(n - 1).is_multiple_of(stride) {
        out.push(f(&samples[n - 1]));
    }
    out
}

/// Where the check of a solve for another solution stands.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum SecondStart {
    /// Not run: no Solve yet, or no face closed (nothing to compare).
    #[default]
    NotRun,
    /// Solving the same problem from bonded faces.
    Running,
    /// Done (`other_solution` says what it found).
    Done,
}

/// A plot's points as `(x, y)` pairs (egui_plot's `PlotPoint` has no serde
/// form), for the run protocol's posts: a y that is not finite (log10 of a
/// residual of 0) as none, read back as NaN, which the plots leave out.
mod plot_points {
    use egui_plot::PlotPoint;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(points: &[PlotPoint], s: S) -> Result<S::Ok, S::Error> {
        let pairs: Vec<(f64, Option<f64>)> = points
            .iter()
            .map(|p| (p.x, p.y.is_finite().then_some(p.y)))
            .collect();
        pairs.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<PlotPoint>, D::Error> {
        Ok(Vec::<(f64, Option<f64>)>::deserialize(d)?
            .into_iter()
            .map(|(x, y)| PlotPoint::new(x, y.unwrap_or(f64::NAN)))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_first_and_last_and_bounds_the_count() {
        let samples: Vec<f64> = (0..10_001).map(f64::from).collect();
        let points = decimate(&samples, |&v| PlotPoint::new(v, v));
        assert!(points.len() <= MAX_PLOT_POINTS + 1);
        assert_eq!(points[0].x, 0.0);
        assert_eq!(points[points.len() - 1].x, 10_000.0);
    }

    #[test]
    fn polyline_length_adds_segments() {
        assert!((polyline_length(&[[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]]) - 6.0).abs() < 1e-12);
    }
}
