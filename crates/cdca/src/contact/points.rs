//! The contact law over every face point, as the outer loop uses it: the
//! Coulomb states and friction limits at a displacement, the inner
//! (Tresca) law with the limits held fixed, the matrix the states give, and
//! the tip slivers that follow their neighbour.

use crate::contact::law::{
    ContactState, FaceState, friction_limit, gaps, keep_at_tie, stick_or_slip, update_point,
};
use crate::contact::status::FlipTracker;
use crate::discretisation::xfem::Xfem;
use crate::geometry::cracks::Crack;

/// The Coulomb states (the return mapping, [`update_point`]) of every face
/// point at `u`; a point at a stick/slip tie keeps its `current` state
/// ([`keep_at_tie`]).
pub(crate) fn coulomb_states(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    current: &[FaceState],
) -> Vec<FaceState> {
    let mut states: Vec<FaceState> = x
        .faces
        .iter()
        .zip(committed.iter().zip(current))
        .map(|(fp, (c, now))| {
            let (gn, gt) = gaps(x, fp, u);
            let crack = &x.funcs.cracks[fp.crack];
            let new = update_point(crack, c.slip, gn, gt);
            keep_at_tie(crack, c.slip, now.state, new, friction_limit(crack, gn))
        })
        .collect();
    update_followers(x, u, &mut states);
    states
}

/// The friction limit each point's state carries: `|p_T|` where it slips,
/// its Coulomb limit where it sticks (zero where open).
pub(crate) fn initial_limits(x: &Xfem, states: &[FaceState]) -> Vec<f64> {
    x.faces
        .iter()
        .zip(states)
        .map(|(fp, s)| match s.state {
            ContactState::Open => 0.0,
            _ => friction_limit(&x.funcs.cracks[fp.crack], s.g_n),
        })
        .collect()
}

/// The Coulomb limit `μ|p_N| + c_c` of every face point at `u` (zero
/// where it is open).
pub(crate) fn coulomb_limits(x: &Xfem, u: &[f64]) -> Vec<f64> {
    x.faces
        .iter()
        .map(|fp| {
            let gn = gaps(x, fp, u).0;
            if gn < 0.0 {
                friction_limit(&x.funcs.cracks[fp.crack], gn)
            } else {
                0.0
            }
        })
        .collect()
}

/// The inner (Tresca) law of a point: the normal penalty where `g_N < 0`,
/// and, independently of it, stick/slip with the friction limit `tau_y`
/// held fixed (open, without any traction, where `g_N ≥ 0` and `τ_y = 0`).
/// Its potential is convex, so the line search's slope is monotone.
pub(crate) fn tresca_point(
    crack: &Crack,
    committed_slip: f64,
    g_n: f64,
    g_t: f64,
    tau_y: f64,
) -> FaceState {
    if g_n >= 0.0 && tau_y <= 0.0 {
        return update_point(crack, committed_slip, g_n, g_t);
    }
    stick_or_slip(
        crack,
        committed_slip,
        g_n,
        g_t,
        crack.kn * g_n.min(0.0),
        tau_y,
    )
}

/// The matrix the states give (its kind per point), or `None` when some
/// point sticks while open (a matrix no [`ContactState`] list names).
pub(crate) fn matrix_kinds(states: &[FaceState]) -> Option<Vec<ContactState>> {
    states
        .iter()
        .map(|s| match s.state {
            ContactState::Stick if s.g_n >= 0.0 => None,
            ContactState::Slip if s.g_n >= 0.0 => Some(ContactState::Open),
            k => Some(k),
        })
        .collect()
}

/// Maps every face point by the inner law ([`tresca_point`]) with the
/// friction limits `limits`, a point at a stick/slip tie keeping its state
/// ([`keep_at_tie`]); returns how many changed state, each change
/// counted in `tracker` (which only reports them: the line search damps
/// the cycling).
pub(crate) fn update_limited(
    x: &Xfem,
    u: &[f64],
    committed: &[FaceState],
    states: &mut [FaceState],
    limits: &[f64],
    tracker: &mut FlipTracker,
    max_flips: u32,
) -> usize {
    let mut changed = 0;
    for i in 0..states.len() {
        let fp = &x.faces[i];
        if fp.follows.is_some() {
            continue;
        }
        let (gn, gt) = gaps(x, fp, u);
        let crack = &x.funcs.cracks[fp.crack];
        let mapped = tresca_point(crack, committed[i].slip, gn, gt, limits[i]);
        let new = keep_at_tie(crack, committed[i].slip, states[i].state, mapped, limits[i]);
        if new.state != states[i].state {
            changed += 1;
            tracker.flip(i, max_flips);
        }
        states[i] = new;
    }
    update_followers(x, u, states);
    changed
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
