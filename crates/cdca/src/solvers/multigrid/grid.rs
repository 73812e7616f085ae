//! One level of the multigrid hierarchy: the grid's geometry and DOFs, and
//! the local DOF layout of its elements. Shared by the coarsening and the
//! Galerkin product.

use crate::discretisation::dofs::FIXED;
use crate::discretisation::enrichment::Enrichment;
use crate::discretisation::xfem::{REGULAR, Xfem};
use crate::geometry::mesh::Mesh;
use crate::geometry::plane::P2;

/// Grid offsets of the corners of an element, in local corner order.
pub const CORNER: [(usize, usize); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

/// What a local DOF of an element is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Std,
    Heaviside(usize),
    Other,
}

/// A local DOF: corner, component, kind.
pub type LocalDof = (usize, usize, Kind);

/// Geometry and DOFs of one level.
#[derive(Clone, Debug)]
pub struct Grid {
    /// Topology (node and element numbering); coordinates in `xs`, `ys`.
    pub topo: Mesh,
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    /// Standard DOFs `(x, y)` of each node, [`FIXED`] if constrained.
    pub std: Vec<[u32; 2]>,
    /// Heaviside DOFs of each node, by crack.
    pub heav: Vec<Vec<(usize, [u32; 2])>>,
    /// Local DOF layout of each element (`None`: the 8 standard DOFs).
    pub layout: Vec<Option<Vec<LocalDof>>>,
}

impl Grid {
    /// The fine grid of a discretisation.
    pub fn fine(x: &Xfem) -> Self {
        let m = &x.mesh;
        let heav = (0..m.node_count())
            .map(|n| {
                let list = x.dofs.node_enr[n].iter().filter_map(|ne| match ne.kind {
                    Enrichment::Heaviside { crack } => {
                        Some((crack, [x.dofs.free[ne.first], x.dofs.free[ne.first + 1]]))
                    }
                    Enrichment::Tip { .. } => None,
                });
                list.collect()
            })
            .collect();
        let layout = (0..m.element_count())
            .map(|e| {
                let slot = x.slot[e];
                (slot != REGULAR).then(|| {
                    let el = &x.enriched[slot as usize];
                    let kinds = el.scalars.iter().map(|s| match s.enr {
                        None => (s.node, Kind::Std),
                        Some((k, _, _)) => match el.enrs[k] {
                            Enrichment::Heaviside { crack } => (s.node, Kind::Heaviside(crack)),
                            Enrichment::Tip { .. } => (s.node, Kind::Other),
                        },
                    });
                    kinds.flat_map(|(q, k)| [(q, 0, k), (q, 1, k)]).collect()
                })
            })
            .collect();
        Self {
            topo: topology(m.nx, m.ny),
            xs: (0..=m.nx).map(|i| i as f64 * m.hx).collect(),
            ys: (0..=m.ny).map(|j| j as f64 * m.hy).collect(),
            std: (0..m.node_count())
                .map(|n| [x.dofs.std_free(n, 0), x.dofs.std_free(n, 1)])
                .collect(),
            heav,
            layout,
        }
    }

    /// Free DOFs of each node (coarse levels: standard and Heaviside).
    pub fn node_dofs(&self) -> Vec<Vec<u32>> {
        self.std
            .iter()
            .zip(&self.heav)
            .map(|(s, h)| {
                s.iter()
                    .chain(h.iter().flat_map(|(_, d)| d))
                    .copied()
                    .filter(|&d| d != FIXED)
                    .collect()
            })
            .collect()
    }

    pub fn pos(&self, n: usize) -> P2 {
        let (i, j) = self.topo.node_ij(n);
        P2::new(self.xs[i], self.ys[j])
    }
}

/// Linear weight of coarse end `side` (0 left, 1 right) at local `t`.
pub fn hat(side: usize, t: f64) -> f64 {
    if side == 0 { 1.0 - t } else { t }
}

/// Topology-only mesh of `nx × ny` elements.
pub fn topology(nx: usize, ny: usize) -> Mesh {
    Mesh::new(nx as f64, ny as f64, nx, ny)
}
