//! The paper's transitions (issue 10, item 3) on the 0.3 m plate with a
//! central 45° crack, with the default criterion: the initial propagation
//! angle falls and the mode turns from tension to shear as the lateral load
//! and the face friction rise.

use cdca::Simulation;
use cdca::report::Mode;
use cdca::scene::{CriterionSpec, Scene, SideBc};

#[path = "support/docs_row.rs"]
mod docs_row;

use docs_row::{record_row, verification_row};

/// Initiation of one plate scene: the lowest vertical load P_V (Pa) at
/// which a tip meets the criterion, with that tip's |angle| (degrees, SPEC
/// §8), mode, K_I and K_II; `None` when nothing initiates up to P_V = 1 GPa.
#[derive(Clone, Copy, Debug)]
struct Initiation {
    p_v: f64,
    angle: f64,
    mode: Mode,
    k1: f64,
    k2: f64,
}

/// Highest vertical load searched, Pa.
const P_MAX: f64 = 1e9;

/// Bisection on the load factor of `name` (a bundled plate scene) with the
/// default criterion on an `n × n` mesh, to 0.5% of P_MAX.
fn initiation(name: &str, n: usize) -> Option<Initiation> {
    let path = format!(
        "{}/../../assets/scenes/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut scene = Scene::from_json(&std::fs::read_to_string(path).expect("scene file"))
        .expect("valid scene")
        .into_file();
    scene.mesh.nx = n;
    scene.mesh.ny = n;
    scene.criterion = CriterionSpec::default();
    let SideBc::Traction { normal: top, .. } = scene.boundary.top else {
        panic!("{name}: no load on top");
    };
    for side in [&mut scene.boundary.top, &mut scene.boundary.right] {
        if let SideBc::Traction { normal, .. } = side {
            *normal *= P_MAX / top.abs();
        }
    }
    // a fresh simulation per load: friction is path dependent, and the slip
    // left by a higher load would stay locked in at a lower one
    let at = |lambda: f64| {
        let mut sim =
            Simulation::new(Scene::try_from(scene.clone()).expect("valid")).expect("builds");
        sim.set_load_factor(lambda);
        let report = sim.solve().expect("solve");
        report
            .tips
            .iter()
            .find(|t| t.criterion.mode != Mode::None)
            .map(|t| Initiation {
                p_v: lambda * P_MAX,
                angle: t.criterion.angle_deg.abs(),
                mode: t.criterion.mode,
                k1: t.k1,
                k2: t.k2,
            })
    };
    let mut found = at(1.0)?;
    let (mut lo, mut hi) = (0.0, 1.0);
    while hi - lo > 0.005 {
        let mid = 0.5 * (lo + hi);
        match at(mid) {
            Some(i) => {
                found = i;
                hi = mid;
            }
            None => lo = mid,
        }
    }
    Some(found)
}

fn table(rows: &[(String, Option<Initiation>)]) {
    println!("case                 P_V (MPa)  angle (°)  mode      K_I (MPa√m)  K_II (MPa√m)");
    for (case, r) in rows {
        match r {
            Some(i) => println!(
                "{case:20} {:9.1}  {:9.1}  {:8}  {:11.3}  {:12.3}",
                i.p_v / 1e6,
                i.angle,
                format!("{:?}", i.mode),
                i.k1 / 1e6,
                i.k2 / 1e6
            ),
            None => println!("{case:20} no initiation up to {} MPa", P_MAX / 1e6),
        }
    }
}

/// Initiation of every scene of a series, printed as a table.
fn series(names: &[(&str, String)]) -> Vec<Option<Initiation>> {
    let rows: Vec<(String, Option<Initiation>)> = names
        .iter()
        .map(|(case, file)| ((*case).to_string(), initiation(file, MESH)))
        .collect();
    table(&rows);
    // the table of docs/fracture-model.md, *The paper's transitions*
    for ((_, file), (_, r)) in names.iter().zip(&rows) {
        let scene = file.trim_start_matches("plate_45_biaxial_");
        let case = scene.replace("_mu", ", ").replace('k', "");
        let cells = match r {
            Some(i) => vec![
                case,
                format!("{:.0} MPa", i.p_v / 1e6),
                format!("{:.1}°", i.angle),
                format!("{:?}", i.mode).to_lowercase(),
                format!("{:.3}", i.k1 / 1e6),
                format!("{:.2}", i.k2.abs() / 1e6),
            ],
            None => vec![case, format!("none up to {} MPa", P_MAX / 1e6)],
        };
        let cells: Vec<&str> = cells.iter().map(String::as_str).collect();
        record_row("transitions", scene, &cells);
    }
    rows.into_iter().map(|(_, r)| r).collect()
}

/// Mesh of the transition tests (h = 5 mm, a = 6h; 120 × 120 gives the
/// same modes and angles within 0.1°, loads within the 4 MPa bisection step).
const MESH: usize = 60;

/// Initiated angles never rise along a series.
fn assert_falls(rows: &[Option<Initiation>]) {
    let angles: Vec<f64> = rows.iter().flatten().map(|i| i.angle).collect();
    assert!(
        angles.windows(2).all(|w| w[1] <= w[0] + 0.5),
        "angles must fall: {angles:?}"
    );
}

/// P_H/P_V = 0.1, 0.2, 0.3 at μ = 0.5 (the paper's lateral-pressure
/// series): the least confined plate initiates a wing in tension at a large
/// angle (> 45°), the most confined one grows in shear, nearly coplanar
/// (< 35°); the angle never rises along the series (0.5° tolerance).
#[test]
fn confinement_turns_tension_into_shear() {
    let rows = series(&[
        ("k = 0.1, μ = 0.5", "plate_45_biaxial_k0.1_mu0.5".into()),
        ("k = 0.2, μ = 0.5", "plate_45_biaxial_k0.2_mu0.5".into()),
        ("k = 0.3, μ = 0.5", "plate_45_biaxial_k0.3_mu0.5".into()),
    ]);
    let first = rows[0].expect("k = 0.1 initiates");
    assert!(
        first.mode == Mode::Tension && first.angle > 45.0,
        "{first:?}"
    );
    let last = rows[2].expect("k = 0.3 initiates");
    assert!(last.mode == Mode::Shear && last.angle < 35.0, "{last:?}");
    assert_falls(&rows);
    let steps: Vec<String> = rows
        .iter()
        .flatten()
        .map(|i| format!("{:.1}° {}", i.angle, format!("{:?}", i.mode).to_lowercase()))
        .collect();
    verification_row(
        "transitions",
        "confinement_turns_tension_into_shear",
        "confinement turns tension into shear (paper's plate, k = 0.1, 0.2, 0.3; the friction series in `friction_turns_tension_into_shear`)",
        "60 × 60",
        &format!(
            "{}; see *The paper's transitions* in [the fracture model](fracture-model.md)",
            steps.join(" → ")
        ),
        "first tension > 45°, last shear < 35°, angles never rise",
    );
}

/// μ = 0.32, 0.48, 0.5, 0.67, 0.83 at P_H/P_V = 0.2 (the paper's friction
/// series): μ = 0.32 initiates in tension at a large angle (> 45°), μ = 0.48
/// in shear on the Mohr–Coulomb plane of the tip's circle, below 35°; the
/// angle does not rise over the sliding cases (0.5° tolerance). For
/// μ ≥ (1 − k)/(1 + k) = 0.667 the faces stick under the uniform biaxial
/// load and the crack carries the shear like intact rock: those plates
/// initiate only through the penalty's compliance, in shear below 35° at
/// more than four times the load. Their angle is then the Coulomb plane of
/// the uniform stress with the faces' friction, which turns away from the
/// crack as μ rises (φ/2: 16.5° and 19.3° measured); not asserted to fall.
#[test]
fn friction_turns_tension_into_shear() {
    let rows = series(&[
        ("k = 0.2, μ = 0.32", "plate_45_biaxial_k0.2_mu0.32".into()),
        ("k = 0.2, μ = 0.48", "plate_45_biaxial_k0.2_mu0.48".into()),
        ("k = 0.2, μ = 0.5", "plate_45_biaxial_k0.2_mu0.5".into()),
        ("k = 0.2, μ = 0.67", "plate_45_biaxial_k0.2_mu0.67".into()),
        ("k = 0.2, μ = 0.83", "plate_45_biaxial_k0.2_mu0.83".into()),
    ]);
    let first = rows[0].expect("μ = 0.32 initiates");
    assert!(
        first.mode == Mode::Tension && first.angle > 45.0,
        "{first:?}"
    );
    let shear = rows[1].expect("μ = 0.48 initiates");
    assert!(shear.mode == Mode::Shear && shear.angle < 35.0, "{shear:?}");
    for stuck in rows[3..].iter().flatten() {
        assert!(stuck.mode == Mode::Shear && stuck.angle < 35.0, "{stuck:?}");
        assert!(stuck.p_v > 4.0 * shear.p_v, "{stuck:?}");
    }
    assert_falls(&rows[..3]);
}

/// The bundled plate `name` grown under its own load control (120 × 120)
/// until the wing from the crack's upper tip is 20 mm long; every step
/// converged. Returns the angle (degrees) between the chord of that wing's
/// first 20 mm and the crack line.
fn wing_chord(name: &str) -> f64 {
    let path = format!(
        "{}/../../assets/scenes/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut file = Scene::from_json(&std::fs::read_to_string(path).expect("scene file"))
        .expect("valid scene")
        .into_file();
    // the paper's paths are its tips' growth: secondary cracks off (on the
    // k = 0.2, μ = 0.32 plate they end the run before the wing is 20 mm)
    file.growth.secondary_cracks = false;
    let scene = Scene::try_from(file).expect("valid scene");
    let [a, b] = [0, 1].map(|i| scene.cracks[0].points.as_ref().expect("points")[i]);
    let mut sim = Simulation::new(scene).expect("builds");
    let len = 0.02;
    loop {
        let step = sim.grow_step().expect("step");
        assert!(
            step.converged,
            "{name}: step {} did not converge",
            step.step
        );
        let c = &sim.cracks()[0];
        let i = c.iter().position(|p| *p == b).expect("upper tip");
        let wing = &c[i..];
        let mut acc = 0.0;
        for w in wing.windows(2) {
            let d = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
            if acc + d >= len {
                let f = (len - acc) / d;
                let p = [
                    w[0][0] + f * (w[1][0] - w[0][0]),
                    w[0][1] + f * (w[1][1] - w[0][1]),
                ];
                let chord = (p[1] - b[1]).atan2(p[0] - b[0]);
                let crack = (b[1] - a[1]).atan2(b[0] - a[0]);
                let angle = (chord - crack).to_degrees().abs();
                println!(
                    "{name}: 20 mm chord at {angle:.1}° to the crack after {} steps",
                    step.step
                );
                return angle;
            }
            acc += d;
        }
        assert!(sim.growth_finished().is_none(), "{name}: no 20 mm wing");
    }
}

/// Paths straighten as confinement and friction rise (the paper's two
/// series): the first 20 mm of the wing from the upper tip
/// turn far from the crack line where the plate starts in tension (k = 0.1,
/// μ = 0.5: measured 57.1°; k = 0.2, μ = 0.32: 68.3°) and stay close to it
/// where it starts in shear (k = 0.2, μ = 0.5: 20.0°; μ = 0.48: 18.9°),
/// below 35°, every step converged.
#[test]
fn paths_straighten_as_confinement_and_friction_rise() {
    for (low, high) in [
        ("plate_45_biaxial_k0.1_mu0.5", "plate_45_biaxial_k0.2_mu0.5"),
        (
            "plate_45_biaxial_k0.2_mu0.32",
            "plate_45_biaxial_k0.2_mu0.48",
        ),
    ] {
        let (turned, straight) = (wing_chord(low), wing_chord(high));
        assert!(
            turned > 45.0 && straight < 35.0,
            "{low} {turned}°, {high} {straight}°"
        );
    }
}
