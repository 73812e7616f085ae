//! Study files in the workbench (the Study tab's *Study file* mode): the
//! files `cdca study` runs (`cdca::study`), the bundled ones offered by
//! name. A run takes every point's first step, or grows the first N points
//! to the end, one point at a time within the frame budget. Its rows are
//! the CLI's rows (seconds aside) and its figures a map per layout over the
//! first two numeric axes (or a plot over one).

use cdca::report::Outcome;
use cdca::study::{Input, Point, Row, RunKind, Study};
use cdca::{Simulation, SolveError};
use web_time::Instant;

use crate::plots::figure::Figure;
use crate::run::pacer::Pacer;
use crate::run::task::{Progress, Task};
pub use crate::study::map::MapColour;

/// A study file shipped with the workbench.
#[derive(Clone, Copy, Debug)]
pub struct BundledStudy {
    pub title: &'static str,
    /// The file's name in `assets/studies/`.
    pub file: &'static str,
    pub json: &'static str,
}

macro_rules! bundled {
    ($title:literal, $file:literal) => {
        BundledStudy {
            title: $title,
            file: $file,
            json: include_str!(concat!("../../assets/studies/", $file)),
        }
    };
}

/// Every bundled study file, the one to start with first.
pub const BUNDLED_STUDIES: &[BundledStudy] = &[
    bundled!("First steps of one flaw", "first_steps.json"),
    bundled!(
        "Coplanar and stepped pairs over angle and bridge",
        "pair_maps.json"
    ),
    bundled!("Held-out flaw pairs", "held_out_pairs.json"),
    bundled!("Flaw range", "flaw_range.json"),
    bundled!("Random layouts, seed 7", "random_layouts.json"),
];

/// Native seconds of one growth step per element (the held-out pairs, 100 ×
/// 100: 0.14 s a step on this project's 2-core machine).
pub const SECONDS_PER_ELEMENT_STEP: f64 = 1.4e-5;

/// Native seconds of a point's first step per element: the simulation
/// built, the uncracked specimen solved, and the λ search's trials (`cdca
/// study` on `first_steps.json`, 16 first steps of 60 × 60 on one core:
/// 3.9 s, 67 µs per element; the Study tab estimated 0.8 s for a run that
/// took 5.6 s in the browser with the later steps' figure).
pub const SECONDS_PER_ELEMENT_FIRST_STEP: f64 = 7e-5;

/// How much slower the browser's WebAssembly runs the solver (frame-time
/// measurements of Run growth, docs/browser.md: about twice).
pub const BROWSER_FACTOR: f64 = 2.0;

/// Steps assumed for a run grown to the end (the held-out pairs take 30 to
/// 60; a scene's `growth.max_steps` caps it).
pub const TYPICAL_STEPS: usize = 40;

/// A study file, read and checked.
#[derive(Clone, Debug)]
pub struct LoadedStudy {
    /// Where it came from (a file's or a bundled study's name).
    pub source: String,
    pub study: Study,
}

impl LoadedStudy {
    /// Reads a study file's text. The scene it names is one of the bundled
    /// scenes, found by its file name (`../scenes/specimen_single_flaw.json`):
    /// the workbench reads no other file for it, so a study of another
    /// scene holds that scene inline.
    pub fn parse(source: &str, text: &str) -> Result<Self, String> {
        let study = Study::parse(text, |path| {
            let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
            crate::files::scenes::BUNDLED
                .iter()
                .find(|b| b.file == name)
                .map(|b| b.json.to_owned())
                .ok_or_else(|| {
                    format!(
                        "the workbench has no scene `{name}` of its own: give the study its \
                         scene inline (\"scene\": {{…}}) or name a bundled scene"
                    )
                })
        })
        .map_err(|e| format!("{source}: {e}"))?;
        Ok(Self {
            source: source.to_owned(),
            study,
        })
    }
}

/// How the Study tab runs a study file (edited in place by the panel).
#[derive(Clone, Debug, PartialEq)]
pub struct StudyFileSetup {
    /// The tab shows study files (else the one-field sweep).
    pub use_file: bool,
    /// Every point's first step (else the first `cap` points grown to the
    /// end).
    pub first_steps: bool,
    pub cap: usize,
    pub colour: MapColour,
    /// The run's rows are shown as a table (else its maps).
    pub table: bool,
}

impl Default for StudyFileSetup {
    fn default() -> Self {
        Self {
            use_file: false,
            first_steps: true,
            cap: 8,
            colour: MapColour::Cracks,
            table: false,
        }
    }
}

impl StudyFileSetup {
    /// The points a run of `study` takes.
    pub fn points<'a>(&self, study: &'a Study) -> &'a [Point] {
        let all = study.points();
        if self.first_steps {
            all
        } else {
            &all[..self.cap.clamp(1, all.len().max(1)).min(all.len())]
        }
    }

    /// A rough time of the run, s, before it starts: points × steps ×
    /// elements × [`SECONDS_PER_ELEMENT_STEP`] (× [`BROWSER_FACTOR`] in
    /// the browser), steps 1 for first steps, else the scene's cap up to
    /// [`TYPICAL_STEPS`].
    pub fn estimate_seconds(&self, study: &Study) -> f64 {
        let points = self.points(study);
        let Some(scene) = points.first().and_then(|p| study.scene(p).ok()) else {
            return 0.0;
        };
        let elements = (scene.mesh.nx * scene.mesh.ny) as f64;
        let later_steps = if self.first_steps {
            0
        } else {
            scene.growth.max_steps.min(TYPICAL_STEPS).saturating_sub(1)
        };
        let browser = if crate::files::io::IN_BROWSER {
            BROWSER_FACTOR
        } else {
            1.0
        };
        let per_point =
            SECONDS_PER_ELEMENT_FIRST_STEP + later_steps as f64 * SECONDS_PER_ELEMENT_STEP;
        points.len() as f64 * elements * per_point * browser
    }
}

/// The point being grown.
struct Current {
    sim: Simulation,
    drawn: usize,
    start: Instant,
}

/// A run of a study file, running or finished.
pub struct FileStudy {
    pub source: String,
    /// The study as run (with `run: first_step` for first steps: its hash
    /// then differs from the file's, so its rows are not the file's table).
    pub study: Study,
    points: Vec<Point>,
    pub rows: Vec<Row>,
    current: Option<Current>,
    pacer: Pacer,
    cancelled: bool,
}

impl FileStudy {
    pub fn new(loaded: &LoadedStudy, setup: &StudyFileSetup) -> Self {
        let study = if setup.first_steps {
            loaded.study.clone().with_run(RunKind::FirstStep)
        } else {
            loaded.study.clone()
        };
        let points = setup.points(&study).to_vec();
        Self {
            source: loaded.source.clone(),
            study,
            points,
            rows: Vec::new(),
            current: None,
            pacer: Pacer::default(),
            cancelled: false,
        }
    }

    /// Points this run takes.
    pub fn planned(&self) -> usize {
        self.points.len()
    }

    pub fn finished(&self) -> bool {
        self.cancelled || self.rows.len() >= self.points.len()
    }

    pub fn cancelled(&self) -> bool {
        self.cancelled
    }

    /// Stops after the points done so far.
    pub fn cancel(&mut self) {
        self.cancelled = true;
        self.current = None;
    }

    /// The time the points left will take at the mean of those done, s
    /// (`None` before the first is done, and once the run has ended).
    pub fn seconds_left(&self) -> Option<f64> {
        if self.rows.is_empty() || self.finished() {
            return None;
        }
        let mean = self.rows.iter().map(|r| r.seconds).sum::<f64>() / self.rows.len() as f64;
        Some(mean * (self.points.len() - self.rows.len()) as f64)
    }

    pub fn progress(&self) -> f32 {
        self.rows.len() as f32 / self.points.len().max(1) as f32
    }

    /// The table as `cdca study` writes it: the header, then the rows.
    pub fn to_csv(&self) -> String {
        let mut out = self.study.header();
        for row in &self.rows {
            out.push_str(&row.csv(self.study.short_hash()));
        }
        out
    }

    /// Starts the next point, or records it at once when its scene or
    /// simulation is refused.
    fn start(&mut self, point: &Point) {
        let start = Instant::now();
        let refused = match self.study.scene(point) {
            Err(e) => Row::invalid(point, &e.to_string()),
            Ok(scene) => {
                let drawn = scene.cracks.len();
                match Simulation::new(scene) {
                    Ok(sim) => {
                        self.current = Some(Current { sim, drawn, start });
                        return;
                    }
                    Err(SolveError::Scene(e)) => Row::invalid(point, &e.to_string()),
                    Err(e) => Row::failed(point, &e.to_string()),
                }
            }
        };
        self.rows.push(Row {
            seconds: start.elapsed().as_secs_f64(),
            ..refused
        });
    }

    /// The map (two numeric axes: one per layout) or the plot (one axis).
    pub fn figures(&self, colour_by: MapColour) -> Vec<Figure> {
        crate::study::map::figures(&self.study, &self.rows, colour_by)
    }
}

impl Task for FileStudy {
    /// Advances the run until about `deadline`: starts the next point, then
    /// grows it in resumable chunks (sized by the pacer) until its run
    /// ends, and records its row: the report of the same steps
    /// `Simulation::grow_to_end` takes (`advance_growth` slices them).
    fn advance(&mut self, deadline: Instant) -> Result<Progress, String> {
        while !self.finished() {
            let begin = Instant::now();
            if self.current.is_none() {
                let point = self.points[self.rows.len()].clone();
                self.start(&point);
                continue;
            }
            let Some(cur) = self.current.as_mut() else {
                continue;
            };
            let n = self.pacer.sweeps();
            let ended = match cur.sim.advance_growth(n) {
                Err(e) => Some(cur.sim.grow_report(Outcome::Error, Some(&e))),
                Ok(_) => cur
                    .sim
                    .growth_finished()
                    .map(|o| cur.sim.grow_report(o, None)),
            };
            if let Some(report) = ended {
                let point = &self.points[self.rows.len()];
                let row = Row::of_report(point, &report, cur.drawn);
                let seconds = cur.start.elapsed().as_secs_f64();
                self.rows.push(Row { seconds, ..row });
                self.current = None;
            }
            if !self.pacer.another_fits(begin, n, deadline) {
                break;
            }
        }
        Ok(if self.finished() {
            Progress::Finished
        } else {
            Progress::Working
        })
    }
}

/// A point's value of an axis as the table shows it.
/// A point's input as the table shows it: a number in its axis's unit
/// (`factor` from SI), a layout's JSON cut to 24 characters.
pub fn input_text(input: &Input, factor: f64) -> String {
    match input {
        Input::Number(x) => crate::style::units::compact(x * factor),
        Input::Json(_) => {
            let text = input.csv();
            if text.chars().count() > 24 {
                format!("{}…", text.chars().take(23).collect::<String>())
            } else {
                text
            }
        }
    }
}
