//! Scene builders and a one-call solve shared by the verification tests.
#![allow(dead_code)]

#[path = "../support/docs_row.rs"]
pub mod docs_row;

use cdca::Simulation;
use cdca::report::SolveReport;
use cdca::scene::{
    Boundary, CrackSpec, CriterionSpec, Fix, GrowthSpec, IntactRock, Material, MeshSpec, Plane,
    PointSupport, Scene, SceneFile, SideBc, SolverSpec, Specimen,
};

pub const PI: f64 = std::f64::consts::PI;

/// A `w × h` plate, steel-like, plane strain, no cracks, free sides,
/// growing by the paper's model (`growth.intact_rock = "ignore"`: the
/// tests of the tip and kink rules check them alone; tests/intact_rock.rs
/// sets `"nucleate"`).
pub fn plate(w: f64, h: f64, nx: usize, ny: usize) -> SceneFile {
    SceneFile {
        name: "test".into(),
        description: String::new(),
        specimen: Specimen {
            width: w,
            height: h,
            thickness: 1.0,
        },
        mesh: MeshSpec {
            nx,
            ny,
            enrichment_radius: None,
        },
        material: Material {
            young: 200e9,
            poisson: 0.3,
            plane: Plane::Strain,
            cohesion: 15e6,
            friction_angle_deg: 30.0,
            k_ic: 1e6,
            k_iic: 1e6,
            tensile_strength: None,
        },
        cracks: Vec::new(),
        boundary: Boundary {
            bottom: SideBc::Free,
            left: SideBc::Free,
            top: SideBc::Free,
            right: SideBc::Free,
            points: Vec::new(),
        },
        criterion: CriterionSpec::default(),
        growth: GrowthSpec {
            intact_rock: IntactRock::Ignore,
            ..GrowthSpec::default()
        },
        solver: SolverSpec::default(),
    }
}

/// Uniform tension `s` on top and bottom, rigid motion removed by two
/// points at mid-height of the left and right sides.
pub fn tension_top_bottom(scene: &mut SceneFile, s: f64) {
    let (w, h) = (scene.specimen.width, scene.specimen.height);
    scene.boundary.top = SideBc::Traction {
        normal: s,
        shear: 0.0,
    };
    scene.boundary.bottom = SideBc::Traction {
        normal: s,
        shear: 0.0,
    };
    scene.boundary.points = vec![
        PointSupport {
            at: [0.0, 0.5 * h],
            fix: Fix::Xy,
        },
        PointSupport {
            at: [w, 0.5 * h],
            fix: Fix::Y,
        },
    ];
}

/// Straight crack through `(cx, cy)` of half-length `a` at `deg` to +x.
pub fn centre_crack(cx: f64, cy: f64, a: f64, deg: f64) -> CrackSpec {
    let (s, c) = deg.to_radians().sin_cos();
    CrackSpec::segment([cx - a * c, cy - a * s], [cx + a * c, cy + a * s])
}

/// Solves at full load and asserts the status every result is compared
/// under: linear solve and contact iteration converged, no point frozen for
/// cycling.
pub fn solve(scene: SceneFile) -> SolveReport {
    let mut sim = Simulation::new(valid(scene)).expect("builds");
    let r = sim.solve().expect("solve");
    assert!(r.converged(), "{:?}", r.failure());
    assert_eq!(
        r.contact.cycling, 0,
        "points frozen for cycling: {:?}",
        r.contact
    );
    r
}

/// The scene, checked (`Scene::try_from`); panics naming the bad field.
pub fn valid(scene: SceneFile) -> Scene {
    Scene::try_from(scene).unwrap_or_else(|e| panic!("invalid test scene: {e}"))
}

/// The compression on a bundled specimen's top, Pa (its reference load:
/// 50 MPa since issue 65, 100 MPa when most reference values below were
/// recorded; a λ recorded then is `100 MPa / top_load` times today's).
pub fn top_load(scene: &SceneFile) -> f64 {
    match scene.boundary.top {
        SideBc::Traction { normal, .. } => -normal,
        _ => panic!("the specimen is loaded on top"),
    }
}

/// A bundled scene's file (assets/scenes/NAME.json), checked, for editing,
/// growing by the paper's model (see [`plate`]).
pub fn bundled(name: &str) -> SceneFile {
    let path = format!(
        "{}/../../assets/scenes/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut file = Scene::from_json(&text)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .into_file();
    file.growth.intact_rock = IntactRock::Ignore;
    file
}

/// Issue 17's flaw range: a 3.5 mm flaw at β = 30–60° (5° steps) with face
/// friction μ = 0–0.6 (0.1 steps), drawn through the default specimen's
/// centre, off the grid (60 × 60, h = 0.5 mm).
pub const RANGE_ANGLES: [f64; 7] = [30.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0];
/// See [`RANGE_ANGLES`].
pub const RANGE_FRICTIONS: [f64; 7] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
/// Length of the range's flaws, m.
pub const RANGE_FLAW: f64 = 0.0035;
/// Centre of the range's flaws, m.
pub const RANGE_CENTRE: (f64, f64) = (0.015 + 0.37 * 0.0005, 0.015 + 0.21 * 0.0005);

/// What drives a flaw at `deg` to the horizontal with face friction `mu`
/// to slide under vertical compression, per unit load: `τ − μσ_n =
/// sin β cos β − μ cos² β` (its faces slide where it is positive: 48 of
/// the range's 49).
pub fn sliding_drive(deg: f64, mu: f64) -> f64 {
    let t = deg.to_radians();
    t.sin() * t.cos() - mu * t.cos() * t.cos()
}

/// The default scene with the range's flaw at `deg` and face friction `mu`
/// in place of its own.
pub fn range_flaw_scene(deg: f64, mu: f64) -> SceneFile {
    let mut s = bundled("specimen_single_flaw");
    let mut crack = centre_crack(RANGE_CENTRE.0, RANGE_CENTRE.1, 0.5 * RANGE_FLAW, deg);
    crack.friction = mu;
    s.cracks = vec![crack];
    s
}

/// Relative difference.
pub fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The default (hybrid) sampling's σ_θθ on the circle r0 around a tip of a
/// closed, sliding crack of half-length `a` at `beta_deg` to a uniaxial
/// compression of unit size applied across the horizontal (infinite
/// plate, faces in slip with friction `mu`), at its peak: returns the peak
/// (per unit load) and the kink angle |θ| (degrees). See
/// [`sliding_crack_peak`].
pub fn sliding_crack_kink(beta_deg: f64, mu: f64, a: f64, r0: f64) -> (f64, f64) {
    sliding_crack_peak(beta_deg, mu, 0.0, 1.0, a, r0)
}

/// [`sliding_crack_kink`] under a compression `s` (Pa) with face cohesion
/// `c` (Pa): the peak σ_θθ (Pa) and its angle |θ| (degrees).
///
/// With σ_n = s cos² β and σ_p = s sin² β the compressions across and
/// along the crack, τ = s sin β cos β, the face traction
/// τ_f = μσ_n + min(c, σ_n) (the contact law's limit) and the sliding
/// crack's K_II = (τ − τ_f)√(πa) (K_I = 0):
/// `σ_θθ(θ) = K_II/√(2πr0) · cos(θ/2)(−3/2 sin θ) − σ_p sin² θ − σ_n cos² θ
/// − 2 τ_f sin θ cos θ` (the singular term plus the uniform stress at the
/// tip: σ11 = −σ_p, σ22 = −σ_n, σ12 = τ_f), sampled every 0.01° on
/// |θ| ≤ 90°. As r0/a → 0 the peak tends to LEFM's 70.5°.
pub fn sliding_crack_peak(beta_deg: f64, mu: f64, c: f64, s: f64, a: f64, r0: f64) -> (f64, f64) {
    let (sb, cb) = beta_deg.to_radians().sin_cos();
    let (sn, sp) = (s * cb * cb, s * sb * sb);
    let tf = mu * sn + c.min(sn);
    let k2 = (s * sb * cb - tf) * (PI * a).sqrt();
    let (th, peak) = (0..=18_000)
        .map(|j| (-90.0 + 0.01 * f64::from(j)).to_radians())
        .map(|th| {
            let (st, ct) = th.sin_cos();
            let singular = k2 / (2.0 * PI * r0).sqrt() * (0.5 * th).cos() * (-1.5 * st);
            (
                th,
                singular - sp * st * st - sn * ct * ct - 2.0 * tf * st * ct,
            )
        })
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .expect("angles");
    (peak, th.to_degrees().abs())
}
