//! The criterion's two checks on circles around each drawn crack's ends
//! after a few growth steps. Where a wing has left an end, that end is a
//! kink vertex: where a secondary (shear) crack into a rock bridge would
//! start, the branching that coplanar flaws need to link (docs/fracture-model.md, *Growth
//! to failure*). Used by `scripts/kink_vertex.sh`.
//!
//! `kink_vertex SCENE STEPS R_MM...` grows STEPS steps under the scene's
//! growth control, solves at the last step's load factor, and prints one CSV
//! row per end and radius r: whether the end is still a free tip, and over
//! the half circle ahead of it (|θ| ≤ 90° from the crack's outward
//! direction) the largest tension check `σ_θθ / σ_t(r)` and the largest
//! shear check `|τ_rθ| / (max(σ_n, 0) μ + c_c + K_IIC/√(2π r))`, each with
//! its angle θ (°). `σ_t(r) = σ_t √(r_p / r)`, the scaling of
//! `CriterionParams::for_crack`, so both read `K ≥ K_c` in a pure singular
//! field at any r. The shear envelope is the scene's (by default the
//! faces' friction μ and cohesion c_c, `criterion.shear_strength`).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use cdca::fracture::criterion::{CriterionParams, Faces, sample_field};
use cdca::geometry::cracks::TipFrame;
use cdca::geometry::plane::P2;
use cdca::{Scene, Simulation};

/// The largest value of `f(σ_θθ, τ_rθ)` on the circle and its angle, °.
fn peak(c: &cdca::fracture::criterion::Circle, f: impl Fn(f64, f64) -> f64) -> (f64, f64) {
    c.theta
        .iter()
        .zip(c.sigma_tt.iter().zip(&c.tau_rt))
        .map(|(t, (s, tau))| (f(*s, *tau), t.to_degrees()))
        .fold(
            (f64::NEG_INFINITY, 0.0),
            |a, b| if b.0 > a.0 { b } else { a },
        )
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: kink_vertex SCENE STEPS R_MM...";
    let scene =
        Scene::from_json(&std::fs::read_to_string(args.get(1).expect(usage)).unwrap()).unwrap();
    let steps: usize = args.get(2).expect(usage).parse().expect(usage);
    let radii: Vec<f64> = args[3..]
        .iter()
        .map(|s| s.parse::<f64>().expect(usage) * 1e-3)
        .collect();
    let base = CriterionParams::of_scene(&scene);
    // each drawn crack's two ends, with the crack's outward direction there
    let ends: Vec<(usize, TipFrame, Faces)> = scene
        .cracks
        .iter()
        .enumerate()
        .flat_map(|(i, c)| {
            let p = c.points.clone().expect("cracks given as polylines");
            let faces = Faces {
                friction: c.friction,
                cohesion: c.cohesion,
                closed: true,
            };
            let frame = |o: [f64; 2], from: [f64; 2]| {
                let e1 = (P2::new(o[0], o[1]) - P2::new(from[0], from[1])).normalize();
                TipFrame {
                    origin: P2::new(o[0], o[1]),
                    e1,
                    e2: P2::new(-e1.y, e1.x),
                }
            };
            let n = p.len();
            [
                (2 * i, frame(p[0], p[1]), faces),
                (2 * i + 1, frame(p[n - 1], p[n - 2]), faces),
            ]
        })
        .collect();
    let n = scene.mesh.nx;
    let mut sim = Simulation::new(scene).unwrap();
    let mut last = None;
    for _ in 0..steps {
        let report = sim.grow_step().unwrap();
        let done = sim.growth_finished().is_some();
        last = Some(report);
        if done {
            break;
        }
    }
    let report = last.expect("at least one growth step");
    sim.set_load_factor(report.load_factor);
    sim.solve().unwrap();
    println!("mesh,step,load_factor,end,free_tip,r_mm,tension,tension_deg,shear,shear_deg");
    for (end, frame, faces) in &ends {
        let free = sim
            .tips()
            .iter()
            .any(|t| (P2::new(t.x, t.y) - frame.origin).norm() < 1e-9);
        for &r in &radii {
            let p = CriterionParams {
                r0: r,
                sigma_t: base.sigma_t * (base.r0 / r).sqrt(),
                ..base
            };
            let (mu, c) = p
                .shear_envelope(*faces)
                .expect("the faces' envelope applies");
            let circle = sample_field(frame, r, &|x| sim.stress_at([x.x, x.y]));
            let (t, t_deg) = peak(&circle, |s, _| s / p.sigma_t);
            let (s, s_deg) = peak(&circle, |s, tau| tau.abs() / ((-s).max(0.0) * mu + c));
            println!(
                "{n},{},{:.4},{end},{free},{:.2},{t:.3},{t_deg:.1},{s:.3},{s_deg:.1}",
                report.step,
                report.load_factor,
                r * 1e3
            );
        }
    }
}
