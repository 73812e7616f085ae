//! Secondary-crack sites (SPEC §8): a crack's sharp kinks stay sites of the
//! same criterion. A flaw's end that a wing has left is such a kink (the
//! wing turns 45–85° off the flaw); so is any sharp turn a crack took.
//!
//! A kink is not a K-tip: there is no interaction integral to read. The
//! criterion is read from the computed stress field on a circle around the
//! vertex, of the process-zone radius `r_p` (the scene's r0, not the
//! short-crack radius of [`CriterionParams::for_crack`]): at `r_p` the
//! shear check at the coplanar pair's flaw ends agreed within 5% and its
//! plane within 8° on 100² to 300² meshes, where 0.3 and 0.6 mm circles
//! did not; the first secondary crack's load and angle agree within 7% and
//! 1.1° on 100² to 200² (`the_first_secondary_crack_is_mesh_converged`,
//! docs/fracture-model.md, *Secondary cracks*). It is sampled over the
//! kink's open (reflex) side, the arms' directions excluded by
//! [`ARM_MARGIN_DEG`]: the wedge between a flaw and its wing is shielded by
//! both, and a crack leaving along an arm would lie on it.

use std::f64::consts::PI;

use crate::contact::law::{ContactState, FaceState};
use crate::discretisation::field::Field;
use crate::discretisation::xfem::Xfem;
use crate::fracture::criterion::{Circle, CriterionParams, Faces, assess};
use crate::fracture::sif::Sifs;
use crate::geometry::cracks::{Crack, TipFrame, TipKind};
use crate::geometry::plane::{P2, cross};
use crate::report::KinkReport;
use crate::scene::CriterionKind;

/// Smallest turn of a polyline at a vertex, degrees, that makes the vertex
/// a secondary-crack site. Wings leave a flaw at 45–85° (held-out flaws
/// with the product defaults: 48–75°); a growing crack turns by less than
/// 30° from one increment to the next once it has left its flaw (the
/// measured turns are listed in docs/fracture-model.md). The turn of a
/// polyline is a property of the path, not of the mesh: with `Δa ≥ r_p`
/// the increments are mesh-independent once `3h ≤ r_p`.
pub const SHARP_TURN_DEG: f64 = 30.0;

/// Directions within this angle of an arm of the kink are not sampled,
/// degrees: the circle there lies on the crack's faces.
pub const ARM_MARGIN_DEG: f64 = 15.0;

/// Samples per degree of the kink's open side.
const SAMPLES_PER_DEG: f64 = 2.0;

/// A sharp vertex of a crack's polyline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kink {
    pub crack: usize,
    /// Index of the vertex in the crack's points.
    pub vertex: usize,
    pub point: P2,
    /// Unit vectors from the vertex along the two arms (to the points
    /// before and after it).
    pub arms: [P2; 2],
    /// Turn of the polyline at the vertex, degrees.
    pub turn_deg: f64,
}

impl Kink {
    /// Frame at the vertex: `e1` bisects the open (reflex) side, away from
    /// both arms.
    pub fn frame(&self) -> TipFrame {
        let e1 = -(self.arms[0] + self.arms[1]).normalize();
        TipFrame {
            origin: self.point,
            e1,
            e2: P2::new(-e1.y, e1.x),
        }
    }

    /// Half the open side's angle less the arms' margins, rad: the circle
    /// is sampled over `θ ∈ [−half, half]` in [`frame`](Self::frame).
    pub fn half_sector(&self) -> f64 {
        0.5 * (PI + self.turn_deg.to_radians()) - ARM_MARGIN_DEG.to_radians()
    }

    /// Angle of a direction off the straight continuation of the arm it is
    /// nearer to continuing, degrees (counter-clockwise +): 0 is a crack
    /// that carries the arm straight on past the vertex.
    pub fn off_arm_deg(&self, d: P2) -> f64 {
        self.arms
            .iter()
            .map(|&a| cross(-a, d).atan2(-a.dot(&d)).to_degrees())
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(0.0)
    }
}

/// Every sharp kink of the cracks ([`SHARP_TURN_DEG`]) from which no crack
/// has started yet: a vertex where another crack's junction tip lies
/// (within `tol`) has branched and is no longer a site.
pub fn sharp_kinks(cracks: &[Crack], tol: f64) -> Vec<Kink> {
    let starts: Vec<P2> = cracks
        .iter()
        .flat_map(|c| {
            (0..2)
                .filter(|&k| matches!(c.tips[k], TipKind::Junction { .. }))
                .map(|k| c.tip_point(k))
        })
        .collect();
    cracks
        .iter()
        .enumerate()
        .flat_map(|(c, crack)| sharp_vertices(c, crack))
        .filter(|k| starts.iter().all(|&s| (s - k.point).norm() > tol))
        .collect()
}

/// Every vertex of crack `c` (`crack`) at which it turns by at least
/// [`SHARP_TURN_DEG`], whether or not a crack has started there.
pub fn sharp_vertices(c: usize, crack: &Crack) -> impl Iterator<Item = Kink> + '_ {
    let p = &crack.points;
    (1..p.len().saturating_sub(1)).filter_map(move |i| {
        let (back, ahead) = ((p[i - 1] - p[i]).normalize(), (p[i + 1] - p[i]).normalize());
        // the turn: 0 for a straight polyline, 180° for one that folds back
        let turn = (PI - back.dot(&ahead).clamp(-1.0, 1.0).acos()).to_degrees();
        (turn >= SHARP_TURN_DEG).then_some(Kink {
            crack: c,
            vertex: i,
            point: p[i],
            arms: [back, ahead],
            turn_deg: turn,
        })
    })
}

/// σ_θθ and τ_rθ on the circle of radius `r` around the kink, over its
/// open side; points outside the body, and points nearer to one of the
/// free `tips` than to the vertex (another tip's singular field, such as
/// that of a wing still shorter than 2r), are skipped.
pub fn sample_kink(
    kink: &Kink,
    r: f64,
    tips: &[P2],
    stress: &dyn Fn(P2) -> Option<[f64; 3]>,
) -> Circle {
    let frame = kink.frame();
    let half = kink.half_sector();
    let n = (2.0 * half.to_degrees() * SAMPLES_PER_DEG).ceil().max(2.0) as usize;
    let mut c = Circle::default();
    for i in 0..=n {
        let th = -half + 2.0 * half * i as f64 / n as f64;
        let er = frame.global(P2::new(th.cos(), th.sin()));
        let et = frame.global(P2::new(-th.sin(), th.cos()));
        let x = frame.origin + r * er;
        if tips.iter().any(|&t| (x - t).norm() < r) {
            continue;
        }
        let Some(s) = stress(x) else {
            continue;
        };
        c.push(th, s, er, et);
    }
    c
}

/// Every kink of [`sharp_kinks`] evaluated by the comprehensive criterion
/// on the computed field ([`sample_kink`] at the scene's r0 with its σ_t,
/// clear of the free tips' fields),
/// with each kink's utilisation (≥ 1 exactly when a crack starts there).
/// The shear branch meets intact rock ([`Faces::at_kink`]), where a K-tip
/// extending its faces has their μ and c_c. With the faces' μ (0–0.6 on
/// the held-out flaws, against tan 49° = 1.15) secondary cracks started
/// below the first wing's load on 14 of the 48 flaws of the range, and
/// 1 of 8 held-out overlapping pairs linked; with tan φ, 2 of 48 and 7 of
/// 8 (docs/fracture-model.md, *Secondary cracks*). The faces count as
/// closed when most of the face length within r0 of the vertex, on either
/// arm, is in contact (within a fixed number of elements, the reach would
/// shrink with the mesh into the opened end of a flaw next to its wing:
/// on 200² the flaw ends read open where 100² read closed). Empty for the MTS criteria, which
/// read K at a tip and have nothing to read at a kink.
pub fn evaluate_kinks(
    x: &Xfem,
    u: &[f64],
    states: &[FaceState],
    params: &CriterionParams,
) -> (Vec<KinkReport>, Vec<f64>) {
    if params.kind != CriterionKind::Comprehensive {
        return (Vec::new(), Vec::new());
    }
    let field = Field { xfem: x, u };
    let h = x.mesh.h();
    let (mut reports, mut utilisation) = (Vec::new(), Vec::new());
    let tips: Vec<P2> = x
        .funcs
        .cracks
        .iter()
        .flat_map(|c| c.free_tips().map(|k| c.tip_point(k)))
        .collect();
    for kink in sharp_kinks(&x.funcs.cracks, 1e-6 * h) {
        let faces = Faces::at_kink(params, closed_arm(x, states, &kink, params.r0));
        let circle = sample_kink(&kink, params.r0, &tips, &|p| field.stress_averaged_at(p));
        let (criterion, u) = assess(params, &circle, &Sifs::default(), faces);
        let frame = kink.frame();
        let th = criterion.angle_deg.to_radians();
        let d = frame.global(P2::new(th.cos(), th.sin()));
        reports.push(KinkReport {
            crack: kink.crack,
            vertex: kink.vertex,
            x: kink.point.x,
            y: kink.point.y,
            turn_deg: kink.turn_deg,
            mode: criterion.mode,
            direction_deg: d.y.atan2(d.x).to_degrees(),
            off_arm_deg: kink.off_arm_deg(d),
            utilisation: u,
        });
        utilisation.push(u);
    }
    (reports, utilisation)
}

/// Whether most of the face length within `reach` of the kink, on either
/// of its arms, is in contact (stick or slip).
fn closed_arm(x: &Xfem, states: &[FaceState], kink: &Kink, reach: f64) -> bool {
    kink.arms.iter().any(|&arm| {
        let (mut closed, mut all) = (0.0, 0.0);
        for (i, fp) in x.faces.iter().enumerate() {
            let d = fp.x - kink.point;
            if fp.crack != kink.crack || d.norm() > reach || d.dot(&arm) <= 0.0 {
                continue;
            }
            all += fp.w;
            if states.get(i).is_some_and(|s| s.state != ContactState::Open) {
                closed += fp.w;
            }
        }
        all > 0.0 && closed > 0.5 * all
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flaw with a wing turned 60° at one end is a kink of 60°; a 20°
    /// bend is not; a vertex a crack has started from is no longer a site.
    /// The open side's bisector points away from both arms, and a
    /// direction straight on from the flaw reads 0° off its arm.
    #[test]
    fn sharp_vertices_are_sites_until_a_crack_starts_there() {
        let (c, s) = (60f64.to_radians().cos(), 60f64.to_radians().sin());
        // then a 20° bend: to 40° off the flaw
        let (c2, s2) = (40f64.to_radians().cos(), 40f64.to_radians().sin());
        let flaw = Crack::bare(
            &[[-1.0, 0.0], [0.0, 0.0], [c, s], [c + c2, s + s2]],
            [TipKind::Free; 2],
        );
        let kinks = sharp_kinks(std::slice::from_ref(&flaw), 1e-9);
        assert_eq!(kinks.len(), 1, "{kinks:?}");
        let k = kinks[0];
        assert_eq!(k.vertex, 1);
        assert!((k.turn_deg - 60.0).abs() < 1e-9, "{}", k.turn_deg);
        // bisector of the reflex side: opposite to the mean of the arms
        let e1 = k.frame().e1;
        assert!(e1.dot(&k.arms[0]) < 0.0 && e1.dot(&k.arms[1]) < 0.0);
        // reflex side 240°, less 2 × 15°: ±105°
        assert!((k.half_sector().to_degrees() - 105.0).abs() < 1e-9);
        assert!(k.off_arm_deg(P2::new(1.0, 0.0)).abs() < 1e-9);
        assert!((k.off_arm_deg(P2::new(1.0, -0.2)) + 0.2f64.atan().to_degrees()).abs() < 1e-9);
        let branch = Crack::bare(
            &[[0.0, 0.0], [0.5, -0.1]],
            [TipKind::Junction { main: 0 }, TipKind::Free],
        );
        assert!(sharp_kinks(&[flaw, branch], 1e-9).is_empty());
    }
}
