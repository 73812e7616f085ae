//! Report contracts of SPEC §11 (`cdca solve`, `cdca grow`). Field names are
//! relied upon by other tools: add fields freely, rename none.

use serde::{Deserialize, Serialize};

use crate::error::SceneError;
pub use crate::scene::Part;
use crate::scene::Resume;

/// Output of `cdca solve`: one solve at full load, no growth.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveReport {
    /// Number of unknowns (free DOFs, standard and enriched).
    pub dofs: usize,
    /// Number of enriched unknowns among them.
    pub enriched_dofs: usize,
    pub solver: SolverReport,
    pub contact: ContactReport,
    pub tips: Vec<TipReport>,
    /// The rock away from the cracks against its own strength (left out
    /// for a rock without cohesion, see `RockStrength::of_material`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intact_rock: Option<IntactRockReport>,
    /// A piece of the specimen that nothing holds (cut off by cracks whose
    /// faces are open, with no support): the solve is then no solution,
    /// and not `converged`, whatever the linear solver reported.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub free_piece: Option<FreePieceReport>,
    /// Every sharp kink of the cracks evaluated as a secondary-crack site
    /// (left out when there is none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub kinks: Vec<KinkReport>,
    /// The same solve from bonded faces found another solution: the
    /// frictional problem has more than one here (left out when it found
    /// the same, or was not run; `cdca solve` runs it where faces close).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub other_solution: Option<OtherSolutionReport>,
    /// What the solve cost and where its time went.
    #[serde(default)]
    pub work: WorkReport,
}

/// What a solve, or a growth step with its λ_cr search's trials, cost:
/// its solves and iterations, and where its wall time went. The parts
/// (`setup_seconds`, `build_seconds`, `solve_seconds`, `evaluate_seconds`,
/// `second_solve_seconds` and `other_seconds`) add up to `seconds`, the
/// whole: a growth step's `seconds`, a solve's from its start to its
/// report, and for `cdca solve` (`Simulation::solve_scene`) the command
/// from reading the scene to its report. The counts are those of the
/// solve from open faces (a step's: all its solves).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct WorkReport {
    /// Contact solves run to their end (a trial load the search scaled
    /// instead is not one).
    pub solves: usize,
    /// Contact iterations summed over them.
    pub contact_iterations: usize,
    /// Linear iterations summed over them (the direct solver: solves
    /// through a factor, its Newton steps' Krylov iterations included).
    pub linear_iterations: usize,
    /// Solves whose Newton steps cycled or missed, finished by the damped
    /// fixed point (`contact::iteration::MAX_NEWTON_STEPS`).
    pub newton_fallbacks: usize,
    /// Integrating the elements a growth changed, the direct solver's
    /// pattern and symbolic factorisation, the tips' integral domains, s.
    pub build_seconds: f64,
    /// The contact solves (factorisations, solves, contact iterations), s.
    pub solve_seconds: f64,
    /// Evaluating the tips, kinks and the intact rock's sites after each
    /// solve, s.
    pub evaluate_seconds: f64,
    /// The rest: the λ_cr search's bookkeeping, extending the cracks and
    /// rebuilding the discretisation; for a solve, its report (a free
    /// piece among it), and for `cdca solve` also comparing the two
    /// solutions and freeing the simulation, s.
    pub other_seconds: f64,
    /// Reading and checking the scene and building its simulation (cracks,
    /// enrichment, DOFs, faces) before the first solve, s: `cdca solve`'s
    /// only (0 in a growth step, whose rebuilds are `other_seconds`).
    #[serde(default)]
    pub setup_seconds: f64,
    /// The second solve `cdca solve` runs where faces close, from bonded
    /// faces (see `other_solution`), all of it (its start, build, contact
    /// solve and evaluation), s; 0 where it does not run.
    #[serde(default)]
    pub second_solve_seconds: f64,
    /// The whole, s: the sum of the parts above.
    #[serde(default)]
    pub seconds: f64,
}

impl WorkReport {
    /// The parts but `other_seconds` (the rest), s.
    #[must_use]
    pub fn measured_seconds(&self) -> f64 {
        self.setup_seconds
            + self.build_seconds
            + self.solve_seconds
            + self.evaluate_seconds
            + self.second_solve_seconds
    }

    /// Closes the account of a whole that took `seconds`: what the
    /// measured parts leave is the rest (`other_seconds`).
    pub fn close(&mut self, seconds: f64) {
        self.seconds = seconds;
        self.other_seconds = seconds - self.measured_seconds();
    }
}

/// Largest difference of a tip's K_I or K_II, over the largest |K| of a
/// solution, below which two solutions are the same (the direct solve's
/// residual is below 1e-8, the contact iteration's tolerance 1e-8).
pub const SAME_SOLUTION_K: f64 = 1e-6;

/// Another solution of the same frictional problem (same scene, load and
/// slip history) from another start of the contact iteration: Coulomb
/// friction with closed faces need not have one solution, and then which
/// one a solve finds depends on where it starts.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct OtherSolutionReport {
    /// What the other solve started from (`"bonded"`: every face point in
    /// stick with friction limits far above any traction; the first starts
    /// with the faces open).
    pub start: String,
    pub open: usize,
    pub stick: usize,
    pub slip: usize,
    /// Largest difference of a tip's K_I or K_II from the first solution's,
    /// over the first solution's largest |K|.
    pub k_difference: f64,
}

impl OtherSolutionReport {
    /// Whether `first` is worth solving again from bonded faces: it
    /// converged and some face point is closed (with every face open no
    /// friction acts, and the problem has one solution).
    pub fn worth_checking(first: &SolveReport) -> bool {
        first.failure().is_none() && first.contact.stick + first.contact.slip > 0
    }

    /// `other`, solved from `start`, against `first`: another solution when
    /// both converged and they differ in their contact counts or by more
    /// than [`SAME_SOLUTION_K`] in K; `None` otherwise.
    pub fn between(first: &SolveReport, other: &SolveReport, start: &str) -> Option<Self> {
        if first.failure().is_some() || other.failure().is_some() {
            return None;
        }
        let scale = first
            .tips
            .iter()
            .map(|t| t.k1.abs().max(t.k2.abs()))
            .fold(0.0, f64::max);
        let k_difference = first
            .tips
            .iter()
            .zip(&other.tips)
            .map(|(a, b)| (a.k1 - b.k1).abs().max((a.k2 - b.k2).abs()))
            .fold(0.0, f64::max)
            / scale.max(f64::MIN_POSITIVE);
        let c = &other.contact;
        let counts = (c.open, c.stick, c.slip);
        let same = counts == (first.contact.open, first.contact.stick, first.contact.slip)
            && k_difference <= SAME_SOLUTION_K;
        (!same).then(|| Self {
            start: start.to_owned(),
            open: c.open,
            stick: c.stick,
            slip: c.slip,
            k_difference,
        })
    }

    /// The sentence the CLI and the workbench print.
    pub fn sentence(&self, first: &ContactReport) -> String {
        format!(
            "the frictional problem has more than one solution here: from open faces \
             {} open, {} stick, {} slip; from {} faces {} open, {} stick, {} slip \
             (K differs by {:.2e} of the largest |K|)",
            first.open,
            first.stick,
            first.slip,
            self.start,
            self.open,
            self.stick,
            self.slip,
            self.k_difference
        )
    }
}

/// A sharp kink of a crack (a flaw's end that a wing has left, or any
/// turn of at least `SHARP_TURN_DEG`) evaluated by the criterion on the
/// computed field around it: where it is met a secondary crack starts
/// (SPEC §8).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct KinkReport {
    pub crack: usize,
    /// Index of the vertex in the crack's points.
    pub vertex: usize,
    /// m
    pub x: f64,
    /// m
    pub y: f64,
    /// Turn of the crack at the vertex, degrees.
    pub turn_deg: f64,
    /// The criterion's decision (`none`: no crack starts here).
    pub mode: Mode,
    /// Direction of the crack it would start, degrees counter-clockwise
    /// from +x.
    pub direction_deg: f64,
    /// That direction off the straight continuation of the nearer arm,
    /// degrees (0: the arm carried straight on).
    pub off_arm_deg: f64,
    /// Demand over strength of the criterion's checks (≥ 1: it starts).
    pub utilisation: f64,
}

/// A secondary crack started at a kink in a growth step.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StartedCrack {
    /// Index of the new crack (appended to the scene's `cracks`).
    pub crack: usize,
    /// The crack it starts on, and the kink's vertex there.
    pub on: usize,
    pub vertex: usize,
    /// Start (the kink), m.
    pub x: f64,
    pub y: f64,
    /// Its free tip after the step, m.
    pub tip_x: f64,
    pub tip_y: f64,
    pub mode: Mode,
    /// Direction, degrees counter-clockwise from +x.
    pub direction_deg: f64,
    /// Off the straight continuation of the kink's nearer arm, degrees.
    pub off_arm_deg: f64,
}

/// A crack started in the intact rock in a growth step (SPEC §8,
/// `growth.intact_rock = "nucleate"`): at the site whose disc reading of
/// the rock's Mohr–Coulomb envelope with its tension cut-off met it first.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct NucleatedCrack {
    /// Index of the new crack (appended to the scene's `cracks`).
    pub crack: usize,
    /// The site: the centre of the element it started at, m.
    pub x: f64,
    pub y: f64,
    /// Its two ends after the step, m.
    pub ends: [[f64; 2]; 2],
    /// `tension` (perpendicular to the most tensile principal stress) or
    /// `shear` (on a Mohr–Coulomb plane, 45° − φ/2 from σ1).
    pub mode: Mode,
    /// Direction of the crack's line, degrees counter-clockwise from +x,
    /// in (−90, 90].
    pub direction_deg: f64,
    /// The site's utilisation at the step's load (≥ 1).
    pub utilisation: f64,
    /// Other sites tied with it (within the λ search's band), which the
    /// tie rule passed over.
    pub tied: usize,
}

/// The most critical site of the intact rock at a step's load: where a
/// crack would start first (SPEC §8).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RockSiteReport {
    /// The site (an element's centre), m.
    pub x: f64,
    pub y: f64,
    /// The disc reading's utilisation `max((σ1 − N_φ σ3)/σ_c, −σ3/σ_t)`
    /// (≥ 1: a crack starts here unless a tip or a kink grows).
    pub utilisation: f64,
    /// Which check decides (`tension` or `shear`; `none` below 1).
    pub mode: Mode,
    /// Sites the reading covered (none within r0 of a crack's faces or a
    /// point support, 2 r0 of a free tip or a kink, or on a loose piece).
    pub sites: usize,
}

/// A grown tip that ended on another crack in a growth step (a
/// junction): what it joins. Two cracks that belong to different flaws
/// (each crack belongs to the flaw it grew from) have coalesced.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LinkReport {
    pub crack: usize,
    pub tip: usize,
    /// The crack it ended on.
    pub main: usize,
    /// The part the tip belongs to, and the part of `main` it ended on.
    pub joins: [Part; 2],
    /// The drawn cracks (flaws) the two belong to.
    pub flaws: [usize; 2],
    /// The two flaws differ (and were not linked before): coalescence.
    pub coalescence: bool,
}

impl LinkReport {
    /// The coalescence category: what the link joins, `"wing–flaw"`,
    /// `"secondary–secondary"`, … (the growing part first).
    pub fn category(&self) -> String {
        format!("{}–{}", self.joins[0].name(), self.joins[1].name())
    }
}

/// The first coalescence of a growth run: two flaws linked.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CoalescenceReport {
    pub step: usize,
    pub load_factor: f64,
    /// What the link joins ([`LinkReport::category`]).
    pub category: String,
    pub flaws: [usize; 2],
}

/// A piece of the specimen cut off by cracks and held by nothing: no
/// supported side, no point support, no crack face in contact with the
/// rest ([`Simulation::free_piece`](crate::Simulation::free_piece)).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FreePieceReport {
    /// Elements in the piece.
    pub elements: usize,
    /// Centre of the piece's elements, m.
    pub centroid: [f64; 2],
    /// The cracks (indices into the scene's `cracks`) that cut it off.
    pub cracks: Vec<usize>,
}

impl FreePieceReport {
    /// The piece in words.
    pub fn describe(&self) -> String {
        let cracks: Vec<String> = self.cracks.iter().map(|c| format!("cracks[{c}]")).collect();
        format!(
            "{} cut off a piece of {} elements around ({:.4}, {:.4}) m that no support or \
             crack face in contact holds",
            if cracks.is_empty() {
                "the cracks".to_owned()
            } else {
                cracks.join(" and ")
            },
            self.elements,
            self.centroid[0],
            self.centroid[1]
        )
    }
}

/// The rock away from the cracks (elements with no enriched node) against
/// its Mohr–Coulomb strength with a tension cut-off: utilisation
/// `u = max((σ1 − N_φ σ3)/σ_c, −σ3/σ_t, 0)` (principal compressions σ1 ≥ σ3,
/// `N_φ = (1 + sin φ)/(1 − sin φ)`), `u ≥ 1` where the uncracked rock
/// would fail. The tip criterion does not check it: growth goes on whatever
/// it reads, and it says when the load has passed what the rock between
/// the cracks could carry.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct IntactRockReport {
    /// Area median of u (the far field's utilisation on a specimen whose
    /// cracks are small).
    pub utilisation: f64,
    /// Area fraction of that rock with u ≥ 1.
    pub failed_fraction: f64,
    /// Unconfined compressive strength `σ_c = 2c cos φ/(1 − sin φ)`, Pa.
    pub ucs: f64,
}

/// How the linear solves went (summed over contact iterations).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolverReport {
    /// `direct`, `automaton`, `cg` or `multigrid`.
    pub kind: String,
    /// Sweeps or iterations (for `direct`: 1 per solve plus its
    /// iterative-refinement steps).
    pub iterations: usize,
    /// Final relative residual ‖f − K u‖/‖f‖.
    pub residual: f64,
    pub converged: bool,
    /// Wall time of the solve (from open faces) after its elements'
    /// integration: the pattern, the contact solve, the evaluation, s.
    /// `work` has the whole, in parts.
    pub seconds: f64,
    /// Relative residual after each iteration of the last linear solve.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub residual_history: Vec<f64>,
}

/// State of the frictional contact on crack faces.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactReport {
    /// Contact iterations (solves) done.
    pub iterations: usize,
    /// True only when the states settled with every point obeying the
    /// contact law and the last linear solve converged.
    pub converged: bool,
    /// Number of face points in each state.
    pub open: usize,
    pub stick: usize,
    pub slip: usize,
    /// Dimensionless normal stiffness k_N h / E (largest over cracks; 0 with
    /// no cracks).
    pub kn_h_over_e: f64,
    /// Points that flipped between states too often: frozen (automaton's
    /// in-sweep rule), or counted when the contact iteration was capped.
    #[serde(default)]
    pub cycling: usize,
    /// Frozen points whose state breaks the stick/slip rule at the final
    /// displacement (the contact iteration is then not converged).
    #[serde(default)]
    pub violating: usize,
    /// Relative change of the displacement in the last contact iteration.
    #[serde(default)]
    pub residual: f64,
    /// The iteration reached `solver.max_contact_iterations` without
    /// settling: states still changing, or (with slip) the displacement
    /// still moving (written only when true).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub capped: bool,
    /// Points the last contact iteration left unsettled: those whose state
    /// it changed or, when none changed, those not in their Coulomb state
    /// at its solution (written only when not zero).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub unsettled: usize,
}

// serde's `skip_serializing_if` passes the field by reference
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Stress intensity factors and the criterion's decision at one free tip.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TipReport {
    /// Index of the crack in the scene's `cracks`.
    pub crack: usize,
    /// 0 for the polyline's first point, 1 for its last.
    pub tip: usize,
    /// m
    pub x: f64,
    /// m
    pub y: f64,
    /// K_I, Pa·√m
    pub k1: f64,
    /// K_II, Pa·√m
    pub k2: f64,
    /// T-stress, Pa
    pub t_stress: f64,
    pub criterion: CriterionReport,
}

/// Growth mode decided by the criterion.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    Tension,
    Shear,
    #[default]
    None,
}

impl Mode {
    /// The name reports, CSV tables and the workbench spell it with
    /// (`"tension"`, `"shear"`, `"none"`, as serialised).
    pub const fn name(self) -> &'static str {
        match self {
            Self::Tension => "tension",
            Self::Shear => "shear",
            Self::None => "none",
        }
    }
}

/// The criterion's decision at a tip (SPEC §8).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CriterionReport {
    pub mode: Mode,
    /// Signed kink angle in the tip frame, degrees (counter-clockwise +).
    pub angle_deg: f64,
    /// max σ_θθ on the circle r0, Pa.
    pub sigma_theta_max: f64,
    /// max |τ_rθ| on the circle r0, Pa.
    pub tau_max: f64,
}

/// Output of `cdca grow`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GrowReport {
    pub steps: Vec<GrowthStepReport>,
    pub outcome: Outcome,
    /// Final crack polylines, m.
    pub cracks: Vec<Vec<[f64; 2]>>,
    /// With outcome `error`: the step that failed and why.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Under critical control, a run that ended `completed` because no
    /// free tip meets its criterion at any λ up to `growth.max_load_factor`:
    /// that cap, and the sentence saying so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_cap: Option<LoadCapReport>,
    /// The first step at which two flaws linked, and how (left out when
    /// none did).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coalescence: Option<CoalescenceReport>,
    /// The specimen's strength, the peak of the load factor, against the
    /// intact rock's at the same load ratio (left out with no step).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub strength: Option<StrengthReport>,
    /// The bound on cracks started in the intact rock at one load stopped
    /// the run (outcome `unstable`; left out otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_limit: Option<StartLimitReport>,
}

/// The specimen's strength (SPEC §8): the peak of the recorded load
/// factors, as in a load-controlled test, against the load factor at
/// which the uncracked specimen's intact rock fails under the same loads.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StrengthReport {
    /// The step with the largest load factor, and that load factor.
    pub peak_step: usize,
    pub peak_load_factor: f64,
    /// The scene's reference stress: the largest magnitude of a side's
    /// normal traction, Pa (`λ` times it is the load shown).
    pub reference_stress: f64,
    /// `peak_load_factor` × `reference_stress`, Pa.
    pub peak_stress: f64,
    /// Load factor at which the uncracked specimen's rock first meets its
    /// envelope (the largest disc reading reaches 1); `None` when it never
    /// does at this load ratio (confinement with k N_φ ≥ 1, or a rock
    /// without cohesion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intact_load_factor: Option<f64>,
    /// `peak_load_factor / intact_load_factor`: below 1 the flaws weaken
    /// the specimen.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// The comparison in words (and why there is none, when there is none).
    pub note: String,
}

/// Cracks started in the intact rock at one load, up to the bound: the
/// rock fails there at a load that does not rise, so the specimen has
/// reached its peak and the run stops (outcome `unstable`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StartLimitReport {
    /// The load factor (within the λ search's band) of the starts.
    pub load_factor: f64,
    /// Starts at that load.
    pub starts: usize,
    /// What stopped the run, in words.
    pub reason: String,
}

/// A growth run stopped by `growth.max_load_factor` (critical control).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct LoadCapReport {
    /// `growth.max_load_factor`, the highest λ the λ_cr search tries.
    pub max_load_factor: f64,
    /// What stopped the run, in words.
    pub reason: String,
}

impl LoadCapReport {
    /// The report of a run stopped at `max_load_factor`.
    pub fn at(max_load_factor: f64) -> Self {
        Self {
            max_load_factor,
            reason: format!(
                "stopped at the load cap growth.max_load_factor = {max_load_factor}: no free \
                 tip meets its criterion at any load factor below it"
            ),
        }
    }
}

/// How a growth run ended.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    #[default]
    Completed,
    Unstable,
    Through,
    MaxSteps,
    /// A step's solve (linear or contact) did not converge: growth stopped
    /// rather than go on from an untrusted state.
    NotConverged,
    /// A step's solve failed with an error (say a singular stiffness):
    /// growth stopped, the history holds the steps before it and the
    /// report's `error` says what happened.
    Error,
}

/// One solve-evaluate-grow step of SPEC §9.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GrowthStepReport {
    pub step: usize,
    pub load_factor: f64,
    pub grown: Vec<GrownTip>,
    pub contact: ContactCounts,
    /// The step's solve passed every convergence test (linear solve and
    /// contact iteration).
    pub converged: bool,
    pub solver_iterations: usize,
    pub seconds: f64,
    /// Total length of all cracks after the step, m (the abscissa of the
    /// load factor: λ_cr rising with it is stable growth).
    #[serde(default)]
    pub crack_length: f64,
    /// Every free tip's SIFs and decision at this step.
    #[serde(default)]
    pub tips: Vec<TipReport>,
    /// Which convergence test failed, in words, when `converged` is false
    /// (the reason growth stopped `not_converged`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    /// The rock away from the cracks against its strength at this step's
    /// load (left out for a rock without cohesion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intact_rock: Option<IntactRockReport>,
    /// Load factors of this step's λ_cr trials whose solve did not
    /// converge (left out when none): up to three the search moved away
    /// from, so that `load_factor` is the lowest root among the converged
    /// trials (one between an unsolved trial and the bracket may have been
    /// passed over); on an unconverged step, also the trial that ended it.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unsolved_trials: Vec<f64>,
    /// Load factors of this step's λ_cr trials whose contact iteration did
    /// not settle from its warm start (the last trial's states and
    /// displacement) and that were solved once more from a cold start, as
    /// a fresh solve of the scene would be (left out when none). A trial
    /// that converged so is an ordinary trial; one that did not is also in
    /// `unsolved_trials`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub cold_trials: Vec<f64>,
    /// Load factors of this step's λ_cr trials that were not solved but
    /// taken from the trial before by scaling (left out when none): with no
    /// cohesion on any crack face, the solution at `s λ` is `s` times the
    /// one at `λ`, with the same contact states (checked). Such a trial, and
    /// `load_factor` when it is one, carries the contact and solver
    /// iterations and residuals of the solve it was scaled from.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub scaled_trials: Vec<f64>,
    /// Secondary cracks started at kinks in this step (left out when none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub started: Vec<StartedCrack>,
    /// Grown tips that ended on another crack in this step (left out when
    /// none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub links: Vec<LinkReport>,
    /// Every kink evaluated at this step's load (left out when none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub kinks: Vec<KinkReport>,
    /// Cracks started in the intact rock in this step (left out when none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nucleated: Vec<NucleatedCrack>,
    /// What the step cost, its λ_cr search's trials included, and where
    /// its `seconds` went.
    #[serde(default)]
    pub work: WorkReport,
    /// The intact rock's most critical site at this step's load (left out
    /// under `growth.intact_rock = "ignore"` and where no site is left).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rock_site: Option<RockSiteReport>,
}

impl GrowthStepReport {
    /// The report without its times (`seconds`, and the seconds of
    /// `work`): what two runs of the same step must agree on to the bit.
    #[must_use]
    pub fn untimed(&self) -> Self {
        Self {
            seconds: 0.0,
            work: WorkReport {
                build_seconds: 0.0,
                solve_seconds: 0.0,
                evaluate_seconds: 0.0,
                other_seconds: 0.0,
                setup_seconds: 0.0,
                second_solve_seconds: 0.0,
                seconds: 0.0,
                ..self.work.clone()
            },
            ..self.clone()
        }
    }
}

/// What one growth step did, as a scene saved mid-run keeps it
/// (`growth.resume.history`): its report's step number, load factor and
/// events, without its tips, trials and times.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepEvents {
    pub step: usize,
    pub load_factor: f64,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub grown: Vec<GrownTip>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub started: Vec<StartedCrack>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub links: Vec<LinkReport>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nucleated: Vec<NucleatedCrack>,
}

impl StepEvents {
    /// The events of `step`'s report.
    pub fn of(step: &GrowthStepReport) -> Self {
        Self {
            step: step.step,
            load_factor: step.load_factor,
            grown: step.grown.clone(),
            started: step.started.clone(),
            links: step.links.clone(),
            nucleated: step.nucleated.clone(),
        }
    }

    /// As the scene file holds it. (Plain numbers and lists: writing one
    /// cannot fail; a non-finite λ would be `null`, which reads back as
    /// an error naming the entry.)
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }

    /// A step report holding these events (a step the run went on from:
    /// it converged); the rest of the report is left at its defaults.
    pub fn report(&self) -> GrowthStepReport {
        GrowthStepReport {
            step: self.step,
            load_factor: self.load_factor,
            converged: true,
            grown: self.grown.clone(),
            started: self.started.clone(),
            links: self.links.clone(),
            nucleated: self.nucleated.clone(),
            ..GrowthStepReport::default()
        }
    }

    /// The steps a saved run did (`resume.history`), as step reports, for
    /// a scene of `cracks` cracks: each entry must read as [`StepEvents`],
    /// the steps follow each other up to `resume.steps`, each at a finite
    /// load factor ≥ 0, naming only the scene's cracks (a link's flaws
    /// index the cracks' lineage). The first bad entry is the error.
    pub fn read(resume: &Resume, cracks: usize) -> Result<Vec<GrowthStepReport>, SceneError> {
        let mut last = 0;
        let mut steps = Vec::with_capacity(resume.history.len());
        for (k, entry) in resume.history.iter().enumerate() {
            let field = |name: &str| format!("growth.resume.history[{k}]{name}");
            let s: Self = serde_json::from_value(entry.clone()).map_err(|e| {
                SceneError::invalid(field(""), "an entry", format!("does not read: {e}"))
            })?;
            if s.step <= last || s.step > resume.steps {
                let reason = format!(
                    "must follow step {last} of the entry before and be at most \
                     growth.resume.steps ({})",
                    resume.steps
                );
                return Err(SceneError::invalid(field(".step"), s.step, reason));
            }
            last = s.step;
            if !(s.load_factor.is_finite() && s.load_factor >= 0.0) {
                let reason = "must be a finite number ≥ 0";
                return Err(SceneError::invalid(
                    field(".load_factor"),
                    s.load_factor,
                    reason,
                ));
            }
            if let Some(c) = s.cracks().find(|&c| c >= cracks) {
                let reason = format!("names crack {c}: must name one of the {cracks} cracks");
                return Err(SceneError::invalid(field(".step"), s.step, reason));
            }
            steps.push(s.report());
        }
        Ok(steps)
    }

    /// The cracks it names.
    fn cracks(&self) -> impl Iterator<Item = usize> + '_ {
        let grown = self.grown.iter().map(|g| g.crack);
        let started = self.started.iter().flat_map(|s| [s.crack, s.on]);
        let links = self
            .links
            .iter()
            .flat_map(|l| [l.crack, l.main, l.flaws[0], l.flaws[1]]);
        let nucleated = self.nucleated.iter().map(|n| n.crack);
        grown.chain(started).chain(links).chain(nucleated)
    }
}

/// A tip that grew in a step: its new position and how it grew.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GrownTip {
    pub crack: usize,
    pub tip: usize,
    pub x: f64,
    pub y: f64,
    pub mode: Mode,
    pub angle_deg: f64,
    pub k1: f64,
    pub k2: f64,
}

/// Counts of face points per contact state, and how the contact iteration
/// that produced them ended.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactCounts {
    pub open: usize,
    pub stick: usize,
    pub slip: usize,
    /// The contact iteration converged (see [`ContactReport::converged`]).
    #[serde(default)]
    pub converged: bool,
    /// Contact iterations done.
    #[serde(default)]
    pub iterations: usize,
    /// Relative displacement change of the last contact iteration.
    #[serde(default)]
    pub residual: f64,
    /// Points frozen for cycling, and those of them breaking the law.
    #[serde(default)]
    pub cycling: usize,
    #[serde(default)]
    pub violating: usize,
}

impl SolveReport {
    /// Whether the solve can be trusted: the linear solver and the contact
    /// iteration both converged.
    pub fn converged(&self) -> bool {
        self.solver.converged && self.contact.converged && self.free_piece.is_none()
    }

    /// One line naming the convergence test that failed, if any: the
    /// linear solve's cap, the contact iteration's cap, or frozen points
    /// that break the contact law once the states settled.
    pub fn failure(&self) -> Option<String> {
        let (s, c) = (&self.solver, &self.contact);
        if let Some(p) = &self.free_piece {
            Some(format!(
                "the specimen is split: {}, so it has no equilibrium",
                p.describe()
            ))
        } else if !s.converged && s.kind == "direct" {
            Some(format!(
                "the direct solve's true relative residual {:.3e} is above {:.0e} after \
                 iterative refinement: the matrix is singular or too ill-conditioned (a \
                 piece held by its crack faces alone, or joint stiffness far above E/h)",
                s.residual,
                crate::scene::DIRECT_TOLERANCE,
            ))
        } else if !s.converged {
            Some(format!(
                "the {} solver stopped at {} iterations with relative residual {:.3e} \
                 above its tolerance (solver.tolerance, solver.max_iterations)",
                s.kind, s.iterations, s.residual
            ))
        } else if c.converged {
            None
        } else if c.capped {
            Some(format!(
                "the contact iteration did not settle within {} contact iterations \
                 (solver.max_contact_iterations): {} points not yet in their Coulomb \
                 state ({} cycling between states), last relative change of u or of \
                 the friction limits {:.3e} (solver.contact_tolerance)",
                c.iterations, c.unsettled, c.cycling, c.residual
            ))
        } else if c.violating > 0 {
            Some(format!(
                "{} of the {} face points frozen for stick–slip cycling break the \
                 contact law at the final displacement (after {} contact iterations)",
                c.violating, c.cycling, c.iterations
            ))
        } else {
            Some(format!(
                "the contact iteration did not settle ({} iterations, relative change \
                 of u {:.3e})",
                c.iterations, c.residual
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// A scene of two drawn cracks saved after step 3, its history's
    /// entries `history` (JSON).
    fn saved(history: &str) -> Resume {
        let text = format!(
            r#"{{"specimen":{{"width":0.03,"height":0.03}},"mesh":{{"nx":30,"ny":30}},
            "material":{{"young":4.78e9,"cohesion":15e6}},
            "cracks":[{{"points":[[0.01,0.01],[0.013,0.013]]}},{{"points":[[0.02,0.02],[0.023,0.023]]}}],
            "growth":{{"resume":{{"steps":3,"load_factor":0.5,"history":[{history}]}}}}}}"#
        );
        let scene = Scene::from_json(&text).expect("the scene holds any JSON entries");
        scene.growth.resume.clone().expect("resume")
    }

    fn field_of(history: &str) -> Option<String> {
        match StepEvents::read(&saved(history), 2) {
            Err(SceneError::Invalid { field, .. }) => Some(field),
            Err(e) => panic!("{e}"),
            Ok(_) => None,
        }
    }

    /// A step's events go into the scene file and back as they were, as
    /// a converged report holding them.
    #[test]
    fn a_steps_events_round_trip() {
        let report = GrowthStepReport {
            step: 3,
            load_factor: 0.6,
            seconds: 1.5,
            grown: vec![GrownTip {
                crack: 0,
                tip: 1,
                mode: Mode::Tension,
                ..GrownTip::default()
            }],
            links: vec![LinkReport {
                crack: 0,
                tip: 1,
                main: 1,
                flaws: [0, 1],
                coalescence: true,
                ..LinkReport::default()
            }],
            ..GrowthStepReport::default()
        };
        let entry = StepEvents::of(&report).to_json().to_string();
        let read = StepEvents::read(&saved(&entry), 2).expect("reads back");
        let expected = GrowthStepReport {
            seconds: 0.0,
            converged: true,
            ..report
        };
        assert_eq!(read, [expected]);
    }

    /// Entries out of order or past `steps`, a bad load factor, a crack
    /// the scene does not have and an entry that does not read are
    /// refused, naming the entry.
    #[test]
    fn a_bad_history_names_its_entry() {
        let cases = [
            (
                r#"{"step":2,"load_factor":0.4},{"step":2,"load_factor":0.5}"#,
                "growth.resume.history[1].step",
            ),
            (
                r#"{"step":4,"load_factor":0.4}"#,
                "growth.resume.history[0].step",
            ),
            (
                r#"{"step":1,"load_factor":-1.0}"#,
                "growth.resume.history[0].load_factor",
            ),
            (
                r#"{"step":1,"load_factor":0.4,"grown":[{"crack":2,"tip":0,"x":0,"y":0,"mode":"tension","angle_deg":0,"k1":0,"k2":0}]}"#,
                "growth.resume.history[0].step",
            ),
            (
                r#"{"step":1,"load_factor":0.4,"pace":1}"#,
                "growth.resume.history[0]",
            ),
            (r#"{"step":1}"#, "growth.resume.history[0]"),
        ];
        for (history, field) in cases {
            assert_eq!(field_of(history).as_deref(), Some(field), "{history}");
        }
        assert_eq!(field_of(r#"{"step":1,"load_factor":0.4}"#), None);
        assert_eq!(field_of(""), None, "a file without the history");
    }
}
