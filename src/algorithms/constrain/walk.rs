//! The walk along a segment from one endpoint: the edge it runs along, the edges it crosses (and
//! the triangle beyond each, from which the cavity's chains are read) up to a vertex on it, or
//! the segment edge it hits.

use super::*;

/// What the walk from a segment's endpoint finds.
pub(super) enum Walk {
    /// The edge `e` from the start runs along the segment to a vertex on it (possibly the end).
    Along(EdgeId),
    /// The segment crosses the edges in [`Constrainer::crossed`] and then reaches `stop`, a
    /// vertex on it (possibly the end).
    Crosses(VertexId),
    /// The segment crosses the segment edge `e` (after the crossings before it).
    HitsSegment(EdgeId),
    /// The edge from the start to the end passed by this vertex within rounding: it was flipped
    /// away, and the segment goes through the vertex.
    Through(VertexId),
}

/// The triangle beyond a crossed half-edge, as the line walk found it: its corner `apex` (at
/// `point`) opposite the crossed edge, on the `side` of the segment, and `other`, its half-edge
/// on the cavity's boundary: the one into the apex on that side's chain when the walk goes on
/// (from the left end of the crossed edge when the apex is left, to its right end otherwise),
/// or the twin of the crossed half-edge when the apex ends the walk (both its other half-edges
/// are then on the boundary). The cavity's chains are read from these without a second walk.
#[derive(Clone, Copy, Debug)]
pub(super) struct Beyond {
    pub(super) other: EdgeId,
    pub(super) apex: VertexId,
    pub(super) point: Point,
    pub(super) side: Side,
}

/// Where the apex beyond a crossed edge lies: left or right of the segment, or on it (where the
/// walk ends).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    Left,
    Right,
    End,
}

impl<P: Predicates> Constrainer<P> {
    /// Walks from `a` toward `b`; the edges crossed are left in `self.scratch.crossed`.
    pub(super) fn walk(&mut self, a: VertexId, b: VertexId) -> Result<Walk, Error> {
        self.scratch.crossed.clear();
        self.scratch.beyond.clear();
        let mesh = self.inserter.mesh();
        let (pa, pb) = (self.pt(a), self.pt(b));
        // Often the segment is an edge already (a polygon's sides between close vertices): look
        // for `b` among the neighbours first, which needs no point and no predicate. (Then no
        // other neighbour lies on the ray to `b` and no wedge strictly contains it, so the search
        // below would find the same edge.)
        if let Some(e) = edge_between(mesh, a, b) {
            let beside = |pu: Point, pv: Point, pw: Point| {
                on_line(P::orient2d(pu, pv, pw), pu, pv) && along(pu, pw, pv) && before(pu, pw, pv)
            };
            if let Some(w) = self.flip_edge_onto_vertex(e, beside) {
                return Ok(Walk::Through(w));
            }
            // A vertex beside the edge that no flip can join to its ends (the quadrilateral is
            // not convex: slivers along nearly collinear vertices, as lattice points on a line
            // rounded off it): the segment still goes through it, along the sliver's two other
            // edges; the edge stays, not a segment.
            let mesh = self.inserter.mesh();
            for h in [e, mesh.twin(e)] {
                if mesh.is_ghost(h.triangle()) {
                    continue;
                }
                let (u, v, w) = (mesh.origin(h), mesh.dest(h), mesh.apex(h));
                if beside(self.pt(u), self.pt(v), self.pt(w)) {
                    return Ok(Walk::Through(w));
                }
            }
            return Ok(Walk::Along(e));
        }
        // Find the triangle (a, x, y) around `a` whose wedge holds the direction to `b`. Each
        // wedge's `y` is the next one's `x`: its orientation is carried over.
        let mut carried = (GHOST, 0.0);
        let mut wedge = None;
        for e in mesh.star(a) {
            let (x, y) = (mesh.dest(e), mesh.apex(e));
            if x == GHOST {
                continue;
            }
            let ox = if carried.0 == x {
                carried.1
            } else {
                P::orient2d(pa, self.pt(x), pb)
            };
            if on_line(ox, pa, pb) && along(pa, self.pt(x), pb) && before(pa, self.pt(x), pb) {
                return Ok(Walk::Along(e));
            }
            if y != GHOST && ox > 0.0 {
                let py = self.pt(y);
                let oy = P::orient2d(pa, py, pb);
                // A `y` within rounding of the segment (an ulp to the right of it) is not the
                // left side of a wedge to cross: the next turn takes it as `x` and walks along
                // the edge to it.
                let y_on_segment = on_line(oy, pa, pb) && along(pa, py, pb) && before(pa, py, pb);
                if oy < 0.0 && !y_on_segment {
                    wedge = Some(e);
                    break;
                }
                carried = (y, oy);
            }
        }
        let Some(e) = wedge else {
            return Err(Error::Internal(format!(
                "segment insertion: no triangle around vertex {a} faces vertex {b}"
            )));
        };
        // Cross edges until a vertex on the segment is reached.
        Ok(
            match cross_edges::<P>(mesh, pa, pb, e.next(), true, &mut self.scratch) {
                Ok(z) => Walk::Crosses(z),
                Err(h) => Walk::HitsSegment(h),
            },
        )
    }

    /// The first vertex that lies exactly on the segment from `a` to `b` beyond the segment edge
    /// `h` it crosses (right → left), if that is not `b`.
    pub(super) fn vertex_on_segment_beyond(
        &mut self,
        a: VertexId,
        b: VertexId,
        h: EdgeId,
    ) -> Option<VertexId> {
        let (pa, pb) = (self.pt(a), self.pt(b));
        let z = cross_edges::<P>(self.inserter.mesh(), pa, pb, h, false, &mut self.scratch).ok()?;
        (z != b).then_some(z)
    }
}

/// The half-edge from `a` to `b` if they are neighbours ([`Mesh::find_edge`]'s answer, the edge
/// being unique), by a leaner turn around `a`: leaving the triangle `(a, x, y)` of half-edge
/// `a → x` through `y → a`, whose twin is the next half-edge `a → y`, the corner `y` read there
/// is that half-edge's destination (no `next` to compute, no second read).
fn edge_between(mesh: &Mesh, a: VertexId, b: VertexId) -> Option<EdgeId> {
    let start = mesh.vertex_edge(a)?;
    if start.raw() >= mesh.edge_count() {
        // Not a half-edge of the mesh (never seen): the checked search.
        return mesh.find_edge(a, b);
    }
    let mut e = start;
    loop {
        let back = e.prev(); // y → a
                             // SAFETY: `e` is a half-edge of the mesh (`a`'s recorded one, checked above, or a twin
                             // read below that is not NONE: twins are half-edges of the mesh), so is `back`, in its
                             // triangle.
        let f = unsafe { mesh.twin_unchecked(back) }; // a → y
        if f == EdgeId::NONE {
            // An open star (a boundary not covered by ghosts): the general search.
            return mesh.find_edge(a, b);
        }
        // SAFETY: as above.
        if unsafe { mesh.corner_unchecked(back) } == b {
            return Some(f);
        }
        if f == start {
            return None;
        }
        e = f;
    }
}

/// Crosses edges along the line from `pa` to `pb`, starting with half-edge `h` (right → left of
/// the line, which crosses it), until the line reaches a vertex: `Ok(vertex)`; or, with
/// `stop_at_segments`, until the next edge to cross is a segment: `Err(that half-edge)`. The
/// half-edges crossed are pushed to `scratch.crossed`, what lies beyond each to
/// `scratch.beyond`.
///
/// The steps of [`Mesh::walk_line`], written out: they record the triangles beyond (which the
/// cavity's chains are made of), and read the mesh unchecked.
fn cross_edges<P: Predicates>(
    mesh: &Mesh,
    pa: Point,
    pb: Point,
    h: EdgeId,
    stop_at_segments: bool,
    scratch: &mut Scratch,
) -> Result<VertexId, EdgeId> {
    let Scratch {
        crossed, beyond, ..
    } = scratch;
    let mut h = h;
    loop {
        if stop_at_segments && mesh.is_segment(h) {
            return Err(h);
        }
        crossed.push(h);
        // SAFETY (both reads): `h` is a half-edge of the mesh (the caller's, or one of the
        // triangle beyond the previous one), so are its twin and that twin's triangle's others.
        let f = unsafe { mesh.twin_unchecked(h) }; // left → right in the next triangle
        let (f_next, f_prev) = Mesh::next_and_prev(f);
        let apex = unsafe { mesh.corner_unchecked(f_prev) };
        let point = mesh.point(apex);
        let orientation = P::orient2d(pa, pb, point);
        if on_line(orientation, pa, pb) {
            beyond.push(Beyond {
                other: f,
                apex,
                point,
                side: Side::End,
            });
            return Ok(apex);
        }
        // Right → apex when the apex is left of the line, apex → left otherwise.
        let (other, side, next) = if orientation > 0.0 {
            (f_prev, Side::Left, f_next)
        } else {
            (f_next, Side::Right, f_prev)
        };
        beyond.push(Beyond {
            other,
            apex,
            point,
            side,
        });
        h = next;
    }
}
