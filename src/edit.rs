//! Editing the scene on the canvas: the active tool, the crack being drawn,
//! the point being dragged, and the undo/redo stack of scene snapshots.

use cdca::scene::CrackSpec;
use cdca::scene::SceneFile;

/// What a primary click on the canvas does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tool {
    /// Select and drag crack points and tips; click a tip to inspect it.
    #[default]
    Select,
    /// Click points of a new crack; double-click or Enter finishes it.
    DrawCrack,
}

/// A crack vertex: crack index and vertex index in its polyline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexRef {
    pub crack: usize,
    pub vertex: usize,
}

/// Editing state that is not part of the scene.
#[derive(Debug, Default)]
pub struct Editor {
    pub tool: Tool,
    /// Points of the crack being drawn, m.
    pub drawing: Vec<[f64; 2]>,
    /// The vertex being dragged.
    pub dragging: Option<VertexRef>,
    /// The crack selected in the canvas (for the parameter panel and Delete).
    pub selected_crack: Option<usize>,
}

impl Editor {
    /// Ends the drawing; returns the new crack if it has two distinct points.
    pub fn finish_drawing(&mut self) -> Option<CrackSpec> {
        let mut points = std::mem::take(&mut self.drawing);
        points.dedup_by(|a, b| (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9);
        self.tool = Tool::Select;
        (points.len() >= 2).then(|| CrackSpec {
            points: Some(points),
            ..CrackSpec::segment([0.0; 2], [0.0; 2])
        })
    }
}

/// `scene` with vertex `v` moved to `to`. An arc crack becomes a polyline.
pub fn move_vertex(scene: &SceneFile, v: VertexRef, to: [f64; 2]) -> SceneFile {
    let mut s = scene.clone();
    let h = s.element_size();
    if let Some(crack) = s.cracks.get_mut(v.crack) {
        let mut points = crack.polyline(h);
        if let Some(p) = points.get_mut(v.vertex) {
            *p = to;
        }
        crack.points = Some(points);
        crack.arc = None;
    }
    s
}

/// Snapshots of the scene before each edit.
#[derive(Debug, Default)]
pub struct UndoStack {
    undo: Vec<SceneFile>,
    redo: Vec<SceneFile>,
    /// The last recorded edit was an ongoing drag: further ongoing edits
    /// belong to the same undo step.
    coalescing: bool,
}

/// Snapshots kept; older ones are dropped.
const MAX_UNDO: usize = 200;

impl UndoStack {
    /// Records `before` as the state to return to, unless this edit
    /// continues an ongoing drag.
    pub fn record(&mut self, before: &SceneFile, ongoing: bool) {
        if !(self.coalescing && ongoing) {
            self.undo.push(before.clone());
            if self.undo.len() > MAX_UNDO {
                self.undo.remove(0);
            }
            self.redo.clear();
        }
        self.coalescing = ongoing;
    }

    /// Ends a drag so the next edit starts a new undo step.
    pub fn end_coalescing(&mut self) {
        self.coalescing = false;
    }

    /// The scene to go back to, given the current one.
    pub fn undo(&mut self, current: &SceneFile) -> Option<SceneFile> {
        self.coalescing = false;
        let previous = self.undo.pop()?;
        self.redo.push(current.clone());
        Some(previous)
    }

    pub fn redo(&mut self, current: &SceneFile) -> Option<SceneFile> {
        self.coalescing = false;
        let next = self.redo.pop()?;
        self.undo.push(current.clone());
        Some(next)
    }

    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::default_scene;

    fn renamed(name: &str) -> SceneFile {
        SceneFile {
            name: name.to_owned(),
            ..default_scene()
        }
    }

    #[test]
    fn undo_then_redo_returns_to_each_state() {
        let (a, b) = (renamed("a"), renamed("b"));
        let mut stack = UndoStack::default();
        stack.record(&a, false);
        assert_eq!(stack.undo(&b), Some(a.clone()));
        assert_eq!(stack.redo(&a), Some(b));
        assert!(stack.can_undo());
    }

    #[test]
    fn a_drag_is_one_undo_step() {
        let mut stack = UndoStack::default();
        stack.record(&renamed("start"), true);
        stack.record(&renamed("mid 1"), true);
        stack.record(&renamed("mid 2"), true);
        stack.end_coalescing();
        assert_eq!(
            stack.undo(&renamed("end")).map(|s| s.name),
            Some("start".to_owned())
        );
        assert!(!stack.can_undo());
    }

    #[test]
    fn a_new_edit_clears_redo() {
        let mut stack = UndoStack::default();
        stack.record(&renamed("a"), false);
        let _ = stack.undo(&renamed("b"));
        stack.record(&renamed("a"), false);
        assert!(!stack.can_redo());
    }

    #[test]
    fn drawing_needs_two_distinct_points() {
        let mut e = Editor {
            tool: Tool::DrawCrack,
            drawing: vec![[0.1, 0.1], [0.1, 0.1]],
            ..Editor::default()
        };
        assert!(e.finish_drawing().is_none());
        assert_eq!(e.tool, Tool::Select);
        e.drawing = vec![[0.1, 0.1], [0.2, 0.1], [0.2, 0.1]];
        let crack = e.finish_drawing().and_then(|c| c.points);
        assert_eq!(crack, Some(vec![[0.1, 0.1], [0.2, 0.1]]));
    }

    #[test]
    fn moving_an_arc_vertex_turns_it_into_a_polyline() {
        let mut s = default_scene();
        s.cracks = vec![CrackSpec {
            points: None,
            arc: Some(cdca::scene::ArcSpec {
                center: [0.15, 0.15],
                radius: 0.05,
                start_deg: 0.0,
                end_deg: 90.0,
            }),
            ..CrackSpec::segment([0.0; 2], [0.0; 2])
        }];
        let moved = move_vertex(
            &s,
            VertexRef {
                crack: 0,
                vertex: 0,
            },
            [0.21, 0.15],
        );
        let points = moved.cracks[0].points.clone().unwrap_or_default();
        assert!(moved.cracks[0].arc.is_none());
        assert_eq!(points[0], [0.21, 0.15]);
    }
}
