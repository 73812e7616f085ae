//! Fields of a scene named by their dotted paths, for parameter studies
//! (`cdca sweep`, `cdca study`, the workbench's Study tab): one number
//! ([`Scene::with_param`]), or any JSON values at once
//! ([`SceneFile::with_values`]: a solver's name, a list of cracks).

use serde_json::Value;

use super::file::SceneFile;
use super::valid::Scene;
use crate::error::{FieldValue, SceneError};

impl Scene {
    /// The scene with the number at `path` set to `value`, checked (the
    /// checked setter of one number, by name).
    /// `path` is dotted, with array indices as numbers:
    /// `cracks.0.friction`, `boundary.right.normal`, `criterion.r0`. The
    /// field must exist in the scene file's layout (an optional field that
    /// is unset counts as existing). A whole number is written as an
    /// integer, so that integer fields (`mesh.nx`, `growth.max_steps`) take
    /// it too; a float field reads it as the same number.
    pub fn with_param(&self, path: &str, value: f64) -> Result<Self, SceneError> {
        if !value.is_finite() {
            return Err(SceneError::invalid(path, value, "must be a finite number"));
        }
        self.has_field(path, true).map_err(|e| match e {
            SceneError::Invalid { field, reason, .. } => SceneError::Invalid {
                field,
                value: FieldValue::Text(value.to_string()),
                reason,
            },
            e => e,
        })?;
        Self::try_from(self.with_values(&[(path, json_number(value))])?)
    }
}

/// `value` as JSON: an integer when it is a whole number that an `i64`
/// holds exactly (−0 stays a float, to keep its sign).
pub fn json_number(value: f64) -> Value {
    const EXACT: f64 = 9_007_199_254_740_992.0; // 2^53
    if value.fract() == 0.0 && value.abs() < EXACT && !(value == 0.0 && value.is_sign_negative()) {
        Value::from(value as i64)
    } else {
        Value::from(value)
    }
}

impl SceneFile {
    /// Checks that `path` names a field of this scene's layout (an unset
    /// optional one included), and with `number` a number field. The error
    /// names the path and why it names nothing.
    pub fn has_field(&self, path: &str, number: bool) -> Result<(), SceneError> {
        let mut root = serde_json::to_value(self).map_err(|e| SceneError::Write(e.to_string()))?;
        let node = node_at(&mut root, path).map_err(|why| SceneError::invalid(path, "–", why))?;
        if number && !(node.is_number() || node.is_null()) {
            return Err(SceneError::invalid(path, "–", "is not a number field"));
        }
        Ok(())
    }

    /// The file with each field `path` set to its JSON value, in order,
    /// not checked (see [`Scene::try_from`]): a value of the wrong type is
    /// an error naming its path.
    pub fn with_values(&self, values: &[(&str, Value)]) -> Result<Self, SceneError> {
        let mut root = serde_json::to_value(self).map_err(|e| SceneError::Write(e.to_string()))?;
        for (path, value) in values {
            let node = node_at(&mut root, path)
                .map_err(|why| SceneError::invalid(*path, value.to_string(), why))?;
            *node = value.clone();
        }
        serde_json::from_value(root).map_err(|e| {
            // the one that does not fit, found by setting each alone
            let culprit = values
                .iter()
                .find(|(p, v)| values.len() == 1 || self.with_values(&[(p, v.clone())]).is_err());
            match culprit {
                Some((path, value)) => SceneError::invalid(
                    *path,
                    value.to_string(),
                    format!("does not fit the field: {e}"),
                ),
                None => SceneError::Parse(e.to_string()),
            }
        })
    }

    /// The paths among `paths` that name a number field of this scene (an
    /// unset optional one included), the fields [`Scene::with_param`] can
    /// set: `boundary.right.normal` only where the right side is a
    /// traction side, `cracks.0.friction` only with a crack.
    pub fn params<'a>(&self, paths: &[&'a str]) -> Vec<&'a str> {
        paths
            .iter()
            .copied()
            .filter(|p| self.has_field(p, true).is_ok())
            .collect()
    }
}

/// The node at the dotted `path` in `root`, or why there is none.
fn node_at<'a>(root: &'a mut Value, path: &str) -> Result<&'a mut Value, String> {
    let mut node = root;
    let segments: Vec<&str> = path.split('.').collect();
    for (i, seg) in segments.iter().enumerate() {
        node = match node {
            Value::Array(items) => {
                let k: usize = seg
                    .parse()
                    .map_err(|_| "expects an index here".to_owned())?;
                let len = items.len();
                items
                    .get_mut(k)
                    .ok_or_else(|| format!("index {k} out of range (0..{len})"))?
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
                map.get_mut(*seg).ok_or(why)?
            }
            _ => return Err(format!("`{seg}` is inside a number")),
        };
    }
    Ok(node)
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

    /// Integer fields take whole numbers; any JSON value goes where its
    /// type fits, and one that does not names its path.
    #[test]
    fn whole_numbers_set_integer_fields_and_json_values_name_their_path() {
        let s = base();
        assert_eq!(s.with_param("mesh.nx", 12.0).map(|t| t.mesh.nx), Ok(12));
        let e = s.with_param("mesh.nx", 12.5).expect_err("not whole");
        assert!(e.to_string().contains("`mesh.nx` = 12.5"), "{e}");
        assert_eq!(
            json_number(-0.0).as_f64().map(f64::is_sign_negative),
            Some(true)
        );
        let file = s
            .with_values(&[
                ("solver.kind", Value::from("cg")),
                ("growth.max_steps", Value::from(3)),
            ])
            .expect("fits");
        assert_eq!(
            (file.solver.kind, file.growth.max_steps),
            (crate::scene::SolverKind::Cg, 3)
        );
        let e = s
            .with_values(&[
                ("growth.max_steps", Value::from(3)),
                ("solver.kind", Value::from("fast")),
            ])
            .expect_err("no such solver");
        assert!(
            e.to_string()
                .starts_with("scene field `solver.kind` = \"fast\""),
            "{e}"
        );
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
