//! What the user types into a Scene panel field: read as a number, checked
//! by the solver crate's rules, and either taken or refused with a message
//! in the panel's own words and units. A typed value is never changed
//! silently: egui's number field would clamp it to the field's range
//! (friction "NaN" became μ = 5, a width of −5 mm became 1 mm, 100 000
//! elements became 800) or, when it does not parse, keep the old value
//! without a word.
//!
//! The solver crate's check ([`cdca::SceneError::Invalid`]) names the field
//! by its path in the scene file and its value in SI units; this module
//! names both as the panel shows them: `cracks[0].points[0]` =
//! `[0.05, 0.0129]` is "Crack 1, point 1 = (50, 12.9) mm". The CLI keeps
//! the crate's own text.

use cdca::scene::SceneFile;
use cdca::{FieldValue, SceneError};

use crate::style::units::{self, MM_PER_M, PA_PER_GPA, PA_PER_MPA};

/// How a Scene panel field shows its value: the name (with its group,
/// "Crack 1, friction μ") and the unit.
#[derive(Clone, Debug, PartialEq)]
pub struct Shown {
    pub name: String,
    /// SI units per display unit (1e-3 for mm).
    pub per_unit: f64,
    /// The display unit ("mm"), empty for a pure number.
    pub unit: &'static str,
}

impl Shown {
    /// A value in SI units as the field shows it, with its unit.
    pub fn value(&self, si: f64) -> String {
        self.with_unit(units::compact(si / self.per_unit))
    }

    fn with_unit(&self, number: String) -> String {
        if self.unit.is_empty() {
            number
        } else {
            format!("{number} {}", self.unit)
        }
    }
}

/// A field's name within its group: "Crack 1" and "Friction μ" make
/// "Crack 1, friction μ"; without a group, the label as it is.
pub fn full_name(group: Option<&str>, label: &str) -> String {
    let label = label.trim();
    match group {
        None => label.to_owned(),
        Some(group) => {
            let mut chars = label.chars();
            let first = chars.next().map(|c| c.to_lowercase().collect::<String>());
            format!("{group}, {}{}", first.unwrap_or_default(), chars.as_str())
        }
    }
}

/// The number typed into a field showing `field`, in SI units; `Err` is
/// the refusal when it is not a finite number (egui's reading: blanks
/// ignored, "−" read as "-"). `kept` is the value the field keeps.
pub fn read_number(text: &str, field: &Shown, kept: f64) -> Result<f64, String> {
    let v = egui_number(text).ok_or_else(|| not_a_number(text, field, &field.value(kept)))?;
    if v.is_finite() {
        Ok(v * field.per_unit)
    } else {
        Err(format!(
            "{}: {} is not a finite number. It stays {}.",
            field.name,
            text.trim(),
            field.value(kept)
        ))
    }
}

/// The whole number typed into a count field (`name`), or the refusal.
pub fn read_count(text: &str, name: &str, kept: usize) -> Result<usize, String> {
    let shown = Shown {
        name: name.to_owned(),
        per_unit: 1.0,
        unit: "",
    };
    let digits: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    digits.parse().map_err(|_| {
        if egui_number(text).is_some() {
            format!(
                "{name}: {} is not a whole number. It stays {kept}.",
                text.trim()
            )
        } else {
            not_a_number(text, &shown, &kept.to_string())
        }
    })
}

/// The refusal of a value outside the field's own range (`(low, high)`,
/// display units), checked after the solver crate's rules: the panel's
/// limits on what it meshes and draws.
pub fn outside_range(
    field: &Shown,
    si: f64,
    (low, high): (f64, f64),
    kept: &str,
) -> Option<String> {
    let v = si / field.per_unit;
    let (word, limit, extreme) = if v < low {
        ("below", low, "least")
    } else if v > high {
        ("above", high, "most")
    } else {
        return None;
    };
    Some(format!(
        "{}: {} is {word} {}, the {extreme} this field takes. It stays {kept}.",
        field.name,
        field.with_unit(units::compact(v)),
        field.with_unit(units::compact(limit)),
    ))
}

/// Why the scene `edited` (one typed value changed from `scene`) is
/// refused: the solver crate's checks fail on it, and passed on `scene`
/// or failed there on something else (a scene a drag left invalid still
/// takes typed values elsewhere); `None` when they take it. `name` and
/// `kept` are the typed field's name and the value it keeps.
pub fn refusal(scene: &SceneFile, edited: &SceneFile, name: &str, kept: &str) -> Option<String> {
    let error = cdca::Scene::try_from(edited.clone()).err()?;
    let before = cdca::Scene::try_from(scene.clone()).err();
    (before.as_ref() != Some(&error)).then(|| {
        format!(
            "Not taken: {}. {name} stays {kept}.",
            describe(&error, edited)
        )
    })
}

/// A scene error in the panel's words: "Crack 1, point 1 = (50, 12.9) mm:
/// outside the specimen, 0 to 30 mm × 0 to 30 mm". A field the panel does
/// not show keeps the file's path and value.
pub fn describe(error: &SceneError, scene: &SceneFile) -> String {
    let SceneError::Invalid {
        field,
        value,
        reason,
    } = error
    else {
        return error.to_string();
    };
    let Some(shown) = shown(field) else {
        return format!("`{field}` = {value}: {reason}");
    };
    let (value, reason) = match *value {
        FieldValue::Number(v) => (shown.value(v), reason.clone()),
        FieldValue::Point(p) => {
            let at = format!(
                "({}, {}) mm",
                units::compact(p[0] * MM_PER_M),
                units::compact(p[1] * MM_PER_M)
            );
            let reason = if p.iter().all(|c| c.is_finite()) && !scene.contains(p) {
                format!(
                    "outside the specimen, 0 to {} mm × 0 to {} mm",
                    units::compact(scene.specimen.width * MM_PER_M),
                    units::compact(scene.specimen.height * MM_PER_M)
                )
            } else {
                reason.clone()
            };
            (at, reason)
        }
        _ => (value.to_string(), reason.clone()),
    };
    format!("{} = {value}: {reason}", shown.name)
}

/// How the Scene panel names the field at `path` (a scene file path,
/// `cracks[0].points[1]`) and shows its value; `None` for a field it does
/// not show.
pub fn shown(path: &str) -> Option<Shown> {
    const MM: f64 = 1.0 / MM_PER_M;
    let (group, rest) = group_of(path);
    let (label, per_unit, unit) = match rest {
        "specimen.width" => ("Width", MM, "mm"),
        "specimen.height" => ("Height", MM, "mm"),
        "specimen.thickness" => ("Thickness", MM, "mm"),
        "mesh.nx" => ("Elements along x", 1.0, ""),
        "mesh.ny" => ("Elements along y", 1.0, ""),
        "mesh" => ("Mesh", 1.0, ""),
        "material.young" => ("Young's modulus E", PA_PER_GPA, "GPa"),
        "material.poisson" => ("Poisson's ratio ν", 1.0, ""),
        "material.k_ic" => ("Toughness K_IC", PA_PER_MPA, "MPa·√m"),
        "material.k_iic" => ("Shear toughness K_IIC", PA_PER_MPA, "MPa·√m"),
        "material.cohesion" => ("Rock cohesion c", PA_PER_MPA, "MPa"),
        "material.friction_angle_deg" => ("Friction angle φ", 1.0, "°"),
        "material.tensile_strength" => ("Tensile strength σ_t", PA_PER_MPA, "MPa"),
        "friction" => ("Friction μ", 1.0, ""),
        "cohesion" => ("Face cohesion c_c", PA_PER_MPA, "MPa"),
        "normal_stiffness" => ("Normal k_N", PA_PER_GPA, "GPa/m"),
        "shear_stiffness" => ("Shear k_T", PA_PER_GPA, "GPa/m"),
        "normal" => ("Normal (tension +)", PA_PER_MPA, "MPa"),
        "shear" => ("Shear", PA_PER_MPA, "MPa"),
        "point" | "at" => ("", MM, "mm"),
        "criterion.r0" => ("Radius r0", MM, "mm"),
        "growth.increment" => ("Increment Δa", MM, "mm"),
        "growth.max_load_factor" => ("Max load factor λ", 1.0, ""),
        "growth.load_steps" => ("Load steps", 1.0, ""),
        "growth.max_growth_per_step" => ("Max growth per load step", 1.0, ""),
        "growth.max_steps" => ("Max steps", 1.0, ""),
        _ => return None,
    };
    let name = match group {
        Some(g) if label.is_empty() => g,
        g => full_name(g.as_deref(), label),
    };
    Some(Shown {
        name,
        per_unit,
        unit,
    })
}

/// A path's group as the panel names it ("Crack 1", "Crack 1, point 2",
/// "Top", "Point support 1") and the rest of the path (`friction`;
/// `point` for a crack's point, `at` for a support's).
fn group_of(path: &str) -> (Option<String>, &str) {
    if let Some(rest) = path.strip_prefix("cracks[") {
        let Some((i, rest)) = index(rest) else {
            return (None, path);
        };
        let crack = format!("Crack {}", i + 1);
        return match rest.strip_prefix(".points[").and_then(index) {
            Some((k, "")) => (Some(format!("{crack}, point {}", k + 1)), "point"),
            Some(_) => (None, path),
            None => (Some(crack), rest.trim_start_matches('.')),
        };
    }
    if let Some(rest) = path.strip_prefix("boundary.points[") {
        return match index(rest) {
            Some((k, ".at")) => (Some(format!("Point support {}", k + 1)), "at"),
            _ => (None, path),
        };
    }
    for side in ["top", "right", "bottom", "left"] {
        if let Some(rest) = path
            .strip_prefix("boundary.")
            .and_then(|p| p.strip_prefix(side))
            .and_then(|p| p.strip_prefix('.'))
        {
            let mut group = side.to_owned();
            group[..1].make_ascii_uppercase();
            return (Some(group), rest);
        }
    }
    (None, path)
}

/// `"3].friction"` → `(3, ".friction")`.
fn index(text: &str) -> Option<(usize, &str)> {
    let (digits, rest) = text.split_once(']')?;
    Some((digits.parse().ok()?, rest))
}

/// A number as egui's number field reads it: blanks anywhere ignored, the
/// minus sign "−" read as "-".
fn egui_number(text: &str) -> Option<f64> {
    let text: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| if c == '−' { '-' } else { c })
        .collect();
    text.parse().ok()
}

fn not_a_number(text: &str, field: &Shown, kept: &str) -> String {
    if text.trim().is_empty() {
        format!("{}: the field was left empty. It stays {kept}.", field.name)
    } else {
        format!(
            "{}: \"{}\" is not a number. It stays {kept}.",
            field.name,
            text.trim()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> SceneFile {
        crate::files::scenes::default_scene()
    }

    #[test]
    fn paths_are_named_as_the_panel_names_them() {
        let names = [
            ("cracks[0].points[0]", "Crack 1, point 1"),
            ("cracks[2].friction", "Crack 3, friction μ"),
            ("cracks[0].normal_stiffness", "Crack 1, normal k_N"),
            ("boundary.top.normal", "Top, normal (tension +)"),
            ("boundary.points[1].at", "Point support 2"),
            ("specimen.width", "Width"),
            ("mesh", "Mesh"),
        ];
        for (path, name) in names {
            assert_eq!(shown(path).map(|s| s.name).as_deref(), Some(name), "{path}");
        }
        assert_eq!(shown("cracks[0].arc.radius"), None);
        assert_eq!(shown("solver.omega"), None);
    }

    #[test]
    fn a_point_outside_the_specimen_is_described_in_mm() {
        let mut s = scene();
        let p = [0.05, 0.0129];
        if let Some(points) = s.cracks[0].points.as_mut() {
            points[0] = p;
        }
        let error = cdca::Scene::try_from(s.clone()).expect_err("outside");
        assert_eq!(
            describe(&error, &s),
            "Crack 1, point 1 = (50, 12.9) mm: outside the specimen, 0 to 30 mm × 0 to 30 mm"
        );
    }

    #[test]
    fn typed_text_is_read_or_refused() {
        let width = shown("specimen.width").expect("shown");
        assert_eq!(read_number(" 2 5 ", &width, 0.03), Ok(0.025));
        assert_eq!(read_number("−5", &width, 0.03), Ok(-0.005));
        assert_eq!(
            read_number("", &width, 0.03),
            Err("Width: the field was left empty. It stays 30 mm.".to_owned())
        );
        assert_eq!(
            read_number("NaN", &width, 0.03),
            Err("Width: NaN is not a finite number. It stays 30 mm.".to_owned())
        );
        assert_eq!(
            read_number("abc", &width, 0.03),
            Err("Width: \"abc\" is not a number. It stays 30 mm.".to_owned())
        );
        assert_eq!(read_count("100 000", "Elements along x", 60), Ok(100_000));
        assert_eq!(
            read_count("2.5", "Elements along x", 60),
            Err("Elements along x: 2.5 is not a whole number. It stays 60.".into())
        );
        assert_eq!(
            outside_range(&width, 0.2, (1.0, 100.0), "30 mm"),
            Some(
                "Width: 200 mm is above 100 mm, the most this field takes. It stays 30 mm.".into()
            )
        );
        assert_eq!(outside_range(&width, 0.02, (1.0, 100.0), "30 mm"), None);
    }
}
