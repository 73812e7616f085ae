//! The bundled example scenes (`assets/scenes/*.json`) parse, validate,
//! round-trip, and say what their file names promise.

use std::path::PathBuf;

use cdca::Scene;
use cdca::scene::SideBc;

fn scenes() -> Vec<(String, Scene)> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenes"));
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("scene file is readable");
            let scene = Scene::from_json(&text)
                .unwrap_or_else(|e| panic!("{} is not a valid scene: {e}", path.display()));
            let name = path
                .file_stem()
                .expect("file name")
                .to_string_lossy()
                .into_owned();
            (name, scene)
        })
        .collect()
}

#[test]
fn every_bundled_scene_is_valid_and_described() {
    let scenes = scenes();
    assert!(scenes.len() >= 10, "only {} bundled scenes", scenes.len());
    for (file, scene) in &scenes {
        assert!(!scene.name.is_empty(), "{file}: no name");
        assert!(scene.description.len() > 40, "{file}: no description");
        let again =
            Scene::from_json(&scene.to_json().expect("writes")).expect("to_json output parses");
        assert_eq!(&again, scene, "{file}: round trip");
    }
}

#[test]
fn the_default_scene_is_small_enough_to_be_interactive() {
    let scenes = scenes();
    let (_, scene) = scenes
        .iter()
        .find(|(file, _)| file == "specimen_single_flaw")
        .expect("specimen_single_flaw.json is bundled");
    assert!(scene.mesh.nx * scene.mesh.ny <= 60 * 60);
    assert_eq!(scene.cracks.len(), 1);
}

/// `plate_45_biaxial_k{k}_mu{mu}`: vertical compression P_V on top, lateral
/// load k·P_V on the right, face friction μ, a central 45° crack of 0.06 m.
#[test]
fn biaxial_family_matches_its_file_names() {
    let mut count = 0;
    for (file, scene) in scenes() {
        let Some(params) = file.strip_prefix("plate_45_biaxial_k") else {
            continue;
        };
        let (k, mu) = params.split_once("_mu").expect("k and mu in the name");
        let (k, mu): (f64, f64) = (k.parse().expect("k"), mu.parse().expect("mu"));
        let normal = |bc: SideBc| match bc {
            SideBc::Traction { normal, .. } => normal,
            other => panic!("{file}: expected a traction, found {other:?}"),
        };
        let (top, right) = (normal(scene.boundary.top), normal(scene.boundary.right));
        assert!(top < 0.0, "{file}: P_V = {top} is not a compression");
        let p_h_matches = (right - k * top).abs() < 1e-9 * top.abs();
        assert!(p_h_matches, "{file}: P_H = {right}, P_V = {top}, k = {k}");
        let crack = &scene.cracks[0];
        assert_eq!(crack.friction, mu, "{file}");
        let [a, b] = [0, 1].map(|i| crack.points.as_ref().expect("a polyline")[i]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let diagonal = (dx.hypot(dy) - 0.06).abs() < 1e-9 && (dx - dy).abs() < 1e-9;
        assert!(diagonal, "{file}: not 45° and 0.06 m");
        count += 1;
    }
    assert_eq!(count, 7);
}

/// A criterion setting the chosen kind would ignore is refused before any
/// work, naming the field: MTS reads no circle (`r0`, `sampling`) and has
/// no shear branch (`shear_strength`); MTS with T samples its own circle
/// (`sampling`) and has no shear branch. SPEC §10's own spelling of the
/// default criterion, every field written, still reads.
#[test]
fn a_criterion_setting_the_kind_would_ignore_is_refused_by_name() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenes/specimen_single_flaw.json"
    ))
    .expect("the default scene");
    let with = |criterion: &str| {
        let mut v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        v["criterion"] = serde_json::from_str(criterion).expect("criterion JSON");
        match Scene::from_json(&v.to_string()) {
            Ok(_) => None,
            Err(cdca::SceneError::Invalid { field, .. }) => Some(field),
            Err(e) => panic!("{criterion}: {e}"),
        }
    };
    for (criterion, field) in [
        (r#"{"kind": "mts", "r0": 0.001}"#, "criterion.r0"),
        (
            r#"{"kind": "mts", "sampling": "hybrid"}"#,
            "criterion.sampling",
        ),
        (
            r#"{"kind": "mts", "shear_strength": "faces"}"#,
            "criterion.shear_strength",
        ),
        (
            r#"{"kind": "mts_t", "sampling": "williams"}"#,
            "criterion.sampling",
        ),
        (
            r#"{"kind": "mts_t", "shear_strength": "rock"}"#,
            "criterion.shear_strength",
        ),
    ] {
        assert_eq!(with(criterion).as_deref(), Some(field), "{criterion}");
    }
    for accepted in [
        r#"{"kind": "comprehensive", "r0": null, "sampling": "hybrid", "shear_strength": "faces"}"#,
        r#"{"kind": "mts", "r0": null}"#,
        r#"{"kind": "mts_t", "r0": 0.001}"#,
        "{}",
    ] {
        assert_eq!(with(accepted), None, "{accepted}");
    }
}
