//! Isotropic linear elasticity in plane stress or plane strain.

use nalgebra::Matrix3;

use crate::scene::{Material, Plane};

/// Elastic constants derived once from the scene's material.
#[derive(Clone, Debug, PartialEq)]
pub struct Elastic {
    pub young: f64,
    pub poisson: f64,
    pub plane: Plane,
    /// Constitutive matrix in Voigt form `[σxx, σyy, τxy] = D [εxx, εyy, γxy]`.
    pub d: Matrix3<f64>,
}

impl Elastic {
    pub fn new(m: &Material) -> Self {
        let (e, nu) = (m.young, m.poisson);
        let d = match m.plane {
            Plane::Stress => {
                let c = e / (1.0 - nu * nu);
                Matrix3::new(
                    c,
                    c * nu,
                    0.0,
                    c * nu,
                    c,
                    0.0,
                    0.0,
                    0.0,
                    c * (1.0 - nu) / 2.0,
                )
            }
            Plane::Strain => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                Matrix3::new(
                    c * (1.0 - nu),
                    c * nu,
                    0.0,
                    c * nu,
                    c * (1.0 - nu),
                    0.0,
                    0.0,
                    0.0,
                    c * (1.0 - 2.0 * nu) / 2.0,
                )
            }
        };
        Self {
            young: e,
            poisson: nu,
            plane: m.plane,
            d,
        }
    }

    /// Shear modulus μ = E / (2(1+ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// Kolosov constant κ: `(3−ν)/(1+ν)` (stress), `3−4ν` (strain).
    pub fn kappa(&self) -> f64 {
        match self.plane {
            Plane::Stress => (3.0 - self.poisson) / (1.0 + self.poisson),
            Plane::Strain => 3.0 - 4.0 * self.poisson,
        }
    }

    /// Effective modulus E' for fracture: E (stress), E/(1−ν²) (strain).
    pub fn e_prime(&self) -> f64 {
        match self.plane {
            Plane::Stress => self.young,
            Plane::Strain => self.young / (1.0 - self.poisson * self.poisson),
        }
    }

    /// Strain (engineering shear) from stress: `D⁻¹ σ` in closed form.
    pub fn strain_from_stress(&self, s: [f64; 3]) -> [f64; 3] {
        let (e, nu) = (self.young, self.poisson);
        let g = self.shear_modulus();
        match self.plane {
            Plane::Stress => [(s[0] - nu * s[1]) / e, (s[1] - nu * s[0]) / e, s[2] / g],
            Plane::Strain => {
                let k = (1.0 + nu) / e;
                [
                    k * ((1.0 - nu) * s[0] - nu * s[1]),
                    k * ((1.0 - nu) * s[1] - nu * s[0]),
                    s[2] / g,
                ]
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compliance_inverts_stiffness() {
        for plane in [Plane::Stress, Plane::Strain] {
            let m = Material {
                young: 3e9,
                poisson: 0.3,
                plane,
                cohesion: 0.0,
                friction_angle_deg: 30.0,
                k_ic: 1e6,
                k_iic: 1e6,
                tensile_strength: None,
            };
            let el = Elastic::new(&m);
            let eps = nalgebra::Vector3::new(1e-3, -2e-4, 5e-4);
            let s = el.d * eps;
            let back = el.strain_from_stress([s[0], s[1], s[2]]);
            for k in 0..3 {
                assert!((back[k] - eps[k]).abs() < 1e-15, "{plane:?} {k}");
            }
        }
    }
}
