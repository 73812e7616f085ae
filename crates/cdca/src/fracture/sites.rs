//! The intact rock as sites of the criterion (SPEC §8,
//! `growth.intact_rock = "nucleate"`): the rock between the cracks fails
//! where its Mohr–Coulomb envelope with a tension cut-off
//! ([`RockStrength`]), read over a disc of radius r0, is met.
//!
//! Every element's centre is a site: the automaton's cell, broken. Its
//! reading is the stress averaged over the disc of radius r0 around it,
//! as the centres of the elements within r0 (centre to centre) sample it:
//! every element has the same area, so the average over the elements that
//! count is the average over the disc's part inside the body, renormalised
//! by that part's area. Elements that a crack enriches do not count (their
//! stress jumps across the crack or carries a tip's singularity). A
//! reading over a fixed length converges with the mesh where the stress of
//! one element at a concentration would not (Pijaudier-Cabot & Bažant
//! 1987; the criterion's own circle of r0 at a tip and a kink).
//!
//! No site where another rule reads, or where the reading means nothing
//! ([`SiteGrid::new`]): within r0 of a crack's faces (the disc would reach
//! across the crack), and within one element of them where r0 is shorter
//! (a crack started there would be joined to the nearby one along its
//! length, see [`Start::snap`]), or of a point support (its reaction is a point
//! force), within twice its own circle's radius of a free tip or a sharp
//! kink (their own circles read there: r0 at a kink, r0 or the short
//! crack's `a/5π` at a tip, `CriterionParams::for_crack`), and on a piece
//! that the cracks have cut off from every support.

use std::f64::consts::FRAC_PI_4;

use crate::discretisation::dofs::FIXED;
use crate::discretisation::xfem::Xfem;
use crate::fracture::rock::RockStrength;
use crate::geometry::cracks::{Crack, root};
use crate::geometry::mesh::{CORNERS, Mesh};
use crate::geometry::plane::{P2, distance_to_segment, segment_intersection};
use crate::report::Mode;

/// Which elements are sites, and which count in a reading, for one crack
/// configuration.
#[derive(Clone, Debug)]
pub struct SiteGrid {
    /// The site elements, in element order.
    sites: Vec<u32>,
    /// Per element: no crack enriches it (its centre's stress counts).
    counts: Vec<bool>,
    /// The disc as rows of elements: for a row `dj` away from the site's,
    /// the elements `±w` away within it (`(dj, w)`).
    rows: Vec<(isize, isize)>,
    /// The radius r0, m.
    radius: f64,
}

impl SiteGrid {
    /// The sites of the discretisation `xfem` for a disc of radius `r0`:
    /// every element whose centre lies at least `max(r0, h)` from every
    /// crack and
    /// outside every disc of `keep_out` (centre and radius, m: the free
    /// tips', the kinks' and the point supports'), on a piece of the
    /// specimen that holds a support: one with a standard DOF in `fixed`
    /// (`fixed[2n + c]`: component `c` of node `n` is held).
    pub fn new(xfem: &Xfem, fixed: &[bool], keep_out: &[(P2, f64)], r0: f64) -> Self {
        let mesh = &xfem.mesh;
        let cracks = &xfem.funcs.cracks;
        let n = mesh.element_count();
        let counts: Vec<bool> = (0..n)
            .map(|e| {
                !mesh
                    .element_nodes(e)
                    .iter()
                    .any(|&k| xfem.dofs.is_enriched(k))
            })
            .collect();
        let mut excluded = vec![false; n];
        // every element whose centre lies nearer than `radius` to a shape
        // in the box `[lo, hi]` (`near`: the centre's distance to it)
        let mut mark = |lo: P2, hi: P2, radius: f64, near: &dyn Fn(P2) -> f64| {
            for e in mesh.elements_in_box(lo, hi, radius) {
                if near(element_centre(mesh, e)) < radius {
                    excluded[e] = true;
                }
            }
        };
        // the distance at which a start's ends join a crack (`Start::snap`):
        // nearer, a shear start along a crack had both ends snapped onto it
        // and lay on it, six times over at one site, until the coincident
        // Heaviside enrichments made the stiffness singular (issue 62: the
        // 300 mm stepped pair at 150 × 150, r0 = 1.34 mm < h = 2 mm)
        let faces = join_distance(r0, mesh);
        for crack in cracks {
            for (a, b) in crack.segments() {
                mark(a.inf(&b), a.sup(&b), faces, &|c| {
                    distance_to_segment(c, a, b)
                });
            }
        }
        for &(p, radius) in keep_out {
            mark(p, p, radius, &|c| (c - p).norm());
        }
        let held = supported_pieces(mesh, cracks, fixed);
        let sites = (0..n)
            .filter(|&e| !excluded[e] && held[e])
            .map(|e| e as u32)
            .collect();
        // a disc wider than the mesh reads every element: its rows stop at
        // the mesh's size, so no radius sizes the stencil beyond the mesh
        // (a 1 Pa rock's r0 of 10¹⁰ m once asked for 1.6e16 bytes)
        let rx = (r0 / mesh.hx).floor().min(mesh.nx as f64) as isize;
        let ry = (r0 / mesh.hy).floor().min(mesh.ny as f64) as isize;
        let rows = (-ry..=ry)
            .map(|dj| {
                let dy = dj as f64 * mesh.hy;
                let w = ((r0 * r0 - dy * dy).max(0.0).sqrt() / mesh.hx).floor() as isize;
                (dj, w.min(rx))
            })
            .collect();
        Self {
            sites,
            counts,
            rows,
            radius: r0,
        }
    }

    /// Number of sites.
    pub fn len(&self) -> usize {
        self.sites.len()
    }

    /// Whether no site is left.
    pub fn is_empty(&self) -> bool {
        self.sites.is_empty()
    }

    /// The disc's radius r0, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Every site's reading at the displacement `u` of `xfem` against
    /// `strength`, taken at load factor `lambda`.
    pub fn read(&self, xfem: &Xfem, u: &[f64], strength: &RockStrength, lambda: f64) -> Readings {
        let mesh = &xfem.mesh;
        let centres = centre_stresses(xfem, u, &self.counts);
        // running sums along each row of elements: `sums[j][i]` holds the
        // stress summed over the counting elements left of column i, and
        // their number, so that a row's part of a disc is one difference
        let (nx, ny) = (mesh.nx, mesh.ny);
        let mut sums = vec![[0.0; 4]; (nx + 1) * ny];
        for j in 0..ny {
            for i in 0..nx {
                let e = j * nx + i;
                let mut s = sums[j * (nx + 1) + i];
                if let Some(c) = centres[e] {
                    s = [s[0] + c[0], s[1] + c[1], s[2] + c[2], s[3] + 1.0];
                }
                sums[j * (nx + 1) + i + 1] = s;
            }
        }
        let sites = self
            .sites
            .iter()
            .filter_map(|&e| {
                let (i, j) = ((e as usize % nx) as isize, (e as usize / nx) as isize);
                let mut total = [0.0; 4];
                for &(dj, w) in &self.rows {
                    let row = j + dj;
                    if row < 0 || row >= ny as isize {
                        continue;
                    }
                    let lo = (i - w).max(0) as usize;
                    let hi = (i + w).min(nx as isize - 1) as usize + 1;
                    let base = row as usize * (nx + 1);
                    let (a, b) = (sums[base + lo], sums[base + hi]);
                    for k in 0..4 {
                        total[k] += b[k] - a[k];
                    }
                }
                (total[3] > 0.0).then(|| {
                    let stress = [total[0], total[1], total[2]].map(|v| v / total[3]);
                    let (tension, shear) = strength.ratios(stress);
                    SiteReading {
                        element: e,
                        stress,
                        tension,
                        shear,
                    }
                })
            })
            .collect();
        Readings {
            lambda,
            radius: self.radius,
            sites,
            centres,
        }
    }
}

/// A site's reading: the disc-averaged stress `[σxx, σyy, τxy]` (Pa,
/// tension positive) and the envelope's two checks on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SiteReading {
    /// The site's element.
    pub element: u32,
    pub stress: [f64; 3],
    /// `−σ3/σ_t` (the tension cut-off) and `(σ1 − N_φ σ3)/σ_c` (the
    /// Mohr–Coulomb line), principal compressions σ1 ≥ σ3.
    pub tension: f64,
    pub shear: f64,
}

impl SiteReading {
    /// The larger check, at least 0: ≥ 1 where the rock fails.
    pub fn utilisation(&self) -> f64 {
        self.tension.max(self.shear).max(0.0)
    }
}

/// Every site's reading after one solve, and the stress at the centre of
/// every element that counts (for the choice between conjugate planes).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Readings {
    /// Load factor of the solve read. The readings are linear in the
    /// stress: at another load of the same contact states they scale
    /// with it.
    pub lambda: f64,
    /// The disc's radius r0, m.
    pub radius: f64,
    pub sites: Vec<SiteReading>,
    centres: Vec<Option<[f64; 3]>>,
}

impl Readings {
    /// The largest utilisation at load factor `lambda` (0 with no site).
    pub fn utilisation_at(&self, lambda: f64) -> f64 {
        self.scale(lambda)
            * self
                .sites
                .iter()
                .map(SiteReading::utilisation)
                .fold(0.0, f64::max)
    }

    /// Factor from the solve's load to `lambda` (0 for readings of no
    /// load).
    pub fn scale(&self, lambda: f64) -> f64 {
        if self.lambda > 0.0 {
            lambda / self.lambda
        } else {
            0.0
        }
    }

    /// The most critical site at load factor `lambda`, and the number of
    /// the others tied with it: those whose own load factor (the search's
    /// root for them alone, `λ/u` for these linear readings) lies within
    /// `band` (relative) of the lowest are tied, and among them the site
    /// nearest the specimen's centre is taken, then the lowest, then the
    /// leftmost (a uniform field is uniform only to round-off). `None`
    /// with no site.
    pub fn critical(&self, mesh: &Mesh, band: f64) -> Option<(&SiteReading, usize)> {
        let top = self
            .sites
            .iter()
            .map(SiteReading::utilisation)
            .fold(0.0, f64::max);
        if top <= 0.0 {
            return None;
        }
        let centre = P2::new(0.5 * mesh.width, 0.5 * mesh.height);
        let tol = 1e-9 * mesh.h() * mesh.h();
        let key = |s: &SiteReading| {
            let c = element_centre(mesh, s.element as usize);
            ((c - centre).norm_squared(), c.y, c.x)
        };
        let tied: Vec<&SiteReading> = self
            .sites
            .iter()
            .filter(|s| s.utilisation() * (1.0 + band) >= top)
            .collect();
        let best = tied.iter().copied().min_by(|a, b| {
            let (ka, kb) = (key(a), key(b));
            if (ka.0 - kb.0).abs() > tol {
                ka.0.total_cmp(&kb.0)
            } else if (ka.1 - kb.1).abs() > tol.sqrt() {
                ka.1.total_cmp(&kb.1)
            } else {
                ka.2.total_cmp(&kb.2)
            }
        })?;
        Some((best, tied.len() - 1))
    }

    /// The stress at the centre of element `e`, if it counts.
    fn centre(&self, e: usize) -> Option<[f64; 3]> {
        self.centres.get(e).copied().flatten()
    }
}

/// A crack to start at a site: through `point` along the unit `direction`,
/// `half_length` to either side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start {
    pub point: P2,
    pub direction: P2,
    pub mode: Mode,
    pub half_length: f64,
    /// An end that comes within this distance of another crack ends on
    /// it: the disc's radius r0, the finest ligament the reading resolves,
    /// or one element h where that is longer (no site lies nearer a crack,
    /// so no start lies along one).
    pub snap: f64,
}

/// The crack that starts at `site` at load factor `lambda` of `readings`
/// (its utilisation at least 1), `half_lengths[0]` to either side in
/// tension, `half_lengths[1]` in shear: in tension
/// (the cut-off met first) perpendicular to the most tensile principal
/// stress; in shear on a Mohr–Coulomb plane, `45° − φ/2` from σ1 (the
/// most compressive principal stress). Of the two conjugate planes the one
/// along which the rock's stress uses more of its shear strength is taken,
/// read at the element centres along each; within `band` of each other
/// they are tied, and the plane whose upper end lies further left is
/// taken (the tie rule's last word, `x`).
pub fn start_at(
    site: &SiteReading,
    readings: &Readings,
    mesh: &Mesh,
    strength: &RockStrength,
    half_lengths: [f64; 2],
    band: f64,
) -> Start {
    let s = site.stress;
    // direction of the most compressive principal stress σ1: the
    // eigenvector of the smaller eigenvalue (tension positive)
    let major = 0.5 * (2.0 * s[2]).atan2(s[0] - s[1]);
    let sigma1 = major + std::f64::consts::FRAC_PI_2;
    let point = element_centre(mesh, site.element as usize);
    let unit = |a: f64| P2::new(a.cos(), a.sin());
    let (mode, direction, half_length) = if site.tension >= 1.0 || site.tension >= site.shear {
        (Mode::Tension, unit(sigma1), half_lengths[0])
    } else {
        let half_length = half_lengths[1];
        let off = FRAC_PI_4 - 0.5 * strength.friction_angle;
        let planes = [unit(sigma1 + off), unit(sigma1 - off)];
        let along = planes.map(|d| shear_along(readings, mesh, strength, point, d, half_length));
        let upper_x = |d: P2| if d.y >= 0.0 { d.x } else { -d.x };
        let pick = if along[0] > along[1] * (1.0 + band) {
            0
        } else if along[1] > along[0] * (1.0 + band) {
            1
        } else {
            // tied: the plane whose upper end lies further left
            usize::from(upper_x(planes[0]) > upper_x(planes[1]))
        };
        (Mode::Shear, planes[pick], half_length)
    };
    Start {
        point,
        direction,
        mode,
        half_length,
        snap: join_distance(readings.radius, mesh),
    }
}

/// Mean shear utilisation `|τ| / (c + max(σ_n, 0) tan φ)` on the plane of
/// direction `d` at the element centres along the segment `point ± a d`
/// (those that count; 0 with none).
fn shear_along(
    readings: &Readings,
    mesh: &Mesh,
    strength: &RockStrength,
    point: P2,
    d: P2,
    a: f64,
) -> f64 {
    let normal = P2::new(-d.y, d.x);
    let steps = (a / (0.5 * mesh.h())).ceil().max(1.0) as i32;
    let (mut sum, mut n) = (0.0, 0.0);
    for k in -steps..=steps {
        let x = point + (f64::from(k) / f64::from(steps) * a) * d;
        let Some(s) = mesh.element_at(x).and_then(|e| readings.centre(e)) else {
            continue;
        };
        let traction = P2::new(
            s[0] * normal.x + s[2] * normal.y,
            s[2] * normal.x + s[1] * normal.y,
        );
        let sigma_n = -traction.dot(&normal);
        let tau = traction.dot(&d).abs();
        sum += tau / (strength.cohesion + sigma_n.max(0.0) * strength.friction_angle.tan());
        n += 1.0;
    }
    if n > 0.0 { sum / n } else { 0.0 }
}

/// The distance within which a start's end joins a crack
/// ([`Start::snap`]), and within which of a crack no site lies: the disc's
/// radius r0, or one element where that is longer.
fn join_distance(r0: f64, mesh: &Mesh) -> f64 {
    r0.max(mesh.h())
}

/// Centre of element `e`, m.
pub fn element_centre(mesh: &Mesh, e: usize) -> P2 {
    let (lo, hi) = mesh.element_box(e);
    0.5 * (lo + hi)
}

/// The stress `[σxx, σyy, τxy]` at the centre of every element that
/// counts (`None` for the others): `D B(0, 0) u_e`, with the Q4's
/// gradients at its centre `∂N_k/∂x = ξ_k/(2 h_x)`, `∂N_k/∂y = η_k/(2 h_y)`.
fn centre_stresses(xfem: &Xfem, u: &[f64], counts: &[bool]) -> Vec<Option<[f64; 3]>> {
    let mesh = &xfem.mesh;
    let d = &xfem.elastic.d;
    let value = |node: usize, c: usize| {
        let f = xfem.dofs.std_free(node, c);
        if f == FIXED { 0.0 } else { u[f as usize] }
    };
    (0..mesh.element_count())
        .map(|e| {
            if !counts[e] {
                return None;
            }
            let mut eps = nalgebra::Vector3::zeros();
            for (k, &node) in mesh.element_nodes(e).iter().enumerate() {
                let (gx, gy) = (
                    CORNERS[k].0 / (2.0 * mesh.hx),
                    CORNERS[k].1 / (2.0 * mesh.hy),
                );
                let (ux, uy) = (value(node, 0), value(node, 1));
                eps[0] += gx * ux;
                eps[1] += gy * uy;
                eps[2] += gy * ux + gx * uy;
            }
            let s = d * eps;
            Some([s[0], s[1], s[2]])
        })
        .collect()
}

/// Per element, whether its piece of the specimen holds a support: the
/// elements joined across every element side that no crack crosses, and
/// a piece held when one of its elements has a held node. Cracks can cut a
/// piece off only where one ends on another or on the boundary, or where
/// two cross; otherwise every element is held.
fn supported_pieces(mesh: &Mesh, cracks: &[Crack], fixed: &[bool]) -> Vec<bool> {
    let n = mesh.element_count();
    let closed = cracks.iter().any(|c| {
        c.tips
            .iter()
            .any(|t| *t != crate::geometry::cracks::TipKind::Free)
    }) || cracks.len() > 1;
    if !closed {
        return vec![true; n];
    }
    // the crack segments near each element, to test its sides against
    let mut near: Vec<Vec<(P2, P2)>> = vec![Vec::new(); n];
    for crack in cracks {
        for (a, b) in crack.segments() {
            for e in mesh.elements_in_box(a.inf(&b), a.sup(&b), mesh.h()) {
                near[e].push((a, b));
            }
        }
    }
    let mut parent: Vec<usize> = (0..n).collect();
    let centre = |e: usize| element_centre(mesh, e);
    for e in 0..n {
        let (i, j) = (e % mesh.nx, e / mesh.nx);
        let right = (i + 1 < mesh.nx).then_some(e + 1);
        let above = (j + 1 < mesh.ny).then_some(e + mesh.nx);
        for f in right.into_iter().chain(above) {
            let (a, b) = (centre(e), centre(f));
            let cut = near[e]
                .iter()
                .chain(&near[f])
                .any(|&(p, q)| segment_intersection(a, b, p, q).is_some());
            if !cut {
                let (ra, rb) = (root(&mut parent, e), root(&mut parent, f));
                parent[ra] = rb;
            }
        }
    }
    let mut held = vec![false; n];
    for e in 0..n {
        if mesh
            .element_nodes(e)
            .iter()
            .any(|&k| fixed[2 * k] || fixed[2 * k + 1])
        {
            let r = root(&mut parent, e);
            held[r] = true;
        }
    }
    (0..n).map(|e| held[root(&mut parent, e)]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::model::Model;
    use crate::scene::Scene;

    /// A 10 mm square plate on rollers (left and bottom), uncracked, on
    /// `n × n` elements, with the nodal displacement `field` (m) at every
    /// free DOF, read with the default r0 (the paper's rock: r_p =
    /// 1.342 mm) and no keep-out disc.
    fn read_field(n: usize, field: impl Fn(P2) -> [f64; 2]) -> (Readings, Mesh, RockStrength) {
        read_field_on(n, None, field)
    }

    /// [`read_field`] over a disc of radius `r0` (`None`: the default).
    fn read_field_on(
        n: usize,
        r0: Option<f64>,
        field: impl Fn(P2) -> [f64; 2],
    ) -> (Readings, Mesh, RockStrength) {
        let json = format!(
            r#"{{"specimen":{{"width":0.01,"height":0.01}},"mesh":{{"nx":{n},"ny":{n}}},
            "material":{{"young":20e9,"poisson":0.25}}}}"#
        );
        let scene = Scene::from_json(&json).expect("scene");
        let model = Model::new(scene.clone());
        let x = model.discretise(model.initial_cracks());
        let mut u = vec![0.0; x.n_free()];
        for node in 0..x.mesh.node_count() {
            let v = field(x.mesh.node_pos(node));
            for (c, value) in v.into_iter().enumerate() {
                let f = x.dofs.std_free(node, c);
                if f != FIXED {
                    u[f as usize] = value;
                }
            }
        }
        let strength = RockStrength::of_material(&scene.material).expect("c > 0");
        let r0 = r0.unwrap_or(crate::fracture::criterion::CriterionParams::of_scene(&scene).r0);
        let grid = SiteGrid::new(&x, &model.fixed, &[], r0);
        assert_eq!(
            grid.len(),
            n * n,
            "no crack, no keep-out: every element a site"
        );
        (grid.read(&x, &u, &strength, 1.0), x.mesh.clone(), strength)
    }

    /// A disc far wider than the specimen (the r0 of 10¹⁰ m a 1 Pa rock
    /// gave) reads every element: its stencil stops at the mesh (it once
    /// asked for 1.6e16 bytes and aborted, issue 62), and every site reads
    /// the mean of the whole plate, here of `σ_xx = 2b D₁₁ x`, linear in x:
    /// its value at the centre, to round-off (1e-9).
    #[test]
    fn a_disc_wider_than_the_specimen_reads_the_whole_specimen() {
        let b = 1e-2;
        let (readings, _, _) = read_field_on(12, Some(1e10), |p| [b * p.x * p.x, 0.0]);
        let mean = 2.0 * b * 20e9 / (1.0 - 0.25 * 0.25) * 0.005;
        for s in &readings.sites {
            let err = (s.stress[0] - mean).abs() / mean;
            assert!(
                err <= 1e-9,
                "σ_xx {} against {mean} ({err:.1e})",
                s.stress[0]
            );
        }
    }

    /// On a mesh coarser than the disc (h = 3 mm, r0 = 1.342 mm) no site
    /// lies within one element of a crack: a start there has its ends
    /// joined to the crack within `Start::snap = max(r0, h)` and lay along
    /// it (issue 62: six coincident starts, then a singular stiffness).
    /// A crack at y = 15.9 mm across the middle of a 30 mm plate on 10 × 10:
    /// the row of centres at y = 13.5 mm, 2.4 mm below it (beyond r0,
    /// within h), holds no site under it; every site is at least h from it.
    #[test]
    fn no_site_lies_within_one_element_of_a_crack() {
        let json = r#"{"specimen":{"width":0.03,"height":0.03},"mesh":{"nx":10,"ny":10},
            "material":{"young":20e9,"poisson":0.25},
            "cracks":[{"points":[[0.0061,0.0159],[0.0239,0.0159]]}]}"#;
        let scene = Scene::from_json(json).expect("scene");
        let model = Model::new(scene);
        let x = model.discretise(model.initial_cracks());
        let h = x.mesh.h();
        let r0 = 1.342e-3;
        assert!(h > 2.0 * r0);
        let grid = SiteGrid::new(&x, &model.fixed, &[], r0);
        let (a, b) = (P2::new(0.0061, 0.0159), P2::new(0.0239, 0.0159));
        for &e in &grid.sites {
            let c = element_centre(&x.mesh, e as usize);
            assert!(distance_to_segment(c, a, b) >= h, "site at {c:?}");
        }
        let below = x.mesh.element_at(P2::new(0.0151, 0.0135)).expect("inside");
        assert!(!grid.sites.contains(&(below as u32)));
        // the rows two elements away are sites along the whole crack
        for i in 0..10 {
            let e = x
                .mesh
                .element_at(P2::new(0.0015 + 0.003 * f64::from(i), 0.0105))
                .expect("in");
            assert!(grid.sites.contains(&(e as u32)), "element {e}");
        }
    }

    fn reading_at(r: &Readings, mesh: &Mesh, at: P2) -> SiteReading {
        let e = mesh.element_at(at).expect("inside") as u32;
        *r.sites.iter().find(|s| s.element == e).expect("a site")
    }

    /// The disc reading of a non-uniform field against the closed form of
    /// the disc's average. `u_x = a x³` gives `ε_xx = 3a x²`, so
    /// `σ_xx = 3a D₁₁ x²`, whose average over a disc of radius r about
    /// `x₀` is `3a D₁₁ (x₀² + r²/4)`: near `x = 0` the `r²/4` term is 45%
    /// of it, so the reading must average over the disc, not read its
    /// centre. `u_x = b x²` gives `σ_xx = 2b D₁₁ x`, linear: over a disc
    /// cut by the plate's edge at a distance `d < r` from its centre, the
    /// average is the value at the centroid of the part inside,
    /// `x₀ + A_s r sin³α · 2/(3 (π r² − A_s) (α − sin α cos α))` with
    /// `cos α = d/r` and the cut-off segment's area `A_s = r²(α − sin α cos α)`.
    /// Both within 1% on a mesh of r0/h = 13.
    #[test]
    fn disc_reading_matches_the_closed_form_of_a_non_uniform_field() {
        let a = 1e3;
        let (r, mesh, _) = read_field(100, |p| [a * p.x.powi(3), 0.0]);
        let d11 = 20e9 / (1.0 - 0.25 * 0.25);
        let r0 = 1.342e-3_f64;
        for x0 in [0.00205, 0.00505] {
            let site = reading_at(&r, &mesh, P2::new(x0, 0.00505));
            let c = element_centre(&mesh, site.element as usize);
            let exact = 3.0 * a * d11 * (c.x * c.x + r0 * r0 / 4.0);
            let err = (site.stress[0] - exact).abs() / exact;
            assert!(
                err < 0.01,
                "x0 = {x0}: σ_xx {} against {exact} ({err:.2e})",
                site.stress[0]
            );
        }
        let b = 1.0;
        let (r, mesh, _) = read_field(100, |p| [b * p.x * p.x, 0.0]);
        let site = reading_at(&r, &mesh, P2::new(0.00065, 0.00505));
        let c = element_centre(&mesh, site.element as usize);
        let alpha = (c.x / r0).acos();
        let (s, co) = alpha.sin_cos();
        let cut = r0 * r0 * (alpha - s * co);
        let x_cut = -2.0 * r0 * s.powi(3) / (3.0 * (alpha - s * co));
        let x_kept = -cut * x_cut / (std::f64::consts::PI * r0 * r0 - cut);
        let exact = 2.0 * b * d11 * (c.x + x_kept);
        let err = (site.stress[0] - exact).abs() / exact;
        assert!(
            err < 0.01,
            "cut disc: σ_xx {} against {exact} ({err:.2e})",
            site.stress[0]
        );
        // the centre alone would read 2b D₁₁ x₀, 27% off
        assert!((exact - 2.0 * b * d11 * c.x).abs() / exact > 0.25);
    }

    /// In a uniform field every site is tied: the one nearest the centre
    /// is taken, then the lowest, then the leftmost. On an even mesh the
    /// four elements around the centre are equally near: the lower left
    /// one. Its crack: in uniaxial tension along the other axis; in
    /// uniaxial compression on a Mohr–Coulomb plane 45° − φ/2 = 20.5° off
    /// the load (φ = 49°), of the two the one whose upper end lies left.
    #[test]
    fn ties_go_to_the_centre_then_the_lowest_then_the_leftmost() {
        // σ_yy uniform: u_y = ε y (tension for ε > 0), u_x = −ν' ε x
        let nu = 0.25;
        for (eps, mode, angle) in [(1e-3, Mode::Tension, 0.0), (-5e-3, Mode::Shear, 110.5)] {
            let (r, mesh, strength) = read_field(40, |p| [-nu * eps * p.x, eps * p.y]);
            let (site, tied) = r.critical(&mesh, 1e-3).expect("a site");
            assert_eq!(tied, 40 * 40 - 1, "every site tied");
            let c = element_centre(&mesh, site.element as usize);
            assert!((c - P2::new(0.004875, 0.004875)).norm() < 1e-12, "{c:?}");
            let start = start_at(site, &r, &mesh, &strength, [1e-3; 2], 1e-3);
            assert_eq!(start.mode, mode);
            let deg = start
                .direction
                .y
                .atan2(start.direction.x)
                .to_degrees()
                .rem_euclid(180.0);
            assert!(
                (deg - angle).abs() < 1e-6,
                "{mode:?}: {deg}° against {angle}°"
            );
        }
    }
}
