//! The contact iteration (SPEC §5), a fixed-point (active-set) loop: solve
//! the linear system of the current states, update every face point's state
//! by the return mapping, repeat until no state changes and the
//! displacement settles. Points that flip state too often are frozen in
//! their latest state and counted, so the loop always ends with an explicit
//! status. Resumable ([`ContactSolve`]); the blocking calls loop over it.

use nalgebra::{DMatrix, DVector};

use crate::contact::law::{ContactState, FaceState, contact_system, gaps, update_point};
use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::geometry::cracks::Crack;
use crate::solvers::linear::{LinearInfo, LinearSolver};
use crate::solvers::relaxation::{RelaxStatus, ResidualSample};

/// Settings of the contact iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactParams {
    /// Converged when `‖Δu‖ ≤ tolerance ‖u‖` and no state changed.
    pub tolerance: f64,
    pub max_iterations: usize,
    /// State changes after which a point is frozen (stick–slip cycling).
    pub max_flips: u32,
}

impl ContactParams {
    /// Contact iterations allowed (at least one).
    pub fn max_contact_iterations(&self) -> usize {
        self.max_iterations.max(1)
    }
}

impl Default for ContactParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-8,
            max_iterations: 50,
            max_flips: 4,
        }
    }
}

/// How the contact iteration ended.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactInfo {
    pub iterations: usize,
    /// True only when every test passed: the last linear solve converged,
    /// no state changed, the displacement settled (with slip points), and
    /// no frozen point breaks the contact law at the final displacement.
    pub converged: bool,
    /// Relative displacement change of the last iteration.
    pub residual: f64,
    /// Ended at `max_iterations` without settling (states changing, or
    /// with slip the displacement still moving).
    pub capped: bool,
    /// Points frozen for cycling.
    pub cycling: usize,
    /// Frozen points whose kept state is not the one the return mapping
    /// gives at the final displacement (they break the stick/slip rule).
    pub violating: usize,
    /// Linear iterations summed over the contact iterations.
    pub linear_iterations: usize,
    /// The last linear solve.
    pub last: LinearInfo,
}

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
/// states (`k_N n⊗n`, `+ k_T t⊗t` at stick, the friction force of slip
/// points from the last iterate), solve it, update every point by the
/// return mapping ([`update_states`]); repeat until no state changed and
/// (with slip points) `‖Δu‖ ≤ tolerance ‖u‖` ([`settled`]), at most
/// `max_iterations` times.
///
/// The next iterate is not always the solution `g` of the last system
/// (with the default penalty `k_N = 100 E/h` the lagged friction let a
/// whole flaw slide back and forth and slam its wings shut):
/// - when some point's state (or slip direction) changed, the step from
///   the iterate `u₀` is damped, `u ← u₀ + β (g − u₀)` with `β ∈ (0, 1]`
///   where the residual of the contact law (the return mapping along the
///   step) has no component along it; a step cut below
///   [`STALLED_STEP`] is taken whole instead, since the same states would
///   give the same step again;
/// - when no state changed, the map `u₀ ↦ g` is affine (the same matrix,
///   friction linear in the gaps), and the next iterate is the Anderson
///   mix of the last [`ANDERSON_DEPTH`] pairs, if it keeps every state.
///
/// Frozen points that break the law once the rest has settled are
/// released. The operator is unchanged (symmetric positive definite), and
/// the tests are taken on `g`, the solution of the last system: the
/// iteration ends converged only with `u = g`.
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
    /// The pairs `(u₀, g)` since the states last changed.
    anderson: Anderson,
}

/// Pairs kept for the Anderson mix (measured on the issue-17 growth
/// runs and 139 contact problems from them: 3 and 10 converged as many).
pub const ANDERSON_DEPTH: usize = 5;

/// A line-search step below this fraction is taken whole (the same
/// states would give the same step again: a stall).
pub const STALLED_STEP: f64 = 0.01;

/// Each point's state and, when it slips, the direction of its friction:
/// the iteration's map `u₀ ↦ g` is affine while this is unchanged.
fn signature(states: &[FaceState]) -> Vec<(ContactState, bool)> {
    states
        .iter()
        .map(|s| (s.state, s.state == ContactState::Slip && s.p_t > 0.0))
        .collect()
}

/// Anderson mixing of the fixed-point map `u₀ ↦ g` (the solution of the
/// system of `u₀`'s states), with `r`, the bulk residual `K u − λ f_ext`,
/// mixed alike (it is affine in `u`).
#[derive(Default)]
struct Anderson {
    /// `(u₀, g, r(g))`, oldest first.
    pairs: Vec<(Vec<f64>, Vec<f64>, Vec<f64>)>,
}

impl Anderson {
    fn clear(&mut self) {
        self.pairs.clear();
    }

    /// Adds `(u₀, g, r(g))`; returns the mixed iterate and its residual
    /// once there are two pairs: `g − Σ γ_j Δg_j` with `γ` minimising
    /// `‖(g − u₀) − Σ γ_j Δ(g − u₀)_j‖`.
    fn push(&mut self, u0: &[f64], g: &[f64], r: &[f64]) -> Option<(Vec<f64>, Vec<f64>)> {
        self.pairs.push((u0.to_vec(), g.to_vec(), r.to_vec()));
        if self.pairs.len() > ANDERSON_DEPTH + 1 {
            self.pairs.remove(0);
        }
        let k = self.pairs.len();
        if k < 2 {
            return None;
        }
        let f = |j: usize, i: usize| self.pairs[j].1[i] - self.pairs[j].0[i];
        let df = DMatrix::from_fn(g.len(), k - 1, |i, j| f(j + 1, i) - f(j, i));
        let fk = DVector::from_fn(g.len(), |i, _| f(k - 1, i));
        let svd = df.svd(true, true);
        let largest = svd.singular_values.max();
        if largest <= 0.0 {
            return None;
        }
        let gamma = svd.solve(&fk, 1e-12 * largest).ok()?;
        let (mut u, mut res) = (g.to_vec(), r.to_vec());
        for (j, w) in self.pairs.windows(2).enumerate() {
            for (v, (a, b)) in u.iter_mut().zip(w[1].1.iter().zip(&w[0].1)) {
                *v -= gamma[j] * (a - b);
            }
            for (v, (a, b)) in res.iter_mut().zip(w[1].2.iter().zip(&w[0].2)) {
                *v -= gamma[j] * (a - b);
            }
        }
        u.iter().all(|v| v.is_finite()).then_some((u, res))
    }
}

/// Where a contact iteration stands, the outer loop's ([`ContactSolve`])
/// or the in-sweep rule's
/// ([`InSweep`](crate::contact::in_sweep::InSweep)): the contact states,
/// how it went, whether it ended, the residual samples so far, and the
/// flip counts of the stick–slip cycling guard.
#[derive(Clone, Debug, Default)]
pub struct Reached {
    /// The states as they are now (the result once finished).
    pub states: Vec<FaceState>,
    /// How it went so far (how it ended, once finished).
    pub info: ContactInfo,
    pub finished: bool,
    /// Relative residual samples, iterations and times from the start.
    pub history: Vec<ResidualSample>,
    /// How often each point changed state, and which are frozen.
    pub tracker: FlipTracker,
}

impl Reached {
    /// The start: the states `initial`, nothing done.
    pub fn new(initial: Vec<FaceState>) -> Self {
        Self {
            tracker: FlipTracker::new(initial.len()),
            states: initial,
            ..Self::default()
        }
    }

    /// Whether the iteration has ended; `committed` must hold one state per
    /// face point (the caller's slip history of this discretisation).
    pub(crate) fn ended(&self, committed: &[FaceState]) -> bool {
        assert_eq!(
            self.states.len(),
            committed.len(),
            "one state per face point"
        );
        self.finished
    }
}

/// The linear system of one contact iteration.
struct System {
    blocks: Vec<ElementBlock>,
    /// The contact forces on the right-hand side.
    force: Vec<f64>,
    /// Samples of this solve already copied to the history.
    copied: usize,
    /// The [`signature`] of the states it was built with.
    signature: Vec<(ContactState, bool)>,
}

impl ContactSolve {
    /// A contact iteration on the load `load` (= λ f_ext), started from the
    /// states `initial` (a guess of which points are open, stuck or
    /// slipping; the slip history is the `committed` states passed to
    /// [`advance`](Self::advance)).
    pub fn new(load: Vec<f64>, initial: Vec<FaceState>, params: ContactParams) -> Self {
        Self {
            params,
            load,
            reached: Reached::new(initial),
            system: None,
            before: Vec::new(),
            done_iterations: 0,
            done_seconds: 0.0,
            bulk_residual: None,
            anderson: Anderson::default(),
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
        let Some(system) = &mut self.system else {
            let mut f = self.load.clone();
            let blocks = contact_system(x, &self.reached.states, committed, &mut f);
            let kinds: Vec<ContactState> = self.reached.states.iter().map(|s| s.state).collect();
            let matrix_changed = factored.as_ref() != Some(&kinds);
            // unknown until the setup below has succeeded
            *factored = None;
            self.before.clone_from(u);
            solver.start(x, &blocks, &f, u, matrix_changed)?;
            *factored = Some(kinds);
            for (a, b) in f.iter_mut().zip(&self.load) {
                *a -= b;
            }
            self.system = Some(System {
                blocks,
                force: f,
                copied: 0,
                signature: signature(&self.reached.states),
            });
            return self.advance(x, committed, factored, u, solver, max_iterations);
        };
        let status = solver.run(x, &system.blocks, max_iterations.max(1))?;
        u.clear();
        u.extend_from_slice(solver.u());
        let samples = solver.samples();
        // later contact iterations do not repeat the iteration-0 sample
        let later = self.done_iterations > 0;
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
        let it = self.reached.info.iterations + 1;
        let Some(system) = self.system.take() else {
            return Ok(self.status(self.reached.finished));
        };
        // the tests are taken on g = u, the solution of the system
        let solved = bulk_residual(x, &system, u);
        let change = relative_change(u, &self.before);
        let mut states = self.reached.states.clone();
        let mut tracker = self.reached.tracker.clone();
        let update = update_states(x, u, committed, &mut states, &mut tracker, self.params);
        let settled = settled(&update, &states, change, self.params);
        let next = if settled || !linear_converged || it >= self.params.max_contact_iterations() {
            self.anderson.clear();
            None
        } else if update.changed == 0 && signature(&states) == system.signature {
            let mixed = self
                .anderson
                .push(&self.before, u, &solved)
                .filter(|(m, _)| {
                    let (mut st, mut tr) = (states.clone(), tracker.clone());
                    update_states(x, m, committed, &mut st, &mut tr, self.params);
                    signature(&st) == system.signature
                });
            if mixed.is_none() {
                self.anderson.clear();
            }
            mixed
        } else {
            self.anderson.clear();
            self.bulk_residual.as_ref().and_then(|r0| {
                let beta = line_search(x, committed, &self.before, u, r0, &solved);
                (STALLED_STEP..1.0).contains(&beta).then(|| {
                    let step = |a: &[f64], b: &[f64]| -> Vec<f64> {
                        a.iter().zip(b).map(|(p, q)| p + beta * (q - p)).collect()
                    };
                    (step(&self.before, u), step(r0, &solved))
                })
            })
        };
        if let Some((v, r)) = next {
            *u = v;
            self.bulk_residual = Some(r);
            update_states(
                x,
                u,
                committed,
                &mut self.reached.states,
                &mut self.reached.tracker,
                self.params,
            );
        } else {
            self.bulk_residual = Some(solved);
            self.reached.states = states;
            self.reached.tracker = tracker;
        }
        self.reached.info.iterations = it;
        self.reached.info.residual = change;
        self.reached.info.violating = update.violating;
        self.reached.info.cycling = self.reached.tracker.frozen();
        if !self.reached.info.residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("contact iteration {it}"),
            });
        }
        // an unconverged linear solve ends the iteration: states updated
        // from it mean little, and the status says so
        if !linear_converged {
            self.reached.finished = true;
        } else if settled {
            if update.violating > 0 && it < self.params.max_contact_iterations() {
                thaw(
                    x,
                    u,
                    committed,
                    &mut self.reached.states,
                    &mut self.reached.tracker,
                );
                self.reached.info.cycling = self.reached.tracker.frozen();
            } else {
                self.reached.info.converged = update.violating == 0;
                self.reached.finished = true;
            }
        } else if it >= self.params.max_contact_iterations() {
            self.reached.info.capped = true;
            self.reached.finished = true;
        }
        Ok(self.status(self.reached.finished))
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
            let st = update_point(
                crack,
                committed[i].slip,
                g0.0 + beta * gd.0,
                g0.1 + beta * gd.1,
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

/// Per point: how often it changed state, and whether it is frozen.
#[derive(Clone, Debug, Default)]
pub struct FlipTracker {
    flips: Vec<u32>,
    frozen: Vec<bool>,
}

impl FlipTracker {
    pub fn new(n: usize) -> Self {
        Self {
            flips: vec![0; n],
            frozen: vec![false; n],
        }
    }

    /// Whether point `i` is frozen.
    pub fn is_frozen(&self, i: usize) -> bool {
        self.frozen[i]
    }

    /// Counts a state change of point `i`, freezing it once it has changed
    /// more than `max_flips` times.
    pub fn flip(&mut self, i: usize, max_flips: u32) {
        self.flips[i] += 1;
        if self.flips[i] > max_flips {
            self.frozen[i] = true;
        }
    }

    /// Number of frozen (cycling) points.
    pub fn frozen(&self) -> usize {
        self.frozen.iter().filter(|&&f| f).count()
    }
}

/// What one state update found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StateUpdate {
    /// Points whose state changed.
    pub changed: usize,
    /// Frozen points whose kept state differs from the return mapping's.
    pub violating: usize,
}

/// Whether the contact iteration has settled after `update`: no state
/// changed, and (when friction follows the iterate at slip points) the
/// displacement changed by at most the tolerance.
pub fn settled(
    update: &StateUpdate,
    states: &[FaceState],
    relative_change: f64,
    params: ContactParams,
) -> bool {
    update.changed == 0 && (!any_slip(states) || relative_change <= params.tolerance)
}

/// Relative size of a frozen point's departure from the contact law below
/// which it still counts as obeying it: a normal gap of this fraction of
/// the crack's largest jump, or a tangential traction within this fraction
/// of the Coulomb limit.
pub const FROZEN_TOLERANCE: f64 = 1e-2;

/// Updates every face point's state from the displacement `u` by the
/// return mapping.
///
/// Points that changed more than `max_flips` times are frozen in their
/// latest state (keeping them closed or bonded instead was tried: on kinked
/// wing cracks it left pieces bonded under shear tractions 40 times their
/// Coulomb limit, or kept the iteration from settling). A frozen point
/// counts as violating when its
/// kept state is not the return mapping's and the difference is more than
/// [`FROZEN_TOLERANCE`]: a normal gap beyond that fraction of its crack's
/// largest jump, or a trial tangential traction beyond that fraction of the
/// Coulomb limit.
///
/// Slivers at tips ([`FacePoint::follows`](crate::discretisation::xfem::FacePoint::follows))
/// take the state of the point they follow.
pub fn update_states(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    states: &mut [FaceState],
    tracker: &mut FlipTracker,
    params: ContactParams,
) -> StateUpdate {
    let (gaps_all, jump_scale) = gaps_and_jump_scales(x, u);
    let mut update = StateUpdate::default();
    for i in 0..states.len() {
        let fp = &x.faces[i];
        if fp.follows.is_some() {
            continue;
        }
        let crack = &x.funcs.cracks[fp.crack];
        let (gn, gt) = gaps_all[i];
        let new = update_point(crack, committed[i].slip, gn, gt);
        if tracker.frozen[i] {
            states[i] = forced(states[i].state, crack, committed[i].slip, gn, gt);
            let breaks = breaks_law(
                states[i].state,
                &new,
                crack,
                committed[i].slip,
                gt,
                jump_scale[fp.crack],
            );
            update.violating += usize::from(breaks);
            continue;
        }
        if new.state != states[i].state {
            update.changed += 1;
            tracker.flip(i, params.max_flips);
        }
        states[i] = new;
    }
    update_followers(x, u, states);
    update
}

/// The gaps `(g_N, g_T)` of every face point at `u`, and per crack its
/// largest jump `|[[u]]|` (the scale of [`FROZEN_TOLERANCE`]).
fn gaps_and_jump_scales(x: &Xfem, u: &[f64]) -> (Vec<(f64, f64)>, Vec<f64>) {
    let gaps_all: Vec<(f64, f64)> = x.faces.iter().map(|fp| gaps(x, fp, u)).collect();
    let mut jump_scale = vec![0.0_f64; x.funcs.cracks.len()];
    for (fp, &(gn, gt)) in x.faces.iter().zip(&gaps_all) {
        jump_scale[fp.crack] = jump_scale[fp.crack].max(gn.hypot(gt));
    }
    (gaps_all, jump_scale)
}

/// Releases the frozen points that break the contact law at `u`: each
/// takes the return mapping's state and starts its flip count afresh.
fn thaw(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    states: &mut [FaceState],
    tracker: &mut FlipTracker,
) {
    let (gaps_all, jump_scale) = gaps_and_jump_scales(x, u);
    for i in 0..states.len() {
        let fp = &x.faces[i];
        if fp.follows.is_some() || !tracker.frozen[i] {
            continue;
        }
        let crack = &x.funcs.cracks[fp.crack];
        let (gn, gt) = gaps_all[i];
        let new = update_point(crack, committed[i].slip, gn, gt);
        if breaks_law(
            states[i].state,
            &new,
            crack,
            committed[i].slip,
            gt,
            jump_scale[fp.crack],
        ) {
            states[i] = new;
            tracker.frozen[i] = false;
            tracker.flips[i] = 0;
        }
    }
    update_followers(x, u, states);
}

/// Whether a frozen point whose kept state is `kept` breaks the contact
/// law by more than [`FROZEN_TOLERANCE`], given the return mapping's state
/// `new` at its gaps (`g_T` = `gt`, the normal gap in `new`): a normal gap
/// beyond that fraction of `jump_scale` (its crack's largest jump) when
/// one of the two is open, a trial tangential traction beyond that
/// fraction of the Coulomb limit otherwise.
pub fn breaks_law(
    kept: ContactState,
    new: &FaceState,
    crack: &Crack,
    committed_slip: f64,
    gt: f64,
    jump_scale: f64,
) -> bool {
    match (kept, new.state) {
        (a, b) if a == b => false,
        (ContactState::Open, _) | (_, ContactState::Open) => {
            new.g_n.abs() > FROZEN_TOLERANCE * jump_scale
        }
        _ => {
            let limit = crack.friction * new.p_n.abs() + crack.cohesion;
            let trial = crack.kt * (gt - committed_slip);
            (trial.abs() - limit).abs() > FROZEN_TOLERANCE * limit.max(trial.abs())
        }
    }
}

/// Slivers at tips take their neighbour's state and traction, with their
/// own gaps from `u`.
pub fn update_followers(x: &Xfem, u: &[f64], states: &mut [FaceState]) {
    for (i, fp) in x.faces.iter().enumerate() {
        if let Some(j) = fp.follows {
            let (g_n, g_t) = gaps(x, fp, u);
            states[i] = FaceState {
                g_n,
                g_t,
                ..states[j]
            };
        }
    }
}

/// `‖a − b‖ / ‖a‖` (or `‖a − b‖` when a = 0): the contact iteration's
/// convergence measure.
pub fn relative_change(a: &[f64], b: &[f64]) -> f64 {
    let d: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt();
    let n: f64 = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 0.0 { d / n } else { d }
}

/// Whether any point slips (its friction force then follows the iterate).
pub fn any_slip(states: &[FaceState]) -> bool {
    states.iter().any(|s| s.state == ContactState::Slip)
}

/// The state of a frozen point: its kind is kept, its tractions follow the
/// gaps.
pub fn forced(kind: ContactState, crack: &Crack, slip: f64, gn: f64, gt: f64) -> FaceState {
    let free = update_point(crack, slip, gn, gt);
    match kind {
        ContactState::Open => FaceState {
            state: ContactState::Open,
            p_n: 0.0,
            p_t: 0.0,
            ..free
        },
        ContactState::Stick => FaceState {
            state: ContactState::Stick,
            slip,
            g_n: gn,
            g_t: gt,
            p_n: crack.kn * gn,
            p_t: crack.kt * (gt - slip),
        },
        ContactState::Slip => {
            let p_n = crack.kn * gn.min(0.0);
            let trial = crack.kt * (gt - slip);
            let p_t = (crack.friction * p_n.abs() + crack.cohesion) * trial.signum();
            FaceState {
                state: ContactState::Slip,
                slip: gt - p_t / crack.kt,
                g_n: gn,
                g_t: gt,
                p_n,
                p_t,
            }
        }
    }
}
