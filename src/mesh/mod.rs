//! The triangle mesh: topology in flat arrays with `u32` indices.
//!
//! Triangle `t` owns the three half-edges `3t`, `3t+1`, `3t+2`. Half-edge `e` starts at corner
//! `e % 3` of its triangle and ends at the next corner; triangles are counter-clockwise, so each
//! triangle lies to the left of its half-edges. `twins[e]` is the opposite half-edge in the
//! neighbouring triangle.
//!
//! The outside of the triangulation is covered with *ghost* triangles that share the vertex at
//! infinity, [`GHOST`]: every hull edge has a real triangle on one side and a ghost on the other,
//! so every half-edge has a twin and insertion outside the hull needs no special case (the ghost
//! "circumcircle" is the open half-plane beyond its hull edge).

use crate::geometry::Point;

/// The vertex at infinity, a corner of every ghost triangle.
pub const GHOST: u32 = u32::MAX;
/// "No half-edge / no triangle".
pub const NONE: u32 = u32::MAX;

/// The half-edge after `e` in its triangle (counter-clockwise).
#[inline(always)]
pub fn next(e: u32) -> u32 {
    if e % 3 == 2 {
        e - 2
    } else {
        e + 1
    }
}

/// The half-edge before `e` in its triangle.
#[inline(always)]
pub fn prev(e: u32) -> u32 {
    if e % 3 == 0 {
        e + 2
    } else {
        e - 1
    }
}

/// The triangle that owns half-edge `e`.
#[inline(always)]
pub fn triangle_of(e: u32) -> u32 {
    e / 3
}

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex coordinates; the index is the vertex id.
    pub points: Vec<Point>,
    /// Corner `i` of triangle `t` at `corners[3t + i]` (the origin of half-edge `3t + i`).
    pub corners: Vec<u32>,
    /// The twin of each half-edge.
    pub twins: Vec<u32>,
    /// Per half-edge: the id of the segment it lies on, or [`NONE`]. Empty while segments are
    /// not tracked (plain Delaunay triangulation); see [`Mesh::track_segments`].
    pub segment: Vec<u32>,
    /// Per vertex: a half-edge that starts at it, or [`NONE`]. Empty while not tracked; see
    /// [`Mesh::track_vertex_edges`].
    pub vertex_edge: Vec<u32>,
    /// Per triangle: a tag (which part of the domain it belongs to; [`OUTSIDE`] for ghosts and
    /// eaten triangles). Empty while not tracked. New triangles inherit the tag of the triangle
    /// they were split from; flips never cross segments, which bound the tagged parts.
    pub tag: Vec<u32>,
}

/// The tag of triangles outside the domain.
pub const OUTSIDE: u32 = 0;

impl Mesh {
    pub fn with_points(points: Vec<Point>) -> Mesh {
        let capacity = 3 * (2 * points.len() + 2);
        Mesh {
            points,
            corners: Vec::with_capacity(capacity),
            twins: Vec::with_capacity(capacity),
            segment: Vec::new(),
            vertex_edge: Vec::new(),
            tag: Vec::new(),
        }
    }

    /// Starts tracking which edges are segments (all none yet). Every operation keeps it up to
    /// date from then on: split halves of a segment stay on it, flips must not touch segments.
    pub fn track_segments(&mut self) {
        if self.segment.is_empty() {
            self.segment = vec![NONE; self.corners.len()];
        }
    }

    /// Starts tracking one outgoing half-edge per vertex, kept valid by every operation.
    pub fn track_vertex_edges(&mut self) {
        self.vertex_edge = vec![NONE; self.points.len()];
        for e in 0..self.corners.len() as u32 {
            let v = self.corners[e as usize];
            if v != GHOST {
                self.vertex_edge[v as usize] = e;
            }
        }
    }

    /// Adds a vertex (not yet connected to the mesh); returns its id.
    pub fn add_point(&mut self, p: Point) -> u32 {
        self.points.push(p);
        if !self.vertex_edge.is_empty() {
            self.vertex_edge.push(NONE);
        }
        (self.points.len() - 1) as u32
    }

    #[inline(always)]
    pub fn segment_of(&self, e: u32) -> u32 {
        if self.segment.is_empty() {
            NONE
        } else {
            self.segment[e as usize]
        }
    }

    #[inline(always)]
    pub fn is_segment(&self, e: u32) -> bool {
        self.segment_of(e) != NONE
    }

    /// Marks both half-edges of the edge of `e` as lying on segment `id`.
    pub fn set_segment(&mut self, e: u32, id: u32) {
        self.track_segments();
        let f = self.twin(e);
        self.segment[e as usize] = id;
        self.segment[f as usize] = id;
    }

    /// Makes the edge of `e` an ordinary edge again.
    pub fn clear_segment(&mut self, e: u32) {
        let f = self.twin(e);
        self.segment[e as usize] = NONE;
        self.segment[f as usize] = NONE;
    }

    /// The half-edge from `a` to `b`, if they are joined by an edge (needs vertex tracking).
    pub fn find_edge(&self, a: u32, b: u32) -> Option<u32> {
        let start = self.vertex_edge[a as usize];
        if start == NONE {
            return None;
        }
        let mut e = start;
        loop {
            if self.dest(e) == b {
                return Some(e);
            }
            e = self.twin(prev(e));
            if e == start {
                return None;
            }
        }
    }

    /// After triangles were rewritten: every corner's outgoing half-edge and every new
    /// half-edge's segment id (copied from its external twin, or none for an inner edge).
    #[inline(always)]
    fn refresh(&mut self, triangles: &[u32], inner: &[u32]) {
        if !self.vertex_edge.is_empty() {
            for &t in triangles {
                for e in 3 * t..3 * t + 3 {
                    let v = self.corners[e as usize];
                    if v != GHOST {
                        self.vertex_edge[v as usize] = e;
                    }
                }
            }
        }
        if !self.segment.is_empty() {
            self.segment.resize(self.corners.len(), NONE);
            for &t in triangles {
                for e in 3 * t..3 * t + 3 {
                    let f = self.twins[e as usize];
                    self.segment[e as usize] = if inner.contains(&e) {
                        NONE
                    } else {
                        self.segment[f as usize]
                    };
                }
            }
        }
    }

    /// Number of triangle slots (real and ghost).
    #[inline(always)]
    pub fn triangle_count(&self) -> u32 {
        (self.corners.len() / 3) as u32
    }

    #[inline(always)]
    pub fn origin(&self, e: u32) -> u32 {
        self.corners[e as usize]
    }

    #[inline(always)]
    pub fn dest(&self, e: u32) -> u32 {
        self.corners[next(e) as usize]
    }

    /// The corner opposite half-edge `e` in its triangle.
    #[inline(always)]
    pub fn apex(&self, e: u32) -> u32 {
        self.corners[prev(e) as usize]
    }

    #[inline(always)]
    pub fn twin(&self, e: u32) -> u32 {
        self.twins[e as usize]
    }

    #[inline(always)]
    pub fn point(&self, v: u32) -> Point {
        self.points[v as usize]
    }

    /// The three corners of triangle `t`.
    #[inline(always)]
    pub fn triangle(&self, t: u32) -> [u32; 3] {
        let i = 3 * t as usize;
        [self.corners[i], self.corners[i + 1], self.corners[i + 2]]
    }

    #[inline(always)]
    pub fn is_ghost(&self, t: u32) -> bool {
        let [a, b, c] = self.triangle(t);
        a == GHOST || b == GHOST || c == GHOST
    }

    #[inline(always)]
    fn link(&mut self, a: u32, b: u32) {
        self.twins[a as usize] = b;
        self.twins[b as usize] = a;
    }

    /// Appends a triangle with the given corners and unset twins; returns its index.
    #[inline(always)]
    pub fn add_triangle(&mut self, a: u32, b: u32, c: u32) -> u32 {
        let t = self.triangle_count();
        self.corners.extend_from_slice(&[a, b, c]);
        self.twins.extend_from_slice(&[NONE, NONE, NONE]);
        t
    }

    #[inline(always)]
    fn set_triangle(&mut self, t: u32, a: u32, b: u32, c: u32) {
        let i = 3 * t as usize;
        self.corners[i] = a;
        self.corners[i + 1] = b;
        self.corners[i + 2] = c;
    }

    /// Covers the boundary of a mesh whose boundary half-edges have no twin yet ([`NONE`]) with
    /// ghost triangles: one `(w, v, ∞)` per boundary half-edge `v → w`, each linked to its
    /// neighbours around the boundary vertices. The boundary need not be convex, and may have
    /// holes and vertices where two parts of the mesh touch: around boundary vertex `v`, turning
    /// counter-clockwise inside the mesh from the boundary edge leaving `v` reaches the boundary
    /// edge entering `v` in the same part, and their ghosts share `v–∞`. A ghost takes the
    /// segment id of its boundary edge and the tag [`OUTSIDE`].
    pub fn cover_boundary_with_ghosts(&mut self) {
        let boundary: Vec<u32> = (0..self.corners.len() as u32)
            .filter(|&e| self.twins[e as usize] == NONE)
            .collect();
        for &h in &boundary {
            let g = self.add_triangle(self.dest(h), self.origin(h), GHOST);
            self.link(h, 3 * g);
        }
        for &h in &boundary {
            let mut e = h;
            let entering = loop {
                let f = self.twin(prev(e));
                if self.is_ghost(triangle_of(f)) {
                    break f;
                }
                e = f;
            };
            // Ghost of h: (w, v, ∞) with slot 1 = v → ∞; ghost of the entering edge x → v:
            // (v, x, ∞) with slot 2 = ∞ → v.
            let (g, ghost_prev) = (triangle_of(self.twin(h)), triangle_of(entering));
            self.link(3 * g + 1, 3 * ghost_prev + 2);
        }
        if !self.segment.is_empty() {
            self.segment.resize(self.corners.len(), NONE);
            for &h in &boundary {
                let ghost_edge = self.twin(h) as usize;
                self.segment[ghost_edge] = self.segment[h as usize];
            }
        }
        if !self.tag.is_empty() {
            self.tag.resize(self.triangle_count() as usize, OUTSIDE);
        }
    }

    /// Keeps only the real triangles for which `keep` holds (their order kept, renumbered from
    /// 0) and covers the new boundary with ghosts. Segment ids, tags and vertex edges (where
    /// tracked) follow; a vertex left in no triangle has no edge.
    pub fn retain_triangles(&mut self, keep: impl Fn(u32) -> bool) {
        let old = std::mem::take(self);
        let mut new_index = vec![NONE; old.triangle_count() as usize];
        let mut kept = 0u32;
        for t in 0..old.triangle_count() {
            if !old.is_ghost(t) && keep(t) {
                new_index[t as usize] = kept;
                kept += 1;
            }
        }
        let tracks_segments = !old.segment.is_empty();
        let tracks_tags = !old.tag.is_empty();
        let mut mesh = Mesh {
            points: old.points.clone(),
            ..Mesh::default()
        };
        for t in 0..old.triangle_count() {
            if new_index[t as usize] == NONE {
                continue;
            }
            mesh.corners
                .extend_from_slice(&old.corners[3 * t as usize..3 * t as usize + 3]);
            for e in 3 * t..3 * t + 3 {
                let f = old.twins[e as usize];
                let u = new_index[triangle_of(f) as usize];
                mesh.twins
                    .push(if u == NONE { NONE } else { 3 * u + f % 3 });
                if tracks_segments {
                    mesh.segment.push(old.segment[e as usize]);
                }
            }
            if tracks_tags {
                mesh.tag.push(old.tag[t as usize]);
            }
        }
        mesh.cover_boundary_with_ghosts();
        if !old.vertex_edge.is_empty() {
            mesh.track_vertex_edges();
        }
        *self = mesh;
    }

    /// Starts a triangulation with the counter-clockwise triangle `(a, b, c)` and the three
    /// ghosts around it. Returns the real triangle.
    pub fn init_triangle(&mut self, a: u32, b: u32, c: u32) -> u32 {
        let t = self.add_triangle(a, b, c);
        let gab = self.add_triangle(b, a, GHOST);
        let gbc = self.add_triangle(c, b, GHOST);
        let gca = self.add_triangle(a, c, GHOST);
        self.link(3 * t, 3 * gab);
        self.link(3 * t + 1, 3 * gbc);
        self.link(3 * t + 2, 3 * gca);
        self.link(3 * gab + 1, 3 * gca + 2);
        self.link(3 * gab + 2, 3 * gbc + 1);
        self.link(3 * gbc + 2, 3 * gca + 1);
        t
    }

    /// Splits triangle `t = (a, b, c)` at the new vertex `p` into `(a, b, p)`, `(b, c, p)` and
    /// `(c, a, p)`. In each of the three, half-edge slot 0 is the edge opposite `p`. Returns the
    /// three triangles. Works for ghosts too (a point beyond a hull edge splits its ghost).
    pub fn split_triangle(&mut self, t: u32, p: u32) -> [u32; 3] {
        let [a, b, c] = self.triangle(t);
        let (tw_ab, tw_bc, tw_ca) = (self.twin(3 * t), self.twin(3 * t + 1), self.twin(3 * t + 2));
        self.set_triangle(t, a, b, p);
        let t1 = self.add_triangle(b, c, p);
        let t2 = self.add_triangle(c, a, p);
        self.link(3 * t, tw_ab);
        self.link(3 * t1, tw_bc);
        self.link(3 * t2, tw_ca);
        self.link(3 * t + 1, 3 * t1 + 2);
        self.link(3 * t1 + 1, 3 * t2 + 2);
        self.link(3 * t2 + 1, 3 * t + 2);
        self.refresh(
            &[t, t1, t2],
            &[
                3 * t + 1,
                3 * t + 2,
                3 * t1 + 1,
                3 * t1 + 2,
                3 * t2 + 1,
                3 * t2 + 2,
            ],
        );
        if !self.tag.is_empty() {
            let tag = self.tag[t as usize];
            self.tag.extend_from_slice(&[tag, tag]);
        }
        [t, t1, t2]
    }

    /// Splits the edge of half-edge `e` (from `a` to `b`) at the new vertex `p`, which lies on it.
    /// The two triangles `(a, b, c)` and `(b, a, d)` become four, each with half-edge slot 0
    /// opposite `p`: `(c, a, p)`, `(b, c, p)`, `(a, d, p)`, `(d, b, p)`. Returned in that order.
    pub fn split_edge(&mut self, e: u32, p: u32) -> [u32; 4] {
        let f = self.twin(e);
        let split_segment = self.segment_of(e);
        let (t1, t2) = (triangle_of(e), triangle_of(f));
        let (a, b, c, d) = (self.origin(e), self.dest(e), self.apex(e), self.apex(f));
        let (tw_bc, tw_ca) = (self.twin(next(e)), self.twin(prev(e)));
        let (tw_ad, tw_db) = (self.twin(next(f)), self.twin(prev(f)));
        self.set_triangle(t1, c, a, p);
        self.set_triangle(t2, b, c, p);
        let t3 = self.add_triangle(a, d, p);
        let t4 = self.add_triangle(d, b, p);
        self.link(3 * t1, tw_ca);
        self.link(3 * t2, tw_bc);
        self.link(3 * t3, tw_ad);
        self.link(3 * t4, tw_db);
        self.link(3 * t1 + 1, 3 * t3 + 2); // a-p
        self.link(3 * t1 + 2, 3 * t2 + 1); // p-c
        self.link(3 * t2 + 2, 3 * t4 + 1); // p-b
        self.link(3 * t3 + 1, 3 * t4 + 2); // d-p
        let (ap, pa, pb, bp) = (3 * t1 + 1, 3 * t3 + 2, 3 * t2 + 2, 3 * t4 + 1);
        let inner = [
            ap,
            pa,
            pb,
            bp,
            3 * t1 + 2,
            3 * t2 + 1,
            3 * t3 + 1,
            3 * t4 + 2,
        ];
        self.refresh(&[t1, t2, t3, t4], &inner);
        if !self.tag.is_empty() {
            // t1 and t2 now lie on e's side, t3 and t4 on its twin's.
            let (e_side, f_side) = (self.tag[t1 as usize], self.tag[t2 as usize]);
            self.tag[t2 as usize] = e_side;
            self.tag.extend_from_slice(&[f_side, f_side]);
        }
        if split_segment != NONE {
            for h in [ap, pa, pb, bp] {
                self.segment[h as usize] = split_segment;
            }
        }
        [t1, t2, t3, t4]
    }

    /// Flips the edge of half-edge `e`, whose triangle is `(a, b, p)` with `e` from `a` to `b`,
    /// against its twin's triangle `(b, a, q)`. Afterwards the two triangles are `(a, q, p)` and
    /// `(q, b, p)`, each with half-edge slot 0 opposite `p` (the edges `a-q` and `q-b`).
    /// Returns the two triangles, first the one that held `e`.
    pub fn flip(&mut self, e: u32) -> [u32; 2] {
        let f = self.twin(e);
        let (t1, t2) = (triangle_of(e), triangle_of(f));
        let (a, b, p, q) = (self.origin(e), self.dest(e), self.apex(e), self.apex(f));
        let (tw_bp, tw_pa) = (self.twin(next(e)), self.twin(prev(e)));
        let (tw_aq, tw_qb) = (self.twin(next(f)), self.twin(prev(f)));
        self.set_triangle(t1, a, q, p);
        self.set_triangle(t2, q, b, p);
        self.link(3 * t1, tw_aq);
        self.link(3 * t1 + 2, tw_pa);
        self.link(3 * t2, tw_qb);
        self.link(3 * t2 + 1, tw_bp);
        self.link(3 * t1 + 1, 3 * t2 + 2);
        self.refresh(&[t1, t2], &[3 * t1 + 1, 3 * t2 + 2]);
        if !self.tag.is_empty() {
            let (tag1, tag2) = (self.tag[t1 as usize], self.tag[t2 as usize]);
            if tag1 != tag2 {
                // Tags mark parts of the plane (with `r`, each input triangle's area bound and
                // attributes): a new triangle takes the tag of the old one its centroid is in.
                let (pa, pb) = (self.point(a), self.point(b));
                let side = |x: u32, y: u32, z: u32| {
                    let (px, py, pz) = (self.point(x), self.point(y), self.point(z));
                    let g = [(px[0] + py[0] + pz[0]) / 3.0, (px[1] + py[1] + pz[1]) / 3.0];
                    let left =
                        (pb[0] - pa[0]) * (g[1] - pa[1]) - (pb[1] - pa[1]) * (g[0] - pa[0]) > 0.0;
                    if left {
                        tag1
                    } else {
                        tag2
                    }
                };
                let (new1, new2) = (side(a, q, p), side(q, b, p));
                self.tag[t1 as usize] = new1;
                self.tag[t2 as usize] = new2;
            }
        }
        [t1, t2]
    }

    /// Iterates the real (non-ghost) triangles.
    pub fn real_triangles(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.triangle_count()).filter(move |&t| !self.is_ghost(t))
    }

    /// Checks the topological invariants (twins are mutual and join the same two vertices in
    /// opposite directions). Used by tests and the `C` switch.
    pub fn check_topology(&self) -> Result<(), String> {
        for e in 0..self.corners.len() as u32 {
            let f = self.twin(e);
            if f == NONE || f as usize >= self.twins.len() {
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
