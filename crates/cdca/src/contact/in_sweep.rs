//! The paper's DCA contact rule (SPEC §5–6, its steps 1–9): the contact
//! states are updated *in* the automaton's sweep, simultaneously with the
//! nonlinear iteration, instead of in an outer loop around converged linear
//! solves ([`ContactSolve`](crate::contact::iteration::ContactSolve)).
//!
//! The sweep visits the cells in order. After a cell's update (`Δu_i = ω
//! K_ii⁻¹ r_i`, with ω = 1 at the cells that carry face points: see the
//! end), each face point whose jump involves one of the cell's DOFs is
//! updated by the return mapping on the current iterate, and its
//! contribution to the system follows at once:
//!
//! - its stiffness in its element's matrix: `w k_N n⊗n` while closed, `+ w
//!   k_T t⊗t` at stick; when its state changes the element matrix changes
//!   and the diagonal blocks of the element's cells are refactorised;
//! - its force: `w k_T g_T^s J_t` at stick (the committed slip), `−w p_T
//!   J_t` at slip (the friction of the current iterate);
//! - the running residual `r = f − K u` by the change of both.
//!
//! It ends converged when, after a sweep, the automaton's tests pass on the
//! true residual (`max |Δu| ≤ tol max |u|`, `‖r‖ ≤ tol ‖λ f_ext‖`), no
//! state changed during the sweep, the return mapping
//! at the final displacement gives every point its state, `‖Δu‖ ≤
//! contact_tolerance ‖u‖` over the sweep, and no frozen point breaks the
//! law. Points that change state more than `max_flips` times are frozen as
//! in the outer loop, but only changes in sweeps that start from a settled
//! displacement count (relative residual ≤ `contact_tolerance`): while the
//! stress front travels through the mesh a point may change state dozens of
//! times (up to 30 in the first 160 sweeps of `closed_crack_biaxial`), which
//! is the iteration's progress, not cycling; a point that still flips once
//! the displacement has settled keeps the iteration from ending. All state lives in [`InSweep`] and changes only at
//! cell visits, so the result does not depend on how [`run`](InSweep::run)
//! calls slice the sweeps.
//!
//! The residual is measured against the load, not against `f` with the
//! contact forces as the outer loop's linear solves do: the slip friction
//! `μ k_N |g_N|` grows with the penetration, and an over-relaxed sweep
//! (ω = 1.8 on `plate_45_biaxial_k0.2_mu0.5` at 40 × 40) ran away to a
//! state whose friction forces were 1e30 times the load, with `‖r‖ ≤
//! 1e-10 ‖f‖`. That coupling (`∂p_T/∂g_N`) is not in the symmetric cell
//! blocks, and over-relaxing it diverged: on the sliding default specimen
//! ω = 1.5 drifted to all-open (residual 6e8 after 1e6 sweeps) and ω = 1.9
//! overflowed. So the cells that carry face points are relaxed at ω = 1
//! (plain Gauss–Seidel, where the friction is updated) and the rest at the
//! scene's ω: the specimen then converges at ω = 1.9 in 28 270 sweeps (431
//! 712 at ω = 1) to the outer loop's answer. Relaxing at ω = 1 only the
//! cells with a point in slip is not enough (the specimen at ω = 1.9 and
//! the 120 × 120 plate at 1.95 overflow again, the 40 × 40 plate at 1.8
//! ends unconverged, all open); a stick-only scene pays 19% more sweeps
//! (the specimen with the paper's joint: 28 495 against 23 968).

use web_time::Instant;

use crate::contact::law::{
    ContactState, FaceState, contact_system, coulomb_limit, gaps, update_point,
};
use crate::contact::points::update_followers;
use crate::contact::status::{ContactParams, FlipTracker, Reached, relative_change};
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{FacePoint, Xfem};
use crate::error::SolveError;
use crate::geometry::cracks::Crack;
use crate::scene::Ordering;
use crate::solvers::automaton::{Automaton, AutomatonParams, relative};
use crate::solvers::cells::Cells;
use crate::solvers::element_op::{ElementOperator, norm};
use crate::solvers::linear::LinearInfo;
use crate::solvers::relaxation::{RelaxStatus, ResidualSample};

/// Settings of the in-sweep contact iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InSweepParams {
    /// The automaton's sweeps (ω, tolerances, refresh).
    pub automaton: AutomatonParams,
    /// The order in which the sweeps visit the cells.
    pub ordering: Ordering,
    /// `tolerance` bounds `‖Δu‖/‖u‖` of the last sweep, `max_flips` freezes
    /// cycling points; `max_iterations` is not used (see `max_sweeps`).
    pub contact: ContactParams,
    /// Sweeps allowed in all (`solver.max_iterations`).
    pub max_sweeps: usize,
}

/// What a face point contributes to the system now.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Applied {
    state: ContactState,
    /// Force along `J_t` (`w k_T g_T^s` at stick, `−w p_T` at slip).
    force: f64,
}

/// The operator, cells and residual of the in-sweep iteration, built at the
/// first [`InSweep::run`].
struct Setup {
    op: ElementOperator,
    cells: Cells,
    /// Right-hand side: the load plus the contact forces (the residual's
    /// `f`; its norm is not the scale, see the module's documentation).
    f: Vec<f64>,
    /// Running residual `f − K u`.
    r: Vec<f64>,
    applied: Vec<Applied>,
    /// Face points of cell `c`: `cell_points[point_start[c]..point_start[c + 1]]`.
    point_start: Vec<usize>,
    cell_points: Vec<u32>,
    /// Cells of each enriched element (by slot), to refactorise.
    slot_cells: Vec<Vec<u32>>,
    since_refresh: usize,
    /// `u` at the start of the current sweep.
    before: Vec<f64>,
}

/// The in-sweep contact iteration as a resumable state machine.
pub struct InSweep {
    params: InSweepParams,
    /// The load `λ f_ext` (without contact forces).
    load: Vec<f64>,
    /// States, status and the relative residual after each sweep (sweep 0:
    /// the start), with times from the start.
    reached: Reached,
    /// Boxed: the cells and operator are large, the rest is small.
    setup: Option<Box<Setup>>,
    sweeps: usize,
    /// Relative residual after the last sweep.
    residual: f64,
    /// Sweep after which a state last changed (0: none yet).
    last_change: usize,
    seconds: f64,
}

impl InSweep {
    /// An in-sweep iteration on the load `load` (= λ f_ext), started from
    /// the states `initial` (the slip history is the `committed` states
    /// passed to [`run`](Self::run)).
    pub fn new(load: Vec<f64>, initial: Vec<FaceState>, params: InSweepParams) -> Self {
        Self {
            params,
            load,
            reached: Reached::new(initial),
            setup: None,
            sweeps: 0,
            residual: f64::INFINITY,
            last_change: 0,
            seconds: 0.0,
        }
    }

    /// Runs at most `max_sweeps` more sweeps (at least one; the first call
    /// also builds the cells). `committed` holds the slip history of the
    /// last converged step, `u` the starting guess, then the iterate, then
    /// the result (zero when its length does not match `x`).
    pub fn run(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut Vec<f64>,
        max_sweeps: usize,
    ) -> Result<RelaxStatus, SolveError> {
        if self.reached.ended(committed) {
            return Ok(self.status());
        }
        let clock = Instant::now();
        if u.len() != x.n_free() {
            *u = vec![0.0; x.n_free()];
        }
        if self.setup.is_none() {
            let setup = self.build(x, committed, u)?;
            let residual = relative(norm(&setup.r), norm(&self.load));
            self.residual = residual;
            self.setup = Some(Box::new(setup));
            self.reached.history.push(ResidualSample {
                iteration: 0,
                seconds: clock.elapsed().as_secs_f64(),
                residual,
            });
        }
        for _ in 0..max_sweeps.max(1) {
            let residual = self.sweep(x, committed, u)?;
            self.residual = residual;
            self.reached.history.push(ResidualSample {
                iteration: self.sweeps,
                seconds: self.seconds + clock.elapsed().as_secs_f64(),
                residual,
            });
            if self.reached.finished {
                self.reached.info.last.history = self.reached.history[self.last_change..]
                    .iter()
                    .map(|h| h.residual)
                    .collect();
                break;
            }
        }
        update_followers(x, u, &mut self.reached.states);
        self.seconds += clock.elapsed().as_secs_f64();
        Ok(self.status())
    }

    fn build(&self, x: &Xfem, committed: &[FaceState], u: &[f64]) -> Result<Setup, SolveError> {
        let mut f = self.load.clone();
        let blocks = contact_system(x, &self.reached.states, committed, &mut f);
        let op = ElementOperator::from_xfem(x, &blocks);
        let cells = Automaton::cells_of(x, &op, self.params.ordering)?;
        let mut r = vec![0.0; op.n];
        op.residual(&f, u, &mut r);
        let applied = x
            .faces
            .iter()
            .zip(&self.reached.states)
            .zip(committed)
            .map(|((fp, s), c)| applied_of(x, fp, s, c.slip))
            .collect();
        // which cell owns each DOF, and each node
        let mut dof_cell = vec![u32::MAX; op.n];
        let mut node_cell = vec![u32::MAX; x.mesh.node_count()];
        for c in 0..cells.len() {
            for &d in cells.dofs(c) {
                dof_cell[d as usize] = c as u32;
            }
            node_cell[cells.node(c)] = c as u32;
        }
        let mut per_cell: Vec<Vec<u32>> = vec![Vec::new(); cells.len()];
        for (p, fp) in x.faces.iter().enumerate() {
            if fp.follows.is_some() {
                continue;
            }
            let dofs = &x.enriched[fp.slot].dofs;
            for (a, &d) in dofs.iter().enumerate() {
                if d != FIXED && fp.jump[a / 2] != 0.0 {
                    let list = &mut per_cell[dof_cell[d as usize] as usize];
                    if list.last() != Some(&(p as u32)) {
                        list.push(p as u32);
                    }
                }
            }
        }
        let mut point_start = vec![0];
        let mut cell_points = Vec::new();
        for list in per_cell {
            cell_points.extend(list);
            point_start.push(cell_points.len());
        }
        let slot_cells = x
            .enriched
            .iter()
            .map(|el| {
                x.mesh
                    .element_nodes(el.elem)
                    .iter()
                    .map(|&n| node_cell[n])
                    .filter(|&c| c != u32::MAX)
                    .collect()
            })
            .collect();
        Ok(Setup {
            op,
            cells,
            f,
            r,
            applied,
            point_start,
            cell_points,
            slot_cells,
            since_refresh: 0,
            before: u.to_vec(),
        })
    }

    /// One sweep: every cell in order, each followed by its face points,
    /// then the convergence tests. Returns the relative residual.
    fn sweep(
        &mut self,
        x: &Xfem,
        committed: &[FaceState],
        u: &mut [f64],
    ) -> Result<f64, SolveError> {
        let Some(s) = self.setup.as_mut() else {
            unreachable!("the iteration is set up before it sweeps")
        };
        let a = self.params.automaton;
        s.before.copy_from_slice(u);
        let mut max_du: f64 = 0.0;
        let mut changed = 0;
        // flips count towards freezing only once the displacement has
        // settled (see the module's documentation)
        let max_flips = self.params.contact.max_flips;
        let counted = (self.residual <= self.params.contact.tolerance).then_some(max_flips);
        for k in 0..s.cells.len() {
            let c = s.cells.order()[k] as usize;
            let points = s.point_start[c]..s.point_start[c + 1];
            let omega = if points.is_empty() { a.omega } else { 1.0 };
            max_du = max_du.max(s.cells.update(&s.op, c, omega, u, &mut s.r)?);
            for q in points {
                let p = s.cell_points[q] as usize;
                changed += usize::from(visit(
                    s,
                    x,
                    p,
                    committed[p].slip,
                    u,
                    &mut self.reached.states[p],
                    &mut self.reached.tracker,
                    counted,
                )?);
            }
        }
        self.sweeps += 1;
        if changed > 0 {
            self.last_change = self.sweeps;
        }
        s.since_refresh += 1;
        if s.since_refresh >= a.refresh {
            s.op.residual(&s.f, u, &mut s.r);
            s.since_refresh = 0;
        }
        let scale = u.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let norm_load = norm(&self.load);
        let mut residual = relative(norm(&s.r), norm_load);
        if !residual.is_finite() {
            return Err(SolveError::NonFinite {
                place: format!("in-sweep contact, sweep {}", self.sweeps),
            });
        }
        let change = relative_change(u, &s.before);
        let mut passed = false;
        if changed == 0 && max_du <= a.tolerance_u * scale && residual <= a.tolerance {
            // confirm with the true residual and the states of the final u
            s.op.residual(&s.f, u, &mut s.r);
            s.since_refresh = 0;
            residual = relative(norm(&s.r), norm_load);
            let (consistent, violating) =
                final_check(x, committed, u, &self.reached.states, &self.reached.tracker);
            self.reached.info.violating = violating;
            passed = residual <= a.tolerance && consistent;
            if passed && change <= self.params.contact.tolerance {
                self.reached.info.converged = violating == 0;
                self.reached.finished = true;
            }
        }
        if self.sweeps >= self.params.max_sweeps.max(1) {
            self.reached.finished = true;
        }
        self.reached.info.iterations = self.sweeps;
        self.reached.info.linear_iterations = self.sweeps;
        self.reached.info.residual = change;
        self.reached.info.cycling = self.reached.tracker.frozen();
        self.reached.info.last = LinearInfo {
            iterations: self.sweeps,
            residual,
            converged: passed,
            history: Vec::new(),
        };
        Ok(residual)
    }

    fn status(&self) -> RelaxStatus {
        RelaxStatus {
            iterations: self.sweeps,
            residual: self.reached.info.last.residual,
            converged: self.reached.finished && self.reached.info.converged,
            finished: self.reached.finished,
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

/// What a point in state `s` contributes (see [`Applied`]).
fn applied_of(x: &Xfem, fp: &FacePoint, s: &FaceState, committed_slip: f64) -> Applied {
    let crack = &x.funcs.cracks[fp.crack];
    let force = match s.state {
        _ if fp.follows.is_some() => 0.0,
        ContactState::Open => 0.0,
        ContactState::Stick => fp.w * crack.kt * committed_slip,
        ContactState::Slip => -fp.w * s.p_t,
    };
    let state = if fp.follows.is_some() {
        ContactState::Open
    } else {
        s.state
    };
    Applied { state, force }
}

/// Updates point `p` by the return mapping on the current iterate and its
/// contribution to the operator, the right-hand side and the residual; a
/// change of state counts towards freezing it after `max_flips` when that
/// is given. Returns whether its state changed.
#[allow(clippy::too_many_arguments)]
fn visit(
    s: &mut Setup,
    x: &Xfem,
    p: usize,
    committed_slip: f64,
    u: &[f64],
    state: &mut FaceState,
    tracker: &mut FlipTracker,
    max_flips: Option<u32>,
) -> Result<bool, SolveError> {
    let fp = &x.faces[p];
    let crack = &x.funcs.cracks[fp.crack];
    let (gn, gt) = gaps(x, fp, u);
    let frozen = tracker.is_frozen(p);
    let new = if frozen {
        forced(state.state, crack, committed_slip, gn, gt)
    } else {
        update_point(crack, committed_slip, gn, gt)
    };
    let changed = !frozen && new.state != state.state;
    if let (true, Some(max_flips)) = (changed, max_flips) {
        tracker.flip(p, max_flips);
    }
    *state = new;
    let now = applied_of(x, fp, state, committed_slip);
    let was = s.applied[p];
    if now == was {
        return Ok(changed);
    }
    s.applied[p] = now;
    let closed = |st: ContactState| f64::from(u8::from(st != ContactState::Open));
    let stuck = |st: ContactState| f64::from(u8::from(st == ContactState::Stick));
    let d_kn = fp.w * crack.kn * (closed(now.state) - closed(was.state));
    let d_kt = fp.w * crack.kt * (stuck(now.state) - stuck(was.state));
    let d_force = now.force - was.force;
    let dofs = &x.enriched[fp.slot].dofs;
    let jn = |a: usize| fp.jump[a / 2] * fp.n[a % 2];
    let jt = |a: usize| fp.jump[a / 2] * fp.t[a % 2];
    // ΔK u_e along the jump: (Δk_N g_N) J_n + (Δk_T g_T) J_t
    let (d_fn, d_ft) = (d_kn * gn, d_kt * gt);
    for (a, &d) in dofs.iter().enumerate() {
        if d != FIXED {
            let v = d_force * jt(a);
            s.f[d as usize] += v;
            s.r[d as usize] += v - d_fn * jn(a) - d_ft * jt(a);
        }
    }
    if d_kn != 0.0 || d_kt != 0.0 {
        let e = x.enriched[fp.slot].elem;
        let nd = dofs.len();
        let k = s.op.element_matrix_mut(e);
        for a in 0..nd {
            for b in 0..nd {
                k[a * nd + b] += d_kn * jn(a) * jn(b) + d_kt * jt(a) * jt(b);
            }
        }
        for &c in &s.slot_cells[fp.slot] {
            s.cells.refactor(&s.op, c as usize)?;
        }
    }
    Ok(changed)
}

/// Whether the return mapping at `u` gives every free point its state, and
/// how many frozen points break the law (see
/// [`breaks_law`]).
fn final_check(
    x: &Xfem,
    committed: &[FaceState],
    u: &[f64],
    states: &[FaceState],
    tracker: &FlipTracker,
) -> (bool, usize) {
    let gaps_all: Vec<(f64, f64)> = x.faces.iter().map(|fp| gaps(x, fp, u)).collect();
    let mut jump_scale = vec![0.0_f64; x.funcs.cracks.len()];
    for (fp, &(gn, gt)) in x.faces.iter().zip(&gaps_all) {
        jump_scale[fp.crack] = jump_scale[fp.crack].max(gn.hypot(gt));
    }
    let (mut consistent, mut violating) = (true, 0);
    for (i, fp) in x.faces.iter().enumerate() {
        if fp.follows.is_some() {
            continue;
        }
        let crack = &x.funcs.cracks[fp.crack];
        let (gn, gt) = gaps_all[i];
        let new = update_point(crack, committed[i].slip, gn, gt);
        if tracker.is_frozen(i) {
            let kept = states[i].state;
            let slip = committed[i].slip;
            violating += usize::from(breaks_law(
                kept,
                &new,
                crack,
                slip,
                gt,
                jump_scale[fp.crack],
            ));
        } else if new.state != states[i].state {
            consistent = false;
        }
    }
    (consistent, violating)
}

/// Relative size of a frozen point's departure from the contact law below
/// which it still counts as obeying it: a normal gap of this fraction of
/// the crack's largest jump, or a tangential traction within this fraction
/// of the Coulomb limit.
const FROZEN_TOLERANCE: f64 = 1e-2;

/// Whether a frozen point whose kept state is `kept` breaks the contact
/// law by more than [`FROZEN_TOLERANCE`], given the return mapping's state
/// `new` at its gaps (`g_T` = `gt`, the normal gap in `new`): a normal gap
/// beyond that fraction of `jump_scale` (its crack's largest jump) when
/// one of the two is open, a trial tangential traction beyond that
/// fraction of the Coulomb limit otherwise.
fn breaks_law(
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
            let limit = coulomb_limit(crack, new.p_n);
            let trial = crack.kt * (gt - committed_slip);
            (trial.abs() - limit).abs() > FROZEN_TOLERANCE * limit.max(trial.abs())
        }
    }
}

/// The state of a frozen point: its kind is kept, its tractions follow the
/// gaps.
fn forced(kind: ContactState, crack: &Crack, slip: f64, gn: f64, gt: f64) -> FaceState {
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
            let p_t = coulomb_limit(crack, p_n) * trial.signum();
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
