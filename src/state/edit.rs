//! Editing the scene on the canvas: the active tool, the crack being drawn,
//! the point being dragged.

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::files::scenes::default_scene;

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
