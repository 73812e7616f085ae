//! What the workbench shows (the canvas's field, the tips' K) against a
//! headless simulation of the same state (shared by the UI tests).

use cdca::Simulation;
use cdca_workbench::WorkbenchApp;

/// Every `stride`-th cell of the canvas's field equals the stresses of
/// `headless` at the cell's centre, to 1e-9 of the largest stress shown;
/// at least `min_samples` cells inside the body are compared.
pub fn assert_shown_field_is(
    app: &WorkbenchApp,
    headless: &Simulation,
    stride: usize,
    min_samples: usize,
) {
    let scene = app.scene();
    let (nx, ny) = (scene.mesh.nx, scene.mesh.ny);
    let stresses = app.shown_stresses();
    let k = ((stresses.len() / (nx * ny)) as f64).sqrt() as usize;
    assert_eq!(stresses.len(), nx * ny * k * k, "a complete field");
    let (cols, rows) = (nx * k, ny * k);
    let (dx, dy) = (
        scene.specimen.width / cols as f64,
        scene.specimen.height / rows as f64,
    );
    let scale = stresses
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let mut compared = 0;
    for (i, s) in stresses.iter().enumerate().step_by(stride) {
        let p = [
            ((i % cols) as f64 + 0.5) * dx,
            ((i / cols) as f64 + 0.5) * dy,
        ];
        if let Some(t) = headless.stress_at(p) {
            for (a, b) in s.iter().zip(t) {
                assert!((a - b).abs() <= 1e-9 * scale, "at {p:?}: {s:?} vs {t:?}");
            }
            compared += 1;
        }
    }
    assert!(
        scale > 0.0 && compared > min_samples,
        "{compared} samples compared"
    );
}

/// The same K_I and K_II at every free tip, in the same order: to 1e-9 of
/// the largest |K| of `theirs` (the same direct solve from the same start;
/// only the summation order of a warm start could differ).
pub fn assert_same_sifs(
    ours: &[cdca::report::TipReport],
    theirs: &[cdca::report::TipReport],
    when: &str,
) {
    assert_eq!(ours.len(), theirs.len(), "{when}: free tips");
    let scale = theirs
        .iter()
        .map(|t| t.k1.abs().max(t.k2.abs()))
        .fold(0.0, f64::max);
    assert!(scale > 0.0, "{when}: loaded tips");
    for (a, b) in ours.iter().zip(theirs) {
        assert!(
            (a.k1 - b.k1).abs() <= 1e-9 * scale && (a.k2 - b.k2).abs() <= 1e-9 * scale,
            "{when}: tip ({}, {}): K {} {} vs {} {}",
            b.x,
            b.y,
            a.k1,
            a.k2,
            b.k1,
            b.k2
        );
    }
}
