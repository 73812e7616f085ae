//! Scenes bundled with the binary (`assets/scenes/*.json`), embedded so the
//! web build needs no file system.

use cdca::scene::SceneFile;

/// A scene shipped with the workbench.
#[derive(Clone, Copy, Debug)]
pub struct Bundled {
    /// Menu label.
    pub title: &'static str,
    /// The file's name in `assets/scenes/` (study files name scenes so).
    pub file: &'static str,
    /// The scene file's text.
    pub json: &'static str,
}

/// The scene the workbench opens on first start.
pub const DEFAULT_TITLE: &str = "Single flaw under uniaxial compression";

macro_rules! bundled {
    ($title:literal, $file:literal) => {
        Bundled {
            title: $title,
            file: $file,
            json: include_str!(concat!("../../assets/scenes/", $file)),
        }
    };
}

/// Every bundled scene, the default first.
pub const BUNDLED: &[Bundled] = &[
    bundled!(
        "Single flaw under uniaxial compression",
        "specimen_single_flaw.json"
    ),
    bundled!(
        "Closed crack under biaxial compression",
        "closed_crack_biaxial.json"
    ),
    bundled!(
        "Centre crack under uniaxial tension",
        "centre_crack_tension.json"
    ),
    bundled!(
        "Edge crack under uniaxial tension",
        "edge_crack_tension.json"
    ),
    bundled!(
        "Inclined centre crack under uniaxial tension",
        "inclined_crack_tension.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.1, mu = 0.5",
        "plate_45_biaxial_k0.1_mu0.5.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.2, mu = 0.32",
        "plate_45_biaxial_k0.2_mu0.32.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.2, mu = 0.48",
        "plate_45_biaxial_k0.2_mu0.48.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.2, mu = 0.5",
        "plate_45_biaxial_k0.2_mu0.5.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.2, mu = 0.67",
        "plate_45_biaxial_k0.2_mu0.67.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.2, mu = 0.83",
        "plate_45_biaxial_k0.2_mu0.83.json"
    ),
    bundled!(
        "45-degree crack, biaxial compression, k = 0.3, mu = 0.5",
        "plate_45_biaxial_k0.3_mu0.5.json"
    ),
    bundled!(
        "two flaws, coplanar, uniaxial compression",
        "specimen_two_flaws_coplanar.json"
    ),
    bundled!(
        "two flaws, overlapping, uniaxial compression",
        "specimen_two_flaws_overlapping.json"
    ),
    bundled!(
        "two flaws, stepped, uniaxial compression",
        "specimen_two_flaws_stepped.json"
    ),
];

/// The default scene (a single closed flaw in the 30 mm specimen under
/// uniaxial compression, growth to failure).
pub fn default_scene() -> SceneFile {
    BUNDLED
        .iter()
        .find_map(|b| {
            cdca::Scene::from_json(b.json)
                .map(cdca::Scene::into_file)
                .ok()
        })
        .unwrap_or_else(fallback_scene)
}

/// A scene built in code, so the app always has something to show even if
/// every embedded file were broken (a bug the tests above catch).
fn fallback_scene() -> SceneFile {
    use cdca::scene::{
        Boundary, CriterionSpec, GrowthSpec, Material, MeshSpec, Plane, SideBc, SolverSpec,
        Specimen,
    };
    SceneFile {
        name: "Plate".to_owned(),
        description: String::new(),
        specimen: Specimen {
            width: 0.3,
            height: 0.3,
            thickness: 1.0,
        },
        mesh: MeshSpec {
            nx: 40,
            ny: 40,
            enrichment_radius: None,
        },
        material: Material {
            young: 4.78e9,
            poisson: 0.25,
            plane: Plane::Stress,
            cohesion: 15e6,
            friction_angle_deg: 49.0,
            k_ic: 1.03e6,
            k_iic: 2.52e6,
            tensile_strength: None,
        },
        cracks: Vec::new(),
        boundary: Boundary {
            top: SideBc::Traction {
                normal: -10e6,
                shear: 0.0,
            },
            ..Boundary::default()
        },
        criterion: CriterionSpec::default(),
        growth: GrowthSpec::default(),
        solver: SolverSpec::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_bundled_scene_parses() {
        for b in BUNDLED {
            assert!(
                cdca::Scene::from_json(b.json)
                    .map(cdca::Scene::into_file)
                    .is_ok(),
                "{} does not parse",
                b.title
            );
        }
    }

    #[test]
    fn bundled_titles_are_the_scene_names() {
        for b in BUNDLED {
            assert_eq!(
                cdca::Scene::from_json(b.json)
                    .map(cdca::Scene::into_file)
                    .map(|s| s.name)
                    .ok()
                    .as_deref(),
                Some(b.title)
            );
        }
    }

    /// File ▸ Bundled scenes lists every scene file shipped in
    /// `assets/scenes` (the three two-flaw specimens used to be missing).
    #[test]
    fn every_scene_file_is_bundled() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/scenes");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .expect("assets/scenes")
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "json"))
            .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
            .collect();
        files.sort();
        let mut bundled: Vec<String> = BUNDLED
            .iter()
            .map(|b| {
                files
                    .iter()
                    .find(|f| {
                        std::fs::read_to_string(format!("{dir}/{f}"))
                            .ok()
                            .as_deref()
                            == Some(b.json)
                    })
                    .cloned()
                    .unwrap_or_default()
            })
            .collect();
        bundled.sort();
        assert_eq!(bundled, files);
    }

    #[test]
    fn default_scene_has_one_rough_crack() {
        let s = default_scene();
        assert_eq!(s.cracks.len(), 1);
        assert!(s.cracks[0].friction > 0.0, "a closed crack with friction");
        assert_eq!((s.mesh.nx, s.mesh.ny), (60, 60));
    }
}
