//! A scene as a link: its JSON deflated and written in URL-safe base64 in
//! the page address's fragment, `#scene=…` (the fragment never reaches the
//! server, and a 30 mm specimen with one flaw takes about 600 characters).
//! A teacher sends one link and the class opens the same crack layout. The
//! browser wrapper reads and writes `location.hash`; the native workbench
//! opens a link with `--link`.
//!
//! A link shares the scene as drawn (the Scene panel's), never the run: a
//! run's end state in a link made its grown cracks drawn ones and lost the
//! story, replay and plots (a 20.7k-character link), while the scene
//! opens and runs to the same end. The address keeps a link only while it
//! shows the scene being edited ([`Address`]): an edit, another scene or
//! Reset takes it out, so that a reload or a copied address never opens
//! something other than what is on screen.

use base64::Engine as _;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use cdca::scene::SceneFile;

/// The fragment's key.
const KEY: &str = "scene=";

/// Largest scene a link may expand to, bytes (a damaged link must not
/// allocate without bound).
const MAX_JSON: usize = 4 << 20;

/// The fragment (without `#`) that carries the scene file `json`.
pub fn to_fragment(json: &str) -> String {
    let packed = miniz_oxide::deflate::compress_to_vec(json.as_bytes(), 9);
    format!("{KEY}{}", URL_SAFE_NO_PAD.encode(packed))
}

/// The scene a link carries, checked like an opened file, from the whole
/// link or its fragment (`https://…/#scene=…`, `#scene=…` or `scene=…`).
/// `None` when the link carries no scene; an error says what is wrong
/// with a damaged, truncated or invalid one.
pub fn from_link(link: &str) -> Option<Result<SceneFile, String>> {
    let fragment = link.split_once('#').map_or(link, |(_, f)| f);
    let data = fragment.split('&').find_map(|p| p.strip_prefix(KEY))?;
    Some(decode(data))
}

/// The scene link the page address holds (Copy link put it there, or the
/// page opened with it), while it still shows the scene being edited.
#[derive(Debug, Default)]
pub struct Address {
    shared: Option<SceneFile>,
}

impl Address {
    /// The address now holds a link to `scene`.
    pub fn holds(&mut self, scene: SceneFile) {
        self.shared = Some(scene);
    }

    /// Whether the address holds a link.
    pub fn is_held(&self) -> bool {
        self.shared.is_some()
    }

    /// Whether the address's link went stale with a command that left
    /// `scene` being edited: the scene differs from the linked one (an
    /// edit, an undo, another scene opened), or the command was Reset (a
    /// run's reset is a new start). A stale link is forgotten: the caller
    /// takes it out of the address, once.
    pub fn went_stale(&mut self, scene: &SceneFile, reset: bool) -> bool {
        let stale = self.shared.as_ref().is_some_and(|s| reset || s != scene);
        if stale {
            self.shared = None;
        }
        stale
    }
}

fn decode(data: &str) -> Result<SceneFile, String> {
    let packed = URL_SAFE_NO_PAD
        .decode(data.trim())
        .map_err(|e| format!("the link is truncated or damaged ({e})"))?;
    let json = miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_JSON)
        .map_err(|e| format!("the link is truncated or damaged ({:?})", e.status))?;
    let text = String::from_utf8(json)
        .map_err(|_| "the link is truncated or damaged (not text)".to_owned())?;
    cdca::Scene::from_json(&text)
        .map(cdca::Scene::into_file)
        .map_err(|e| format!("the linked scene is not valid: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> SceneFile {
        let mut s = crate::files::scenes::default_scene();
        s.name = "Class demo, flaw at 35°".to_owned();
        s.cracks[0].friction = 0.37;
        s
    }

    /// A scene goes through a link unchanged, to the last bit, from the
    /// whole address or the fragment alone.
    #[test]
    fn a_scene_survives_the_link() {
        let s = scene();
        let fragment = to_fragment(&s.to_json().expect("json"));
        assert!(fragment.len() < 2000, "{} characters", fragment.len());
        assert!(
            fragment
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b"=-_".contains(&b))
        );
        for link in [
            format!("https://example.org/cdca/?x=1#{fragment}"),
            format!("#{fragment}"),
            fragment.clone(),
        ] {
            assert_eq!(from_link(&link), Some(Ok(s.clone())), "{link}");
        }
    }

    /// The address keeps its link while the scene is the linked one, and
    /// lets it go (once) at an edit or a Reset; without a link there is
    /// nothing to take out.
    #[test]
    fn an_edit_or_reset_takes_the_link_out_of_the_address() {
        let mut address = Address::default();
        let linked = scene();
        assert!(!address.went_stale(&linked, true), "no link held");
        address.holds(linked.clone());
        assert!(!address.went_stale(&linked, false), "the same scene");
        let mut edited = linked.clone();
        edited.cracks[0].friction = 0.4;
        assert!(address.went_stale(&edited, false), "an edit");
        assert!(!address.went_stale(&linked, false), "taken out once");
        address.holds(linked.clone());
        assert!(address.went_stale(&linked, true), "Reset");
        assert!(!address.went_stale(&edited, true), "taken out once");
    }

    /// A link without a scene is not an error; a truncated, damaged or
    /// invalid one is, and says which.
    #[test]
    fn bad_links_say_why() {
        assert_eq!(from_link("https://example.org/cdca/"), None);
        assert_eq!(from_link("#view=1"), None);
        let fragment = to_fragment(&scene().to_json().expect("json"));
        let truncated = &fragment[..fragment.len() / 2];
        let e = from_link(truncated)
            .and_then(Result::err)
            .unwrap_or_default();
        assert!(e.starts_with("the link is truncated or damaged"), "{e}");
        let e = from_link("#scene=@@@")
            .and_then(Result::err)
            .unwrap_or_default();
        assert!(e.starts_with("the link is truncated or damaged"), "{e}");
        // a whole number of base64 blocks, cut inside the deflate stream
        let cut = &fragment[..KEY.len() + 4 * ((fragment.len() - KEY.len()) / 8)];
        let e = from_link(cut).and_then(Result::err).unwrap_or_default();
        assert!(e.starts_with("the link is truncated or damaged"), "{e}");
        let mut bad = scene();
        bad.material.poisson = 0.5;
        let json = serde_json::to_string(&bad).expect("json");
        let packed = miniz_oxide::deflate::compress_to_vec(json.as_bytes(), 9);
        let link = format!("#scene={}", URL_SAFE_NO_PAD.encode(packed));
        let e = from_link(&link).and_then(Result::err).unwrap_or_default();
        assert!(e.contains("material.poisson"), "{e}");
    }
}
