//! The extended finite element discretisation of one crack configuration,
//! in three parts: which nodes are enriched and how ([`classify`]), the
//! enriched elements' quadrature and stiffness ([`element`]), and the
//! crack-face pieces where contact acts ([`faces`]). [`Xfem`] holds them
//! with the DOF map.
//!
//! Built from the model (mesh, material, supports) and the current cracks;
//! rebuilt when cracks change. Elements with no enriched node share one
//! stiffness matrix `k0`, computed once.

pub mod classify;
pub mod element;
pub mod faces;

use std::cell::{OnceCell, RefCell};

use nalgebra::{DMatrix, SMatrix};

use crate::discretisation::dofs::{DofMap, FIXED};
use crate::discretisation::enrichment::EnrichmentFunctions;
use crate::discretisation::material::Elastic;
use crate::discretisation::pattern::{Pattern, Unanalysed};
use crate::discretisation::xfem::classify::{classify_nodes, element_segments, element_tips};
use crate::discretisation::xfem::element::{
    Previous, STIFFNESS_BATCH, add_stiffness, build_elements, eval_scalars, regular_stiffness,
};
use crate::discretisation::xfem::faces::build_faces;
use crate::error::SolveError;
use crate::geometry::cracks::{Crack, TipKind};
use crate::geometry::mesh::Mesh;
use crate::geometry::plane::P2;

pub use classify::{ScalarFn, XfemParams, prepare_cracks};
pub use element::{EnrichedElement, REGULAR};
pub use faces::{FACE_ORDER, FacePoint, MIN_TIP_PIECE};

/// Panic message for a solver given a discretisation built with
/// [`Xfem::build`] before [`Xfem::integrate`] completed it.
pub const NOT_INTEGRATED: &str = "element stiffness not yet integrated (Xfem::integrate)";

/// What may be reused from the previous discretisation after a crack
/// change: element data far enough from every point that moved, of
/// elements no redrawn crack enriches.
pub struct Reuse<'a> {
    pub previous: &'a Xfem,
    /// Old and new positions of the tips that changed.
    pub moved: Vec<P2>,
    /// Per crack (new numbering): its polyline was edited (not grown), so
    /// its enrichment changed everywhere; none of its elements is reused.
    pub redrawn: Vec<bool>,
}

/// The discretisation.
#[derive(Clone, Debug)]
pub struct Xfem {
    pub mesh: Mesh,
    pub elastic: Elastic,
    pub thickness: f64,
    pub params: XfemParams,
    pub funcs: EnrichmentFunctions,
    pub dofs: DofMap,
    /// Per element: index into `enriched`, or [`REGULAR`].
    pub slot: Vec<u32>,
    pub enriched: Vec<EnrichedElement>,
    /// Stiffness of an ordinary element (DOF order `x0 y0 x1 y1 …`).
    pub k0: SMatrix<f64, 8, 8>,
    pub faces: Vec<FacePoint>,
    /// Sparsity pattern and symbolic Cholesky of the stiffness, computed on
    /// first use and shared by every factorisation on this discretisation.
    pattern: OnceCell<Pattern>,
    /// The previous discretisation's pattern, taken by
    /// [`pattern`](Self::pattern) where it [fits](Pattern::fits).
    offered: RefCell<Option<Pattern>>,
    /// The pattern's first half, made by
    /// [`prepare_pattern`](Self::prepare_pattern).
    structure: RefCell<Option<Unanalysed>>,
    /// Slots of enriched elements whose stiffness is still to be integrated
    /// (see [`build`](Self::build)); empty once usable.
    unintegrated: Vec<u32>,
    /// Quadrature points of the last of `unintegrated` already summed.
    integrated_points: usize,
}

impl Xfem {
    /// Builds everything for the given cracks (tips already classified)
    /// but the stiffness of the enriched elements that could not be reused
    /// (the costly part of a rebuild after growth): [`integrate`](Self::integrate)
    /// computes it, at once or in chunks (so that the workbench can spread a
    /// rebuild over frames); solvers need it complete.
    pub fn build(
        mesh: Mesh,
        elastic: Elastic,
        thickness: f64,
        cracks: Vec<Crack>,
        fixed: &[bool],
        params: XfemParams,
        reuse: Option<&Reuse>,
    ) -> Self {
        let h = mesh.h();
        let funcs = EnrichmentFunctions::new(cracks, 1e-9 * h);
        let segs = element_segments(&mesh, &funcs.cracks);
        let tips = element_tips(&mesh, &funcs.cracks);
        let node_enr = classify_nodes(&mesh, &funcs, &segs, params);
        let dofs = DofMap::new(node_enr, fixed);
        let mut x = Self {
            k0: regular_stiffness(&mesh, &elastic, thickness),
            mesh,
            elastic,
            thickness,
            params,
            funcs,
            dofs,
            slot: Vec::new(),
            enriched: Vec::new(),
            faces: Vec::new(),
            pattern: OnceCell::new(),
            offered: RefCell::new(None),
            structure: RefCell::new(None),
            unintegrated: Vec::new(),
            integrated_points: 0,
        };
        let far = reuse.map_or(0.0, |r| {
            r.previous
                .funcs
                .cracks
                .iter()
                .chain(&x.funcs.cracks)
                .flat_map(|c| c.free_tips().map(|k| params.zone_radius(c, k, x.mesh.h())))
                .fold(0.0, f64::max)
                + 2.0 * x.mesh.h()
        });
        let changed = reuse.map_or_else(Vec::new, |r| {
            let mut changed = changed_functions(&r.previous.funcs.cracks, &x.funcs.cracks);
            for (c, &redrawn) in changed.iter_mut().zip(&r.redrawn) {
                *c |= redrawn;
            }
            changed
        });
        let previous = reuse.map(|r| Previous {
            slot: &r.previous.slot,
            enriched: &r.previous.enriched,
            moved: &r.moved,
            far,
            changed: &changed,
        });
        let elements = build_elements(&x.mesh, &x.funcs, &x.dofs, &segs, &tips, previous.as_ref());
        x.slot = elements.slot;
        x.enriched = elements.enriched;
        x.unintegrated = elements.unintegrated;
        x.faces = build_faces(&x.mesh, &x.funcs, &x.slot, &x.enriched, x.thickness);
        x
    }

    /// Integrates the stiffness of the enriched elements still without one,
    /// over about `max_points` quadrature points (whole batches of
    /// `add_stiffness`, at least one: an element may take several calls,
    /// near a tip one can have thousands of points); returns whether all have
    /// their stiffness now. Whole elements are integrated on the machine's
    /// threads (natively; a browser has one). The result depends neither on
    /// `max_points` nor on the threads.
    pub fn integrate(&mut self, max_points: usize) -> bool {
        let mut left = max_points;
        while left > 0
            && let Some(&slot) = self.unintegrated.last()
        {
            let slot = slot as usize;
            let (from, n) = (self.integrated_points, self.enriched[slot].qps.len());
            if from == 0 && n <= left {
                // whole elements on the threads; an element that does not
                // fit waits for the next call
                self.integrate_whole(left);
                break;
            }
            // slices end on a batch of `add_stiffness` (the stiffness does
            // not depend on the slicing), at least one batch a call
            let to = n.min(
                from.saturating_add(left.max(STIFFNESS_BATCH)) / STIFFNESS_BATCH * STIFFNESS_BATCH,
            );
            let mut k = if from == 0 {
                let nd = 2 * self.enriched[slot].scalars.len();
                DMatrix::zeros(nd, nd)
            } else {
                std::mem::take(&mut self.enriched[slot].k)
            };
            add_stiffness(
                &self.mesh,
                &self.funcs,
                &self.elastic,
                self.thickness,
                &self.enriched[slot],
                from..to,
                &mut k,
            );
            self.enriched[slot].k = k;
            left = left.saturating_sub(to - from);
            if to == n {
                self.unintegrated.pop();
                self.integrated_points = 0;
            } else {
                self.integrated_points = to;
            }
        }
        self.unintegrated.is_empty()
    }

    /// Integrates the stiffness of the last elements of `unintegrated`
    /// whose points add up to at most `max_points` (at least one), whole,
    /// spread over the [`worker_threads`]. Each element is summed by one
    /// thread in the order one thread would sum it, so the stiffness does
    /// not depend on the number of threads.
    fn integrate_whole(&mut self, max_points: usize) {
        let mut points = 0;
        let mut count = 0;
        for &s in self.unintegrated.iter().rev() {
            let n = self.enriched[s as usize].qps.len();
            if count > 0 && points + n > max_points {
                break;
            }
            points += n;
            count += 1;
        }
        let mut slots = self.unintegrated.split_off(self.unintegrated.len() - count);
        let threads = if points >= MIN_POINTS_PER_THREAD {
            worker_threads().min(points / MIN_POINTS_PER_THREAD)
        } else {
            1
        };
        // the largest first, each to the thread with the fewest points
        slots.sort_by_key(|&s| std::cmp::Reverse(self.enriched[s as usize].qps.len()));
        let mut groups = vec![(0, Vec::new()); threads];
        for s in slots {
            let g = groups
                .iter_mut()
                .min_by_key(|g| g.0)
                .expect("at least one group");
            g.0 += self.enriched[s as usize].qps.len();
            g.1.push(s);
        }
        let (mesh, funcs, elastic, enriched) =
            (&self.mesh, &self.funcs, &self.elastic, &self.enriched);
        let thickness = self.thickness;
        let integrate = |group: &[u32]| -> Vec<(u32, DMatrix<f64>)> {
            group
                .iter()
                .map(|&s| {
                    let el = &enriched[s as usize];
                    let nd = 2 * el.scalars.len();
                    let mut k = DMatrix::zeros(nd, nd);
                    let all = 0..el.qps.len();
                    add_stiffness(mesh, funcs, elastic, thickness, el, all, &mut k);
                    (s, k)
                })
                .collect()
        };
        let done: Vec<(u32, DMatrix<f64>)> = std::thread::scope(|scope| {
            let (first, rest) = groups.split_first().expect("at least one group");
            let handles: Vec<_> = rest
                .iter()
                .map(|g| scope.spawn(|| integrate(&g.1)))
                .collect();
            let mut done = integrate(&first.1);
            for h in handles {
                done.extend(h.join().expect("an integration thread panicked"));
            }
            done
        });
        for (s, k) in done {
            self.enriched[s as usize].k = k;
        }
    }

    /// Whether every element's stiffness is integrated (needed by every
    /// solver; see [`build`](Self::build)).
    pub fn is_integrated(&self) -> bool {
        self.unintegrated.is_empty()
    }

    /// Quadrature points still to be summed by [`integrate`](Self::integrate).
    pub fn points_to_integrate(&self) -> usize {
        self.unintegrated
            .iter()
            .map(|&s| self.enriched[s as usize].qps.len())
            .sum::<usize>()
            - self.integrated_points
    }

    /// Whether [`pattern`](Self::pattern) has been computed.
    pub fn has_pattern(&self) -> bool {
        self.pattern.get().is_some()
    }

    /// Values and gradients of the scalar shape functions of an enriched
    /// element at `x`.
    pub fn eval_enriched(
        &self,
        el: &EnrichedElement,
        x: P2,
        vals: &mut Vec<f64>,
        grads: &mut Vec<P2>,
    ) {
        eval_scalars(&self.mesh, &self.funcs, el, x, None, vals, grads);
    }

    /// The same at a point of crack `face.0`, taken on side `face.1` (±1).
    pub fn eval_enriched_sided(
        &self,
        el: &EnrichedElement,
        x: P2,
        face: Option<(usize, f64)>,
        vals: &mut Vec<f64>,
        grads: &mut Vec<P2>,
    ) {
        eval_scalars(&self.mesh, &self.funcs, el, x, face, vals, grads);
    }

    /// Scalar shape functions of any element at `x` and the element's free
    /// DOFs (two per scalar).
    pub fn eval_element(
        &self,
        e: usize,
        x: P2,
        vals: &mut Vec<f64>,
        grads: &mut Vec<P2>,
        dofs: &mut Vec<u32>,
    ) {
        dofs.clear();
        let slot = self.slot[e];
        if slot == REGULAR {
            let (n, dn) = self.mesh.shape(e, x);
            vals.clear();
            grads.clear();
            vals.extend_from_slice(&n);
            grads.extend_from_slice(&dn);
            dofs.extend_from_slice(&self.regular_dofs(e));
        } else {
            let el = &self.enriched[slot as usize];
            self.eval_enriched(el, x, vals, grads);
            dofs.extend_from_slice(&el.dofs);
        }
    }

    /// Free DOFs of an ordinary element, order `x0 y0 … x3 y3`.
    pub fn regular_dofs(&self, e: usize) -> [u32; 8] {
        let nodes = self.mesh.element_nodes(e);
        let mut d = [FIXED; 8];
        for (i, &n) in nodes.iter().enumerate() {
            d[2 * i] = self.dofs.std_free(n, 0);
            d[2 * i + 1] = self.dofs.std_free(n, 1);
        }
        d
    }
    /// The stiffness pattern with its symbolic factorisation (computed once).
    /// Its elements are the regular elements in mesh order, then the
    /// enriched ones in slot order.
    pub fn pattern(&self) -> Result<&Pattern, SolveError> {
        if let Some(p) = self.pattern.get() {
            return Ok(p);
        }
        let structure = self.structure.borrow_mut().take();
        let p = match structure {
            Some(u) => u.analyse()?,
            None => match self.kept_or_structure()? {
                Ok(p) => p,
                Err(u) => u.analyse()?,
            },
        };
        Ok(self.pattern.get_or_init(|| p))
    }

    /// Half of [`pattern`](Self::pattern) per call, for a frame that
    /// should hold only one (the structure, then its symbolic
    /// factorisation; or the offered pattern, which needs neither):
    /// whether the pattern is ready.
    pub fn prepare_pattern(&self) -> Result<bool, SolveError> {
        if self.pattern.get().is_some() || self.structure.borrow().is_some() {
            self.pattern()?;
            return Ok(true);
        }
        match self.kept_or_structure()? {
            Ok(p) => {
                self.pattern.get_or_init(|| p);
                Ok(true)
            }
            Err(u) => {
                *self.structure.borrow_mut() = Some(u);
                Ok(false)
            }
        }
    }

    /// The offered pattern where it fits, or else the first half of a new
    /// one ([`Pattern::structure`]).
    fn kept_or_structure(&self) -> Result<Result<Pattern, Unanalysed>, SolveError> {
        let n_elements = self.mesh.element_count();
        let mut dofs = Vec::with_capacity(8 * n_elements);
        let mut starts = Vec::with_capacity(n_elements + 1);
        starts.push(0);
        for e in 0..n_elements {
            if self.slot[e] == REGULAR {
                dofs.extend_from_slice(&self.regular_dofs(e));
                starts.push(dofs.len());
            }
        }
        for el in &self.enriched {
            dofs.extend_from_slice(&el.dofs);
            starts.push(dofs.len());
        }
        let perm: Vec<usize> = self
            .mesh
            .nested_dissection()
            .into_iter()
            .flat_map(|node| self.dofs.node_free(node).map(|d| d as usize))
            .collect();
        let offered = self.offered.borrow_mut().take();
        Ok(match offered {
            Some(p) if p.fits(&dofs, &starts, &perm) => Ok(p),
            _ => Err(Pattern::structure(self.n_free(), &dofs, &starts, perm)?),
        })
    }

    /// The pattern, if computed, taken out (to be
    /// [offered](Self::offer_pattern) to the next discretisation).
    pub fn take_pattern(&mut self) -> Option<Pattern> {
        self.pattern.take()
    }

    /// Offers `pattern` (the previous discretisation's) to
    /// [`pattern`](Self::pattern), which takes it instead of computing its
    /// own where its elements couple the same DOFs in the same order.
    pub fn offer_pattern(&mut self, pattern: Option<Pattern>) {
        *self.offered.get_mut() = pattern;
    }

    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.dofs.n_free
    }
}

/// Quadrature points below which one more thread does not pay for its
/// start (about 0.2 ms of element integration).
const MIN_POINTS_PER_THREAD: usize = 500;

/// Threads the element integration uses: as set by
/// [`set_integration_threads`], else the machine's, at most four (one
/// where threads are not available, as in a browser).
fn worker_threads() -> usize {
    static THREADS: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    match THREADS_SET.load(std::sync::atomic::Ordering::Relaxed) {
        0 => *THREADS
            .get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get().min(4))),
        n => n,
    }
}

/// The cap set by [`set_integration_threads`] (0: none).
static THREADS_SET: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// Caps the threads of the element integration at `n` (0: the machine's,
/// at most four) for every simulation of the process from now on: a
/// caller that runs simulations side by side (`cdca study --jobs N`) keeps
/// jobs × threads within the cores. The stiffness does not depend on it
/// (see [`Xfem::integrate`]). The solver's other parts use one thread
/// (faer is built without its thread pool, and runs with `Par::Seq`).
pub fn set_integration_threads(n: usize) {
    THREADS_SET.store(n, std::sync::atomic::Ordering::Relaxed);
}

/// Per crack of `new`: whether its enrichment functions may differ from
/// those of `old` away from its moved tips: it is new, its tip kinds
/// changed, or one of its tips is a junction on a crack whose polyline
/// changed (the junction function follows the main crack's level set).
fn changed_functions(old: &[Crack], new: &[Crack]) -> Vec<bool> {
    let moved = |m: usize| old.get(m).is_none_or(|o| o.points != new[m].points);
    new.iter()
        .enumerate()
        .map(|(i, c)| {
            old.get(i).is_none_or(|o| o.tips != c.tips)
                || c.tips
                    .iter()
                    .any(|t| matches!(*t, TipKind::Junction { main } if moved(main)))
        })
        .collect()
}
