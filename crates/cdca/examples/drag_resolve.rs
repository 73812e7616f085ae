//! The re-solve of a dragged crack, as the workbench does it while the
//! pointer moves: `drag_resolve SCENE [FRAMES] [STEP_H] [CSV]`. The end
//! point of the scene's first crack moves `STEP_H` element sizes a frame
//! (default 0.05) for `FRAMES` frames (default 60), each position built and
//! solved with the direct solver, either as a new simulation or from the
//! last one (`Simulation::with_scene`). Prints the median and mean ms per
//! frame for each, how many kept the stiffness pattern, and that both give
//! the same K (every tenth frame compared, bit for bit); writes a CSV.
#![allow(clippy::unwrap_used, clippy::expect_used)]
use std::fmt::Write;
use std::sync::Arc;

use cdca::scene::SceneFile;
use cdca::{Scene, Simulation};
use web_time::Instant;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let path = a
        .get(1)
        .expect("usage: drag_resolve SCENE [FRAMES] [STEP_H] [CSV]");
    let frames: usize = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(60);
    let step_h: f64 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(0.05);
    let csv = a
        .get(4)
        .cloned()
        .unwrap_or_else(|| "bench-out/drag.csv".to_owned());
    let base = SceneFile::from_json(&std::fs::read_to_string(path).unwrap()).unwrap();
    let h = base.specimen.width / base.mesh.nx as f64;
    let at = |i: usize| {
        let mut s = base.clone();
        let d = step_h * h * i as f64;
        if let Some(p) = s.cracks[0].points.as_mut() {
            let k = p.len() - 1;
            p[k][0] += 0.8 * d;
            p[k][1] += 0.6 * d;
        }
        Scene::try_from(s).expect("a valid dragged scene")
    };
    let mut rows = Vec::new();
    let mut same = 0;
    for kept in [false, true] {
        let mut ms = Vec::new();
        let mut patterns = 0;
        let mut last: Option<Simulation> = None;
        for i in 0..frames {
            let scene = at(i);
            // (held, so that a new pattern cannot take the old one's address)
            let before = last
                .as_ref()
                .map(|s| Arc::clone(s.xfem().pattern().unwrap().ordered()));
            let start = Instant::now();
            let mut sim = match last.take() {
                Some(old) if kept => old.with_scene(scene.clone()).unwrap(),
                _ => Simulation::new(scene.clone()).unwrap(),
            };
            let report = sim.solve().unwrap();
            ms.push(start.elapsed().as_secs_f64() * 1e3);
            assert!(report.converged(), "frame {i}: {:?}", report.failure());
            let after = sim.xfem().pattern().unwrap().ordered();
            patterns += usize::from(before.is_some_and(|b| Arc::ptr_eq(&b, after)));
            if kept && i % 10 == 0 {
                let fresh = Simulation::new(scene).unwrap().solve().unwrap();
                let k = |r: &cdca::report::SolveReport| {
                    r.tips.iter().map(|t| (t.k1, t.k2)).collect::<Vec<_>>()
                };
                assert_eq!(
                    k(&report),
                    k(&fresh),
                    "frame {i}: the same K as a new simulation"
                );
                same += 1;
            }
            last = Some(sim);
        }
        let mean = ms.iter().sum::<f64>() / ms.len() as f64;
        ms.sort_by(f64::total_cmp);
        let mode = if kept { "with_scene" } else { "new" };
        rows.push((
            mode,
            ms[ms.len() / 2],
            mean,
            ms[ms.len() * 9 / 10],
            patterns,
        ));
    }
    println!(
        "{frames} frames, the tip moved {step_h} h a frame; K of with_scene bit for bit that \
         of a new simulation in {same} checks"
    );
    println!("| build | median ms | mean ms | p90 ms | pattern kept |");
    println!("| --- | --- | --- | --- | --- |");
    let mut out = String::from("build,median_ms,mean_ms,p90_ms,pattern_kept,frames,step_h\n");
    for (mode, median, mean, p90, patterns) in rows {
        println!("| {mode} | {median:.1} | {mean:.1} | {p90:.1} | {patterns} of {frames} |");
        writeln!(
            out,
            "{mode},{median:.3},{mean:.3},{p90:.3},{patterns},{frames},{step_h}"
        )
        .unwrap();
    }
    if let Some(dir) = std::path::Path::new(&csv).parent() {
        std::fs::create_dir_all(dir).unwrap();
    }
    std::fs::write(&csv, out).unwrap();
}
