//! The topological operations on a mesh: adding triangles, splitting a triangle or an edge at a
//! new vertex, flipping an edge, covering a boundary with ghosts, keeping part of a mesh. Each
//! keeps the twins mutual and the optional tracking (segments, vertex edges, tags) up to date.
//! They work on the raw `u32` arrays; the public wrappers at the end take typed ids.

use super::raw::{next, prev, triangle_of};
use super::{EdgeId, Mesh, TriangleId, VertexId, GHOST, NONE, OUTSIDE};
use crate::geometry::Point;

const G: u32 = GHOST.raw();

impl Mesh {
    /// The half-edges after and before `e` in its triangle (`e.next()`, `e.prev()`) from one
    /// division by 3 (the two methods each take `e` modulo 3), for walks that need both.
    #[inline(always)]
    pub fn next_and_prev(e: EdgeId) -> (EdgeId, EdgeId) {
        let base = 3 * (e.raw() / 3);
        // Slot 0 → (1, 2), 1 → (2, 0), 2 → (0, 1): two 2-bit fields per slot.
        let pair = 0b0100_0010_1001u32 >> (4 * (e.raw() - base));
        (
            EdgeId::new(base + (pair & 3)),
            EdgeId::new(base + ((pair >> 2) & 3)),
        )
    }

    #[inline(always)]
    fn c(&self, e: u32) -> u32 {
        self.corners[e as usize]
    }

    #[inline(always)]
    fn dst(&self, e: u32) -> u32 {
        self.corners[next(e) as usize]
    }

    #[inline(always)]
    fn apx(&self, e: u32) -> u32 {
        self.corners[prev(e) as usize]
    }

    #[inline(always)]
    fn tw(&self, e: u32) -> u32 {
        self.twins[e as usize]
    }

    #[inline(always)]
    fn pt(&self, v: u32) -> Point {
        self.points[v as usize]
    }

    #[inline(always)]
    fn tri(&self, t: u32) -> [u32; 3] {
        let i = 3 * t as usize;
        [self.corners[i], self.corners[i + 1], self.corners[i + 2]]
    }

    #[inline(always)]
    fn ghost(&self, t: u32) -> bool {
        let [a, b, c] = self.tri(t);
        a == G || b == G || c == G
    }

    /// After triangles were rewritten: every corner's outgoing half-edge and every new
    /// half-edge's segment id (copied from its external twin, or none for an inner edge).
    #[inline(always)]
    pub(super) fn refresh(&mut self, triangles: &[u32], inner: &[u32]) {
        if !self.vertex_edge.is_empty() {
            for &t in triangles {
                for e in 3 * t..3 * t + 3 {
                    let v = self.corners[e as usize];
                    if v != G {
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

    #[inline(always)]
    fn link_raw(&mut self, a: u32, b: u32) {
        self.twins[a as usize] = b;
        self.twins[b as usize] = a;
    }

    /// Appends a triangle with the given corners and unset twins; returns its index.
    #[inline(always)]
    fn add_triangle_raw(&mut self, a: u32, b: u32, c: u32) -> u32 {
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
    /// edge entering `v` in the same part (a fan). Where one fan meets `v`, the ghosts of those
    /// two edges share `v–∞`; where several do (a pinch: a bow-tie's waist), the ghost of each
    /// fan's entering edge shares `v–∞` with the ghost of the leaving edge of the next fan
    /// counter-clockwise, so that the star of `v` is still one cycle, in angular order, and
    /// every edge at `v` is found by turning around it ([`Self::find_edge`]). A ghost takes the
    /// segment id of its boundary edge and the tag [`OUTSIDE`].
    pub fn cover_boundary_with_ghosts(&mut self) {
        let boundary: Vec<u32> = (0..self.corners.len() as u32)
            .filter(|&e| self.twins[e as usize] == NONE)
            .collect();
        for &h in &boundary {
            let g = self.add_triangle_raw(self.dst(h), self.c(h), G);
            self.link_raw(h, 3 * g);
        }
        // Per boundary half-edge h = v → w: v, the direction of h, the ghost's v → ∞ and the
        // ∞ → v of the ghost of the edge entering v in h's fan.
        let mut fans: Vec<(u32, f64, u32, u32)> = Vec::with_capacity(boundary.len());
        for &h in &boundary {
            let entering = self
                .star_from(EdgeId::new(h))
                .skip(1)
                .find(|&f| self.is_ghost(f.triangle()))
                .expect("turning inside the mesh reaches a boundary edge")
                .raw();
            // Ghost of h: (w, v, ∞) with slot 1 = v → ∞; ghost of the entering edge x → v:
            // (v, x, ∞) with slot 2 = ∞ → v.
            let (g, ghost_prev) = (triangle_of(self.tw(h)), triangle_of(entering));
            let (v, w) = (self.pt(self.c(h)), self.pt(self.dst(h)));
            let direction = (w[1] - v[1]).atan2(w[0] - v[0]);
            fans.push((self.c(h), direction, 3 * g + 1, 3 * ghost_prev + 2));
        }
        // By vertex, then counter-clockwise (fans at one vertex are disjoint sectors: their
        // leaving edges differ in direction).
        fans.sort_unstable_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        for at_vertex in fans.chunk_by(|a, b| a.0 == b.0) {
            for (k, fan) in at_vertex.iter().enumerate() {
                let next = &at_vertex[(k + 1) % at_vertex.len()];
                self.link_raw(next.2, fan.3);
            }
        }
        if !self.segment.is_empty() {
            self.segment.resize(self.corners.len(), NONE);
            for &h in &boundary {
                let ghost_edge = self.tw(h) as usize;
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
    pub fn retain_triangles(&mut self, keep: impl Fn(TriangleId) -> bool) {
        let old = std::mem::take(self);
        let mut new_index = vec![NONE; old.triangle_count() as usize];
        let mut kept = 0u32;
        for t in 0..old.triangle_count() {
            if !old.ghost(t) && keep(TriangleId::new(t)) {
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
    fn init_triangle_raw(&mut self, a: u32, b: u32, c: u32) -> u32 {
        let t = self.add_triangle_raw(a, b, c);
        let gab = self.add_triangle_raw(b, a, G);
        let gbc = self.add_triangle_raw(c, b, G);
        let gca = self.add_triangle_raw(a, c, G);
        self.link_raw(3 * t, 3 * gab);
        self.link_raw(3 * t + 1, 3 * gbc);
        self.link_raw(3 * t + 2, 3 * gca);
        self.link_raw(3 * gab + 1, 3 * gca + 2);
        self.link_raw(3 * gab + 2, 3 * gbc + 1);
        self.link_raw(3 * gbc + 2, 3 * gca + 1);
        t
    }

    /// Splits triangle `t = (a, b, c)` at the new vertex `p` into `(a, b, p)`, `(b, c, p)` and
    /// `(c, a, p)`. In each of the three, half-edge slot 0 is the edge opposite `p`. Returns the
    /// three triangles. Works for ghosts too (a point beyond a hull edge splits its ghost).
    fn split_triangle_raw(&mut self, t: u32, p: u32) -> [u32; 3] {
        let [a, b, c] = self.tri(t);
        let (tw_ab, tw_bc, tw_ca) = (self.tw(3 * t), self.tw(3 * t + 1), self.tw(3 * t + 2));
        self.set_triangle(t, a, b, p);
        let t1 = self.add_triangle_raw(b, c, p);
        let t2 = self.add_triangle_raw(c, a, p);
        self.link_raw(3 * t, tw_ab);
        self.link_raw(3 * t1, tw_bc);
        self.link_raw(3 * t2, tw_ca);
        self.link_raw(3 * t + 1, 3 * t1 + 2);
        self.link_raw(3 * t1 + 1, 3 * t2 + 2);
        self.link_raw(3 * t2 + 1, 3 * t + 2);
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
    fn split_edge_raw(&mut self, e: u32, p: u32) -> [u32; 4] {
        let f = self.tw(e);
        let split_segment = self.segment_of(EdgeId::new(e));
        let (t1, t2) = (triangle_of(e), triangle_of(f));
        let (a, b, c, d) = (self.c(e), self.dst(e), self.apx(e), self.apx(f));
        let (tw_bc, tw_ca) = (self.tw(next(e)), self.tw(prev(e)));
        let (tw_ad, tw_db) = (self.tw(next(f)), self.tw(prev(f)));
        self.set_triangle(t1, c, a, p);
        self.set_triangle(t2, b, c, p);
        let t3 = self.add_triangle_raw(a, d, p);
        let t4 = self.add_triangle_raw(d, b, p);
        self.link_raw(3 * t1, tw_ca);
        self.link_raw(3 * t2, tw_bc);
        self.link_raw(3 * t3, tw_ad);
        self.link_raw(3 * t4, tw_db);
        self.link_raw(3 * t1 + 1, 3 * t3 + 2); // a-p
        self.link_raw(3 * t1 + 2, 3 * t2 + 1); // p-c
        self.link_raw(3 * t2 + 2, 3 * t4 + 1); // p-b
        self.link_raw(3 * t3 + 1, 3 * t4 + 2); // d-p
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
    fn flip_raw(&mut self, e: u32) -> [u32; 2] {
        let f = self.tw(e);
        let (t1, t2) = (triangle_of(e), triangle_of(f));
        let (a, b, p, q) = (self.c(e), self.dst(e), self.apx(e), self.apx(f));
        let (tw_bp, tw_pa) = (self.tw(next(e)), self.tw(prev(e)));
        let (tw_aq, tw_qb) = (self.tw(next(f)), self.tw(prev(f)));
        self.set_triangle(t1, a, q, p);
        self.set_triangle(t2, q, b, p);
        self.link_raw(3 * t1, tw_aq);
        self.link_raw(3 * t1 + 2, tw_pa);
        self.link_raw(3 * t2, tw_qb);
        self.link_raw(3 * t2 + 1, tw_bp);
        self.link_raw(3 * t1 + 1, 3 * t2 + 2);
        // What `refresh(&[t1, t2], &[3 * t1 + 1, 3 * t2 + 2])` does, written out: each
        // corner's outgoing half-edge (the last one `refresh` would write: `q` and `p` in
        // `t2`), the outer half-edges' segment ids from their twins, none on the diagonal.
        if !self.vertex_edge.is_empty() {
            for (v, h) in [(a, 3 * t1), (q, 3 * t2), (b, 3 * t2 + 1), (p, 3 * t2 + 2)] {
                if v != G {
                    self.vertex_edge[v as usize] = h;
                }
            }
        }
        if !self.segment.is_empty() {
            self.segment.resize(self.corners.len(), NONE);
            for (h, outer) in [
                (3 * t1, tw_aq),
                (3 * t1 + 2, tw_pa),
                (3 * t2, tw_qb),
                (3 * t2 + 1, tw_bp),
            ] {
                self.segment[h as usize] = self.segment[outer as usize];
            }
            self.segment[3 * t1 as usize + 1] = NONE;
            self.segment[3 * t2 as usize + 2] = NONE;
        }
        if !self.tag.is_empty() {
            let (tag1, tag2) = (self.tag[t1 as usize], self.tag[t2 as usize]);
            if tag1 != tag2 {
                // Tags mark parts of the plane (with `r`, each input triangle's area bound and
                // attributes): a new triangle takes the tag of the old one its centroid is in.
                let (pa, pb) = (self.pt(a), self.pt(b));
                let side = |x: u32, y: u32, z: u32| {
                    let (px, py, pz) = (self.pt(x), self.pt(y), self.pt(z));
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

    // ---- The operations, with typed ids ----

    /// Joins `a` and `b` as twins.
    #[inline(always)]
    pub fn link(&mut self, a: EdgeId, b: EdgeId) {
        self.link_raw(a.raw(), b.raw());
    }

    /// Appends a triangle with the given corners and unset twins; returns its index.
    #[inline(always)]
    pub fn add_triangle(&mut self, a: VertexId, b: VertexId, c: VertexId) -> TriangleId {
        TriangleId::new(self.add_triangle_raw(a.raw(), b.raw(), c.raw()))
    }

    /// Rewrites the corners of triangle `t` (twins and tracking untouched: the caller relinks).
    #[inline(always)]
    pub fn set_corners(&mut self, t: TriangleId, [a, b, c]: [VertexId; 3]) {
        self.set_triangle(t.raw(), a.raw(), b.raw(), c.raw());
    }

    /// Rewrites triangle `t` with new corners, for a retriangulation in place (segment
    /// recovery): its half-edges lose their segment ids (where tracked), and each corner's
    /// tracked outgoing half-edge becomes its half-edge here. The caller links the twins.
    pub fn rewrite_triangle(&mut self, t: TriangleId, corners: [VertexId; 3]) {
        let base = 3 * t.index();
        self.corners[base..base + 3].copy_from_slice(&corners.map(VertexId::raw));
        if !self.segment.is_empty() {
            self.segment[base..base + 3].fill(NONE);
        }
        if !self.vertex_edge.is_empty() {
            for (k, v) in corners.into_iter().enumerate() {
                self.vertex_edge[v.index()] = (base + k) as u32;
            }
        }
    }

    /// [`Self::rewrite_triangle`] for a whole retriangulated region, in order: triangle
    /// `slots[j]` takes the corners `triangles[j].0`, and its slot-0 half-edge is joined to
    /// `triangles[j].1` unless that is [`EdgeId::NONE`]. (One pass, the tracking tested once,
    /// no bounds checks: segment recovery rewrites every crossed triangle through here.)
    ///
    /// # Safety
    /// Every slot is a triangle of the mesh, every corner a vertex of the mesh (not
    /// [`GHOST`]), and every join other than [`EdgeId::NONE`] a half-edge of the mesh.
    pub unsafe fn rewrite_triangles_unchecked(
        &mut self,
        slots: &[TriangleId],
        triangles: &[([VertexId; 3], EdgeId)],
    ) {
        let tracks_segments = !self.segment.is_empty();
        let tracks_vertex_edges = !self.vertex_edge.is_empty();
        // The per-array lengths the contract's indices are measured against (checked once).
        assert!(self.twins.len() == self.corners.len());
        assert!(!tracks_segments || self.segment.len() == self.corners.len());
        assert!(!tracks_vertex_edges || self.vertex_edge.len() == self.points.len());
        for (&t, &(corners, join)) in slots.iter().zip(triangles) {
            let base = 3 * t.index();
            let corners = corners.map(VertexId::raw);
            debug_assert!(base + 3 <= self.corners.len());
            debug_assert!(corners.iter().all(|&v| (v as usize) < self.points.len()));
            debug_assert!(join == EdgeId::NONE || join.index() < self.twins.len());
            // SAFETY: `t` is a triangle of the mesh (the contract), so its three slots are in
            // `corners`, and in `segment` (asserted the same length) where tracked.
            unsafe {
                self.corners
                    .get_unchecked_mut(base..base + 3)
                    .copy_from_slice(&corners);
                if tracks_segments {
                    self.segment.get_unchecked_mut(base..base + 3).fill(NONE);
                }
            }
            if tracks_vertex_edges {
                for (k, v) in corners.into_iter().enumerate() {
                    // SAFETY: `v` is a vertex of the mesh (the contract), `< points.len()`,
                    // asserted the length of `vertex_edge`.
                    unsafe { *self.vertex_edge.get_unchecked_mut(v as usize) = (base + k) as u32 };
                }
            }
            if join != EdgeId::NONE {
                // SAFETY: `base` is a half-edge of the mesh (slot 0 of `t`), `join` one by the
                // contract.
                unsafe { self.link_unchecked(EdgeId::new(base as u32), join) };
            }
        }
    }

    /// Joins each `inner[i]` to `outer[i]` (unless that is [`EdgeId::NONE`]) as
    /// [`Self::link_to_outer`] does, `inner[i]` taking segment id `segments[i]` (where tracked):
    /// the caller read it before the rewrite from the old half-edge across from `outer[i]`,
    /// which holds the same id and lies in a triangle it had just read, where `outer[i]`'s
    /// entry would be a cache miss each. Without bounds checks.
    ///
    /// # Safety
    /// Every `inner[i]` whose `outer[i]` is not [`EdgeId::NONE`] is a half-edge of the mesh,
    /// and so is every `outer[i]` other than [`EdgeId::NONE`]; `segments` is as long as `outer`.
    pub unsafe fn link_all_to_outer_unchecked(
        &mut self,
        inner: &[EdgeId],
        outer: &[EdgeId],
        segments: &[u32],
    ) {
        let tracks_segments = !self.segment.is_empty();
        // The length the contract's half-edges are measured against (checked once).
        assert!(!tracks_segments || self.segment.len() == self.corners.len());
        for ((&inner, &outer), &segment) in inner.iter().zip(outer).zip(segments) {
            if outer != EdgeId::NONE {
                debug_assert!(inner.index().max(outer.index()) < self.corners.len());
                debug_assert_eq!(segment, self.segment_of(outer));
                // SAFETY: both are half-edges of the mesh (the contract): below the length of
                // `twins`, and of `segment` where tracked (asserted above).
                unsafe {
                    self.link_unchecked(inner, outer);
                    if tracks_segments {
                        *self.segment.get_unchecked_mut(inner.index()) = segment;
                    }
                }
            }
        }
    }

    /// Joins `inner`, a half-edge of a rewritten triangle, to `outer`, an untouched one across
    /// the boundary of the rewritten region: `inner` takes `outer`'s segment id (where tracked).
    #[inline]
    pub fn link_to_outer(&mut self, inner: EdgeId, outer: EdgeId) {
        self.link_raw(inner.raw(), outer.raw());
        if !self.segment.is_empty() {
            self.segment[inner.index()] = self.segment[outer.index()];
        }
    }

    /// Starts a triangulation with the counter-clockwise triangle `(a, b, c)` and the three
    /// ghosts around it. Returns the real triangle.
    pub fn init_triangle(&mut self, a: VertexId, b: VertexId, c: VertexId) -> TriangleId {
        TriangleId::new(self.init_triangle_raw(a.raw(), b.raw(), c.raw()))
    }

    /// Splits triangle `t = (a, b, c)` at the new vertex `p` into `(a, b, p)`, `(b, c, p)` and
    /// `(c, a, p)`. In each of the three, half-edge slot 0 is the edge opposite `p`. Returns the
    /// three triangles. Works for ghosts too (a point beyond a hull edge splits its ghost).
    pub fn split_triangle(&mut self, t: TriangleId, p: VertexId) -> [TriangleId; 3] {
        self.split_triangle_raw(t.raw(), p.raw())
            .map(TriangleId::new)
    }

    /// Splits the edge of half-edge `e` (from `a` to `b`) at the new vertex `p`, which lies on it.
    /// The two triangles `(a, b, c)` and `(b, a, d)` become four, each with half-edge slot 0
    /// opposite `p`: `(c, a, p)`, `(b, c, p)`, `(a, d, p)`, `(d, b, p)`. Returned in that order.
    pub fn split_edge(&mut self, e: EdgeId, p: VertexId) -> [TriangleId; 4] {
        self.split_edge_raw(e.raw(), p.raw()).map(TriangleId::new)
    }

    /// Flips the edge of half-edge `e`, whose triangle is `(a, b, p)` with `e` from `a` to `b`,
    /// against its twin's triangle `(b, a, q)`. Afterwards the two triangles are `(a, q, p)` and
    /// `(q, b, p)`, each with half-edge slot 0 opposite `p` (the edges `a-q` and `q-b`).
    /// Returns the two triangles, first the one that held `e`.
    pub fn flip(&mut self, e: EdgeId) -> [TriangleId; 2] {
        self.flip_raw(e.raw()).map(TriangleId::new)
    }

    /// Appends the triangles of `other` (over the same points, or points this mesh will be
    /// given) after this mesh's, their half-edges renumbered; neither mesh tracks anything. The
    /// two parts are not joined: the caller links them (the merge of two halves).
    pub fn append(&mut self, mut other: Mesh) {
        debug_assert!(
            self.segment.is_empty() && self.vertex_edge.is_empty() && self.tag.is_empty()
        );
        let offset = self.edge_count();
        drop(std::mem::take(&mut other.points));
        let corners = std::mem::take(&mut other.corners);
        self.corners.extend_from_slice(&corners);
        drop(corners);
        let twins = std::mem::take(&mut other.twins);
        self.twins.extend(twins.iter().map(|&f| f + offset));
    }
}
