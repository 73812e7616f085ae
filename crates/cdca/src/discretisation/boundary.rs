//! Supports and loads of the four sides and the point supports (SPEC §10).

use crate::geometry::mesh::Mesh;
use crate::scene::{Boundary, Fix, SideBc};

/// The four sides of the specimen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    Bottom,
    Right,
    Top,
    Left,
}

impl Side {
    pub const ALL: [Side; 4] = [Side::Bottom, Side::Right, Side::Top, Side::Left];

    /// The side's condition in the scene.
    pub fn of(self, b: &Boundary) -> SideBc {
        match self {
            Side::Bottom => b.bottom,
            Side::Right => b.right,
            Side::Top => b.top,
            Side::Left => b.left,
        }
    }

    /// Outward unit normal.
    pub fn normal(self) -> [f64; 2] {
        match self {
            Side::Bottom => [0.0, -1.0],
            Side::Right => [1.0, 0.0],
            Side::Top => [0.0, 1.0],
            Side::Left => [-1.0, 0.0],
        }
    }

    /// Global axis along which `shear` acts: +x on top/bottom, +y on left/right.
    pub fn shear_axis(self) -> [f64; 2] {
        match self {
            Side::Bottom | Side::Top => [1.0, 0.0],
            Side::Right | Side::Left => [0.0, 1.0],
        }
    }

    /// Nodes on the side, in order along it.
    pub fn nodes(self, m: &Mesh) -> Vec<usize> {
        match self {
            Side::Bottom => (0..=m.nx).map(|i| m.node_id(i, 0)).collect(),
            Side::Top => (0..=m.nx).map(|i| m.node_id(i, m.ny)).collect(),
            Side::Left => (0..=m.ny).map(|j| m.node_id(0, j)).collect(),
            Side::Right => (0..=m.ny).map(|j| m.node_id(m.nx, j)).collect(),
        }
    }

    /// Elements along the side with the local corner indices of their edge
    /// on it.
    pub fn edges(self, m: &Mesh) -> Vec<(usize, [usize; 2])> {
        match self {
            Side::Bottom => (0..m.nx).map(|i| (i, [0, 1])).collect(),
            Side::Top => (0..m.nx).map(|i| ((m.ny - 1) * m.nx + i, [3, 2])).collect(),
            Side::Left => (0..m.ny).map(|j| (j * m.nx, [0, 3])).collect(),
            Side::Right => (0..m.ny).map(|j| (j * m.nx + m.nx - 1, [1, 2])).collect(),
        }
    }

    /// Traction vector (Pa) of a `traction` side, or `None`.
    pub fn traction(self, b: &Boundary) -> Option<[f64; 2]> {
        match self.of(b) {
            SideBc::Traction { normal, shear } => {
                let (n, s) = (self.normal(), self.shear_axis());
                Some([normal * n[0] + shear * s[0], normal * n[1] + shear * s[1]])
            }
            _ => None,
        }
    }
}

/// Constrained standard DOFs: `fixed[2n + c]` for node `n`, component `c`.
pub fn constrained_dofs(m: &Mesh, b: &Boundary) -> Vec<bool> {
    let mut fixed = vec![false; 2 * m.node_count()];
    for side in Side::ALL {
        let comps: &[usize] = match (side.of(b), side) {
            (SideBc::Fixed, _) => &[0, 1],
            (SideBc::Roller, Side::Left | Side::Right) => &[0],
            (SideBc::Roller, Side::Bottom | Side::Top) => &[1],
            _ => &[],
        };
        for n in side.nodes(m) {
            for &c in comps {
                fixed[2 * n + c] = true;
            }
        }
    }
    for p in &b.points {
        let n = nearest_node(m, p.at);
        let comps: &[usize] = match p.fix {
            Fix::X => &[0],
            Fix::Y => &[1],
            Fix::Xy => &[0, 1],
        };
        for &c in comps {
            fixed[2 * n + c] = true;
        }
    }
    fixed
}

/// The node nearest to a point.
pub fn nearest_node(m: &Mesh, at: [f64; 2]) -> usize {
    let i = ((at[0] / m.hx).round().max(0.0) as usize).min(m.nx);
    let j = ((at[1] / m.hy).round().max(0.0) as usize).min(m.ny);
    m.node_id(i, j)
}
