//! The intact rock in a growth run (SPEC §8, `growth.intact_rock =
//! "nucleate"`): its sites read after every real solve of the run
//! ([`SiteGrid::read`]), their utilisation scaled with the load in the λ
//! search's scaled trials, and a crack started at the most critical site
//! when it fails below every tip's and kink's load.

use super::state::Simulation;
use crate::discretisation::boundary::nearest_node;
use crate::error::SolveError;
use crate::fracture::kinks::sharp_vertices;
use crate::fracture::rock::RockStrength;
use crate::fracture::sites::{SiteGrid, Start, element_centre, start_at};
use crate::geometry::cracks::system_lengths;
use crate::geometry::plane::P2;
use crate::report::{GrowthStepReport, Mode, RockSiteReport, StartLimitReport};
use crate::scene::IntactRock;
use crate::simulation::search::LAMBDA_TOLERANCE;

impl Simulation {
    /// The rock's strength when the run lets it fail: the scene asks for
    /// it (`growth.intact_rock = "nucleate"`) and the rock has one (a rock
    /// without cohesion has no unconfined strength).
    pub(super) fn rock_strength(&self) -> Option<RockStrength> {
        (self.model.scene.growth.intact_rock == IntactRock::Nucleate)
            .then(|| RockStrength::of_material(&self.model.scene.material))
            .flatten()
    }

    /// After a real solve in a growth run: every site's reading (the site
    /// grid made first, once per crack configuration). Nothing outside
    /// growth (a scene's solve, a drag) and nothing for a rock that is not
    /// to fail.
    pub(super) fn read_rock(&mut self) {
        let growing = self.scratch.critical.is_some() || self.scratch.growth_start.is_some();
        let Some(strength) = self.rock_strength().filter(|_| growing) else {
            self.scratch.rock = None;
            return;
        };
        if self.scratch.site_grid.is_none() {
            let grid = SiteGrid::new(
                &self.scratch.xfem,
                &self.model.fixed,
                &self.keep_out(),
                self.criterion_params().r0,
            );
            self.scratch.site_grid = Some(grid);
        }
        let x = &self.scratch.xfem;
        self.scratch.rock = self
            .scratch
            .site_grid
            .as_ref()
            .map(|g| g.read(x, &self.state.u, &strength, self.state.lambda));
    }

    /// The sites' largest utilisation at the current load factor (their
    /// readings scaled from the solve they were taken at), 0 without any.
    pub(super) fn rock_utilisation(&self) -> f64 {
        self.scratch
            .rock
            .as_ref()
            .map_or(0.0, |r| r.utilisation_at(self.state.lambda))
    }

    /// The most critical site at the current load factor, as reported.
    pub(super) fn rock_site(&self) -> Option<RockSiteReport> {
        let readings = self.scratch.rock.as_ref()?;
        let (site, _) = readings.critical(&self.model.mesh, LAMBDA_TOLERANCE)?;
        let scale = readings.scale(self.state.lambda);
        let c = element_centre(&self.model.mesh, site.element as usize);
        let (tension, shear) = (site.tension * scale, site.shear * scale);
        Some(RockSiteReport {
            x: c.x,
            y: c.y,
            utilisation: tension.max(shear).max(0.0),
            mode: if tension >= 1.0 {
                Mode::Tension
            } else if shear >= 1.0 {
                Mode::Shear
            } else {
                Mode::None
            },
            sites: readings.sites.len(),
        })
    }

    /// The crack to start in the intact rock at the current load factor,
    /// when the sites' largest utilisation is at least 1 (the caller asks
    /// only when no tip or kink grows): at the most critical site, the one
    /// the tie rule takes among those within the search's band of the
    /// largest, with its utilisation and the number of sites tied with it.
    pub(super) fn rock_start(&self, da: f64) -> Option<(Start, f64, usize)> {
        let strength = self.rock_strength()?;
        let readings = self.scratch.rock.as_ref()?;
        let mesh = &self.model.mesh;
        if readings.utilisation_at(self.state.lambda) < 1.0 {
            return None;
        }
        let (site, tied) = readings.critical(mesh, LAMBDA_TOLERANCE)?;
        let scale = readings.scale(self.state.lambda);
        let utilisation = site.utilisation() * scale;
        let mut at_load = *site;
        at_load.tension *= scale;
        at_load.shear *= scale;
        let start = start_at(
            &at_load,
            readings,
            mesh,
            &strength,
            start_half_lengths(&strength, self.model.scene.material.k_ic, da),
            LAMBDA_TOLERANCE,
        );
        Some((start, utilisation, tied))
    }

    /// After a step: raises the run's peak when the step's load passed it
    /// (by more than the λ search's band) and counts a start in the intact
    /// rock at the peak or below. Returns the bound's report when the
    /// starts at one load reach [`start_bound`](Self::start_bound): the
    /// rock keeps failing at a load that does not rise, so the specimen
    /// has reached its peak (in a load-controlled test every one of them
    /// happens at the peak load) and more starts would only fill it.
    pub(super) fn count_rock_starts(
        &mut self,
        step: &GrowthStepReport,
    ) -> Option<StartLimitReport> {
        let grew = !(step.grown.is_empty() && step.started.is_empty() && step.nucleated.is_empty());
        let counter = &mut self.state.rock_starts;
        if grew && step.load_factor > counter.peak * (1.0 + LAMBDA_TOLERANCE) {
            counter.peak = step.load_factor;
            counter.at_peak = 0;
        }
        counter.at_peak += step.nucleated.len();
        let (peak, starts) = (counter.peak, counter.at_peak);
        let bound = self.start_bound();
        (!step.nucleated.is_empty() && starts >= bound).then(|| StartLimitReport {
            load_factor: peak,
            starts,
            reason: format!(
                "{starts} cracks started in the intact rock at loads not above the peak \
                 λ = {peak:.4}, the bound for one load ({bound}: as many starts as one band \
                 of them across the specimen takes): the rock keeps failing without the \
                 load rising, so the specimen has failed at its peak"
            ),
        })
    }

    /// Most cracks started in the intact rock at one load: as many as one
    /// band of them, end to end, across the specimen's larger side takes,
    /// `⌈max(W, H) / 2a⌉` with `a` their half-length.
    pub(super) fn start_bound(&self) -> usize {
        let Some(strength) = self.rock_strength() else {
            return usize::MAX;
        };
        let m = &self.model.mesh;
        let da = self.increment();
        let a = start_half_lengths(&strength, self.model.scene.material.k_ic, da)[1];
        (m.width.max(m.height) / (2.0 * a)).ceil().max(1.0) as usize
    }

    /// The load factor at which the uncracked specimen (this scene without
    /// its cracks) first fails: its sites read at λ = 1, `1 / max u`, solved by the direct solver.
    /// `None` for a rock without cohesion, or where no load factor brings
    /// its rock to the envelope (the loads confine it, `k N_φ ≥ 1`); with
    /// the sentence saying which. Solved once per simulation.
    pub fn intact_load_factor(&self) -> (Option<f64>, String) {
        self.scratch
            .intact
            .get_or_init(|| self.uncracked_strength())
            .clone()
    }

    fn uncracked_strength(&self) -> (Option<f64>, String) {
        let Some(strength) = RockStrength::of_material(&self.model.scene.material) else {
            return (
                None,
                "a rock without cohesion has no unconfined strength to compare with".to_owned(),
            );
        };
        // linear and without contact: the direct solver's one factorisation
        // is exact and the quickest, whatever solver the scene grows with
        let uncracked = self.model.scene.edit(|f| {
            f.cracks.clear();
            f.growth.resume = None;
            f.solver.kind = crate::scene::SolverKind::Direct;
        });
        let solved = uncracked.map_err(SolveError::from).and_then(|scene| {
            let mut sim = Simulation::new(scene)?;
            sim.set_load_factor(1.0);
            sim.solve()?;
            Ok(sim)
        });
        let sim = match solved {
            Ok(sim) => sim,
            Err(e) => {
                return (
                    None,
                    format!("the uncracked specimen could not be solved: {e}"),
                );
            }
        };
        let x = &sim.scratch.xfem;
        let grid = SiteGrid::new(
            x,
            &self.model.fixed,
            &self.keep_out(),
            self.criterion_params().r0,
        );
        let readings = grid.read(x, &sim.state.u, &strength, 1.0);
        let top = readings.utilisation_at(1.0);
        if top > 0.0 {
            let lambda = 1.0 / top;
            (
                Some(lambda),
                format!(
                    "the uncracked specimen's rock fails at λ = {lambda:.4} ({:.1} MPa)",
                    lambda * self.reference_stress() / 1e6
                ),
            )
        } else {
            let k = readings
                .sites
                .first()
                .map_or(0.0, |s| confinement(s.stress));
            (
                None,
                format!(
                    "the loads confine the uncracked specimen's rock (σ3/σ1 = {k:.3}, \
                     N_φ = {:.3}: k N_φ = {:.2} ≥ 1), so it cannot fail at any load factor",
                    strength.n_phi,
                    k * strength.n_phi
                ),
            )
        }
    }

    /// Where no site lies besides the cracks' faces (centres and radii,
    /// m): within twice its own circle's radius of a free tip (the tip's
    /// r0, [`for_crack`](crate::fracture::criterion::CriterionParams::for_crack)
    /// of its crack system's length)
    /// and of a sharp kink (the scene's r0), and within r0 of a point
    /// support (the node it holds).
    fn keep_out(&self) -> Vec<(P2, f64)> {
        let params = self.criterion_params();
        let cracks = &self.state.cracks;
        let lengths = system_lengths(cracks);
        let mesh = &self.model.mesh;
        let tips = cracks.iter().zip(&lengths).flat_map(|(c, &l)| {
            let r = 2.0 * params.for_crack(l).r0;
            c.free_tips().map(move |k| (c.tip_point(k), r))
        });
        let kinks = cracks
            .iter()
            .enumerate()
            .flat_map(|(c, crack)| sharp_vertices(c, crack).map(|k| (k.point, 2.0 * params.r0)));
        let points = self
            .model
            .scene
            .boundary
            .points
            .iter()
            .map(|p| (mesh.node_pos(nearest_node(mesh, p.at)), params.r0));
        tips.chain(kinks).chain(points).collect()
    }
}

/// Half the length of a crack started in the intact rock, m, in tension
/// and in shear.
///
/// In tension: the half-length `a = (K_IC/σ_t)²/π` at which a crack in
/// uniform tension at the rock's tensile strength σ_t reaches
/// `K_I = σ_t √(π a) = K_IC`, so that it grows at the load it starts at
/// (`2 r_p` with the default r0, the process zone `r_p = (K_IC/σ_t)²/2π`),
/// and never less than one growth increment `da`.
///
/// In shear: one increment. No length lets a shear start grow by the tip
/// criterion at the load it starts at: on its Mohr–Coulomb plane it slides
/// with the net shear c (its faces have the rock's friction), so its
/// `K_II = c √(π a)` reaches K_IIC only at `a = (K_IIC/c)²/π` (9 mm for
/// the paper's rock), and its wings' tension at the tip circle is held
/// down by the compression along it (σ11 ≈ 0.9 σ_c at r0: measured −47
/// MPa at λ 0.62 on a 2 r_p start in the uncracked specimen, against
/// 31 MPa of tension needed). It is joined instead by the starts its own
/// field makes critical next to it, and by the cracks within r0 of its ends
/// (`Start::snap`): it links within a few steps (docs/fracture-model.md,
/// *The intact rock*). A longer start only moves more load at once.
fn start_half_lengths(strength: &RockStrength, k_ic: f64, da: f64) -> [f64; 2] {
    let tension = ((k_ic / strength.tensile).powi(2) / std::f64::consts::PI).max(da);
    [tension, da]
}

/// `σ3/σ1` of the stress `[σxx, σyy, τxy]` (principal compressions, 0
/// without compression).
fn confinement(s: [f64; 3]) -> f64 {
    let centre = 0.5 * (s[0] + s[1]);
    let radius = (0.25 * (s[0] - s[1]).powi(2) + s[2] * s[2]).sqrt();
    let (sigma1, sigma3) = (radius - centre, -radius - centre);
    if sigma1 > 0.0 { sigma3 / sigma1 } else { 0.0 }
}
