//! One solve at the current load factor: the contact iteration around the
//! scene's linear solver (SPEC §5–6), then every free tip evaluated (SIFs
//! and criterion, SPEC §7–8), and the solve report (SPEC §11), which names
//! a piece of the specimen held by nothing ([`Simulation::free_piece`]).

use web_time::Instant;

use super::state::Simulation;
use crate::contact::law::{ContactState, FaceState, counts};
use crate::error::SolveError;
use crate::fracture::rock::{RockStrength, intact_rock};
use crate::fracture::tips::evaluate_tips;
use crate::geometry::cracks::split_specimen;
use crate::report::{ContactReport, FreePieceReport, IntactRockReport, SolveReport, SolverReport};
use crate::scene::SideBc;

impl Simulation {
    /// Full solve (with contact) at the current load factor with the scene's
    /// solver; fills SIFs and criterion at every free tip. The resumable
    /// solve of [`relax`](Self::relax), run to its end. Its `seconds` leave
    /// out the element integration of a new simulation (part of the build).
    pub fn solve(&mut self) -> Result<SolveReport, SolveError> {
        self.start_relaxation();
        self.scratch.xfem.integrate(usize::MAX);
        let start = Instant::now();
        while !self.relax(usize::MAX)?.finished {}
        Ok(SolveReport {
            intact_rock: self.intact_rock(),
            ..self.report(start.elapsed().as_secs_f64())
        })
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
        let e = evaluate_tips(
            &self.scratch.xfem,
            &self.state.u,
            &self.state.faces,
            &self.criterion_params(),
            self.model.scene.criterion_settings().sampling(),
        );
        self.scratch.tips = e.tips;
        self.scratch.circles = e.circles;
        self.scratch.tip_faces = e.faces;
        self.scratch.utilisation = e.utilisation;
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
    /// contact states (see the module docs), or `None`.
    pub fn free_piece(&self) -> Option<FreePieceReport> {
        if !split_specimen(&self.state.cracks) {
            return None;
        }
        let scene = self.scene();
        let (nx, ny) = (scene.mesh.nx, scene.mesh.ny);
        let (w, h) = (scene.specimen.width, scene.specimen.height);
        let (dx, dy) = (w / nx as f64, h / ny as f64);
        let centre = |e: usize| [((e % nx) as f64 + 0.5) * dx, ((e / nx) as f64 + 0.5) * dy];
        let element_at = |p: [f64; 2]| {
            let i = ((p[0] / dx).floor().max(0.0) as usize).min(nx - 1);
            let j = ((p[1] / dy).floor().max(0.0) as usize).min(ny - 1);
            j * nx + i
        };
        let cracks = self.cracks();
        let cut = |a: [f64; 2], b: [f64; 2]| {
            cracks
                .iter()
                .position(|c| c.windows(2).any(|s| crosses(a, b, s[0], s[1])))
        };
        let mut parent: Vec<usize> = (0..nx * ny).collect();
        let mut cutting = Vec::new();
        for e in 0..nx * ny {
            let (i, j) = (e % nx, e / nx);
            let mut join = |f: usize| match cut(centre(e), centre(f)) {
                None => union(&mut parent, e, f),
                Some(c) => cutting.push((e, f, c)),
            };
            if i + 1 < nx {
                join(e + 1);
            }
            if j + 1 < ny {
                join(e + nx);
            }
        }
        // faces in contact hold the pieces on either side together
        let eps = 0.5 * dx.min(dy);
        for p in self.contact_points() {
            if p.state != ContactState::Open {
                let [x, y] = [p.x, p.y];
                let a = element_at([x + eps * p.normal[0], y + eps * p.normal[1]]);
                let b = element_at([x - eps * p.normal[0], y - eps * p.normal[1]]);
                union(&mut parent, a, b);
            }
        }
        let mut held = vec![false; nx * ny];
        let b = &scene.boundary;
        let supports = |s: SideBc| matches!(s, SideBc::Fixed | SideBc::Roller);
        let mut hold = |e: usize, parent: &mut Vec<usize>| {
            let r = root(parent, e);
            held[r] = true;
        };
        for i in 0..nx {
            if supports(b.bottom) {
                hold(i, &mut parent);
            }
            if supports(b.top) {
                hold((ny - 1) * nx + i, &mut parent);
            }
        }
        for j in 0..ny {
            if supports(b.left) {
                hold(j * nx, &mut parent);
            }
            if supports(b.right) {
                hold(j * nx + nx - 1, &mut parent);
            }
        }
        for p in &b.points {
            hold(element_at(p.at), &mut parent);
        }
        let free_root = (0..nx * ny).find(|&e| {
            let r = root(&mut parent, e);
            !held[r]
        })?;
        let free_root = root(&mut parent, free_root);
        let members: Vec<usize> = (0..nx * ny)
            .filter(|&e| root(&mut parent, e) == free_root)
            .collect();
        let n = members.len() as f64;
        let (sx, sy) = members.iter().fold((0.0, 0.0), |(sx, sy), &e| {
            let c = centre(e);
            (sx + c[0], sy + c[1])
        });
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
            centroid: [sx / n, sy / n],
            cracks: bounding,
        })
    }
}

fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (root(parent, a), root(parent, b));
    parent[ra] = rb;
}

/// The segments `a`–`b` and `c`–`d` cross or touch (orientation tests; a
/// crack ending on the segment cuts it).
fn crosses(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let orient = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    };
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && (d1 != 0.0 || d2 != 0.0 || d3 != 0.0 || d4 != 0.0)
}

#[cfg(test)]
mod tests {
    use super::crosses;

    #[test]
    fn segments_cross_touch_or_miss() {
        assert!(crosses([0.0, 0.0], [1.0, 0.0], [0.5, -1.0], [0.5, 1.0]));
        assert!(
            crosses([0.0, 0.0], [1.0, 0.0], [0.5, 0.0], [0.5, 1.0]),
            "a crack ending on it"
        );
        assert!(!crosses([0.0, 0.0], [1.0, 0.0], [0.5, 0.1], [0.5, 1.0]));
        assert!(!crosses([0.0, 0.0], [1.0, 0.0], [2.0, -1.0], [2.0, 1.0]));
    }
}
