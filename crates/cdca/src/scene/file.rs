//! The scene file (SPEC §10) as written: a serde type whose values are not
//! yet checked. [`Scene`](super::Scene) is the checked form: convert with
//! `Scene::try_from(file)` or parse with [`Scene::from_json`](super::Scene::from_json),
//! which reject unknown fields and every invalid value before any work is
//! done, naming the field and the value.
//! All quantities are SI (m, Pa, Pa/m); compression is negative.

use serde::{Deserialize, Serialize};

use crate::error::SceneError;

/// A whole scene as in the file: specimen, mesh, material, cracks, supports
/// and loads, and the settings of criterion, growth and solver. Any values:
/// this is what an editor changes; [`Scene`](super::Scene) is the valid one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Free text shown to the user.
    #[serde(default)]
    pub name: String,
    /// Longer description (optional).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    pub specimen: Specimen,
    pub mesh: MeshSpec,
    pub material: Material,
    #[serde(default)]
    pub cracks: Vec<CrackSpec>,
    #[serde(default)]
    pub boundary: Boundary,
    #[serde(default)]
    pub criterion: CriterionSpec,
    #[serde(default)]
    pub growth: GrowthSpec,
    #[serde(default)]
    pub solver: SolverSpec,
}

/// Rectangle `width × height` with its lower-left corner at the origin.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Specimen {
    /// m
    pub width: f64,
    /// m
    pub height: f64,
    /// m (forces are per unit thickness times `thickness`)
    #[serde(default = "one")]
    pub thickness: f64,
}

/// Structured `nx × ny` grid of bilinear quadrilaterals.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    pub nx: usize,
    pub ny: usize,
    /// Smallest radius of the tip enrichment in element sizes (default
    /// 2.5). The zone is geometric above it: a fifth of the crack's length
    /// per tip (and of its end segment), at most 16 element sizes (see
    /// [`XfemParams`](crate::discretisation::xfem::XfemParams)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub enrichment_radius: Option<f64>,
}

/// Plane stress or plane strain.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Plane {
    #[default]
    Stress,
    Strain,
}

/// Isotropic linear elastic rock with its strength parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus E, Pa.
    pub young: f64,
    /// Poisson's ratio ν.
    #[serde(default = "default_poisson")]
    pub poisson: f64,
    #[serde(default)]
    pub plane: Plane,
    /// Cohesion c of the rock (shear criterion), Pa.
    #[serde(default = "default_cohesion")]
    pub cohesion: f64,
    /// Internal friction angle φ of the rock, degrees.
    #[serde(default = "default_friction_angle")]
    pub friction_angle_deg: f64,
    /// Mode-I toughness K_IC, Pa·√m.
    #[serde(default = "default_k_ic")]
    pub k_ic: f64,
    /// Mode-II toughness K_IIC, Pa·√m.
    #[serde(default = "default_k_iic")]
    pub k_iic: f64,
    /// Tensile strength σ_t, Pa; `null` means `K_IC / √(2π r0)` when
    /// `criterion.r0` is given, else the Mohr–Coulomb tension cut-off
    /// `2c cos φ / (1 + sin φ)`.
    #[serde(default)]
    pub tensile_strength: Option<f64>,
}

impl Material {
    /// Tensile strength of the Mohr–Coulomb envelope with a tension cut-off at
    /// its apex tangent, `σ_t = 2c cos φ / (1 + sin φ)`, Pa: the uniaxial
    /// tension at which the Mohr circle `(σ_t, 0)` touches `τ = c + σ_n tan φ`.
    pub fn tension_cutoff(&self) -> f64 {
        let phi = self.friction_angle_deg.to_radians();
        2.0 * self.cohesion * phi.cos() / (1.0 + phi.sin())
    }

    /// The rock's tensile strength σ_t, Pa: `tensile_strength`, else the
    /// [`tension_cutoff`](Self::tension_cutoff).
    pub fn tensile(&self) -> f64 {
        self.tensile_strength
            .unwrap_or_else(|| self.tension_cutoff())
    }

    /// Irwin's process zone at the tensile strength `sigma_t`,
    /// `r_p = (K_IC/σ_t)² / 2π`, m.
    pub fn process_zone(&self, sigma_t: f64) -> f64 {
        (self.k_ic / sigma_t).powi(2) / (2.0 * std::f64::consts::PI)
    }
}

/// Geometry of an arc crack: centre, radius, start and end angle (degrees,
/// counter-clockwise from +x).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArcSpec {
    pub center: [f64; 2],
    pub radius: f64,
    pub start_deg: f64,
    pub end_deg: f64,
}

/// One crack: a polyline (or an arc) and its face properties.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CrackSpec {
    /// Polyline vertices, m. Exactly one of `points` and `arc` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<Vec<[f64; 2]>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arc: Option<ArcSpec>,
    /// Coulomb friction coefficient μ of the faces.
    #[serde(default)]
    pub friction: f64,
    /// Cohesion of the faces c_c, Pa.
    #[serde(default)]
    pub cohesion: f64,
    /// Normal joint stiffness k_N, Pa/m; `None` means the penalty `100 E/h`.
    #[serde(default)]
    pub normal_stiffness: Option<f64>,
    /// Shear joint stiffness k_T, Pa/m; `None` means `k_N/10`.
    #[serde(default)]
    pub shear_stiffness: Option<f64>,
}

/// Support or load on one side of the specimen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum SideBc {
    /// Traction-free.
    #[default]
    Free,
    /// Both displacements zero.
    Fixed,
    /// Normal displacement zero.
    Roller,
    /// Uniform traction: `normal` along the outward normal (tension
    /// positive), `shear` along the global axis of the side (+x on top and
    /// bottom, +y on left and right), both in Pa.
    Traction {
        #[serde(default)]
        normal: f64,
        #[serde(default)]
        shear: f64,
    },
}

/// Which displacement components a point support fixes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Fix {
    X,
    Y,
    Xy,
}

/// A point support: fixes the node nearest to `at`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointSupport {
    pub at: [f64; 2],
    pub fix: Fix,
}

/// Supports and loads of the four sides plus point supports.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Boundary {
    #[serde(default = "roller")]
    pub bottom: SideBc,
    #[serde(default = "roller")]
    pub left: SideBc,
    #[serde(default)]
    pub top: SideBc,
    #[serde(default)]
    pub right: SideBc,
    #[serde(default)]
    pub points: Vec<PointSupport>,
}

impl Default for Boundary {
    fn default() -> Self {
        Self {
            bottom: SideBc::Roller,
            left: SideBc::Roller,
            top: SideBc::Free,
            right: SideBc::Free,
            points: Vec::new(),
        }
    }
}

/// Which fracture criterion decides growth (SPEC §8).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CriterionKind {
    /// Tensile first, then Mohr–Coulomb shear (the paper's).
    #[default]
    Comprehensive,
    /// Maximum tangential stress from K_I, K_II (Erdogan–Sih).
    Mts,
    /// Generalised MTS with the T-stress term.
    MtsT,
}

/// Where σ_θθ and τ_rθ on the circle r0 come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Sampling {
    /// From the computed (enriched) stress field.
    Field,
    /// From the Williams expansion with K_I, K_II, T.
    Williams,
    /// Singular Williams terms with K_I⁺ = max(K_I, 0) and K_II at r0 plus
    /// the uniform stress at the tip: σ22, σ12 from the tractions of the
    /// faces within 2h of the tip (zero when open) and σ11 = T + σ22
    /// (`criterion::sample_hybrid`): independent of r0/h, the same at every
    /// tip.
    #[default]
    Hybrid,
}

/// Shear strength of the comprehensive criterion's shear branch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShearStrength {
    /// `|τ| ≥ σ_n μ + c_c + K_IIC/√(2π r0)`: friction and cohesion of the
    /// crack's own faces plus the shear analogue of σ_t, at a tip whose
    /// faces are closed, on the circle's Mohr–Coulomb critical plane (the
    /// largest |τ| over strength). Straight ahead of a closed tip
    /// (θ1 = 0) it is `K_II ≥ K_IIC`.
    #[default]
    Faces,
    /// `|τ| ≥ σ_n tan φ + c` with the rock's friction angle and cohesion,
    /// on the circle's Mohr–Coulomb critical plane, at every tip.
    Rock,
}

/// The criterion settings as the file writes them (SPEC §10's flat form).
/// A setting the kind would not read is refused when the file becomes a
/// [`Scene`](crate::scene::Scene) ([`CriterionSpec::settings`], which gives
/// the tagged [`Criterion`](crate::scene::Criterion)); `sampling` and
/// `shear_strength` are left out of the file when not given.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CriterionSpec {
    #[serde(default)]
    pub kind: CriterionKind,
    /// Radius of the evaluation circle, m; `None` means the process-zone
    /// size `r_p = (K_IC/σ_t)² / 2π` (`criterion::radius_and_strength`),
    /// or `a/5π` on a crack of half-length `a < 5π r_p`
    /// (`CriterionParams::for_crack`).
    #[serde(default)]
    pub r0: Option<f64>,
    /// Where the circle's stresses come from (comprehensive only; `None`:
    /// the default, hybrid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sampling: Option<Sampling>,
    /// The shear branch's envelope (comprehensive only; `None`: the
    /// default, the faces').
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_strength: Option<ShearStrength>,
}

/// How the load follows the growth (SPEC §9 "Control").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GrowthControl {
    /// Proportional ramp to the scene's load in `load_steps` increments.
    #[default]
    Load,
    /// Growth to failure: before each step the load factor λ_cr at which
    /// the most critical free tip just meets its criterion.
    Critical,
}

/// How the intact rock between the cracks fails (SPEC §8,
/// `growth.intact_rock`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IntactRock {
    /// Where the rock's Mohr–Coulomb envelope with its tension cut-off,
    /// read over a disc of radius r0, is met below every tip's and kink's
    /// load, a new crack starts there (`fracture::sites`).
    #[default]
    Nucleate,
    /// The paper's model: only crack tips and kinks grow; the rock between
    /// them never fails.
    Ignore,
}

impl IntactRock {
    /// As in the scene file: `"nucleate"`, `"ignore"`.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Nucleate => "nucleate",
            Self::Ignore => "ignore",
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "GrowthFields")]
pub struct GrowthSpec {
    pub control: GrowthControl,
    /// Growth increment Δa, m; `None` means `max(r0, 3h)` with the scene's
    /// r0 (`r_p` when `criterion.r0` is not given), the same for every crack.
    pub increment: Option<f64>,
    pub load_steps: usize,
    pub max_growth_per_step: usize,
    pub max_steps: usize,
    /// With critical control, growth ends (`completed`) when λ_cr would
    /// exceed this factor of the scene's loads.
    pub max_load_factor: f64,
    /// Whether a crack's sharp kinks are sites of the criterion, where
    /// secondary cracks start (SPEC §8; `fracture::kinks`). `false`: only
    /// free tips grow, so a flaw grows its wings alone (as before secondary
    /// cracks existed; for teaching wing cracks, or to compare).
    #[serde(skip_serializing_if = "is_true")]
    pub secondary_cracks: bool,
    /// Whether the intact rock fails (SPEC §8). Always written. A file
    /// without it reads `"nucleate"`, except one that resumes a saved run
    /// (`resume` given), which reads `"ignore"`: a run saved before the
    /// field existed continues as it would have.
    pub intact_rock: IntactRock,
    /// Where a run saved mid-way stands; `None` in a scene not yet grown.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resume: Option<super::Resume>,
}

/// [`GrowthSpec`] as read from a file, before `intact_rock`'s default is
/// resolved (it depends on whether the file resumes a run).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GrowthFields {
    #[serde(default)]
    control: GrowthControl,
    #[serde(default)]
    increment: Option<f64>,
    #[serde(default = "default_load_steps")]
    load_steps: usize,
    #[serde(default = "default_max_growth_per_step")]
    max_growth_per_step: usize,
    #[serde(default = "default_max_steps")]
    max_steps: usize,
    #[serde(default = "default_max_load_factor")]
    max_load_factor: f64,
    #[serde(default = "yes")]
    secondary_cracks: bool,
    #[serde(default)]
    intact_rock: Option<IntactRock>,
    #[serde(default)]
    resume: Option<super::Resume>,
}

impl From<GrowthFields> for GrowthSpec {
    fn from(g: GrowthFields) -> Self {
        let intact_rock = g.intact_rock.unwrap_or(if g.resume.is_some() {
            IntactRock::Ignore
        } else {
            IntactRock::Nucleate
        });
        Self {
            control: g.control,
            increment: g.increment,
            load_steps: g.load_steps,
            max_growth_per_step: g.max_growth_per_step,
            max_steps: g.max_steps,
            max_load_factor: g.max_load_factor,
            secondary_cracks: g.secondary_cracks,
            intact_rock,
            resume: g.resume,
        }
    }
}

impl Default for GrowthSpec {
    fn default() -> Self {
        Self {
            increment: None,
            load_steps: default_load_steps(),
            max_growth_per_step: default_max_growth_per_step(),
            max_steps: default_max_steps(),
            control: GrowthControl::default(),
            max_load_factor: default_max_load_factor(),
            secondary_cracks: true,
            intact_rock: IntactRock::Nucleate,
            resume: None,
        }
    }
}

/// Which linear solver runs (SPEC §6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolverKind {
    /// Sparse Cholesky of the assembled matrix.
    #[default]
    Direct,
    /// The paper's cell-by-cell relaxation (block Gauss–Seidel / SOR).
    Automaton,
    /// Conjugate gradients with the automaton's symmetric sweep.
    Cg,
    /// Conjugate gradients with sweep smoothing plus a coarse-grid correction.
    Multigrid,
}

/// Order in which the automaton visits its cells.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Ordering {
    #[default]
    Lexicographic,
    /// Four-colour ordering of the nodes by the parities of their grid
    /// indices (i mod 2, j mod 2): nodes of one colour never share a Q4
    /// element, so their updates commute. Named `red_black` in scene files
    /// after the two-colour ordering of 5-point stencils it generalises; on
    /// Q4 elements two colours do not decouple the nodes, four do.
    RedBlack,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    #[serde(default)]
    pub kind: SolverKind,
    /// Relative residual tolerance of iterative solvers.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// Over-relaxation factor ω of the automaton, in (0, 2) (with
    /// `in_sweep` contact, 1 at the cells that carry face points).
    #[serde(default = "one")]
    pub omega: f64,
    #[serde(default)]
    pub ordering: Ordering,
    /// Relative change of the displacement that ends the contact iteration.
    #[serde(default = "default_contact_tolerance")]
    pub contact_tolerance: f64,
    #[serde(default = "default_max_contact_iterations")]
    pub max_contact_iterations: usize,
    /// When the contact states are updated: `outer` (after each linear
    /// solve, the default) or `in_sweep` (at each cell visit of the
    /// automaton; `kind` must be `automaton`).
    #[serde(default, skip_serializing_if = "ContactUpdate::is_outer")]
    pub contact_update: ContactUpdate,
}

/// When the contact iteration updates the face points' states (SPEC §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactUpdate {
    /// An outer fixed-point loop: solve the linear system of the current
    /// states, then update every point by the return mapping.
    #[default]
    Outer,
    /// The paper's DCA rule: the automaton updates the states and
    /// tractions of the points a cell affects as the sweep passes the cell.
    InSweep,
}

impl ContactUpdate {
    /// Whether this is the default, [`ContactUpdate::Outer`].
    pub fn is_outer(&self) -> bool {
        *self == Self::Outer
    }

    /// Name as in the scene file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Outer => "outer",
            Self::InSweep => "in_sweep",
        }
    }
}

impl Default for SolverSpec {
    fn default() -> Self {
        Self {
            kind: SolverKind::Direct,
            tolerance: default_tolerance(),
            max_iterations: default_max_iterations(),
            omega: 1.0,
            ordering: Ordering::Lexicographic,
            contact_tolerance: default_contact_tolerance(),
            max_contact_iterations: default_max_contact_iterations(),
            contact_update: ContactUpdate::Outer,
        }
    }
}

/// A direct solve has converged when its true relative residual
/// ‖f − K u‖/‖f‖ is at most this: the contact iteration's default
/// tolerance. A factorisation reaches about 4e-13 on the bundled scenes
/// and 4e-10 with joint penalties of 10⁶ E/h; a singular matrix (a piece
/// held by its crack faces alone) leaves residuals of order one.
pub const DIRECT_TOLERANCE: f64 = 1e-8;

fn one() -> f64 {
    1.0
}
fn roller() -> SideBc {
    SideBc::Roller
}
fn default_poisson() -> f64 {
    0.25
}
fn default_cohesion() -> f64 {
    15e6
}
fn default_friction_angle() -> f64 {
    49.0
}
fn default_k_ic() -> f64 {
    1.03e6
}
fn yes() -> bool {
    true
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if signature
fn is_true(b: &bool) -> bool {
    *b
}

fn default_k_iic() -> f64 {
    2.52e6
}
fn default_load_steps() -> usize {
    10
}
fn default_max_growth_per_step() -> usize {
    20
}
fn default_max_steps() -> usize {
    200
}
fn default_max_load_factor() -> f64 {
    100.0
}
fn default_tolerance() -> f64 {
    1e-10
}
fn default_max_iterations() -> usize {
    100_000
}
fn default_contact_tolerance() -> f64 {
    1e-8
}
/// Contact iterations allowed per solve. On 16 held-out flaw pairs grown
/// to failure (1159 trial solves) a solve that converged took 8 iterations
/// (median), 27 (99th percentile) and at most 73; with 50, four of the
/// runs stopped unconverged at a trial that needed 51–73. The last steps
/// of a specimen coming apart need more: with 100, one of 40 random
/// layouts stopped at its last step on a trial that needed 151–200, and a
/// cohesive flaw (30 MPa) on one that needed 101–120.
fn default_max_contact_iterations() -> usize {
    200
}

impl SceneFile {
    /// Parses a scene file without checking its values (unknown fields and
    /// wrong types are errors naming the field).
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        serde_json::from_str(text).map_err(|e| SceneError::Parse(e.to_string()))
    }

    /// Pretty JSON; `from_json(to_json(s)?) == s`.
    pub fn to_json(&self) -> Result<String, SceneError> {
        serde_json::to_string_pretty(self).map_err(|e| SceneError::Write(e.to_string()))
    }

    /// Element size h (the larger of the two cell sides), m.
    pub fn element_size(&self) -> f64 {
        (self.specimen.width / self.mesh.nx as f64).max(self.specimen.height / self.mesh.ny as f64)
    }

    /// Polyline of crack `i` (arcs sampled, see [`CrackSpec::polyline`]).
    pub fn crack_polyline(&self, i: usize) -> Vec<[f64; 2]> {
        self.cracks[i].polyline(self.element_size())
    }
}

impl CrackSpec {
    /// Straight crack between two points with no friction, no cohesion and
    /// the penalty stiffness.
    pub fn segment(a: [f64; 2], b: [f64; 2]) -> Self {
        Self {
            points: Some(vec![a, b]),
            arc: None,
            friction: 0.0,
            cohesion: 0.0,
            normal_stiffness: None,
            shear_stiffness: None,
        }
    }

    /// The crack as a polyline. An arc is sampled with segments no longer
    /// than `h/2` (and at least 8 of them).
    pub fn polyline(&self, h: f64) -> Vec<[f64; 2]> {
        if let Some(points) = &self.points {
            return points.clone();
        }
        let Some(arc) = &self.arc else {
            return Vec::new();
        };
        let sweep = (arc.end_deg - arc.start_deg).to_radians();
        let length = (sweep * arc.radius).abs();
        let n = ((length / (0.5 * h)).ceil() as usize).clamp(8, 10_000);
        (0..=n)
            .map(|k| {
                let a = arc.start_deg.to_radians() + sweep * k as f64 / n as f64;
                [
                    arc.center[0] + arc.radius * a.cos(),
                    arc.center[1] + arc.radius * a.sin(),
                ]
            })
            .collect()
    }
}
