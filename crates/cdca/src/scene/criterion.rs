//! The criterion settings as a tagged type: each kind of criterion with
//! exactly the settings it reads ([`Criterion`]). The scene file keeps
//! SPEC §10's flat form (`kind`, `r0`, `sampling`, `shear_strength`);
//! a setting given for a kind that would ignore it is refused, naming the
//! field, and [`CriterionKind::fields`] is the one place that says which
//! settings a kind reads (the scene check and the workbench ask it).

use crate::error::SceneError;
use crate::scene::{CriterionKind, CriterionSpec, Sampling, ShearStrength};

/// Which of the optional criterion settings a kind reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CriterionFields {
    /// `criterion.r0`: the radius of the circle the criterion reads.
    pub r0: bool,
    /// `criterion.sampling`: where the stresses on that circle come from.
    pub sampling: bool,
    /// `criterion.shear_strength`: the envelope of the shear branch.
    pub shear_strength: bool,
}

impl CriterionKind {
    /// The settings this kind reads. MTS decides from K_I and K_II alone
    /// (no circle, no σ_t); MTS with T samples its own circle, the Williams
    /// expansion at r0, and has no shear branch; the comprehensive
    /// criterion reads all three.
    pub const fn fields(self) -> CriterionFields {
        match self {
            Self::Comprehensive => CriterionFields {
                r0: true,
                sampling: true,
                shear_strength: true,
            },
            Self::Mts => CriterionFields {
                r0: false,
                sampling: false,
                shear_strength: false,
            },
            Self::MtsT => CriterionFields {
                r0: true,
                sampling: false,
                shear_strength: false,
            },
        }
    }

    /// The name a scene file spells it with.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Comprehensive => "comprehensive",
            Self::Mts => "mts",
            Self::MtsT => "mts_t",
        }
    }
}

/// The criterion of a valid scene, with the settings its kind reads and no
/// other.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Criterion {
    /// Tension first, then Mohr–Coulomb shear (the paper's), on the circle
    /// r0 sampled as `sampling` says.
    Comprehensive {
        /// m; `None`: from the material and the crack's size.
        r0: Option<f64>,
        sampling: Sampling,
        shear_strength: ShearStrength,
    },
    /// Maximum tangential stress from K_I and K_II (Erdogan–Sih).
    Mts,
    /// MTS with the T-stress term, on the Williams expansion at r0.
    MtsT {
        /// m; `None`: from the material and the crack's size.
        r0: Option<f64>,
    },
}

impl Default for Criterion {
    fn default() -> Self {
        Self::Comprehensive {
            r0: None,
            sampling: Sampling::default(),
            shear_strength: ShearStrength::default(),
        }
    }
}

impl Criterion {
    /// Which criterion this is.
    pub const fn kind(self) -> CriterionKind {
        match self {
            Self::Comprehensive { .. } => CriterionKind::Comprehensive,
            Self::Mts => CriterionKind::Mts,
            Self::MtsT { .. } => CriterionKind::MtsT,
        }
    }

    /// The radius the scene gives, m (`None`: the default, or MTS, which
    /// reads no circle).
    pub const fn r0(self) -> Option<f64> {
        match self {
            Self::Comprehensive { r0, .. } | Self::MtsT { r0 } => r0,
            Self::Mts => None,
        }
    }

    /// Where the stresses on the circle come from: the scene's sampling
    /// for the comprehensive criterion, the Williams expansion for MTS
    /// with T; `None` for MTS, which reads no circle.
    pub const fn sampling(self) -> Option<Sampling> {
        match self {
            Self::Comprehensive { sampling, .. } => Some(sampling),
            Self::MtsT { .. } => Some(Sampling::Williams),
            Self::Mts => None,
        }
    }

    /// The shear branch's envelope; `None` for the MTS criteria, which
    /// have no shear branch.
    pub const fn shear_strength(self) -> Option<ShearStrength> {
        match self {
            Self::Comprehensive { shear_strength, .. } => Some(shear_strength),
            Self::Mts | Self::MtsT { .. } => None,
        }
    }
}

impl CriterionSpec {
    /// The tagged criterion, or an error naming the first setting given
    /// that the kind would ignore.
    pub fn settings(&self) -> Result<Criterion, SceneError> {
        let fields = self.kind.fields();
        let ignored = |field: &str, value: String, what: &str| {
            SceneError::invalid(
                format!("criterion.{field}"),
                value,
                format!(
                    "the `{}` criterion reads no {what}, so this setting would be ignored; \
                     leave it out or choose `comprehensive`",
                    self.kind.name()
                ),
            )
        };
        if let (false, Some(r0)) = (fields.r0, self.r0) {
            return Err(ignored("r0", r0.to_string(), "circle"));
        }
        if let (false, Some(s)) = (fields.sampling, self.sampling) {
            let what = if fields.r0 {
                "sampling (it samples its own circle, the Williams expansion)"
            } else {
                "circle"
            };
            return Err(ignored("sampling", format!("{s:?}").to_lowercase(), what));
        }
        if let (false, Some(s)) = (fields.shear_strength, self.shear_strength) {
            return Err(ignored(
                "shear_strength",
                format!("{s:?}").to_lowercase(),
                "shear branch",
            ));
        }
        Ok(match self.kind {
            CriterionKind::Comprehensive => Criterion::Comprehensive {
                r0: self.r0,
                sampling: self.sampling.unwrap_or_default(),
                shear_strength: self.shear_strength.unwrap_or_default(),
            },
            CriterionKind::Mts => Criterion::Mts,
            CriterionKind::MtsT => Criterion::MtsT { r0: self.r0 },
        })
    }

    /// The settings with kind `kind`, keeping those it reads and dropping
    /// the others (what an editor writes when the kind changes).
    #[must_use]
    pub fn with_kind(&self, kind: CriterionKind) -> Self {
        let fields = kind.fields();
        Self {
            kind,
            r0: self.r0.filter(|_| fields.r0),
            sampling: self.sampling.filter(|_| fields.sampling),
            shear_strength: self.shear_strength.filter(|_| fields.shear_strength),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(kind: CriterionKind) -> CriterionSpec {
        CriterionSpec {
            kind,
            r0: Some(1e-3),
            sampling: Some(Sampling::Field),
            shear_strength: Some(ShearStrength::Rock),
        }
    }

    fn refused(s: &CriterionSpec) -> Option<String> {
        match s.settings() {
            Ok(_) => None,
            Err(SceneError::Invalid { field, .. }) => Some(field),
            Err(e) => Some(format!("{e}")),
        }
    }

    /// Every setting a kind would ignore is refused by its name; each
    /// kind's own settings are kept.
    #[test]
    fn ignored_settings_are_refused_by_name() {
        let mts = spec(CriterionKind::Mts);
        assert_eq!(refused(&mts).as_deref(), Some("criterion.r0"));
        let mts = CriterionSpec { r0: None, ..mts };
        assert_eq!(refused(&mts).as_deref(), Some("criterion.sampling"));
        let mts = CriterionSpec {
            sampling: None,
            ..mts
        };
        assert_eq!(refused(&mts).as_deref(), Some("criterion.shear_strength"));
        let mts_t = spec(CriterionKind::MtsT);
        assert_eq!(refused(&mts_t).as_deref(), Some("criterion.sampling"));
        let mts_t = CriterionSpec {
            sampling: None,
            ..mts_t
        };
        assert_eq!(refused(&mts_t).as_deref(), Some("criterion.shear_strength"));
        assert_eq!(
            spec(CriterionKind::Comprehensive).settings(),
            Ok(Criterion::Comprehensive {
                r0: Some(1e-3),
                sampling: Sampling::Field,
                shear_strength: ShearStrength::Rock
            })
        );
    }

    /// Changing the kind keeps what the new kind reads and drops the rest,
    /// so the result is always accepted.
    #[test]
    fn with_kind_keeps_only_what_the_kind_reads() {
        for from in [
            CriterionKind::Comprehensive,
            CriterionKind::Mts,
            CriterionKind::MtsT,
        ] {
            for to in [
                CriterionKind::Comprehensive,
                CriterionKind::Mts,
                CriterionKind::MtsT,
            ] {
                let changed = spec(from).with_kind(to);
                let c = changed.settings().expect("accepted");
                assert_eq!(c.kind(), to);
            }
        }
        assert_eq!(
            spec(CriterionKind::Comprehensive)
                .with_kind(CriterionKind::MtsT)
                .settings(),
            Ok(Criterion::MtsT { r0: Some(1e-3) })
        );
        assert_eq!(
            Criterion::MtsT { r0: None }.sampling(),
            Some(Sampling::Williams)
        );
        assert_eq!(Criterion::Mts.sampling(), None);
    }
}
