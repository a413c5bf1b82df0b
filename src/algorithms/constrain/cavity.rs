//! Recovering a segment whose line crosses triangles: the cavity of the crossed triangles is
//! retriangulated in place as the constrained Delaunay triangulations of the two polygons on
//! either side of the segment (Anglada 1997; Shewchuk and Brown 2015), with Sloan's flips
//! (1993) and a Lawson restore as the fallback when the cavity's plan is refused.

use super::*;

/// A polygon of the cavity: its vertices in order (and their positions, contiguous for the
/// circle tests) and, per consecutive pair `(v[i], v[i+1])`, the half-edge from `v[i]` to
/// `v[i+1]` that stays (outside the cavity, across its boundary).
#[derive(Clone, Default)]
pub(super) struct Chain {
    vertices: Vec<VertexId>,
    points: Vec<Point>,
    outer: Vec<EdgeId>,
}

impl Chain {
    pub(super) fn clear(&mut self) {
        self.vertices.clear();
        self.points.clear();
        self.outer.clear();
    }

    pub(super) fn push(&mut self, vertex: VertexId, point: Point) {
        self.vertices.push(vertex);
        self.points.push(point);
    }

    pub(super) fn reverse(&mut self) {
        self.vertices.reverse();
        self.points.reverse();
        self.outer.reverse();
    }
}

#[derive(Clone, Copy)]
pub(super) enum Polygon {
    Left,
    Right,
}

impl<P: Predicates> Constrainer<P> {
    /// Replaces the triangles that the segment `a`–`b` crosses (the edges in
    /// `self.scratch.crossed`, which must be the complete list from `a` to `b`) by the constrained
    /// Delaunay triangulations of the two polygons the segment cuts their union into, and marks
    /// the segment's edge as segment `id`. Returns false, changing nothing, if triangles are
    /// tagged or the plan is not a valid triangulation (a new triangle not counter-clockwise, an
    /// edge with the cavity on both sides not matched up); neither was seen with exact
    /// predicates, and the caller then recovers the segment by flips.
    // Not inlined into `insert_segment`: inlined, the two loops' register pressure costs more
    // (callgrind: 1.5% more instructions on the star polygon of benches/cdt.rs).
    #[inline(never)]
    pub(super) fn retriangulate_cavity(&mut self, a: VertexId, b: VertexId, id: u32) -> bool {
        if self.inserter.mesh().tracks_tags() {
            // Tags would have to be assigned per new triangle; the flip path does that.
            return false;
        }
        let Scratch {
            crossed,
            left,
            right,
            slots,
            tasks,
            triangles,
            outer_links,
            cavity_of,
            cavity_filter,
            cavity_serial,
            inner_links,
            ..
        } = &mut self.scratch;
        let mesh = self.inserter.mesh();
        // A new serial number marks this cavity's slots (all marks are cleared when it wraps).
        let serial = match cavity_serial.checked_add(1) {
            Some(serial) => serial,
            None => {
                cavity_of.fill(0);
                1
            }
        };
        *cavity_serial = serial;
        cavity_of.resize((mesh.triangle_count() as usize).max(cavity_of.len()), 0);
        let k = crossed.len();
        debug_assert!(k > 0);
        // The crossed triangles T0 … Tk: T0 = (a, r1, l1) holds the first crossed edge r1 → l1;
        // each later one adds its apex to the left or the right chain; Tk has apex b. A chain
        // edge's outer half-edge is the twin of the cavity triangle's half-edge on it.
        // The right chain is collected from a to b here and reversed below.
        left.clear();
        right.clear();
        slots.clear();
        let h1 = crossed[0];
        slots.push(h1.triangle());
        let (pa, l1, r1) = (mesh.point(a), mesh.dest(h1), mesh.origin(h1));
        left.push(a, pa);
        left.push(l1, mesh.point(l1));
        left.outer.push(mesh.twin(h1.next())); // a → l1
        right.push(a, pa);
        right.push(r1, mesh.point(r1));
        right.outer.push(mesh.twin(h1.prev())); // r1 → a
        for i in 0..k {
            let f = mesh.twin(crossed[i]); // left → right, in the next triangle of the cavity
            slots.push(f.triangle());
            let z = mesh.apex(f);
            let pz = mesh.point(z);
            let last = i + 1 == k;
            // The next crossed edge is right → z when z is on the left, z → left otherwise.
            if last || crossed[i + 1] == f.next() {
                left.push(z, pz);
                left.outer.push(mesh.twin(f.prev())); // left → z
            }
            if last || crossed[i + 1] == f.prev() {
                right.push(z, pz);
                right.outer.push(mesh.twin(f.next())); // z → right
            }
        }
        debug_assert!(*left.vertices.last().unwrap() == b && *right.vertices.last().unwrap() == b);
        right.reverse();
        // The union of the crossed triangles need not be a simple polygon: the segment can leave
        // the star of a vertex and enter it again, so a chain may visit a vertex twice, and an
        // edge between two crossed triangles that the segment does not cross lies on a chain
        // twice, once in each direction (Shewchuk and Brown 2015 allow the same). Such an edge's
        // "outer" half-edge is in the cavity; its two new half-edges are joined to each other.
        *cavity_filter = [0; CAVITY_FILTER_WORDS];
        for &t in slots.iter() {
            cavity_of[t.index()] = serial;
            let (word, mask) = cavity_filter_bit(t);
            cavity_filter[word] |= mask;
        }
        let in_cavity = |t: TriangleId| {
            let (word, mask) = cavity_filter_bit(t);
            cavity_filter[word] & mask != 0 && cavity_of[t.index()] == serial
        };
        inner_links.clear();

        // Plan the new triangles: top-down from each polygon's base (the segment), each
        // sub-polygon's base joined to the half-edge of its parent triangle. Slot `slots[j]` takes
        // the `j`-th new triangle; the left polygon's first triangle holds the segment a → b, the
        // right polygon's first one b → a.
        triangles.clear();
        outer_links.clear();
        tasks.clear();
        tasks.push((
            Polygon::Right,
            0,
            right.vertices.len() as u32 - 1,
            EdgeId::NONE,
        ));
        tasks.push((
            Polygon::Left,
            0,
            left.vertices.len() as u32 - 1,
            EdgeId::NONE,
        ));
        while let Some((polygon, first, last, join)) = tasks.pop() {
            let chain = match polygon {
                Polygon::Left => &*left,
                Polygon::Right => &*right,
            };
            // A boundary edge of the cavity (a sub-polygon of two vertices, `first` and
            // `first + 1`): the new half-edge `join` becomes the twin of its outer half-edge.
            let mut join_boundary = |first: u32, join: EdgeId| {
                let outer = chain.outer[first as usize];
                if in_cavity(outer.triangle()) {
                    inner_links.push((join, outer, mesh.segment_of(outer)));
                } else {
                    outer_links.push((join, outer));
                }
            };
            if last == first + 1 {
                join_boundary(first, join);
                continue;
            }
            let (v, points) = (&chain.vertices, &chain.points);
            let (u, w) = (points[first as usize], points[last as usize]);
            // A triangle's worth of polygon has its apex already: no circle to compare.
            let apex = if last == first + 2 {
                first + 1
            } else {
                first
                    + 1
                    + P::smallest_circle(u, w, &points[first as usize + 1..last as usize]) as u32
            };
            if P::orient2d(u, w, points[apex as usize]) <= 0.0 {
                return false;
            }
            let t = slots[triangles.len()];
            let corners = [v[first as usize], v[last as usize], v[apex as usize]];
            let join = if join == EdgeId::NONE && matches!(polygon, Polygon::Right) {
                // The right polygon's base b → a is the twin of the left one's a → b, which is the
                // first new triangle's base (the left polygon is planned first).
                slots[0].edge(0)
            } else {
                join
            };
            triangles.push((corners, join));
            // Triangle (u, w, c): w → c at 3t + 1 faces the sub-polygon (apex … last), c → u at
            // 3t + 2 the sub-polygon (first … apex). Boundary edges are joined at once (the order
            // of the joins does not matter); the others wait on the stack, in the same order as
            // if the boundary edges were stacked too (they make no triangles).
            if last == apex + 1 {
                join_boundary(apex, t.edge(1));
            } else {
                tasks.push((polygon, apex, last, t.edge(1)));
            }
            if apex == first + 1 {
                join_boundary(first, t.edge(2));
            } else {
                tasks.push((polygon, first, apex, t.edge(2)));
            }
        }
        debug_assert_eq!(triangles.len(), slots.len());
        if !inner_links.is_empty() {
            // Each such edge came up twice, as old half-edge h and as its old twin: pair the two
            // new half-edges by the edge's smaller old half-edge.
            if inner_links.len() % 2 != 0 {
                return false;
            }
            for link in inner_links.iter_mut() {
                link.1 = link.1.min(mesh.twin(link.1));
            }
            inner_links.sort_unstable_by_key(|&(_, key, _)| key);
            if inner_links
                .chunks_exact(2)
                .any(|pair| pair[0].1 != pair[1].1)
            {
                return false;
            }
        }

        // Commit: the slots' triangles are rewritten, joined to each other and to the outside.
        let mesh = self.inserter.mesh_mut();
        for (&t, &(corners, join)) in slots.iter().zip(triangles.iter()) {
            // Every cavity vertex is a corner of a new triangle: its outgoing half-edge is
            // refreshed here (the old one may have been in the cavity).
            mesh.rewrite_triangle(t, corners);
            if join != EdgeId::NONE {
                mesh.link(t.edge(0), join);
            }
        }
        for &(inner, outer) in outer_links.iter() {
            mesh.link_to_outer(inner, outer);
        }
        for pair in inner_links.chunks_exact(2) {
            // The segment did not cross this edge, so it may be a segment: it stays one.
            let (x, y, segment) = (pair[0].0, pair[1].0, pair[0].2);
            mesh.link(x, y);
            mesh.set_segment(x, segment);
        }
        mesh.set_segment(slots[0].edge(0), id);
        true
    }

    /// Removes the edges crossing the new segment `a`–`b` by Sloan's flips, marks the recovered
    /// edge as segment `id`, then restores the constrained Delaunay property around the new edges.
    pub(super) fn remove_crossings(
        &mut self,
        a: VertexId,
        b: VertexId,
        crossed: Vec<(VertexId, VertexId)>,
        id: u32,
    ) -> Result<(), Error> {
        let lost = |what: &str| Error::Internal(format!("segment recovery by flips: {what}"));
        let mut queue: VecDeque<(VertexId, VertexId)> = crossed.into();
        let mut new_edges = Vec::new();
        let mut stalls = 0usize;
        while let Some((u, v)) = queue.pop_front() {
            let mesh = self.inserter.mesh();
            let e = mesh
                .find_edge(u, v)
                .ok_or_else(|| lost("a crossing edge is gone"))?;
            let f = mesh.twin(e);
            let (p, q) = (mesh.apex(e), mesh.apex(f));
            // The quadrilateral u, q, v, p is strictly convex when p–q crosses u–v.
            let convex = self.orient(p, q, u) * self.orient(p, q, v) < 0.0;
            if !convex {
                queue.push_back((u, v));
                stalls += 1;
                if stalls > 4 * queue.len() * queue.len() + 16 {
                    return Err(lost("no progress"));
                }
                continue;
            }
            stalls = 0;
            self.inserter.mesh_mut().flip(e);
            let crosses = {
                let (op, oq) = (self.orient(a, b, p), self.orient(a, b, q));
                p != a && p != b && q != a && q != b && op * oq < 0.0
            };
            if crosses {
                queue.push_back((p, q));
            } else {
                new_edges.push((p, q));
            }
        }
        let e = self
            .inserter
            .mesh()
            .find_edge(a, b)
            .ok_or_else(|| lost("the segment is not an edge afterwards"))?;
        self.inserter.mesh_mut().set_segment(e, id);
        self.restore_delaunay(new_edges);
        Ok(())
    }
}
