//! The screen says what the run did (issue 65): each sentence checked
//! against the run's own report, on the bundled stepped pair, whose
//! default run starts every crack in the intact rock and grows no flaw
//! tip. They drive the solver: run them with `--release`.

use cdca_workbench::state::command::Command;
use cdca_workbench::{Options, PlotTab, WorkbenchApp};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

#[path = "support/harness.rs"]
mod support;
use support::{harness, open_bundled, run_until_paused};

/// The stepped pair, grown to its end.
fn stepped_pair_run() -> Harness<'static, WorkbenchApp> {
    let mut h = harness(Options::default());
    h.run_steps(3);
    run_until_paused(&mut h, 2000);
    open_bundled(&mut h, "specimen_two_flaws_stepped.json");
    h.state_mut().push(Command::RunGrowth);
    h.run_steps(2);
    run_until_paused(&mut h, 20_000);
    h.run_steps(3);
    h
}

/// The labels on screen that contain `text`.
fn labels(h: &Harness<'_, WorkbenchApp>, text: &str) -> Vec<String> {
    // a label's text is its AccessKit value, another widget's its label
    h.query_all_by_label_contains(text)
        .filter_map(|n| {
            let node = n.accesskit_node();
            node.value().or_else(|| node.label())
        })
        .collect()
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_stepped_pairs_run_is_told_as_it_happened() {
    let mut h = stepped_pair_run();
    let history = h.state().growth_history().to_vec();
    let rock: usize = history.iter().map(|s| s.nucleated.len()).sum();
    let flaw_grew = history.iter().any(|s| s.grown.iter().any(|g| g.crack < 2));
    eprintln!(
        "{} steps, {rock} rock cracks, a flaw tip grew: {flaw_grew}",
        history.len()
    );
    assert!(
        rock > 0 && !flaw_grew,
        "the default run of the stepped pair"
    );

    // the Angles tab: no "every tip stayed below its criterion" while
    // cracks started at every step
    h.state_mut().push(Command::ShowPlot(PlotTab::Angles));
    h.run_steps(2);
    let tip_grew = history.iter().any(|s| !s.grown.is_empty());
    if tip_grew {
        assert!(labels(&h, "No tip").is_empty());
    } else {
        let said = format!("the run started {rock} cracks in the intact rock instead");
        assert_eq!(labels(&h, &said).len(), 1, "{:?}", labels(&h, "No tip"));
        assert!(labels(&h, "every tip stayed below its criterion").is_empty());
    }

    // the intact rock's strength: one λ, the uncracked specimen's, and the
    // median as a utilisation
    let intact = h
        .state()
        .strength()
        .and_then(|s| s.intact_load_factor)
        .expect("the uncracked specimen fails");
    let said = format!("The uncracked specimen reaches its strength at λ = {intact:.3}");
    assert_eq!(
        labels(&h, &said).len(),
        1,
        "{:?}",
        labels(&h, "Intact rock")
    );
    assert!(labels(&h, "median reaches the strength at λ").is_empty());

    // the story: its events in time order, the ending last
    let story = h.state().run_story().expect("the run ended");
    let steps: Vec<usize> = story
        .lines
        .iter()
        .filter_map(|l| {
            let at = l.find("step ")? + 5;
            l[at..]
                .split(|c: char| !c.is_ascii_digit())
                .next()?
                .parse()
                .ok()
        })
        .collect();
    eprintln!("story: {:#?}, steps {steps:?}", story.lines);
    assert!(steps.len() >= 3, "{story:?}");
    assert!(steps.is_sorted(), "out of time order: {steps:?}");
    assert!(story.lines.last().is_some_and(|l| l.contains("failed")));

    // the replay's tip inspector names the cracks as they were then: two
    // steps after the first rock crack (the end's names used to show)
    let first = history
        .iter()
        .find(|s| !s.nucleated.is_empty())
        .expect("a rock crack")
        .step
        + 2;
    h.state_mut().push(Command::Replay(Some(first)));
    h.run_steps(3);
    assert_eq!(
        labels(&h, &format!("Replaying step {first}: the free tips")).len(),
        1
    );
    let existing: usize = history
        .iter()
        .filter(|s| s.step <= first)
        .map(|s| s.nucleated.len())
        .sum();
    // the inspector's rows ("Rock crack 2, end 1"; the replay's marks name
    // every step's cracks, as they should)
    let rows: Vec<String> = labels(&h, "Rock crack ")
        .into_iter()
        .filter(|l| l.contains(", end "))
        .collect();
    eprintln!("replayed tips: {rows:?}");
    assert!(!rows.is_empty(), "the rock cracks' tips at step {first}");
    for label in rows {
        let Some(n) = label
            .split("Rock crack ")
            .skip(1)
            .filter_map(|t| {
                t.split(|c: char| !c.is_ascii_digit())
                    .next()?
                    .parse::<usize>()
                    .ok()
            })
            .max()
        else {
            continue; // words about rock cracks, no name
        };
        assert!(
            n <= existing,
            "{label} at step {first}, when {existing} existed"
        );
    }
}

/// The default scene's first screen: a state the rock carries (the
/// bundled specimens' reference load is 50 MPa), and the intact rock's
/// median as a utilisation, not as a second λ of its strength.
#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "the solver is slow without optimisation: run with --release"
)]
fn the_first_screen_shows_a_load_the_rock_carries() {
    let mut h = harness(Options::default());
    h.run_steps(3);
    run_until_paused(&mut h, 2000);
    h.run_steps(2);
    let said = labels(&h, "Intact rock:");
    eprintln!("{said:?}");
    assert_eq!(said.len(), 1);
    assert!(said[0].contains("× strength") && !said[0].contains("reaches the strength at λ"));
    let median: f64 = said[0]
        .split("its median at ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .expect("the median's utilisation");
    assert!(median < 1.0, "the first screen's rock is past its strength");
}
