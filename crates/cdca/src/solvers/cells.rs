//! The cells of the automaton (SPEC §6): one cell per node, owning the
//! node's free DOFs (2 standard + its enriched ones).
//!
//! A cell knows only the elements around it: for each, the element's index
//! in the [`ElementOperator`] and the local positions of the cell's DOFs in
//! that element. Its diagonal block `K_ii = Σ_{e∋i} K_e[loc_i, loc_i]` is
//! assembled from those element matrices and inverted once per operator
//! (through a Cholesky factorisation, which also checks that it is SPD).
//!
//! A cell update against the running residual `r = f − K u` is
//!
//! ```text
//! Δu_i = ω K_ii⁻¹ r_i,   u_i += Δu_i,   r_k −= Σ_{e∋i} K_e[k, loc_i] Δu_i
//! ```
//!
//! for every DOF `k` of the elements around the cell (the cell's own DOFs
//! included). Sweeping the cells in order is block Gauss–Seidel (ω = 1) or
//! block SOR; a forward then a backward sweep is block symmetric SOR.

use nalgebra::DMatrix;

use crate::discretisation::dofs::FIXED;
use crate::error::SolveError;
use crate::geometry::mesh::Mesh;
use crate::scene::Ordering;
use crate::solvers::element_op::ElementOperator;

/// Per-node cells of one operator, with their factorised diagonal blocks.
#[derive(Clone, Debug, Default)]
pub struct Cells {
    /// Node of each cell (nodes without a free DOF have no cell).
    node: Vec<u32>,
    /// Cell `c` owns `dofs[dof_start[c]..dof_start[c + 1]]`.
    dof_start: Vec<usize>,
    dofs: Vec<u32>,
    /// `K_ii⁻¹` of cell `c`, row-major, at `inv[inv_start[c]..]`.
    inv_start: Vec<usize>,
    inv: Vec<f64>,
    /// Cell `c`'s elements are `link_elem[link_start[c]..link_start[c + 1]]`;
    /// link `l` has the cell's local positions `local[local_start[l]..]`.
    link_start: Vec<usize>,
    link_elem: Vec<u32>,
    local_start: Vec<usize>,
    local: Vec<u16>,
    /// Sweep order (cell indices).
    order: Vec<u32>,
    /// Scratch: the cell's residual and update.
    ri: Vec<f64>,
    du: Vec<f64>,
}

impl Cells {
    /// Builds the cells of `op` on a structured grid `topo` (only its
    /// topology is used), where `node_dofs[n]` lists node `n`'s free DOFs.
    pub fn new(
        op: &ElementOperator,
        topo: &Mesh,
        node_dofs: &[Vec<u32>],
        ordering: Ordering,
    ) -> Result<Self, SolveError> {
        let mut c = Self {
            dof_start: vec![0],
            inv_start: vec![0],
            link_start: vec![0],
            ..Self::default()
        };
        let mut max_m = 0;
        for (n, nd) in node_dofs.iter().enumerate() {
            if nd.is_empty() {
                continue;
            }
            let m = nd.len();
            max_m = max_m.max(m);
            for e in topo.node_elements(n) {
                let ed = op.element_dofs(e);
                let first = c.local.len();
                for &d in nd {
                    let pos = ed.iter().position(|&x| x == d);
                    let Some(pos) = pos else {
                        panic!("DOF {d} of node {n} is missing from element {e}");
                    };
                    c.local.push(pos as u16);
                }
                c.local_start.push(first);
                c.link_elem.push(e as u32);
            }
            c.link_start.push(c.link_elem.len());
            c.dofs.extend_from_slice(nd);
            c.dof_start.push(c.dofs.len());
            c.node.push(n as u32);
            let inv = c.inverse_block(op, c.node.len() - 1)?;
            c.inv.extend_from_slice(inv.as_slice());
            c.inv_start.push(c.inv.len());
        }
        c.local_start.push(c.local.len());
        c.order = sweep_order(topo, &c.node, ordering);
        c.ri = vec![0.0; max_m];
        c.du = vec![0.0; max_m];
        Ok(c)
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.node.len()
    }

    pub fn is_empty(&self) -> bool {
        self.node.is_empty()
    }

    /// `K_ii⁻¹` of cell `c` from the current element matrices of `op`
    /// (its links must be in place).
    fn inverse_block(&self, op: &ElementOperator, c: usize) -> Result<DMatrix<f64>, SolveError> {
        let m = self.dof_start[c + 1] - self.dof_start[c];
        let mut kii = DMatrix::<f64>::zeros(m, m);
        for l in self.link_start[c]..self.link_start[c + 1] {
            let e = self.link_elem[l] as usize;
            let size = op.element_dofs(e).len();
            let loc = &self.local[self.local_start[l]..self.local_start[l] + m];
            let k = op.element_matrix(e);
            for (a, &la) in loc.iter().enumerate() {
                for (b, &lb) in loc.iter().enumerate() {
                    kii[(a, b)] += k[la as usize * size + lb as usize];
                }
            }
        }
        invert_spd(kii).ok_or_else(|| SolveError::NotPositiveDefinite {
            dofs: op.n,
            detail: format!(
                "diagonal block of node {} ({m} DOFs) is not positive definite",
                self.node[c]
            ),
        })
    }

    /// Refactors the diagonal block of cell `c` after the matrix of one of
    /// its elements in `op` changed (a contact point changed state).
    pub fn refactor(&mut self, op: &ElementOperator, c: usize) -> Result<(), SolveError> {
        let inv = self.inverse_block(op, c)?;
        self.inv[self.inv_start[c]..self.inv_start[c + 1]].copy_from_slice(inv.as_slice());
        Ok(())
    }

    /// Node of cell `c`.
    pub fn node(&self, c: usize) -> usize {
        self.node[c] as usize
    }

    /// Free DOFs of cell `c` (standard first).
    pub fn dofs(&self, c: usize) -> &[u32] {
        &self.dofs[self.dof_start[c]..self.dof_start[c + 1]]
    }

    /// The cells in sweep order.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// One sweep over all cells (forward order, or backward when
    /// `backward`), updating `u` and the running residual `r` in place.
    /// Returns `max |Δu|`.
    pub fn sweep(
        &mut self,
        op: &ElementOperator,
        omega: f64,
        backward: bool,
        u: &mut [f64],
        r: &mut [f64],
    ) -> Result<f64, SolveError> {
        let mut max_du: f64 = 0.0;
        for k in 0..self.order.len() {
            let c = if backward {
                self.order[self.order.len() - 1 - k]
            } else {
                self.order[k]
            } as usize;
            max_du = max_du.max(self.update(op, c, omega, u, r)?);
        }
        Ok(max_du)
    }

    /// Updates cell `c` against the running residual `r` (`Δu_c = ω K_cc⁻¹
    /// r_c`, then `r_k −= K_kc Δu_c`); returns its `max |Δu|`.
    #[inline]
    pub fn update(
        &mut self,
        op: &ElementOperator,
        c: usize,
        omega: f64,
        u: &mut [f64],
        r: &mut [f64],
    ) -> Result<f64, SolveError> {
        let dofs = &self.dofs[self.dof_start[c]..self.dof_start[c + 1]];
        let m = dofs.len();
        let inv = &self.inv[self.inv_start[c]..self.inv_start[c + 1]];
        let (ri, du) = (&mut self.ri[..m], &mut self.du[..m]);
        for (v, &d) in ri.iter_mut().zip(dofs) {
            *v = r[d as usize];
        }
        let mut max_du: f64 = 0.0;
        for (a, row) in inv.chunks_exact(m).enumerate() {
            let v = omega * row.iter().zip(ri.iter()).map(|(x, y)| x * y).sum::<f64>();
            if !v.is_finite() {
                return Err(SolveError::NonFinite {
                    place: format!("cell update of node {}", self.node[c]),
                });
            }
            du[a] = v;
            u[dofs[a] as usize] += v;
            max_du = max_du.max(v.abs());
        }
        for l in self.link_start[c]..self.link_start[c + 1] {
            let e = self.link_elem[l] as usize;
            let ed = op.element_dofs(e);
            let k = op.element_matrix(e);
            let nd = ed.len();
            let loc = &self.local[self.local_start[l]..self.local_start[l] + m];
            // K_e is symmetric: column `loc[a]` is row `loc[a]`
            if m == 2 && nd == 8 {
                let c0 = &k[loc[0] as usize * 8..loc[0] as usize * 8 + 8];
                let c1 = &k[loc[1] as usize * 8..loc[1] as usize * 8 + 8];
                for j in 0..8 {
                    if ed[j] != FIXED {
                        r[ed[j] as usize] -= c0[j] * du[0] + c1[j] * du[1];
                    }
                }
            } else {
                for (a, &la) in loc.iter().enumerate() {
                    let col = &k[la as usize * nd..(la as usize + 1) * nd];
                    for (&d, &kv) in ed.iter().zip(col) {
                        if d != FIXED {
                            r[d as usize] -= kv * du[a];
                        }
                    }
                }
            }
        }
        Ok(max_du)
    }
}

/// Free DOFs of every node of a discretisation (standard first).
pub fn node_dofs(x: &crate::discretisation::xfem::Xfem) -> Vec<Vec<u32>> {
    (0..x.mesh.node_count())
        .map(|n| x.dofs.node_free(n).collect())
        .collect()
}

/// Inverse of a symmetric positive definite block through its Cholesky
/// factor; `None` when the block is not SPD (or not finite).
fn invert_spd(k: DMatrix<f64>) -> Option<DMatrix<f64>> {
    if !k.iter().all(|v| v.is_finite()) {
        return None;
    }
    let chol = k.cholesky()?;
    let inv = chol.inverse();
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// Visiting order of the cells: lexicographic (node number), or four
/// colours `(i mod 2, j mod 2)` one after the other. Nodes of one colour
/// share no element, so their updates are independent (the Q4 analogue of
/// red–black ordering).
fn sweep_order(topo: &Mesh, nodes: &[u32], ordering: Ordering) -> Vec<u32> {
    let mut order: Vec<u32> = (0..nodes.len() as u32).collect();
    if ordering == Ordering::RedBlack {
        let colour = |c: &u32| {
            let (i, j) = topo.node_ij(nodes[*c as usize] as usize);
            (i % 2) + 2 * (j % 2)
        };
        order.sort_by_key(colour); // stable: lexicographic within a colour
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four-colour ordering: nodes of one colour never share an element,
    /// so their updates commute (the property red–black ordering needs).
    #[test]
    fn same_colour_nodes_share_no_element() {
        let m = Mesh::new(1.0, 1.0, 5, 4);
        let nodes: Vec<u32> = (0..m.node_count() as u32).collect();
        let order = sweep_order(&m, &nodes, Ordering::RedBlack);
        assert_eq!(order.len(), m.node_count());
        let colour = |n: usize| {
            let (i, j) = m.node_ij(n);
            (i % 2) + 2 * (j % 2)
        };
        let colours: Vec<usize> = order.iter().map(|&c| colour(c as usize)).collect();
        assert!(
            colours.windows(2).all(|w| w[0] <= w[1]),
            "colours are not contiguous"
        );
        for e in 0..m.element_count() {
            let c: Vec<usize> = m.element_nodes(e).iter().map(|&n| colour(n)).collect();
            for a in 0..4 {
                for b in a + 1..4 {
                    assert_ne!(c[a], c[b], "element {e} has two nodes of one colour");
                }
            }
        }
    }
}
