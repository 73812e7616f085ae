//! One solve at the current load factor: the contact iteration around the
//! scene's linear solver (SPEC §5–6), then every free tip evaluated (SIFs
//! and criterion, SPEC §7–8), and the solve report (SPEC §11).

use web_time::Instant;

use super::state::Simulation;
use crate::contact::law::{FaceState, counts};
use crate::error::SolveError;
use crate::fracture::rock::{RockStrength, intact_rock};
use crate::fracture::tips::evaluate_tips;
use crate::report::{ContactReport, IntactRockReport, SolveReport, SolverReport};

impl Simulation {
    /// Full solve (with contact) at the current load factor with the scene's
    /// solver; fills SIFs and criterion at every free tip. The resumable
    /// solve of [`relax`](Self::relax), run to its end. Its `seconds` leave
    /// out the element integration of a new simulation (part of the build).
    pub fn solve(&mut self) -> Result<SolveReport, SolveError> {
        self.start_relaxation();
        self.scratch.xfem.integrate(usize::MAX);
        let start = Instant::now();
        while !self.relax(usize::MAX)?.finished {}
        Ok(SolveReport {
            intact_rock: self.intact_rock(),
            ..self.report(start.elapsed().as_secs_f64())
        })
    }

    /// The states the next contact iteration starts from: the guess left
    /// by the last critical-control trial, or the committed states.
    pub(super) fn initial_contact_states(&mut self) -> Vec<FaceState> {
        self.scratch
            .contact_guess
            .take()
            .filter(|g| g.len() == self.state.faces.len())
            .unwrap_or_else(|| self.state.faces.clone())
    }

    pub(super) fn evaluate(&mut self) {
        let e = evaluate_tips(
            &self.scratch.xfem,
            &self.state.u,
            &self.state.faces,
            &self.criterion_params(),
            self.model.scene.criterion_settings().sampling(),
        );
        self.scratch.tips = e.tips;
        self.scratch.circles = e.circles;
        self.scratch.tip_faces = e.faces;
        self.scratch.utilisation = e.utilisation;
    }

    /// The rock away from the cracks against its strength at the solved
    /// displacement; `None` while the state is not a solution of the
    /// current cracks, or for a rock without cohesion.
    pub fn intact_rock(&self) -> Option<IntactRockReport> {
        let x = &self.scratch.xfem;
        let strength = RockStrength::of_material(&self.model.scene.material)?;
        (self.state.solved && self.state.u.len() == x.n_free())
            .then(|| intact_rock(x, &self.state.u, &strength))
    }

    /// The report of the last solve (SPEC §11), `intact_rock` left at its
    /// default (see [`intact_rock`](Self::intact_rock)).
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
                violating: info.violating,
                residual: info.residual,
                capped: info.capped,
                unsettled: info.unsettled,
            },
            tips: self.scratch.tips.clone(),
            // filled where a solve is reported, not for every λ_cr trial
            intact_rock: None,
        }
    }
}
