//! Evaluation of every free tip after a solve: SIFs by the interaction
//! integral (with the contact tractions) and the criterion's decision.

use crate::contact::FaceState;
use crate::cracks::TipFrame;
use crate::criterion::{Circle, CriterionParams, decide, sample_field, sample_williams};
use crate::field::Field;
use crate::geometry::P2;
use crate::report::TipReport;
use crate::scene::Sampling;
use crate::sif::{Sifs, tip_sifs};
use crate::xfem::Xfem;

/// Radius of the interaction-integral domain, in element sizes.
pub const DOMAIN_RADIUS: f64 = 3.0;

/// K_I, K_II and T of every free tip (in the order crack, tip) with the
/// interaction-integral domain of [`DOMAIN_RADIUS`] element sizes and the
/// crack-face `tractions` (one per face piece of `x`, or empty).
pub fn all_tip_sifs(x: &Xfem, u: &[f64], tractions: &[P2]) -> Vec<(usize, usize, TipFrame, Sifs)> {
    let field = Field { xfem: x, u };
    let r_j = DOMAIN_RADIUS * x.mesh.h();
    let mut out = Vec::new();
    for (c, crack) in x.funcs.cracks.iter().enumerate() {
        for k in crack.free_tips() {
            let frame = TipFrame::of(crack, k);
            out.push((c, k, frame, tip_sifs(&field, c, &frame, r_j, tractions)));
        }
    }
    out
}

/// Tip reports and the sampled circles, in the order crack, tip.
pub fn evaluate_tips(
    x: &Xfem,
    u: &[f64],
    states: &[FaceState],
    params: &CriterionParams,
    sampling: Sampling,
) -> (Vec<TipReport>, Vec<Circle>) {
    let field = Field { xfem: x, u };
    let tractions: Vec<P2> = x
        .faces
        .iter()
        .zip(states)
        .map(|(fp, s)| s.traction(fp))
        .collect();
    let mut reports = Vec::new();
    let mut circles = Vec::new();
    for (c, k, frame, s) in all_tip_sifs(x, u, &tractions) {
        let circle = match sampling {
            Sampling::Field => sample_field(&frame, params.r0, &|p| field.stress_averaged_at(p)),
            Sampling::Williams => sample_williams(&s, params.r0),
        };
        let criterion = decide(params, &circle, &s);
        reports.push(TipReport {
            crack: c,
            tip: k,
            x: frame.origin.x,
            y: frame.origin.y,
            k1: s.k1,
            k2: s.k2,
            t_stress: s.t,
            criterion,
        });
        circles.push(circle);
    }
    (reports, circles)
}
