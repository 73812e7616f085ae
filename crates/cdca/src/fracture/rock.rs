//! The intact rock's own strength, away from the cracks: Mohr–Coulomb with
//! a tension cut-off. The tip criterion checks the rock only on the circle
//! r0 around each tip; this is the yardstick for the rest of the specimen,
//! so that a report can say when the load has passed what the uncracked
//! rock could carry.

use crate::discretisation::field::Field;
use crate::discretisation::xfem::Xfem;
use crate::geometry::plane::P2;
use crate::report::IntactRockReport;
use crate::scene::Material;

/// Mohr–Coulomb strength of the rock with a tension cut-off.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RockStrength {
    /// Unconfined compressive strength `σ_c = 2c cos φ / (1 − sin φ)`, Pa.
    pub ucs: f64,
    /// Passive coefficient `N_φ = (1 + sin φ) / (1 − sin φ)`.
    pub n_phi: f64,
    /// Tensile strength σ_t, Pa: the material's `tensile_strength`, else
    /// the Mohr–Coulomb cut-off `2c cos φ / (1 + sin φ)`.
    pub tensile: f64,
    /// Cohesion c, Pa, and friction angle φ, rad.
    pub cohesion: f64,
    pub friction_angle: f64,
}

impl RockStrength {
    /// The material's strength, or `None` for a rock without cohesion
    /// (c = 0): its envelope passes through the origin, so scaling the load
    /// brings a state to failure at once or never, and no utilisation can
    /// be given.
    pub fn of_material(m: &Material) -> Option<Self> {
        let (c, phi) = (m.cohesion, m.friction_angle_deg.to_radians());
        let s = Self {
            ucs: 2.0 * c * phi.cos() / (1.0 - phi.sin()),
            n_phi: (1.0 + phi.sin()) / (1.0 - phi.sin()),
            tensile: m.tensile(),
            cohesion: c,
            friction_angle: phi,
        };
        (s.ucs > 0.0 && s.tensile > 0.0).then_some(s)
    }

    /// Utilisation of the strength by the stress `[σxx, σyy, τxy]` (Pa,
    /// tension positive): with the principal compressions `σ1 ≥ σ3`
    /// (compression positive),
    /// `u = max((σ1 − N_φ σ3) / σ_c, −σ3 / σ_t, 0)`; `u ≥ 1` is failure,
    /// 0 a state that no scaling brings to the envelope (confinement with
    /// `σ3 N_φ ≥ σ1`). Scales with the stress, so `u(λ) = λ u(1)` for a
    /// linear response.
    pub fn utilisation(&self, s: [f64; 3]) -> f64 {
        let (tension, shear) = self.ratios(s);
        shear.max(tension).max(0.0)
    }

    /// The envelope's two checks on the stress `[σxx, σyy, τxy]` (Pa,
    /// tension positive): the tension cut-off `−σ3/σ_t` and the
    /// Mohr–Coulomb line `(σ1 − N_φ σ3)/σ_c` (principal compressions
    /// σ1 ≥ σ3, compression positive), each 1 on its part of the envelope.
    pub fn ratios(&self, s: [f64; 3]) -> (f64, f64) {
        let centre = 0.5 * (s[0] + s[1]);
        let radius = (0.25 * (s[0] - s[1]).powi(2) + s[2] * s[2]).sqrt();
        // compression positive: σ1 the larger compression
        let (sigma1, sigma3) = (radius - centre, -radius - centre);
        (
            -sigma3 / self.tensile,
            (sigma1 - self.n_phi * sigma3) / self.ucs,
        )
    }
}

/// The rock away from the cracks (elements with no enriched node) against
/// its strength, from the stress at each element's centre; on a mesh so
/// coarse that the enrichment covers every element, all elements. Every
/// element has the same area, so the median over elements is the area
/// median.
pub fn intact_rock(xfem: &Xfem, u: &[f64], strength: &RockStrength) -> IntactRockReport {
    let field = Field { xfem, u };
    let mesh = &xfem.mesh;
    let at_centre = |e: usize| {
        let (lo, hi) = mesh.element_box(e);
        let centre = P2::new(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y));
        strength.utilisation(field.stress(&field.in_element(e, centre)))
    };
    let enriched = |e: usize| {
        mesh.element_nodes(e)
            .iter()
            .any(|&n| xfem.dofs.is_enriched(n))
    };
    let all = 0..mesh.element_count();
    let mut values: Vec<f64> = all
        .clone()
        .filter(|&e| !enriched(e))
        .map(at_centre)
        .collect();
    if values.is_empty() {
        values = all.map(at_centre).collect();
    }
    values.retain(|v| v.is_finite());
    if values.is_empty() {
        return IntactRockReport {
            ucs: strength.ucs,
            ..IntactRockReport::default()
        };
    }
    let failed = values.iter().filter(|&&v| v >= 1.0).count();
    let mid = values.len() / 2;
    let (_, median, _) = values.select_nth_unstable_by(mid, f64::total_cmp);
    IntactRockReport {
        utilisation: *median,
        failed_fraction: failed as f64 / values.len() as f64,
        ucs: strength.ucs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Plane;

    /// c = 15 MPa, φ = 49°: the defaults of the bundled scenes.
    fn material() -> Material {
        Material {
            young: 50e9,
            poisson: 0.25,
            plane: Plane::Strain,
            cohesion: 15e6,
            friction_angle_deg: 49.0,
            k_ic: 1e6,
            k_iic: 2e6,
            tensile_strength: None,
        }
    }

    fn rock() -> RockStrength {
        RockStrength::of_material(&material()).expect("c > 0")
    }

    /// Closed forms: uniaxial compression at σ_c, a triaxial state on the
    /// envelope `σ1 = σ_c + N_φ σ3`, and uniaxial tension at σ_t, each at
    /// utilisation 1 (rotated by 30°, so the principal axes are not the
    /// mesh's), and equal biaxial tension at σ_t.
    #[test]
    fn utilisation_is_one_on_the_envelope() {
        let r = rock();
        // σ_c = 2c cos φ/(1 − sin φ) = 80.24 MPa for these values
        assert!((r.ucs - 80.24e6).abs() < 0.01e6, "σ_c = {}", r.ucs);
        let rotate = |p1: f64, p2: f64| {
            let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
            [
                p1 * c * c + p2 * s * s,
                p1 * s * s + p2 * c * c,
                (p1 - p2) * s * c,
            ]
        };
        let sigma3 = 10e6;
        for (s, what) in [
            (rotate(0.0, -r.ucs), "uniaxial compression"),
            (rotate(-sigma3, -(r.ucs + r.n_phi * sigma3)), "triaxial"),
            (rotate(r.tensile, 0.0), "uniaxial tension"),
        ] {
            let u = r.utilisation(s);
            assert!((u - 1.0).abs() < 1e-12, "{what}: u = {u}");
        }
        let u = r.utilisation([r.tensile, r.tensile, 0.0]);
        assert!((u - 1.0).abs() < 1e-12, "biaxial tension: u = {u}");
        // half the uniaxial strength is half used; biaxial compression at
        // k N_φ > 1 (k = 0.2, N_φ = 7.15) can never reach the envelope
        let u = r.utilisation(rotate(0.0, -0.5 * r.ucs));
        assert!((u - 0.5).abs() < 1e-12, "half σ_c: u = {u}");
        assert!((r.n_phi - 7.153).abs() < 1e-3, "N_φ = {}", r.n_phi);
        // no cohesion: no unconfined strength, no utilisation
        let cohesionless = Material {
            cohesion: 0.0,
            tensile_strength: Some(5e6),
            ..material()
        };
        assert_eq!(RockStrength::of_material(&cohesionless), None);
        assert_eq!(r.utilisation(rotate(-0.2e8, -1e8)), 0.0);
    }
}
