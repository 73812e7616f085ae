//! Penalty frictional contact on closed crack faces (SPEC §5).
//!
//! At a face point, `[[u]] = u⁺ − u⁻`, `g_N = [[u]]·n`, `g_T = [[u]]·t`.
//! `g_N ≥ 0`: open. Otherwise `p_N = k_N g_N`, trial `p_T* = k_T (g_T − g_T^s)`,
//! `τ_y = μ|p_N| + min(c_c, |p_N|)` ([`coulomb_limit`]): stick if
//! `|p_T*| ≤ τ_y`, else slip with `p_T = τ_y sign(p_T*)`. Stick points add
//! `k_T t⊗t`, closed points `k_N n⊗n`; slip friction enters as a force from
//! the last iterate, so the operator stays symmetric positive definite for
//! every solver.

use std::collections::BTreeMap;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::{FacePoint, Xfem};
use crate::geometry::cracks::Crack;
use crate::geometry::plane::P2;

/// State of a crack-face contact point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactState {
    Open,
    Stick,
    Slip,
}

/// State of one face point, kept between load steps.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaceState {
    pub state: ContactState,
    /// Slipped (plastic) part of the tangential gap g_T^s, m.
    pub slip: f64,
    /// Normal gap g_N, m.
    pub g_n: f64,
    /// Tangential gap g_T, m.
    pub g_t: f64,
    /// Tractions p_N, p_T, Pa.
    pub p_n: f64,
    pub p_t: f64,
}

impl Default for FaceState {
    fn default() -> Self {
        Self {
            state: ContactState::Open,
            slip: 0.0,
            g_n: 0.0,
            g_t: 0.0,
            p_n: 0.0,
            p_t: 0.0,
        }
    }
}

impl FaceState {
    /// The state as `growth.resume` stores it (see
    /// [`Resume`](crate::scene::Resume)): `[state, g_T^s, g_N, g_T, p_N,
    /// p_T]`, state 0 open, 1 stick, 2 slip.
    pub fn saved(&self) -> [f64; 6] {
        let state = match self.state {
            ContactState::Open => 0.0,
            ContactState::Stick => 1.0,
            ContactState::Slip => 2.0,
        };
        [state, self.slip, self.g_n, self.g_t, self.p_n, self.p_t]
    }

    /// The state of a `growth.resume` entry (see [`saved`](Self::saved)).
    pub fn restored(f: &[f64; 6]) -> Self {
        let state = if f[0] == 2.0 {
            ContactState::Slip
        } else if f[0] == 1.0 {
            ContactState::Stick
        } else {
            ContactState::Open
        };
        Self {
            state,
            slip: f[1],
            g_n: f[2],
            g_t: f[3],
            p_n: f[4],
            p_t: f[5],
        }
    }

    /// Traction vector `p_N n + p_T t` that the `−` side exerts against
    /// the `+` side's motion (zero when open).
    pub fn traction(&self, fp: &FacePoint) -> P2 {
        fp.n * self.p_n + fp.t * self.p_t
    }
}

/// Normal and tangential jump operators of a face point over its element's
/// DOFs: `g_N = J_n · u_e`, `g_T = J_t · u_e`.
pub fn jump_operators(fp: &FacePoint) -> (DVector<f64>, DVector<f64>) {
    let nd = 2 * fp.jump.len();
    let mut jn = DVector::zeros(nd);
    let mut jt = DVector::zeros(nd);
    for (s, &j) in fp.jump.iter().enumerate() {
        for c in 0..2 {
            jn[2 * s + c] = j * fp.n[c];
            jt[2 * s + c] = j * fp.t[c];
        }
    }
    (jn, jt)
}

/// Gaps `(g_N, g_T)` of a face point from the free-DOF displacement.
pub fn gaps(x: &Xfem, fp: &FacePoint, u: &[f64]) -> (f64, f64) {
    let dofs = &x.enriched[fp.slot].dofs;
    let (mut gn, mut gt) = (0.0, 0.0);
    for (s, &j) in fp.jump.iter().enumerate() {
        for c in 0..2 {
            let d = dofs[2 * s + c];
            if d != FIXED {
                let v = j * u[d as usize];
                gn += v * fp.n[c];
                gt += v * fp.t[c];
            }
        }
    }
    (gn, gt)
}

/// The return mapping: new state of a point from its gaps, given the slip
/// committed at the last converged step: open where `g_N ≥ 0`, else
/// the tangential return mapping with `p_N = k_N g_N` and the Coulomb limit.
pub fn update_point(crack: &Crack, committed_slip: f64, g_n: f64, g_t: f64) -> FaceState {
    if g_n >= 0.0 {
        return FaceState {
            state: ContactState::Open,
            slip: g_t,
            g_n,
            g_t,
            p_n: 0.0,
            p_t: 0.0,
        };
    }
    let tau_y = friction_limit(crack, g_n);
    stick_or_slip(crack, committed_slip, g_n, g_t, crack.kn * g_n, tau_y)
}

/// The Coulomb limit at the normal traction `p_n`:
/// `τ_y = μ|p_N| + min(c_c, |p_N|)`.
///
/// Faces pressed together harder than their cohesion c_c carry SPEC §5's
/// `μ|p_N| + c_c`; lightly touching faces mobilise the cohesion with the
/// pressure, so the limit falls to zero as a point opens (the shape of
/// Patton's bilinear envelope for rock joints: a steeper branch through
/// the origin at low normal stress). With `μ|p_N| + c_c` down to `p_N = 0`
/// the limit jumps from c_c to 0 where a face point opens, and such a point
/// has no consistent state: closed it carries c_c and the shear opens it,
/// open it carries nothing and closes. With c_c = 15 MPa on the default
/// flaw the contact iteration cycled on one of them until its cap (growth
/// stopped `not_converged` at step 4). Without cohesion nothing changes.
pub fn coulomb_limit(crack: &Crack, p_n: f64) -> f64 {
    let p = p_n.abs();
    crack.friction * p + crack.cohesion.min(p)
}

/// [`coulomb_limit`] at the normal gap `g_n` (`p_N = k_N min(g_N, 0)`:
/// zero when open).
pub fn friction_limit(crack: &Crack, g_n: f64) -> f64 {
    coulomb_limit(crack, crack.kn * g_n.min(0.0))
}

/// Relative width of a stick/slip tie: a point whose trial traction is
/// within `TIE · τ_y` of its friction limit τ_y carries the same traction
/// (to that width) stuck or slipping, so the outer contact iteration keeps
/// the state it has (`keep_at_tie`). Round-off puts such a point on
/// either side at each solve: a run's final solve at its last load starts
/// from slips committed at exactly that load (trial = τ_y to 1e-12), and six
/// points changed state at every iteration until the 200-iteration cap.
/// 1e-9 is three orders above that round-off and below the contact
/// tolerance (1e-8), so a kept state moves the solution by less than the
/// tolerance the iteration accepts.
pub const TIE: f64 = 1e-9;

/// `new` (the return mapping at the gaps with friction limit `tau_y`), or,
/// where it changes `current` between stick and slip at a tie (see
/// [`TIE`]), `current`'s state with the traction that state carries.
pub(crate) fn keep_at_tie(
    crack: &Crack,
    committed_slip: f64,
    current: ContactState,
    new: FaceState,
    tau_y: f64,
) -> FaceState {
    let trial = crack.kt * (new.g_t - committed_slip);
    let tie = (trial.abs() - tau_y).abs() <= TIE * tau_y;
    match (current, new.state) {
        (ContactState::Stick, ContactState::Slip) if tie => FaceState {
            state: ContactState::Stick,
            slip: committed_slip,
            p_t: trial,
            ..new
        },
        (ContactState::Slip, ContactState::Stick) if tie => {
            let p_t = tau_y * trial.signum();
            FaceState {
                state: ContactState::Slip,
                slip: new.g_t - p_t / crack.kt,
                p_t,
                ..new
            }
        }
        _ => new,
    }
}

/// The tangential return mapping at the gaps `(g_n, g_t)` with the normal
/// traction `p_n` and the friction limit `tau_y`: stick while the trial
/// traction `k_T (g_T − g_T^s)` stays within ±τ_y, else slip at ±τ_y with
/// the slip moved along.
pub(crate) fn stick_or_slip(
    crack: &Crack,
    committed_slip: f64,
    g_n: f64,
    g_t: f64,
    p_n: f64,
    tau_y: f64,
) -> FaceState {
    let trial = crack.kt * (g_t - committed_slip);
    if trial.abs() <= tau_y {
        FaceState {
            state: ContactState::Stick,
            slip: committed_slip,
            g_n,
            g_t,
            p_n,
            p_t: trial,
        }
    } else {
        let p_t = tau_y * trial.signum();
        FaceState {
            state: ContactState::Slip,
            slip: g_t - p_t / crack.kt,
            g_n,
            g_t,
            p_n,
            p_t,
        }
    }
}

/// Contact stiffness blocks and the force they add to the right-hand side,
/// for the current states (and the committed slips).
pub fn contact_system(
    x: &Xfem,
    states: &[FaceState],
    committed: &[FaceState],
    f: &mut [f64],
) -> Vec<ElementBlock> {
    contact_system_split(x, states, committed, |_| true, f)
}

/// [`contact_system`] with the normal penalty `k_N n⊗n` only at the stuck
/// or slipping points `closed` accepts (the Tresca inner problem of the
/// contact iteration, where a point may open and still carry friction).
pub fn contact_system_split(
    x: &Xfem,
    states: &[FaceState],
    committed: &[FaceState],
    closed: impl Fn(&FaceState) -> bool,
    f: &mut [f64],
) -> Vec<ElementBlock> {
    let mut blocks: BTreeMap<usize, DMatrix<f64>> = BTreeMap::new();
    for (i, fp) in x.faces.iter().enumerate() {
        let st = &states[i];
        if st.state == ContactState::Open || fp.follows.is_some() {
            continue;
        }
        let crack = &x.funcs.cracks[fp.crack];
        let (jn, jt) = jump_operators(fp);
        let nd = jn.len();
        let k = blocks
            .entry(fp.slot)
            .or_insert_with(|| DMatrix::zeros(nd, nd));
        if closed(st) {
            k.ger(fp.w * crack.kn, &jn, &jn, 1.0);
        }
        // force on the right-hand side: stick `+w k_T g_T^s J_t`, slip `−w p_T J_t`
        let ft = match st.state {
            ContactState::Stick => {
                k.ger(fp.w * crack.kt, &jt, &jt, 1.0);
                fp.w * crack.kt * committed[i].slip
            }
            _ => -fp.w * st.p_t,
        };
        let dofs = &x.enriched[fp.slot].dofs;
        for (a, &d) in dofs.iter().enumerate() {
            if d != FIXED {
                f[d as usize] += ft * jt[a];
            }
        }
    }
    blocks
        .into_iter()
        .map(|(slot, k)| ElementBlock { slot, k })
        .collect()
}

/// Counts of points per state.
/// The traction `p_N n + p_T t` at every face piece of `x` (on the `−`
/// side; zero where open), one per piece of `x.faces`.
pub fn face_tractions(x: &Xfem, states: &[FaceState]) -> Vec<P2> {
    x.faces
        .iter()
        .zip(states)
        .map(|(fp, s)| s.traction(fp))
        .collect()
}

pub fn counts(states: &[FaceState]) -> crate::report::ContactCounts {
    let mut c = crate::report::ContactCounts::default();
    for s in states {
        match s.state {
            ContactState::Open => c.open += 1,
            ContactState::Stick => c.stick += 1,
            ContactState::Slip => c.slip += 1,
        }
    }
    c
}

/// Carries face states over to a new discretisation: each new point takes
/// the state of the nearest old point of the same crack (new faces start
/// open).
pub fn carry_over(
    old: &[FacePoint],
    old_states: &[FaceState],
    new: &[FacePoint],
    h: f64,
) -> Vec<FaceState> {
    new.iter()
        .map(|fp| {
            old.iter()
                .zip(old_states)
                .filter(|(o, _)| o.crack == fp.crack)
                .map(|(o, s)| ((o.x - fp.x).norm(), s))
                .filter(|(d, _)| *d < 0.5 * h)
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, s)| *s)
                .unwrap_or_default()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::cracks::TipKind;
    use crate::geometry::plane::p2;

    fn crack(friction: f64, cohesion: f64) -> Crack {
        Crack {
            points: vec![p2([0.0, 0.0]), p2([1.0, 0.0])],
            tips: [TipKind::Free; 2],
            friction,
            cohesion,
            kn: 1e12,
            kt: 1e11,
        }
    }

    /// At a tie (trial traction within `TIE · τ_y` of the limit) a point
    /// keeps its state, stuck or slipping, with that state's traction;
    /// beyond it the return mapping decides. Both sides of the limit, both
    /// signs of the traction.
    #[test]
    fn a_point_at_a_stick_slip_tie_keeps_its_state() {
        let c = crack(0.5, 0.0);
        let (g_n, slip) = (-2e-5, 1e-7);
        let tau_y = friction_limit(&c, g_n);
        for sign in [1.0, -1.0] {
            for (excess, tie) in [(1e-12, true), (-1e-12, true), (1e-6, false), (-1e-6, false)] {
                let g_t = slip + sign * tau_y * (1.0 + excess) / c.kt;
                let mapped = update_point(&c, slip, g_n, g_t);
                for current in [ContactState::Stick, ContactState::Slip] {
                    let kept = keep_at_tie(&c, slip, current, mapped, tau_y);
                    let expected = if tie { current } else { mapped.state };
                    assert_eq!(kept.state, expected, "{sign} {excess} {current:?}");
                    let p_t = match kept.state {
                        ContactState::Stick => c.kt * (g_t - slip),
                        _ => sign * tau_y,
                    };
                    assert!((kept.p_t - p_t).abs() <= 1e-12 * tau_y, "{kept:?}");
                    assert!((kept.p_t.abs() - tau_y).abs() <= 2e-6 * tau_y);
                }
            }
        }
        let open = update_point(&c, slip, 1e-9, 0.0);
        assert_eq!(keep_at_tie(&c, slip, ContactState::Stick, open, 0.0), open);
    }

    /// SPEC §5's μ|p_N| + c_c once |p_N| ≥ c_c; below, the cohesion grows
    /// with the pressure, so the limit is continuous (zero) where a point
    /// opens; without cohesion μ|p_N| everywhere.
    #[test]
    fn the_coulomb_limit_is_continuous_where_faces_open() {
        let c = crack(0.5, 15e6);
        assert_eq!(coulomb_limit(&c, -40e6), 0.5 * 40e6 + 15e6);
        assert_eq!(coulomb_limit(&c, -15e6), 0.5 * 15e6 + 15e6);
        assert_eq!(coulomb_limit(&c, -6e6), 1.5 * 6e6);
        assert_eq!(coulomb_limit(&c, 0.0), 0.0);
        assert_eq!(friction_limit(&c, 1e-9), 0.0, "open");
        assert_eq!(friction_limit(&c, -2e-5), 0.5 * 2e7 + 15e6);
        let dry = crack(0.5, 0.0);
        assert_eq!(coulomb_limit(&dry, -6e6), 0.5 * 6e6);
    }
}
