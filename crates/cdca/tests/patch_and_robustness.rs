//! Patch tests and robustness on awkward crack geometry (issue: solver core).

mod common;

use cdca::scene::{CrackSpec, Fix, PointSupport};
use common::*;

fn uniform_stress_error(s: cdca::Scene, sigma_yy: f64) -> f64 {
    let mut sim = cdca::Simulation::new(s).expect("valid");
    sim.solve().expect("solve");
    let mut worst: f64 = 0.0;
    for i in 0..=10 {
        for j in 0..=10 {
            let p = [0.013 + 0.097 * f64::from(i), 0.011 + 0.0975 * f64::from(j)];
            let st = sim.stress_at(p).expect("inside");
            let e = (st[0].abs() + (st[1] - sigma_yy).abs() + st[2].abs()) / sigma_yy.abs();
            worst = worst.max(e);
        }
    }
    worst
}

/// Patch test: an uncracked plate under uniform traction reproduces the
/// uniform stress σ_yy = σ, σ_xx = τ_xy = 0 to 1e-10 relative.
#[test]
fn patch_test_uncracked_plate() {
    let mut s = plate(1.0, 1.0, 7, 9);
    tension_top_bottom(&mut s, 3e6);
    assert!(uniform_stress_error(s, 3e6) < 1e-10);
}

/// A straight crack parallel to the load leaves the uniform field unchanged,
/// including inside cut and tip-enriched elements. The uniform field lies in
/// the enriched space, so the only error is the quadrature of the √r branch
/// functions: 1e-5 relative, with free tips off the grid lines.
#[test]
fn patch_test_crack_parallel_to_load() {
    let mut s = plate(1.0, 1.0, 10, 10);
    tension_top_bottom(&mut s, 3e6);
    s.cracks
        .push(CrackSpec::segment([0.437, 0.31], [0.437, 0.68]));
    let e = uniform_stress_error(s, 3e6);
    assert!(e < 1e-5, "relative error {e:.3e}");
}

/// Awkward geometries solve with finite values and, against the reference
/// K_I of the same crack placed generically, stay within 2%.
#[test]
fn awkward_crack_positions_stay_accurate() {
    // centre crack (a = 0.15, a/b = 0.3) on a 40 × 120 mesh (h = 0.025)
    let k_of = |crack: CrackSpec| {
        let mut s = plate(1.0, 3.0, 40, 120);
        tension_top_bottom(&mut s, 1e6);
        s.cracks.push(crack);
        let r = solve(s);
        assert!(
            r.tips
                .iter()
                .all(|t| t.k1.is_finite() && t.k2.is_finite() && t.t_stress.is_finite())
        );
        r.tips.iter().map(|t| t.k1).sum::<f64>() / r.tips.len() as f64
    };
    let generic = k_of(CrackSpec::segment([0.3513, 1.5117], [0.6513, 1.5117]));
    let cases = [
        (
            "along an element edge, tips on nodes",
            CrackSpec::segment([0.35, 1.5], [0.65, 1.5]),
        ),
        (
            "through mesh nodes (diagonal)",
            CrackSpec::segment([0.35, 1.35], [0.65, 1.65]),
        ),
        (
            "tip exactly on a node",
            CrackSpec::segment([0.3513, 1.5117], [0.65, 1.5117]),
        ),
        (
            "cutting an element corner by 1e-6 of its area",
            CrackSpec::segment([0.35 + 1e-6, 1.5 - 0.0249], [0.65 + 1e-6, 1.5 - 0.0249]),
        ),
    ];
    for (what, crack) in cases {
        let diag = what.contains("diagonal");
        let k = k_of(crack);
        // the diagonal crack has a different geometry: compare with Tada on
        // its projected length only for finiteness
        if diag {
            assert!(k.is_finite() && k > 0.0, "{what}: K_I {k}");
        } else {
            assert!(
                rel(k, generic) < 0.02,
                "{what}: K_I {k:.5e} vs {generic:.5e}"
            );
        }
    }
}

/// An edge crack that starts on the boundary: one tip, K_I within 2% of
/// Tada's 2.8266 σ√(πa) on a coarse 40 × 80 mesh, with very coarse (10 × 20)
/// still finite.
#[test]
fn edge_crack_from_boundary_coarse_meshes() {
    for (n, tol) in [(40usize, 0.02), (10, 1.0)] {
        let mut s = plate(1.0, 2.0, n, 2 * n);
        tension_top_bottom(&mut s, 1e6);
        s.boundary.points = vec![
            PointSupport {
                at: [1.0, 1.0],
                fix: Fix::Xy,
            },
            PointSupport {
                at: [1.0, 2.0],
                fix: Fix::X,
            },
        ];
        s.cracks
            .push(CrackSpec::segment([0.0, 1.0 + 1e-3], [0.5, 1.0 + 1e-3]));
        let r = solve(s);
        assert_eq!(r.tips.len(), 1);
        let f = r.tips[0].k1 / (1e6 * (PI * 0.5f64).sqrt());
        assert!(f.is_finite() && rel(f, 2.8266) < tol, "n = {n}: F = {f}");
    }
}
