//! A whole growth run (SPEC §9, §11): growth steps until the run ends, and
//! the run's report: the history, how it ended, the first link between two
//! flaws, and the specimen's strength against the intact rock's. The CLI's
//! `grow`, its `study` and the workbench report a run through this one
//! place.

use super::state::Simulation;
use crate::error::SolveError;
use crate::geometry::cracks::root;
use crate::report::{
    CoalescenceReport, GrowReport, GrowthStepReport, LinkReport, LoadCapReport, Outcome,
    StrengthReport,
};
use crate::scene::Lineage;
use crate::scene::SideBc;

impl Simulation {
    /// Grows until the run ends ([`grow_step`](Self::grow_step) in a loop),
    /// or until a step fails: then the report holds the steps before it,
    /// outcome `error` and the message naming the step, and the error is
    /// returned too (for an exit code).
    pub fn grow_to_end(&mut self) -> (GrowReport, Option<SolveError>) {
        self.grow_with(|sim| sim.grow_step().map(drop))
    }

    /// [`grow_to_end`](Self::grow_to_end) with `step` as the growth step.
    fn grow_with(
        &mut self,
        mut step: impl FnMut(&mut Self) -> Result<(), SolveError>,
    ) -> (GrowReport, Option<SolveError>) {
        let mut failed = None;
        let outcome = loop {
            if let Some(outcome) = self.growth_finished() {
                break outcome;
            }
            if let Err(e) = step(self) {
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
            strength: self.strength(outcome),
            start_limit: self.state.start_limit.clone(),
        }
    }

    /// Under critical control, a run ended `completed`: the λ_cr search
    /// reached `growth.max_load_factor` with no free tip meeting its
    /// criterion, so the cap stopped it.
    pub fn load_cap(&self) -> Option<LoadCapReport> {
        (self.critical_control() && self.state.outcome == Some(Outcome::Completed))
            .then(|| LoadCapReport::at(self.model.scene.growth.max_load_factor))
    }

    /// The first link between two flaws in the run, if any (the steps of
    /// a run this scene resumes included): directly, or through cracks
    /// started in the intact rock (the flaws named are the lowest-numbered
    /// drawn flaw on either side).
    pub fn coalescence(&self) -> Option<CoalescenceReport> {
        let history: Vec<&GrowthStepReport> = self.run_steps().collect();
        history.iter().enumerate().find_map(|(k, s)| {
            let i = s.links.iter().position(|l| l.coalescence)?;
            let l = &s.links[i];
            // what a crack started in the intact rock linked first in the
            // step counts (see `Simulation::link`)
            let same_step = if self.state.lineage[l.crack].is_intact() {
                &s.links[..i]
            } else {
                &[]
            };
            let before = history[..k].iter().flat_map(|s| &s.links);
            let mut groups = Groups::linked(&self.state.lineage, before.chain(same_step));
            Some(CoalescenceReport {
                step: s.step,
                load_factor: s.load_factor,
                category: l.category(),
                flaws: groups.coalesce(l.flaws).unwrap_or(l.flaws),
            })
        })
    }

    /// The specimen's strength so far ([`peak`](Self::peak)) against the
    /// uncracked specimen's ([`intact_load_factor`](Self::intact_load_factor)),
    /// for a run that ended (or stands) with `outcome`: the note says when
    /// the peak is only a bound (a run that reached its load or the load
    /// cap without failing) or the run stopped early.
    pub fn strength(&self, outcome: Outcome) -> Option<StrengthReport> {
        let mut s = self.peak()?;
        let (intact, why) = self.intact_load_factor();
        s.intact_load_factor = intact;
        s.ratio = intact.map(|l| s.peak_load_factor / l);
        let peak = format!(
            "{:.1} MPa (λ = {:.4} at step {})",
            s.peak_stress / 1e6,
            s.peak_load_factor,
            s.peak_step
        );
        let against = s.ratio.map_or_else(
            || why.clone(),
            |r| format!("{:.1}% of the intact rock's: {why}", 100.0 * r),
        );
        s.note = match outcome {
            Outcome::Through | Outcome::Unstable => format!("specimen strength {peak}, {against}"),
            Outcome::Completed => {
                let reached = if self.critical_control() {
                    self.model.scene.growth.max_load_factor
                } else {
                    1.0
                };
                format!(
                    "the specimen did not fail up to λ = {reached} ({:.1} MPa): its strength \
                     is above that; the largest load at which a crack grew {peak}, {against}",
                    reached * s.reference_stress / 1e6
                )
            }
            Outcome::MaxSteps => format!(
                "the run stopped at growth.max_steps before the specimen failed: the peak so \
                 far {peak}, {against}"
            ),
            Outcome::NotConverged | Outcome::Error => {
                format!("the run stopped early (a step failed): the peak so far {peak}, {against}")
            }
        };
        Some(s)
    }

    /// The specimen's strength so far: the peak of the recorded load
    /// factors over the steps in which something grew or started (the
    /// last record of a run stopped at the load cap grew nothing; the steps
    /// of a run this scene resumes included), as in a load-controlled
    /// test; `None` before any such step.
    pub fn peak(&self) -> Option<StrengthReport> {
        let peak = self
            .run_steps()
            .filter(|s| !(s.grown.is_empty() && s.started.is_empty() && s.nucleated.is_empty()))
            .fold(None, |best: Option<&GrowthStepReport>, s| match best {
                Some(b) if b.load_factor >= s.load_factor => Some(b),
                _ => Some(s),
            })?;
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

/// The crack groups of a run linked by its links so far: a group is a
/// drawn flaw with what grew from it, or a crack started in the intact rock
/// with what grew from it ([`Lineage::flaw`] names it), as a union–find
/// forest over group indices.
pub(super) struct Groups<'a> {
    lineage: &'a [Lineage],
    parent: Vec<usize>,
}

impl<'a> Groups<'a> {
    /// The groups of `lineage` joined by `links`.
    pub(super) fn linked<'b>(
        lineage: &'a [Lineage],
        links: impl Iterator<Item = &'b LinkReport>,
    ) -> Self {
        let mut parent: Vec<usize> = (0..lineage.len()).collect();
        for l in links {
            let (a, b) = (root(&mut parent, l.flaws[0]), root(&mut parent, l.flaws[1]));
            parent[a] = b;
        }
        Self { lineage, parent }
    }

    /// The lowest-numbered drawn flaw linked with group `g`, if any.
    fn drawn_flaw(&mut self, g: usize) -> Option<usize> {
        let r = root(&mut self.parent, g);
        (0..self.lineage.len()).find(|&i| {
            self.lineage[i].drawn > 0 && self.lineage[i].flaw == i && root(&mut self.parent, i) == r
        })
    }

    /// Whether a link between groups `flaws` is a coalescence, two drawn
    /// flaws not linked before now linked (through cracks started in the
    /// intact rock, perhaps): the lowest-numbered drawn flaw on either
    /// side, or `None`.
    pub(super) fn coalesce(&mut self, flaws: [usize; 2]) -> Option<[usize; 2]> {
        if root(&mut self.parent, flaws[0]) == root(&mut self.parent, flaws[1]) {
            return None;
        }
        Some([self.drawn_flaw(flaws[0])?, self.drawn_flaw(flaws[1])?])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// A step that fails ends growth with the steps before it in the
    /// report: the first two steps of the bundled single flaw (40 × 40),
    /// equal to those of an uninterrupted run (time aside), outcome
    /// `error`, and the message naming step 3; the error is handed back
    /// for the exit code.
    #[test]
    fn a_failing_step_keeps_the_steps_before_it() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/scenes/specimen_single_flaw.json"
        );
        let text = std::fs::read_to_string(path).expect("bundled scene");
        let mut file = Scene::from_json(&text).expect("valid").into_file();
        file.mesh.nx = 40;
        file.mesh.ny = 40;
        file.growth.max_steps = 3;
        let scene = Scene::try_from(file).expect("valid");
        let untimed = |steps: &[GrowthStepReport]| -> Vec<GrowthStepReport> {
            steps.iter().map(GrowthStepReport::untimed).collect()
        };
        let mut sim = Simulation::new(scene.clone()).expect("solvable");
        let (reference, failed) = sim.grow_to_end();
        assert!(failed.is_none() && reference.error.is_none());
        assert_eq!(
            (reference.outcome, reference.steps.len()),
            (Outcome::MaxSteps, 3)
        );

        let mut sim = Simulation::new(scene).expect("solvable");
        let (report, failed) = sim.grow_with(|sim| {
            if sim.history().len() == 2 {
                Err(SolveError::NotPositiveDefinite {
                    dofs: 7,
                    detail: "NonPositivePivot { index: 6 }".to_owned(),
                })
            } else {
                sim.grow_step().map(drop)
            }
        });
        assert!(matches!(
            failed,
            Some(SolveError::NotPositiveDefinite { dofs: 7, .. })
        ));
        assert_eq!(report.outcome, Outcome::Error);
        assert_eq!(untimed(&report.steps), untimed(&reference.steps[..2]));
        let json = serde_json::to_value(&report).expect("JSON");
        assert_eq!(json["outcome"], "error");
        assert_eq!(json["steps"].as_array().map(Vec::len), Some(2));
        assert_eq!(
            json["error"],
            "step 3: stiffness matrix is not positive definite (7 DOFs): \
             NonPositivePivot { index: 6 }"
        );
        // a run that ends normally has no `error` field
        let json = serde_json::to_value(&reference).expect("JSON");
        assert!(json.get("error").is_none());
    }
}
