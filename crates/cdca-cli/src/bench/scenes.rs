//! The benchmark's scenes: a 0.3 m square plate (E = 4.78 GPa), rollers on
//! the bottom and left sides, one crack.

use cdca::Scene;

/// A benchmark scene family, built for a mesh size `n`.
pub struct BenchScene {
    pub name: &'static str,
    pub build: fn(usize) -> Scene,
    /// Largest size it is run at (the stiff variants stop early: they only
    /// show how the rates degrade).
    pub max_size: usize,
}

pub const SCENES: [BenchScene; 4] = [
    BenchScene {
        name: "open",
        build: open,
        max_size: usize::MAX,
    },
    BenchScene {
        name: "closed",
        build: closed,
        max_size: usize::MAX,
    },
    BenchScene {
        name: "closed-kn1e6",
        build: closed_stiff,
        max_size: 80,
    },
    BenchScene {
        name: "open-nu0.49",
        build: open_incompressible,
        max_size: 80,
    },
];

const STRESS: &str = r#""young":4.78e9,"poisson":0.25,"plane":"stress""#;
const TENSION: &str = r#""top":{"kind":"traction","normal":10e6}"#;
const BIAXIAL: &str =
    r#""top":{"kind":"traction","normal":-10e6},"right":{"kind":"traction","normal":-2e6}"#;
const HORIZONTAL: &str = "[[0.1,0.1525],[0.2,0.1525]]";
const INCLINED: &str = r#"[[0.1,0.1],[0.2,0.2]],"friction":0.5"#;

/// Open horizontal centre crack in tension (+10 MPa on top).
fn open(n: usize) -> Scene {
    scene(n, STRESS, HORIZONTAL, TENSION)
}

/// Closed 45° crack, friction 0.5, top −10 MPa and right −2 MPa.
fn closed(n: usize) -> Scene {
    scene(n, STRESS, INCLINED, BIAXIAL)
}

/// The closed crack with a stiff penalty, `k_N h/E = 1e6`.
fn closed_stiff(n: usize) -> Scene {
    let kn = 1e6 * 4.78e9 * n as f64 / 0.3;
    scene(
        n,
        STRESS,
        &format!(r#"{INCLINED},"normal_stiffness":{kn:e}"#),
        BIAXIAL,
    )
}

/// The open crack, nearly incompressible: ν = 0.49, plane strain.
fn open_incompressible(n: usize) -> Scene {
    scene(
        n,
        r#""young":4.78e9,"poisson":0.49,"plane":"strain""#,
        HORIZONTAL,
        TENSION,
    )
}

fn scene(n: usize, material: &str, crack: &str, loads: &str) -> Scene {
    let json = format!(
        r#"{{"specimen":{{"width":0.3,"height":0.3}},"mesh":{{"nx":{n},"ny":{n}}},
        "material":{{{material}}},
        "cracks":[{{"points":{crack}}}],
        "boundary":{{"bottom":{{"kind":"roller"}},"left":{{"kind":"roller"}},{loads}}}}}"#
    );
    match Scene::from_json(&json) {
        Ok(s) => s,
        Err(e) => panic!("built-in bench scene is invalid (a bug): {e}"),
    }
}
