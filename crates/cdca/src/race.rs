//! Error against run time: one scene's linear system at full load with its
//! contact states settled, the direct solution as the reference, and the
//! errors of any iterate against it. Shared by `cdca bench` and the
//! workbench's solver race, so that both measure the same thing.
//!
//! Uses the discretisation, the solvers, the contact law and the SIFs.

use crate::contact::iteration::solve_with_contact;
use crate::contact::law::{FaceState, contact_system, gaps, update_point};
use crate::contact::status::ContactParams;
use crate::discretisation::assembly::ElementBlock;
use crate::discretisation::loads::traction_forces;
use crate::discretisation::model::Model;
use crate::discretisation::xfem::Xfem;
use crate::error::SolveError;
use crate::fracture::tips::TipDomains;
use crate::geometry::plane::P2;
use crate::scene::Scene;
use crate::solvers::element_op::ElementOperator;
use crate::solvers::linear::DirectSolver;

/// The system every solver of a race solves: `(K + blocks) u = f`.
pub struct RaceSystem {
    /// A fresh discretisation: nothing cached, so the first direct solve on
    /// it pays for its symbolic factorisation, as a real solve does.
    pub x: Xfem,
    pub blocks: Vec<ElementBlock>,
    pub f: Vec<f64>,
}

impl RaceSystem {
    /// The scene at full load with its contact states settled by the
    /// direct solver from the scene's own (open) states.
    pub fn settle(scene: &Scene, params: ContactParams) -> Result<Self, SolveError> {
        let model = Model::new(scene.clone());
        let settling = model.discretise(model.initial_cracks());
        let f_ext = traction_forces(&settling, &scene.boundary);
        let committed = vec![FaceState::default(); settling.faces.len()];
        let mut u = vec![0.0; settling.n_free()];
        let (states, _) = solve_with_contact(
            &settling,
            &f_ext,
            &committed,
            &mut u,
            &mut DirectSolver::default(),
            params,
        )?;
        let x = model.discretise(model.initial_cracks());
        let mut f = f_ext;
        let blocks = contact_system(&x, &states, &committed, &mut f);
        Ok(Self { x, blocks, f })
    }
}

/// Errors at one checkpoint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub iteration: usize,
    /// Solver time so far (setup included), s.
    pub seconds: f64,
    /// ‖u − u_ref‖_K / ‖u_ref‖_K.
    pub energy: f64,
    /// max over tips |K_I − K_I,ref| / max |K_ref|.
    pub k1: f64,
    /// The same for K_II.
    pub k2: f64,
}

/// The direct solution, its energy norm and its SIFs (and the tips'
/// interaction-integral domains, made once: every sample reads them).
pub struct Reference {
    u: Vec<f64>,
    domains: TipDomains,
    energy: f64,
    k: Vec<(f64, f64)>,
    /// Largest |K| of the reference (the scale of the K errors).
    scale: f64,
}

impl Reference {
    pub fn new(x: &Xfem, op: &ElementOperator, u: &[f64]) -> Self {
        let mut kv = vec![0.0; u.len()];
        let domains = TipDomains::new(x);
        let k = sifs(x, &domains, u);
        let scale = k
            .iter()
            .fold(0.0_f64, |m, (a, b)| m.max(a.abs()).max(b.abs()));
        Self {
            u: u.to_vec(),
            domains,
            energy: op.energy(u, &mut kv).max(0.0).sqrt(),
            k,
            scale,
        }
    }

    /// Errors of `u` against the reference.
    pub fn sample(
        &self,
        x: &Xfem,
        op: &ElementOperator,
        u: &[f64],
        iteration: usize,
        seconds: f64,
    ) -> Sample {
        let e: Vec<f64> = u.iter().zip(&self.u).map(|(a, b)| a - b).collect();
        let mut kv = vec![0.0; u.len()];
        let energy = relative(op.energy(&e, &mut kv).max(0.0).sqrt(), self.energy);
        let k = sifs(x, &self.domains, u);
        let err = |pick: fn(&(f64, f64)) -> f64| {
            k.iter().zip(&self.k).fold(0.0_f64, |m, (a, b)| {
                m.max(relative((pick(a) - pick(b)).abs(), self.scale))
            })
        };
        Sample {
            iteration,
            seconds,
            energy,
            k1: err(|p| p.0),
            k2: err(|p| p.1),
        }
    }
}

/// `a / b`, or `a` itself when `b` is zero (nothing to be relative to).
fn relative(a: f64, b: f64) -> f64 {
    if b > 0.0 { a / b } else { a }
}

/// (K_I, K_II) of every free tip (`domains`: `x`'s), with the contact
/// tractions of the states that `u` itself implies.
fn sifs(x: &Xfem, domains: &TipDomains, u: &[f64]) -> Vec<(f64, f64)> {
    let tractions: Vec<P2> = x
        .faces
        .iter()
        .map(|fp| {
            let (gn, gt) = gaps(x, fp, u);
            update_point(&x.funcs.cracks[fp.crack], 0.0, gn, gt).traction(fp)
        })
        .collect();
    domains
        .sifs(x, u, &tractions)
        .into_iter()
        .map(|(_, _, _, s)| (s.k1, s.k2))
        .collect()
}
