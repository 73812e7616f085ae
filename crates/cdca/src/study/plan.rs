//! [`Study`]: a study file checked, its points made, and each point's
//! scene.

use serde_json::Value;
use sha2::{Digest, Sha256};
use web_time::Instant;

use super::axis::{Axis, FlawsInput, Input, MAX_POINTS, Point, Target};
use super::error::StudyError;
use super::file::{Combine, RunKind, StudyFile};
use super::flaws::{Flaws, Layout};
use super::random::SplitMix64;
use super::row::Row;
use crate::error::{SceneError, SolveError};
use crate::scene::{Scene, SceneFile};
use crate::simulation::Simulation;

/// Hex digits of the study's hash in every row (64 bits).
pub const SHORT_HASH: usize = 16;

/// A checked study: the base scene with the file's `set`, the flaws
/// generator's values, the axes and every point (random ones drawn).
#[derive(Clone, Debug)]
pub struct Study {
    pub name: String,
    pub description: String,
    /// SHA-256 of the study file's bytes followed by those of the scene
    /// file it names (if it names one), hex: `cat STUDY SCENE | sha256sum`.
    pub hash: String,
    pub axes: Vec<Axis>,
    pub combine: Combine,
    pub run: RunKind,
    /// The base scene (without cracks when the flaws generator draws them).
    base: Scene,
    flaws: Option<Flaws>,
    points: Vec<Point>,
}

impl Study {
    /// Reads a study file's text. `read_scene` gives the text of the scene
    /// file the study names (its path as written in the study), or why it
    /// cannot: the library has no file system.
    pub fn parse(
        text: &str,
        read_scene: impl FnOnce(&str) -> Result<String, String>,
    ) -> Result<Self, StudyError> {
        let file = StudyFile::from_json(text)?;
        let mut hasher = Sha256::new();
        hasher.update(text.as_bytes());
        let base = match &file.scene {
            Value::String(path) => {
                let scene_text = read_scene(path).map_err(|reason| StudyError::Scene {
                    path: path.clone(),
                    reason,
                })?;
                hasher.update(scene_text.as_bytes());
                Scene::from_json(&scene_text).map_err(|e| StudyError::Scene {
                    path: path.clone(),
                    reason: e.to_string(),
                })?
            }
            Value::Object(_) => serde_json::from_value::<SceneFile>(file.scene.clone())
                .map_err(|e| SceneError::Parse(e.to_string()))
                .and_then(Scene::try_from)
                .map_err(|e| StudyError::field("scene", e.to_string()))?,
            _ => {
                return Err(StudyError::field(
                    "scene",
                    "must be a scene file's path or a scene (an object)",
                ));
            }
        };
        let hash = hex(&hasher.finalize());
        Self::new(file, &base, hash)
    }

    fn new(file: StudyFile, base: &Scene, hash: String) -> Result<Self, StudyError> {
        let generated =
            file.flaws.is_some() || file.axes.iter().any(|a| a.field.starts_with("flaws."));
        let sets: Vec<(&str, Value)> = file
            .set
            .iter()
            .map(|(p, v)| (p.as_str(), v.clone()))
            .collect();
        if let Some((path, _)) = sets.iter().find(|(p, _)| generated && is_cracks(p)) {
            return Err(StudyError::field(
                format!("set.{path}"),
                "the flaws generator draws the cracks (set `flaws` instead)",
            ));
        }
        let base = base
            .with_values(&sets)
            .and_then(|mut f| {
                if generated {
                    f.cracks.clear();
                }
                Scene::try_from(f)
            })
            .map_err(|e| StudyError::field("set", e.to_string()))?;
        let flaws = generated.then(|| {
            let spec = file.flaws.clone().unwrap_or_default();
            let d = Flaws::default();
            Flaws {
                layout: spec.layout.unwrap_or(d.layout),
                length: spec.length.unwrap_or(d.length),
                angle_deg: spec.angle_deg.unwrap_or(d.angle_deg),
                friction: spec.friction.unwrap_or(d.friction),
                bridge_over_flaw: spec.bridge_over_flaw.unwrap_or(d.bridge_over_flaw),
                offset_elements: spec.offset_elements.unwrap_or(d.offset_elements),
            }
        });
        if file.axes.is_empty() {
            return Err(StudyError::field("axes", "a study needs at least one axis"));
        }
        let mut rng = file.seed.map(SplitMix64::new);
        let mut axes: Vec<Axis> = Vec::new();
        for (k, spec) in file.axes.iter().enumerate() {
            let axis = Axis::new(spec, k, file.combine, rng.as_mut())?;
            if let Some(j) = axes.iter().position(|a| a.field == axis.field) {
                return Err(StudyError::field(
                    format!("axes[{k}].field"),
                    format!("`{}` is axis {j}'s field too", axis.field),
                ));
            }
            if let Target::Scene(path) = &axis.target {
                if generated && is_cracks(path) {
                    return Err(StudyError::field(
                        format!("axes[{k}].field"),
                        format!("`{path}`: the flaws generator draws the cracks (vary `flaws.…`)"),
                    ));
                }
                base.has_field(path, axis.is_numeric())
                    .map_err(|e| StudyError::field(format!("axes[{k}].field"), e.to_string()))?;
            }
            axes.push(axis);
        }
        let points = points(&file, &axes, rng.as_mut())?;
        Ok(Self {
            name: file.name,
            description: file.description,
            hash,
            axes,
            combine: file.combine,
            run: file.run,
            base,
            flaws,
            points,
        })
    }

    /// The same study run as `run` (the workbench runs a study's first
    /// steps in the browser). Its hash changes with it (the hash of the
    /// file's hash and the run's name), so that its rows are not taken for
    /// the file's.
    #[must_use]
    pub fn with_run(mut self, run: RunKind) -> Self {
        if run != self.run {
            let name = match run {
                RunKind::Grow => "grow",
                RunKind::FirstStep => "first_step",
            };
            self.hash = hex(&Sha256::digest(format!("{} run {name}", self.hash)));
            self.run = run;
        }
        self
    }

    /// Every point, in order (ids 1, 2, …).
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// Point `id` (1-based).
    pub fn point(&self, id: usize) -> Option<&Point> {
        id.checked_sub(1).and_then(|i| self.points.get(i))
    }

    /// The points of shard `i` of `n` (1-based): every n-th, from the i-th.
    pub fn shard(&self, i: usize, n: usize) -> impl Iterator<Item = &Point> {
        self.points
            .iter()
            .filter(move |p| n > 0 && (p.id - 1) % n == i.wrapping_sub(1))
    }

    /// The first [`SHORT_HASH`] hex digits of the hash, written in every
    /// row.
    pub fn short_hash(&self) -> &str {
        &self.hash[..SHORT_HASH.min(self.hash.len())]
    }

    /// The scene of `point`: the base scene with the point's values (all
    /// set at once, then checked), its flaws drawn in the resulting
    /// specimen, and for `run: first_step` `growth.max_steps = 1`. A
    /// value or a geometry the scene refuses is the error (an `invalid`
    /// row).
    pub fn scene(&self, point: &Point) -> Result<Scene, SceneError> {
        let mut values: Vec<(&str, Value)> = Vec::new();
        let mut flaws = self.flaws;
        for (axis, input) in self.axes.iter().zip(&point.inputs) {
            match (&axis.target, flaws.as_mut()) {
                (Target::Scene(path), _) => values.push((path, input.to_json())),
                (Target::Flaws(which), Some(f)) => set_flaws_input(f, *which, input),
                (Target::Flaws(_), None) => {}
            }
        }
        if self.run == RunKind::FirstStep {
            values.push(("growth.max_steps", Value::from(1)));
        }
        let mut file = self.base.with_values(&values)?;
        if let Some(f) = flaws {
            let h = file.element_size();
            file.cracks = f.cracks(file.specimen.width, file.specimen.height, h);
        }
        Scene::try_from(file)
    }

    /// The CSV header of this study's table ([`Row::csv`]).
    pub fn header(&self) -> String {
        let fields: Vec<String> = self
            .axes
            .iter()
            .map(|a| crate::csv::field(&a.field))
            .collect();
        super::row::header(&fields)
    }

    /// Runs `point`: its scene's growth to the end
    /// ([`Simulation::grow_to_end`], as `cdca grow`), or its refusal, as a
    /// row timed from the scene's making to the report.
    pub fn run_point(&self, point: &Point) -> Row {
        let start = Instant::now();
        let row = match self.scene(point) {
            Err(e) => Row::invalid(point, &e.to_string()),
            Ok(scene) => {
                let drawn = scene.cracks.len();
                match Simulation::new(scene) {
                    Err(SolveError::Scene(e)) => Row::invalid(point, &e.to_string()),
                    Err(e) => Row::failed(point, &e.to_string()),
                    Ok(mut sim) => Row::of_report(point, &sim.grow_to_end().0, drawn),
                }
            }
        };
        Row {
            seconds: start.elapsed().as_secs_f64(),
            ..row
        }
    }
}

/// The points of a checked study: a grid, a zip or a joint random sample.
fn points(
    file: &StudyFile,
    axes: &[Axis],
    rng: Option<&mut SplitMix64>,
) -> Result<Vec<Point>, StudyError> {
    if file.combine != Combine::Random && file.count.is_some() {
        return Err(StudyError::field(
            "count",
            "only a joint random sample (`combine: \"random\"`) has a count",
        ));
    }
    let lists: Vec<&[Input]> = axes.iter().filter_map(Axis::values).collect();
    let inputs: Vec<Vec<Input>> = match file.combine {
        Combine::Grid => {
            let total = lists
                .iter()
                .try_fold(1_usize, |n, l| n.checked_mul(l.len()))
                .filter(|n| *n <= MAX_POINTS)
                .ok_or_else(|| {
                    StudyError::field(
                        "axes",
                        format!("the grid has more than {MAX_POINTS} points"),
                    )
                })?;
            (0..total)
                .map(|mut i| {
                    // the last axis varies fastest
                    let mut point = vec![Input::Number(0.0); lists.len()];
                    for (slot, l) in point.iter_mut().zip(&lists).rev() {
                        *slot = l[i % l.len()].clone();
                        i /= l.len();
                    }
                    point
                })
                .collect()
        }
        Combine::Zip => {
            let n = lists[0].len();
            if let Some(k) = lists.iter().position(|l| l.len() != n) {
                return Err(StudyError::field(
                    format!("axes[{k}]"),
                    format!(
                        "{} values, axis 0 has {n}: zipped axes need as many values each",
                        lists[k].len()
                    ),
                ));
            }
            (0..n)
                .map(|i| lists.iter().map(|l| l[i].clone()).collect())
                .collect()
        }
        Combine::Random => {
            let count = match file.count {
                Some(n) if (1..=MAX_POINTS).contains(&n) => n,
                other => {
                    return Err(StudyError::field(
                        "count",
                        format!(
                            "{}: a joint random sample needs a count of 1 to {MAX_POINTS}",
                            other.map_or("missing".to_owned(), |n| n.to_string())
                        ),
                    ));
                }
            };
            let rng = rng.ok_or_else(|| {
                StudyError::field("seed", "a joint random sample needs the file's `seed`")
            })?;
            (0..count)
                .map(|_| axes.iter().map(|a| a.draw(rng)).collect())
                .collect()
        }
    };
    Ok(inputs
        .into_iter()
        .enumerate()
        .map(|(i, inputs)| Point { id: i + 1, inputs })
        .collect())
}

fn set_flaws_input(f: &mut Flaws, which: FlawsInput, input: &Input) {
    match (which, input) {
        (FlawsInput::Layout, Input::Json(Value::String(name))) => {
            if let Some(l) = Layout::from_name(name) {
                f.layout = l;
            }
        }
        (FlawsInput::Length, Input::Number(x)) => f.length = *x,
        (FlawsInput::AngleDeg, Input::Number(x)) => f.angle_deg = *x,
        (FlawsInput::Friction, Input::Number(x)) => f.friction = *x,
        (FlawsInput::BridgeOverFlaw, Input::Number(x)) => f.bridge_over_flaw = *x,
        // checked when the axis was read (`Axis::new`)
        _ => {}
    }
}

/// Whether a dotted path is a scene's cracks or inside them.
fn is_cracks(path: &str) -> bool {
    path == "cracks" || path.starts_with("cracks.")
}

fn hex(bytes: &[u8]) -> String {
    use std::fmt::Write as _;
    bytes.iter().fold(String::new(), |mut s, b| {
        let _ = write!(s, "{b:02x}");
        s
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A coarse plate with one crack (a valid scene).
    const SCENE: &str = r#"{"specimen":{"width":0.03,"height":0.03},"mesh":{"nx":100,"ny":100},
        "material":{"young":4.78e9},
        "cracks":[{"points":[[0.012,0.012],[0.018,0.018]],"friction":0.5}],
        "boundary":{"bottom":{"kind":"roller"},"top":{"kind":"traction","normal":-1e8},
          "points":[{"at":[0,0],"fix":"x"}]},
        "growth":{"control":"critical","max_steps":3}}"#;

    fn study(body: &str) -> Result<Study, StudyError> {
        let text = format!(r#"{{"scene":"plate.json",{body}}}"#);
        Study::parse(&text, |path| {
            assert_eq!(path, "plate.json");
            Ok(SCENE.to_owned())
        })
    }

    fn numbers(p: &Point) -> Vec<f64> {
        p.inputs.iter().filter_map(Input::as_f64).collect()
    }

    /// A grid varies the last axis fastest; a zip pairs the k-th values;
    /// a range includes its ends.
    #[test]
    fn grids_and_zips_make_their_points() {
        let axes = r#""axes":[{"field":"cracks.0.friction","values":[0.1,0.2]},
            {"field":"criterion.r0","range":{"from":1e-4,"to":3e-4,"count":3}}]"#;
        let grid = study(axes).expect("valid");
        let p: Vec<Vec<f64>> = grid.points().iter().map(numbers).collect();
        assert_eq!(p.len(), 6);
        assert_eq!(p[0], [0.1, 1e-4]);
        assert_eq!(p[1], [0.1, 2e-4]);
        assert_eq!(p[3], [0.2, 1e-4]);
        assert_eq!(grid.points()[5].id, 6);
        let zip = study(
            r#""axes":[{"field":"cracks.0.friction","values":[0.1,0.2,0.3]},
            {"field":"criterion.r0","range":{"from":1e-4,"to":3e-4,"count":3}}],"combine":"zip""#,
        )
        .expect("valid");
        let p: Vec<Vec<f64>> = zip.points().iter().map(numbers).collect();
        assert_eq!(p, [[0.1, 1e-4], [0.2, 2e-4], [0.3, 3e-4]]);
        // the point's scene has its values
        let s = zip.scene(&zip.points()[1]).expect("valid");
        assert_eq!((s.cracks[0].friction, s.criterion.r0), (0.2, Some(2e-4)));
        assert_eq!(grid.header().lines().next().map(|h| h.starts_with(
            "point,study,cracks.0.friction,criterion.r0,outcome,steps,"
        )), Some(true));
        // shards take every n-th point
        let ids: Vec<usize> = grid.shard(2, 4).map(|p| p.id).collect();
        assert_eq!(ids, [2, 6]);
    }

    /// Random points are fixed by the seed: the same file draws the same
    /// points, another seed others; listed axes give one of their values.
    #[test]
    fn a_random_sample_is_fixed_by_the_seed() {
        let body = |seed: u64| {
            format!(
                r#""axes":[{{"field":"cracks.0.friction","random":{{"from":0,"to":0.6}}}},
                {{"field":"growth.max_steps","values":[1,2]}}],
                "combine":"random","count":20,"seed":{seed}"#
            )
        };
        let a = study(&body(7)).expect("valid");
        let b = study(&body(7)).expect("valid");
        let c = study(&body(8)).expect("valid");
        assert_eq!(a.points(), b.points());
        assert_ne!(a.points(), c.points());
        assert_eq!(a.hash, b.hash);
        assert_ne!(a.hash, c.hash);
        assert_eq!(a.points().len(), 20);
        assert!(a.points().iter().all(|p| {
            let v = numbers(p);
            (0.0..0.6).contains(&v[0]) && (v[1] == 1.0 || v[1] == 2.0)
        }));
        // an integer field takes the listed whole numbers
        let s = a.scene(&a.points()[0]).expect("valid");
        assert!(s.growth.max_steps == 1 || s.growth.max_steps == 2);
    }

    /// Bad files name the field: an unknown field, an empty range, a path
    /// that is not a field, zipped axes of different lengths, a random
    /// sample without a seed.
    #[test]
    fn bad_files_name_the_field() {
        let cases = [
            (r#""axes":[],"colour":1"#, "unknown field `colour`"),
            (
                r#""axes":[{"field":"criterion.r0","range":{"from":1,"to":2,"count":0}}]"#,
                "study field `axes[0].range.count`: 0: an empty range",
            ),
            (
                r#""axes":[{"field":"cracks.0.frictoin","values":[1]}]"#,
                "study field `axes[0].field`: scene field `cracks.0.frictoin`",
            ),
            (
                r#""axes":[{"field":"criterion.r0","values":[1]},{"field":"mesh.nx","values":[1,2]}],"combine":"zip""#,
                "study field `axes[1]`: 2 values, axis 0 has 1",
            ),
            (
                r#""axes":[{"field":"criterion.r0","values":[1]}],"combine":"random","count":3"#,
                "study field `seed`",
            ),
            (
                r#""axes":[{"field":"flaws.layout","values":["stepped","diagonal"]}]"#,
                "study field `axes[0].values[1]`: \"diagonal\": must be one of single, coplanar",
            ),
            (
                r#""axes":[]"#,
                "study field `axes`: a study needs at least one axis",
            ),
        ];
        for (body, needle) in cases {
            let e = study(body).expect_err(body);
            assert!(e.to_string().contains(needle), "{body}: {e}");
        }
        let e = Study::parse(r#"{"scene":"x.json","axes":[]}"#, |_| {
            Err("not found".into())
        })
        .expect_err("no scene");
        assert_eq!(e.to_string(), "scene file `x.json` of the study: not found");
    }

    /// The held-out pairs as the script drew them: two of its points
    /// (Python's numbers, printed with `repr`) give the script's cracks to
    /// the bit.
    #[test]
    fn flaws_are_drawn_to_the_bits_of_the_held_out_script() {
        let s = study(
            r#""axes":[
                {"field":"flaws.layout","values":["overlapping_mirrored","stepped"]},
                {"field":"flaws.length","values":[0.0031234572866122353,0.0035486946056438222]},
                {"field":"flaws.angle_deg","values":[47.43469411537059,53.76352375964177]},
                {"field":"flaws.friction","values":[0.46,0.45]},
                {"field":"flaws.bridge_over_flaw","values":[1.0145173860832282,1.2190270743700058]}],
              "combine":"zip""#,
        )
        .expect("valid");
        let expected = [
            [
                [
                    [0.014461206435057954, 0.012515617315041562],
                    [0.016574007020044537, 0.014816064903962343],
                ],
                [
                    [0.013425992979955463, 0.015183935096037656],
                    [0.015538793564942045, 0.017484382684958437],
                ],
            ],
            [
                [
                    [0.01328514518762266, 0.01000930941107676],
                    [0.015382847000061128, 0.0128716302369483],
                ],
                [
                    [0.01461715299993887, 0.0171283697630517],
                    [0.01671485481237734, 0.01999069058892324],
                ],
            ],
        ];
        for (p, want) in s.points().iter().zip(expected) {
            let scene = s.scene(p).expect("valid");
            let got: Vec<Vec<[f64; 2]>> = scene
                .cracks
                .iter()
                .map(|c| c.points.clone().unwrap_or_default())
                .collect();
            assert_eq!(got, want.map(|c| c.to_vec()).to_vec());
        }
        assert_eq!(
            s.scene(&s.points()[1]).map(|x| x.cracks[1].friction),
            Ok(0.45)
        );
    }
}
