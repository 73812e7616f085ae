//! One solve at the current load factor: the contact iteration around the
//! scene's linear solver (SPEC §5–6), then every free tip evaluated (SIFs
//! and criterion, SPEC §7–8), and the solve report (SPEC §11), which names
//! a piece of the specimen held by nothing ([`Simulation::free_piece`]).

use web_time::Instant;

use super::state::Simulation;
use crate::contact::law::{ContactState, FaceState, counts};
use crate::error::SolveError;
use crate::fracture::kinks::evaluate_kinks;
use crate::fracture::rock::{RockStrength, intact_rock};
use crate::fracture::tips::{TipDomains, evaluate_tips};
use crate::geometry::cracks::{root, split_specimen};
use crate::geometry::plane::{P2, segment_intersection};
use crate::report::{
    ContactReport, FreePieceReport, IntactRockReport, OtherSolutionReport, SolveReport,
    SolverReport, WorkReport,
};
use crate::scene::SideBc;

impl Simulation {
    /// Full solve (with contact) at the current load factor with the scene's
    /// solver; fills SIFs and criterion at every free tip. The resumable
    /// solve of [`relax`](Self::relax), run to its end. Its `seconds` leave
    /// out the element integration of a new simulation (part of the build);
    /// its `work` splits the whole: the build (that integration, the
    /// pattern, the tips' domains), the contact solve, the evaluation (the
    /// intact rock's too) and the rest (the report).
    pub fn solve(&mut self) -> Result<SolveReport, SolveError> {
        let clock = Instant::now();
        self.start_relaxation();
        self.scratch.work = WorkReport::default();
        self.scratch.xfem.integrate(usize::MAX);
        self.scratch.work.build_seconds = clock.elapsed().as_secs_f64();
        let start = Instant::now();
        while !self.relax(usize::MAX)?.finished {}
        let seconds = start.elapsed().as_secs_f64();
        let rock = Instant::now();
        let intact_rock = self.intact_rock();
        self.scratch.work.evaluate_seconds += rock.elapsed().as_secs_f64();
        let mut report = SolveReport {
            intact_rock,
            ..self.report(seconds)
        };
        report.work = std::mem::take(&mut self.scratch.work);
        report.work.close(clock.elapsed().as_secs_f64());
        Ok(report)
    }

    /// What `cdca solve` reports: this new simulation's solve at full load
    /// and, where faces close, the same problem solved again from bonded
    /// faces ([`bonded_start`](Self::bonded_start), on this simulation's
    /// own discretisation), whose finding is `other_solution`. `started`
    /// is when the caller began (reading the scene); the report's `work`
    /// accounts for all from then to the report, this simulation freed:
    /// the time until this call is its `setup_seconds`, the second solve
    /// its `second_solve_seconds`, what no part times its `other_seconds`.
    pub fn solve_scene(mut self, started: Instant) -> Result<SolveReport, SolveError> {
        let setup_seconds = started.elapsed().as_secs_f64();
        self.set_load_factor(1.0);
        let mut report = self.solve()?;
        let mut second_solve_seconds = 0.0;
        // Coulomb friction need not have one solution
        if OtherSolutionReport::worth_checking(&report) {
            let clock = Instant::now();
            let second = self.into_bonded_start()?.solve()?;
            report.other_solution = OtherSolutionReport::between(&report, &second, "bonded");
            second_solve_seconds = clock.elapsed().as_secs_f64();
        } else {
            drop(self);
        }
        let w = &mut report.work;
        w.setup_seconds = setup_seconds;
        w.second_solve_seconds = second_solve_seconds;
        w.close(started.elapsed().as_secs_f64());
        Ok(report)
    }

    /// A new simulation of this one's scene, cracks and load factor, with
    /// its discretisation copied (integrated elements, stiffness pattern)
    /// and nothing solved, set up so that its next solve starts from the
    /// opposite of the start [`solve`](Self::solve) makes on a new
    /// simulation: every face point closed and stuck with friction limits
    /// far above any traction (the faces bonded) instead of open with none.
    /// The contact iteration holds the friction limits fixed in a convex
    /// inner (Tresca) problem, whose solution does not depend on the
    /// states it starts from; the limits it starts from are what can lead
    /// it to another solution. Compare the two reports with
    /// [`OtherSolutionReport::between`](crate::report::OtherSolutionReport::between).
    /// Meant for a simulation without growth history (a scene's solve).
    pub fn bonded_start(&self) -> Result<Self, SolveError> {
        Self::from_parts(
            self.model.clone(),
            self.state.cracks.clone(),
            self.scratch.xfem.clone(),
            self.scratch.rebuild_points,
        )
        .map(|s| s.bonded(self.state.lambda))
    }

    /// [`bonded_start`](Self::bonded_start) from this simulation's own
    /// discretisation, not a copy of it, where this one is no longer
    /// needed; its factor goes on as storage for the first factorisation
    /// (as in [`with_scene`](Self::with_scene)), which then redoes only
    /// the supernodes whose values changed, the same to the last bit.
    fn into_bonded_start(self) -> Result<Self, SolveError> {
        let lambda = self.state.lambda;
        let Self {
            model,
            state,
            mut scratch,
        } = self;
        let factor = scratch.solver.hand_over_factor();
        Self::from_parts(model, state.cracks, scratch.xfem, scratch.rebuild_points)
            .map(|s| s.adopt(factor).bonded(lambda))
    }

    /// This new simulation at `lambda`, its faces bonded (see
    /// [`bonded_start`](Self::bonded_start)).
    fn bonded(mut self, lambda: f64) -> Self {
        self.set_load_factor(lambda);
        // closed by the specimen's width: the first friction limits (μ k_N
        // |g_N| + c_c) lie far above any traction
        let g_n = -self.model.mesh.width;
        self.scratch.contact_guess = Some(
            self.state
                .faces
                .iter()
                .map(|f| FaceState {
                    state: ContactState::Stick,
                    g_n,
                    ..*f
                })
                .collect(),
        );
        self
    }

    /// The states the next contact iteration starts from: the guess left
    /// by the last critical-control trial, or the committed states.
    pub(super) fn initial_contact_states(&mut self) -> Vec<FaceState> {
        self.scratch
            .contact_guess
            .take()
            .filter(|g| g.len() == self.state.faces.len())
            .unwrap_or_else(|| self.state.faces.clone())
    }

    pub(super) fn evaluate(&mut self) {
        let x = &self.scratch.xfem;
        let kept = TipDomains::kept_for(&mut self.scratch.tip_domains, x);
        while kept.make_next(x) {}
        let domains = self.scratch.tip_domains.as_ref().expect("just made");
        let e = evaluate_tips(
            &self.scratch.xfem,
            domains,
            &self.state.u,
            &self.state.faces,
            &self.criterion_params(),
            self.model.scene.criterion_settings().sampling(),
        );
        self.scratch.tips = e.tips;
        self.scratch.circles = e.circles;
        self.scratch.tip_faces = e.faces;
        self.scratch.utilisation = e.utilisation;
        let (kinks, utilisation) = if self.model.scene.growth.secondary_cracks {
            evaluate_kinks(
                &self.scratch.xfem,
                &self.state.u,
                &self.state.faces,
                &self.criterion_params(),
            )
        } else {
            (Vec::new(), Vec::new())
        };
        self.scratch.kinks = kinks;
        self.scratch.kink_utilisation = utilisation;
    }

    /// The rock away from the cracks against its strength at the solved
    /// displacement; `None` while the state is not a solution of the
    /// current cracks, or for a rock without cohesion.
    pub fn intact_rock(&self) -> Option<IntactRockReport> {
        let x = &self.scratch.xfem;
        let strength = RockStrength::of_material(&self.model.scene.material)?;
        (self.state.solved && self.state.u.len() == x.n_free())
            .then(|| intact_rock(x, &self.state.u, &strength))
    }

    /// The report of the last solve (SPEC §11), `intact_rock` left at its
    /// default (see [`intact_rock`](Self::intact_rock)).
    pub fn report(&self, seconds: f64) -> SolveReport {
        let x = &self.scratch.xfem;
        let c = counts(&self.state.faces);
        let info = &self.scratch.contact;
        let kn_h_over_e = x
            .funcs
            .cracks
            .iter()
            .map(|c| c.kn * x.mesh.h() / x.elastic.young)
            .fold(0.0, f64::max);
        SolveReport {
            dofs: x.n_free(),
            enriched_dofs: x.dofs.n_enriched,
            solver: SolverReport {
                kind: self.scratch.solver.name().to_string(),
                iterations: info.linear_iterations,
                residual: info.last.residual,
                converged: info.last.converged,
                seconds,
                residual_history: info.last.history.clone(),
            },
            contact: ContactReport {
                iterations: info.iterations,
                converged: info.converged,
                open: c.open,
                stick: c.stick,
                slip: c.slip,
                kn_h_over_e,
                cycling: info.cycling,
                violating: info.violating,
                residual: info.residual,
                capped: info.capped,
                unsettled: info.unsettled,
            },
            tips: self.scratch.tips.clone(),
            // filled where a solve is reported, not for every λ_cr trial
            intact_rock: None,
            free_piece: if self.state.solved {
                self.free_piece()
            } else {
                None
            },
            kinks: self.scratch.kinks.clone(),
            other_solution: None,
            work: WorkReport::default(),
        }
    }
}

// Pieces of the specimen after a solve: the elements joined across every
// element side that no crack cuts, and across crack faces in contact
// (stick or slip), which carry load between the pieces. A piece with no
// support (no supported side, no point support) is free: under any load
// but a balanced one it has no equilibrium, and a solve of it is not a
// solution, whatever the linear solver reported (a direct solve of the
// cut-through edge crack used to report converged with true relative
// residuals of 0.25–2.9).
//
// Only specimens whose cracks join boundary to boundary
// ([`split_specimen`]) are checked, so the check costs nothing otherwise.
// A piece counts as supported when any of its elements touches a fixed
// or roller side or holds a point support (a roller alone would leave it
// free to slide: such a piece is not reported).

impl Simulation {
    /// The first piece of the specimen that nothing holds at the current
    /// contact states (see the comment above), or `None`.
    pub fn free_piece(&self) -> Option<FreePieceReport> {
        if !split_specimen(&self.state.cracks) {
            return None;
        }
        let mesh = &self.model.mesh;
        let n = mesh.element_count();
        let centre = |e: usize| {
            let (lo, hi) = mesh.element_box(e);
            (lo + hi) / 2.0
        };
        let cut = |a: P2, b: P2| {
            self.state.cracks.iter().position(|c| {
                c.segments()
                    .any(|(p, q)| segment_intersection(a, b, p, q).is_some())
            })
        };
        let mut parent: Vec<usize> = (0..n).collect();
        let union = |parent: &mut Vec<usize>, a: usize, b: usize| {
            let (ra, rb) = (root(parent, a), root(parent, b));
            parent[ra] = rb;
        };
        let mut cutting = Vec::new();
        for e in 0..n {
            let (i, j) = (e % mesh.nx, e / mesh.nx);
            let right = (i + 1 < mesh.nx).then_some(e + 1);
            let above = (j + 1 < mesh.ny).then_some(e + mesh.nx);
            for f in right.into_iter().chain(above) {
                match cut(centre(e), centre(f)) {
                    None => union(&mut parent, e, f),
                    Some(c) => cutting.push((e, f, c)),
                }
            }
        }
        // faces in contact hold the pieces on either side together
        let eps = 0.5 * mesh.hx.min(mesh.hy);
        for p in self.contact_points() {
            if p.state != ContactState::Open {
                let (x, nrm) = (P2::new(p.x, p.y), P2::new(p.normal[0], p.normal[1]));
                if let (Some(a), Some(b)) = (
                    mesh.element_at(x + eps * nrm),
                    mesh.element_at(x - eps * nrm),
                ) {
                    union(&mut parent, a, b);
                }
            }
        }
        let mut held = vec![false; n];
        let b = &self.scene().boundary;
        let supports = |s: SideBc| matches!(s, SideBc::Fixed | SideBc::Roller);
        let (nx, ny) = (mesh.nx, mesh.ny);
        let supported = (0..nx)
            .filter(|_| supports(b.bottom))
            .chain(
                (0..nx)
                    .filter(|_| supports(b.top))
                    .map(|i| (ny - 1) * nx + i),
            )
            .chain((0..ny).filter(|_| supports(b.left)).map(|j| j * nx))
            .chain(
                (0..ny)
                    .filter(|_| supports(b.right))
                    .map(|j| j * nx + nx - 1),
            )
            .chain(
                b.points
                    .iter()
                    .filter_map(|p| mesh.element_at(P2::new(p.at[0], p.at[1]))),
            )
            .collect::<Vec<_>>();
        for e in supported {
            let r = root(&mut parent, e);
            held[r] = true;
        }
        let free_root = (0..n).find(|&e| !held[root(&mut parent, e)])?;
        let free_root = root(&mut parent, free_root);
        let members: Vec<usize> = (0..n)
            .filter(|&e| root(&mut parent, e) == free_root)
            .collect();
        let sum = members.iter().fold(P2::zeros(), |s, &e| s + centre(e));
        let mid = sum / members.len() as f64;
        let mut bounding: Vec<usize> = cutting
            .iter()
            .filter(|&&(e, f, _)| {
                (root(&mut parent, e) == free_root) != (root(&mut parent, f) == free_root)
            })
            .map(|&(_, _, c)| c)
            .collect();
        bounding.sort_unstable();
        bounding.dedup();
        Some(FreePieceReport {
            elements: members.len(),
            centroid: [mid.x, mid.y],
            cracks: bounding,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// The solve from bonded faces on the first simulation's own
    /// discretisation, its factor taken on as storage (what `cdca solve`
    /// runs), reports what it reports on a copy with a new factor, to the
    /// last bit (times aside), on the bundled scenes whose faces close.
    #[test]
    fn the_bonded_start_solves_the_same_on_its_own_discretisation() {
        let untimed = |mut r: SolveReport| {
            r.solver.seconds = 0.0;
            r.work = WorkReport::default();
            r
        };
        for name in [
            "specimen_single_flaw",
            "specimen_two_flaws_stepped",
            "closed_crack_biaxial",
            "plate_45_biaxial_k0.2_mu0.5",
        ] {
            let path = format!(
                "{}/../../assets/scenes/{name}.json",
                env!("CARGO_MANIFEST_DIR")
            );
            let text = std::fs::read_to_string(&path).expect("bundled scene");
            let mut sim = Simulation::new(Scene::from_json(&text).expect("valid")).expect("valid");
            sim.set_load_factor(1.0);
            let first = sim.solve().expect("solve");
            assert!(OtherSolutionReport::worth_checking(&first), "{name}");
            let copied = sim.bonded_start().expect("valid").solve().expect("solve");
            let own = sim
                .into_bonded_start()
                .expect("valid")
                .solve()
                .expect("solve");
            assert_eq!(untimed(own), untimed(copied), "{name}");
        }
    }
}
