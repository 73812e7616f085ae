//! Verification of the fracture criterion and crack growth (issue: growth).

mod common;

use cdca::Simulation;
use cdca::cracks::TipKind;
use cdca::report::{Mode, Outcome};
use cdca::scene::{CrackSpec, CriterionKind, Fix, Plane, PointSupport, Sampling, Scene, SideBc};
use common::*;

fn run(sim: &mut Simulation) {
    while sim.growth_finished().is_none() {
        sim.grow_step().expect("growth step");
    }
}

/// Mode I: a centre crack under tension grows straight (|angle| < 1° at every
/// step) and symmetrically (the two tips stay mirror images about the plate's
/// centre line within 1% of Δa).
#[test]
fn mode_i_growth_is_straight_and_symmetric() {
    // ny odd: the crack runs along the middle of an element row, and the
    // plate, mesh and loads are symmetric about it
    let mut s = plate(1.0, 1.0, 40, 41);
    tension_top_bottom(&mut s, 5e6);
    s.cracks.push(CrackSpec::segment([0.4, 0.5], [0.6, 0.5]));
    s.growth.load_steps = 2;
    s.growth.max_growth_per_step = 4;
    s.growth.max_steps = 5;
    let da = 3.0 * 0.025;
    let mut sim = Simulation::new(s).expect("valid");
    run(&mut sim);
    let grown: Vec<_> = sim
        .history()
        .iter()
        .flat_map(|st| st.grown.clone())
        .collect();
    assert!(grown.len() >= 4, "the crack grew {} times", grown.len());
    for g in &grown {
        assert!(g.angle_deg.abs() < 1.0, "angle {}", g.angle_deg);
        assert_eq!(g.mode, Mode::Tension);
    }
    let c = &sim.cracks()[0];
    let (a, b) = (c[0], c[c.len() - 1]);
    assert!((a[0] + b[0] - 1.0).abs() < 0.01 * da, "x: {a:?} {b:?}");
    assert!((a[1] - b[1]).abs() < 0.01 * da, "y: {a:?} {b:?}");
}

/// Mixed mode: an open crack at 45° under tension (K_I = K_II, T = 0) kinks
/// by θc = −53.13° (Erdogan–Sih) ± 3°, negative in the tip frame at both
/// tips; MTS and the comprehensive criterion with Williams sampling agree.
#[test]
fn mixed_mode_kink_angle_is_erdogan_sih() {
    for (kind, sampling) in [
        (CriterionKind::Mts, Sampling::Field),
        (CriterionKind::Comprehensive, Sampling::Williams),
    ] {
        let mut s = plate(1.0, 1.0, 100, 100);
        tension_top_bottom(&mut s, 20e6);
        s.cracks.push(centre_crack(0.5 + 1e-4, 0.5, 0.05, 45.0));
        s.criterion.kind = kind;
        s.criterion.sampling = sampling;
        s.growth.load_steps = 1;
        let mut sim = Simulation::new(s).expect("valid");
        let step = sim.grow_step().expect("step");
        assert_eq!(step.grown.len(), 2, "{kind:?}: both tips grow");
        for g in &step.grown {
            assert!(
                (g.angle_deg + 53.13).abs() < 3.0,
                "{kind:?} {sampling:?}: {}",
                g.angle_deg
            );
        }
        // the new segment leaves the old direction by that angle
        let c = &sim.cracks()[0];
        let n = c.len();
        let old = (c[n - 2][1] - c[n - 3][1]).atan2(c[n - 2][0] - c[n - 3][0]);
        let new = (c[n - 1][1] - c[n - 2][1]).atan2(c[n - 1][0] - c[n - 2][0]);
        assert!(((new - old).to_degrees() + 53.13).abs() < 3.0);
    }
}

/// The 30 mm specimen with one 6 mm flaw at 45° (joint 200/20 GPa/m,
/// μ = 0.5) under uniaxial compression.
fn wing_scene(n: usize, increment: Option<f64>) -> Scene {
    let mut s = plate(0.03, 0.03, n, n);
    s.specimen.thickness = 0.015;
    s.material.young = 4.78e9;
    s.material.poisson = 0.25;
    s.material.plane = Plane::Stress;
    s.material.cohesion = 15e6;
    s.material.friction_angle_deg = 49.0;
    s.material.k_ic = 1.03e6;
    let mut c = centre_crack(0.015, 0.015, 0.003, 45.0);
    c.friction = 0.5;
    c.normal_stiffness = Some(200e9);
    c.shear_stiffness = Some(20e9);
    s.cracks.push(c);
    s.boundary.bottom = SideBc::Roller;
    s.boundary.top = SideBc::Traction {
        normal: -120e6,
        shear: 0.0,
    };
    s.boundary.points = vec![PointSupport {
        at: [0.0, 0.0],
        fix: Fix::X,
    }];
    s.criterion.r0 = Some(0.0009);
    s.growth.increment = increment;
    s.growth.load_steps = 10;
    s.growth.max_steps = 60;
    s
}

/// The wing grown from tip 1 (upper end), as a polyline from the flaw tip.
fn upper_wing(sim: &Simulation) -> Vec<[f64; 2]> {
    let c = &sim.cracks()[0];
    let start = c
        .iter()
        .position(|p| (p[0] - 0.015 - 0.003 / 2f64.sqrt()).abs() < 1e-9)
        .expect("flaw tip");
    c[start..].to_vec()
}

fn length(p: &[[f64; 2]]) -> f64 {
    p.windows(2)
        .map(|w| ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt())
        .sum()
}

/// Closed flaw under uniaxial compression: wing cracks start from both tips
/// at a large angle (> 45°) to the flaw and curve toward the loading axis:
/// once a wing is as long as the flaw, its last segment is within 20° of
/// the vertical. A wing that reaches the boundary stops there.
#[test]
fn wing_cracks_curve_toward_the_load() {
    let mut sim = Simulation::new(wing_scene(100, None)).expect("valid");
    run(&mut sim);
    let first: Vec<_> = sim
        .history()
        .iter()
        .flat_map(|s| s.grown.clone())
        .take(2)
        .collect();
    assert_eq!(first.len(), 2);
    for g in &first {
        assert!(g.angle_deg.abs() > 45.0 && g.mode == Mode::Tension, "{g:?}");
    }
    let c = &sim.cracks()[0];
    let wing = upper_wing(&sim);
    assert!(length(&wing) >= 0.006, "wing length {}", length(&wing));
    let n = wing.len();
    let d = [
        wing[n - 1][0] - wing[n - 2][0],
        wing[n - 1][1] - wing[n - 2][1],
    ];
    let from_vertical = d[0].atan2(d[1].abs()).to_degrees().abs();
    assert!(
        from_vertical < 20.0,
        "last segment {from_vertical:.1}° from the load axis"
    );
    // every point inside the specimen; boundary tips are not free
    for p in c {
        assert!(p[0] >= -1e-12 && p[0] <= 0.03 + 1e-12 && p[1] >= -1e-12 && p[1] <= 0.03 + 1e-12);
    }
    let tips = &sim.xfem().funcs.cracks[0].tips;
    if tips.contains(&TipKind::Boundary) {
        assert!(sim.tips().len() < 2);
    }
}

/// Path sensitivity: the upper wing at h and h/2, and at Δa and Δa/2, stays
/// within 2h (coarse h) of the reference path over the first 4 mm.
#[test]
fn wing_path_is_insensitive_to_mesh_and_increment() {
    let path = |n: usize, da: f64| {
        let mut sim = Simulation::new(wing_scene(n, Some(da))).expect("valid");
        while sim.growth_finished().is_none() && length(&upper_wing(&sim)) < 0.004 {
            sim.grow_step().expect("step");
        }
        upper_wing(&sim)
    };
    let h = 0.03 / 60.0;
    let reference = path(60, 0.0009);
    for (n, da) in [(120, 0.0009), (60, 0.00045)] {
        let other = path(n, da);
        let d = hausdorff_prefix(&reference, &other, 0.004);
        println!("n = {n}, Δa = {da}: distance {:.3} h", d / h);
        assert!(d < 2.0 * h, "n = {n}, Δa = {da}: paths {d:.3e} m apart");
    }
}

/// Largest distance from a point of one path (within `len` of its start)
/// to the other path, both ways.
fn hausdorff_prefix(a: &[[f64; 2]], b: &[[f64; 2]], len: f64) -> f64 {
    let sample = |p: &[[f64; 2]]| {
        let mut out = Vec::new();
        let mut s = 0.0;
        for w in p.windows(2) {
            let l = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
            for k in 0..10 {
                let t = f64::from(k) / 10.0;
                if s + t * l <= len {
                    out.push(cdca::geometry::P2::new(
                        w[0][0] + t * (w[1][0] - w[0][0]),
                        w[0][1] + t * (w[1][1] - w[0][1]),
                    ));
                }
            }
            s += l;
        }
        out
    };
    let to_pts = |p: &[[f64; 2]]| p.iter().map(|q| cdca::geometry::p2(*q)).collect::<Vec<_>>();
    let (pa, pb) = (to_pts(a), to_pts(b));
    let dist = |x: cdca::geometry::P2, poly: &[cdca::geometry::P2]| {
        poly.windows(2)
            .map(|w| cdca::geometry::distance_to_segment(x, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
    };
    let ab = sample(a)
        .into_iter()
        .map(|x| dist(x, &pb))
        .fold(0.0, f64::max);
    let ba = sample(b)
        .into_iter()
        .map(|x| dist(x, &pa))
        .fold(0.0, f64::max);
    ab.max(ba)
}

/// Coalescence: in the stepped flaw pair a growing wing reaches the other
/// flaw's crack and ends on it as a junction; no tip ends outside the body.
#[test]
fn stepped_flaws_coalesce() {
    let text = include_str!("../../../assets/scenes/specimen_two_flaws_stepped.json");
    let mut sim = Simulation::new(Scene::from_json(text).expect("scene")).expect("valid");
    run(&mut sim);
    assert_ne!(sim.growth_finished(), Some(Outcome::Unstable));
    let junctions = sim
        .xfem()
        .funcs
        .cracks
        .iter()
        .flat_map(|c| c.tips)
        .filter(|t| matches!(t, TipKind::Junction { .. }))
        .count();
    assert!(junctions >= 1, "no junction formed: {:?}", sim.cracks());
}

/// The paper's observations on the 0.3 m plate with a central 45° crack:
/// the initial propagation angle falls as P_H/P_V rises and as μ rises.
#[test]
fn initial_angle_falls_with_confinement_and_friction() {
    let first = |name: &str| -> Option<(f64, Mode)> {
        let path = format!(
            "{}/../../assets/scenes/{name}.json",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(path).expect("scene file");
        let mut sim = Simulation::new(Scene::from_json(&text).expect("scene")).expect("valid");
        while sim.growth_finished().is_none() {
            let st = sim.grow_step().expect("step");
            if let Some(g) = st.grown.first() {
                return Some((g.angle_deg.abs(), g.mode));
            }
        }
        None
    };
    println!("scene                         initial angle  mode");
    let mut by_k = Vec::new();
    for k in ["0.1", "0.2", "0.3"] {
        let r = first(&format!("plate_45_biaxial_k{k}_mu0.5"));
        println!("k = {k}, μ = 0.5              {r:?}");
        by_k.push(r);
    }
    let mut by_mu = Vec::new();
    for mu in ["0.32", "0.48", "0.5", "0.67", "0.83"] {
        let r = first(&format!("plate_45_biaxial_k0.2_mu{mu}"));
        println!("k = 0.2, μ = {mu}             {r:?}");
        by_mu.push(r);
    }
    // falls: each angle below the previous, or no initiation at all
    for seq in [&by_k, &by_mu] {
        let angles: Vec<f64> = seq.iter().map(|r| r.map_or(0.0, |(a, _)| a)).collect();
        assert!(
            angles[0] > 0.0,
            "the least confined case initiates: {angles:?}"
        );
        for w in angles.windows(2) {
            assert!(w[1] <= w[0], "angles must fall: {angles:?}");
        }
    }
}

/// Regression: after growth the discretisation reuses element matrices away
/// from the moved tips; K must equal (1e-10) a fresh discretisation of the
/// grown scene (open crack, so no contact history is involved).
#[test]
fn element_reuse_after_growth_matches_a_fresh_build() {
    let mut s = plate(1.0, 1.0, 40, 41);
    tension_top_bottom(&mut s, 5e6);
    s.cracks.push(centre_crack(0.5, 0.5, 0.1, 20.0));
    s.growth.load_steps = 1;
    s.growth.max_growth_per_step = 3;
    let mut sim = Simulation::new(s).expect("valid");
    for _ in 0..2 {
        sim.grow_step().expect("step");
    }
    let grown = sim.solve().expect("solve");
    let fresh = solve(sim.scene().clone());
    assert_eq!(grown.tips.len(), fresh.tips.len());
    for (a, b) in grown.tips.iter().zip(&fresh.tips) {
        assert!(
            rel(a.k1, b.k1) < 1e-10 && (a.k2 - b.k2).abs() < 1e-10 * b.k1.abs(),
            "{a:?} vs {b:?}"
        );
    }
}

/// The resumable growth step (a few sweeps per call, as the workbench runs
/// it) records the same history as `grow_step`: same tips, angles to 1e-9°
/// and positions to 1e-12 m with the direct solver.
#[test]
fn resumable_growth_matches_grow_step() {
    let text = include_str!("../../../assets/scenes/closed_crack_biaxial.json");
    let scene = Scene::from_json(text).expect("scene");
    let mut a = Simulation::new(scene.clone()).expect("valid");
    let mut b = Simulation::new(scene).expect("valid");
    for _ in 0..4 {
        a.grow_step().expect("step");
        let mut calls = 0;
        while b.advance_growth(1).expect("advance").is_none() {
            calls += 1;
            assert!(calls < 1000);
        }
    }
    assert_eq!(a.history().len(), b.history().len());
    for (x, y) in a.history().iter().zip(b.history()) {
        assert_eq!(x.grown.len(), y.grown.len());
        assert!((x.load_factor - y.load_factor).abs() < 1e-15);
        for (p, q) in x.grown.iter().zip(&y.grown) {
            assert!(
                (p.angle_deg - q.angle_deg).abs() < 1e-9
                    && (p.x - q.x).abs() < 1e-12
                    && (p.y - q.y).abs() < 1e-12
            );
        }
    }
}
