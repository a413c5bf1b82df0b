//! Deleting a vertex on a segment: the two subsegments beside it become one.
//!
//! Refinement splits subsegments; once the mesh is finished, a split that later splits nearby
//! made superfluous can be undone (the improvement of a finished refinement). The vertex `v`
//! between subsegments `a`–`v` and `v`–`b` of one segment is taken out much as
//! [`Mesh::delete_vertex`] takes out a free vertex: on each side of the segment, edges to `v`
//! whose quadrilateral is strictly convex are flipped (planned on the link first) until one
//! link vertex is left there, `l` on one side and `r` on the other (or the vertex at infinity,
//! beside a hull segment); then the four triangles `(v, a, l)`, `(v, l, b)`, `(v, b, r)`,
//! `(v, r, a)` become `(a, l, b)` and `(b, r, a)`, edge `a`–`b` the segment, and Lawson flips,
//! segments fixed, restore the constrained Delaunay property inside the old star.

use super::{EdgeId, Mesh, TriangleId, VertexId, GHOST};
use crate::geometry::Predicates;

impl Mesh {
    /// The two vertices joined to `v` by subsegments of one segment, if `v` lies between
    /// exactly two such (a vertex refinement put on a segment, where it stays one segment).
    pub fn segment_neighbours(&self, v: VertexId) -> Option<[VertexId; 2]> {
        let mut on_segment = self.star(v).filter(|&e| self.is_segment(e));
        let (first, second) = (on_segment.next()?, on_segment.next()?);
        let one_segment =
            on_segment.next().is_none() && self.segment_of(first) == self.segment_of(second);
        one_segment.then(|| [self.dest(first), self.dest(second)])
    }

    /// Deletes vertex `v`, which lies between exactly two subsegments of one segment, from a
    /// constrained Delaunay mesh (exact predicates `P`; see the module documentation): the
    /// subsegments become one, from `a` to `b`, and the mesh stays constrained Delaunay.
    /// Returns the triangles that now fill its old star, or `None` when `v` is kept and the
    /// mesh left as it is: `v` is not such a vertex, a side of the segment has no vertex (a flat
    /// triangle) or a vertex at infinity among others, a side's triangles have two tags, the link is degenerate, or `a`
    /// –`b` would not have its two triangles counter-clockwise. As with
    /// [`Self::delete_vertex`], the vertex keeps its id and point in no triangle, and two slots
    /// are freed (the last ones move into them).
    pub fn delete_segment_vertex<P: Predicates>(&mut self, v: VertexId) -> Option<Vec<TriangleId>> {
        if !self.tracks_segments() || !self.tracks_vertex_edges() {
            return None;
        }
        let star: Vec<EdgeId> = self.star(v).collect();
        let on_segment: Vec<usize> = (0..star.len())
            .filter(|&i| self.is_segment(star[i]))
            .collect();
        let &[i, j] = on_segment.as_slice() else {
            return None;
        };
        let segment = self.segment_of(star[i]);
        if segment != self.segment_of(star[j]) {
            return None;
        }
        let link: Vec<VertexId> = star.iter().map(|&e| self.dest(e)).collect();
        let k = link.len();
        // The two sides, each from one end of the segment around to the other.
        let side = |from: usize, to: usize| -> Vec<VertexId> {
            let mut ring = vec![link[from]];
            let mut m = (from + 1) % k;
            while m != to {
                ring.push(link[m]);
                m = (m + 1) % k;
            }
            ring.push(link[to]);
            ring
        };
        let sides = [side(i, j), side(j, i)];
        let pv = self.point(v);
        let mut plan: Vec<(VertexId, (VertexId, VertexId))> = Vec::new();
        for (s, ring) in sides.iter().enumerate() {
            let (from, to) = if s == 0 { (i, j) } else { (j, i) };
            // One tag per side (each side's triangles: from `from` to just before `to`).
            if self.tracks_tags() {
                let tag = self.tag(star[from].triangle());
                let mut m = from;
                while m != to {
                    if self.tag(star[m].triangle()) != tag {
                        return None;
                    }
                    m = (m + 1) % k;
                }
            }
            // No vertex on this side: `v` is off the line from `a` to `b`, in a flat triangle.
            if ring.len() < 3 {
                return None;
            }
            if ring.contains(&GHOST) {
                if ring.len() != 3 {
                    return None;
                }
                continue;
            }
            let mut ring = ring.clone();
            while ring.len() > 3 {
                let n = ring.len();
                let ear = (1..n - 1).find(|&m| {
                    let (a, b, c) = (ring[m - 1], ring[m], ring[m + 1]);
                    let (pa, pb, pc) = (self.point(a), self.point(b), self.point(c));
                    P::orient2d(pa, pb, pc) > 0.0 && P::orient2d(pv, pa, pc) > 0.0
                })?;
                plan.push((ring[ear], (ring[ear - 1], ring[ear + 1])));
                ring.remove(ear);
            }
            // The triangle left on this side once `v` is gone must be counter-clockwise.
            let [a, l, b] = [ring[0], ring[1], ring[2]].map(|w| self.point(w));
            if P::orient2d(a, l, b) <= 0.0 {
                return None;
            }
        }
        let (a, b) = (link[i], link[j]);
        let mut stack: Vec<(VertexId, VertexId, EdgeId)> = Vec::new();
        for (w, (x, y)) in plan {
            let e = self.find_edge(v, w).expect("an edge of the star");
            // (v, x, y) and (x, w, y): the diagonal is the first one's slot 1.
            let [t, _] = self.flip(e);
            stack.push((x, y, t.edge(1)));
        }
        // Degree 4: v→a, v→l, v→b, v→r counter-clockwise.
        let e_a = self.find_edge(v, a).expect("a subsegment");
        let e_b = self.find_edge(v, b).expect("a subsegment");
        let e_l = self.twin(e_a.next().next());
        let e_r = self.twin(e_b.next().next());
        let (l, r) = (self.dest(e_l), self.dest(e_r));
        let outer = [e_a, e_l, e_b, e_r].map(|e| self.twin(e.next()));
        let [t_al, t_lb, t_br, t_ra] = [e_a, e_l, e_b, e_r].map(EdgeId::triangle);
        // (v, a, l) becomes (b, a, l) and (v, b, r) becomes (a, b, r).
        self.set_corners(t_al, [b, a, l]);
        self.set_corners(t_br, [a, b, r]);
        self.link(t_al.edge(0), t_br.edge(0));
        self.link(t_al.edge(1), outer[0]);
        self.link(t_al.edge(2), outer[1]);
        self.link(t_br.edge(1), outer[2]);
        self.link(t_br.edge(2), outer[3]);
        self.refresh(&[t_al.raw(), t_br.raw()], &[]);
        self.set_segment(t_al.edge(0), segment);
        self.vertex_edge[v.index()] = super::NONE;
        self.remove_slot(t_lb.max(t_ra));
        self.remove_slot(t_lb.min(t_ra));
        let start = self
            .find_edge(a, b)
            .expect("the merged subsegment")
            .triangle();
        let mut made = Vec::new();
        self.restore_hole::<P>(start, &link, &mut stack, &mut Vec::new(), &mut made, true);
        Some(made)
    }
}
