//! One numeric field of a scene, named by its dotted path, for parameter
//! studies (`cdca sweep`, the workbench's Study tab).

use serde_json::Value;

use super::file::SceneFile;
use super::valid::Scene;
use crate::error::SceneError;

impl Scene {
    /// The scene with the number at `path` set to `value`, checked (the
    /// checked setter of one number, by name).
    /// `path` is dotted, with array indices as numbers:
    /// `cracks.0.friction`, `boundary.right.normal`, `criterion.r0`. The
    /// field must exist in the scene file's layout (an optional field that
    /// is unset counts as existing).
    pub fn with_param(&self, path: &str, value: f64) -> Result<Self, SceneError> {
        let bad = |reason: &str| SceneError::invalid(path, value, reason);
        if !value.is_finite() {
            return Err(bad("must be a finite number"));
        }
        let mut root = serde_json::to_value(self).map_err(|e| SceneError::Write(e.to_string()))?;
        let mut node = &mut root;
        let segments: Vec<&str> = path.split('.').collect();
        for (i, seg) in segments.iter().enumerate() {
            let last = i + 1 == segments.len();
            node = match node {
                Value::Array(items) => {
                    let k: usize = seg.parse().map_err(|_| bad("expects an index here"))?;
                    let len = items.len();
                    items
                        .get_mut(k)
                        .ok_or_else(|| bad(&format!("index {k} out of range (0..{len})")))?
                }
                Value::Object(map) => {
                    // a tagged variant (a side's `kind`) says which it is
                    let why = match map.get("kind").and_then(Value::as_str) {
                        Some(kind) => format!(
                            "no field `{seg}` here: `{}` is of kind `{kind}`",
                            segments[..i].join(".")
                        ),
                        None => format!("no field `{seg}` here"),
                    };
                    map.get_mut(*seg).ok_or_else(|| bad(&why))?
                }
                _ => return Err(bad(&format!("`{seg}` is inside a number"))),
            };
            if last && !(node.is_number() || node.is_null()) {
                return Err(bad("is not a number field"));
            }
        }
        *node = Value::from(value);
        let file: SceneFile =
            serde_json::from_value(root).map_err(|e| SceneError::Parse(e.to_string()))?;
        Self::try_from(file)
    }
}

impl SceneFile {
    /// The paths among `paths` that name a number field of this scene (an
    /// unset optional one included), the fields [`Scene::with_param`] can
    /// set: `boundary.right.normal` only where the right side is a
    /// traction side, `cracks.0.friction` only with a crack.
    pub fn params<'a>(&self, paths: &[&'a str]) -> Vec<&'a str> {
        let Ok(root) = serde_json::to_value(self) else {
            return Vec::new();
        };
        paths
            .iter()
            .copied()
            .filter(|p| {
                root.pointer(&format!("/{}", p.replace('.', "/")))
                    .is_some_and(|n| n.is_number() || n.is_null())
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> Scene {
        Scene::from_json(
            r#"{"specimen":{"width":0.3,"height":0.3},"mesh":{"nx":10,"ny":10},
               "material":{"young":4.78e9},
               "cracks":[{"points":[[0.1,0.1],[0.2,0.2]],"friction":0.5}],
               "boundary":{"bottom":{"kind":"roller"},"left":{"kind":"roller"},
                 "top":{"kind":"traction","normal":-10e6},
                 "right":{"kind":"traction","normal":-2e6}}}"#,
        )
        .expect("valid base scene")
    }

    #[test]
    fn sets_nested_fields_and_unset_options() {
        let s = base();
        assert_eq!(
            s.with_param("cracks.0.friction", 0.83)
                .map(|t| t.cracks[0].friction),
            Ok(0.83)
        );
        let t = s.with_param("boundary.right.normal", -3e6).expect("valid");
        assert!(
            matches!(t.boundary.right, crate::scene::SideBc::Traction { normal, .. } if normal == -3e6)
        );
        assert_eq!(
            s.with_param("criterion.r0", 1e-3).map(|t| t.criterion.r0),
            Ok(Some(1e-3))
        );
    }

    #[test]
    fn bad_paths_and_values_name_the_path() {
        let s = base();
        for (path, value) in [
            ("cracks.3.friction", 0.5),
            ("cracks.0.frictoin", 0.5),
            ("material", 1.0),
            ("cracks.0.friction", -1.0),
            ("cracks.0.friction", f64::NAN),
        ] {
            let e = s.with_param(path, value).expect_err(path);
            assert!(
                e.to_string()
                    .contains(path.split('.').next().unwrap_or(path)),
                "{path}: {e}"
            );
        }
    }

    /// The fields a scene has: a free side has no traction, a scene
    /// without cracks no crack friction, and an unset optional number counts.
    #[test]
    fn a_scene_offers_only_its_own_number_fields() {
        let mut file = base().into_file();
        let paths = [
            "cracks.0.friction",
            "cracks.0.cohesion",
            "boundary.right.normal",
            "boundary.bottom.normal",
            "criterion.r0",
            "material",
        ];
        assert_eq!(
            file.params(&paths),
            [
                "cracks.0.friction",
                "cracks.0.cohesion",
                "boundary.right.normal",
                "criterion.r0"
            ]
        );
        file.cracks.clear();
        file.boundary.right = crate::scene::SideBc::Free;
        assert_eq!(file.params(&paths), ["criterion.r0"]);
    }

    /// A field of another variant names the variant the scene has.
    #[test]
    fn a_field_of_another_kind_of_side_names_the_kind() {
        let e = base()
            .with_param("boundary.bottom.normal", -1e6)
            .expect_err("a roller has no traction");
        assert!(
            e.to_string()
                .contains("no field `normal` here: `boundary.bottom` is of kind `roller`"),
            "{e}"
        );
    }
}
