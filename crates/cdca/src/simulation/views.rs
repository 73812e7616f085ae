//! What the workbench and exports read from a simulation: the field at any
//! point, the contact points with their states and tractions, and the
//! criterion's curves around each tip.

use super::state::Simulation;
use crate::contact::law::ContactState;
use crate::discretisation::field::Field;
use crate::fracture::tips::TipDomains;
use crate::geometry::cracks::system_lengths;
use crate::geometry::plane::P2;
use crate::report::TipReport;
use crate::scene::SolverKind;

/// A crack-face integration point as the UI shows it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
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
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
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
    /// Shear branch `|τ| ≥ max(σ_n, 0) μ_s + c_s` at this tip: μ_s and
    /// c_s (Pa); `None` where the branch does not apply (the default
    /// envelope at an open tip).
    pub shear_envelope: Option<(f64, f64)>,
}

impl Simulation {
    /// SIFs and criterion at every free tip after the last solve.
    pub fn tips(&self) -> &[TipReport] {
        &self.scratch.tips
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

    /// σ_xx, σ_yy, τ_xy of the current iterate at a point, Pa: the
    /// solution after a solve, during a relaxation the displacement of its
    /// last chunk of sweeps (None outside the specimen).
    pub fn current_stress_at(&self, p: [f64; 2]) -> Option<[f64; 3]> {
        self.current_field().stress_at(P2::new(p[0], p[1]))
    }

    /// Displacement of the current iterate at a point, m (see
    /// [`current_stress_at`](Self::current_stress_at)).
    pub fn current_displacement_at(&self, p: [f64; 2]) -> Option<[f64; 2]> {
        self.current_field()
            .at(P2::new(p[0], p[1]))
            .map(|v| [v.u.x, v.u.y])
    }

    fn current_field(&self) -> Field<'_> {
        Field {
            xfem: &self.scratch.xfem,
            u: &self.state.u,
        }
    }

    /// Whether a resumable solve is under way (started and not finished):
    /// the displacement is then an iterate, not a solution.
    pub fn is_relaxing(&self) -> bool {
        self.scratch.job.is_some()
    }

    /// Whether the displacement is an iterate worth showing as a field: a
    /// solve under way whose linear solver iterates (the automaton, CG)
    /// has made at least one iteration. Otherwise, while a solve is under
    /// way, it is no field: before the first iteration it is the start
    /// (zero after a rebuild: a field of exact zeros), and a solver that
    /// keeps a factor (the direct one) takes Newton steps whose working
    /// vector is exact on the faces' DOFs and on the rows their solves
    /// reach, and keeps the iterate before elsewhere (zero after a
    /// rebuild: stresses of GPa along the nested dissection's separators).
    pub fn has_live_iterate(&self) -> bool {
        !self.scratch.solver.keeps_factor()
            && self
                .scratch
                .job
                .as_ref()
                .is_some_and(|j| j.reached().history.iter().any(|s| s.iteration > 0))
    }

    /// While a new discretisation (after a growth step, or a new
    /// simulation's) is being prepared across calls (see
    /// [`advance_growth`](Self::advance_growth), [`relax`](Self::relax)):
    /// the fraction done, in [0, 1), counting the stiffness integration of
    /// the changed elements as one part, the direct solver's pattern as
    /// another, and each free tip's interaction-integral domain as one.
    pub fn rebuild_progress(&self) -> Option<f64> {
        let x = &self.scratch.xfem;
        let left = x.points_to_integrate();
        let integrated = 1.0 - left as f64 / self.scratch.rebuild_points.max(left).max(1) as f64;
        let pattern = self.model.scene.solver.kind == SolverKind::Direct;
        let pattern_made = pattern && x.has_pattern();
        let (made, tips) = TipDomains::progress(self.scratch.tip_domains.as_ref(), x);
        let parts = 1 + usize::from(pattern) + tips;
        let done = integrated + f64::from(u8::from(pattern_made)) + made as f64;
        (done < parts as f64).then(|| done / parts as f64)
    }

    /// Crack-face contact points with their state and tractions: those of
    /// the current contact iteration while a relaxation runs, else those of
    /// the last solve.
    pub fn contact_points(&self) -> Vec<ContactPointView> {
        let states = self
            .scratch
            .job
            .as_ref()
            .map_or(&self.state.faces[..], |j| &j.reached().states[..]);
        self.scratch
            .xfem
            .faces
            .iter()
            .zip(states)
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

    /// σ_θθ and τ_rθ around tip `index` of `tips()`; `None` for MTS, which
    /// reads no circle.
    pub fn criterion_curve(&self, index: usize) -> Option<CriterionCurve> {
        // MTS reads no circle
        let c = self
            .scratch
            .circles
            .get(index)
            .filter(|c| !c.theta.is_empty())?;
        let tip = self.scratch.tips.get(index)?;
        let lengths = system_lengths(&self.scratch.xfem.funcs.cracks);
        let p = self.criterion_params().for_crack(*lengths.get(tip.crack)?);
        let faces = *self.scratch.tip_faces.get(index)?;
        Some(CriterionCurve {
            theta_deg: c.theta.iter().map(|t| t.to_degrees()).collect(),
            sigma_tt: c.sigma_tt.clone(),
            tau_rt: c.tau_rt.clone(),
            sigma_t: p.sigma_t,
            r0: p.r0,
            shear_envelope: p.shear_envelope(faces),
        })
    }
}
