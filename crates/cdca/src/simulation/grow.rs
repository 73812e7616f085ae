//! The growth driver (SPEC §9): load increments, solve, evaluate the free
//! tips, extend those that meet the criterion, rebuild the discretisation
//! locally, and record the history; resumable for the workbench.

use web_time::Instant;

use super::run::Groups;
use super::search::{MAX_TRIALS, Trials};
use super::state::Simulation;
use crate::contact::law::{FaceState, carry_over, counts};
use crate::discretisation::xfem::Reuse;
use crate::error::SolveError;
use crate::fracture::growth::{Extension, apply, default_increment, extend, extend_from};
use crate::fracture::sites::Start;
use crate::fracture::tips::TipDomains;
use crate::geometry::cracks::{Crack, TipKind, classify_tips, split_specimen};
use crate::geometry::plane::{P2, distance_to_segment};
use crate::report::{
    ContactCounts, GrownTip, GrowthStepReport, KinkReport, LinkReport, Mode, NucleatedCrack,
    Outcome, SolveReport, StartedCrack, StepEvents, TipReport, WorkReport,
};
use crate::scene::{CrackSpec, GrowthControl, Lineage, Resume, SolverKind};

/// Quadrature points whose stiffness contributions one
/// [`Simulation::advance_growth`] call sums after a rebuild: about 4 ms
/// natively (an element near a tip holds up to 6 400 points in the default
/// scene's growth).
pub const INTEGRATION_CHUNK: usize = 2_500;

impl Simulation {
    /// One growth step of SPEC §9: solve at the current load increment
    /// (under critical control, at λ_cr), evaluate every free tip, extend
    /// those that meet the criterion by Δa (or, if none does, advance the
    /// load factor). [`advance_growth`](Self::advance_growth) run to the
    /// step's end.
    pub fn grow_step(&mut self) -> Result<GrowthStepReport, SolveError> {
        loop {
            if let Some(step) = self.advance_growth(usize::MAX)? {
                return Ok(step);
            }
        }
    }

    /// Whether the scene asks for critical control (SPEC §9).
    pub(super) fn critical_control(&self) -> bool {
        self.model.scene.growth.control == GrowthControl::Critical
    }

    /// The growth increment Δa, m: `growth.increment`, else
    /// [`default_increment`] of the scene's r0.
    pub(super) fn increment(&self) -> f64 {
        self.model
            .scene
            .growth
            .increment
            .unwrap_or(default_increment(
                self.criterion_params().r0,
                self.model.mesh.h(),
            ))
    }

    /// Load factor of the growth loop's current increment.
    fn increment_load_factor(&self) -> f64 {
        self.state.increment as f64 / self.model.scene.growth.load_steps as f64
    }

    /// One growth step, resumable: in calls of a few milliseconds each when
    /// `max_iterations` is small, so that the workbench grows cracks
    /// without freezing a frame; [`grow_step`](Self::grow_step) is a loop
    /// over it, so the two record the same steps whatever the slicing.
    /// Each call does one of:
    /// - integrate [`INTEGRATION_CHUNK`] quadrature points of the elements
    ///   the last extension changed;
    /// - for the direct solver, the stiffness pattern, then its symbolic
    ///   factorisation (a call each, once per rebuild);
    /// - at most `max_iterations` sweeps of the step's solve, with at most
    ///   one setup (a slice of a factorisation, cells or hierarchy; see
    ///   [`relax`](Self::relax));
    /// - under critical control, the next trial, or λ_cr restored once the
    ///   search has ended ([`at_critical_load`](Self::at_critical_load));
    /// - evaluate the tips, extend them and rebuild the discretisation
    ///   (element stiffness left to later calls), returning the step's
    ///   report.
    ///
    /// It returns `None` until that last call; after a solve the state is
    /// solved and can be shown.
    ///
    /// Growth ends [`Outcome::Through`] at the step whose extension splits
    /// the specimen ([`split_specimen`]: a chain of cracks from boundary to
    /// boundary), free tips left or not: its pieces are then held, if at
    /// all, by their crack faces alone.
    pub fn advance_growth(
        &mut self,
        max_iterations: usize,
    ) -> Result<Option<GrowthStepReport>, SolveError> {
        if self.state.outcome.is_some() {
            return Ok(Some(self.state.history.last().cloned().unwrap_or_default()));
        }
        if !self.prepare_chunk()? {
            return Ok(None);
        }
        if self.critical_control() {
            if self.scratch.critical.is_none() {
                self.begin_critical();
            }
            if !(self.state.solved && self.scratch.job.is_none()) {
                self.relax(max_iterations)?;
                return Ok(None);
            }
            return Ok(self.trial_done());
        }
        let start = if let Some(t) = self.scratch.growth_start {
            t
        } else {
            let lambda = self.increment_load_factor();
            if lambda != self.state.lambda || !self.state.solved {
                self.set_load_factor(lambda);
                // every step starts from what the scene carries
                // (`growth.resume`): no displacement
                self.state.u.fill(0.0);
                self.start_relaxation();
            }
            let t = Instant::now();
            self.scratch.growth_start = Some(t);
            self.scratch.work = WorkReport::default();
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
        let trials = Trials {
            start,
            unsolved: &[],
            cold: &[],
            scaled: &[],
        };
        Ok(Some(self.finish_growth_step(&report, &trials, true)))
    }

    /// One chunk of what a rebuild after growth, or a new simulation, left
    /// to do (see [`rebuild`](Self::rebuild)): the stiffness of
    /// [`INTEGRATION_CHUNK`] quadrature points of the changed elements, or, for the direct solver,
    /// the stiffness pattern or its symbolic factorisation, or one free
    /// tip's interaction-integral domain (read after every solve on this
    /// discretisation: made here, a slice each, not all in the slice that
    /// ends the first solve). Returns whether nothing is left, i.e.
    /// whether a solve can start.
    pub(super) fn prepare_chunk(&mut self) -> Result<bool, SolveError> {
        let clock = Instant::now();
        let done = self.prepare_chunk_untimed();
        self.scratch.work.build_seconds += clock.elapsed().as_secs_f64();
        done
    }

    /// [`prepare_chunk`](Self::prepare_chunk), its time counted there.
    fn prepare_chunk_untimed(&mut self) -> Result<bool, SolveError> {
        let x = &mut self.scratch.xfem;
        if !x.is_integrated() {
            x.integrate(INTEGRATION_CHUNK);
            return Ok(false);
        }
        if self.model.scene.solver.kind == SolverKind::Direct && !x.has_pattern() {
            x.prepare_pattern()?;
            return Ok(false);
        }
        let x = &self.scratch.xfem;
        Ok(!TipDomains::kept_for(&mut self.scratch.tip_domains, x).make_next(x))
    }

    /// After the step's solve: decide, extend the growing tips (or advance
    /// the load), and record the step. A solve that did not converge (or,
    /// `search_closed` false, a λ_cr search that did not close its bracket)
    /// is recorded with `converged: false` and the failed test in words
    /// (`failure`), and ends the growth with
    /// [`Outcome::NotConverged`]: no tip is extended from an untrusted state
    /// (raise `solver.max_iterations` or `solver.max_contact_iterations`).
    ///
    /// Under critical control the solve is the one at λ_cr; a step where no
    /// tip grows is the search reaching `growth.max_load_factor`
    /// ([`Outcome::Completed`]), and growth ends `through` as soon as no
    /// free tip is left.
    pub(super) fn finish_growth_step(
        &mut self,
        report: &SolveReport,
        trials: &Trials,
        search_closed: bool,
    ) -> GrowthStepReport {
        let critical = self.critical_control();
        let g = &self.model.scene.growth;
        let (load_steps, max_here, max_steps) = (g.load_steps, g.max_growth_per_step, g.max_steps);
        let da = self.increment();
        let growing: Vec<TipReport> = report
            .tips
            .iter()
            .filter(|t| t.criterion.mode != Mode::None)
            .cloned()
            .collect();
        let starting: Vec<KinkReport> = report
            .kinks
            .iter()
            .filter(|k| k.mode != Mode::None)
            .cloned()
            .collect();
        // tips and kinks beat the intact rock: a crack starts there only
        // in a step where none of them grows
        let rock = if growing.is_empty() && starting.is_empty() {
            self.rock_start(da)
        } else {
            None
        };
        let nothing = growing.is_empty() && starting.is_empty() && rock.is_none();
        let mut step = GrowthStepReport {
            step: self.steps_done() + 1,
            load_factor: self.state.lambda,
            grown: Vec::new(),
            contact: ContactCounts {
                converged: report.contact.converged,
                iterations: report.contact.iterations,
                residual: report.contact.residual,
                cycling: report.contact.cycling,
                violating: report.contact.violating,
                ..counts(&self.state.faces)
            },
            converged: report.converged() && search_closed,
            failure: if search_closed {
                report.failure()
            } else {
                Some(format!(
                    "the λ_cr search did not close its bracket in {MAX_TRIALS} trials"
                ))
            },
            solver_iterations: report.solver.iterations,
            seconds: 0.0,
            crack_length: 0.0,
            tips: report.tips.clone(),
            intact_rock: self.intact_rock(),
            unsolved_trials: trials.unsolved.to_vec(),
            cold_trials: trials.cold.to_vec(),
            scaled_trials: trials.scaled.to_vec(),
            kinks: report.kinks.clone(),
            rock_site: self.rock_site(),
            ..GrowthStepReport::default()
        };
        if !step.converged {
            self.state.outcome = Some(Outcome::NotConverged);
        } else if critical {
            if nothing {
                self.state.outcome = Some(Outcome::Completed);
            } else {
                self.grow_tips(&growing, &starting, rock, da, &mut step);
            }
        } else if nothing {
            self.state.increment += 1;
            self.state.growths_here = 0;
            if self.state.increment > load_steps {
                self.state.outcome = Some(Outcome::Completed);
            }
        } else {
            self.state.growths_here += 1;
            self.grow_tips(&growing, &starting, rock, da, &mut step);
            if self.state.growths_here >= max_here {
                self.state.outcome = Some(Outcome::Unstable);
            }
        }
        let bound = self.count_rock_starts(&step);
        if !(step.grown.is_empty() && step.started.is_empty() && step.nucleated.is_empty())
            && split_specimen(&self.state.cracks)
        {
            // a chain of cracks from boundary to boundary: the specimen
            // has failed, whether or not contact still holds its pieces
            self.state.outcome = Some(Outcome::Through);
        }
        if self.state.outcome.is_none()
            && self.state.cracks.iter().all(|c| c.free_tips().count() == 0)
        {
            let any_boundary = self
                .state
                .cracks
                .iter()
                .any(|c| c.tips.contains(&TipKind::Boundary));
            if !self.state.cracks.is_empty() && (any_boundary || critical) {
                self.state.outcome = Some(Outcome::Through);
            }
        }
        if let Some(limit) = bound.filter(|_| self.state.outcome.is_none()) {
            self.state.outcome = Some(Outcome::Unstable);
            self.state.start_limit = Some(limit);
        }
        if self.state.outcome.is_none() && step.step >= max_steps {
            self.state.outcome = Some(Outcome::MaxSteps);
        }
        step.crack_length = self.state.cracks.iter().map(Crack::length).sum();
        step.seconds = trials.start.elapsed().as_secs_f64();
        let mut work = std::mem::take(&mut self.scratch.work);
        work.close(step.seconds);
        step.work = work;
        self.state.history.push(step.clone());
        self.state.scene.set_resume(self.resume(step.step));
        step
    }

    /// Where the run stands after `steps` steps, for the simulated scene
    /// ([`Resume`]): the next step starts from exactly this.
    fn resume(&self, steps: usize) -> Resume {
        Resume {
            steps,
            load_factor: self.state.lambda,
            increment: self.state.increment,
            growths_here: self.state.growths_here,
            faces: self.state.faces.iter().map(FaceState::saved).collect(),
            grown: Vec::new(),
            lineage: self.state.lineage.clone(),
            rock_starts: self.rock_strength().map(|_| self.state.rock_starts),
            history: self
                .run_steps()
                .map(|s| StepEvents::of(s).to_json())
                .collect(),
        }
    }

    /// Extends the growing tips and starts a secondary crack at each kink
    /// that meets the criterion (all from the same solution), or starts the
    /// crack `rock` in the intact rock (with its site's utilisation and the
    /// number of sites tied with it), records them and the links they make
    /// in `step`, and rebuilds the discretisation, carrying contact states
    /// and displacement over.
    fn grow_tips(
        &mut self,
        growing: &[TipReport],
        starting: &[KinkReport],
        rock: Option<(Start, f64, usize)>,
        da: f64,
        step: &mut GrowthStepReport,
    ) {
        let m = &self.model.mesh;
        let (snap, width, height) = (m.h(), m.width, m.height);
        let ext: Vec<Extension> = growing
            .iter()
            .map(|t| {
                let angle = t.criterion.angle_deg.to_radians();
                extend(
                    &self.state.cracks,
                    t.crack,
                    t.tip,
                    angle,
                    da,
                    width,
                    height,
                    snap,
                )
            })
            .collect();
        // each secondary crack as a first segment of Δa from its kink
        let first = self.state.cracks.len();
        let branches: Vec<Extension> = starting
            .iter()
            .map(|k| {
                let d = k.direction_deg.to_radians();
                let d = P2::new(d.cos(), d.sin());
                let a = P2::new(k.x, k.y);
                extend_from(&self.state.cracks, None, a, d, da, width, height, snap)
            })
            .collect();
        let mut moved = Vec::new();
        let mut links = Vec::new();
        for (t, e) in growing.iter().zip(ext) {
            let p = e.point();
            moved.push(self.state.cracks[t.crack].tip_point(t.tip));
            moved.push(p);
            if (p - self.state.cracks[t.crack].tip_point(t.tip)).norm() > 1e-6 * snap {
                apply(&mut self.state.cracks[t.crack], t.tip, p);
                let shear = t.criterion.mode == Mode::Shear;
                self.state.lineage[t.crack].grew(t.tip, shear);
            }
            if let Extension::Junction(_, main) = e {
                links.push((t.crack, t.tip, main, p));
            }
            step.grown.push(GrownTip {
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
        for (i, (e, k)) in branches.into_iter().zip(starting).enumerate() {
            let (start, p) = (P2::new(k.x, k.y), e.point());
            moved.extend([start, p]);
            // the faces of the crack it starts on
            let on = &self.state.cracks[k.crack];
            let crack = Crack {
                points: vec![start, p],
                tips: [TipKind::Junction { main: k.crack }, TipKind::Free],
                friction: on.friction,
                cohesion: on.cohesion,
                kn: on.kn,
                kt: on.kt,
            };
            self.state.cracks.push(crack);
            let flaw = self.state.lineage[k.crack].flaw;
            self.state.lineage.push(Lineage::secondary(flaw));
            if let Extension::Junction(_, main) = e {
                links.push((first + i, 1, main, p));
            }
            step.started.push(StartedCrack {
                crack: first + i,
                on: k.crack,
                vertex: k.vertex,
                x: start.x,
                y: start.y,
                tip_x: p.x,
                tip_y: p.y,
                mode: k.mode,
                direction_deg: k.direction_deg,
                off_arm_deg: k.off_arm_deg,
            });
        }
        if let Some((start, utilisation, tied)) = rock {
            let crack = self.state.cracks.len();
            let ends = [-1.0, 1.0].map(|side| {
                extend_from(
                    &self.state.cracks,
                    None,
                    start.point,
                    start.direction * side,
                    start.half_length,
                    width,
                    height,
                    start.snap,
                )
            });
            let (a, b) = (ends[0].point(), ends[1].point());
            moved.extend([a, b]);
            let m = &self.model.scene.material;
            let kn = 100.0 * m.young / snap;
            self.state.cracks.push(Crack {
                points: vec![a, b],
                tips: [TipKind::Free; 2],
                friction: m.friction_angle_deg.to_radians().tan(),
                cohesion: 0.0,
                kn,
                kt: 0.1 * kn,
            });
            self.state.lineage.push(Lineage::intact(crack));
            for (tip, e) in ends.into_iter().enumerate() {
                if let Extension::Junction(p, main) = e {
                    links.push((crack, tip, main, p));
                }
            }
            let d = start.direction;
            // the line's direction in (−90°, 90°]
            let deg = d.y.atan2(d.x).to_degrees();
            let deg = if deg > 90.0 {
                deg - 180.0
            } else if deg <= -90.0 {
                deg + 180.0
            } else {
                deg
            };
            step.nucleated.push(NucleatedCrack {
                crack,
                x: start.point.x,
                y: start.point.y,
                ends: [[a.x, a.y], [b.x, b.y]],
                mode: start.mode,
                direction_deg: deg,
                utilisation,
                tied,
            });
        }
        classify_tips(&mut self.state.cracks, width, height, 1e-9 * snap);
        for (crack, tip, main, p) in links {
            // a crack started in the intact rock may end on two cracks in
            // its step: its second link sees its first
            let earlier = if self.state.lineage[crack].is_intact() {
                step.links.as_slice()
            } else {
                &[]
            };
            let link = self.link(crack, tip, main, p, earlier);
            step.links.push(link);
        }
        self.rebuild(moved);
    }

    /// What the junction of `crack`'s tip `tip` at `p` on `main` joins, and
    /// whether it is the first link between the two flaws (coalescence):
    /// flaws linked by an earlier link of the run (those of earlier steps,
    /// and `earlier` of this one), directly or through others, do not
    /// coalesce again.
    fn link(
        &self,
        crack: usize,
        tip: usize,
        main: usize,
        p: P2,
        earlier: &[LinkReport],
    ) -> LinkReport {
        let lineage = &self.state.lineage;
        let segments = self.state.cracks[crack].points.len() - 1;
        let own = lineage[crack].part_of_segment(if tip == 0 { 0 } else { segments - 1 });
        let hit = nearest_segment(&self.state.cracks[main], p);
        let flaws = [lineage[crack].flaw, lineage[main].flaw];
        let before = self.run_steps().flat_map(|s| &s.links);
        let mut groups = Groups::linked(lineage, before.chain(earlier));
        LinkReport {
            crack,
            tip,
            main,
            joins: [own, lineage[main].part_of_segment(hit)],
            flaws,
            coalescence: groups.coalesce(flaws).is_some(),
        }
    }

    /// New discretisation for the current cracks (reusing element data away
    /// from the `moved` tips); states and displacement carried over. The
    /// stiffness of the elements that changed is integrated later, by
    /// [`advance_growth`](Self::advance_growth) in chunks or at once by the
    /// next solve.
    fn rebuild(&mut self, moved: Vec<P2>) {
        let reuse = Reuse {
            previous: &self.scratch.xfem,
            moved,
            redrawn: Vec::new(),
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
        self.scratch.f_ext =
            crate::discretisation::loads::traction_forces(&new, &self.model.scene.boundary);
        self.scratch.rebuild_points = new.points_to_integrate();
        self.scratch.xfem = new;
        self.scratch.job = None;
        // the solver stays (a direct one refactorises into its factors'
        // storage): with `factored` unknown, its next matrix is a new one
        self.scratch.factored = None;
        self.scratch.site_grid = None;
        self.scratch.rock = None;
        self.state.faces = faces;
        // the next step starts from no displacement (see `Resume`)
        self.state.u = vec![0.0; self.scratch.xfem.n_free()];
        self.state.solved = false;
        // a secondary crack has the faces of the crack system it belongs
        // to; a crack started in the intact rock the rock's friction
        let specs = &self.state.scene.cracks;
        let rock = CrackSpec {
            friction: self
                .model
                .scene
                .material
                .friction_angle_deg
                .to_radians()
                .tan(),
            ..CrackSpec::segment([0.0; 2], [0.0; 2])
        };
        let grown = self
            .state
            .cracks
            .iter()
            .zip(&self.state.lineage)
            .enumerate()
            .map(|(i, (c, l))| CrackSpec {
                points: Some(c.points.iter().map(|p| [p.x, p.y]).collect()),
                arc: None,
                ..specs
                    .get(i)
                    .or_else(|| (!l.is_intact()).then(|| &specs[l.flaw]))
                    .unwrap_or(&rock)
                    .clone()
            })
            .collect();
        self.state.scene.set_grown_cracks(grown);
    }

    /// After growth has ended: the final cracks at the last step's load
    /// factor (λ_cr under critical control), set up to be solved by the
    /// next [`relax`](Self::relax) calls or [`solve`](Self::solve), so that
    /// the state shown at the end is the final geometry at the load the
    /// history prints. Returns that load factor, or `None` when growth has
    /// not ended or no step was recorded. A specimen cut in two has no
    /// stiffness against the rigid motion of a piece: its solve then fails
    /// with [`SolveError::NotPositiveDefinite`].
    pub fn start_final_solve(&mut self) -> Option<f64> {
        self.state.outcome?;
        let lambda = self.state.history.last()?.load_factor;
        self.state.lambda = lambda;
        self.state.solved = false;
        self.state.u.fill(0.0);
        self.scratch.critical = None;
        self.start_relaxation();
        Some(lambda)
    }

    /// Growth history so far: the steps of this simulation (a scene that
    /// resumes a run, `growth.resume`, starts with none).
    pub fn history(&self) -> &[GrowthStepReport] {
        &self.state.history
    }

    /// The steps of the run this scene resumes (`growth.resume.history`:
    /// each step's load factor and events only), before
    /// [`history`](Self::history).
    pub fn earlier(&self) -> &[GrowthStepReport] {
        &self.state.earlier
    }

    /// Every step of the run: [`earlier`](Self::earlier), then
    /// [`history`](Self::history).
    pub(super) fn run_steps(&self) -> impl Iterator<Item = &GrowthStepReport> {
        self.state.earlier.iter().chain(&self.state.history)
    }

    /// Growth steps done, those of the run this scene resumes included
    /// (`growth.resume.steps` + [`history`](Self::history)): the `step`
    /// number of the last report, 0 before any.
    pub fn steps_done(&self) -> usize {
        self.state.steps_before + self.state.history.len()
    }

    /// Whether the step in progress has solved at the load it records and
    /// its tips have not moved yet: under critical control the solve at
    /// λ_cr ([`at_critical_load`](Self::at_critical_load)), under load
    /// control the solve at the increment's load factor. The state can be
    /// shown; the next [`advance_growth`](Self::advance_growth) call
    /// decides and extends the tips.
    pub fn at_step_load(&self) -> bool {
        if self.critical_control() {
            self.at_critical_load()
        } else {
            self.scratch.growth_start.is_some() && self.state.solved && self.scratch.job.is_none()
        }
    }

    /// Whether growth has ended (through, unstable, max steps, completed).
    pub fn growth_finished(&self) -> Option<Outcome> {
        self.state.outcome
    }

    /// What each crack's parts are (flaw, wing, secondary).
    pub fn lineage(&self) -> &[Lineage] {
        &self.state.lineage
    }

    /// Current crack polylines, m.
    pub fn cracks(&self) -> Vec<Vec<[f64; 2]>> {
        self.state
            .cracks
            .iter()
            .map(|c| c.points.iter().map(|p| [p.x, p.y]).collect())
            .collect()
    }
}

/// Index of the segment of `crack` nearest to `p`.
fn nearest_segment(crack: &Crack, p: P2) -> usize {
    crack
        .segments()
        .map(|(a, b)| distance_to_segment(p, a, b))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0, |(j, _)| j)
}
