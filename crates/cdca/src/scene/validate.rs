//! The checks of a [`SceneFile`] (SPEC §10), the one place where scene
//! values are checked: `Scene::try_from` runs them.
//!
//! Every value is checked before any work is done. The first problem found is
//! returned as [`SceneError::Invalid`] whose `field` is a dotted JSON path
//! (`material.poisson`, `cracks[1].points[0]`, `boundary.top.normal`).

mod rigid_body;

use crate::error::{FieldValue, Num, SceneError};
use crate::scene::{ArcSpec, CrackSpec, Material, SceneFile, SideBc, SolverKind};

/// Largest accepted mesh, in elements (`nx × ny`).
pub const MAX_ELEMENTS: usize = 4_000_000;

/// Largest magnitude of a physical value in SI units ([`MIN_MAGNITUDE`]
/// the smallest non-zero one). No quantity of a rock specimen is within
/// ten orders of either (a penalty stiffness of 1e15 Pa/m, a length of a
/// micrometre); inside the range, products of the ten or so factors that
/// meet in a stiffness entry, a load vector's squared norm or the
/// process-zone radius `(K_IC/σ_t)²/2π` stay finite and normal in double
/// precision. Outside it the solver's arithmetic overflows or underflows
/// (a Young's modulus of 1e-300 Pa gave a non-finite solution, a
/// cohesion of 1e300 Pa a process zone of 0 m and a criterion angle of
/// NaN).
const MAX_MAGNITUDE: f64 = 1e30;

/// Smallest magnitude of a non-zero physical value (see [`MAX_MAGNITUDE`]).
const MIN_MAGNITUDE: f64 = 1e-30;

/// Smallest distance between a crack's ends, in element sizes: a tip's
/// interaction-integral domain is path independent from 1.5 h and stops
/// one element short of the crack's other end
/// ([`domain_radius`](crate::fracture::tips::domain_radius)). A centre
/// crack in tension, at six angles and off the grid, reads K within 0.5%
/// from 3.5 h, 3–6.5% at 2.5–3 h and 36–80% off at 1–2 h, where a crack a
/// thousandth of an element long made the stiffness singular.
const MIN_CRACK_SPAN: f64 = 2.5;

/// Shortest segment at a free crack end, and shortest growth increment,
/// in element sizes: a tip takes its direction (its enrichment's frame and
/// the criterion's angles) from its last segment, which the mesh cannot
/// resolve below this. An end segment a thousandth or a hundredth of an
/// element long, turned 90°, made the stiffness singular (the random
/// geometry fuzzer, 3 scenes in 400); from 0.03 h it solved.
pub const MIN_END_SEGMENT: f64 = 0.1;

type Check = Result<(), SceneError>;

impl SceneFile {
    /// Checks every value; the first problem found is returned, naming the
    /// field and the value.
    pub(super) fn validate(&self) -> Result<(), SceneError> {
        self.validate_specimen_and_mesh()?;
        validate_material(&self.material)?;
        for (i, crack) in self.cracks.iter().enumerate() {
            self.validate_crack(i, crack)?;
        }
        self.validate_boundary()?;
        self.validate_settings()?;
        self.validate_rigid_body()
    }

    fn validate_specimen_and_mesh(&self) -> Check {
        let s = &self.specimen;
        positive_quantity("specimen.width", s.width)?;
        positive_quantity("specimen.height", s.height)?;
        positive_quantity("specimen.thickness", s.thickness)?;
        let m = &self.mesh;
        at_least_one("mesh.nx", m.nx)?;
        at_least_one("mesh.ny", m.ny)?;
        let small = m.nx.checked_mul(m.ny).is_some_and(|n| n <= MAX_ELEMENTS);
        let reason = format!("more than {MAX_ELEMENTS} elements; use a coarser mesh");
        ensure(small, "mesh", format!("{} × {}", m.nx, m.ny), reason)?;
        if let Some(r) = m.enrichment_radius {
            let field = "mesh.enrichment_radius";
            ensure(
                finite(field, r)? >= 1.0,
                field,
                r,
                "must be at least 1 (element sizes)",
            )?;
        }
        Ok(())
    }

    fn validate_crack(&self, i: usize, crack: &CrackSpec) -> Check {
        let field = |name: &str| format!("cracks[{i}]{name}");
        match (&crack.points, &crack.arc) {
            (Some(points), None) => {
                let name = |k: usize| field(&format!(".points[{k}]"));
                self.validate_polyline(&field(".points"), points, name)?;
                // a crack the saved run started (at a kink or in the rock)
                // may run between two others, shorter than a drawn crack
                // may be: it was valid where the run made it
                let started = self
                    .growth
                    .resume
                    .as_ref()
                    .and_then(|r| r.lineage.get(i))
                    .is_some_and(|l| l.drawn == 0);
                if !started {
                    self.resolved_span(&field(".points"), points)?;
                }
            }
            (None, Some(arc)) => self.validate_arc(&field(".arc"), arc, crack)?,
            (points, _) => {
                let value = if points.is_some() { "both" } else { "neither" };
                let reason = "give exactly one of `points` and `arc`";
                return Err(SceneError::invalid(field(""), value, reason));
            }
        }
        non_negative_quantity(&field(".friction"), crack.friction)?;
        non_negative_quantity(&field(".cohesion"), crack.cohesion)?;
        for (name, k) in [
            (".normal_stiffness", crack.normal_stiffness),
            (".shear_stiffness", crack.shear_stiffness),
        ] {
            if let Some(k) = k {
                self.penalty(&field(name), k)?;
            }
        }
        Ok(())
    }

    /// A joint stiffness `k` (Pa/m): positive, and `k h/E` below 1/ε, the
    /// ratio at which the rock's own stiffness is lost in the round-off of
    /// the faces' (with `k h/E` = 1e17 the factorisation of the default
    /// scene found a negative pivot; up to 1e12 the solve runs, and says
    /// when its contact iteration does not settle).
    fn penalty(&self, field: &str, k: f64) -> Check {
        positive_quantity(field, k)?;
        let (h, e) = (self.element_size(), self.material.young);
        let ratio = k * h / e;
        let reason = format!(
            "k h/E = {ratio:.3e} (h = {h:.4e} m, E = {e:.4e} Pa) is beyond 1/ε = {:.1e}: \
             the rock's stiffness would be lost in the round-off of the joint's",
            1.0 / f64::EPSILON
        );
        ensure(ratio * f64::EPSILON < 1.0, field, k, reason)
    }

    /// A crack polyline: at least 2 finite points inside the specimen, a
    /// length, no zero-length segment, and not all of it along the boundary
    /// (it would cut nothing). `point_field(k)` names point `k`.
    fn validate_polyline(
        &self,
        field: &str,
        points: &[[f64; 2]],
        point_field: impl Fn(usize) -> String,
    ) -> Check {
        let count = format!("{} point(s)", points.len());
        ensure(
            points.len() >= 2,
            field,
            count,
            "a crack needs at least 2 points",
        )?;
        for (k, &p) in points.iter().enumerate() {
            self.inside(&point_field(k), p)?;
        }
        let tiny = 1e-12 * self.specimen.width.max(self.specimen.height);
        let length: f64 = points.windows(2).map(|s| distance(s[0], s[1])).sum();
        ensure(length > tiny, field, length, "the crack has zero length")?;
        for k in 1..points.len() {
            let reason = "repeats the previous point (zero-length segment)";
            let long = distance(points[k - 1], points[k]) > tiny;
            ensure(long, &point_field(k), points[k], reason)?;
        }
        let along = points.windows(2).all(|s| self.along_a_side(s[0], s[1]));
        let reason = "lies along the specimen's boundary: it cuts nothing";
        ensure(!along, field, points[0], reason)
    }

    /// A drawn crack's ends at least [`MIN_CRACK_SPAN`] element sizes
    /// apart.
    fn resolved_span(&self, field: &str, points: &[[f64; 2]]) -> Check {
        let h = self.element_size();
        let span = distance(points[0], points[points.len() - 1]);
        let reason = format!(
            "its ends are less than {MIN_CRACK_SPAN} element sizes (h = {} m) apart: \
             the mesh cannot resolve its stress intensity factors (a tip's \
             interaction-integral domain, at least 1.5 h, must end an element short \
             of the other end; at 2 h K was off by 40%); refine the mesh or draw \
             the crack longer",
            Num(h)
        );
        ensure(
            span >= MIN_CRACK_SPAN * h,
            field,
            format!("{} m", Num(span)),
            reason,
        )
    }

    /// Whether the segment `a`–`b` runs along one side of the specimen
    /// (both ends on it, within 1e-9 of the specimen size).
    fn along_a_side(&self, a: [f64; 2], b: [f64; 2]) -> bool {
        let (w, h) = (self.specimen.width, self.specimen.height);
        let tol = 1e-9 * w.max(h);
        let on = |v: f64, side: f64| (v - side).abs() <= tol;
        (on(a[0], 0.0) && on(b[0], 0.0))
            || (on(a[0], w) && on(b[0], w))
            || (on(a[1], 0.0) && on(b[1], 0.0))
            || (on(a[1], h) && on(b[1], h))
    }

    fn validate_arc(&self, field: &str, arc: &ArcSpec, crack: &CrackSpec) -> Check {
        finite_point(&format!("{field}.center"), arc.center)?;
        positive_quantity(&format!("{field}.radius"), arc.radius)?;
        finite(&format!("{field}.start_deg"), arc.start_deg)?;
        let end = format!("{field}.end_deg");
        let sweep = (finite(&end, arc.end_deg)? - arc.start_deg).abs();
        let reason = "equals start_deg: the arc has zero length";
        ensure(sweep > 0.0, &end, arc.end_deg, reason)?;
        let reason = "the arc sweeps 360° or more (a closed crack cuts a piece free)";
        ensure(sweep < 360.0, &end, arc.end_deg, reason)?;
        let polyline = crack.polyline(self.element_size());
        self.validate_polyline(field, &polyline, |_| field.to_owned())?;
        self.resolved_span(field, &polyline)
    }

    fn validate_boundary(&self) -> Check {
        let b = &self.boundary;
        let sides = [
            ("bottom", b.bottom),
            ("left", b.left),
            ("top", b.top),
            ("right", b.right),
        ];
        for (side, bc) in sides {
            if let SideBc::Traction { normal, shear } = bc {
                for (name, t) in [("normal", normal), ("shear", shear)] {
                    self.small_strain(&format!("boundary.{side}.{name}"), t)?;
                }
            }
        }
        for (k, point) in b.points.iter().enumerate() {
            self.inside(&format!("boundary.points[{k}].at"), point.at)?;
        }
        Ok(())
    }

    fn validate_settings(&self) -> Check {
        self.criterion.settings()?;
        if let Some(r0) = self.criterion.r0 {
            positive_quantity("criterion.r0", r0)?;
        }
        let m = &self.material;
        if self.criterion.r0.is_none() && m.tensile_strength.is_none() {
            let reason = "gives no tensile strength 2c cos φ/(1 + sin φ) for the default \
                          criterion radius (K_IC/σ_t)²/2π: give material.cohesion > 0, \
                          material.tensile_strength or criterion.r0";
            ensure(m.cohesion > 0.0, "material.cohesion", m.cohesion, reason)?;
        }
        self.process_zone_fits()?;
        let g = &self.growth;
        if let Some(da) = g.increment {
            positive_quantity("growth.increment", da)?;
            let h = self.element_size();
            let reason = format!(
                "less than {MIN_END_SEGMENT} h (h = {} m, the element size): each step adds \
                 a segment this long at the tip, the tip takes its direction from it, and \
                 the mesh cannot resolve one this short (give at least {} m, or leave it \
                 out for the default max(r0, 3 h))",
                Num(h),
                Num(MIN_END_SEGMENT * h)
            );
            ensure(da >= MIN_END_SEGMENT * h, "growth.increment", da, reason)?;
        }
        at_least_one("growth.load_steps", g.load_steps)?;
        at_least_one("growth.max_steps", g.max_steps)?;
        at_least_one("growth.max_growth_per_step", g.max_growth_per_step)?;
        positive("growth.max_load_factor", g.max_load_factor)?;
        if let Some(r) = &g.resume {
            r.validate(self.cracks.len())?;
        }
        let s = &self.solver;
        open_interval("solver.tolerance", s.tolerance, 0.0, 1.0)?;
        at_least_one("solver.max_iterations", s.max_iterations)?;
        open_interval("solver.omega", s.omega, 0.0, 2.0)?;
        positive("solver.contact_tolerance", s.contact_tolerance)?;
        at_least_one("solver.max_contact_iterations", s.max_contact_iterations)?;
        // in-sweep updates are a rule of the automaton's cell visits
        let kind = format!("{:?}", s.kind).to_lowercase();
        ensure(
            s.contact_update.is_outer() || s.kind == SolverKind::Automaton,
            "solver.contact_update",
            s.contact_update.name(),
            format!("needs solver.kind \"automaton\" (it is \"{kind}\")"),
        )
    }

    /// The process zone `r_p = (K_IC/σ_t)²/2π` of the rock's tensile
    /// strength σ_t (the default criterion radius, half a tension start's
    /// length in the intact rock) and a given `criterion.r0`, each within
    /// the specimen's shorter side. A rock of 1 Pa cohesion has an r_p of
    /// 3e11 m: its site stencil once asked for 1.6e16 bytes and aborted
    /// the run (issue 62). σ_t is `material.tensile_strength` when given,
    /// else the tension cut-off of c and φ (`material.cohesion` named; a
    /// rock without cohesion starts no crack and has no cut-off).
    fn process_zone_fits(&self) -> Check {
        let m = &self.material;
        let side = self.specimen.width.min(self.specimen.height);
        let too_large = |what: &str, r: f64| {
            format!(
                "gives {what} {r:.3e} m, larger than the specimen's shorter side {} m: no \
                 crack of this rock is resolved in this specimen (raise the strength, or \
                 give criterion.r0 and material.tensile_strength)",
                Num(side)
            )
        };
        if let Some(r0) = self.criterion.r0 {
            let reason = too_large("a criterion radius r0 =", r0);
            ensure(r0 <= side, "criterion.r0", r0, reason)?;
        }
        let (field, value) = match m.tensile_strength {
            Some(st) => ("material.tensile_strength", st),
            None if m.cohesion > 0.0 => ("material.cohesion", m.cohesion),
            None => return Ok(()),
        };
        let sigma_t = m.tensile();
        let r_p = m.process_zone(sigma_t);
        let what = format!("σ_t = {sigma_t:.3e} Pa and a process zone r_p = (K_IC/σ_t)²/2π =");
        ensure(
            r_p.is_finite() && r_p <= side,
            field,
            value,
            too_large(&what, r_p),
        )
    }

    /// A traction `t` (Pa) below Young's modulus in magnitude: `|t|/E` is
    /// the strain it causes, and small-strain elasticity ends well before
    /// 100% (a traction of 1e300 Pa overflowed the residual's norm).
    fn small_strain(&self, field: &str, t: f64) -> Check {
        physical(field, t)?;
        let e = self.material.young;
        let reason = format!(
            "is not below Young's modulus E = {e:e} Pa in magnitude: strains of \
             |t|/E = {:.3e} are outside small-strain elasticity",
            t.abs() / e
        );
        ensure(t.abs() < e, field, t, reason)
    }

    /// `p` is finite and inside the closed specimen rectangle (tolerance
    /// 1e-9 of the specimen size).
    fn inside(&self, field: &str, p: [f64; 2]) -> Check {
        finite_point(field, p)?;
        let (w, h) = (self.specimen.width, self.specimen.height);
        let reason = format!("outside the specimen [0, {w}] × [0, {h}]");
        ensure(self.contains(p), field, p, reason)
    }

    /// Whether `p` lies in the closed specimen rectangle, within 1e-9 of
    /// the specimen size: the test a crack's or a support's point passes.
    pub fn contains(&self, p: [f64; 2]) -> bool {
        let (w, h) = (self.specimen.width, self.specimen.height);
        let tol = 1e-9 * w.max(h);
        (-tol..=w + tol).contains(&p[0]) && (-tol..=h + tol).contains(&p[1])
    }
}

fn validate_material(m: &Material) -> Check {
    positive_quantity("material.young", m.young)?;
    let nu = finite("material.poisson", m.poisson)?;
    let reason = "must be below 0.5 (0.5 is incompressible: the stiffness is singular)";
    ensure(nu < 0.5, "material.poisson", nu, reason)?;
    // ν = −1 itself is excluded too: the shear modulus E/(2(1+ν)) is infinite.
    ensure(nu > -1.0, "material.poisson", nu, "must be greater than -1")?;
    non_negative_quantity("material.cohesion", m.cohesion)?;
    let field = "material.friction_angle_deg";
    let phi = finite(field, m.friction_angle_deg)?;
    ensure(
        (0.0..90.0).contains(&phi),
        field,
        phi,
        "must be in [0, 90) degrees",
    )?;
    positive_quantity("material.k_ic", m.k_ic)?;
    positive_quantity("material.k_iic", m.k_iic)?;
    if let Some(st) = m.tensile_strength {
        positive_quantity("material.tensile_strength", st)?;
    }
    Ok(())
}

/// `Ok` when `ok`, otherwise the error naming `field`, `value` and `reason`.
fn ensure(ok: bool, field: &str, value: impl Into<FieldValue>, reason: impl Into<String>) -> Check {
    if ok {
        Ok(())
    } else {
        Err(SceneError::invalid(field, value, reason))
    }
}

fn finite(field: &str, v: f64) -> Result<f64, SceneError> {
    ensure(v.is_finite(), field, v, "must be a finite number").map(|()| v)
}

fn finite_point(field: &str, p: [f64; 2]) -> Check {
    let ok = p.iter().all(|c| c.is_finite());
    ensure(ok, field, p, "must be finite numbers")
}

fn positive(field: &str, v: f64) -> Check {
    ensure(finite(field, v)? > 0.0, field, v, "must be positive")
}

/// A physical value (SI units): finite, and zero or within
/// [`MIN_MAGNITUDE`, `MAX_MAGNITUDE`] in magnitude.
fn physical(field: &str, v: f64) -> Check {
    let m = finite(field, v)?.abs();
    let ok = m == 0.0 || (MIN_MAGNITUDE..=MAX_MAGNITUDE).contains(&m);
    let reason = format!(
        "is outside {} to {} in magnitude (SI units), where the solver's \
         arithmetic would overflow or underflow",
        Num(MIN_MAGNITUDE),
        Num(MAX_MAGNITUDE)
    );
    ensure(ok, field, v, reason)
}

/// A positive [`physical`] value.
fn positive_quantity(field: &str, v: f64) -> Check {
    positive(field, v)?;
    physical(field, v)
}

/// A non-negative [`physical`] value.
fn non_negative_quantity(field: &str, v: f64) -> Check {
    non_negative(field, v)?;
    physical(field, v)
}

fn non_negative(field: &str, v: f64) -> Check {
    ensure(finite(field, v)? >= 0.0, field, v, "must not be negative")
}

fn open_interval(field: &str, v: f64, low: f64, high: f64) -> Check {
    let ok = finite(field, v)? > low && v < high;
    ensure(ok, field, v, format!("must be in ({low}, {high})"))
}

fn at_least_one(field: &str, n: usize) -> Check {
    ensure(n >= 1, field, n, "must be at least 1")
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

/// A point as the scene errors show it (`[x, y]`, see [`FieldValue`]).
pub(crate) fn fmt_point(p: [f64; 2]) -> String {
    FieldValue::Point(p).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Fix, Plane, PointSupport, Scene, SideBc::Traction};

    /// The SPEC §10 example with every optional field set and an arc crack.
    const FULL: &str = r#"{
      "name": "inclined crack, biaxial compression",
      "description": "every field given",
      "specimen": { "width": 0.3, "height": 0.3, "thickness": 1.0 },
      "mesh": { "nx": 30, "ny": 30, "enrichment_radius": 2.5 },
      "material": { "young": 4.78e9, "poisson": 0.25, "plane": "stress", "cohesion": 15e6,
        "friction_angle_deg": 49.0, "k_ic": 1.03e6, "k_iic": 2.52e6, "tensile_strength": 5e6 },
      "cracks": [
        { "points": [[0.1, 0.1], [0.2, 0.2]], "friction": 0.5, "cohesion": 0.0,
          "normal_stiffness": 200e9, "shear_stiffness": 20e9 },
        { "arc": { "center": [0.2, 0.22], "radius": 0.04, "start_deg": 0.0, "end_deg": 90.0 } }
      ],
      "boundary": {
        "bottom": { "kind": "roller" }, "left": { "kind": "roller" },
        "top": { "kind": "traction", "normal": -10e6, "shear": 0.0 },
        "right": { "kind": "traction", "normal": -2e6, "shear": 1e5 },
        "points": [{ "at": [0.3, 0.3], "fix": "x" }]
      },
      "criterion": { "kind": "comprehensive", "r0": 0.03, "sampling": "williams",
        "shear_strength": "rock" },
      "growth": { "increment": 0.01, "load_steps": 5, "max_growth_per_step": 3, "max_steps": 50 },
      "solver": { "kind": "cg", "tolerance": 1e-10, "max_iterations": 1000, "omega": 1.2,
        "ordering": "red_black", "contact_tolerance": 1e-8, "max_contact_iterations": 50 }
    }"#;

    fn full() -> SceneFile {
        Scene::from_json(FULL)
            .expect("the full example scene is valid")
            .into_file()
    }

    fn field_of(scene: &SceneFile) -> Option<String> {
        match scene.validate() {
            Err(SceneError::Invalid { field, .. }) => Some(field),
            Err(e @ (SceneError::Parse(_) | SceneError::Write(_))) => {
                panic!("validate returned a parse or write error: {e}")
            }
            Ok(()) => None,
        }
    }

    type Case = (&'static str, fn(&mut SceneFile));

    /// Every invalid case of SPEC §10 and the brief, with the field it names.
    #[rustfmt::skip]
    const CASES: &[Case] = &[
        ("specimen.width", |s| s.specimen.width = 0.0),
        ("specimen.width", |s| s.specimen.width = -0.3),
        ("specimen.width", |s| s.specimen.width = f64::NAN),
        ("specimen.height", |s| s.specimen.height = 0.0),
        ("specimen.height", |s| s.specimen.height = f64::INFINITY),
        ("specimen.thickness", |s| s.specimen.thickness = -1.0),
        ("mesh.nx", |s| s.mesh.nx = 0),
        ("mesh.ny", |s| s.mesh.ny = 0),
        ("mesh", |s| (s.mesh.nx, s.mesh.ny) = (2001, 2000)),
        ("mesh", |s| (s.mesh.nx, s.mesh.ny) = (usize::MAX, 2)),
        ("mesh.enrichment_radius", |s| s.mesh.enrichment_radius = Some(0.5)),
        ("mesh.enrichment_radius", |s| s.mesh.enrichment_radius = Some(f64::NAN)),
        ("material.young", |s| s.material.young = 0.0),
        ("material.young", |s| s.material.young = -1e9),
        ("material.young", |s| s.material.young = f64::INFINITY),
        ("material.poisson", |s| s.material.poisson = 0.5),
        ("material.poisson", |s| s.material.poisson = 0.7),
        ("material.poisson", |s| s.material.poisson = -1.5),
        ("material.poisson", |s| s.material.poisson = -1.0),
        ("material.poisson", |s| s.material.poisson = f64::NAN),
        ("material.poisson", |s| (s.material.plane, s.material.poisson) = (Plane::Strain, 0.5)),
        ("material.cohesion", |s| s.material.cohesion = -1.0),
        ("material.cohesion", |s| {
            (s.material.cohesion, s.material.tensile_strength, s.criterion.r0) = (0.0, None, None);
        }),
        ("material.friction_angle_deg", |s| s.material.friction_angle_deg = -1.0),
        ("material.friction_angle_deg", |s| s.material.friction_angle_deg = 90.0),
        ("material.friction_angle_deg", |s| s.material.friction_angle_deg = f64::NAN),
        ("material.k_ic", |s| s.material.k_ic = 0.0),
        ("material.k_iic", |s| s.material.k_iic = -1.0),
        ("material.tensile_strength", |s| s.material.tensile_strength = Some(0.0)),
        ("material.tensile_strength", |s| s.material.tensile_strength = Some(f64::NAN)),
        ("cracks[0]", |s| s.cracks[0].points = None),
        ("cracks[1]", |s| s.cracks[1].points = Some(vec![[0.1, 0.1], [0.2, 0.1]])),
        ("cracks[0].points", |s| s.cracks[0].points = Some(vec![[0.1, 0.1]])),
        ("cracks[0].points", |s| s.cracks[0].points = Some(vec![])),
        ("cracks[0].points", |s| s.cracks[0].points = Some(vec![[0.1, 0.1]; 3])),
        ("cracks[0].points", |s| s.cracks[0].points = Some(vec![[0.0, 0.0], [0.3, 1e-12]])),
        ("cracks[0].points", |s| s.cracks[0].points = Some(vec![[0.3, 0.1], [0.3, 0.3], [0.2, 0.3]])),
        ("cracks[0].points[2]", |s| s.cracks[0].points = Some(vec![[0.1, 0.1], [0.2, 0.2], [0.2, 0.2]])),
        ("cracks[0].points[1]", |s| s.cracks[0].points = Some(vec![[0.1, 0.1], [0.31, 0.2]])),
        ("cracks[0].points[0]", |s| s.cracks[0].points = Some(vec![[0.1, -0.01], [0.2, 0.2]])),
        ("cracks[0].points[0]", |s| s.cracks[0].points = Some(vec![[f64::NAN, 0.1], [0.2, 0.2]])),
        ("cracks[1].arc.radius", |s| arc(s).radius = 0.0),
        ("cracks[1].arc.radius", |s| arc(s).radius = -0.1),
        ("cracks[1].arc.center", |s| arc(s).center[1] = f64::NAN),
        ("cracks[1].arc.start_deg", |s| arc(s).start_deg = f64::INFINITY),
        ("cracks[1].arc.end_deg", |s| arc(s).end_deg = 0.0),
        ("cracks[1].arc.end_deg", |s| arc(s).end_deg = 360.0),
        ("cracks[1].arc", |s| arc(s).radius = 0.09),
        ("cracks[1].arc", |s| arc(s).radius = 0.01),
        ("cracks[0].points", |s| s.cracks[0].points = Some(vec![[0.1, 0.1], [0.12, 0.11]])),
        ("cracks[0].friction", |s| s.cracks[0].friction = -0.1),
        ("cracks[0].friction", |s| s.cracks[0].friction = f64::NAN),
        ("cracks[1].cohesion", |s| s.cracks[1].cohesion = -1.0),
        ("cracks[0].normal_stiffness", |s| s.cracks[0].normal_stiffness = Some(0.0)),
        ("cracks[0].normal_stiffness", |s| s.cracks[0].normal_stiffness = Some(-2e11)),
        ("cracks[0].shear_stiffness", |s| s.cracks[0].shear_stiffness = Some(0.0)),
        ("cracks[0].shear_stiffness", |s| s.cracks[0].shear_stiffness = Some(f64::INFINITY)),
        ("boundary.top.normal", |s| s.boundary.top = Traction { normal: f64::NAN, shear: 0.0 }),
        ("boundary.right.shear", |s| s.boundary.right = Traction { normal: 0.0, shear: -f64::INFINITY }),
        ("boundary.points[0].at", |s| s.boundary.points[0].at = [0.31, 0.1]),
        ("boundary.points[0].at", |s| s.boundary.points[0].at = [0.1, f64::NAN]),
        ("criterion.r0", |s| s.criterion.r0 = Some(0.0)),
        ("criterion.r0", |s| s.criterion.r0 = Some(f64::INFINITY)),
        ("growth.increment", |s| s.growth.increment = Some(-0.01)),
        ("growth.load_steps", |s| s.growth.load_steps = 0),
        ("growth.max_steps", |s| s.growth.max_steps = 0),
        ("growth.max_growth_per_step", |s| s.growth.max_growth_per_step = 0),
        ("growth.max_load_factor", |s| s.growth.max_load_factor = 0.0),
        ("growth.max_load_factor", |s| s.growth.max_load_factor = f64::NAN),
        ("solver.tolerance", |s| s.solver.tolerance = 0.0),
        ("solver.tolerance", |s| s.solver.tolerance = 1.0),
        ("solver.tolerance", |s| s.solver.tolerance = f64::NAN),
        ("solver.max_iterations", |s| s.solver.max_iterations = 0),
        ("solver.omega", |s| s.solver.omega = 0.0),
        ("solver.omega", |s| s.solver.omega = 2.0),
        ("solver.contact_tolerance", |s| s.solver.contact_tolerance = 0.0),
        ("solver.max_contact_iterations", |s| s.solver.max_contact_iterations = 0),
        ("material.young", |s| s.material.young = 1e-300),
        ("material.young", |s| s.material.young = 1.7e308),
        ("material.cohesion", |s| s.material.cohesion = 1e300),
        ("material.k_ic", |s| s.material.k_ic = 1e-300),
        ("material.k_iic", |s| s.material.k_iic = 1e31),
        ("material.tensile_strength", |s| s.material.tensile_strength = Some(1e300)),
        ("specimen.thickness", |s| s.specimen.thickness = 1e300),
        ("specimen.width", |s| s.specimen.width = 1e-31),
        ("cracks[0].friction", |s| s.cracks[0].friction = 1e300),
        ("cracks[1].cohesion", |s| s.cracks[1].cohesion = 1e-300),
        ("cracks[0].normal_stiffness", |s| s.cracks[0].normal_stiffness = Some(1e30)),
        ("cracks[0].shear_stiffness", |s| s.cracks[0].shear_stiffness = Some(1e28)),
        ("cracks[1].arc.radius", |s| arc(s).radius = 1e-31),
        ("boundary.top.normal", |s| s.boundary.top = Traction { normal: -1e300, shear: 0.0 }),
        ("boundary.top.normal", |s| s.boundary.top = Traction { normal: -4.78e9, shear: 0.0 }),
        ("boundary.right.shear", |s| s.boundary.right = Traction { normal: 0.0, shear: 5e9 }),
        ("criterion.r0", |s| s.criterion.r0 = Some(1e-31)),
        ("growth.increment", |s| s.growth.increment = Some(1e31)),
        // process zones larger than the 0.3 m specimen (issue 62)
        ("material.cohesion", |s| (s.material.cohesion, s.material.tensile_strength) = (1.0, None)),
        ("material.cohesion", |s| (s.material.cohesion, s.material.tensile_strength) = (1e-12, None)),
        ("material.tensile_strength", |s| s.material.tensile_strength = Some(1e3)),
        ("criterion.r0", |s| (s.criterion.r0, s.material.tensile_strength) = (Some(0.31), None)),
        ("material.cohesion", |s| (s.criterion.r0, s.material.tensile_strength, s.material.cohesion) = (Some(0.01), None, 1.0)),
        ("criterion.r0", |s| s.criterion.r0 = Some(0.5)),
        ("boundary", |s| (s.boundary.left, s.boundary.points) = (SideBc::Free, vec![])),
        ("boundary", |s| (s.boundary.left, s.boundary.bottom) = (SideBc::Free, SideBc::Free)),
    ];

    fn arc(scene: &mut SceneFile) -> &mut crate::scene::ArcSpec {
        scene.cracks[1].arc.as_mut().expect("cracks[1] is an arc")
    }

    #[test]
    fn every_invalid_case_names_its_field() {
        assert_eq!(field_of(&full()), None);
        for (k, (field, break_it)) in CASES.iter().enumerate() {
            let mut scene = full();
            break_it(&mut scene);
            assert_eq!(field_of(&scene).as_deref(), Some(*field), "case {k}");
        }
    }

    #[test]
    fn the_message_names_field_and_value() {
        let mut scene = full();
        scene.material.poisson = 0.5;
        let message = scene.validate().expect_err("ν = 0.5").to_string();
        assert!(message.contains("`material.poisson` = 0.5"), "{message}");
    }

    #[test]
    fn edges_of_the_valid_ranges_are_accepted() {
        let mut scene = full();
        scene.material.poisson = -0.999;
        scene.material.friction_angle_deg = 0.0;
        scene.material.cohesion = 0.0;
        scene.mesh.enrichment_radius = Some(1.0);
        // The ends of the physical range, a traction just below E, and a
        // joint stiffness just below k h/E = 1/ε (h = 0.3 mm, E = 1e30 Pa:
        // k < 4.5e15 × 1e30 / 1.5e-4).
        scene.material.young = 1e30;
        scene.material.k_iic = 1e-30;
        scene.cracks[0].friction = 1e30;
        scene.boundary.top = Traction {
            normal: -0.999e30,
            shear: 0.0,
        };
        scene.cracks[0].normal_stiffness = Some(1e30);
        scene.cracks[0].shear_stiffness = None;
        (scene.mesh.nx, scene.mesh.ny) = (2000, 2000);
        // A crack that starts on the boundary, within the tolerance.
        scene.cracks[0].points = Some(vec![[0.0, -1e-12], [0.2, 0.1]]);
        assert_eq!(field_of(&scene), None);
    }

    #[test]
    fn a_full_scene_round_trips_through_json() {
        let scene = full();
        let text = scene.to_json().expect("a valid scene writes");
        let again = Scene::from_json(&text).expect("to_json output parses");
        assert_eq!(*again, scene);
        assert_eq!(again.to_json().expect("writes"), text);
    }

    #[test]
    fn unknown_fields_are_rejected_at_every_level() {
        let top = FULL.replacen("\"material\"", "\"materail\"", 1);
        let nested = FULL.replacen("\"young\"", "\"yong\"", 1);
        for (text, name) in [(top, "materail"), (nested, "yong")] {
            match Scene::from_json(&text) {
                Err(SceneError::Parse(m)) => assert!(m.contains(&format!("`{name}`")), "{m}"),
                other => panic!("`{name}` accepted: {other:?}"),
            }
        }
    }

    #[test]
    fn traction_on_four_sides_needs_two_point_supports() {
        let mut scene = full();
        let b = &mut scene.boundary;
        (b.bottom, b.left) = (b.top, b.right);
        b.points = vec![PointSupport {
            at: [0.0, 0.15],
            fix: Fix::Xy,
        }];
        let err = scene
            .validate()
            .expect_err("rotation about the point is free");
        assert!(
            err.to_string().contains("rotation about [0, 0.15]"),
            "{err}"
        );
        // A `y` support at the same x leaves the rotation free too.
        scene.boundary.points.push(PointSupport {
            at: [0.0, 0.3],
            fix: Fix::Y,
        });
        assert_eq!(field_of(&scene).as_deref(), Some("boundary"));
        scene.boundary.points[1].at = [0.3, 0.15];
        assert_eq!(field_of(&scene), None);
    }
}
