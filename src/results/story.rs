//! How a growth run ended, in the UI's words: why it stopped, which flaws
//! linked through which cracks and at what load, the specimen's strength
//! against the intact rock's, and when the wings, secondary cracks and
//! cracks in the intact rock first started. Cracks are named as the Scene
//! panel names them (`SolutionView::crack_name`), loads as λ and as the
//! stress λ times the scene's reference stress.

use cdca::report::{GrowthStepReport, Mode, Outcome};
use cdca::scene::{GrowthControl, SceneFile, SideBc};

use crate::results::solution::SolutionView;
use crate::style::units;

/// The end of a run as sentences, and whether it went wrong (a solve that
/// did not converge or failed: only then the warning colour).
#[derive(Clone, Debug, PartialEq)]
pub struct Story {
    pub lines: Vec<String>,
    pub went_wrong: bool,
}

/// The story of the run `view` holds, once it has ended.
pub fn story(view: &SolutionView, scene: &SceneFile) -> Option<Story> {
    let outcome = view.outcome?;
    let reference = reference_stress(scene);
    let at = |s: &GrowthStepReport| {
        format!(
            "step {} (λ = {:.3}, {})",
            s.step,
            s.load_factor,
            units::mpa(s.load_factor * reference)
        )
    };
    // the events in the order they happened (a tie keeps this order: the
    // first cracks, the link, the peak), then how the run ended
    let mut events: Vec<(usize, String)> = firsts(view, &at);
    let flaws = view.lineage.iter().filter(|l| l.drawn > 0).count();
    if let Some(c) = &view.coalescence {
        let step = view.history.iter().find(|s| s.step == c.step);
        events.push((
            c.step,
            format!(
                "Crack {} and Crack {} linked at {}, {} meeting {}.",
                c.flaws[0] + 1,
                c.flaws[1] + 1,
                step.map_or_else(|| format!("step {}", c.step), &at),
                article(c.category.split('–').next().unwrap_or("crack")),
                article(c.category.split('–').nth(1).unwrap_or("crack")),
            ),
        ));
    }
    if let Some(s) = &view.strength {
        let of_rock = s.ratio.map_or_else(String::new, |r| {
            format!(", {:.0} % of the intact rock's", 100.0 * r)
        });
        events.push((
            s.peak_step,
            format!(
                "Peak at step {}: specimen strength {}{of_rock}.",
                s.peak_step,
                units::mpa(s.peak_stress)
            ),
        ));
    }
    events.sort_by_key(|(step, _)| *step);
    let mut lines: Vec<String> = untold(view).into_iter().collect();
    lines.extend(events.into_iter().map(|(_, line)| line));
    if view.coalescence.is_none() && flaws >= 2 {
        lines.push("The flaws did not link.".to_owned());
    }
    lines.push(ending(view, scene, outcome, &at));
    Some(Story {
        lines,
        went_wrong: matches!(outcome, Outcome::NotConverged | Outcome::Error),
    })
}

/// Why the run stopped, with the last step's load.
fn ending(
    view: &SolutionView,
    scene: &SceneFile,
    outcome: Outcome,
    at: &dyn Fn(&GrowthStepReport) -> String,
) -> String {
    let last = view.history.last();
    let when = last.map_or_else(String::new, |s| format!(" at {}", at(s)));
    let g = &scene.growth;
    match outcome {
        Outcome::Through => format!("The cracks ran through the specimen{when}: it failed."),
        Outcome::Unstable if last.is_some_and(|s| !s.nucleated.is_empty()) => format!(
            "The specimen failed{when}: cracks started in the intact rock at a load that no \
             longer rises."
        ),
        Outcome::Unstable => format!(
            "The specimen failed{when}: a crack grew on at one load for {} steps \
             (growth.max_growth_per_step), unstable growth.",
            g.max_growth_per_step
        ),
        Outcome::Completed if g.control == GrowthControl::Critical => format!(
            "No crack grows below λ = {} (growth.max_load_factor): the specimen carries at \
             least {}.",
            g.max_load_factor,
            units::mpa(g.max_load_factor * reference_stress(scene))
        ),
        Outcome::Completed => format!(
            "All {} load steps applied: the specimen carries the scene's load.",
            g.load_steps
        ),
        Outcome::MaxSteps => format!(
            "Stopped after {} steps (growth.max_steps){when}, before the specimen failed.",
            g.max_steps
        ),
        Outcome::NotConverged => {
            let why = view.history.iter().rev().find_map(|s| s.failure.clone());
            format!(
                "Stopped{when}: a solve did not converge{}.",
                why.map_or_else(String::new, |w| format!(" ({w})"))
            )
        }
        Outcome::Error => "Stopped: a step's solve failed with an error.".to_owned(),
    }
}

/// The steps before the first one the view holds: those of a run saved
/// in a scene file without their history (`growth.resume.history`, which
/// older versions did not write), which the story cannot tell.
fn untold(view: &SolutionView) -> Option<String> {
    let first = view.history.first()?.step;
    let steps = match first {
        0 | 1 => return None,
        2 => "Step 1".to_owned(),
        _ => format!("Steps 1–{}", first - 1),
    };
    Some(format!(
        "{steps} ran before this scene was saved, in a file without their history \
         (growth.resume.history): the story, the peak and the link are told from step \
         {first} on."
    ))
}

/// The first wing, secondary crack and crack in the intact rock (those the
/// run had), each with its step.
fn firsts(view: &SolutionView, at: &dyn Fn(&GrowthStepReport) -> String) -> Vec<(usize, String)> {
    let drawn = |c: usize| view.lineage.get(c).is_some_and(|l| l.drawn > 0);
    let h = &view.history;
    let wing = h.iter().find(|s| {
        s.grown
            .iter()
            .any(|g| g.mode == Mode::Tension && drawn(g.crack))
    });
    let secondary = h.iter().find(|s| {
        !s.started.is_empty()
            || s.grown
                .iter()
                .any(|g| g.mode == Mode::Shear && drawn(g.crack))
    });
    let rock = h.iter().find(|s| !s.nucleated.is_empty());
    [
        ("wing", wing),
        ("secondary crack", secondary),
        ("crack in the intact rock", rock),
    ]
    .into_iter()
    .filter_map(|(what, s)| {
        let s = s?;
        Some((s.step, format!("First {what} at {}.", at(s))))
    })
    .collect()
}

/// "a wing", "a secondary crack", "a flaw", "a crack started in the
/// intact rock" for a part's name in a link category.
fn article(part: &str) -> String {
    match part {
        "intact" => "a crack started in the intact rock".to_owned(),
        "secondary" => "a secondary crack".to_owned(),
        other => format!("a {other}"),
    }
}

/// The scene's reference stress: the largest magnitude of a side's normal
/// traction, Pa (λ times it is the load shown; 0 without a traction side),
/// as the report's `strength.reference_stress`.
pub fn reference_stress(scene: &SceneFile) -> f64 {
    let b = &scene.boundary;
    [&b.bottom, &b.left, &b.top, &b.right]
        .into_iter()
        .map(|s| match s {
            SideBc::Traction { normal, .. } => normal.abs(),
            _ => 0.0,
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cdca::report::{CoalescenceReport, GrownTip, StrengthReport};
    use cdca::scene::Lineage;

    fn step(step: usize, load_factor: f64, grown: Vec<GrownTip>) -> GrowthStepReport {
        GrowthStepReport {
            step,
            load_factor,
            grown,
            ..GrowthStepReport::default()
        }
    }

    /// A two-flaw run that ends through, linked by a wing at step 2: the
    /// story names both cracks as the Scene panel does, the link's load in
    /// λ and MPa (λ × 50 MPa), the peak against the intact rock's, and
    /// the first wing; nothing in it is a warning.
    #[test]
    fn a_linked_pair_reads_as_a_story() {
        let scene = crate::files::scenes::default_scene();
        let wing = GrownTip {
            crack: 0,
            mode: Mode::Tension,
            ..GrownTip::default()
        };
        let view = SolutionView {
            outcome: Some(Outcome::Through),
            lineage: vec![Lineage::drawn(0, 2), Lineage::drawn(1, 2)],
            history: vec![step(1, 0.4, vec![wing.clone()]), step(2, 0.5, vec![wing])],
            coalescence: Some(CoalescenceReport {
                step: 2,
                load_factor: 0.5,
                category: "wing–flaw".to_owned(),
                flaws: [0, 1],
            }),
            strength: Some(StrengthReport {
                peak_step: 2,
                peak_load_factor: 0.5,
                reference_stress: 50e6,
                peak_stress: 50e6,
                intact_load_factor: Some(0.8),
                ratio: Some(0.625),
                note: String::new(),
            }),
            ..SolutionView::default()
        };
        let s = story(&view, &scene).expect("the run ended");
        assert!(!s.went_wrong);
        assert_eq!(
            s.lines,
            [
                "First wing at step 1 (λ = 0.400, 20.00 MPa).",
                "Crack 1 and Crack 2 linked at step 2 (λ = 0.500, 25.00 MPa), a wing meeting a flaw.",
                "Peak at step 2: specimen strength 50.00 MPa, 62 % of the intact rock's.",
                "The cracks ran through the specimen at step 2 (λ = 0.500, 25.00 MPa): it failed.",
            ]
        );
    }
}
