use cdca::Simulation;
use cdca::scene::Scene;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100);
    let k: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.2);
    let mu: f64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(0.2);
    let kn: f64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let coh: f64 = args.get(5).and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let p = 10e6;
    let a = 0.05;
    let c = 0.5;
    let d = a / 2f64.sqrt();
    let h = 1.0 / n as f64;
    let kn_s = if kn > 0.0 { format!(r#","normal_stiffness":{},"shear_stiffness":{}"#, kn * 4.78e9 / h, 0.1 * kn * 4.78e9 / h) } else { String::new() };
    let json = format!(r#"{{"specimen":{{"width":1.0,"height":1.0}},"mesh":{{"nx":{n},"ny":{n}}},
      "material":{{"young":4.78e9,"poisson":0.25}},
      "cracks":[{{"points":[[{},{}],[{},{}]],"friction":{mu},"cohesion":{coh}{kn_s}}}],
      "boundary":{{"bottom":{{"kind":"roller"}},"left":{{"kind":"roller"}},"top":{{"kind":"traction","normal":{}}},"right":{{"kind":"traction","normal":{}}}}}}}"#,
      c - d + 1e-7, c - d, c + d + 1e-7, c + d, -p, -k * p);
    let scene = Scene::from_json(&json).unwrap();
    let mut sim = Simulation::new(scene).unwrap();
    let t = std::time::Instant::now();
    let r = sim.solve().unwrap();
    let sn = p * (1.0 + k) / 2.0;
    let tau = p * (1.0 - k) / 2.0;
    let pa = (std::f64::consts::PI * a).sqrt();
    let k2ref = ((tau - mu * sn - coh).max(0.0)) * pa;
    for tip in &r.tips {
        println!("n={n} k={k} mu={mu} tip{}: K1={:.4e} ({:.3}% of sn√πa) K2={:.5e} ref {:.5e} err {:+.3}%  (|K2|/τ√πa={:.4})", tip.tip, tip.k1, 100.0*tip.k1/(sn*pa), tip.k2, k2ref,
            if k2ref > 0.0 { 100.0 * (tip.k2.abs() / k2ref - 1.0) } else { f64::NAN }, tip.k2.abs()/(tau*pa));
    }
    if std::env::var("DUMP").is_ok() { dump(&sim); }
    if std::env::var("RADII").is_ok() { radii(&sim); }
    println!("contact: it {} conv {} open {} stick {} slip {} cyc {} res {:.2e} knh/E {:.1}  time {:.3}s", r.contact.iterations, r.contact.converged, r.contact.open, r.contact.stick, r.contact.slip, r.contact.cycling, r.contact.residual, r.contact.kn_h_over_e, t.elapsed().as_secs_f64());
}
#[allow(dead_code)]
fn dump(sim: &Simulation) {
    for p in sim.contact_points() {
        println!("  ({:.5},{:.5}) {:?} pn={:.3e} pt={:.3e} slip={:.3e}", p.x, p.y, p.state, p.p_n, p.p_t, p.slip);
    }
}
#[allow(dead_code)]
fn radii(sim: &Simulation) {
    use cdca::cracks::TipFrame;
    use cdca::geometry::P2;
    let x = sim.xfem();
    let f = cdca::field::Field { xfem: x, u: sim.displacement() };
    let tr: Vec<P2> = sim.contact_points().iter().map(|p| { let n = P2::new(p.normal[0], p.normal[1]); let t = P2::new(n.y, -n.x); n * p.p_n + t * p.p_t }).collect();
    for rj in [1.5, 2.0, 2.5, 3.0, 4.0, 5.0] {
        let fr = TipFrame::of(&x.funcs.cracks[0], 1);
        let s = cdca::sif::tip_sifs(&f, 0, &fr, rj * x.mesh.h(), &tr);
        let s0 = cdca::sif::tip_sifs(&f, 0, &fr, rj * x.mesh.h(), &[]);
        println!("  rJ={rj}: K1={:.4e} K2={:.5e}   (no face term: K1={:.4e} K2={:.5e})", s.k1, s.k2, s0.k1, s0.k2);
    }
    let mut pn: Vec<(f64,f64)> = sim.contact_points().iter().map(|p| (p.x, p.p_n)).collect();
    pn.sort_by(|a,b| a.0.total_cmp(&b.0));
    let mean = pn.iter().map(|p| p.1).sum::<f64>() / pn.len() as f64;
    println!("  mean p_n over points {:.4e}", mean);
}
