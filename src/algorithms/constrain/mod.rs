//! Constrained Delaunay triangulation: inserting segments into a Delaunay triangulation.
//!
//! Each segment is recovered by walking from one endpoint toward the other and collecting the
//! edges it crosses. A vertex lying on the segment splits it there; a segment crossed by another
//! gets a new vertex at the crossing, which splits both. The triangles the segment crosses form a
//! cavity, which the segment cuts into two polygons; each is retriangulated by its constrained
//! Delaunay triangulation, which together with the untouched triangles is the constrained
//! Delaunay triangulation with the segment (Anglada, "An improved incremental algorithm for
//! constructing restricted Delaunay triangulations", 1997; Shewchuk and Brown, "Fast segment
//! insertion and incremental construction of constrained Delaunay triangulations", 2015). A
//! polygon's triangulation is found from its base edge: the chain vertex whose circle through the
//! base holds no other chain vertex makes the base's triangle, and the two sub-chains recurse.
//! This touches only the cavity's triangles, reuses their slots, and needs no edge lookups by
//! vertex pair, which the flip-based alternative does at every step.
//!
//! Should the new triangles not all be counter-clockwise (inexact predicates, `X`), the cavity is
//! left alone and the crossing edges are removed by flipping instead (Sloan, "A fast algorithm
//! for generating constrained Delaunay triangulations", 1993): flip an edge when its
//! quadrilateral is convex, re-queue it otherwise; then the new edges are made locally Delaunay
//! by Lawson flips that never cross a segment (Chew 1989; Lee and Lin 1986).

use std::collections::{HashSet, VecDeque};

use crate::algorithms::delaunay::{Inserter, Location};
use crate::error::Error;
use crate::geometry::{Point, Predicates};
use crate::mesh::{BetweenSegments, EdgeId, Mesh, TriangleId, VertexId, GHOST, NONE};

// The parts: this file inserts segments (crossings, vertices on segments, hull segments, point
// location for holes and regions); `walk` walks along a segment from an endpoint, recording the
// edges it crosses and what lies beyond them; `cavity` recovers a segment across crossed triangles;
// `snap` makes vertices within a distance of a segment vertices of it (before refinement);
// `grid` moves vertices onto the caller's grid (before the outputs).
mod cavity;
mod grid;
mod snap;
#[cfg(test)]
mod tests;
mod walk;

use cavity::CavityScratch;
use walk::{Beyond, Walk};

/// A vertex created where two segments cross: it lies on the edge from `from` to `to` at
/// parameter `t` (for interpolating attributes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    pub vertex: VertexId,
    pub from: VertexId,
    pub to: VertexId,
    pub t: f64,
}

/// Crossings closer than this (relative to the lengths involved) to a vertex snap to it.
const SNAP_RELATIVE: f64 = 1e-12;

/// Where two segments cross.
enum CrossingPoint {
    /// A new vertex.
    New(VertexId),
    /// An endpoint of the crossed segment (the crossing rounds onto it).
    Existing(VertexId),
    /// Another vertex, which the crossed segment passes through in floating point.
    ThroughVertex(VertexId),
}

#[derive(Clone)]
pub struct Constrainer<P: Predicates> {
    inserter: Inserter<P>,
    /// Vertices created at crossings, in creation order.
    pub crossings: Vec<Crossing>,
    /// The marker of each segment id (the ids that [`Mesh::segment`](crate::mesh::Mesh) holds).
    pub markers: Vec<i32>,
    /// The endpoints of each segment id, as given (before crossings split it).
    pub ends: Vec<(VertexId, VertexId)>,
    /// `s`: recover segments by inserting midpoints (a conforming triangulation) instead of
    /// flipping crossing edges away.
    pub split_segments: bool,
    /// Scratch space of segment insertion, reused from segment to segment.
    scratch: Scratch,
    /// Pairs of segment ids (smaller first) that have crossed: two straight segments cross at
    /// most once, so a second crossing means they are nearly collinear and a rounded crossing
    /// point bent one across the other again.
    crossed_pairs: HashSet<(u32, u32)>,
}

/// Buffers of segment insertion, kept between segments so that inserting one allocates nothing.
#[derive(Clone, Default)]
struct Scratch {
    /// Pieces of the segment still to insert: (from, to, id).
    work: Vec<(VertexId, VertexId, u32)>,
    /// The half-edges the walk crossed, in order; each runs from the right of the segment to its
    /// left, in the triangle before the crossing.
    crossed: Vec<EdgeId>,
    /// Per crossed half-edge, what lies beyond it (see [`Beyond`]), in the same order.
    beyond: Vec<Beyond>,
    /// Buffers of the cavity retriangulation.
    cavity: CavityScratch,
    /// The Lawson stack of [`Constrainer::move_vertex`], which the improvement of a refined
    /// mesh calls for nearly every vertex it tries.
    lawson: Vec<(VertexId, VertexId, EdgeId)>,
}

impl<P: Predicates> Constrainer<P> {
    /// Prepares `inserter`'s mesh (a Delaunay triangulation with ghosts) for segments.
    pub fn new(mut inserter: Inserter<P>) -> Self {
        inserter.mesh_mut().track_vertex_edges();
        inserter.mesh_mut().track_segments();
        Constrainer {
            inserter,
            crossings: Vec::new(),
            markers: Vec::new(),
            ends: Vec::new(),
            split_segments: false,
            scratch: Scratch::default(),
            crossed_pairs: HashSet::new(),
        }
    }

    /// The mesh.
    #[inline(always)]
    pub fn mesh(&self) -> &Mesh {
        self.inserter.mesh()
    }

    /// The mesh, for its tags (the domain) and segment marks; the topology changes only
    /// through the constrainer's operations.
    #[inline(always)]
    pub fn mesh_mut(&mut self) -> &mut Mesh {
        self.inserter.mesh_mut()
    }

    /// The mesh, consuming the constrainer.
    pub fn into_mesh(self) -> Mesh {
        self.inserter.into_mesh()
    }

    /// Adds a vertex at `p`, not yet connected (see [`Self::insert_at`]).
    pub fn add_point(&mut self, p: Point) -> VertexId {
        self.inserter.mesh_mut().add_point(p)
    }

    /// Locates `p` by a walk from triangle `start` (see [`Inserter::locate`]).
    pub fn locate(&mut self, p: Point, start: TriangleId) -> Location {
        self.inserter.locate(p, start)
    }

    /// Locates `p` in a mesh that need not be convex (see [`Inserter::locate_thoroughly`]).
    pub fn locate_thoroughly(&mut self, p: Point, start: TriangleId) -> Location {
        self.inserter.locate_thoroughly(p, start)
    }

    /// Inserts vertex `v` at a known location with Lawson flips that keep segments (see
    /// [`Inserter::insert_at`]); `Err(u)` if it lies on vertex `u`.
    pub fn insert_at(&mut self, v: VertexId, location: Location) -> Result<(), VertexId> {
        self.inserter.insert_at(v, location)
    }

    /// Keeps only the triangles for which `keep` holds (see [`Mesh::retain_triangles`]).
    pub fn retain_triangles(&mut self, keep: impl Fn(TriangleId) -> bool) {
        self.inserter.retain_triangles(keep);
    }

    /// Deletes vertex `v`, a vertex inside the domain on no segment, keeping the triangulation
    /// constrained Delaunay (see [`Mesh::delete_vertex`]): the triangles made, or `None` when
    /// it stays.
    pub fn delete_vertex(&mut self, v: VertexId) -> Option<Vec<TriangleId>> {
        self.inserter.delete_vertex(v)
    }

    /// [`Self::delete_vertex`] into `made` (cleared first): whether `v` was deleted.
    pub fn delete_vertex_into(&mut self, v: VertexId, made: &mut Vec<TriangleId>) -> bool {
        self.inserter.delete_vertex_into(v, made)
    }

    /// Deletes vertex `v` between two subsegments of one segment, which become one, keeping
    /// the triangulation constrained Delaunay (see [`Mesh::delete_segment_vertex`]): the
    /// triangles made, or `None` when it stays.
    pub fn delete_segment_vertex(&mut self, v: VertexId) -> Option<Vec<TriangleId>> {
        self.inserter.delete_segment_vertex(v)
    }

    /// Drops deleted vertices from the numbering (see [`Mesh::remove_vertices`]).
    pub fn remove_vertices(&mut self, keep: impl Fn(VertexId) -> bool) -> Vec<u32> {
        self.inserter.remove_vertices(keep)
    }

    /// The tracked outgoing half-edge of `v` ([`EdgeId::NONE`] for a vertex in no triangle).
    fn vertex_edge(&self, v: VertexId) -> EdgeId {
        self.inserter.mesh().vertex_edge(v).unwrap_or(EdgeId::NONE)
    }

    fn pt(&self, v: VertexId) -> Point {
        self.inserter.mesh().point(v)
    }

    fn orient(&self, a: VertexId, b: VertexId, c: VertexId) -> f64 {
        P::orient2d(self.pt(a), self.pt(b), self.pt(c))
    }

    /// Room for `n` more segments' ids, so that registering them does not regrow the arrays.
    pub fn reserve_segments(&mut self, n: usize) {
        self.markers.reserve(n);
        self.ends.reserve(n);
    }

    /// Registers a segment from `a` to `b` with its marker; returns the new segment's id.
    pub fn new_segment_id(&mut self, marker: i32, a: VertexId, b: VertexId) -> u32 {
        self.markers.push(marker);
        self.ends.push((a, b));
        (self.markers.len() - 1) as u32
    }

    /// Inserts the segment from vertex `a` to vertex `b` with id `id` (from
    /// [`Self::new_segment_id`]). Both must be vertices of the triangulation. An `Err` is an
    /// internal invariant failure (a bug), reported instead of a panic.
    pub fn insert_segment(&mut self, a: VertexId, b: VertexId, id: u32) -> Result<(), Error> {
        let mut work = std::mem::take(&mut self.scratch.work);
        work.clear();
        work.push((a, b, id));
        // `s` splits a segment at midpoints until its pieces are edges; a piece that would need
        // more splits than this (it grazes a vertex) is recovered by flips instead.
        let mut midpoints_left = 64u32;
        while let Some((a, b, id)) = work.pop() {
            if a == b {
                continue;
            }
            match self.walk(a, b)? {
                Walk::Along(e) => {
                    let mesh = self.inserter.mesh_mut();
                    let c = mesh.dest(e);
                    // Where segments overlap, a later non-zero marker replaces a zero one, as in
                    // Triangle.
                    let old = mesh.segment_of(e);
                    if old == NONE
                        || (self.markers[old as usize] == 0 && self.markers[id as usize] != 0)
                    {
                        mesh.set_segment(e, id);
                    }
                    work.push((c, b, id));
                }
                Walk::Through(w) => {
                    work.push((w, b, id));
                    work.push((a, w, id));
                }
                Walk::Crosses(stop) if stop != b && self.orient(a, b, stop) != 0.0 => {
                    // The walk stopped at a vertex within rounding of the segment (see
                    // [`on_line`]): the segment goes through it, and the piece up to it is walked
                    // again, so that the crossed edges are those of that piece.
                    work.push((stop, b, id));
                    work.push((a, stop, id));
                }
                Walk::Crosses(stop) => {
                    work.push((stop, b, id));
                    let split = self.split_segments && midpoints_left > 0;
                    match split.then(|| self.insert_midpoint(a, stop)).flatten() {
                        Some(m) => {
                            midpoints_left -= 1;
                            work.push((m, stop, id));
                            work.push((a, m, id));
                        }
                        None => {
                            if !self.retriangulate_cavity(a, stop, id) {
                                let mesh = self.inserter.mesh();
                                let crossed = self
                                    .scratch
                                    .crossed
                                    .iter()
                                    .map(|&h| (mesh.origin(h), mesh.dest(h)))
                                    .collect();
                                self.remove_crossings(a, stop, crossed, id)?;
                            }
                        }
                    }
                }
                Walk::HitsSegment(e) => {
                    // A vertex lying exactly on this segment beyond the crossed one splits it
                    // first: the piece after the (rounded) crossing point would miss it by an ulp.
                    if let Some(w) = self.vertex_on_segment_beyond(a, b, e) {
                        work.push((w, b, id));
                        work.push((a, w, id));
                        continue;
                    }
                    // Read the crossed segment now: making the crossing vertex may rewrite `e`.
                    let mesh = self.inserter.mesh();
                    let (u, v, other) = (mesh.origin(e), mesh.dest(e), mesh.segment_of(e));
                    if !self.crossed_pairs.insert((id.min(other), id.max(other))) {
                        // They crossed already: nearly collinear. Rather than a cascade of new
                        // crossing points, this piece goes through the crossed edge's end
                        // nearer to it, on the other segment.
                        let w = if self.orient(a, b, u).abs() <= self.orient(a, b, v).abs() {
                            u
                        } else {
                            v
                        };
                        work.push((w, b, id));
                        work.push((a, w, id));
                        continue;
                    }
                    match self.split_at_crossing(a, b, e) {
                        CrossingPoint::New(p) | CrossingPoint::Existing(p) => {
                            // The two pieces bend slightly at the rounded crossing point.
                            work.push((p, b, id));
                            work.push((a, p, id));
                        }
                        CrossingPoint::ThroughVertex(w) => {
                            // The crossed segment passes through `w` (in floating point): it is
                            // re-inserted as two pieces meeting at `w`, then this one is retried.
                            if let Some(crossed) = self.inserter.mesh().find_edge(u, v) {
                                self.inserter.mesh_mut().clear_segment(crossed);
                                self.restore_delaunay(vec![(u, v)]);
                            }
                            work.push((a, b, id));
                            work.push((w, v, other));
                            work.push((u, w, other));
                        }
                    }
                }
            }
        }
        self.scratch.work = work;
        Ok(())
    }

    /// After inserting a vertex at a rounded position (a crossing, a midpoint), which may lie
    /// off the edge it split by an ulp: the edges around it are made locally Delaunay too (Lawson
    /// checks only the edges opposite a new vertex, which suffices only for exact positions).
    ///
    /// Refinement settles every vertex it puts on a segment: the spokes go on the Lawson stack
    /// with their half-edges as hints (found again without a turn around the vertex), in the
    /// constrainer's reused stack.
    pub fn settle(&mut self, vertex: VertexId) {
        let mut stack = self.take_lawson_stack();
        let mesh = self.inserter.mesh();
        stack.extend(
            mesh.star(vertex)
                .map(|e| (vertex, mesh.dest(e), e))
                .filter(|&(_, w, _)| w != GHOST),
        );
        self.legalize_stack(stack);
    }

    /// The constrainer's reused Lawson stack, empty (give it back through
    /// [`Self::legalize_stack`]).
    fn take_lawson_stack(&mut self) -> Vec<(VertexId, VertexId, EdgeId)> {
        let mut stack = std::mem::take(&mut self.scratch.lawson);
        stack.clear();
        stack
    }

    /// Lawson flips, segments fixed, from the entries of `stack` (vertex pairs with a half-edge
    /// as a hint, or [`EdgeId::NONE`]); the stack goes back to the constrainer for reuse.
    fn legalize_stack(&mut self, mut stack: Vec<(VertexId, VertexId, EdgeId)>) {
        self.inserter
            .mesh_mut()
            .legalize::<P, _>(&mut stack, &mut BetweenSegments::default());
        self.scratch.lawson = stack;
    }

    /// `s`: inserts the midpoint of `a`–`b` as a vertex (recorded with the crossings, for its
    /// attributes); `None` when it cannot be told apart from the ends.
    fn insert_midpoint(&mut self, a: VertexId, b: VertexId) -> Option<VertexId> {
        let (pa, pb) = (self.pt(a), self.pt(b));
        let m = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
        if m == pa || m == pb {
            return None;
        }
        let start = self.vertex_edge(a).triangle();
        let location = self.inserter.locate(m, start);
        if let Location::OnVertex(_) = location {
            return None;
        }
        let vertex = self.inserter.mesh_mut().add_point(m);
        let _ = self.inserter.insert_at(vertex, location);
        self.settle(vertex);
        self.crossings.push(Crossing {
            vertex,
            from: a,
            to: b,
            t: 0.5,
        });
        Some(vertex)
    }

    /// If the vertex beside the edge of `e` on either side lies on it as far as `on_edge(u, v,
    /// w)` tells (within rounding: no vertex lies exactly on an edge), flips the edge away so
    /// that the vertex joins its ends (Lawson flips then make the other edges around locally
    /// Delaunay again), and returns the vertex; a segment edge becomes the two edges to the
    /// vertex. Not when the edge is on the hull or the flip would not be valid.
    fn flip_edge_onto_vertex(
        &mut self,
        e: EdgeId,
        on_edge: impl Fn(Point, Point, Point) -> bool,
    ) -> Option<VertexId> {
        let mesh = self.inserter.mesh();
        for h in [e, mesh.twin(e)] {
            let f = mesh.twin(h);
            if mesh.is_ghost(h.triangle()) || mesh.is_ghost(f.triangle()) {
                return None;
            }
            let (u, v, w, z) = (mesh.origin(h), mesh.dest(h), mesh.apex(h), mesh.apex(f));
            let (pu, pv, pw, pz) = (mesh.point(u), mesh.point(v), mesh.point(w), mesh.point(z));
            // The flip needs the quadrilateral u, z, v, w convex: z–w crosses u–v.
            if !(on_edge(pu, pv, pw)
                && P::orient2d(pz, pw, pu) > 0.0
                && P::orient2d(pz, pw, pv) < 0.0)
            {
                continue;
            }
            let id = mesh.segment_of(h);
            let mesh = self.inserter.mesh_mut();
            mesh.flip(h);
            if id != NONE {
                for (x, y) in [(u, w), (w, v)] {
                    if let Some(g) = mesh.find_edge(x, y) {
                        mesh.set_segment(g, id);
                    }
                }
            }
            self.restore_delaunay(vec![(u, z), (z, v), (v, w), (w, u), (z, w)]);
            return Some(w);
        }
        None
    }

    /// Finds or makes the vertex where the segment from `a` to `b` crosses the segment edge `e`.
    fn split_at_crossing(&mut self, a: VertexId, b: VertexId, e: EdgeId) -> CrossingPoint {
        let mesh = self.inserter.mesh();
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        let (pu, pv) = (self.pt(u), self.pt(v));
        // Parameter along u → v of the crossing with the line a → b.
        let du = self.orient(a, b, u);
        let dv = self.orient(a, b, v);
        let t = du / (du - dv);
        let p = [pu[0] + t * (pv[0] - pu[0]), pu[1] + t * (pv[1] - pu[1])];
        // A crossing within rounding distance of a vertex is that vertex: three segments through
        // one point, or a segment through a vertex that the exact test finds off by an ulp. A new
        // vertex there would create a feature far smaller than the input's, which refinement
        // could only resolve with a cascade of tiny triangles.
        let (pa, pb) = (self.pt(a), self.pt(b));
        let dist2 = |q: Point| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
        let scale2 = dist2(pu).max(dist2(pv)).max(dist2(pa)).max(dist2(pb));
        let snap2 = scale2 * SNAP_RELATIVE * SNAP_RELATIVE;
        for (w, at_crossed_end) in [(u, true), (v, true), (a, false), (b, false)] {
            if dist2(self.pt(w)) <= snap2 {
                return if at_crossed_end {
                    CrossingPoint::Existing(w)
                } else {
                    CrossingPoint::ThroughVertex(w)
                };
            }
        }
        let (c, d) = (mesh.apex(e), mesh.apex(mesh.twin(e)));
        let (pc, pd) = (self.pt(c), self.pt(d));
        let splits_cleanly = P::orient2d(pc, pu, p) > 0.0
            && P::orient2d(pv, pc, p) > 0.0
            && P::orient2d(pu, pd, p) > 0.0
            && P::orient2d(pd, pv, p) > 0.0;
        if !splits_cleanly {
            // The rounded crossing is not inside the crossed edge's quadrilateral (next to a
            // sliver left by an earlier bent segment): insert it where it is, and let both
            // segments bend through it.
            let start = e.triangle();
            return match self.inserter.locate(p, start) {
                Location::OnVertex(w) => CrossingPoint::ThroughVertex(w),
                location => {
                    let vertex = self.inserter.mesh_mut().add_point(p);
                    let _ = self.inserter.insert_at(vertex, location);
                    self.settle(vertex);
                    self.crossings.push(Crossing {
                        vertex,
                        from: u,
                        to: v,
                        t,
                    });
                    CrossingPoint::ThroughVertex(vertex)
                }
            };
        }
        let vertex = self.inserter.mesh_mut().add_point(p);
        let _ = self.inserter.insert_at(vertex, Location::OnEdge(e));
        self.settle(vertex);
        self.crossings.push(Crossing {
            vertex,
            from: u,
            to: v,
            t,
        });
        CrossingPoint::New(vertex)
    }

    /// Lawson flips from the given edges until every non-segment edge is locally Delaunay.
    pub fn restore_delaunay(&mut self, edges: Vec<(VertexId, VertexId)>) {
        let mut stack = self.take_lawson_stack();
        stack.extend(edges.into_iter().map(|(u, v)| (u, v, EdgeId::NONE)));
        self.legalize_stack(stack);
    }

    /// Marks every hull edge that is not a segment yet as a segment with marker `marker` (the `c`
    /// switch, the boundary of a mesh being refined, and refinement of a point set). Each is a
    /// segment of its own, ending at its two vertices.
    pub fn mark_hull(&mut self, marker: i32) {
        for e in self.inserter.mesh().edges() {
            let mesh = self.inserter.mesh();
            let (a, b) = (mesh.origin(e), mesh.dest(e));
            if a != GHOST
                && b != GHOST
                && mesh.apex(mesh.twin(e)) == GHOST
                && mesh.segment_of(e) == NONE
            {
                let id = self.new_segment_id(marker, a, b);
                self.inserter.mesh_mut().set_segment(e, id);
            }
        }
    }

    /// The triangle containing `p`, if `p` lies in the triangulated area.
    pub fn triangle_at(&mut self, p: Point) -> Option<TriangleId> {
        let start = self.inserter.last_triangle();
        match self.inserter.locate(p, start) {
            Location::InTriangle(t) => Some(t),
            Location::OnEdge(e) => Some(e.triangle()),
            Location::OnVertex(v) => self
                .inserter
                .mesh()
                .vertex_edge(v)
                .map(EdgeId::triangle)
                .filter(|&t| !self.inserter.mesh().is_ghost(t)),
            Location::Outside(_) => None,
        }
    }
}

/// Whether a vertex whose orientation with the segment `a`–`b` is `orientation` lies on its
/// line: exactly, or within rounding (closer than [`SNAP_RELATIVE`] times the segment's
/// length). Such a vertex splits the segment: kept apart, it and the segment would make a
/// feature far below the input's scale (a third segment crossing both at points an ulp apart,
/// where lattice coordinates such as 0.2 and 0.6 make overlapping segments miss each other's
/// ends by an ulp), which no refinement could resolve. Triangle keeps them apart, and crashes
/// on some such inputs.
fn on_line(orientation: f64, a: Point, b: Point) -> bool {
    let length2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
    orientation == 0.0 || orientation.abs() <= SNAP_RELATIVE * length2
}

/// Whether `x`, near the line through `a` and `b`, lies before `b` seen from `a` (an edge from
/// `a` to a vertex within rounding of the line may pass by `b`).
fn before(a: Point, x: Point, b: Point) -> bool {
    let d = [b[0] - a[0], b[1] - a[1]];
    (x[0] - a[0]) * d[0] + (x[1] - a[1]) * d[1] < d[0] * d[0] + d[1] * d[1]
}

/// Whether `x`, on or near the line through `a` and `b`, lies on the side of `a` toward `b`.
fn along(a: Point, x: Point, b: Point) -> bool {
    (x[0] - a[0]) * (b[0] - a[0]) + (x[1] - a[1]) * (b[1] - a[1]) > 0.0
}
