//! The intact rock fails at its own strength (SPEC §8, `growth.intact_rock
//! = "nucleate"`): uncracked specimens of a held-out rock (not the
//! paper's) start their first crack where Mohr–Coulomb with its tension
//! cut-off says, on the plane it says.
//!
//! The rock: c = 10 MPa, φ = 35°, so `σ_c = 2c cos φ/(1 − sin φ)` =
//! 38.42 MPa, `N_φ = (1 + sin φ)/(1 − sin φ)` = 3.690 and the cut-off
//! `σ_t = 2c cos φ/(1 + sin φ)` = 10.41 MPa; E = 20 GPa, ν = 0.2, plane
//! strain, K_IC = 0.8 MPa√m. A 40 mm × 80 mm specimen under critical
//! control, loaded on its sides by uniform tractions held by two point
//! supports (so that every stress state is uniform).

mod common;

use cdca::Simulation;
use cdca::report::{GrowthStepReport, Mode};
use cdca::scene::{Fix, GrowthControl, IntactRock, Plane, PointSupport, SceneFile, SideBc};
use common::docs_row::{sig, verification_row};
use common::valid;

const C: f64 = 10e6;
const PHI_DEG: f64 = 35.0;

fn ucs() -> f64 {
    let p = PHI_DEG.to_radians();
    2.0 * C * p.cos() / (1.0 - p.sin())
}

fn n_phi() -> f64 {
    let p = PHI_DEG.to_radians();
    (1.0 + p.sin()) / (1.0 - p.sin())
}

fn tensile() -> f64 {
    let p = PHI_DEG.to_radians();
    2.0 * C * p.cos() / (1.0 + p.sin())
}

/// The uncracked specimen on `nx × 2nx` elements under the uniform stress
/// `[σxx, σyy, τxy]` (Pa, tension positive), each side loaded by the
/// traction that stress puts on it.
fn specimen(nx: usize, s: [f64; 3]) -> SceneFile {
    let mut f = common::plate(0.04, 0.08, nx, 2 * nx);
    f.material.young = 20e9;
    f.material.poisson = 0.2;
    f.material.plane = Plane::Strain;
    f.material.cohesion = C;
    f.material.friction_angle_deg = PHI_DEG;
    f.material.k_ic = 0.8e6;
    f.material.k_iic = 1.6e6;
    f.growth.control = GrowthControl::Critical;
    f.growth.intact_rock = IntactRock::Nucleate;
    // outward normals: top +y, bottom −y, right +x, left −x; `shear` along
    // +x on top and bottom, +y on the sides
    f.boundary.top = SideBc::Traction {
        normal: s[1],
        shear: s[2],
    };
    f.boundary.bottom = SideBc::Traction {
        normal: s[1],
        shear: -s[2],
    };
    f.boundary.right = SideBc::Traction {
        normal: s[0],
        shear: s[2],
    };
    f.boundary.left = SideBc::Traction {
        normal: s[0],
        shear: -s[2],
    };
    f.boundary.points = vec![
        PointSupport {
            at: [0.0, 0.0],
            fix: Fix::Xy,
        },
        PointSupport {
            at: [0.04, 0.0],
            fix: Fix::Y,
        },
    ];
    f
}

/// The first growth step of `scene`: the first crack started.
fn first_step(scene: SceneFile) -> GrowthStepReport {
    let mut sim = Simulation::new(valid(scene)).expect("builds");
    let step = sim.grow_step().expect("a step");
    assert!(step.converged, "{:?}", step.failure);
    assert_eq!(step.nucleated.len(), 1, "one crack started: {step:?}");
    step
}

/// The most compressive principal direction of `s`, degrees in [0, 180).
fn sigma1_deg(s: [f64; 3]) -> f64 {
    (0.5 * (2.0 * s[2]).atan2(s[0] - s[1]).to_degrees() + 90.0).rem_euclid(180.0)
}

/// Angle between two line directions, degrees in [0, 90].
fn between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(180.0);
    d.min(180.0 - d)
}

/// Uniaxial compression of 10 MPa: the first crack starts at λ σ = σ_c,
/// in shear, 45° − φ/2 = 27.5° off the load, on three meshes (10 × 20,
/// 20 × 40 and 30 × 60) within 5%.
#[test]
fn an_uncracked_specimen_fails_at_its_uniaxial_strength_on_three_meshes() {
    let p = 10e6;
    let mut worst = 0.0_f64;
    for nx in [10, 20, 30] {
        let step = first_step(specimen(nx, [0.0, -p, 0.0]));
        let start = &step.nucleated[0];
        let err = (step.load_factor * p - ucs()).abs() / ucs();
        worst = worst.max(err);
        assert!(
            err < 0.05,
            "{nx}: σ = {} against σ_c = {}",
            step.load_factor * p,
            ucs()
        );
        assert_eq!(start.mode, Mode::Shear);
        let off = between(start.direction_deg, 90.0);
        assert!(
            (off - (45.0 - PHI_DEG / 2.0)).abs() < 1e-6,
            "{nx}: {off}° off the load"
        );
    }
    verification_row(
        "intact_rock",
        "an_uncracked_specimen_fails_at_its_uniaxial_strength_on_three_meshes",
        "uncracked specimen, uniaxial compression (σ_c = 2c cos φ/(1 − sin φ))",
        "10 × 20, 20 × 40, 30 × 60",
        &format!(
            "σ within {} of σ_c; plane 27.5° off the load",
            sig(worst, 2)
        ),
        "5%",
    );
}

/// With a lateral pressure σ3 = 0.1 σ1 (`k N_φ` = 0.37 < 1) the first
/// crack starts where `σ1 = σ_c + N_φ σ3`, in shear.
#[test]
fn with_lateral_pressure_the_rock_fails_on_the_mohr_coulomb_line() {
    let p = 10e6;
    let k = 0.1;
    let step = first_step(specimen(20, [-k * p, -p, 0.0]));
    let sigma1 = step.load_factor * p;
    let expected = ucs() / (1.0 - k * n_phi());
    let err = (sigma1 - expected).abs() / expected;
    assert!(
        err < 0.05,
        "σ1 = {sigma1} against σ_c + N_φ σ3 = {expected}"
    );
    assert_eq!(step.nucleated[0].mode, Mode::Shear);
    verification_row(
        "intact_rock",
        "with_lateral_pressure_the_rock_fails_on_the_mohr_coulomb_line",
        "uncracked specimen, σ3 = 0.1 σ1 (σ1 = σ_c + N_φ σ3)",
        "20 × 40",
        &format!("σ1 within {}", sig(err, 2)),
        "5%",
    );
}

/// Uniaxial tension: the first crack starts at λ σ = σ_t in tension,
/// perpendicular to the load.
#[test]
fn in_uniaxial_tension_the_rock_fails_at_its_tensile_strength() {
    let p = 2e6;
    let step = first_step(specimen(20, [0.0, p, 0.0]));
    let err = (step.load_factor * p - tensile()).abs() / tensile();
    assert!(
        err < 0.05,
        "σ = {} against σ_t = {}",
        step.load_factor * p,
        tensile()
    );
    let start = &step.nucleated[0];
    assert_eq!(start.mode, Mode::Tension);
    assert!(
        between(start.direction_deg, 0.0) < 1e-6,
        "{}°",
        start.direction_deg
    );
    verification_row(
        "intact_rock",
        "in_uniaxial_tension_the_rock_fails_at_its_tensile_strength",
        "uncracked specimen, uniaxial tension (σ_t = 2c cos φ/(1 + sin φ))",
        "20 × 40",
        &format!("σ within {}; crack ⊥ load", sig(err, 2)),
        "5%",
    );
}

/// A shear traction on every side turns the principal axes (σyy = −10,
/// τxy = ±4 MPa: σ1 14.5° off the vertical either way): the crack starts
/// on a plane 45° − φ/2 off σ1, following it within 7°, at the load the
/// Mohr–Coulomb line gives for the principal stresses.
#[test]
fn a_crack_started_in_shear_follows_the_turned_principal_axes() {
    let mut worst = 0.0_f64;
    for tau in [4e6, -4e6] {
        let s = [0.0, -10e6, tau];
        let step = first_step(specimen(20, s));
        let start = &step.nucleated[0];
        assert_eq!(start.mode, Mode::Shear);
        let off = between(start.direction_deg, sigma1_deg(s));
        worst = worst.max((off - (45.0 - PHI_DEG / 2.0)).abs());
        assert!(
            (off - (45.0 - PHI_DEG / 2.0)).abs() < 7.0,
            "τ {tau}: {off}° off σ1"
        );
        // principal compressions σ1, σ3 of the applied stress
        let (centre, radius) = (
            0.5 * (s[0] + s[1]),
            (0.25 * (s[0] - s[1]).powi(2) + tau * tau).sqrt(),
        );
        let (sigma1, sigma3) = (radius - centre, -radius - centre);
        let lambda = ucs() / (sigma1 - n_phi() * sigma3);
        assert!(
            (step.load_factor - lambda).abs() / lambda < 0.05,
            "{} against {lambda}",
            step.load_factor
        );
    }
    verification_row(
        "intact_rock",
        "a_crack_started_in_shear_follows_the_turned_principal_axes",
        "uncracked specimen, σ1 turned 14.5° by a shear traction (plane 45° − φ/2 off σ1)",
        "20 × 40",
        &format!("plane within {}° of 27.5° off σ1", sig(worst, 2)),
        "7°",
    );
}
