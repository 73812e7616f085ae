//! The rigid-body check of SPEC §10: the supports must hold the two
//! translations and the rotation of the specimen.

use nalgebra::{Matrix3, Vector3};

use crate::error::SceneError;
use crate::scene::{Fix, SceneFile, SideBc};

/// A rigid-body motion counts as free when its eigenvalue of the constraint
/// Gram matrix is below this fraction of the largest one.
const RIGID_BODY_RTOL: f64 = 1e-10;

/// A displacement component held at zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Axis {
    X,
    Y,
}

impl SceneFile {
    /// Rejects supports that leave a rigid-body motion free: the 3×3 Gram
    /// matrix of the modes (1,0), (0,1), (−y,x) sampled at the fixed
    /// components must have full rank. Coordinates are scaled by the
    /// specimen size so that the test does not depend on units.
    pub(super) fn validate_rigid_body(&self) -> Result<(), SceneError> {
        let scale = self.specimen.width.max(self.specimen.height);
        let mut gram = Matrix3::zeros();
        for (p, axis) in self.constrained_components() {
            let (x, y) = (p[0] / scale, p[1] / scale);
            let mode = match axis {
                Axis::X => Vector3::new(1.0, 0.0, -y),
                Axis::Y => Vector3::new(0.0, 1.0, x),
            };
            gram += mode * mode.transpose();
        }
        let eigen = gram.symmetric_eigen();
        let largest = eigen.eigenvalues.max();
        let free: Vec<String> = (0..3)
            .filter(|&k| eigen.eigenvalues[k] <= RIGID_BODY_RTOL * largest)
            .map(|k| describe_motion(eigen.eigenvectors.column(k).into_owned(), scale))
            .collect();
        if free.is_empty() {
            return Ok(());
        }
        let reason = "the supports leave this rigid-body motion free; \
                      add a roller, a fixed side or a point support";
        Err(SceneError::invalid("boundary", free.join(" and "), reason))
    }

    /// Displacement components that the boundary holds at zero, on the
    /// structured node grid (node (i, j) at (i·width/nx, j·height/ny)): a
    /// `fixed` side holds x and y of its nodes, a `roller` the normal
    /// component, a point support the node nearest to its `at`.
    pub(crate) fn constrained_components(&self) -> Vec<([f64; 2], Axis)> {
        let (nx, ny) = (self.mesh.nx, self.mesh.ny);
        let dx = self.specimen.width / nx as f64;
        let dy = self.specimen.height / ny as f64;
        let node = |i: usize, j: usize| [i as f64 * dx, j as f64 * dy];
        let b = &self.boundary;
        let sides: [(SideBc, Axis, Vec<[f64; 2]>); 4] = [
            (b.bottom, Axis::Y, (0..=nx).map(|i| node(i, 0)).collect()),
            (b.top, Axis::Y, (0..=nx).map(|i| node(i, ny)).collect()),
            (b.left, Axis::X, (0..=ny).map(|j| node(0, j)).collect()),
            (b.right, Axis::X, (0..=ny).map(|j| node(nx, j)).collect()),
        ];
        let mut fixed = Vec::new();
        for (bc, normal, nodes) in sides {
            let axes: &[Axis] = match bc {
                SideBc::Fixed => &[Axis::X, Axis::Y],
                SideBc::Roller if normal == Axis::X => &[Axis::X],
                SideBc::Roller => &[Axis::Y],
                SideBc::Free | SideBc::Traction { .. } => &[],
            };
            for &p in &nodes {
                fixed.extend(axes.iter().map(|&a| (p, a)));
            }
        }
        for point in &b.points {
            let i = ((point.at[0] / dx).round().max(0.0) as usize).min(nx);
            let j = ((point.at[1] / dy).round().max(0.0) as usize).min(ny);
            let axes: &[Axis] = match point.fix {
                Fix::X => &[Axis::X],
                Fix::Y => &[Axis::Y],
                Fix::Xy => &[Axis::X, Axis::Y],
            };
            fixed.extend(axes.iter().map(|&a| (node(i, j), a)));
        }
        fixed
    }
}

/// Names a rigid-body motion `(a, b, θ)` given in coordinates scaled by
/// `scale`: the displacement is `(a − θ y, b + θ x)`, a rotation about
/// `(−b/θ, a/θ)` when θ ≠ 0.
fn describe_motion(v: Vector3<f64>, scale: f64) -> String {
    let (a, b, theta) = (v[0], v[1], v[2]);
    let size = v.norm();
    if theta.abs() >= 1e-3 * size {
        let centre = [-b / theta * scale, a / theta * scale].map(|c| (c * 1e6).round() / 1e6);
        format!("rotation about [{}, {}]", centre[0], centre[1])
    } else if b.abs() <= 1e-3 * size {
        "translation in x".to_owned()
    } else if a.abs() <= 1e-3 * size {
        "translation in y".to_owned()
    } else {
        format!("translation along ({:.3}, {:.3})", a / size, b / size)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Boundary, PointSupport};

    fn plate(boundary: Boundary) -> SceneFile {
        let text = r#"{ "specimen": { "width": 2.0, "height": 1.0 }, "mesh": { "nx": 20, "ny": 10 },
                        "material": { "young": 1e9 } }"#;
        let mut scene: SceneFile = serde_json::from_str(text).expect("plate parses");
        scene.boundary = boundary;
        scene
    }

    fn free_motion(boundary: Boundary) -> Option<String> {
        match plate(boundary).validate_rigid_body() {
            Err(SceneError::Invalid { value, .. }) => Some(value.to_string()),
            _ => None,
        }
    }

    fn supports(points: &[([f64; 2], Fix)]) -> Boundary {
        Boundary {
            bottom: SideBc::Free,
            left: SideBc::Free,
            points: points
                .iter()
                .map(|&(at, fix)| PointSupport { at, fix })
                .collect(),
            ..Boundary::default()
        }
    }

    #[test]
    fn each_free_motion_is_named() {
        let left_roller = Boundary {
            bottom: SideBc::Free,
            ..Boundary::default()
        };
        assert_eq!(
            free_motion(left_roller).as_deref(),
            Some("translation in y")
        );
        let bottom_roller = Boundary {
            left: SideBc::Free,
            ..Boundary::default()
        };
        assert_eq!(
            free_motion(bottom_roller).as_deref(),
            Some("translation in x")
        );
        let pinned = supports(&[([1.0, 0.5], Fix::Xy)]);
        assert_eq!(
            free_motion(pinned).as_deref(),
            Some("rotation about [1, 0.5]")
        );
        assert_eq!(
            free_motion(supports(&[])).map(|m| m.matches(" and ").count()),
            Some(2)
        );
    }

    #[test]
    fn held_plates_pass() {
        assert_eq!(
            free_motion(Boundary::default()),
            None,
            "bottom and left rollers"
        );
        let clamped = Boundary {
            bottom: SideBc::Fixed,
            left: SideBc::Free,
            ..Boundary::default()
        };
        assert_eq!(free_motion(clamped), None, "one fixed side");
        let two_points = supports(&[([0.0, 0.5], Fix::Xy), ([2.0, 0.5], Fix::Y)]);
        assert_eq!(free_motion(two_points), None);
        // A `y` point on the line x = 0 leaves the rotation about it free.
        let collinear = supports(&[([0.0, 0.5], Fix::Xy), ([0.0, 1.0], Fix::Y)]);
        assert_eq!(
            free_motion(collinear).as_deref(),
            Some("rotation about [0, 0.5]")
        );
    }

    #[test]
    fn point_supports_fix_the_nearest_node() {
        let scene = plate(supports(&[([1.04, 0.96], Fix::X), ([-5.0, 7.0], Fix::Y)]));
        let fixed = scene.constrained_components();
        assert_eq!(fixed.len(), 2);
        let ([x, y], axis) = fixed[0];
        assert!(
            (x - 1.0).abs() < 1e-12 && (y - 1.0).abs() < 1e-12,
            "h = 0.1: node (10, 10)"
        );
        assert_eq!(axis, Axis::X);
        assert_eq!(
            fixed[1],
            ([0.0, 1.0], Axis::Y),
            "clamped to the corner node"
        );
    }

    #[test]
    fn sides_fix_their_normal_or_both_components() {
        let scene = plate(Boundary {
            top: SideBc::Fixed,
            right: SideBc::Roller,
            ..supports(&[])
        });
        let fixed = scene.constrained_components();
        assert_eq!(fixed.len(), 2 * 21 + 11);
        assert!(fixed[..42].iter().all(|&([_, y], _)| y == 1.0));
        assert!(
            fixed[42..]
                .iter()
                .all(|&([x, _], a)| x == 2.0 && a == Axis::X)
        );
    }
}
