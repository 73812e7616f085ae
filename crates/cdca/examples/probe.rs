use cdca::cracks::TipFrame;
use cdca::direct::Factor;
use cdca::field::Field;
use cdca::geometry::P2;
use cdca::model::Model;
use cdca::scene::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(40);
    let rj: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3.0);
    let kind = args.get(3).map(String::as_str).unwrap_or("centre");
    let json = match kind {
        "edge" => format!(r#"{{"specimen":{{"width":1.0,"height":2.0}},"mesh":{{"nx":{n},"ny":{}}},"material":{{"young":200e9,"poisson":0.3,"plane":"strain"}},
          "cracks":[{{"points":[[0.0,1.0],[0.5,1.0]]}}],
          "boundary":{{"bottom":{{"kind":"traction","normal":1e6}},"top":{{"kind":"traction","normal":1e6}},"left":{{"kind":"free"}},"right":{{"kind":"free"}},
          "points":[{{"at":[1.0,1.0],"fix":"xy"}},{{"at":[1.0,2.0],"fix":"x"}}]}}}}"#, 2*n),
        "incl" => { let b: f64 = 30f64.to_radians(); let a = 0.05; format!(r#"{{"specimen":{{"width":1.0,"height":1.0}},"mesh":{{"nx":{n},"ny":{n}}},"material":{{"young":200e9,"poisson":0.3,"plane":"strain"}},
          "cracks":[{{"points":[[{},{}],[{},{}]]}}],
          "boundary":{{"bottom":{{"kind":"traction","normal":1e6}},"top":{{"kind":"traction","normal":1e6}},"left":{{"kind":"free"}},"right":{{"kind":"free"}},
          "points":[{{"at":[0.0,0.5],"fix":"xy"}},{{"at":[1.0,0.5],"fix":"y"}}]}}}}"#, 0.5-a*b.cos(), 0.5-a*b.sin(), 0.5+a*b.cos(), 0.5+a*b.sin()) }
        _ => format!(r#"{{"specimen":{{"width":1.0,"height":3.0}},"mesh":{{"nx":{n},"ny":{}}},"material":{{"young":200e9,"poisson":0.3,"plane":"strain"}},
          "cracks":[{{"points":[[0.35,1.5],[0.65,1.5]]}}],
          "boundary":{{"bottom":{{"kind":"traction","normal":1e6}},"top":{{"kind":"traction","normal":1e6}},"left":{{"kind":"free"}},"right":{{"kind":"free"}},
          "points":[{{"at":[0.0,1.5],"fix":"xy"}},{{"at":[1.0,1.5],"fix":"y"}}]}}}}"#, 3*n),
    };
    let scene: Scene = serde_json::from_str(&json).unwrap();
    let t0 = std::time::Instant::now();
    let model = Model::new(scene.clone());
    let cracks = model.initial_cracks();
    let x = model.discretise(cracks.clone());
    let t1 = t0.elapsed().as_secs_f64();
    let f = cdca::loads::traction_forces(&x, &scene.boundary);
    let fac = Factor::new(&x, &[]).unwrap();
    let t2 = t0.elapsed().as_secs_f64();
    let u = fac.solve(&f).unwrap();
    let t3 = t0.elapsed().as_secs_f64();
    let field = Field { xfem: &x, u: &u };
    for k in cracks[0].free_tips() {
        let fr = TipFrame::of(&cracks[0], k);
        let s = cdca::sif::tip_sifs(&field, 0, &fr, rj * x.mesh.h(), &[]);
        let pi = std::f64::consts::PI;
        let (k1ref, k2ref, tref) = match kind {
            "edge" => (2.8266 * 1e6 * (pi * 0.5f64).sqrt(), 0.0, 0.0),
            "incl" => { let b: f64 = 30f64.to_radians(); let s0 = 1e6*(pi*0.05f64).sqrt(); (s0*b.cos().powi(2), s0*b.sin()*b.cos(), -1e6*(2.0*b).cos()) }
            _ => { let al: f64 = 0.3; (1e6 * (pi*0.15f64).sqrt() * (1.0 - 0.025*al*al + 0.06*al.powi(4)) * (1.0/(pi*al/2.0).cos()).sqrt(), 0.0, -1e6) }
        };
        println!("n={n} tip {k}: K1={:.6e} ({:+.3}%) K2={:.4e} ({:+.3}% ) T={:.4e} (ref {:.3e}) dofs={} enr={} setup {:.3}s fact {:.3}s solve {:.3}s sif {:.3}s",
          s.k1, 100.0*(s.k1/k1ref-1.0), s.k2, if k2ref!=0.0 {100.0*(s.k2/k2ref-1.0)} else {0.0}, s.t, tref, x.n_free(), x.dofs.n_enriched, t1, t2-t1, t3-t2, t0.elapsed().as_secs_f64()-t3);
        let _ = P2::zeros();
    }
}
