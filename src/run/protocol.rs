//! The run protocol: what the UI asks of the host that holds the
//! simulation ([`Request`]), and what the host posts back ([`Post`]),
//! whatever carries them (`run::link`: in-process, or a thread of its
//! own). The UI never holds a simulation; it shows the host's posts.

use cdca::scene::{SceneFile, SolverKind};
use cdca::{CriterionCurve, Scene};
use serde::{Deserialize, Serialize};

use web_time::Duration;

use crate::results::field::{FieldKey, FieldSamples};
use crate::results::solution::SolutionView;
use crate::run::RunMode;

/// Least time between two posts while a run goes on without an event
/// (a step, a step's load, a field, the end): the UI repaints when a post
/// comes, at most this often (10 Hz for the residual and progress), not
/// continuously, so that painting takes little from the host on a 2-core
/// machine. (Painted in software, as under Xvfb, a frame of the workbench
/// took about 30 ms of CPU: at 25 frames a second the growth thread had
/// 40% of a core, and Run growth took 2.7 times as long as `cdca grow`.)
pub const POST_INTERVAL: Duration = Duration::from_millis(100);

/// A host away from the UI (a thread, a worker) works in pieces this long
/// between looks at its requests: as long as a frame slice was, so that a
/// request waits at most about this long (plus one call that cannot be
/// split).
pub const PIECE: Duration = Duration::from_millis(12);

/// A run paced by the user (sweeps per call) is watched a call per frame:
/// a host away from the UI waits this long between calls.
pub const PACED_CALL: Duration = Duration::from_millis(16);

/// What the UI asks of the host. Each is handled in the order sent.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub enum Request {
    /// The scene was edited: forget the simulation (kept as the spare
    /// whose discretisation the next build reuses) and check the scene.
    Invalidate(#[serde(with = "scene_file_json")] Box<SceneFile>),
    /// Build a simulation of the scene (nothing solved yet).
    Rebuild(#[serde(with = "scene_file_json")] Box<SceneFile>),
    /// An edit during a drag that the solves follow: check the scene only.
    EditDuringDrag(#[serde(with = "scene_file_json")] Box<SceneFile>),
    /// Start the solve of the dragged scene, if the last one has ended.
    FollowDrag,
    /// The drag ended: its last solve stands as Solve's.
    CheckAfterDrag,
    /// Another scene is opened: forget the last solve's contact verdict.
    ForgetContact,
    /// Keep the run on screen under this id (for Undo), and forget it here.
    TakeRun(u64),
    /// Bring back the run kept under this id, with the edited scene.
    RestoreRun(u64, #[serde(with = "scene_file_json")] Box<SceneFile>),
    /// The UI dropped the run kept under this id.
    ForgetRun(u64),
    /// Solve from `cdca solve`'s start; a grown run on screen is kept
    /// under the id given.
    Solve {
        keep: Option<u64>,
    },
    /// One relaxation sweep.
    Step,
    /// Relax to convergence.
    Relax,
    /// Grow (`one`: one step, then the solve of the grown cracks).
    StartGrowth {
        one: bool,
    },
    Pause,
    /// Sweeps per call (None: as many as fit).
    SetPace(Option<usize>),
    SetAccelerateGrowth(bool),
    /// Calls that would overrun a frame wait for the work between frames
    /// (the in-process host in a browser's frames).
    LeaveLongCalls(bool),
    /// The field the canvas wants (its version is the host's choice).
    WantField(Option<FieldKey>),
    /// The displacement and stress fields as a VTU file, if solved.
    ExportFields,
}

/// What the host posts back.
#[derive(Serialize, Deserialize)]
pub enum Post {
    Shown(Box<Shown>),
    /// The answer to [`Request::ExportFields`].
    Fields(Result<String, String>),
    /// The host stopped (its worker failed), or a message was garbled:
    /// what happened, for the UI to say.
    Failed(String),
}

/// What the UI shows of the host's simulation and run, as of the
/// requests it has handled. (Independent flags, so bools.)
#[allow(clippy::struct_excessive_bools)]
#[derive(Clone, Default, Serialize, Deserialize)]
pub struct Shown {
    /// Requests handled so far.
    pub handled: u64,
    pub view: SolutionView,
    /// The view holds a growth step's solve at the load it records (λ_cr,
    /// or the load increment's λ), before the tips move on.
    pub at_step_load: bool,
    /// A growth run advanced: the replay records this post.
    pub growing: bool,
    /// A field completed since the last post.
    #[serde(with = "field_without_samples")]
    pub field: Option<FieldSamples>,
    /// The fraction of a field being sampled, if one is.
    pub field_progress: Option<f32>,
    /// The host has the field `want_field` asked for, or has nothing to
    /// sample.
    pub field_done: bool,
    pub mode: RunMode,
    /// A run or the check from bonded faces goes on.
    pub checking_second_start: bool,
    /// The simulated scene, when it changed since the last post.
    #[serde(with = "scene_json")]
    pub scene: Option<Scene>,
    /// A simulation exists.
    pub has_sim: bool,
    /// The simulation has growth steps.
    pub grown: bool,
    /// Growth on this simulation is (or will be) set up for.
    pub growth_solver: Option<SolverKind>,
    /// Quadrature points still to integrate.
    pub points_to_integrate: Option<usize>,
    /// Each tip's criterion curve (empty unless the view is solved), when
    /// the view changed since the last post.
    pub curves: Option<Vec<Option<CriterionCurve>>>,
    pub last_solve_seconds: Option<f64>,
    pub last_solve_elements: usize,
    pub last_build_seconds: f64,
    /// An error since the last post (a run that failed, a build).
    pub error: Option<String>,
    /// The host's own time so far, s: handling requests, advancing its
    /// runs, making posts (issue 63: a run's wall time against it says how
    /// long the host waited).
    pub host_seconds: f64,
}

/// Requests and posts as a Web Worker's messages: JSON (`float_roundtrip`:
/// every finite `f64` bit for bit), the field's samples aside as `f32`s
/// (a transferred `Float32Array`: NaN marks a sample off the specimen,
/// which JSON cannot carry). MessagePack, tried first, made the bundle a
/// fifth larger (1.1 MiB of decoders); JSON reuses the scene files' code.
#[cfg(any(test, target_arch = "wasm32"))]
pub mod wire {
    use super::{Post, Request};
    use crate::results::field::Sample;

    /// Floats per sample: σ_xx, σ_yy, τ_xy, then the four corners' u_x, u_y.
    const FLOATS: usize = 11;

    pub fn request_to_json(request: &Request) -> String {
        // plain data: only a map key that is not a string could fail
        serde_json::to_string(request).expect("requests serialise")
    }

    pub fn request_from_json(json: &str) -> Result<Request, String> {
        serde_json::from_str(json).map_err(|e| format!("a garbled request to the solver: {e}"))
    }

    /// `post` as JSON, and its field's samples (if it carries a field).
    pub fn post_to_message(post: &Post) -> (String, Option<Vec<f32>>) {
        let json = serde_json::to_string(post).expect("posts serialise");
        let samples = match post {
            Post::Shown(shown) => shown.field.as_ref().map(|f| {
                f.samples
                    .iter()
                    .flat_map(|s| {
                        let [[a, b], [c, d], [e, f], [g, h]] = s.corner_disp;
                        let [xx, yy, xy] = s.stress;
                        [xx, yy, xy, a, b, c, d, e, f, g, h]
                    })
                    .map(|v| v as f32)
                    .collect()
            }),
            _ => None,
        };
        (json, samples)
    }

    /// The post [`post_to_message`] wrote.
    pub fn post_from_message(json: &str, samples: Option<&[f32]>) -> Result<Post, String> {
        let mut post: Post =
            serde_json::from_str(json).map_err(|e| format!("a garbled post of the solver: {e}"))?;
        if let (Post::Shown(shown), Some(samples)) = (&mut post, samples)
            && let Some(field) = shown.field.as_mut()
        {
            let f = |c: &[f32], i: usize| f64::from(c[i]);
            field.samples = samples
                .chunks_exact(FLOATS)
                .map(|c| Sample {
                    stress: [f(c, 0), f(c, 1), f(c, 2)],
                    corner_disp: [
                        [f(c, 3), f(c, 4)],
                        [f(c, 5), f(c, 6)],
                        [f(c, 7), f(c, 8)],
                        [f(c, 9), f(c, 10)],
                    ],
                })
                .collect();
        }
        Ok(post)
    }
}

/// A field without its samples (they travel aside: [`wire`]).
mod field_without_samples {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    use crate::results::field::{FieldKey, FieldSamples};

    #[allow(clippy::ref_option)] // serde's `with` passes `&Option<T>`
    pub fn serialize<S: Serializer>(field: &Option<FieldSamples>, s: S) -> Result<S::Ok, S::Error> {
        field.as_ref().map(|f| (f.key, f.load_factor)).serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<FieldSamples>, D::Error> {
        Ok(
            Option::<(FieldKey, f64)>::deserialize(d)?.map(|(key, load_factor)| FieldSamples {
                key,
                load_factor,
                samples: Vec::new(),
            }),
        )
    }
}

/// A scene file as its JSON (the scene files' own code), inside a request.
mod scene_file_json {
    use cdca::scene::SceneFile;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[allow(clippy::borrowed_box)] // serde's `with` passes `&Box<T>`
    pub fn serialize<S: Serializer>(scene: &Box<SceneFile>, s: S) -> Result<S::Ok, S::Error> {
        scene
            .to_json()
            .map_err(serde::ser::Error::custom)?
            .serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Box<SceneFile>, D::Error> {
        let json = String::deserialize(d)?;
        SceneFile::from_json(&json)
            .map(Box::new)
            .map_err(serde::de::Error::custom)
    }
}

/// The simulated scene as its scene file's JSON.
mod scene_json {
    use cdca::Scene;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[allow(clippy::ref_option)] // serde's `with` passes `&Option<T>`
    pub fn serialize<S: Serializer>(scene: &Option<Scene>, s: S) -> Result<S::Ok, S::Error> {
        let json = match scene {
            Some(scene) => Some(scene.to_json().map_err(serde::ser::Error::custom)?),
            None => None,
        };
        json.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Scene>, D::Error> {
        Option::<String>::deserialize(d)?
            .map(|json| Scene::from_json(&json).map_err(serde::de::Error::custom))
            .transpose()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::field::{FieldKey, FieldSamples, Sample};

    /// A post goes through the wire as it was: the view and the scene bit
    /// for bit, the field's samples as `f32`s (NaN off the specimen), and
    /// a request with its scene file.
    #[test]
    fn a_post_crosses_the_wire() {
        let scene = Scene::try_from(crate::files::scenes::default_scene()).expect("valid");
        let view = SolutionView {
            version: 7,
            load_factor: 0.1 + 0.2,
            ..SolutionView::default()
        };
        let key = FieldKey {
            version: 7,
            cols: 2,
            rows: 1,
            width: 0.05,
            height: 0.1,
            with_displacement: true,
        };
        let sample = |v: f64| Sample {
            stress: [v, -v, f64::NAN],
            corner_disp: [[v * 1e-12; 2]; 4],
        };
        let shown = Shown {
            handled: 3,
            view,
            field: Some(FieldSamples {
                key,
                load_factor: 1.0 / 3.0,
                samples: vec![sample(1e7 / 3.0), sample(-2.5e-9)],
            }),
            scene: Some(scene.clone()),
            curves: Some(vec![None, Some(CriterionCurve::default())]),
            ..Shown::default()
        };
        let (json, samples) = wire::post_to_message(&Post::Shown(Box::new(shown.clone())));
        let back = wire::post_from_message(&json, samples.as_deref()).expect("decodes");
        let Post::Shown(back) = back else {
            panic!("a Shown post")
        };
        assert_eq!(back.handled, 3);
        assert_eq!(back.view.load_factor.to_bits(), (0.1f64 + 0.2).to_bits());
        let (a, b) = (shown.field.unwrap(), back.field.expect("field"));
        assert_eq!(a.key, b.key);
        assert_eq!(a.load_factor.to_bits(), b.load_factor.to_bits());
        assert_eq!(a.samples.len(), b.samples.len());
        for (a, b) in a.samples.iter().zip(&b.samples) {
            // f32: 7 significant digits
            assert!((a.stress[0] - b.stress[0]).abs() <= 1e-7 * a.stress[0].abs());
            assert!(
                (a.corner_disp[3][1] - b.corner_disp[3][1]).abs()
                    <= 1e-7 * a.corner_disp[3][1].abs()
            );
            assert!(b.stress[2].is_nan());
        }
        assert_eq!(
            back.scene.expect("scene").to_json().ok(),
            scene.to_json().ok()
        );
        assert_eq!(back.curves, shown.curves);
        let request = Request::RestoreRun(4, Box::new(crate::files::scenes::default_scene()));
        let back = wire::request_from_json(&wire::request_to_json(&request)).expect("decodes");
        assert!(
            matches!(back, Request::RestoreRun(4, s) if *s == crate::files::scenes::default_scene())
        );
    }
}
