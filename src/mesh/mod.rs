//! The triangle mesh: topology in flat arrays with `u32` indices, behind typed ids.
//!
//! Triangle `t` owns the three half-edges `3t`, `3t+1`, `3t+2`. Half-edge `e` starts at corner
//! `e % 3` of its triangle and ends at the next corner; triangles are counter-clockwise, so each
//! triangle lies to the left of its half-edges. The twin of `e` is the opposite half-edge in the
//! neighbouring triangle.
//!
//! The outside of the triangulation is covered with *ghost* triangles that share the vertex at
//! infinity, [`GHOST`]: every hull edge has a real triangle on one side and a ghost on the other,
//! so every half-edge has a twin and insertion outside the hull needs no special case (the ghost
//! "circumcircle" is the open half-plane beyond its hull edge).
//!
//! The arrays are private: the algorithms see typed ids ([`VertexId`], [`EdgeId`],
//! [`TriangleId`]), accessors, and operations that keep the invariants (twins mutual, tracking
//! up to date). The parts: `ids` the typed ids; `ops` the topological operations (splits, flips,
//! ghosts, retaining part of a mesh); `star` the half-edges around a vertex; `walk` the edges
//! along a line; `legalize` Lawson's flips with a policy; `delete` deleting a vertex (Chew's
//! rule in refinement) and dropping deleted vertices from the numbering; `raw` unchecked access
//! for the bulk Delaunay build and the `u32` view that the output numbering reads.

use crate::geometry::Point;

mod delete;
mod ids;
mod legalize;
mod ops;
pub mod raw;
mod star;
mod unsplit;
mod walk;

pub use delete::Deletion;
pub use ids::{EdgeId, TriangleId, VertexId};
pub use legalize::{BetweenSegments, Ghosts, Lawson, Quad};
pub use star::Star;
pub use walk::{LineStep, LineWalk};

/// The vertex at infinity, a corner of every ghost triangle.
pub const GHOST: VertexId = VertexId::GHOST;
/// "No segment" (and, in `u32` lists at the edges, "no index").
pub const NONE: u32 = u32::MAX;
/// The tag of triangles outside the domain.
pub const OUTSIDE: u32 = 0;

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex coordinates; the index is the vertex id.
    points: Vec<Point>,
    /// Corner `i` of triangle `t` at `corners[3t + i]` (the origin of half-edge `3t + i`): a
    /// vertex id (`< points.len()`) or [`GHOST`].
    corners: Vec<u32>,
    /// The twin of each half-edge (`NONE` only while a mesh is being assembled).
    twins: Vec<u32>,
    /// Per half-edge: the id of the segment it lies on, or [`NONE`]. Empty while segments are
    /// not tracked (plain Delaunay triangulation); see [`Mesh::track_segments`].
    segment: Vec<u32>,
    /// Per vertex: a half-edge that starts at it, or [`NONE`]. Empty while not tracked; see
    /// [`Mesh::track_vertex_edges`].
    vertex_edge: Vec<u32>,
    /// Per triangle: a tag (which part of the domain it belongs to; [`OUTSIDE`] for ghosts and
    /// eaten triangles). Empty while not tracked. New triangles inherit the tag of the triangle
    /// they were split from; flips never cross segments, which bound the tagged parts.
    tag: Vec<u32>,
}

/// What [`Mesh::into_corners_and_points`] gives back: the corner array and the points.
pub struct MeshParts {
    /// Three corners per triangle slot, ghosts included ([`GHOST`] is `u32::MAX`).
    pub corners: Vec<u32>,
    /// The vertices' coordinates.
    pub points: Vec<Point>,
}

impl Mesh {
    /// An empty mesh over `points`, with room for the triangles of their triangulation.
    pub fn with_points(points: Vec<Point>) -> Mesh {
        let capacity = 2 * points.len() + 2;
        Mesh::with_capacity(points, capacity)
    }

    /// An empty mesh over `points`, with room for `triangles` triangle slots.
    pub fn with_capacity(points: Vec<Point>, triangles: usize) -> Mesh {
        Mesh {
            points,
            corners: crate::memory::with_capacity_on_huge_pages(3 * triangles),
            twins: crate::memory::with_capacity_on_huge_pages(3 * triangles),
            segment: Vec::new(),
            vertex_edge: Vec::new(),
            tag: Vec::new(),
        }
    }

    // ---- Sizes and iteration ----

    /// Number of vertices (points), including any not yet connected.
    #[inline(always)]
    pub fn vertex_count(&self) -> u32 {
        self.points.len() as u32
    }

    /// Number of triangle slots (real and ghost).
    #[inline(always)]
    pub fn triangle_count(&self) -> u32 {
        (self.corners.len() / 3) as u32
    }

    /// Number of half-edges (three per triangle slot).
    #[inline(always)]
    pub fn edge_count(&self) -> u32 {
        self.corners.len() as u32
    }

    /// Every triangle slot, real and ghost.
    pub fn triangles(&self) -> impl Iterator<Item = TriangleId> {
        (0..self.triangle_count()).map(TriangleId::new)
    }

    /// Every half-edge.
    pub fn edges(&self) -> impl Iterator<Item = EdgeId> {
        (0..self.edge_count()).map(EdgeId::new)
    }

    /// Iterates the real (non-ghost) triangles.
    pub fn real_triangles(&self) -> impl Iterator<Item = TriangleId> + '_ {
        self.triangles().filter(move |&t| !self.is_ghost(t))
    }

    // ---- Reading the topology ----

    /// The vertex half-edge `e` starts at.
    #[inline(always)]
    pub fn origin(&self, e: EdgeId) -> VertexId {
        VertexId::new(self.corners[e.index()])
    }

    /// The vertex half-edge `e` ends at.
    #[inline(always)]
    pub fn dest(&self, e: EdgeId) -> VertexId {
        self.origin(e.next())
    }

    /// The corner opposite half-edge `e` in its triangle.
    #[inline(always)]
    pub fn apex(&self, e: EdgeId) -> VertexId {
        self.origin(e.prev())
    }

    /// The opposite half-edge, in the neighbouring triangle.
    #[inline(always)]
    pub fn twin(&self, e: EdgeId) -> EdgeId {
        EdgeId::new(self.twins[e.index()])
    }

    /// The position of vertex `v` (not [`GHOST`]).
    #[inline(always)]
    pub fn point(&self, v: VertexId) -> Point {
        self.points[v.index()]
    }

    /// All vertex positions, by vertex id.
    #[inline(always)]
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// The three corners of triangle `t`.
    #[inline(always)]
    pub fn triangle(&self, t: TriangleId) -> [VertexId; 3] {
        let i = 3 * t.index();
        [self.corners[i], self.corners[i + 1], self.corners[i + 2]].map(VertexId::new)
    }

    /// Whether `t` is a ghost triangle (a corner is [`GHOST`]).
    #[inline(always)]
    pub fn is_ghost(&self, t: TriangleId) -> bool {
        self.triangle(t).contains(&GHOST)
    }

    /// The ghost triangles (one per hull edge), in order around the hull: the ring walked from
    /// the ghost nearest the end of the arrays (found by a backward scan, at once where the last
    /// triangle made was a ghost, as after the two-core merge), each ghost's next across its
    /// half-edge from the vertex at infinity. `None` without a ghost, or where the walk does not
    /// close within the mesh's triangles (not a proper ring).
    pub fn ghost_ring(&self) -> Option<Vec<TriangleId>> {
        let count = self.triangle_count();
        let start = (0..count)
            .rev()
            .map(TriangleId::new)
            .find(|&t| self.is_ghost(t))?;
        let mut ring = vec![start];
        let mut t = start;
        loop {
            let from_infinity = t.edges().into_iter().find(|&e| self.origin(e) == GHOST)?;
            t = self.twin(from_infinity).triangle();
            if t == start {
                return Some(ring);
            }
            if ring.len() as u32 >= count || !self.is_ghost(t) {
                return None;
            }
            ring.push(t);
        }
    }

    /// The half-edge from `a` to `b`, if they are joined by an edge (needs vertex tracking).
    pub fn find_edge(&self, a: VertexId, b: VertexId) -> Option<EdgeId> {
        self.star(a).find(|&e| self.dest(e) == b)
    }

    /// [`Self::find_edge`] given a guess: `hint` if it is a half-edge from `a` to `b` (any
    /// half-edge id, [`EdgeId::NONE`] included), without the walk around `a`. The same
    /// half-edge either way, since a mesh has at most one from `a` to `b`.
    #[inline(always)]
    pub fn find_edge_hinted(&self, a: VertexId, b: VertexId, hint: EdgeId) -> Option<EdgeId> {
        // A valid `hint` first: its successor in its triangle is then valid too.
        if self.corners.get(hint.index()) == Some(&a.raw())
            && self.corners[hint.next().index()] == b.raw()
        {
            return Some(hint);
        }
        self.find_edge(a, b)
    }

    /// The corner array, read-only: three `u32` corners per triangle slot ([`GHOST`] is
    /// `u32::MAX`), for the output numbering at the edges of the crate.
    #[inline(always)]
    pub fn raw_corners(&self) -> &[u32] {
        &self.corners
    }

    /// The twin array, read-only (see [`Self::raw_corners`]).
    #[inline(always)]
    pub fn raw_twins(&self) -> &[u32] {
        &self.twins
    }

    // ---- Optional tracking: segments, vertex edges, tags ----

    /// Starts tracking which edges are segments (all none yet). Every operation keeps it up to
    /// date from then on: split halves of a segment stay on it, flips must not touch segments.
    pub fn track_segments(&mut self) {
        if self.segment.is_empty() {
            self.segment = vec![NONE; self.corners.len()];
        }
    }

    /// Whether segments are tracked.
    #[inline(always)]
    pub fn tracks_segments(&self) -> bool {
        !self.segment.is_empty()
    }

    /// The segment id of every half-edge ([`NONE`] for none); empty while not tracked.
    #[inline(always)]
    pub fn raw_segments(&self) -> &[u32] {
        &self.segment
    }

    /// The id of the segment the edge of `e` lies on, or [`NONE`].
    #[inline(always)]
    pub fn segment_of(&self, e: EdgeId) -> u32 {
        if self.segment.is_empty() {
            NONE
        } else {
            self.segment[e.index()]
        }
    }

    /// Asks the processor to bring triangle `t`'s twins and segment ids into the cache: a hint
    /// for a traversal that knows a triangle well before it reads it (a breadth-first flood,
    /// whose triangles are otherwise each a cache miss away; no effect on the mesh).
    #[inline(always)]
    pub fn prefetch_adjacency(&self, t: TriangleId) {
        let i = 3 * t.index();
        for array in [&self.twins, &self.segment] {
            if let Some(first) = array.get(i) {
                crate::memory::prefetch(first);
            }
        }
    }

    /// Whether the edge of `e` lies on a segment.
    #[inline(always)]
    pub fn is_segment(&self, e: EdgeId) -> bool {
        self.segment_of(e) != NONE
    }

    /// Marks both half-edges of the edge of `e` as lying on segment `id`.
    pub fn set_segment(&mut self, e: EdgeId, id: u32) {
        self.track_segments();
        let f = self.twin(e);
        self.segment[e.index()] = id;
        self.segment[f.index()] = id;
    }

    /// Makes the edge of `e` an ordinary edge again.
    pub fn clear_segment(&mut self, e: EdgeId) {
        let f = self.twin(e);
        self.segment[e.index()] = NONE;
        self.segment[f.index()] = NONE;
    }

    /// Starts tracking one outgoing half-edge per vertex, kept valid by every operation.
    pub fn track_vertex_edges(&mut self) {
        self.vertex_edge = vec![NONE; self.points.len()];
        for e in 0..self.corners.len() as u32 {
            let v = self.corners[e as usize];
            if v != GHOST.raw() {
                self.vertex_edge[v as usize] = e;
            }
        }
    }

    /// Whether one outgoing half-edge per vertex is tracked.
    #[inline(always)]
    pub fn tracks_vertex_edges(&self) -> bool {
        !self.vertex_edge.is_empty()
    }

    /// A half-edge that starts at `v`: `None` for a vertex in no triangle (needs vertex
    /// tracking).
    #[inline(always)]
    pub fn vertex_edge(&self, v: VertexId) -> Option<EdgeId> {
        let e = self.vertex_edge[v.index()];
        (e != NONE).then_some(EdgeId::new(e))
    }

    /// Whether triangle tags are tracked.
    #[inline(always)]
    pub fn tracks_tags(&self) -> bool {
        !self.tag.is_empty()
    }

    /// The tag of triangle `t` (needs tag tracking).
    #[inline(always)]
    pub fn tag(&self, t: TriangleId) -> u32 {
        self.tag[t.index()]
    }

    /// The tags of every triangle slot; empty while not tracked.
    #[inline(always)]
    pub fn tags(&self) -> &[u32] {
        &self.tag
    }

    /// Sets every triangle's tag (one per slot) and tracks them from then on.
    pub fn set_tags(&mut self, tags: Vec<u32>) {
        assert_eq!(
            tags.len(),
            self.triangle_count() as usize,
            "one tag per slot"
        );
        self.tag = tags;
    }

    /// Takes the tags out (tracking stops until [`Self::set_tags`] gives them back), so that
    /// they can be rewritten while the topology is read.
    pub fn take_tags(&mut self) -> Vec<u32> {
        std::mem::take(&mut self.tag)
    }

    // ---- Vertices ----

    /// Makes room for `vertices` more vertices and the two triangles each adds, in every array
    /// the mesh keeps (refinement, which adds them one at a time, would otherwise regrow each
    /// array some log₂(growth) times: 4 % of a 250-triangle quality mesh's instructions).
    /// A hint: where the memory is not there, nothing is reserved (the arrays grow as needed, as
    /// they would have).
    pub fn reserve_vertices(&mut self, vertices: usize) {
        let half_edges = 6 * vertices;
        let _ = self.points.try_reserve(vertices);
        let _ = self.corners.try_reserve(half_edges);
        let _ = self.twins.try_reserve(half_edges);
        if !self.segment.is_empty() {
            let _ = self.segment.try_reserve(half_edges);
        }
        if !self.vertex_edge.is_empty() {
            let _ = self.vertex_edge.try_reserve(vertices);
        }
        if !self.tag.is_empty() {
            let _ = self.tag.try_reserve(2 * vertices);
        }
    }

    /// Adds a vertex (not yet connected to the mesh); returns its id.
    pub fn add_point(&mut self, p: Point) -> VertexId {
        self.points.push(p);
        if !self.vertex_edge.is_empty() {
            self.vertex_edge.push(NONE);
        }
        VertexId::new((self.points.len() - 1) as u32)
    }

    /// Moves vertex `v` to `p` (the caller sees that its triangles stay counter-clockwise and
    /// restores what else it needs, such as the Delaunay property).
    pub fn move_point(&mut self, v: VertexId, p: Point) {
        self.points[v.index()] = p;
    }

    /// Replaces the points (the vertex ids stay: the new list must give every corner a point),
    /// returning the old ones.
    pub fn replace_points(&mut self, points: Vec<Point>) -> Vec<Point> {
        std::mem::replace(&mut self.points, points)
    }

    /// Renames every finite corner `v` to `rename(v)` (vertex edges are not moved: see
    /// [`Self::swap_vertex_edges`]).
    pub fn rename_vertices(&mut self, mut rename: impl FnMut(VertexId) -> VertexId) {
        for c in self.corners.iter_mut() {
            if *c != GHOST.raw() {
                *c = rename(VertexId::new(*c)).raw();
            }
        }
    }

    /// Swaps the tracked outgoing half-edges of `u` and `w` (after renaming one to the other).
    pub fn swap_vertex_edges(&mut self, u: VertexId, w: VertexId) {
        if !self.vertex_edge.is_empty() {
            self.vertex_edge.swap(u.index(), w.index());
        }
    }

    /// Takes the points out, leaving none: for a mesh whose points become an output and which
    /// is read no further (every other operation needs the points).
    pub fn take_points(&mut self) -> Vec<Point> {
        std::mem::take(&mut self.points)
    }

    /// Consumes the mesh for its corner array and points (the twins and the tracking are freed
    /// first, so that the caller can build outputs in place without the mesh's peak memory).
    pub fn into_corners_and_points(self) -> MeshParts {
        let Mesh {
            points,
            corners,
            twins,
            segment,
            vertex_edge,
            tag,
        } = self;
        drop((twins, segment, vertex_edge, tag));
        MeshParts { corners, points }
    }

    /// Checks the topological invariants (twins are mutual and join the same two vertices in
    /// opposite directions). Used by tests and the `C` switch.
    pub fn check_topology(&self) -> Result<(), String> {
        for e in self.edges() {
            let f = self.twin(e);
            if f == EdgeId::NONE || f.index() >= self.twins.len() {
                return Err(format!("half-edge {e} has no twin"));
            }
            if self.twin(f) != e {
                return Err(format!("twins of {e} and {f} are not mutual"));
            }
            if self.origin(e) != self.dest(f) || self.dest(e) != self.origin(f) {
                return Err(format!(
                    "half-edges {e} and {f} do not join the same vertices"
                ));
            }
        }
        Ok(())
    }
}
