//! A replay of the growth run: after a run, a step slider shows the
//! cracks, the contact states, the tips and the field at any step, and its
//! marks name the events (the first wing, each secondary crack, each crack
//! started in the intact rock, the link).
//!
//! Each step is stored as the run passes it, not solved again: the cracks,
//! contact points and tips are a few kB a step, and the field is the one
//! the canvas already sampled at the step's load (the run samples it
//! before the tips move on), kept rather than recomputed. On the default
//! 60 × 60 scene a field is 14 400 samples of 88 bytes, 1.3 MB a step,
//! about 18 MB for its 14 steps; solving a step again would need the
//! run replayed from its start (the discretisation changes every step),
//! seconds a step in the browser. Fields are kept for the last
//! [`FIELDS_KEPT`] steps; earlier steps replay their geometry only. A run
//! kept by Undo shares its steps' fields with the replay on screen.

use std::sync::Arc;

use cdca::report::{GrowthStepReport, Mode};

use crate::results::field::FieldSamples;
use crate::results::solution::SolutionView;

/// Steps whose sampled field is kept (about 130 MB at most on a 60 × 60
/// mesh); older steps keep their geometry and contact states.
pub const FIELDS_KEPT: usize = 100;

/// One step of the run as the canvas showed it after the step: the cracks
/// grown by it, and the contact states, tips and field of the solve at the
/// step's load (λ_cr under critical control).
#[derive(Clone)]
pub struct Snapshot {
    /// The step's number (as the reports number it).
    pub step: usize,
    /// What the canvas reads: cracks, their kinds, contact points, tips,
    /// the link once made, and the step's λ.
    pub view: SolutionView,
    /// The field sampled at the step's load, if it was sampled and is kept.
    pub field: Option<Arc<FieldSamples>>,
}

impl Snapshot {
    /// The canvas's part of `view` after its last step, with the contact
    /// points and tips of that step's solve (`at_load`, taken before the
    /// tips moved on) and `field` if it was sampled at the step's load.
    pub fn of(
        view: &SolutionView,
        at_load: Option<&AtLoad>,
        field: Option<&FieldSamples>,
    ) -> Option<Self> {
        let last = view.history.last()?;
        let at_load = at_load.filter(|a| a.load_factor == last.load_factor);
        let linked = view.coalescence.as_ref().filter(|c| c.step <= last.step);
        let field = field
            .filter(|f| f.load_factor == last.load_factor)
            .map(|f| Arc::new(f.clone()));
        Some(Self {
            step: last.step,
            view: SolutionView {
                solved: true,
                cracks: view.cracks.clone(),
                secondary: view.secondary.clone(),
                intact: view.intact.clone(),
                lineage: view.lineage.clone(),
                tips: at_load.map(|a| a.tips.clone()).unwrap_or_default(),
                contact: at_load.map(|a| a.contact.clone()).unwrap_or_default(),
                load_factor: last.load_factor,
                coalescence: linked.cloned(),
                junction: linked.and(view.junction),
                ..SolutionView::default()
            },
            field,
        })
    }
}

/// The contact points and tips of a step's solve at its load, kept until
/// the step is recorded (by then the tips have moved and the view holds
/// neither).
#[derive(Clone)]
pub struct AtLoad {
    pub load_factor: f64,
    pub contact: Vec<cdca::ContactPointView>,
    pub tips: Vec<cdca::report::TipReport>,
}

/// The run's steps as stored for the replay.
#[derive(Clone, Default)]
pub struct Replay {
    pub snapshots: Vec<Snapshot>,
    at_load: Option<AtLoad>,
}

impl Replay {
    pub fn clear(&mut self) {
        *self = Self::default();
    }

    /// After a growth slice: keeps what a solve at the step's load shows
    /// (`at_step_load`), and stores a snapshot once the view's history has
    /// a step the replay has not.
    pub fn record(
        &mut self,
        view: &SolutionView,
        at_step_load: bool,
        field: Option<&FieldSamples>,
    ) {
        if at_step_load && view.solved {
            self.at_load = Some(AtLoad {
                load_factor: view.load_factor,
                contact: view.contact.clone(),
                tips: view.tips.clone(),
            });
        }
        let newest = view.history.last().map(|s| s.step);
        if newest.is_none() || newest == self.snapshots.last().map(|s| s.step) {
            return;
        }
        if let Some(s) = Snapshot::of(view, self.at_load.as_ref(), field) {
            self.snapshots.push(s);
        }
        let n = self.snapshots.len();
        if n > FIELDS_KEPT {
            self.snapshots[n - 1 - FIELDS_KEPT].field = None;
        }
    }

    /// The snapshot of step `step`, if the replay has it.
    pub fn at(&self, step: usize) -> Option<&Snapshot> {
        self.snapshots.iter().find(|s| s.step == step)
    }
}

/// An event of the run, for a mark of the slider.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    pub step: usize,
    pub text: String,
}

/// The events of `history`: the first wing, each secondary crack, each
/// crack started in the intact rock, and the first link between flaws
/// (`link_step`), in step order.
pub fn marks(
    history: &[GrowthStepReport],
    view: &SolutionView,
    link_step: Option<usize>,
) -> Vec<Mark> {
    let drawn = |c: usize| view.lineage.get(c).is_some_and(|l| l.drawn > 0);
    let mut out = Vec::new();
    if let Some(s) = history.iter().find(|s| {
        s.grown
            .iter()
            .any(|g| g.mode == Mode::Tension && drawn(g.crack))
    }) {
        out.push(Mark {
            step: s.step,
            text: "first wing".to_owned(),
        });
    }
    for s in history {
        for c in &s.started {
            out.push(Mark {
                step: s.step,
                text: view.crack_name(c.crack),
            });
        }
        if !s.nucleated.is_empty() {
            let names: Vec<String> = s
                .nucleated
                .iter()
                .map(|n| view.crack_name(n.crack))
                .collect();
            out.push(Mark {
                step: s.step,
                text: if names.len() > 2 {
                    format!("{} rock cracks", names.len())
                } else {
                    names.join(", ")
                },
            });
        }
    }
    if let Some(step) = link_step {
        out.push(Mark {
            step,
            text: "link".to_owned(),
        });
    }
    out.sort_by_key(|m| m.step);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdca::report::{GrownTip, NucleatedCrack, StartedCrack};
    use cdca::scene::Lineage;

    /// The marks name the first wing (a flaw's tip in tension), a
    /// secondary crack and a crack started in the intact rock by the
    /// Scene panel's names, and the link, in step order.
    #[test]
    fn the_marks_name_the_events() {
        let view = SolutionView {
            lineage: vec![
                Lineage::drawn(0, 2),
                Lineage::drawn(1, 2),
                Lineage {
                    ends: [cdca::scene::Part::Secondary; 2],
                    ..Lineage::intact(0)
                },
                Lineage::intact(3),
            ],
            ..SolutionView::default()
        };
        let step = |step: usize| GrowthStepReport {
            step,
            ..GrowthStepReport::default()
        };
        let mut history = vec![step(1), step(2), step(3), step(4)];
        history[0].grown.push(GrownTip {
            crack: 1,
            mode: Mode::Tension,
            ..GrownTip::default()
        });
        history[1].started.push(StartedCrack {
            crack: 2,
            ..StartedCrack::default()
        });
        history[2].nucleated.push(NucleatedCrack {
            crack: 3,
            ..NucleatedCrack::default()
        });
        let marks = marks(&history, &view, Some(4));
        let texts: Vec<(usize, &str)> = marks.iter().map(|m| (m.step, m.text.as_str())).collect();
        assert_eq!(
            texts,
            [
                (1, "first wing"),
                (2, "Crack 1 · secondary 1"),
                (3, "Rock crack 1"),
                (4, "link")
            ]
        );
    }
}
