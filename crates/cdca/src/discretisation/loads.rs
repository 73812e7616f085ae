//! Consistent nodal forces of the side tractions, enriched DOFs included.

use crate::discretisation::boundary::Side;
use crate::discretisation::dofs::FIXED;
use crate::discretisation::quadrature::segment_rule;
use crate::discretisation::xfem::{REGULAR, Xfem};
use crate::geometry::plane::segment_intersection;
use crate::scene::Boundary;

/// External force vector (free numbering) at load factor 1:
/// `f_a = t ∫_side ψ_a(x) · traction ds`.
pub fn traction_forces(x: &Xfem, b: &Boundary) -> Vec<f64> {
    let mut f = vec![0.0; x.n_free()];
    let (mut vals, mut grads, mut dofs) = (Vec::new(), Vec::new(), Vec::new());
    for side in Side::ALL {
        let Some(tr) = side.traction(b) else { continue };
        for (e, [c0, c1]) in side.edges(&x.mesh) {
            let poly = x.mesh.element_polygon(e);
            let (p0, p1) = (poly[c0], poly[c1]);
            let mut cuts = vec![0.0, 1.0];
            for crack in &x.funcs.cracks {
                for (a, bb) in crack.segments() {
                    if let Some((s, _)) = segment_intersection(p0, p1, a, bb) {
                        cuts.push(s);
                    }
                }
            }
            cuts.sort_by(f64::total_cmp);
            let order = if x.slot[e] == REGULAR { 2 } else { 6 };
            let mut q = Vec::new();
            for w in cuts.windows(2) {
                if w[1] - w[0] > 1e-12 {
                    segment_rule(p0 + w[0] * (p1 - p0), p0 + w[1] * (p1 - p0), order, &mut q);
                }
            }
            for p in q {
                x.eval_element(e, p.x, &mut vals, &mut grads, &mut dofs);
                for (s, &v) in vals.iter().enumerate() {
                    for c in 0..2 {
                        let d = dofs[2 * s + c];
                        if d != FIXED {
                            f[d as usize] += v * tr[c] * p.w * x.thickness;
                        }
                    }
                }
            }
        }
    }
    f
}
