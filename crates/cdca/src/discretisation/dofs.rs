//! The one authority for DOF numbers.
//!
//! Every node has two standard DOFs `(u_x, u_y)` followed by two per scalar
//! enrichment function it carries. DOFs are numbered node by node ("all"
//! numbering); constrained standard DOFs are then dropped and the rest are
//! renumbered densely ("free" numbering), which is what solvers see.

use crate::discretisation::enrichment::Enrichment;

/// Marks a constrained DOF in the free numbering.
pub const FIXED: u32 = u32::MAX;

/// An enrichment carried by a node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeEnrichment {
    pub kind: Enrichment,
    /// Value of each scalar function at the node (the shift).
    pub shift: [f64; 4],
    /// "All" index of the first (x) DOF of its first scalar function.
    pub first: usize,
}

/// DOF numbering of the whole mesh.
#[derive(Clone, Debug, Default)]
pub struct DofMap {
    /// "All" index of `u_x` of each node.
    pub node_first: Vec<usize>,
    /// Enrichments of each node (empty for most nodes).
    pub node_enr: Vec<Vec<NodeEnrichment>>,
    /// Free index of each "all" DOF, or [`FIXED`].
    pub free: Vec<u32>,
    /// Number of free DOFs.
    pub n_free: usize,
    /// Number of free enriched DOFs.
    pub n_enriched: usize,
}

impl DofMap {
    /// Numbers the DOFs. `enr[n]` lists node `n`'s enrichments (with their
    /// shifts) and `fixed[2n + c]` tells whether standard component `c` of
    /// node `n` is constrained.
    pub fn new(enr: Vec<Vec<(Enrichment, [f64; 4])>>, fixed: &[bool]) -> Self {
        let nn = enr.len();
        let mut node_first = Vec::with_capacity(nn);
        let mut node_enr = Vec::with_capacity(nn);
        let mut next = 0;
        for list in enr {
            node_first.push(next);
            next += 2;
            let mut v = Vec::with_capacity(list.len());
            for (kind, shift) in list {
                v.push(NodeEnrichment {
                    kind,
                    shift,
                    first: next,
                });
                next += 2 * kind.functions();
            }
            node_enr.push(v);
        }
        let mut free = vec![FIXED; next];
        let mut n_free = 0u32;
        let mut n_enriched = 0;
        for n in 0..nn {
            let end = node_first.get(n + 1).copied().unwrap_or(next);
            for a in node_first[n]..end {
                let is_std = a < node_first[n] + 2;
                if is_std && fixed[2 * n + (a - node_first[n])] {
                    continue;
                }
                free[a] = n_free;
                n_free += 1;
                if !is_std {
                    n_enriched += 1;
                }
            }
        }
        Self {
            node_first,
            node_enr,
            free,
            n_free: n_free as usize,
            n_enriched,
        }
    }

    /// Free index of standard component `c` (0 = x, 1 = y) of node `n`.
    pub fn std_free(&self, n: usize, c: usize) -> u32 {
        self.free[self.node_first[n] + c]
    }

    /// Free indices of all DOFs of node `n` (standard first), skipping
    /// constrained ones.
    pub fn node_free(&self, n: usize) -> impl Iterator<Item = u32> + '_ {
        let end = self
            .node_first
            .get(n + 1)
            .copied()
            .unwrap_or(self.free.len());
        self.free[self.node_first[n]..end]
            .iter()
            .copied()
            .filter(|&f| f != FIXED)
    }

    /// Whether node `n` carries any enrichment.
    pub fn is_enriched(&self, n: usize) -> bool {
        !self.node_enr[n].is_empty()
    }
}
