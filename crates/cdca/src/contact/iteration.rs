//! The contact iteration (SPEC §5). Where the linear solver keeps a factor
//! (the direct solver), semismooth Newton steps
//! ([`newton`](crate::contact::newton)): solve the system of the current
//! states, correct it to the Newton solution of the law linearised there,
//! map every point's state at it, until the law holds (11 contact
//! iterations where the fixed point below took 50, on 39 closed cracks).
//! Otherwise (CG, the automaton, and where the Newton steps' states cycle)
//! a damped fixed-point (active-set) loop: solve the linear system of the
//! current states, update every face point's state by the return mapping,
//! repeat until no state changes and the displacement settles. Friction
//! limits are held fixed in an inner (Tresca) problem and updated in an
//! outer loop; cycling points are damped by a line search and counted, so
//! the loop always ends with an explicit status. Resumable
//! ([`ContactSolve`]); the blocking calls loop over it. Its settings, cycling guard and bookkeeping are in
//! [`status`](crate::contact::status) (the in-sweep rule shares them), the
//! law over every face point in [`points`](crate::contact::points).

use crate::contact::law::{ContactState, FaceState, contact_system_split, gaps};
use crate::contact::limit_mix::LimitMix;
use crate::contact::limit_newton::newton_limits;
use crate::contact::newton::{
    KRYLOV_TOLERANCE, LOOSE_KRYLOV_TOLERANCE, cohesive, law_force, newton_step, norm,
};
use crate::contact::points::{
    coulomb_limits, coulomb_states, initial_limits, matrix_kinds, tresca_point, update_limited,
};
use crate::contact::status::{ContactInfo, ContactParams, FlipTracker, Reached, relative_change};
use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::solvers::linear::LinearSolver;
use crate::solvers::relaxation::{RelaxStatus, ResidualSample};
use std::hash::{Hash, Hasher};

use web_time::Instant;

/// The contact iteration as a resumable state machine: each
/// [`advance`](Self::advance) call runs a slice of the current linear
/// solve's iterations, after its setup (a factorisation, cells or a
/// multigrid hierarchy) if it starts one, and ends when a linear solve
/// ends, so that a call sets up at most one. The contact states are updated only
/// when a linear solve has finished, so the result does not depend on how
/// the caller slices the work: [`solve_with_contact_from`] is a loop over
/// `advance` with no limit, and the workbench calls it a few sweeps a frame.
///
/// One contact iteration: assemble the contact system of the current
/// states (`k_N n⊗n` at closed points, `+ k_T t⊗t` at stick, the friction
/// force `±τ_y` of slip points), solve it, map every point's state at the
/// solution; at most `max_iterations` times. With a factor (the direct
/// solver), an iteration that changes a state is solved on the faces'
/// rows only (`Self::state_change_on_the_faces`).
///
/// Friction is solved by an outer loop over the friction limits `τ_y`
/// (with the default penalty `k_N = 100 E/h`, friction taken from the last
/// iterate let whole flaws slide back and forth, and groups of points
/// switch state without end):
/// - the inner problem holds each point's `τ_y` fixed (Tresca friction,
///   `tresca_point`): its potential is convex, and when a state (or slip
///   direction, or closure) changed the step from the iterate `u₀` is
///   damped, `u ← u₀ + β (g − u₀)` with `β ∈ (0, 1]` where the law's
///   residual has no component along it (a step cut below
///   [`STALLED_STEP`] is taken whole: the same states would give it
///   again). The inner problem is solved when no state changes: its
///   system is then exact;
/// - the outer loop then sets `τ_y ← μ|p_N| + c_c` from that solution
///   (zero where open), Anderson-mixed over the last few limit vectors
///   ([`LimitMix::next`]: restarted from the plain step when the mix would
///   take a limit that step raises below zero), until the Coulomb return
///   mapping at the solution gives
///   the same states and the limits or the solution settle
///   (`‖Δτ‖ ≤ tolerance ‖τ‖` or `‖Δu‖ ≤ tolerance ‖u‖` between inner
///   solutions). The limits start from the initial states.
///
/// The operator is symmetric positive definite throughout, and the tests
/// are taken on `g`, the solution of the last system: the iteration ends
/// converged only with `u = g` and every point in its Coulomb state.
pub struct ContactSolve {
    params: ContactParams,
    /// The load `λ f_ext` (without contact forces).
    load: Vec<f64>,
    /// States, status and residual samples (those of the finished contact
    /// iterations, then those of the current one, with cumulative
    /// iterations and times).
    reached: Reached,
    /// The current contact iteration's system, once assembled.
    system: Option<System>,
    /// Displacement at the start of the current contact iteration.
    before: Vec<f64>,
    done_iterations: usize,
    done_seconds: f64,
    /// `K u − λ f_ext` (bulk only) at the current iterate, once a linear
    /// solve has given it.
    bulk_residual: Option<Vec<f64>>,
    /// The friction limits `τ_y` per face point that the inner problem
    /// holds fixed (set from the initial states when the first system is
    /// built).
    limits: Option<Vec<f64>>,
    /// Anderson mix of the limits' fixed-point map `τ ↦ μ|p_N(g(τ))| + c_c`.
    limit_mix: LimitMix,
    /// The solution of the last inner problem (for the outer change).
    inner_solution: Option<Vec<f64>>,
    /// The last outer step was Newton's ([`newton_limits`]).
    after_newton: bool,
    /// The DOFs the face points' gaps read, once needed
    /// ([`Self::state_change_on_the_faces`]).
    face_dofs: Option<Vec<usize>>,
    /// Newton steps after which some point was not in its Coulomb state:
    /// at [`NEWTON_MISSES`] the limits are mixed for the rest of the solve.
    newton_misses: u32,
    /// The iteration takes semismooth Newton steps ([`newton_step`]): the
    /// solver keeps a factor, and the steps have not cycled.
    newton: bool,
    /// The states each Newton step mapped to (hashed
    /// [`newton_signature`]s), to see a cycle.
    newton_seen: Vec<u64>,
    /// The states and displacement the iteration started from: where the
    /// damped fixed point starts if the Newton steps cycle.
    start: (Vec<FaceState>, Vec<f64>),
    /// The Newton steps have converged on the faces: the states found,
    /// while the whole solution is solved.
    finishing: Option<Vec<FaceState>>,
    /// The last Newton iteration's states were those of an earlier one.
    newton_cycled: bool,
}

/// Newton steps to the friction limits that may miss (some point then
/// leaves its state) before the outer loop goes back to the Anderson mix
/// for the rest of a contact solve. On a 20 × 20 mesh with μ = 5 on cracks
/// along element edges (a fuzzed scene), Newton's steps flipped the same
/// points between stick and slip in a cycle of four iterations until the
/// cap, where the mix converges in 18; after two misses the mix takes
/// over there, and growth runs, where a Newton step is seldom missed, are
/// unchanged.
pub const NEWTON_MISSES: u32 = 2;

/// Newton steps after which, unconverged, the damped fixed point takes
/// over (as it does at once where the steps' states repeat).
pub const MAX_NEWTON_STEPS: usize = 20;

/// A line-search step below this fraction is taken whole (the same
/// states would give the same step again: a stall).
pub const STALLED_STEP: f64 = 0.01;

/// Each point's state, whether it slips forwards and whether it is
/// closed: the inner problem's system (matrix and forces) is fixed by
/// this and the limits.
fn signature(states: &[FaceState]) -> Vec<(ContactState, bool, bool)> {
    states
        .iter()
        .map(|s| {
            (
                s.state,
                s.state == ContactState::Slip && s.p_t > 0.0,
                s.g_n < 0.0,
            )
        })
        .collect()
}

/// The [`signature`] and, per point, whether its friction limit is on
/// the cohesion's rising branch: the law the Newton step linearises.
fn newton_signature(x: &Xfem, states: &[FaceState]) -> Vec<(ContactState, bool, bool)> {
    signature(states)
        .into_iter()
        .enumerate()
        .map(|(i, (state, forward, closed))| {
            let rising = cohesive(x, i, states[i].g_n);
            (state, forward, closed && !rising)
        })
        .collect()
}

/// The states the next Newton step linearises at: those the Coulomb law
/// gives at its solution (`mapped`), but stuck where a point's slip turned
/// round (from `was`): the step that took it slipping one way maps it
/// slipping the other, and the step from there back (a cycle of the active
/// sets, seen on late steps of the held-out pairs); stuck, it slips on
/// only if its traction then exceeds the limit.
fn next_active_set(
    x: &Xfem,
    was: &[FaceState],
    mut mapped: Vec<FaceState>,
    committed: &[FaceState],
) -> Vec<FaceState> {
    for (i, (s, old)) in mapped.iter_mut().zip(was).enumerate() {
        let turned = s.state == ContactState::Slip
            && old.state == ContactState::Slip
            && s.p_t * old.p_t < 0.0;
        if turned && s.g_n < 0.0 {
            let crack = &x.funcs.cracks[x.faces[i].crack];
            s.state = ContactState::Stick;
            s.slip = committed[i].slip;
            s.p_t = crack.kt * (s.g_t - s.slip);
        }
    }
    mapped
}

/// `‖r‖/‖f‖` (or `‖r‖` when f = 0): a force relative to the load.
fn relative_to(r: &[f64], f: &[f64]) -> f64 {
    let scale = norm(f);
    if scale > 0.0 {
        norm(r) / scale
    } else {
        norm(r)
    }
}

/// Points whose [`signature`] entries differ.
fn differ(a: &[(ContactState, bool, bool)], b: &[(ContactState, bool, bool)]) -> usize {
    a.iter().zip(b).filter(|(p, q)| p != q).count()
}

/// The states of a contact iteration that converged at one load, carried
/// to the same scene at `s` times that load, with `u` already scaled by `s`:
/// the Coulomb states at `u` when every point keeps its [`signature`],
/// else `None`.
///
/// Without face cohesion the law is positively homogeneous: a point is
/// open where `g_N ≥ 0`, sticks while `k_T |g_T − g_T^s| ≤ μ k_N |g_N|`
/// (with no slip committed), and a tie is a relative width
/// ([`TIE`](crate::contact::law::TIE)). Every load is `λ f_ext` and every
/// support holds at zero, so `s u` solves the scene at `s λ` with the same
/// states, limits `s τ_y` and relative residuals. The check against the
/// signature is what makes that a test rather than an assumption.
pub(crate) fn states_at_scaled_load(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    solved: &[FaceState],
) -> Option<Vec<FaceState>> {
    let homogeneous =
        x.funcs.cracks.iter().all(|c| c.cohesion == 0.0) && committed.iter().all(|c| c.slip == 0.0);
    if !homogeneous || committed.len() != solved.len() {
        return None;
    }
    let states = coulomb_states(x, u, committed, solved);
    (differ(&signature(&states), &signature(solved)) == 0).then_some(states)
}

/// The linear system of one contact iteration.
struct System {
    blocks: Vec<ElementBlock>,
    /// The contact forces on the right-hand side.
    force: Vec<f64>,
    /// Samples of this solve already copied to the history.
    copied: usize,
    /// The [`signature`] of the states it was built with.
    signature: Vec<(ContactState, bool, bool)>,
}

impl ContactSolve {
    /// A contact iteration on the load `load` (= λ f_ext), started from the
    /// states `initial` (a guess of which points are open, stuck or
    /// slipping; the slip history is the `committed` states passed to
    /// [`advance`](Self::advance)).
    pub fn new(load: Vec<f64>, initial: Vec<FaceState>, params: ContactParams) -> Self {
        Self {
            start: (initial.clone(), Vec::new()),
            finishing: None,
            newton_cycled: false,
            params,
            load,
            reached: Reached::new(initial),
            system: None,
            before: Vec::new(),
            done_iterations: 0,
            done_seconds: 0.0,
            bulk_residual: None,
            limits: None,
            limit_mix: LimitMix::default(),
            inner_solution: None,
            after_newton: false,
            face_dofs: None,
            newton_misses: 0,
            newton: false,
            newton_seen: Vec::new(),
        }
    }

    /// Advances the iteration by at most `max_iterations` linear iterations
    /// (at least one), setting the next linear solve up first if it starts
    /// one; a call that ends a linear solve updates the contact states and
    /// returns.
    ///
    /// `committed` holds the slip history of the last converged step; `u`
    /// is the current iterate (the starting guess, then the latest
    /// iterate, then the result). `factored` holds the contact states
    /// (open, stick, slip per point) that `solver`'s current matrix was
    /// built with on this discretisation, or `None` when it has none or
    /// they are unknown; it is kept up to date. The matrix `K + k_N n⊗n
    /// (+ k_T t⊗t)` depends on nothing else (not on the load), so a solve
    /// whose states match it is not set up again: the λ_cr search's trials
    /// mostly start with the states the last trial ended with (of 231
    /// factorisations in a 40-step growth run, 123 were these).
    ///
    /// Returns the progress; `finished` once the iteration has ended, with
    /// [`reached`](Self::reached)`.info` saying how.
    pub fn advance(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        factored: &mut Option<Vec<ContactState>>,
        u: &mut Vec<f64>,
        solver: &mut dyn LinearSolver,
        max_iterations: usize,
    ) -> Result<RelaxStatus, SolveError> {
        if self.reached.ended(committed) {
            return Ok(self.status(true));
        }
        if self.system.is_none() {
            self.set_up(x, committed, factored, u, solver)?;
            if solver.factorising() {
                // a factorisation runs in calls of its own (frame slices in
                // the workbench): the solve follows it
                return Ok(self.waiting());
            }
            return self.advance(x, committed, factored, u, solver, max_iterations);
        }
        if self.newton && self.finishing.is_none() {
            if solver.factorising() {
                // the factorisation in slices of its own, as `run` makes it
                solver.factorise_next()?;
                return Ok(self.waiting());
            }
            if let Some(status) = self.newton_on_faces(x, committed, u, solver)? {
                return Ok(status);
            }
            if self.system.is_none() {
                return self.advance(x, committed, factored, u, solver, max_iterations);
            }
        }
        if let Some(status) = self.state_change_on_the_faces(x, committed, u, solver)? {
            return Ok(status);
        }
        let system = self.system.as_mut().expect("set up above");
        let status = solver.run(x, &system.blocks, max_iterations.max(1))?;
        u.clear();
        u.extend_from_slice(solver.u());
        // later contact iterations do not repeat the iteration-0 sample
        let later = self.done_iterations > 0;
        let samples = solver.samples();
        self.reached.history.extend(
            samples[system.copied.min(samples.len())..]
                .iter()
                .filter(|s| !(later && s.iteration == 0))
                .map(|s| ResidualSample {
                    iteration: s.iteration + self.done_iterations,
                    seconds: s.seconds + self.done_seconds,
                    residual: s.residual,
                }),
        );
        system.copied = samples.len();
        if !status.finished {
            if status.iterations == 0 {
                // the linear solver is still setting up (a factorisation)
                return Ok(self.waiting());
            }
            return Ok(RelaxStatus {
                iterations: self.done_iterations + status.iterations,
                residual: status.residual,
                converged: false,
                finished: false,
            });
        }
        // the linear solve has ended: one contact iteration
        let lin = solver.info();
        self.done_iterations += lin.iterations;
        self.done_seconds += samples.last().map_or(0.0, |s| s.seconds);
        self.reached.info.linear_iterations += lin.iterations;
        let linear_converged = lin.converged;
        self.reached.info.last = lin;
        match self.system.take() {
            Some(system) => {
                self.end_contact_iteration(x, committed, u, &system, linear_converged, &*solver)
            }
            None => Ok(self.status(self.reached.finished)),
        }
    }

    /// A contact iteration whose solve changes some point's state needs
    /// the solution only on the faces' DOFs: its damped step and the
    /// states mapped there read nothing else, and the next iteration
    /// solves its own system anew. So the solve is first taken on the rows
    /// those DOFs need ([`LinearSolver::solve_reaching`]: the load's
    /// forward solve kept per factor, the contact forces' on the part of
    /// the factor they reach, the backward solve on the faces' part; the
    /// whole solve's values there to round-off). Where a state changes,
    /// the iteration ends on it (every other DOF keeps the last iterate's
    /// value, so the change it reports is that of the faces' part), with
    /// no whole solve and no residual check. Where none
    /// changes, `None`: the outer step needs the whole solution, and the
    /// linear solve completes the one begun. Never in the last iteration
    /// allowed, so an iteration that ends the solve always has the whole
    /// solution, with its residual checked.
    fn state_change_on_the_faces(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut Vec<f64>,
        solver: &mut dyn LinearSolver,
    ) -> Result<Option<RelaxStatus>, SolveError> {
        let last = self.reached.info.iterations + 1 >= self.params.max_contact_iterations();
        let Some(system) = self.system.as_ref().filter(|s| s.copied == 0) else {
            return Ok(None);
        };
        if last || solver.factorising() || self.newton {
            return Ok(None);
        }
        let clock = Instant::now();
        let dofs = self.face_dofs.get_or_insert_with(|| face_dofs(x));
        let Some(g) = solver.solve_reaching(&self.load, dofs, u) else {
            return Ok(None);
        };
        let limits = self.limits.clone().unwrap_or_default();
        let mut states = self.reached.states.clone();
        let changed = update_limited(
            x,
            &g,
            committed,
            &mut states,
            &limits,
            &mut self.reached.tracker.clone(),
            self.params.max_flips,
        );
        if changed == 0 && differ(&signature(&states), &system.signature) == 0 {
            return Ok(None);
        }
        *u = g;
        self.done_iterations += 1;
        self.done_seconds += clock.elapsed().as_secs_f64();
        self.reached.info.linear_iterations += 1;
        self.reached.info.face_solves += 1;
        let system = self.system.take().expect("checked above");
        self.end_contact_iteration(x, committed, u, &system, true, &*solver)
            .map(Some)
    }

    /// The progress while a linear solve is set up: the last contact
    /// iteration's residual (1 before the first).
    fn waiting(&self) -> RelaxStatus {
        RelaxStatus {
            residual: if self.done_iterations == 0 {
                1.0
            } else {
                self.reached.info.last.residual
            },
            ..self.status(false)
        }
    }

    /// Assembles the contact system of the current states (and the
    /// friction limits, at the first one) and sets the linear solve up,
    /// refactorising only when the matrix changed (see [`Self::advance`]).
    fn set_up(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        factored: &mut Option<Vec<ContactState>>,
        u: &[f64],
        solver: &mut dyn LinearSolver,
    ) -> Result<(), SolveError> {
        if self.limits.is_none() {
            self.limits = Some(initial_limits(x, &self.reached.states));
            self.newton = self.params.newton && solver.keeps_factor();
            if self.newton {
                self.start.1 = u.to_vec();
            }
        }
        let mut f = self.load.clone();
        let blocks =
            contact_system_split(x, &self.reached.states, committed, |s| s.g_n < 0.0, &mut f);
        let kinds = matrix_kinds(&self.reached.states);
        let matrix_changed = kinds.is_none() || *factored != kinds;
        // unknown until the setup below has succeeded
        *factored = None;
        self.before.clear();
        self.before.extend_from_slice(u);
        solver.start(x, &blocks, &f, u, matrix_changed)?;
        *factored = kinds;
        for (a, b) in f.iter_mut().zip(&self.load) {
            *a -= b;
        }
        self.system = Some(System {
            blocks,
            force: f,
            copied: 0,
            signature: signature(&self.reached.states),
        });
        Ok(())
    }

    /// A contact iteration's linear solve `g` (in `u`) has ended: maps the
    /// states by the inner law; if none changed, takes the outer step
    /// ([`Self::outer_step`]), else damps the step from the last iterate
    /// ([`Self::damped_step`]); then says whether the iteration has ended
    /// and how.
    fn end_contact_iteration(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut Vec<f64>,
        system: &System,
        linear_converged: bool,
        solver: &dyn LinearSolver,
    ) -> Result<RelaxStatus, SolveError> {
        if let Some(states) = self.finishing.take() {
            // the whole solution of the Newton steps' last system
            self.reached.states = states;
            self.reached.info.converged = linear_converged;
            self.reached.finished = true;
            return Ok(self.status(true));
        }
        if self.newton {
            return self.newton_whole(x, committed, u, linear_converged);
        }
        let it = self.reached.info.iterations + 1;
        // the tests are taken on g = u, the solution of the system
        let solved = bulk_residual(x, system, u);
        let limits = self.limits.clone().unwrap_or_default();
        let more = linear_converged && it < self.params.max_contact_iterations();
        let mut states = self.reached.states.clone();
        let changed = update_limited(
            x,
            u,
            committed,
            &mut states,
            &limits,
            &mut self.reached.tracker,
            self.params.max_flips,
        );
        let sig = signature(&states);
        let unsettled = if changed > 0 {
            changed
        } else {
            differ(&sig, &system.signature)
        };
        if std::mem::take(&mut self.after_newton) && unsettled > 0 {
            self.newton_misses += 1;
        }
        let (residual, unsettled, settled) = if unsettled == 0 {
            self.outer_step(
                x,
                committed,
                u,
                &mut states,
                &sig,
                &limits,
                more,
                solved,
                solver,
            )
        } else {
            let change = relative_change(u, &self.before);
            self.damped_step(x, committed, u, &mut states, &limits, more, solved);
            (change, unsettled, false)
        };
        self.reached.states = states;
        self.reached.info.iterations = it;
        self.reached.info.residual = residual;
        self.reached.info.unsettled = unsettled;
        if !residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("contact iteration {it}"),
            });
        }
        // an unconverged linear solve ends the iteration: states updated
        // from it mean little, and the status says so
        if !linear_converged {
            self.reached.finished = true;
        } else if settled {
            self.reached.info.converged = true;
            self.reached.finished = true;
        } else if it >= self.params.max_contact_iterations() {
            self.reached.info.capped = true;
            self.reached.info.cycling = self.reached.tracker.frozen();
            self.reached.finished = true;
        }
        Ok(self.status(self.reached.finished))
    }

    /// A contact iteration of the semismooth Newton method
    /// ([`newton`](crate::contact::newton)), on the faces' DOFs: the
    /// solution `g` of the system of the current states there, corrected
    /// to the Newton solution of the law linearised at them, and the states
    /// the Coulomb law gives at it. Converged when the law holds there to
    /// the contact tolerance ([`law_force`]): the system is then solved
    /// whole once more with the Newton step's forces (`Some(None)`: the
    /// caller goes on to that solve), and those states are the result.
    /// Otherwise the iteration ends with them (`Some(status)`), and the
    /// next one builds their system; where their states cycle, or the slip
    /// system was not solved, the damped fixed point takes over
    /// ([`fall_back`](Self::fall_back)). `None` also where no point slips:
    /// the system is then solved whole ([`newton_whole`](Self::newton_whole)).
    fn newton_on_faces(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut Vec<f64>,
        solver: &mut dyn LinearSolver,
    ) -> Result<Option<RelaxStatus>, SolveError> {
        let clock = Instant::now();
        let it = self.reached.info.iterations + 1;
        let Some(system) = self.system.as_ref() else {
            return Ok(None);
        };
        if !self
            .reached
            .states
            .iter()
            .any(|s| s.state == ContactState::Slip)
        {
            // the Newton step is the system's solution: solved whole
            // ([`newton_whole`](Self::newton_whole))
            return Ok(None);
        }
        let faces = self.face_dofs.get_or_insert_with(|| face_dofs(x)).clone();
        let whole: Vec<f64> = self
            .load
            .iter()
            .zip(&system.force)
            .map(|(a, b)| a + b)
            .collect();
        let Some(g) = solver
            .solve_reaching(&self.load, &faces, u)
            .or_else(|| solver.solve_again(&whole))
        else {
            return Ok(Some(self.fall_back(x, u)));
        };
        let relative = |r: &[f64]| relative_to(r, &self.load);
        // a step taken while many states change, or from the states the
        // iteration started with (open faces or a guess), is solved
        // loosely; one that leaves them holding is taken on to the tight
        // tolerance, from the loose solve's Krylov space
        let changing = self.reached.info.unsettled > 2 || it == 1;
        let tolerance = if changing {
            LOOSE_KRYLOV_TOLERANCE
        } else {
            KRYLOV_TOLERANCE
        };
        let mut krylov = None;
        let states_now = &self.reached.states;
        let mut take = |tolerance: f64| {
            newton_step(x, states_now, &g, &faces, &*solver, tolerance, &mut krylov).map(|step| {
                let mapped = coulomb_states(x, &step.u, committed, states_now);
                let force = law_force(x, states_now, &mapped, committed);
                (step, mapped, force)
            })
        };
        let mut taken = take(tolerance);
        if let Some((loose, _, force)) = &taken
            && loose.residual > KRYLOV_TOLERANCE
            && relative(force) <= self.params.tolerance
        {
            let solves = loose.solves;
            taken = take(KRYLOV_TOLERANCE).map(|(mut step, mapped, force)| {
                step.solves += solves;
                (step, mapped, force)
            });
        }
        let Some((step, states, force)) = taken else {
            return Ok(Some(self.fall_back(x, u)));
        };
        self.done_iterations += step.solves + 1;
        self.reached.info.linear_iterations += step.solves + 1;
        self.reached.info.face_solves += 1;
        self.done_seconds += clock.elapsed().as_secs_f64();
        let converged = self.newton_end(x, &states, relative(&force), step.residual)?;
        if converged {
            // the whole solution: the system's solve with the step's forces
            let system = self.system.as_ref().expect("checked above");
            let mut f = whole;
            for &(d, a) in &step.correction {
                f[d] += a;
            }
            solver.start(x, &system.blocks, &f, u, false)?;
            self.finishing = Some(states);
            return Ok(None);
        }
        Ok(Some(self.newton_next(
            x,
            committed,
            states,
            u,
            Some(step.u),
        )))
    }

    /// A Newton iteration whose states hold no slipping point: the
    /// system's whole solution `g` (in `u`) is the Newton step's, its
    /// states those the Coulomb law gives at it (as
    /// [`newton_on_faces`](Self::newton_on_faces) decides).
    fn newton_whole(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut Vec<f64>,
        linear_converged: bool,
    ) -> Result<RelaxStatus, SolveError> {
        let states = coulomb_states(x, u, committed, &self.reached.states);
        let force = law_force(x, &self.reached.states, &states, committed);
        let law = relative_to(&force, &self.load);
        if self.newton_end(x, &states, law, 0.0)? || !linear_converged {
            self.reached.states = states;
            self.reached.info.converged = linear_converged;
            self.reached.finished = true;
            return Ok(self.status(true));
        }
        Ok(self.newton_next(x, committed, states, u, None))
    }

    /// The bookkeeping of a Newton iteration that mapped the states
    /// `states` at its solution, where the law's relative residual is
    /// `law` and the slip system's `krylov`: counts it, tracks the states'
    /// changes and cycles, and says whether it has converged (the law holds
    /// to the contact tolerance, with the states it gives there: a point
    /// whose state changed without its traction changing leaves no
    /// residual; the step solved tightly).
    fn newton_end(
        &mut self,
        x: &Xfem,
        states: &[FaceState],
        law: f64,
        krylov: f64,
    ) -> Result<bool, SolveError> {
        let it = self.reached.info.iterations + 1;
        self.reached.info.iterations = it;
        if !law.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("contact iteration {it}"),
            });
        }
        let signature = newton_signature(x, states);
        let unsettled = differ(&signature, &newton_signature(x, &self.reached.states));
        let key = {
            let mut h = std::hash::DefaultHasher::new();
            signature.hash(&mut h);
            h.finish()
        };
        self.newton_cycled = unsettled > 0 && self.newton_seen.contains(&key);
        self.newton_seen.push(key);
        let converged = law <= self.params.tolerance && krylov <= KRYLOV_TOLERANCE;
        for (i, (a, b)) in states.iter().zip(&self.reached.states).enumerate() {
            if a.state != b.state {
                self.reached.tracker.flip(i, self.params.max_flips);
            }
        }
        self.reached.info.residual = law.max(krylov);
        self.reached.info.unsettled = if converged { 0 } else { unsettled };
        Ok(converged)
    }

    /// An unconverged Newton iteration ends: the next one linearises at
    /// `states` ([`next_active_set`]) from the iterate `u` (`iterate` in
    /// it where given: exact on the faces' DOFs), unless the cap is
    /// reached, or the states cycle (the damped fixed point then takes
    /// over: Newton's method has no global convergence here).
    fn newton_next(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        states: Vec<FaceState>,
        u: &mut Vec<f64>,
        iterate: Option<Vec<f64>>,
    ) -> RelaxStatus {
        self.reached.states = next_active_set(x, &self.reached.states, states, committed);
        self.system = None;
        if let Some(v) = iterate {
            *u = v;
        }
        if self.reached.info.iterations >= self.params.max_contact_iterations() {
            self.reached.info.capped = true;
            self.reached.info.cycling = self.reached.tracker.frozen();
            self.reached.finished = true;
        } else if self.newton_cycled || self.newton_seen.len() >= MAX_NEWTON_STEPS {
            return self.fall_back(x, u);
        }
        self.status(self.reached.finished)
    }

    /// The damped fixed point takes over, from the states and displacement
    /// the iteration started from: the solve it would have made without
    /// the Newton steps, which then count among its iterations.
    fn fall_back(&mut self, x: &Xfem, u: &mut Vec<f64>) -> RelaxStatus {
        self.newton = false;
        self.system = None;
        self.reached.info.newton_fallback = true;
        self.reached.states.clone_from(&self.start.0);
        self.reached.tracker = FlipTracker::new(self.start.0.len());
        self.reached.info.unsettled = 0;
        u.clone_from(&self.start.1);
        self.limits = Some(initial_limits(x, &self.reached.states));
        self.limit_mix = LimitMix::default();
        self.inner_solution = None;
        self.bulk_residual = None;
        self.status(false)
    }

    /// No state changed: `g` (in `u`) solves the inner (Tresca) problem of
    /// the `limits` exactly. Converged (`states` become the Coulomb states)
    /// when the Coulomb return mapping at `g` gives the same states and the
    /// limits or the inner solutions settled; otherwise, with iterations
    /// left (`more`), the limits move on and `states` are those of the new
    /// limits: to their fixed point with these states by Newton's method
    /// where the solver keeps a factor ([`newton_limits`]), else (or where
    /// that step would open a slipping point) by the Anderson mix
    /// ([`LimitMix::next`]). `sig` is the [`signature`] of `states`
    /// as they come. Returns the outer change, the points not in their
    /// Coulomb state, and whether it converged.
    #[allow(clippy::too_many_arguments)]
    fn outer_step(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &[f64],
        states: &mut Vec<FaceState>,
        sig: &[(ContactState, bool, bool)],
        limits: &[f64],
        more: bool,
        solved: Vec<f64>,
        solver: &dyn LinearSolver,
    ) -> (f64, usize, bool) {
        let target = coulomb_limits(x, u);
        let outer = self.inner_solution.as_ref().map(|p| relative_change(u, p));
        // the friction forces one more Coulomb solve would change
        let slipping = |l: &[f64]| -> Vec<f64> {
            l.iter()
                .zip(states.iter())
                .map(|(v, s)| {
                    if s.state == ContactState::Slip {
                        *v
                    } else {
                        0.0
                    }
                })
                .collect()
        };
        let limit_change = relative_change(&slipping(&target), &slipping(limits));
        let residual = outer.map_or(limit_change, |c| c.min(limit_change));
        let coulomb = coulomb_states(x, u, committed, states);
        let unsettled = differ(&signature(&coulomb), sig);
        let settled = unsettled == 0 && residual <= self.params.tolerance;
        if settled {
            *states = coulomb;
        } else if more {
            self.inner_solution = Some(u.to_vec());
            let newton = (self.newton_misses < NEWTON_MISSES)
                .then(|| newton_limits(x, u, states, limits, &target, solver))
                .flatten();
            self.after_newton = newton.is_some();
            // the mix keeps its history of the map either way
            let mixed = self.limit_mix.next(limits, target);
            let next = newton.unwrap_or(mixed);
            states.clone_from(&self.reached.states);
            update_limited(
                x,
                u,
                committed,
                states,
                &next,
                &mut self.reached.tracker,
                self.params.max_flips,
            );
            self.limits = Some(next);
        }
        self.bulk_residual = Some(solved);
        (residual, unsettled, settled)
    }

    /// Some state changed: with iterations left (`more`), the step from the
    /// last iterate to `g` (in `u`) is cut at the line search's `β` when
    /// that lies in [[`STALLED_STEP`], 1), and `states` are mapped again
    /// at the damped iterate.
    #[allow(clippy::too_many_arguments)]
    fn damped_step(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut Vec<f64>,
        states: &mut [FaceState],
        limits: &[f64],
        more: bool,
        solved: Vec<f64>,
    ) {
        let step = self.bulk_residual.as_ref().filter(|_| more).and_then(|r0| {
            let beta = line_search(x, committed, limits, &self.before, u, r0, &solved);
            (STALLED_STEP..1.0).contains(&beta).then(|| {
                let step = |a: &[f64], b: &[f64]| -> Vec<f64> {
                    a.iter().zip(b).map(|(p, q)| p + beta * (q - p)).collect()
                };
                (step(&self.before, u), step(r0, &solved))
            })
        });
        if let Some((v, r)) = step {
            *u = v;
            self.bulk_residual = Some(r);
            states.clone_from_slice(&self.reached.states);
            update_limited(
                x,
                u,
                committed,
                states,
                limits,
                &mut FlipTracker::new(committed.len()),
                self.params.max_flips,
            );
        } else {
            self.bulk_residual = Some(solved);
        }
    }

    fn status(&self, finished: bool) -> RelaxStatus {
        RelaxStatus {
            iterations: self.done_iterations,
            residual: self.reached.info.last.residual,
            converged: finished && self.reached.info.converged,
            finished,
        }
    }

    /// Where the iteration stands: states, status, residual samples (the
    /// result once finished).
    pub fn reached(&self) -> &Reached {
        &self.reached
    }

    /// The result.
    pub fn into_reached(self) -> Reached {
        self.reached
    }
}

/// The free DOFs of the elements holding face points (those their gaps
/// and contact blocks read), ascending.
fn face_dofs(x: &Xfem) -> Vec<usize> {
    let mut dofs: Vec<usize> = x
        .faces
        .iter()
        .flat_map(|fp| &x.enriched[fp.slot].dofs)
        .filter(|&&d| d != FIXED)
        .map(|&d| d as usize)
        .collect();
    dofs.sort_unstable();
    dofs.dedup();
    dofs
}

/// `K u − λ f_ext` at the solution `u` of `system`: its contact forces
/// minus its contact stiffness times `u`.
fn bulk_residual(x: &Xfem, system: &System, u: &[f64]) -> Vec<f64> {
    let mut r = system.force.clone();
    for b in &system.blocks {
        let dofs = &x.enriched[b.slot].dofs;
        for (a, &da) in dofs.iter().enumerate() {
            if da == FIXED {
                continue;
            }
            let mut s = 0.0;
            for (c, &dc) in dofs.iter().enumerate() {
                if dc != FIXED {
                    s += b.k[(a, c)] * u[dc as usize];
                }
            }
            r[da as usize] -= s;
        }
    }
    r
}

/// The step `β ∈ (0, 1]` along `d = u − u0` at which the residual of the
/// contact law (the return mapping at `u0 + β d`) has no component along `d`.
fn line_search(
    x: &Xfem,
    committed: &[FaceState],
    limits: &[f64],
    u0: &[f64],
    u: &[f64],
    r0: &[f64],
    r1: &[f64],
) -> f64 {
    // per face point with stiffness: its index, its gaps at u0 and of d
    struct Pt {
        i: usize,
        g0: (f64, f64),
        gd: (f64, f64),
    }
    let d: Vec<f64> = u.iter().zip(u0).map(|(a, b)| a - b).collect();
    let a: f64 = d.iter().zip(r0).map(|(p, q)| p * q).sum();
    let b: f64 = d
        .iter()
        .zip(r0)
        .zip(r1)
        .map(|((p, q0), q1)| p * (q1 - q0))
        .sum();
    let pts: Vec<Pt> = x
        .faces
        .iter()
        .enumerate()
        .filter(|(_, fp)| fp.follows.is_none())
        .map(|(i, fp)| Pt {
            i,
            g0: gaps(x, fp, u0),
            gd: gaps(x, fp, &d),
        })
        .collect();
    let slope = |beta: f64| -> f64 {
        let mut s = a + beta * b;
        for &Pt { i, g0, gd } in &pts {
            let fp = &x.faces[i];
            let crack = &x.funcs.cracks[fp.crack];
            let st = tresca_point(
                crack,
                committed[i].slip,
                g0.0 + beta * gd.0,
                g0.1 + beta * gd.1,
                limits[i],
            );
            s += fp.w * (st.p_n * gd.0 + st.p_t * gd.1);
        }
        s
    };
    let (s0, s1) = (slope(0.0), slope(1.0));
    if s1 <= 0.0 || s0 >= 0.0 {
        return 1.0;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..40 {
        let m = 0.5 * (lo + hi);
        if slope(m) > 0.0 {
            hi = m;
        } else {
            lo = m;
        }
    }
    hi
}

/// Solves with contact from the committed states of the last converged
/// step; returns the new states. `u` is the starting guess and the result.
pub fn solve_with_contact(
    x: &Xfem,
    f_ext: &[f64],
    committed: &[FaceState],
    u: &mut Vec<f64>,
    solver: &mut dyn LinearSolver,
    params: ContactParams,
) -> Result<(Vec<FaceState>, ContactInfo), SolveError> {
    solve_with_contact_from(
        x,
        f_ext,
        committed,
        committed.to_vec(),
        &mut None,
        u,
        solver,
        params,
    )
}

/// [`solve_with_contact`] started from the states `initial` and with the
/// solver's current matrix built for `factored` (see
/// [`ContactSolve::advance`]): [`ContactSolve`] run to its end.
pub fn solve_with_contact_from(
    x: &Xfem,
    f_ext: &[f64],
    committed: &[FaceState],
    initial: Vec<FaceState>,
    factored: &mut Option<Vec<ContactState>>,
    u: &mut Vec<f64>,
    solver: &mut dyn LinearSolver,
    params: ContactParams,
) -> Result<(Vec<FaceState>, ContactInfo), SolveError> {
    let mut iteration = ContactSolve::new(f_ext.to_vec(), initial, params);
    while !iteration
        .advance(x, committed, factored, u, solver, usize::MAX)?
        .finished
    {}
    let reached = iteration.into_reached();
    Ok((reached.states, reached.info))
}
