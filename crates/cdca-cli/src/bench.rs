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

use cdca::contact::status::ContactParams;
use cdca::discretisation::assembly::ElementBlock;
use cdca::discretisation::xfem::Xfem;
use cdca::race::{RaceSystem, Reference, Sample};
use cdca::scene::{Ordering, Scene, SolverKind, SolverSpec};
use cdca::solvers::automaton::sor_omega;
use cdca::solvers::relaxation::Relaxation;
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
    // contact states settled by the direct solver; the system to race on a
    // fresh discretisation, so that the timed direct solve pays for its
    // symbolic factorisation too
    let RaceSystem { x, blocks, f } = RaceSystem::settle(scene, ContactParams::default())?;
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
        let omega = omega.unwrap_or(sor_omega(n));
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
    blocks: &'a [ElementBlock],
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
    cdca::csv::race(runs.iter().map(|r| cdca::csv::RaceRun {
        scene: r.scene,
        size: r.size,
        solver: r.solver,
        samples: &r.samples,
    }))
}
