//! The stress and displacement fields as the canvas shows them: sampled from
//! the solver at sub-cell points, cached, and refreshed a few rows per frame
//! (the field task) so that sampling never blows the frame budget.

use cdca::Simulation;
use cdca::fracture::rock::RockStrength;
use cdca::scene::{Material, Plane};
use serde::{Deserialize, Serialize};
use web_time::Instant;

/// While a run goes on, the canvas's field follows the solver at most this
/// often (sampled coarsely, one sample per element), s.
pub const LIVE_FIELD_INTERVAL: f64 = 0.15;

/// Which scalar the colour map shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum FieldKind {
    None,
    SigmaXx,
    SigmaYy,
    TauXy,
    Sigma1,
    #[default]
    Sigma3,
    VonMises,
    /// The rock's Mohr–Coulomb utilisation (≥ 1: the rock fails there).
    Strength,
    Displacement,
}

impl FieldKind {
    pub const ALL: [Self; 9] = [
        Self::None,
        Self::SigmaXx,
        Self::SigmaYy,
        Self::TauXy,
        Self::Sigma1,
        Self::Sigma3,
        Self::VonMises,
        Self::Strength,
        Self::Displacement,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Self::None => "No field",
            Self::SigmaXx => "σ_xx",
            Self::SigmaYy => "σ_yy",
            Self::TauXy => "τ_xy",
            Self::Sigma1 => "σ_1 (major)",
            Self::Sigma3 => "σ_3 (minor)",
            Self::VonMises => "von Mises",
            Self::Strength => "Strength used",
            Self::Displacement => "|u|",
        }
    }

    /// Unit on the legend, and the factor from SI to it.
    pub fn unit(self) -> (&'static str, f64) {
        match self {
            Self::Displacement => ("mm", 1e3),
            Self::Strength => ("–", 1.0),
            _ => ("MPa", 1e-6),
        }
    }

    /// The scalar at one sample, SI (Pa or m; the strength used as a
    /// fraction, see [`RockStrength::utilisation`]).
    pub fn value(self, s: &Sample, m: &Rock) -> f64 {
        let [sx, sy, txy] = s.stress;
        let centre = 0.5 * (sx + sy);
        let radius = (0.5 * (sx - sy)).hypot(txy);
        match self {
            Self::None => f64::NAN,
            Self::SigmaXx => sx,
            Self::SigmaYy => sy,
            Self::TauXy => txy,
            Self::Sigma1 => centre + radius,
            Self::Sigma3 => centre - radius,
            Self::VonMises => von_mises(s.stress, m.plane, m.poisson),
            Self::Strength => m.strength.map_or(f64::NAN, |r| r.utilisation(s.stress)),
            Self::Displacement => {
                let mean = s
                    .corner_disp
                    .iter()
                    .fold([0.0; 2], |a, u| [a[0] + u[0] / 4.0, a[1] + u[1] / 4.0]);
                mean[0].hypot(mean[1])
            }
        }
    }
}

/// What the scalars need of the material, worked out once per field.
#[derive(Clone, Copy, Debug)]
pub struct Rock {
    pub plane: Plane,
    pub poisson: f64,
    /// `None` for a rock without cohesion.
    pub strength: Option<RockStrength>,
}

impl Rock {
    pub fn of(m: &Material) -> Self {
        Self {
            plane: m.plane,
            poisson: m.poisson,
            strength: RockStrength::of_material(m),
        }
    }
}

/// von Mises stress of an in-plane state; in plane strain σ_zz = ν(σ_xx + σ_yy).
pub fn von_mises([sx, sy, txy]: [f64; 3], plane: Plane, poisson: f64) -> f64 {
    let sz = match plane {
        Plane::Stress => 0.0,
        Plane::Strain => poisson * (sx + sy),
    };
    (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2)) + 3.0 * txy * txy).sqrt()
}

/// One sub-cell: stress at its centre and displacement at its four corners
/// (taken slightly inside, so a crack through a corner shows its opening).
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    /// σ_xx, σ_yy, τ_xy, Pa (NaN where the solver has no value).
    pub stress: [f64; 3],
    /// Displacement at the corners (SW, SE, NE, NW), m.
    pub corner_disp: [[f64; 2]; 4],
}

const NAN_SAMPLE: Sample = Sample {
    stress: [f64::NAN; 3],
    corner_disp: [[0.0; 2]; 4],
};

/// What a sampled field was sampled from.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FieldKey {
    pub version: u64,
    pub cols: usize,
    pub rows: usize,
    pub width: f64,
    pub height: f64,
    pub with_displacement: bool,
}

/// A complete sampled field on a `cols × rows` grid of sub-cells.
#[derive(Clone, Debug)]
pub struct FieldSamples {
    pub key: FieldKey,
    /// The load factor of the state sampled.
    pub load_factor: f64,
    /// Row-major from the bottom-left.
    pub samples: Vec<Sample>,
}

/// How large a sampled field's stresses are against the load it was
/// sampled at: the sign of a field that is not one (issue 63), a field of
/// zeros (a solve's start) or a working vector's GPa spikes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldScale {
    /// Largest finite |σ| component, Pa.
    pub peak: f64,
    /// 99th percentile of the finite |σ| components, Pa.
    pub p99: f64,
    /// Largest boundary traction at the field's load factor, Pa.
    pub load: f64,
}

impl FieldScale {
    /// A field, not a vanished or garbled one: its peak is at least 1e-6
    /// of the load, and its 99th percentile at most 10 times the load (the
    /// bundled scenes' solved fields stay under 2 times it; a direct
    /// solve's working vector between Newton steps gave 75 times it).
    /// Without a load (displacements only) any field is one.
    pub fn is_a_field(&self) -> bool {
        self.load == 0.0 || (self.peak >= 1e-6 * self.load && self.p99 <= 10.0 * self.load)
    }
}

impl FieldSamples {
    /// How large its stresses are against `traction` (the largest
    /// boundary traction at λ = 1, Pa) at its load factor.
    pub fn scale(&self, traction: f64) -> FieldScale {
        let mut v: Vec<f64> = self
            .samples
            .iter()
            .flat_map(|s| s.stress)
            .filter(|v| v.is_finite())
            .map(f64::abs)
            .collect();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        FieldScale {
            peak: v.last().copied().unwrap_or(0.0),
            p99: if n == 0 { 0.0 } else { v[(n - 1) * 99 / 100] },
            load: traction * self.load_factor.abs(),
        }
    }

    /// Sub-cell size, m.
    pub fn cell(&self) -> [f64; 2] {
        [
            self.key.width / self.key.cols as f64,
            self.key.height / self.key.rows as f64,
        ]
    }
}

/// Keeps the last complete field and builds the next one row by row.
#[derive(Default)]
pub struct FieldSampler {
    current: Option<FieldSamples>,
    building: Option<FieldSamples>,
}

/// Fraction of a sub-cell by which corner samples are pulled inwards.
const CORNER_INSET: f64 = 0.02;

impl FieldSampler {
    pub fn current(&self) -> Option<&FieldSamples> {
        self.current.as_ref()
    }

    /// Whether `key` is already shown.
    pub fn is_current(&self, key: &FieldKey) -> bool {
        self.current.as_ref().is_some_and(|f| f.key == *key)
    }

    /// Fraction of the field being built, if one is.
    pub fn progress(&self) -> Option<f32> {
        let b = self.building.as_ref()?;
        Some(b.samples.len() as f32 / (b.key.cols * b.key.rows) as f32)
    }

    pub fn clear(&mut self) {
        self.current = None;
        self.building = None;
    }

    /// Shows `field`, sampled elsewhere (the host) or before (a run
    /// brought back by Undo); a field being built is dropped.
    pub fn show(&mut self, field: FieldSamples) {
        self.current = Some(field);
        self.building = None;
    }

    /// Samples rows of the field `key` from `sim`'s current iterate (the
    /// solution, or the displacement of a solve under way) until
    /// `deadline` (at least one row); true (finished) once the field is
    /// complete and current.
    pub fn advance(&mut self, sim: &Simulation, key: FieldKey, deadline: Instant) -> bool {
        if self.is_current(&key) {
            return true;
        }
        if self.building.as_ref().is_none_or(|b| b.key != key) {
            self.building = Some(FieldSamples {
                key,
                load_factor: sim.load_factor(),
                samples: Vec::with_capacity(key.cols * key.rows),
            });
        }
        let Some(b) = self.building.as_mut() else {
            return false;
        };
        let [dx, dy] = b.cell();
        while b.samples.len() < key.cols * key.rows {
            let row = b.samples.len() / key.cols;
            let y = (row as f64 + 0.5) * dy;
            for col in 0..key.cols {
                let x = (col as f64 + 0.5) * dx;
                b.samples
                    .push(sample_at(sim, [x, y], [dx, dy], key.with_displacement));
            }
            if Instant::now() >= deadline {
                break;
            }
        }
        if b.samples.len() == key.cols * key.rows {
            self.current = self.building.take();
            return true;
        }
        false
    }
}

fn sample_at(
    sim: &Simulation,
    centre: [f64; 2],
    [dx, dy]: [f64; 2],
    with_displacement: bool,
) -> Sample {
    let Some(stress) = sim.current_stress_at(centre) else {
        return NAN_SAMPLE;
    };
    let mut corner_disp = [[0.0; 2]; 4];
    if with_displacement {
        let hx = (0.5 - CORNER_INSET) * dx;
        let hy = (0.5 - CORNER_INSET) * dy;
        let corners = [[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]];
        for (u, c) in corner_disp.iter_mut().zip(corners) {
            *u = sim
                .current_displacement_at([centre[0] + c[0], centre[1] + c[1]])
                .unwrap_or([0.0; 2]);
        }
    }
    Sample {
        stress,
        corner_disp,
    }
}

/// Colour range of a field: the 1st and 99th percentiles of the finite
/// values (crack tips are singular, a min–max range would show one colour),
/// or the full range when `clip` is false.
pub fn value_range(values: &[f64], clip: bool) -> Option<(f64, f64)> {
    let mut finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.is_empty() {
        return None;
    }
    finite.sort_by(f64::total_cmp);
    let n = finite.len();
    let (lo, hi) = if clip {
        (finite[n / 100], finite[(n - 1) - n / 100])
    } else {
        (finite[0], finite[n - 1])
    };
    if hi > lo {
        Some((lo, hi))
    } else {
        let pad = lo.abs().max(1e-12) * 1e-3;
        Some((lo - pad, hi + pad))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Plane stress, ν = 0.25, σ_c = 50 MPa, N_φ = 3 (φ = 30°), σ_t =
    /// 5 MPa (c = σ_c/2√N_φ = 14.43 MPa).
    fn rock() -> Rock {
        Rock {
            plane: Plane::Stress,
            poisson: 0.25,
            strength: Some(RockStrength {
                ucs: 50e6,
                n_phi: 3.0,
                tensile: 5e6,
                cohesion: 50e6 / (2.0 * 3f64.sqrt()),
                friction_angle: 30f64.to_radians(),
            }),
        }
    }

    fn at(stress: [f64; 3]) -> Sample {
        Sample {
            stress,
            corner_disp: [[3e-3, 4e-3]; 4],
        }
    }

    #[test]
    fn principal_stresses_of_pure_shear_are_plus_and_minus_tau() {
        let s = at([0.0, 0.0, 5e6]);
        assert!((FieldKind::Sigma1.value(&s, &rock()) - 5e6).abs() < 1e-6);
        assert!((FieldKind::Sigma3.value(&s, &rock()) + 5e6).abs() < 1e-6);
    }

    #[test]
    fn von_mises_of_uniaxial_stress_is_its_magnitude() {
        assert!((von_mises([-10e6, 0.0, 0.0], Plane::Stress, 0.25) - 10e6).abs() < 1e-6);
    }

    #[test]
    fn displacement_magnitude_is_the_corner_mean() {
        assert!((FieldKind::Displacement.value(&at([0.0; 3]), &rock()) - 5e-3).abs() < 1e-12);
    }

    /// Uniaxial compression at σ_c uses the whole strength; a rock without
    /// strength has no value (the field is not offered then).
    #[test]
    fn strength_used_is_one_at_the_unconfined_strength() {
        let u = FieldKind::Strength.value(&at([0.0, -50e6, 0.0]), &rock());
        assert!((u - 1.0).abs() < 1e-12, "{u}");
        let none = Rock {
            strength: None,
            ..rock()
        };
        assert!(
            FieldKind::Strength
                .value(&at([0.0, -50e6, 0.0]), &none)
                .is_nan()
        );
    }

    #[test]
    fn clipped_range_ignores_a_singular_outlier() {
        let mut v: Vec<f64> = (0..1000).map(f64::from).collect();
        v.push(1e12);
        v.push(f64::NAN);
        let (lo, hi) = value_range(&v, true).unwrap_or_default();
        assert!(lo >= 0.0 && hi < 1000.0);
        let (_, full_hi) = value_range(&v, false).unwrap_or_default();
        assert_eq!(full_hi, 1e12);
    }
}
