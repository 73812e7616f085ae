//! `cdca bench`: error against run time for every solver, side by side.
//!
//! For each scene (an open centre crack in tension; a closed frictional 45°
//! crack under biaxial compression; up to 80² also the stiff variants
//! `k_N h/E = 1e6` and ν = 0.49 in plane strain) and mesh size, the contact states are
//! settled first with the direct solver; then every solver solves the same
//! final linear system `(K + K_contact) u = f` from zero. The direct solve
//! is timed whole (operator, assembly, factorisation, solve); the iterative
//! ones are sampled at checkpoints, where the relative energy-norm error
//! `‖u − u_ref‖_K / ‖u_ref‖_K` and the relative K_I, K_II errors are
//! measured with the clock paused. Prints a table, writes
//! `DIR/error_vs_time.csv` and draws `DIR/error_vs_time.svg`.

mod scenes;
mod svg;

use std::fmt::Write as _;
use std::path::PathBuf;

use cdca::contact::{FaceState, contact_system, gaps, update_point};
use cdca::contact_loop::{ContactParams, solve_with_contact};
use cdca::geometry::P2;
use cdca::model::Model;
use cdca::relaxation::Relaxation;
use cdca::scene::{Ordering, Scene, SolverKind, SolverSpec};
use cdca::solver::DirectSolver;
use cdca::tips::all_tip_sifs;
use cdca::xfem::Xfem;
use scenes::SCENES;

use crate::error::CliError;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output directory for the CSV and the SVG.
    #[arg(long, default_value = "bench-out")]
    out: PathBuf,
    /// Mesh sizes n (n × n elements), comma separated.
    #[arg(long, value_delimiter = ',', default_value = "20,40,80,160,320")]
    sizes: Vec<usize>,
    /// Smoke run: sizes capped at 40.
    #[arg(long)]
    quick: bool,
    /// Time budget of one iterative run, as a multiple of the direct time
    /// (at least 2 s).
    #[arg(long, default_value_t = 30.0)]
    budget: f64,
}

/// One checkpoint of one run.
#[derive(Clone, Debug)]
pub struct Sample {
    pub iteration: usize,
    pub seconds: f64,
    pub energy: f64,
    pub k1: f64,
    pub k2: f64,
}

/// One solver on one scene and size.
#[derive(Clone, Debug)]
pub struct Run {
    pub scene: &'static str,
    pub size: usize,
    pub solver: &'static str,
    pub samples: Vec<Sample>,
}

/// The solvers compared: name, kind, ordering, ω (`None`: 2/(1 + sin(π/n))).
const SOLVERS: [(&str, SolverKind, Ordering, Option<f64>); 4] = [
    (
        "automaton",
        SolverKind::Automaton,
        Ordering::Lexicographic,
        Some(1.0),
    ),
    (
        "automaton-sor",
        SolverKind::Automaton,
        Ordering::RedBlack,
        None,
    ),
    ("cg", SolverKind::Cg, Ordering::Lexicographic, Some(1.0)),
    (
        "multigrid",
        SolverKind::Multigrid,
        Ordering::Lexicographic,
        Some(1.0),
    ),
];

pub fn run(args: &Args) -> Result<(), CliError> {
    let mut sizes: Vec<usize> = args.sizes.iter().copied().filter(|&n| n >= 4).collect();
    if args.quick {
        sizes.retain(|&n| n <= 40);
    }
    if sizes.is_empty() {
        return Err(CliError::Input("--sizes: no size of at least 4".to_owned()));
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::Input(format!("{}: {e}", args.out.display())))?;
    let mut runs = Vec::new();
    for sc in &SCENES {
        for &n in sizes.iter().filter(|&&n| n <= sc.max_size) {
            runs.extend(bench_case(sc.name, &(sc.build)(n), n, args.budget)?);
        }
    }
    println!("{}", table(&runs));
    let csv = args.out.join("error_vs_time.csv");
    std::fs::write(&csv, to_csv(&runs))
        .map_err(|e| CliError::Failure(format!("{}: {e}", csv.display())))?;
    let largest = sizes.iter().copied().max().unwrap_or(0);
    let pic = args.out.join("error_vs_time.svg");
    std::fs::write(&pic, svg::draw(&runs, largest))
        .map_err(|e| CliError::Failure(format!("{}: {e}", pic.display())))?;
    println!("wrote {} and {}", csv.display(), pic.display());
    Ok(())
}

/// Every solver on one scene and size.
fn bench_case(
    name: &'static str,
    scene: &Scene,
    n: usize,
    budget: f64,
) -> Result<Vec<Run>, CliError> {
    let model = Model::new(scene.clone());
    let x = model.discretise(model.initial_cracks());
    let f_ext = cdca::loads::traction_forces(&x, &scene.boundary);
    // settle the contact states with the direct solver
    let committed = vec![FaceState::default(); x.faces.len()];
    let mut u = vec![0.0; x.n_free()];
    let (states, _) = solve_with_contact(
        &x,
        &f_ext,
        &committed,
        &mut u,
        &mut DirectSolver::default(),
        ContactParams::default(),
    )?;
    let mut f = f_ext.clone();
    let blocks = contact_system(&x, &states, &committed, &mut f);
    let zero = vec![0.0; x.n_free()];
    let spec = |kind, ordering, omega| SolverSpec {
        kind,
        ordering,
        omega,
        tolerance: 1e-14,
        max_iterations: usize::MAX,
        ..SolverSpec::default()
    };
    let mut direct = Relaxation::new(
        SolverKind::Direct,
        &spec(SolverKind::Direct, Ordering::Lexicographic, 1.0),
        &x,
        &blocks,
        &f,
        &zero,
    )?;
    direct.run(&x, &blocks, 1, &mut |_| {})?;
    let u_ref = direct.u().to_vec();
    let reference = Reference::new(&x, direct.operator(), &u_ref);
    let t_direct = direct.seconds();
    let mut runs = vec![Run {
        scene: name,
        size: n,
        solver: "direct",
        samples: vec![reference.sample(&x, direct.operator(), &u_ref, 1, t_direct)],
    }];
    eprintln!("{name} {n}²: {} DOFs, direct {t_direct:.3} s", x.n_free());
    let limit = (budget * t_direct).max(2.0);
    for (solver, kind, ordering, omega) in SOLVERS {
        let omega = omega.unwrap_or(2.0 / (1.0 + (std::f64::consts::PI / n as f64).sin()));
        let case = Case {
            x: &x,
            blocks: &blocks,
            f: &f,
            reference: &reference,
            limit,
        };
        match case.sample_run(&spec(kind, ordering, omega)) {
            Ok(samples) => runs.push(Run {
                scene: name,
                size: n,
                solver,
                samples,
            }),
            // an explicit failure (e.g. a non-SPD cell block) is reported, not fatal
            Err(e) => eprintln!("  {solver:14} failed: {e}"),
        }
    }
    Ok(runs)
}

/// The linear system of one scene and size, with its reference.
struct Case<'a> {
    x: &'a Xfem,
    blocks: &'a [cdca::assembly::ElementBlock],
    f: &'a [f64],
    reference: &'a Reference,
    /// Time budget, s.
    limit: f64,
}

impl Case<'_> {
    /// Runs one iterative solver from zero, sampling the errors at
    /// checkpoints (every 25 % more iterations) with the clock paused.
    fn sample_run(&self, spec: &SolverSpec) -> Result<Vec<Sample>, cdca::SolveError> {
        let (x, blocks, reference) = (self.x, self.blocks, self.reference);
        let zero = vec![0.0; x.n_free()];
        let mut r = Relaxation::new(spec.kind, spec, x, blocks, self.f, &zero)?;
        let mut samples = vec![reference.sample(x, r.operator(), r.u(), 0, r.seconds())];
        let mut next = 1;
        let status = loop {
            let status = r.run(x, blocks, next - r.status().iterations, &mut |_| {})?;
            let s = reference.sample(x, r.operator(), r.u(), status.iterations, r.seconds());
            let done = status.converged || s.energy <= 1e-11 || r.seconds() > self.limit;
            samples.push(s);
            if done {
                break status;
            }
            next = (next + 1).max((next as f64 * 1.25) as usize);
        };
        let last = samples.last().map_or(f64::NAN, |s| s.energy);
        eprintln!(
            "  {:14} {:8} iterations {:8.3} s, energy error {last:.2e}",
            label(spec),
            status.iterations,
            r.seconds()
        );
        Ok(samples)
    }
}

/// Short label of a solver setting for progress messages.
fn label(spec: &SolverSpec) -> String {
    format!("{:?} ω={:.3}", spec.kind, spec.omega)
}

/// The direct solution and its SIFs.
struct Reference {
    u: Vec<f64>,
    energy: f64,
    k: Vec<(f64, f64)>,
    scale: f64,
}

impl Reference {
    fn new(x: &Xfem, op: &cdca::element_op::ElementOperator, u: &[f64]) -> Self {
        let mut kv = vec![0.0; u.len()];
        let k = sifs(x, u);
        let scale = k
            .iter()
            .fold(0.0_f64, |m, (a, b)| m.max(a.abs()).max(b.abs()));
        Self {
            u: u.to_vec(),
            energy: op.energy(u, &mut kv).sqrt(),
            k,
            scale,
        }
    }

    /// Errors of `u` against the reference.
    fn sample(
        &self,
        x: &Xfem,
        op: &cdca::element_op::ElementOperator,
        u: &[f64],
        iteration: usize,
        seconds: f64,
    ) -> Sample {
        let e: Vec<f64> = u.iter().zip(&self.u).map(|(a, b)| a - b).collect();
        let mut kv = vec![0.0; u.len()];
        let energy = op.energy(&e, &mut kv).max(0.0).sqrt() / self.energy;
        let k = sifs(x, u);
        let err = |pick: fn(&(f64, f64)) -> f64| {
            k.iter().zip(&self.k).fold(0.0_f64, |m, (a, b)| {
                m.max((pick(a) - pick(b)).abs() / self.scale)
            })
        };
        Sample {
            iteration,
            seconds,
            energy,
            k1: err(|p| p.0),
            k2: err(|p| p.1),
        }
    }
}

/// (K_I, K_II) of every free tip, with the contact tractions of the
/// states that `u` itself implies.
fn sifs(x: &Xfem, u: &[f64]) -> Vec<(f64, f64)> {
    let tractions: Vec<P2> = x
        .faces
        .iter()
        .map(|fp| {
            let (gn, gt) = gaps(x, fp, u);
            update_point(&x.funcs.cracks[fp.crack], 0.0, gn, gt).traction(fp)
        })
        .collect();
    all_tip_sifs(x, u, &tractions)
        .into_iter()
        .map(|(_, _, _, s)| (s.k1, s.k2))
        .collect()
}

/// First time at which the energy error is at most `tol`.
fn time_to(run: &Run, tol: f64) -> Option<f64> {
    run.samples
        .iter()
        .find(|s| s.energy <= tol)
        .map(|s| s.seconds)
}

fn table(runs: &[Run]) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "scene   size solver          iterations  t(1e-6) s  t(1e-8) s  final energy  K_I err   K_II err  time s"
    );
    let fmt = |v: Option<f64>| v.map_or_else(|| "—".to_owned(), |s| format!("{s:.4}"));
    for r in runs {
        let Some(last) = r.samples.last() else {
            continue;
        };
        let _ = writeln!(
            t,
            "{:7} {:4} {:15} {:10} {:>10} {:>10} {:12.2e} {:9.1e} {:9.1e} {:7.3}",
            r.scene,
            r.size,
            r.solver,
            last.iteration,
            fmt(time_to(r, 1e-6)),
            fmt(time_to(r, 1e-8)),
            last.energy,
            last.k1,
            last.k2,
            last.seconds
        );
    }
    t
}

fn to_csv(runs: &[Run]) -> String {
    let mut s =
        String::from("scene,size,solver,iteration,seconds,energy_error,k1_error,k2_error\n");
    for r in runs {
        for p in &r.samples {
            let _ = writeln!(
                s,
                "{},{},{},{},{:e},{:e},{:e},{:e}",
                r.scene, r.size, r.solver, p.iteration, p.seconds, p.energy, p.k1, p.k2
            );
        }
    }
    s
}
