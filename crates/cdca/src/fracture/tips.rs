//! Evaluation of every free tip after a solve: SIFs by the interaction
//! integral (with the contact tractions) and the criterion's decision.

use crate::contact::law::{ContactState, FaceState, face_tractions};
use crate::discretisation::field::Field;
use crate::discretisation::material::Elastic;
use crate::discretisation::xfem::{FacePoint, Xfem, XfemParams};
use crate::fracture::criterion::{
    Circle, CriterionParams, Faces, assess, sample_field, sample_hybrid, sample_williams,
    uniform_stress,
};
use crate::fracture::sif::{Domain, Sifs};
use crate::geometry::cracks::{Crack, TipFrame, system_lengths};
use crate::geometry::mesh::Mesh;
use crate::geometry::plane::P2;
use crate::report::TipReport;
use crate::scene::Sampling;

/// Radius of the interaction-integral domain, in element sizes.
pub const DOMAIN_RADIUS: f64 = 3.0;

/// K_I, K_II and T of every free tip (in the order crack, tip) with the
/// interaction-integral domain of [`domain_radius`] and the crack-face
/// `tractions` (one per face piece of `x`, or empty).
pub fn all_tip_sifs(x: &Xfem, u: &[f64], tractions: &[P2]) -> Vec<(usize, usize, TipFrame, Sifs)> {
    TipDomains::new(x).sifs(x, u, tractions)
}

/// The interaction-integral domains of every free tip of one
/// discretisation ([`Domain`]: what the integrals need besides the
/// displacement, about four fifths of their cost), made once and read
/// after every solve on it. It remembers what they depend on (cracks,
/// mesh, enrichment, material), so a caller that keeps one asks
/// [`fits`](Self::fits) before reading it with another discretisation.
#[derive(Clone, Debug)]
pub struct TipDomains {
    /// Per free tip, in the order crack, tip: crack, tip, frame, domain.
    tips: Vec<(usize, usize, TipFrame, Domain)>,
    cracks: Vec<Crack>,
    mesh: Mesh,
    params: XfemParams,
    elastic: Elastic,
    thickness: f64,
    free_dofs: usize,
}

impl TipDomains {
    /// The domains of [`domain_radius`] of `x`'s free tips.
    pub fn new(x: &Xfem) -> Self {
        let mut domains = Self::start(x);
        while domains.make_next(x) {}
        domains
    }

    /// None of `x`'s domains made yet: [`make_next`](Self::make_next)
    /// makes them one at a time (so that the workbench can spread them
    /// over frames).
    pub fn start(x: &Xfem) -> Self {
        Self {
            tips: Vec::new(),
            cracks: x.funcs.cracks.clone(),
            mesh: x.mesh.clone(),
            params: x.params,
            elastic: x.elastic.clone(),
            thickness: x.thickness,
            free_dofs: x.n_free(),
        }
    }

    /// The domains kept in `kept` when they fit `x`, or else a start on `x`
    /// put there in their place.
    pub fn kept_for<'a>(kept: &'a mut Option<Self>, x: &Xfem) -> &'a mut Self {
        if !kept.as_ref().is_some_and(|d| d.fits(x)) {
            *kept = None;
        }
        kept.get_or_insert_with(|| Self::start(x))
    }

    /// Makes the next free tip's domain on `x` (which these
    /// [`fit`](Self::fits)); `false` when every one was made already.
    pub fn make_next(&mut self, x: &Xfem) -> bool {
        let h = x.mesh.h();
        let next = free_tips(x).nth(self.tips.len());
        let Some((c, k)) = next else {
            return false;
        };
        let crack = &x.funcs.cracks[c];
        let frame = TipFrame::of(crack, k);
        let r_j = domain_radius(crack, k, h);
        self.tips.push((c, k, frame, Domain::new(x, c, frame, r_j)));
        true
    }

    /// Of `x`'s free tips, how many have their domain made in `kept` (none
    /// when it does not [`fit`](Self::fits) `x`), and how many there are.
    pub fn progress(kept: Option<&Self>, x: &Xfem) -> (usize, usize) {
        let made = kept.filter(|d| d.fits(x)).map_or(0, |d| d.tips.len());
        (made, free_tips(x).count())
    }

    /// Whether these are the domains of `x` (made on a discretisation of
    /// the same cracks, mesh, enrichment and material).
    pub fn fits(&self, x: &Xfem) -> bool {
        self.free_dofs == x.n_free()
            && self.thickness == x.thickness
            && self.params == x.params
            && self.elastic == x.elastic
            && self.cracks == x.funcs.cracks
            && self.mesh == x.mesh
    }

    /// K_I, K_II and T of every free tip of `x` (which these domains
    /// [`fit`](Self::fits)) at `u`, as [`all_tip_sifs`].
    pub fn sifs(
        &self,
        x: &Xfem,
        u: &[f64],
        tractions: &[P2],
    ) -> Vec<(usize, usize, TipFrame, Sifs)> {
        debug_assert!(self.fits(x), "tip domains of another discretisation");
        let field = Field { xfem: x, u };
        self.tips
            .iter()
            .map(|(c, k, frame, d)| (*c, *k, *frame, d.sifs(&field, tractions)))
            .collect()
    }
}

/// The free tips of `x` (crack, tip), in the order their domains are made.
fn free_tips(x: &Xfem) -> impl Iterator<Item = (usize, usize)> + '_ {
    x.funcs
        .cracks
        .iter()
        .enumerate()
        .flat_map(|(c, crack)| crack.free_tips().map(move |k| (c, k)))
}

/// Smallest turn of a crack's polyline at a vertex, in degrees, that ends
/// the straight stretch behind a tip ([`domain_radius`]). Below half a
/// degree the capped and the full domain read K alike (within 0.5%).
pub const MIN_TURN_DEG: f64 = 0.5;

/// Radius of tip `k`'s interaction-integral domain: [`DOMAIN_RADIUS`]
/// element sizes, or one element short of where the crack stops being
/// straight when that is nearer (at least one element): its other end, or
/// the nearest vertex at which it turns by more than [`MIN_TURN_DEG`]. The
/// auxiliary fields are a straight crack's along the tip's tangent,
/// discontinuous along the whole line behind the tip; a domain (with its
/// band of q gradient, one element wide) that reaches past the other end
/// integrates them where the true field is continuous, and one that
/// reaches past a kink integrates them off the true crack. A centre crack
/// two elements long read K_I 1.2–1.5 times the closed form with the fixed
/// domain; one reaching past a kink read K_II 1.7 times the converged
/// value on a wing one increment (3 h) past a 60° kink, and circular-arc
/// cracks 7–11% off the closed form (2.7–8.5% short of the turns).
pub fn domain_radius(crack: &Crack, k: usize, h: f64) -> f64 {
    let p = &crack.points;
    let n = p.len();
    // point i counted from the tip
    let at = |i: usize| if k == 0 { p[i] } else { p[n - 1 - i] };
    let straight = (1..n - 1)
        .find(|&i| {
            let (before, after) = (at(i) - at(i - 1), at(i + 1) - at(i));
            let cos = before.dot(&after) / (before.norm() * after.norm());
            cos.clamp(-1.0, 1.0).acos() > MIN_TURN_DEG.to_radians()
        })
        .map_or(at(n - 1), at);
    (DOMAIN_RADIUS * h).min(((straight - at(0)).norm() - h).max(h))
}

/// Every free tip evaluated, in the order crack, tip.
#[derive(Clone, Debug, Default)]
pub struct Evaluation {
    pub tips: Vec<TipReport>,
    /// The sampled circles.
    pub circles: Vec<Circle>,
    /// The faces at each tip, as the criterion saw them.
    pub faces: Vec<Faces>,
    /// Each tip's utilisation (see [`assess`]): ≥ 1 exactly when it grows.
    pub utilisation: Vec<f64>,
}

/// Tip reports, the sampled circles and the utilisations, in the order
/// crack, tip; `domains`: `x`'s ([`TipDomains::new`], or one kept that
/// [`fits`](TipDomains::fits) it).
pub fn evaluate_tips(
    x: &Xfem,
    domains: &TipDomains,
    u: &[f64],
    states: &[FaceState],
    params: &CriterionParams,
    sampling: Option<Sampling>,
) -> Evaluation {
    let field = Field { xfem: x, u };
    let tractions = face_tractions(x, states);
    let mut out = Evaluation::default();
    let lengths = system_lengths(&x.funcs.cracks);
    for (c, k, frame, s) in domains.sifs(x, u, &tractions) {
        let crack = &x.funcs.cracks[c];
        let params = &params.for_crack(lengths[c]);
        let faces = Faces {
            friction: crack.friction,
            cohesion: crack.cohesion,
            closed: closed_near_tip(x, states, c, &frame),
        };
        // no circle for a criterion that reads none (MTS)
        let circle = match sampling {
            None => Circle::default(),
            Some(Sampling::Field) => {
                sample_field(&frame, params.r0, &|p| field.stress_averaged_at(p))
            }
            Some(Sampling::Williams) => sample_williams(&s, params.r0),
            Some(Sampling::Hybrid) => sample_hybrid(
                &s,
                uniform_stress(&s, face_stress(x, &tractions, c, &frame)),
                params.r0,
            ),
        };
        let (criterion, utilisation) = assess(params, &circle, &s, faces);
        out.tips.push(TipReport {
            crack: c,
            tip: k,
            x: frame.origin.x,
            y: frame.origin.y,
            k1: s.k1,
            k2: s.k2,
            t_stress: s.t,
            criterion,
        });
        out.circles.push(circle);
        out.faces.push(faces);
        out.utilisation.push(utilisation);
    }
    out
}

/// Stress `[σ12, σ22]` (tip frame) on the faces next to a tip: the mean,
/// weighted by length, over crack `c`'s face pieces whose midpoints lie
/// within two element sizes of the tip. Zero on open faces.
///
/// A piece's traction `p = p_N n + p_T t = k_N g_N n + k_T (g_T − g_T^s) t`
/// is the force per area on the `−` side (`p_N < 0` in compression), so
/// `σ·n = p`; with `e2 = ±n`, `σ22 = ±p·e2` and `σ12 = ±p·e1`.
fn face_stress(x: &Xfem, tractions: &[P2], c: usize, frame: &TipFrame) -> P2 {
    let (mut sum, mut w) = (P2::zeros(), 0.0);
    for (i, fp) in near_tip(x, c, frame) {
        let p = tractions[i];
        let side = if fp.n.dot(&frame.e2) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        sum += side * fp.w * P2::new(p.dot(&frame.e1), p.dot(&frame.e2));
        w += fp.w;
    }
    if w > 0.0 { sum / w } else { P2::zeros() }
}

/// Whether most of crack `c`'s face length within two element sizes of
/// the tip is in contact (stick or slip).
fn closed_near_tip(x: &Xfem, states: &[FaceState], c: usize, frame: &TipFrame) -> bool {
    let (mut closed, mut all) = (0.0, 0.0);
    for (i, fp) in near_tip(x, c, frame) {
        all += fp.w;
        if states.get(i).is_some_and(|s| s.state != ContactState::Open) {
            closed += fp.w;
        }
    }
    all > 0.0 && closed > 0.5 * all
}

/// Crack `c`'s face pieces (index, piece) whose midpoints lie within two
/// element sizes of the tip.
fn near_tip<'a>(
    x: &'a Xfem,
    c: usize,
    frame: &'a TipFrame,
) -> impl Iterator<Item = (usize, &'a FacePoint)> + 'a {
    let reach = 2.0 * x.mesh.h();
    x.faces
        .iter()
        .enumerate()
        .filter(move |(_, fp)| fp.crack == c && (fp.x - frame.origin).norm() <= reach)
}
