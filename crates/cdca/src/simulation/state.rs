//! The simulation's data: the model (immutable), the state (what a saved
//! session would need to resume) and the scratch (derived, never
//! serialised), and the settings read from the scene.

use web_time::Instant;

use super::job::Job;
use super::search::CriticalRun;
use crate::contact::in_sweep::InSweepParams;
use crate::contact::law::{ContactState, FaceState};
use crate::contact::status::{ContactInfo, ContactParams};
use crate::discretisation::model::Model;
use crate::discretisation::xfem::{Reuse, Xfem};
use crate::error::{SceneError, SolveError};
use crate::fracture::criterion::{Circle, CriterionParams, Faces};
use crate::fracture::sites::{Readings, SiteGrid};
use crate::fracture::tips::TipDomains;
use crate::geometry::cracks::{Crack, TipKind, split_specimen};
use crate::report::{
    GrowthStepReport, KinkReport, Outcome, StartLimitReport, StepEvents, TipReport, WorkReport,
};
use crate::scene::{Lineage, MIN_END_SEGMENT, RockStarts, Scene, SceneFile, SideBc, fmt_point};
use crate::solvers::automaton::AutomatonParams;
use crate::solvers::direct::Factor;
use crate::solvers::linear::LinearSolver;
use crate::solvers::relaxation::ResidualSample;

/// One scene being simulated: the model (immutable), the state (cracks,
/// load factor, displacement, committed contact states, history) and the
/// scratch (discretisation, solver and its factorisation, tip results).
pub struct Simulation {
    pub(super) model: Model,
    pub(super) state: State,
    pub(super) scratch: Scratch,
}

/// What a saved session would need to resume.
pub(super) struct State {
    /// The scene with the current (grown) cracks.
    pub(super) scene: Scene,
    pub(super) cracks: Vec<Crack>,
    pub(super) lambda: f64,
    /// Free-DOF displacement of the current discretisation.
    pub(super) u: Vec<f64>,
    /// Contact states of the last converged solve.
    pub(super) faces: Vec<FaceState>,
    pub(super) solved: bool,
    pub(super) history: Vec<GrowthStepReport>,
    /// The steps of the run this scene resumes (`growth.resume.history`:
    /// their events only), before [`history`](Self::history).
    pub(super) earlier: Vec<GrowthStepReport>,
    pub(super) outcome: Option<Outcome>,
    /// Load increment (1-based) the growth loop is at, and growths there.
    pub(super) increment: usize,
    pub(super) growths_here: usize,
    /// Growth steps done before this simulation (`growth.resume.steps`).
    pub(super) steps_before: usize,
    /// What each crack's parts are (flaw, wing, secondary), for the links
    /// the growth report names.
    pub(super) lineage: Vec<Lineage>,
    /// The run's peak and the starts in the intact rock at it
    /// (`growth.intact_rock = "nucleate"`).
    pub(super) rock_starts: RockStarts,
    /// The bound on those starts stopped the run.
    pub(super) start_limit: Option<StartLimitReport>,
}

/// Derived data, rebuilt from model and state; never serialised.
pub(super) struct Scratch {
    pub(super) xfem: Xfem,
    pub(super) f_ext: Vec<f64>,
    pub(super) solver: Box<dyn LinearSolver>,
    pub(super) tips: Vec<TipReport>,
    pub(super) circles: Vec<Circle>,
    /// The faces at each free tip, as the criterion saw them.
    pub(super) tip_faces: Vec<Faces>,
    pub(super) contact: ContactInfo,
    pub(super) residual: Vec<ResidualSample>,
    /// The solve in progress (the contact iteration), if any.
    pub(super) job: Option<Job>,
    /// Start of a resumable growth step in progress.
    pub(super) growth_start: Option<Instant>,
    /// Each free tip's utilisation after the last solve (≥ 1: it grows).
    pub(super) utilisation: Vec<f64>,
    /// Every sharp kink evaluated after the last solve, and each one's
    /// utilisation (≥ 1: a secondary crack starts there).
    pub(super) kinks: Vec<KinkReport>,
    pub(super) kink_utilisation: Vec<f64>,
    /// The free tips' interaction-integral domains on `xfem`, once a solve
    /// has been evaluated (remade when they no longer fit it).
    pub(super) tip_domains: Option<TipDomains>,
    /// The critical-control step in progress, if any.
    pub(super) critical: Option<CriticalRun>,
    /// Contact states the next solve's contact iteration starts from (a
    /// guess: the slip history stays `State::faces`); `None`: from those.
    pub(super) contact_guess: Option<Vec<FaceState>>,
    /// The contact states `solver`'s current matrix was built with (see
    /// [`ContactSolve::advance`](crate::contact::iteration::ContactSolve::advance));
    /// `None` with a new solver or
    /// discretisation.
    pub(super) factored: Option<Vec<ContactState>>,
    /// Quadrature points the last rebuild left to integrate.
    pub(super) rebuild_points: usize,
    /// The intact rock's sites on `xfem` (made at the first reading of a
    /// growth run under `growth.intact_rock = "nucleate"`, remade after
    /// every rebuild).
    pub(super) site_grid: Option<SiteGrid>,
    /// Their readings after the last real solve of a growth run.
    pub(super) rock: Option<Readings>,
    /// The uncracked specimen's failure load factor, and the sentence
    /// (solved at the first ask).
    pub(super) intact: std::cell::OnceCell<(Option<f64>, String)>,
    /// What the solve or growth step under way has cost so far.
    pub(super) work: WorkReport,
}

/// Whether `b` has the discretisation of `a`
/// ([`Simulation::with_scene`]): the same but for load values, the faces'
/// contact law, the criterion, the growth and the solver settings (read at
/// solve time; the solver is made anew), name and description, and
/// neither resumes a growth run.
fn same_discretisation(a: &SceneFile, b: &SceneFile) -> bool {
    a.cracks.len() == b.cracks.len()
        && a.cracks
            .iter()
            .zip(&b.cracks)
            .all(|(ca, cb)| ca.points == cb.points && ca.arc == cb.arc)
        && same_plate(a, b)
}

/// Whether `b` has the mesh, material and supports of `a`: the same but
/// for the cracks and what [`same_discretisation`] leaves out, and
/// neither resumes a growth run.
fn same_plate(a: &SceneFile, b: &SceneFile) -> bool {
    if a.growth.resume.is_some() || b.growth.resume.is_some() {
        return false;
    }
    let mut b = b.clone();
    b.cracks.clone_from(&a.cracks);
    b.name.clone_from(&a.name);
    b.description.clone_from(&a.description);
    b.criterion = a.criterion.clone();
    b.growth = a.growth.clone();
    b.solver = a.solver.clone();
    for (sa, sb) in [
        (&a.boundary.bottom, &mut b.boundary.bottom),
        (&a.boundary.left, &mut b.boundary.left),
        (&a.boundary.top, &mut b.boundary.top),
        (&a.boundary.right, &mut b.boundary.right),
    ] {
        if matches!(
            (sa, &*sb),
            (SideBc::Traction { .. }, SideBc::Traction { .. })
        ) {
            *sb = *sa;
        }
    }
    *a == b
}

/// Whether a scene's cracks leave the specimen in one piece, none meets
/// itself and every free tip's last segment is one the mesh resolves,
/// checked before any work (`cdca` runs it on every scene it reads; see
/// `untangled` and `resolved_tips` for the second and third): cracks that
/// run from the boundary back to the boundary, alone or linked
/// ([`split_specimen`]), have failed the specimen before any load (growth
/// ends `through` at such a split), and a piece held by crack faces alone
/// has no support once they open: the stiffness is singular. A scene saved
/// mid-growth (`growth.resume`) may hold a split: that run has ended.
///
/// Errors name the crack (`cracks[i]`, its end points) when one alone runs
/// from boundary to boundary, `cracks` for a linked chain, and the point
/// (`cracks[i].points[k]`, or `cracks[i].arc`) where a crack meets itself
/// or ends in too short a segment.
pub fn check_cracks(scene: &Scene) -> Result<(), SceneError> {
    let model = Model::new(scene.clone());
    sound(scene, &model.initial_cracks())
}

/// The checks of [`check_cracks`] on the built `cracks`.
fn sound(scene: &Scene, cracks: &[Crack]) -> Result<(), SceneError> {
    untangled(scene, cracks)?;
    resolved_tips(scene, cracks)?;
    unsplit(scene, cracks)
}

/// No crack meets itself ([`Crack::self_contact`], within a thousandth of
/// an element): its faces would have to meet themselves, and a closed loop
/// cuts a piece free. A crack that ran 26 mm along a line and turned back
/// along it, 0.5 µm off, solved and then stopped growth at its second step
/// with a non-positive pivot.
fn untangled(scene: &Scene, cracks: &[Crack]) -> Result<(), SceneError> {
    let tol = 1e-3 * scene.element_size();
    for (i, crack) in cracks.iter().enumerate() {
        if let Some(k) = crack.self_contact(tol) {
            return Err(SceneError::invalid(
                point_field(scene, i, k),
                fmt_point([crack.points[k].x, crack.points[k].y]),
                "the crack turns straight back, crosses itself or comes within a \
                 thousandth of an element of itself here (a crack's faces cannot meet \
                 themselves; a closed loop cuts a piece free)",
            ));
        }
    }
    Ok(())
}

/// The scene field of point `k` of crack `i`'s polyline: the point itself,
/// or the arc it was sampled from.
fn point_field(scene: &Scene, i: usize, k: usize) -> String {
    match scene.cracks[i].arc {
        Some(_) => format!("cracks[{i}].arc"),
        None => format!("cracks[{i}].points[{k}]"),
    }
}

/// Every free tip's last segment is at least [`MIN_END_SEGMENT`] elements
/// long: the tip takes its direction from it. Growth never makes a shorter
/// one (`growth.increment` has the same floor); a segment cut short at a
/// junction or the boundary ends at no tip.
fn resolved_tips(scene: &Scene, cracks: &[Crack]) -> Result<(), SceneError> {
    let h = scene.element_size();
    for (i, crack) in cracks.iter().enumerate() {
        for k in crack.free_tips() {
            let (inner, end) = crack.end_segment(k);
            let length = (end - inner).norm();
            if length >= MIN_END_SEGMENT * h {
                continue;
            }
            let index = if k == 0 { 0 } else { crack.points.len() - 1 };
            return Err(SceneError::invalid(
                point_field(scene, i, index),
                fmt_point([end.x, end.y]),
                format!(
                    "the segment at this free end is {length:.3e} m long, less than \
                     {MIN_END_SEGMENT} h (h = {h} m, the element size): the tip takes its \
                     direction from it, and the mesh cannot resolve one this short \
                     (remove the point or move it further out)"
                ),
            ));
        }
    }
    Ok(())
}

fn unsplit(scene: &Scene, cracks: &[Crack]) -> Result<(), SceneError> {
    if scene.growth.resume.is_some() || !split_specimen(cracks) {
        return Ok(());
    }
    let path = "from the boundary back to the boundary";
    let why = "before any load: a piece held by its crack faces alone has no support once \
               they open (end the cracks inside the specimen)";
    Err(
        match cracks.iter().position(|c| c.tips == [TipKind::Boundary; 2]) {
            Some(i) => {
                let ends = [cracks[i].tip_point(0), cracks[i].tip_point(1)];
                SceneError::invalid(
                    format!("cracks[{i}]"),
                    format!(
                        "from [{}, {}] to [{}, {}]",
                        ends[0].x, ends[0].y, ends[1].x, ends[1].y
                    ),
                    format!("this crack runs {path} and cuts the specimen in two {why}"),
                )
            }
            None => SceneError::invalid(
                "cracks",
                format!("{} cracks", cracks.len()),
                format!("linked, these cracks run {path} and cut the specimen in two {why}"),
            ),
        },
    )
}

impl Simulation {
    /// Builds the discretisation of a (valid) scene; no solve yet: the
    /// enriched elements' stiffness is integrated by the first
    /// [`relax`](Self::relax) calls, a chunk at a time, as after growth.
    /// Fails when the cracks split the specimen ([`check_cracks`]) or
    /// `growth.resume` does not fit the cracks' discretisation.
    pub fn new(scene: Scene) -> Result<Self, SolveError> {
        let model = Model::new(scene);
        let cracks = model.initial_cracks();
        sound(&model.scene, &cracks)?;
        let xfem = model.rediscretise(cracks.clone(), None);
        let rebuild_points = xfem.points_to_integrate();
        Self::from_parts(model, cracks, xfem, rebuild_points)
    }

    /// A simulation of `scene` that keeps this one's discretisation (its
    /// integrated elements, stiffness pattern and symbolic factorisation)
    /// when nothing it depends on changed: `scene` differs from this one's
    /// only in load values (traction sides), the faces' contact law
    /// (friction, cohesion, stiffness), the criterion, the growth settings
    /// (without `growth.resume`), the solver settings, name or description,
    /// and no tip has grown here. Everything else starts afresh, as in
    /// [`new`](Self::new), so it solves exactly as a new simulation of
    /// `scene` would; otherwise it is one. An edit of the load or the
    /// friction in the workbench then re-solves without integrating or
    /// ordering anything.
    ///
    /// Where only the cracks differ (a crack dragged, drawn or removed),
    /// the elements no edited crack enriches keep their stiffness, and the
    /// stiffness pattern is kept when the elements couple the same DOFs (a
    /// crack moved within the elements it cuts and enriches); the result
    /// is the same, to the last bit, as a new simulation's.
    pub fn with_scene(self, scene: Scene) -> Result<Self, SolveError> {
        if !self.state.history.is_empty() || !same_plate(&self.model.scene, &scene) {
            // freed first: a large factor need not live beside the new build
            drop(self);
            return Self::new(scene);
        }
        if !same_discretisation(&self.model.scene, &scene) {
            return self.with_cracks(scene);
        }
        // the current factor goes on as storage (see `adopt`); the rest
        // (solver, state) is freed at the block's end
        let (mut xfem, rebuild_points, factor) = {
            let mut old = self;
            let factor = old.scratch.solver.hand_over_factor();
            (old.scratch.xfem, old.scratch.rebuild_points, factor)
        };
        let model = Model::new(scene);
        let cracks = model.initial_cracks();
        for (kept, new) in xfem.funcs.cracks.iter_mut().zip(&cracks) {
            kept.friction = new.friction;
            kept.cohesion = new.cohesion;
            kept.kn = new.kn;
            kept.kt = new.kt;
        }
        debug_assert!(xfem.funcs.cracks == cracks, "the same crack geometry");
        Self::from_parts(model, cracks, xfem, rebuild_points).map(|s| s.adopt(factor))
    }

    /// [`with_scene`](Self::with_scene) for a scene whose cracks differ
    /// from this one's (and nothing else it is built from).
    fn with_cracks(self, scene: Scene) -> Result<Self, SolveError> {
        let model = Model::new(scene);
        let cracks = model.initial_cracks();
        sound(&model.scene, &cracks)?;
        // the current factor goes on as storage (see `adopt`); the rest
        // (solver, state) is freed at the block's end
        let (mut previous, factor) = {
            let mut old = self;
            let factor = old.scratch.solver.hand_over_factor();
            (old.scratch.xfem, factor)
        };
        let old = &previous.funcs.cracks;
        let redrawn = cracks
            .iter()
            .enumerate()
            .map(|(i, c)| old.get(i).is_none_or(|o| o.points != c.points))
            .collect();
        let reuse = Reuse {
            previous: &previous,
            moved: Vec::new(),
            redrawn,
        };
        let mut xfem = model.rediscretise(cracks.clone(), Some(&reuse));
        xfem.offer_pattern(previous.take_pattern());
        drop(previous);
        let rebuild_points = xfem.points_to_integrate();
        Self::from_parts(model, cracks, xfem, rebuild_points).map(|s| s.adopt(factor))
    }

    /// This simulation with its solver given `factor`, the factor of the
    /// simulation it was built from, as storage for its first
    /// factorisation: on a kept stiffness pattern (a crack moved within the
    /// elements it enriches, a load or the faces' law edited) that redoes
    /// only the supernodes whose values changed, bit for bit as a
    /// factorisation anew (`Factor::reassemble`).
    pub(super) fn adopt(mut self, factor: Option<Factor>) -> Self {
        if let Some(f) = factor {
            self.scratch.solver.adopt_factor(f);
        }
        self
    }

    /// Drops the solver's factorisations and setup (a new solver of the
    /// scene's kind takes its place): for a simulation kept only for its
    /// discretisation, which [`with_scene`](Self::with_scene) reuses with
    /// a solver of its own. A direct factor of a 400 × 400 mesh holds
    /// about 0.8 GB.
    pub fn release_solver(&mut self) {
        self.scratch.solver = crate::solvers::choice::make_solver(&self.model.scene.solver);
        self.scratch.factored = None;
        self.scratch.job = None;
    }

    /// The simulation of `model.scene` on the discretisation `xfem` of
    /// `cracks`, before any solve.
    pub(super) fn from_parts(
        model: Model,
        cracks: Vec<Crack>,
        xfem: Xfem,
        rebuild_points: usize,
    ) -> Result<Self, SolveError> {
        let scene = model.scene.clone();
        let f_ext = crate::discretisation::loads::traction_forces(&xfem, &scene.boundary);
        let n = xfem.n_free();
        let nf = xfem.faces.len();
        let resume = scene.growth.resume.clone();
        let faces = match &resume {
            Some(r) if r.faces.len() == nf => r.faces.iter().map(FaceState::restored).collect(),
            Some(r) => {
                return Err(SceneError::invalid(
                    "growth.resume.faces",
                    format!("{} entries", r.faces.len()),
                    format!("the cracks have {nf} face points"),
                )
                .into());
            }
            None => vec![FaceState::default(); nf],
        };
        let earlier = match &resume {
            Some(r) => StepEvents::read(r, cracks.len())?,
            None => Vec::new(),
        };
        let lineage = match resume.as_ref().and_then(|r| r.lineage_of(cracks.len())) {
            Some(saved) => saved.to_vec(),
            None => (0..cracks.len())
                .map(|i| Lineage::drawn(i, cracks[i].points.len()))
                .collect(),
        };
        Ok(Self {
            scratch: Scratch {
                xfem,
                f_ext,
                solver: crate::solvers::choice::make_solver(&scene.solver),
                tips: Vec::new(),
                circles: Vec::new(),
                tip_faces: Vec::new(),
                contact: ContactInfo::default(),
                residual: Vec::new(),
                job: None,
                growth_start: None,
                utilisation: Vec::new(),
                kinks: Vec::new(),
                kink_utilisation: Vec::new(),
                tip_domains: None,
                critical: None,
                contact_guess: None,
                factored: None,
                rebuild_points,
                site_grid: None,
                rock: None,
                intact: std::cell::OnceCell::new(),
                work: WorkReport::default(),
            },
            state: State {
                scene,
                cracks,
                lambda: resume.as_ref().map_or(1.0, |r| r.load_factor),
                u: vec![0.0; n],
                faces,
                solved: false,
                history: Vec::new(),
                earlier,
                outcome: None,
                increment: resume.as_ref().map_or(1, |r| r.increment),
                growths_here: resume.as_ref().map_or(0, |r| r.growths_here),
                steps_before: resume.as_ref().map_or(0, |r| r.steps),
                lineage,
                rock_starts: resume
                    .as_ref()
                    .and_then(|r| r.rock_starts)
                    .unwrap_or_default(),
                start_limit: None,
            },
            model,
        })
    }

    /// The scene as currently simulated (cracks include grown segments).
    pub fn scene(&self) -> &Scene {
        &self.state.scene
    }

    /// The discretisation (for exports and diagnostics).
    pub fn xfem(&self) -> &Xfem {
        &self.scratch.xfem
    }

    /// Free-DOF displacement of the last solve.
    pub fn displacement(&self) -> &[f64] {
        &self.state.u
    }

    /// Load factor λ applied to every load: in [0, 1] under load control
    /// and as set by [`set_load_factor`](Self::set_load_factor); λ_cr of
    /// the current step under critical control.
    pub fn load_factor(&self) -> f64 {
        self.state.lambda
    }

    pub fn set_load_factor(&mut self, lambda: f64) {
        if lambda.is_finite() {
            self.state.lambda = lambda.clamp(0.0, 1.0);
            self.state.solved = false;
            self.scratch.job = None;
            self.scratch.critical = None;
        }
    }

    pub(super) fn contact_params(&self) -> ContactParams {
        let s = &self.model.scene.solver;
        ContactParams {
            tolerance: s.contact_tolerance,
            max_iterations: s.max_contact_iterations,
            ..ContactParams::default()
        }
    }

    /// The in-sweep iteration's settings: the automaton's as
    /// [`Relaxation`](crate::solvers::Relaxation) sets them from the scene,
    /// at most `solver.max_iterations` sweeps.
    pub(super) fn in_sweep_params(&self) -> InSweepParams {
        let s = &self.model.scene.solver;
        InSweepParams {
            automaton: AutomatonParams {
                omega: s.omega,
                tolerance: s.tolerance,
                tolerance_u: s.tolerance,
                ..AutomatonParams::default()
            },
            ordering: s.ordering,
            contact: self.contact_params(),
            max_sweeps: s.max_iterations,
        }
    }

    pub(super) fn criterion_params(&self) -> CriterionParams {
        CriterionParams::of_scene(&self.model.scene)
    }

    /// Whether the displacement belongs to the current cracks and load.
    pub fn is_solved(&self) -> bool {
        self.state.solved
    }
}
