//! A whole growth run (SPEC §9, §11): growth steps until the run ends, and
//! the run's report: the history, how it ended, the first link between two
//! flaws, and the specimen's strength against the intact rock's. The CLI's
//! `grow`, its `study` and the workbench report a run through this one
//! place.

use super::state::Simulation;
use crate::error::SolveError;
use crate::report::{CoalescenceReport, GrowReport, LoadCapReport, Outcome, StrengthReport};
use crate::scene::SideBc;

impl Simulation {
    /// Grows until the run ends ([`grow_step`](Self::grow_step) in a loop),
    /// or until a step fails: then the report holds the steps before it,
    /// outcome `error` and the message naming the step, and the error is
    /// returned too (for an exit code).
    pub fn grow_to_end(&mut self) -> (GrowReport, Option<SolveError>) {
        let mut failed = None;
        let outcome = loop {
            if let Some(outcome) = self.growth_finished() {
                break outcome;
            }
            if let Err(e) = self.grow_step() {
                failed = Some(e);
                break Outcome::Error;
            }
        };
        let report = self.grow_report(outcome, failed.as_ref());
        (report, failed)
    }

    /// The report of the run so far, ended with `outcome` (and `error`,
    /// when a step failed with one).
    pub fn grow_report(&self, outcome: Outcome, error: Option<&SolveError>) -> GrowReport {
        // the scene's `growth.resume.steps` counts the steps done, this
        // run's and any before it
        let next = self.steps_done() + 1;
        GrowReport {
            steps: self.history().to_vec(),
            outcome,
            cracks: self.cracks(),
            error: error.map(|e| format!("step {next}: {e}")),
            load_cap: self.load_cap(),
            coalescence: self.coalescence(),
            strength: self.peak(),
            start_limit: None,
        }
    }

    /// Under critical control, a run ended `completed`: the λ_cr search
    /// reached `growth.max_load_factor` with no free tip meeting its
    /// criterion, so the cap stopped it.
    pub fn load_cap(&self) -> Option<LoadCapReport> {
        (self.critical_control() && self.state.outcome == Some(Outcome::Completed))
            .then(|| LoadCapReport::at(self.model.scene.growth.max_load_factor))
    }

    /// The first link between two flaws in this run's history, if any.
    pub fn coalescence(&self) -> Option<CoalescenceReport> {
        self.state.history.iter().find_map(|s| {
            s.links
                .iter()
                .find(|l| l.coalescence)
                .map(|l| CoalescenceReport {
                    step: s.step,
                    load_factor: s.load_factor,
                    category: l.category(),
                    flaws: l.flaws,
                })
        })
    }

    /// The specimen's strength so far: the peak of the recorded load
    /// factors over the steps in which something grew or started (the
    /// last record of a run stopped at the load cap grew nothing), as in a
    /// load-controlled test; `None` before any such step.
    pub fn peak(&self) -> Option<StrengthReport> {
        let peak = self
            .state
            .history
            .iter()
            .filter(|s| !(s.grown.is_empty() && s.started.is_empty() && s.nucleated.is_empty()))
            .fold(
                None,
                |best: Option<&crate::report::GrowthStepReport>, s| match best {
                    Some(b) if b.load_factor >= s.load_factor => Some(b),
                    _ => Some(s),
                },
            )?;
        let reference = self.reference_stress();
        Some(StrengthReport {
            peak_step: peak.step,
            peak_load_factor: peak.load_factor,
            reference_stress: reference,
            peak_stress: peak.load_factor * reference,
            intact_load_factor: None,
            ratio: None,
            note: String::new(),
        })
    }

    /// The scene's reference stress: the largest magnitude of a side's
    /// normal traction, Pa (0 with no traction side).
    pub fn reference_stress(&self) -> f64 {
        let b = &self.model.scene.boundary;
        [b.bottom, b.left, b.top, b.right]
            .iter()
            .map(|s| match s {
                SideBc::Traction { normal, .. } => normal.abs(),
                _ => 0.0,
            })
            .fold(0.0, f64::max)
    }
}
