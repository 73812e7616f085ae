//! The facade used by the CLI and the workbench: one scene, its model, its
//! mutable state and its scratch, and the steps of the method.

use web_time::Instant;

use crate::assembly::ElementBlock;
use crate::contact::{FaceState, carry_over, contact_system, counts};
use crate::contact_loop::{
    ContactInfo, ContactParams, FlipTracker, any_slip, relative_change, solve_with_contact,
    update_states,
};
use crate::cracks::{Crack, TipKind, classify_tips};
use crate::criterion::{Circle, CriterionParams};
use crate::error::SolveError;
use crate::field::Field;
use crate::geometry::P2;
use crate::growth::{apply, extend};
use crate::model::Model;
use crate::relaxation::Relaxation;
use crate::report::{
    ContactReport, GrownTip, GrowthStepReport, Mode, Outcome, SolveReport, SolverReport, TipReport,
};
use crate::scene::Scene;
use crate::solver::LinearSolver;
use crate::tips::evaluate_tips;
use crate::xfem::Xfem;

/// State of a crack-face contact point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactState {
    Open,
    Stick,
    Slip,
}

/// A crack-face integration point as the UI shows it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPointView {
    /// Index of the crack in the scene's `cracks`.
    pub crack: usize,
    /// Position, m.
    pub x: f64,
    pub y: f64,
    /// Unit normal pointing into the φ > 0 side.
    pub normal: [f64; 2],
    pub state: ContactState,
    /// Normal traction p_N, Pa (≤ 0 in contact).
    pub p_n: f64,
    /// Tangential traction p_T, Pa, along `t = (n_y, −n_x)` (the crack's
    /// direction). The traction acting on the φ > 0 face is
    /// `−(p_N n + p_T t)`, on the φ < 0 face `+(p_N n + p_T t)`.
    pub p_t: f64,
    /// Tangential gap (slip) g_T, m.
    pub slip: f64,
}

/// σ_θθ and τ_rθ on the circle r0 around one tip (SPEC §8), for plots.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CriterionCurve {
    /// Angles in the tip frame, degrees.
    pub theta_deg: Vec<f64>,
    /// σ_θθ(θ, r0), Pa.
    pub sigma_tt: Vec<f64>,
    /// τ_rθ(θ, r0), Pa.
    pub tau_rt: Vec<f64>,
    /// Tensile strength σ_t, Pa.
    pub sigma_t: f64,
    /// r0, m.
    pub r0: f64,
}

/// Relative residual below which the automaton updates contact states
/// inside its sweeps.
pub const IN_SWEEP_CONTACT_RESIDUAL: f64 = 1e-3;

/// One sample of an iterative solve's progress.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ResidualSample {
    pub iteration: usize,
    /// Wall time since the relaxation started, s.
    pub seconds: f64,
    /// ‖f − K u‖ / ‖f‖.
    pub residual: f64,
}

/// Progress of a resumable relaxation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RelaxStatus {
    pub iterations: usize,
    pub residual: f64,
    pub converged: bool,
}

/// One scene being simulated: the model (immutable), the state (cracks,
/// load factor, displacement, committed contact states, history) and the
/// scratch (discretisation, solver and its factorisation, tip results).
pub struct Simulation {
    model: Model,
    state: State,
    scratch: Scratch,
}

/// What a saved session would need to resume.
struct State {
    /// The scene with the current (grown) cracks.
    scene: Scene,
    cracks: Vec<Crack>,
    lambda: f64,
    /// Free-DOF displacement of the current discretisation.
    u: Vec<f64>,
    /// Contact states of the last converged solve.
    faces: Vec<FaceState>,
    solved: bool,
    history: Vec<GrowthStepReport>,
    outcome: Option<Outcome>,
    /// Load increment (1-based) the growth loop is at, and growths there.
    increment: usize,
    growths_here: usize,
}

/// Derived data, rebuilt from model and state; never serialised.
struct Scratch {
    xfem: Xfem,
    f_ext: Vec<f64>,
    solver: Box<dyn LinearSolver>,
    tips: Vec<TipReport>,
    circles: Vec<Circle>,
    contact: ContactInfo,
    residual: Vec<ResidualSample>,
    /// The resumable solve in progress, if any.
    job: Option<RelaxJob>,
    /// Start of a resumable growth step in progress.
    growth_start: Option<Instant>,
}

/// A resumable solve with contact: the linear relaxation of the current
/// contact system, and the contact iteration around it.
struct RelaxJob {
    relaxation: Relaxation,
    blocks: Vec<ElementBlock>,
    /// Contact states of the current contact iteration.
    states: Vec<FaceState>,
    tracker: FlipTracker,
    contact_iterations: usize,
    /// Iterations and seconds of earlier contact iterations (for the
    /// cumulative residual history).
    done_iterations: usize,
    done_seconds: f64,
    /// Displacement at the start of this contact iteration.
    start_u: Vec<f64>,
    /// Samples of `relaxation.history()` already copied to the cumulative
    /// history.
    copied: usize,
}

impl Simulation {
    /// Validates the scene and builds the discretisation (no solve yet).
    pub fn new(scene: Scene) -> Result<Self, SolveError> {
        scene.validate()?;
        let model = Model::new(scene.clone());
        let cracks = model.initial_cracks();
        let xfem = model.discretise(cracks.clone());
        let f_ext = crate::loads::traction_forces(&xfem, &scene.boundary);
        let n = xfem.n_free();
        let nf = xfem.faces.len();
        Ok(Self {
            scratch: Scratch {
                xfem,
                f_ext,
                solver: crate::solvers::make_solver(&scene.solver),
                tips: Vec::new(),
                circles: Vec::new(),
                contact: ContactInfo::default(),
                residual: Vec::new(),
                job: None,
                growth_start: None,
            },
            state: State {
                scene,
                cracks,
                lambda: 1.0,
                u: vec![0.0; n],
                faces: vec![FaceState::default(); nf],
                solved: false,
                history: Vec::new(),
                outcome: None,
                increment: 1,
                growths_here: 0,
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

    /// Load factor λ in [0, 1] applied to every load.
    pub fn load_factor(&self) -> f64 {
        self.state.lambda
    }

    pub fn set_load_factor(&mut self, lambda: f64) {
        if lambda.is_finite() {
            self.state.lambda = lambda.clamp(0.0, 1.0);
            self.state.solved = false;
            self.scratch.job = None;
        }
    }

    fn contact_params(&self) -> ContactParams {
        let s = &self.model.scene.solver;
        ContactParams {
            tolerance: s.contact_tolerance,
            max_iterations: s.max_contact_iterations,
            ..ContactParams::default()
        }
    }

    fn criterion_params(&self) -> CriterionParams {
        let h = self.model.mesh.h();
        let c = &self.model.scene.criterion;
        CriterionParams::new(c.kind, c.r0.unwrap_or(3.0 * h), &self.model.scene.material)
    }

    /// Full solve (with contact) at the current load factor with the scene's
    /// solver; fills SIFs and criterion at every free tip.
    pub fn solve(&mut self) -> Result<SolveReport, SolveError> {
        self.scratch.job = None;
        self.scratch.growth_start = None;
        let start = Instant::now();
        let f: Vec<f64> = self
            .scratch
            .f_ext
            .iter()
            .map(|v| v * self.state.lambda)
            .collect();
        let params = self.contact_params();
        let (states, info) = solve_with_contact(
            &self.scratch.xfem,
            &f,
            &self.state.faces,
            &mut self.state.u,
            self.scratch.solver.as_mut(),
            params,
        )?;
        self.state.faces = states;
        self.scratch.contact = info;
        self.state.solved = true;
        self.evaluate();
        let seconds = start.elapsed().as_secs_f64();
        self.scratch.residual = self
            .scratch
            .contact
            .last
            .history
            .iter()
            .enumerate()
            .map(|(i, &r)| ResidualSample {
                iteration: i + 1,
                seconds,
                residual: r,
            })
            .collect();
        Ok(self.report(seconds))
    }

    fn evaluate(&mut self) {
        let (tips, circles) = evaluate_tips(
            &self.scratch.xfem,
            &self.state.u,
            &self.state.faces,
            &self.criterion_params(),
            self.model.scene.criterion.sampling,
        );
        self.scratch.tips = tips;
        self.scratch.circles = circles;
    }

    /// The report of the last solve (SPEC §11).
    pub fn report(&self, seconds: f64) -> SolveReport {
        let x = &self.scratch.xfem;
        let c = counts(&self.state.faces);
        let info = &self.scratch.contact;
        let kn_h_over_e = x
            .funcs
            .cracks
            .iter()
            .map(|c| c.kn * x.mesh.h() / x.elastic.young)
            .fold(0.0, f64::max);
        SolveReport {
            dofs: x.n_free(),
            enriched_dofs: x.dofs.n_enriched,
            solver: SolverReport {
                kind: self.scratch.solver.name().to_string(),
                iterations: info.linear_iterations,
                residual: info.last.residual,
                converged: info.last.converged,
                seconds,
                residual_history: info.last.history.clone(),
            },
            contact: ContactReport {
                iterations: info.iterations,
                converged: info.converged,
                open: c.open,
                stick: c.stick,
                slip: c.slip,
                kn_h_over_e,
                cycling: info.cycling,
                residual: info.residual,
            },
            tips: self.scratch.tips.clone(),
        }
    }

    /// Starts (or restarts) a resumable solve from the current displacement
    /// with the scene's solver. The setup (cells, factorisations) happens at
    /// the first [`relax`](Self::relax) call, which reports its errors.
    pub fn start_relaxation(&mut self) {
        self.scratch.residual.clear();
        self.scratch.job = None;
    }

    fn new_job(
        &self,
        states: Vec<FaceState>,
        tracker: FlipTracker,
        contact_iterations: usize,
        done_iterations: usize,
        done_seconds: f64,
    ) -> Result<RelaxJob, SolveError> {
        let x = &self.scratch.xfem;
        let mut f: Vec<f64> = self
            .scratch
            .f_ext
            .iter()
            .map(|v| v * self.state.lambda)
            .collect();
        let blocks = contact_system(x, &states, &self.state.faces, &mut f);
        let spec = &self.model.scene.solver;
        let relaxation = Relaxation::new(spec.kind, spec, x, &blocks, &f, &self.state.u)?;
        Ok(RelaxJob {
            relaxation,
            blocks,
            states,
            tracker,
            contact_iterations,
            done_iterations,
            done_seconds,
            start_u: self.state.u.clone(),
            // later contact iterations do not repeat the iteration-0 sample
            copied: usize::from(done_iterations > 0),
        })
    }

    /// Runs at most `max_iterations` sweeps (or iterations) of the solve
    /// started by [`start_relaxation`](Self::start_relaxation) (started now
    /// if none is under way); cheap enough to call once per frame. When the
    /// linear solve converges, the contact states are updated and, if any
    /// changed, the relaxation continues on the new contact system; once
    /// nothing changes the tips are evaluated and the status is converged.
    pub fn relax(&mut self, max_iterations: usize) -> Result<RelaxStatus, SolveError> {
        if self.scratch.job.is_none() {
            self.scratch.residual.clear();
            let fresh = FlipTracker::new(self.state.faces.len());
            self.scratch.job = Some(self.new_job(self.state.faces.clone(), fresh, 0, 0, 0.0)?);
        }
        let Some(mut job) = self.scratch.job.take() else {
            unreachable!("a job was just started")
        };
        let status =
            job.relaxation
                .run(&self.scratch.xfem, &job.blocks, max_iterations, &mut |_| {})?;
        let offset = (job.done_iterations, job.done_seconds);
        let history = job.relaxation.history();
        self.scratch
            .residual
            .extend(
                history[job.copied.min(history.len())..]
                    .iter()
                    .map(|s| ResidualSample {
                        iteration: s.iteration + offset.0,
                        seconds: s.seconds + offset.1,
                        residual: s.residual,
                    }),
            );
        job.copied = history.len();
        self.state.u.copy_from_slice(job.relaxation.u());
        if !status.converged {
            let total = offset.0 + status.iterations;
            let job = self.contact_inside_sweeps(job, status, total)?;
            self.scratch.job = Some(job);
            return Ok(RelaxStatus {
                iterations: total,
                ..status
            });
        }
        // the linear solve converged: the contact iteration
        let params = self.contact_params();
        let committed = self.state.faces.clone();
        let changed = update_states(
            &self.scratch.xfem,
            &self.state.u,
            &committed,
            &mut job.states,
            &mut job.tracker,
            params,
        );
        let du = relative_change(&self.state.u, &job.start_u);
        let iterations = offset.0 + status.iterations;
        let contact_iterations = job.contact_iterations + 1;
        let settled = changed == 0 && (!any_slip(&job.states) || du <= params.tolerance);
        if settled || contact_iterations >= params.max_contact_iterations() {
            self.state.faces = job.states;
            self.scratch.contact = ContactInfo {
                iterations: contact_iterations,
                converged: settled,
                residual: du,
                cycling: job.tracker.frozen(),
                linear_iterations: iterations,
                last: crate::solver::LinearInfo {
                    iterations: status.iterations,
                    residual: status.residual,
                    converged: true,
                    history: job
                        .relaxation
                        .history()
                        .iter()
                        .map(|s| s.residual)
                        .collect(),
                },
            };
            self.state.solved = true;
            self.evaluate();
            return Ok(RelaxStatus {
                iterations,
                residual: status.residual,
                converged: true,
            });
        }
        let seconds = offset.1 + job.relaxation.seconds();
        let next = self.new_job(
            job.states,
            job.tracker,
            contact_iterations,
            iterations,
            seconds,
        )?;
        self.scratch.job = Some(next);
        Ok(RelaxStatus {
            iterations,
            residual: status.residual,
            converged: false,
        })
    }

    /// The paper's automaton updates the contact states inside its sweeps
    /// (steps 1–9): once the iterate means something (relative residual
    /// below [`IN_SWEEP_CONTACT_RESIDUAL`]), every chunk of sweeps
    /// re-evaluates the face states by the return mapping and, if any
    /// changed, continues on the new contact system from the current
    /// displacement. Points that keep flipping are frozen as in the outer
    /// loop. Other solvers keep the outer contact iteration.
    fn contact_inside_sweeps(
        &self,
        job: RelaxJob,
        status: RelaxStatus,
        total: usize,
    ) -> Result<RelaxJob, SolveError> {
        let automaton = self.model.scene.solver.kind == crate::scene::SolverKind::Automaton;
        if !automaton || job.states.is_empty() || status.residual > IN_SWEEP_CONTACT_RESIDUAL {
            return Ok(job);
        }
        let mut states = job.states.clone();
        let mut tracker = job.tracker.clone();
        let changed = update_states(
            &self.scratch.xfem,
            &self.state.u,
            &self.state.faces,
            &mut states,
            &mut tracker,
            self.contact_params(),
        );
        if changed == 0 {
            return Ok(job);
        }
        let seconds = job.done_seconds + job.relaxation.seconds();
        self.new_job(states, tracker, job.contact_iterations + 1, total, seconds)
    }

    /// Residual samples of the current relaxation.
    pub fn residual_history(&self) -> &[ResidualSample] {
        &self.scratch.residual
    }

    /// One growth step of SPEC §9: solve at the current load increment,
    /// evaluate every free tip, extend those that meet the criterion by Δa
    /// (or, if none does, advance the load factor).
    pub fn grow_step(&mut self) -> Result<GrowthStepReport, SolveError> {
        if self.state.outcome.is_some() {
            return Ok(self.state.history.last().cloned().unwrap_or_default());
        }
        let start = Instant::now();
        let lambda = self.increment_load_factor();
        // a state already solved at this load (e.g. the re-solve after the
        // last growth) is not solved again
        let report =
            if self.state.solved && self.scratch.job.is_none() && lambda == self.state.lambda {
                self.report(0.0)
            } else {
                self.state.lambda = lambda;
                self.solve()?
            };
        Ok(self.finish_growth_step(&report, start))
    }

    /// Load factor of the growth loop's current increment.
    fn increment_load_factor(&self) -> f64 {
        self.state.increment as f64 / self.model.scene.growth.load_steps as f64
    }

    /// The same step as [`grow_step`](Self::grow_step), resumable: each call
    /// runs at most `max_iterations` sweeps of the step's solve (see
    /// [`relax`](Self::relax)) and returns `None` until the solve has
    /// converged (the state is then solved and can be shown); the call after
    /// that evaluates the tips, extends them, rebuilds the discretisation
    /// and returns the step's report.
    /// This is how the workbench grows cracks without freezing a frame.
    pub fn advance_growth(
        &mut self,
        max_iterations: usize,
    ) -> Result<Option<GrowthStepReport>, SolveError> {
        if self.state.outcome.is_some() {
            return Ok(self.state.history.last().cloned());
        }
        let start = if let Some(t) = self.scratch.growth_start {
            t
        } else {
            let lambda = self.increment_load_factor();
            if lambda != self.state.lambda || !self.state.solved {
                self.set_load_factor(lambda);
                self.start_relaxation();
            }
            let t = Instant::now();
            self.scratch.growth_start = Some(t);
            t
        };
        if !(self.state.solved && self.scratch.job.is_none()) {
            // the call that converges returns the solved state to the
            // caller (to show it); the next one decides and extends
            self.relax(max_iterations)?;
            return Ok(None);
        }
        self.scratch.growth_start = None;
        let report = self.report(start.elapsed().as_secs_f64());
        Ok(Some(self.finish_growth_step(&report, start)))
    }

    /// After the step's solve: decide, extend the growing tips (or advance
    /// the load), and record the step.
    fn finish_growth_step(&mut self, report: &SolveReport, start: Instant) -> GrowthStepReport {
        let g = &self.model.scene.growth;
        let (load_steps, max_here, max_steps) = (g.load_steps, g.max_growth_per_step, g.max_steps);
        let da = self
            .model
            .scene
            .growth
            .increment
            .unwrap_or(self.criterion_params().r0);
        let growing: Vec<TipReport> = report
            .tips
            .iter()
            .filter(|t| t.criterion.mode != Mode::None)
            .cloned()
            .collect();
        let mut step = GrowthStepReport {
            step: self.state.history.len() + 1,
            load_factor: self.state.lambda,
            grown: Vec::new(),
            contact: counts(&self.state.faces),
            solver_iterations: report.solver.iterations,
            seconds: 0.0,
            tips: report.tips.clone(),
        };
        if growing.is_empty() {
            self.state.increment += 1;
            self.state.growths_here = 0;
            if self.state.increment > load_steps {
                self.state.outcome = Some(Outcome::Completed);
            }
        } else {
            self.state.growths_here += 1;
            step.grown = self.grow_tips(&growing, da);
            if self.state.growths_here >= max_here {
                self.state.outcome = Some(Outcome::Unstable);
            }
        }
        if self.state.outcome.is_none()
            && self.state.cracks.iter().all(|c| c.free_tips().count() == 0)
        {
            let any_boundary = self
                .state
                .cracks
                .iter()
                .any(|c| c.tips.contains(&TipKind::Boundary));
            if !self.state.cracks.is_empty() && any_boundary {
                self.state.outcome = Some(Outcome::Through);
            }
        }
        if self.state.outcome.is_none() && step.step >= max_steps {
            self.state.outcome = Some(Outcome::MaxSteps);
        }
        step.seconds = start.elapsed().as_secs_f64();
        self.state.history.push(step.clone());
        step
    }

    /// Extends the growing tips (all from the same solution) and rebuilds
    /// the discretisation, carrying contact states and displacement over.
    fn grow_tips(&mut self, growing: &[TipReport], da: f64) -> Vec<GrownTip> {
        let m = &self.model.mesh;
        let snap = 0.5 * m.h();
        let mut ext = Vec::new();
        for t in growing {
            let e = extend(
                &self.state.cracks,
                t.crack,
                t.tip,
                t.criterion.angle_deg.to_radians(),
                da,
                m.width,
                m.height,
                snap,
            );
            ext.push((t, e));
        }
        let mut grown = Vec::new();
        let mut moved = Vec::new();
        for (t, e) in ext {
            let p = e.point();
            moved.push(self.state.cracks[t.crack].tip_point(t.tip));
            moved.push(p);
            if (p - self.state.cracks[t.crack].tip_point(t.tip)).norm() > 1e-6 * m.h() {
                apply(&mut self.state.cracks[t.crack], t.tip, p);
            }
            grown.push(GrownTip {
                crack: t.crack,
                tip: t.tip,
                x: p.x,
                y: p.y,
                mode: t.criterion.mode,
                angle_deg: t.criterion.angle_deg,
                k1: t.k1,
                k2: t.k2,
            });
        }
        classify_tips(&mut self.state.cracks, m.width, m.height, 1e-9 * m.h());
        self.rebuild(moved);
        grown
    }

    /// New discretisation for the current cracks (reusing element data away
    /// from the `moved` tips); states and displacement carried over.
    fn rebuild(&mut self, moved: Vec<P2>) {
        let reuse = crate::xfem::Reuse {
            previous: &self.scratch.xfem,
            moved,
        };
        let new = self
            .model
            .rediscretise(self.state.cracks.clone(), Some(&reuse));
        let faces = carry_over(
            &self.scratch.xfem.faces,
            &self.state.faces,
            &new.faces,
            self.model.mesh.h(),
        );
        let mut u = vec![0.0; new.n_free()];
        let old = &self.scratch.xfem.dofs;
        for n in 0..self.model.mesh.node_count() {
            for c in 0..2 {
                let (a, b) = (old.std_free(n, c), new.dofs.std_free(n, c));
                if a != crate::dofs::FIXED && b != crate::dofs::FIXED {
                    u[b as usize] = self.state.u[a as usize];
                }
            }
        }
        self.scratch.f_ext = crate::loads::traction_forces(&new, &self.model.scene.boundary);
        self.scratch.xfem = new;
        self.scratch.job = None;
        self.scratch.solver = crate::solvers::make_solver(&self.model.scene.solver);
        self.state.faces = faces;
        self.state.u = u;
        self.state.solved = false;
        self.state.scene.cracks = self
            .state
            .cracks
            .iter()
            .zip(&self.model.scene.cracks)
            .map(|(c, spec)| crate::scene::CrackSpec {
                points: Some(c.points.iter().map(|p| [p.x, p.y]).collect()),
                arc: None,
                ..spec.clone()
            })
            .collect();
    }

    /// Growth history so far.
    pub fn history(&self) -> &[GrowthStepReport] {
        &self.state.history
    }

    /// Whether growth has ended (through, unstable, max steps, completed).
    pub fn growth_finished(&self) -> Option<Outcome> {
        self.state.outcome
    }

    /// Current crack polylines, m.
    pub fn cracks(&self) -> Vec<Vec<[f64; 2]>> {
        self.state
            .cracks
            .iter()
            .map(|c| c.points.iter().map(|p| [p.x, p.y]).collect())
            .collect()
    }

    /// SIFs and criterion at every free tip after the last solve.
    pub fn tips(&self) -> &[TipReport] {
        &self.scratch.tips
    }

    /// Whether the displacement belongs to the current cracks and load.
    pub fn is_solved(&self) -> bool {
        self.state.solved
    }

    fn field(&self) -> Option<Field<'_>> {
        self.state.solved.then(|| Field {
            xfem: &self.scratch.xfem,
            u: &self.state.u,
        })
    }

    /// σ_xx, σ_yy, τ_xy at a point, Pa (None outside the specimen or before a solve).
    pub fn stress_at(&self, p: [f64; 2]) -> Option<[f64; 3]> {
        let f = self.field()?;
        f.stress_at(P2::new(p[0], p[1]))
    }

    /// Displacement at a point, m.
    pub fn displacement_at(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        let f = self.field()?;
        f.at(P2::new(p[0], p[1])).map(|v| [v.u.x, v.u.y])
    }

    /// Crack-face contact points with their state and tractions.
    pub fn contact_points(&self) -> Vec<ContactPointView> {
        self.scratch
            .xfem
            .faces
            .iter()
            .zip(&self.state.faces)
            .map(|(fp, s)| ContactPointView {
                crack: fp.crack,
                x: fp.x.x,
                y: fp.x.y,
                normal: [fp.n.x, fp.n.y],
                state: s.state,
                p_n: s.p_n,
                p_t: s.p_t,
                slip: s.g_t,
            })
            .collect()
    }

    /// σ_θθ and τ_rθ around tip `index` of `tips()`.
    pub fn criterion_curve(&self, index: usize) -> Option<CriterionCurve> {
        let c = self.scratch.circles.get(index)?;
        let p = self.criterion_params();
        Some(CriterionCurve {
            theta_deg: c.theta.iter().map(|t| t.to_degrees()).collect(),
            sigma_tt: c.sigma_tt.clone(),
            tau_rt: c.tau_rt.clone(),
            sigma_t: p.sigma_t,
            r0: p.r0,
        })
    }
}
