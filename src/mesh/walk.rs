//! A walk along a line through the triangulation: the half-edges the line crosses, in order,
//! then the vertex where it meets one (Lawson's straight walk; the walk of segment insertion,
//! Anglada 1997, Shewchuk and Brown 2015).

use std::marker::PhantomData;

use super::{EdgeId, Mesh, VertexId};
use crate::geometry::{Point, Predicates};

/// What a [`LineWalk`] meets next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineStep {
    /// The line crosses this half-edge, from its right to its left (the half-edge runs from the
    /// right of the line to its left, in the triangle before the crossing).
    Cross(EdgeId),
    /// The line reaches this vertex (the walk ends).
    Vertex(VertexId),
}

#[derive(Clone, Copy)]
enum State {
    /// The half-edge to report next.
    Report(EdgeId),
    /// The half-edge reported last: the next step looks beyond it.
    Beyond(EdgeId),
    Done,
}

/// The walk along the line from `pa` toward `pb` from a first crossed half-edge: yields each
/// crossed half-edge, then the first vertex that `on_line` (given the vertex's orientation with
/// `pa → pb`) counts as on the line. Lazy: the orientation beyond a crossed half-edge is tested
/// only when the next step is asked for.
pub struct LineWalk<'a, P: Predicates, F: Fn(f64) -> bool> {
    mesh: &'a Mesh,
    pa: Point,
    pb: Point,
    on_line: F,
    state: State,
    _predicates: PhantomData<P>,
}

impl<P: Predicates, F: Fn(f64) -> bool> Iterator for LineWalk<'_, P, F> {
    type Item = LineStep;

    #[inline]
    fn next(&mut self) -> Option<LineStep> {
        match self.state {
            State::Report(h) => {
                self.state = State::Beyond(h);
                Some(LineStep::Cross(h))
            }
            State::Beyond(h) => {
                let f = self.mesh.twin(h); // left → right in the next triangle
                let (f_next, f_prev) = Mesh::next_and_prev(f);
                let z = self.mesh.origin(f_prev);
                let oz = P::orient2d(self.pa, self.pb, self.mesh.point(z));
                if (self.on_line)(oz) {
                    self.state = State::Done;
                    return Some(LineStep::Vertex(z));
                }
                // Right → z when z is left of the line, z → left otherwise.
                let h = if oz > 0.0 { f_next } else { f_prev };
                self.state = State::Beyond(h);
                Some(LineStep::Cross(h))
            }
            State::Done => None,
        }
    }
}

impl Mesh {
    /// Walks along the line from `pa` toward `pb`, starting with the half-edge `first` that it
    /// crosses (right → left); see [`LineWalk`].
    pub fn walk_line<P: Predicates, F: Fn(f64) -> bool>(
        &self,
        pa: Point,
        pb: Point,
        first: EdgeId,
        on_line: F,
    ) -> LineWalk<'_, P, F> {
        LineWalk {
            mesh: self,
            pa,
            pb,
            on_line,
            state: State::Report(first),
            _predicates: PhantomData,
        }
    }
}
