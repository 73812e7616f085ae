//! Where a growth run saved mid-way stands (`growth.resume`): what the next
//! growth step starts from besides the cracks, so that a scene saved at any
//! moment of a run and opened again grows the same next step, to the last
//! digit, as the run that went on.
//!
//! Every step starts from the scene: displacement zero, the contact states
//! below (the committed slip history of load control, the initial guess of
//! the contact iteration under critical control), and, under critical
//! control, its first λ_cr trial at the last step's load factor.

use serde::{Deserialize, Serialize};

use crate::error::SceneError;

/// State of a growth run between two steps. Written by the solver into
/// the simulated scene after every step; absent in a scene not yet grown.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Resume {
    /// Growth steps done (the next one is `steps + 1`).
    pub steps: usize,
    /// Load factor λ of the last step (critical control: λ_cr, where the
    /// next step's search starts).
    pub load_factor: f64,
    /// Load control: the load increment (1-based) the run is at, and the
    /// growths done at it.
    #[serde(default = "first_increment")]
    pub increment: usize,
    #[serde(default)]
    pub growths_here: usize,
    /// One entry per crack-face point of the saved cracks' discretisation,
    /// in its order: `[state, g_T^s, g_N, g_T, p_N, p_T]` with state 0 open,
    /// 1 stick, 2 slip; gaps in m, tractions in Pa.
    #[serde(default)]
    pub faces: Vec<[f64; 6]>,
    /// Per crack, the segments grown at its two ends, as scenes saved by
    /// version 0.1 wrote them. Read and ignored: the criterion no longer
    /// depends on which tips grew (one rule at every tip), so nothing
    /// needs it; never written.
    #[serde(default, skip_serializing)]
    pub grown: Vec<[usize; 2]>,
    /// Per crack, what its parts are (for the growth report's links; the
    /// criterion reads none of it). Left out, every crack is a flaw as
    /// drawn.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lineage: Vec<Lineage>,
    /// The run's peak load factor so far, and the cracks started in the
    /// intact rock at a load not above it since it was last raised (the
    /// bound on starts at one load counts them; written under
    /// `growth.intact_rock = "nucleate"` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rock_starts: Option<RockStarts>,
    /// The steps done, in order, each with its load factor and what grew,
    /// started and linked in it: what the run's story, its cracks' kinds,
    /// its peak and its first link between two flaws are told from, and
    /// what a later link is checked against (flaws linked before do not
    /// coalesce again). Each entry is a step's events as the growth report
    /// writes them ([`StepEvents`](crate::report::StepEvents)), held here
    /// as JSON because the scene sits below the report; they are read,
    /// and a bad entry named, when a simulation is built, as `faces` is
    /// checked then. Left out (a scene saved before issue 66 added it),
    /// the run reopens knowing only its steps from `steps + 1` on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub history: Vec<serde_json::Value>,
}

/// Cracks started in the intact rock at one load (see
/// [`Resume::rock_starts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RockStarts {
    /// The largest load factor of a step that grew or started a crack.
    pub peak: f64,
    /// Starts at a load factor within the λ search's band of `peak` or
    /// below it, since `peak` was last raised.
    pub at_peak: usize,
}

/// What a part of a crack is (Park & Bobet 2009, Wong & Einstein 2009):
/// the flaw as drawn, a wing (grown from a flaw's end, first in tension),
/// a secondary crack (started at a kink, or grown from a flaw's end first
/// in shear), or a crack started in the intact rock (SPEC §8,
/// `growth.intact_rock`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Part {
    #[default]
    Flaw,
    Wing,
    Secondary,
    Intact,
}

impl Part {
    /// As serialised: `"flaw"`, `"wing"`, `"secondary"`, `"intact"`.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Flaw => "flaw",
            Self::Wing => "wing",
            Self::Secondary => "secondary",
            Self::Intact => "intact",
        }
    }
}

/// What the parts of one crack's polyline are: the drawn polyline (the
/// flaw), and what grew at each of its ends; or, for a crack started at
/// another crack's kink, a secondary crack throughout; or, for a crack
/// started in the intact rock, such a crack throughout (its own group:
/// `flaw` is its own index).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Lineage {
    /// The drawn crack it belongs to (itself when drawn, and for a crack
    /// started in the intact rock).
    pub flaw: usize,
    /// Points grown at its first end, before the drawn polyline.
    pub front: usize,
    /// Points of the drawn polyline; 0 for a crack started at a kink or
    /// in the intact rock.
    pub drawn: usize,
    /// What grew at each end (`flaw`: nothing yet).
    pub ends: [Part; 2],
}

impl Lineage {
    /// Crack `flaw` as drawn, with `points` points.
    pub fn drawn(flaw: usize, points: usize) -> Self {
        Self {
            flaw,
            front: 0,
            drawn: points,
            ends: [Part::Flaw; 2],
        }
    }

    /// A secondary crack started on a crack of `flaw`.
    pub fn secondary(flaw: usize) -> Self {
        Self {
            flaw,
            front: 0,
            drawn: 0,
            ends: [Part::Secondary; 2],
        }
    }

    /// Crack `own`, started in the intact rock: a group of its own.
    pub fn intact(own: usize) -> Self {
        Self {
            flaw: own,
            front: 0,
            drawn: 0,
            ends: [Part::Intact; 2],
        }
    }

    /// Whether the crack started at another crack's kink.
    pub fn is_secondary(&self) -> bool {
        self.drawn == 0 && self.ends[0] == Part::Secondary
    }

    /// Whether the crack started in the intact rock.
    pub fn is_intact(&self) -> bool {
        self.drawn == 0 && self.ends[0] == Part::Intact
    }

    /// The part segment `j` (from point `j` to `j + 1`) belongs to.
    pub fn part_of_segment(&self, j: usize) -> Part {
        if self.drawn == 0 {
            // started at a kink or in the intact rock: one part throughout
            self.ends[0]
        } else if j < self.front {
            self.ends[0]
        } else if j + 1 >= self.front + self.drawn {
            self.ends[1]
        } else {
            Part::Flaw
        }
    }

    /// Per segment of a polyline of `points` points, whether it is part of
    /// a secondary crack ([`part_of_segment`](Self::part_of_segment)).
    pub fn secondary_segments(&self, points: usize) -> Vec<bool> {
        (0..points.saturating_sub(1))
            .map(|j| self.part_of_segment(j) == Part::Secondary)
            .collect()
    }

    /// Records a growth at end `k`; the first growth at an end names its
    /// part: a wing when in tension, a secondary crack when in shear.
    pub fn grew(&mut self, k: usize, shear: bool) {
        if k == 0 {
            self.front += 1;
        }
        if self.ends[k] == Part::Flaw {
            self.ends[k] = if shear { Part::Secondary } else { Part::Wing };
        }
    }
}

fn first_increment() -> usize {
    1
}

impl Resume {
    /// The saved lineage when it has one entry per crack of a scene of
    /// `cracks` cracks (a scene saved before lineages were written has
    /// none: its cracks count as drawn).
    pub fn lineage_of(&self, cracks: usize) -> Option<&[Lineage]> {
        (self.lineage.len() == cracks).then_some(self.lineage.as_slice())
    }

    /// Checks the values against a scene of `cracks` cracks (the face
    /// count is checked against the discretisation when a simulation is
    /// built).
    pub(crate) fn validate(&self, cracks: usize) -> Result<(), SceneError> {
        if !self.lineage.is_empty() && self.lineage.len() != cracks {
            return Err(SceneError::invalid(
                "growth.resume.lineage",
                format!("{} entries", self.lineage.len()),
                format!("must have one per crack ({cracks})"),
            ));
        }
        if let Some((i, l)) = self
            .lineage
            .iter()
            .enumerate()
            .find(|(_, l)| l.flaw >= cracks)
        {
            return Err(SceneError::invalid(
                format!("growth.resume.lineage[{i}].flaw"),
                l.flaw,
                format!("must name one of the {cracks} cracks"),
            ));
        }
        if let Some(s) = self.rock_starts
            && !(s.peak.is_finite() && s.peak >= 0.0)
        {
            return Err(SceneError::invalid(
                "growth.resume.rock_starts.peak",
                s.peak,
                "must be a finite number ≥ 0",
            ));
        }
        let lambda = self.load_factor;
        if !lambda.is_finite() || lambda < 0.0 {
            return Err(SceneError::invalid(
                "growth.resume.load_factor",
                lambda,
                "must be a finite number ≥ 0",
            ));
        }
        if self.increment == 0 {
            return Err(SceneError::invalid(
                "growth.resume.increment",
                0_usize,
                "must be at least 1",
            ));
        }
        for (i, f) in self.faces.iter().enumerate() {
            let field = format!("growth.resume.faces[{i}]");
            if let Some(v) = f.iter().find(|v| !v.is_finite()) {
                return Err(SceneError::invalid(field, *v, "must be finite"));
            }
            if ![0.0, 1.0, 2.0].contains(&f[0]) {
                return Err(SceneError::invalid(
                    format!("{field}[0]"),
                    f[0],
                    "must be 0 (open), 1 (stick) or 2 (slip)",
                ));
            }
        }
        Ok(())
    }
}
