//! The undo/redo stack. An entry is what one Undo brings back: the scene
//! with its title, and what the action it undoes replaced of the results:
//! the run on screen (Open, Reset, a Solve after growth, an edit after a
//! run) and the finished study (a new study, Open).

use cdca::scene::SceneFile;

use crate::run::runner::KeptRun;
use crate::study::Study;

/// The state one Undo (or Redo) goes back to.
pub struct Entry {
    pub scene: SceneFile,
    /// The title the scene had (`scene_source`), and the scene as opened
    /// (the title's ", edited" compares with it).
    pub source: String,
    pub opened: SceneFile,
    /// The run that was on screen: its simulation, plots, field and
    /// replay.
    pub run: Option<Box<KeptRun>>,
    /// The finished study that was in the Study tab.
    pub study: Option<Box<Study>>,
}

impl Entry {
    /// The scene `scene` titled `source`, opened as `opened`, alone.
    pub fn new(scene: &SceneFile, source: &str, opened: &SceneFile) -> Self {
        Self {
            scene: scene.clone(),
            source: source.to_owned(),
            opened: opened.clone(),
            run: None,
            study: None,
        }
    }
}

/// Entries kept; older ones are dropped.
const MAX_UNDO: usize = 200;

/// Entries on each stack that keep their run: a run holds its simulation
/// (the discretisation: a few MB at 100 × 100, a few hundred at
/// 400 × 400), so older entries keep only their scene.
const KEPT_RUNS: usize = 2;

/// Entries before each edit, and after each Undo for Redo.
#[derive(Default)]
pub struct UndoStack {
    undo: Vec<Entry>,
    redo: Vec<Entry>,
    /// The last recorded edit was an ongoing drag: further ongoing edits
    /// belong to the same undo step.
    coalescing: bool,
}

impl UndoStack {
    /// Records the state to return to (`before`, called only when needed),
    /// unless this edit continues an ongoing drag. Clears Redo.
    pub fn record(&mut self, before: impl FnOnce() -> Entry, ongoing: bool) {
        if !(self.coalescing && ongoing) {
            push(&mut self.undo, before());
            self.redo.clear();
        }
        self.coalescing = ongoing;
    }

    /// Ends a drag so the next edit starts a new undo step.
    pub fn end_coalescing(&mut self) {
        self.coalescing = false;
    }

    /// The state to go back to; the caller gives the state it replaces to
    /// [`undone`](Self::undone).
    pub fn undo(&mut self) -> Option<Entry> {
        self.coalescing = false;
        self.undo.pop()
    }

    /// The state an Undo replaced, for Redo.
    pub fn undone(&mut self, present: Entry) {
        push(&mut self.redo, present);
    }

    /// The state to go forward to; the caller gives the state it replaces
    /// to [`redone`](Self::redone).
    pub fn redo(&mut self) -> Option<Entry> {
        self.coalescing = false;
        self.redo.pop()
    }

    /// The state a Redo replaced, for Undo.
    pub fn redone(&mut self, present: Entry) {
        push(&mut self.undo, present);
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
}

/// Pushes `entry`, dropping the oldest entry beyond [`MAX_UNDO`] and the
/// runs of entries beyond the newest [`KEPT_RUNS`] that have one.
fn push(stack: &mut Vec<Entry>, entry: Entry) {
    stack.push(entry);
    if stack.len() > MAX_UNDO {
        stack.remove(0);
    }
    stack
        .iter_mut()
        .rev()
        .filter(|e| e.run.is_some())
        .skip(KEPT_RUNS)
        .for_each(|e| e.run = None);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::scenes::default_scene;

    fn renamed(name: &str) -> Entry {
        let scene = SceneFile {
            name: name.to_owned(),
            ..default_scene()
        };
        Entry::new(&scene, "", &scene)
    }

    fn name(e: Option<Entry>) -> Option<String> {
        e.map(|e| e.scene.name)
    }

    #[test]
    fn undo_then_redo_returns_to_each_state() {
        let mut stack = UndoStack::default();
        stack.record(|| renamed("a"), false);
        assert_eq!(name(stack.undo()), Some("a".to_owned()));
        stack.undone(renamed("b"));
        assert_eq!(name(stack.redo()), Some("b".to_owned()));
        stack.redone(renamed("a"));
        assert!(stack.can_undo());
        assert!(!stack.can_redo());
    }

    #[test]
    fn a_drag_is_one_undo_step() {
        let mut stack = UndoStack::default();
        stack.record(|| renamed("start"), true);
        stack.record(|| renamed("mid 1"), true);
        stack.record(|| renamed("mid 2"), true);
        stack.end_coalescing();
        assert_eq!(name(stack.undo()), Some("start".to_owned()));
        assert!(!stack.can_undo());
    }

    #[test]
    fn a_new_edit_clears_redo() {
        let mut stack = UndoStack::default();
        stack.record(|| renamed("a"), false);
        let _ = stack.undo();
        stack.undone(renamed("b"));
        stack.record(|| renamed("a"), false);
        assert!(!stack.can_redo());
    }
}
