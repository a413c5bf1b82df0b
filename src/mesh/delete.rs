//! Deleting a vertex from a constrained Delaunay triangulation, and dropping deleted vertices
//! from the numbering.
//!
//! Delaunay refinement after Chew ("Guaranteed-quality mesh generation for curved surfaces",
//! 1993; "Guaranteed-quality Delaunay meshing in 3D", 1997), as Shewchuk describes it
//! ("Delaunay refinement algorithms for triangular mesh generation", CGTA 2002, §5): when a
//! subsegment is split, the free vertices inside its diametral circle are deleted first. A
//! vertex inside the domain, on no segment, is deleted here by flips that lower its degree:
//! an edge to it whose quadrilateral is strictly convex is flipped (which makes it one edge
//! fewer) until three are left — planned on its link first: where no such edge is left (a
//! degenerate star, neighbours on lines through it, as on a grid) the vertex is kept and the
//! mesh left as it is — then its three triangles become one, and Lawson flips of the edges in
//! its old star, segments fixed, restore the constrained Delaunay property (Lawson 1977; Chew
//! 1989). Only the triangles of its old star change: the others stay constrained Delaunay when a
//! vertex goes (their circumcircles hold no more visible vertices than before).

use super::{BetweenSegments, EdgeId, Mesh, TriangleId, VertexId, GHOST, NONE};
use crate::geometry::Predicates;

/// Buffers of [`Mesh::delete_vertex_with`], kept between deletions so that one allocates
/// nothing once they have grown (the improvement deletes, and puts back, nearly every free
/// vertex).
#[derive(Clone, Debug, Default)]
pub struct Deletion {
    /// The deleted vertex's link.
    link: Vec<VertexId>,
    /// The link while flips are planned on it.
    ring: Vec<VertexId>,
    /// The planned flips: each link vertex that leaves, with the diagonal it leaves.
    plan: Vec<(VertexId, (VertexId, VertexId))>,
    /// The Lawson stack.
    stack: Vec<(VertexId, VertexId, EdgeId)>,
    /// The triangles of the flips.
    flipped: Vec<TriangleId>,
}

impl Mesh {
    /// Whether [`Self::delete_vertex`] may delete `v`: it is a corner of some triangle, not on
    /// the hull or the domain's boundary (no edge to the vertex at infinity), on no segment (no
    /// edge of it is one), and its triangles all have one tag (the merged triangle keeps it).
    /// Needs segment and vertex tracking.
    pub fn is_deletable(&self, v: VertexId) -> bool {
        if !self.tracks_segments() || !self.tracks_vertex_edges() {
            return false;
        }
        let Some(first) = self.vertex_edge(v) else {
            return false;
        };
        let tag = self.tracks_tags().then(|| self.tag(first.triangle()));
        self.star(v).all(|e| {
            self.dest(e) != GHOST
                && !self.is_segment(e)
                && tag.is_none_or(|tag| self.tag(e.triangle()) == tag)
        })
    }

    /// Deletes vertex `v` (see the module documentation) from a constrained Delaunay mesh, which
    /// stays constrained Delaunay (exact predicates `P`). Returns the triangles that now fill
    /// its old star, or `None` when `v` is kept and the mesh left as it is
    /// ([`Self::is_deletable`] says no, or its star is degenerate). The vertex keeps its id
    /// and point, in no triangle (see [`Self::remove_vertices`]). Two triangle slots are
    /// freed: the last slots move into them, so that the slots stay `0 .. triangle_count()`
    /// (ids of the moved triangles change; twins, segment ids, tags and vertex edges follow).
    pub fn delete_vertex<P: Predicates>(&mut self, v: VertexId) -> Option<Vec<TriangleId>> {
        let mut made = Vec::new();
        self.delete_vertex_with::<P>(v, &mut Deletion::default(), &mut made)
            .then_some(made)
    }

    /// [`Self::delete_vertex`] with buffers kept by the caller: whether `v` was deleted, the
    /// triangles that now fill its old star in `made` (cleared first; left empty when not).
    pub fn delete_vertex_with<P: Predicates>(
        &mut self,
        v: VertexId,
        scratch: &mut Deletion,
        made: &mut Vec<TriangleId>,
    ) -> bool {
        made.clear();
        if !self.is_deletable(v) {
            return false;
        }
        let Deletion {
            link,
            ring,
            plan,
            stack,
            flipped,
        } = scratch;
        link.clear();
        link.extend(self.star(v).map(|e| self.dest(e)));
        // The edges to check afterwards, as vertex pairs (flips renumber half-edges), each with
        // its half-edge as a hint.
        stack.clear();
        // The flips planned on the link alone, so that a degenerate star leaves the mesh as it
        // is. Flipping edge v → w_i, in (v, w_i, w_i+1) and (w_i, v, w_i-1), makes them
        // (v, w_i-1, w_i+1) and (w_i-1, w_i, w_i+1), both counter-clockwise exactly when the
        // quadrilateral is strictly convex; w_i leaves v's link.
        ring.clear();
        ring.extend_from_slice(link);
        plan.clear();
        let pv = self.point(v);
        while ring.len() > 3 {
            let k = ring.len();
            let ear = (0..k).find(|&i| {
                let (a, b, c) = (ring[(i + k - 1) % k], ring[i], ring[(i + 1) % k]);
                let (pa, pb, pc) = (self.point(a), self.point(b), self.point(c));
                P::orient2d(pa, pb, pc) > 0.0 && P::orient2d(pv, pa, pc) > 0.0
            });
            // None: a degenerate star, `v` stays.
            let Some(i) = ear else {
                return false;
            };
            plan.push((ring[i], (ring[(i + k - 1) % k], ring[(i + 1) % k])));
            ring.remove(i);
        }
        for &(w, (x, y)) in plan.iter() {
            let e = self.find_edge(v, w).expect("an edge of the star");
            // (v, x, y) and (x, w, y): the diagonal is the first one's slot 1.
            let [t, _] = self.flip(e);
            stack.push((x, y, t.edge(1)));
        }
        // Degree 3: (v, a, b), (v, b, c), (v, c, a) become (a, b, c) in the first one's slot.
        let mut star = self.star(v);
        let edges = [(); 3].map(|_| star.next().expect("a star of three"));
        let [a, b, c] = edges.map(|e| self.dest(e));
        let outer = edges.map(|e| self.twin(e.next()));
        let [t0, t1, t2] = edges.map(EdgeId::triangle);
        self.set_corners(t0, [a, b, c]);
        for (k, &o) in outer.iter().enumerate() {
            self.link(t0.edge(k as u32), o);
        }
        // Vertex edges of a, b, c into t0, segment ids from the outer twins.
        self.refresh(&[t0.raw()], &[]);
        self.vertex_edge[v.index()] = NONE;
        self.remove_slot(t1.max(t2));
        self.remove_slot(t1.min(t2));
        let start = self
            .find_edge(a, b)
            .expect("the merged triangle")
            .triangle();
        // The stack holds every diagonal of the hole (each planned flip made one): the polygon's
        // edges, Delaunay before, stay so (the triangles that fill a deleted vertex's star are
        // the constrained Delaunay triangulation of its link; nothing outside changes).
        self.restore_hole::<P>(start, link, stack, flipped, made, false);
        debug_assert!(made.len() >= link.len() - 2);
        #[cfg(debug_assertions)]
        {
            // Every edge of the filled hole is locally Delaunay already: Lawson flips nothing.
            let mut all: Vec<_> = made
                .iter()
                .flat_map(|t| t.edges())
                .map(|e| (self.origin(e), self.dest(e), e))
                .filter(|&(x, y, _)| x != GHOST && y != GHOST)
                .collect();
            let mut check = BetweenSegments {
                record: true,
                flipped: Vec::new(),
            };
            self.legalize::<P, _>(&mut all, &mut check);
            debug_assert!(
                check.flipped.is_empty(),
                "a deletion left a non-Delaunay edge"
            );
        }
        true
    }

    /// After a vertex is taken out: Lawson flips, segments fixed, from `stack` and, with
    /// `stack_hole_edges`, from the edges of the triangles inside its old link `link` (found
    /// from triangle `start`, see [`Self::hole`]). Puts in `made` (empty) those triangles and
    /// the ones flips made, without repeats; `flipped`: scratch space.
    pub(super) fn restore_hole<P: Predicates>(
        &mut self,
        start: TriangleId,
        link: &[VertexId],
        stack: &mut Vec<(VertexId, VertexId, EdgeId)>,
        flipped: &mut Vec<TriangleId>,
        made: &mut Vec<TriangleId>,
        stack_hole_edges: bool,
    ) {
        self.hole(start, link, made);
        if stack_hole_edges {
            for &t in made.iter() {
                stack.extend(
                    t.edges()
                        .into_iter()
                        .map(|e| (self.origin(e), self.dest(e), e))
                        .filter(|&(x, y, _)| x != GHOST && y != GHOST),
                );
            }
        }
        flipped.clear();
        let mut lawson = BetweenSegments {
            record: true,
            flipped: std::mem::take(flipped),
        };
        self.legalize::<P, _>(stack, &mut lawson);
        // Flips keep their two slots: the hole's slots are still its triangles (and, were
        // rounding to flip an edge of its polygon, the flipped ones beyond).
        made.extend_from_slice(&lawson.flipped);
        *flipped = lawson.flipped;
        made.sort_unstable();
        made.dedup();
    }

    /// The triangles inside the polygon `link` (a vertex's old star, counter-clockwise) from
    /// triangle `start` inside it: across every edge that is not one of the polygon's, into
    /// triangles whose corners are all on it. Into `hole` (empty).
    pub(super) fn hole(&self, start: TriangleId, link: &[VertexId], hole: &mut Vec<TriangleId>) {
        let k = link.len();
        let polygon_edge = |x: VertexId, y: VertexId| {
            link.iter()
                .position(|&w| w == x)
                .is_some_and(|i| link[(i + 1) % k] == y || link[(i + k - 1) % k] == y)
        };
        debug_assert!(hole.is_empty());
        hole.push(start);
        let mut i = 0;
        while i < hole.len() {
            let t = hole[i];
            i += 1;
            for e in t.edges() {
                if polygon_edge(self.origin(e), self.dest(e)) {
                    continue;
                }
                let n = self.twin(e).triangle();
                if !hole.contains(&n) && self.triangle(n).iter().all(|w| link.contains(w)) {
                    hole.push(n);
                }
            }
        }
    }

    /// Frees triangle slot `t`, which no half-edge's twin and no vertex edge refers to: the
    /// last slot's triangle moves into it (its neighbours' twins, its corners' vertex edges,
    /// its segment ids and tag follow), and the arrays shrink by one triangle.
    pub(super) fn remove_slot(&mut self, t: TriangleId) {
        let last = self.triangle_count() - 1;
        let (to, from) = (3 * t.index(), 3 * last as usize);
        if t.raw() != last {
            for k in 0..3 {
                let corner = self.corners[from + k];
                let twin = self.twins[from + k];
                self.corners[to + k] = corner;
                self.twins[to + k] = twin;
                self.twins[twin as usize] = (to + k) as u32;
                if !self.segment.is_empty() {
                    self.segment[to + k] = self.segment[from + k];
                }
                if corner != GHOST.raw()
                    && !self.vertex_edge.is_empty()
                    && self.vertex_edge[corner as usize] == (from + k) as u32
                {
                    self.vertex_edge[corner as usize] = (to + k) as u32;
                }
            }
            if !self.tag.is_empty() {
                self.tag[t.index()] = self.tag[last as usize];
            }
        }
        self.corners.truncate(from);
        self.twins.truncate(from);
        if !self.segment.is_empty() {
            self.segment.truncate(from);
        }
        if !self.tag.is_empty() {
            self.tag.truncate(last as usize);
        }
    }

    /// Removes the vertices for which `keep` is false, none of which may be a corner (vertices
    /// deleted by [`Self::delete_vertex`]); the others keep their order, renumbered from 0
    /// (corners and vertex edges follow). Returns each old vertex's new id, [`NONE`] for the
    /// removed ones.
    pub fn remove_vertices(&mut self, keep: impl Fn(VertexId) -> bool) -> Vec<u32> {
        let n = self.points.len();
        let mut new_id = vec![NONE; n];
        let mut count = 0;
        for (v, id) in new_id.iter_mut().enumerate() {
            if keep(VertexId::new(v as u32)) {
                *id = count as u32;
                self.points[count] = self.points[v];
                if !self.vertex_edge.is_empty() {
                    self.vertex_edge[count] = self.vertex_edge[v];
                }
                count += 1;
            }
        }
        self.points.truncate(count);
        if !self.vertex_edge.is_empty() {
            self.vertex_edge.truncate(count);
        }
        for c in self.corners.iter_mut() {
            if *c != GHOST.raw() {
                *c = new_id[*c as usize];
                assert!(*c != NONE, "a removed vertex is a corner");
            }
        }
        new_id
    }
}
