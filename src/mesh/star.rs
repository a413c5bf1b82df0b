//! The star of a vertex: its outgoing half-edges, counter-clockwise.
//!
//! With ghosts covering the outside, every vertex of a triangulation has a closed star (the
//! ghosts' half-edges to the vertex at infinity included), so turning from any outgoing
//! half-edge comes back to it: around vertex `v`, the half-edge after `e = v → x` is the twin of
//! `prev(e)` (`y → v` in the triangle `(v, x, y)`), that is `v → y`.

use super::{EdgeId, Mesh, VertexId};

/// The outgoing half-edges of a vertex, counter-clockwise from a starting one, each once.
#[derive(Clone)]
pub struct Star<'a> {
    mesh: &'a Mesh,
    start: EdgeId,
    /// The half-edge to return next ([`EdgeId::NONE`] when done).
    next: EdgeId,
}

impl Iterator for Star<'_> {
    type Item = EdgeId;

    #[inline]
    fn next(&mut self) -> Option<EdgeId> {
        let e = self.next;
        if e == EdgeId::NONE {
            return None;
        }
        // Read ahead: the twin of a half-edge of the mesh is always readable (it may be unset,
        // `NONE`, at a boundary being covered with ghosts; then it is never followed).
        let f = self.mesh.twin(e.prev());
        self.next = if f == self.start { EdgeId::NONE } else { f };
        Some(e)
    }
}

impl Mesh {
    /// The outgoing half-edges of `v`, counter-clockwise, from its tracked edge (needs vertex
    /// tracking; empty for a vertex in no triangle). Ghost half-edges (to [`super::GHOST`]) are
    /// included.
    #[inline]
    pub fn star(&self, v: VertexId) -> Star<'_> {
        self.star_from(self.vertex_edge(v).unwrap_or(EdgeId::NONE))
    }

    /// The outgoing half-edges of the origin of `e`, counter-clockwise, starting with `e`.
    #[inline]
    pub fn star_from(&self, e: EdgeId) -> Star<'_> {
        Star {
            mesh: self,
            start: e,
            next: e,
        }
    }
}
