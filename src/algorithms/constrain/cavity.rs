//! Recovering a segment whose line crosses triangles: the cavity of the crossed triangles is
//! retriangulated in place as the constrained Delaunay triangulations of the two polygons on
//! either side of the segment (Anglada 1997; Shewchuk and Brown 2015), with Sloan's flips
//! (1993) and a Lawson restore as the fallback when the cavity's plan is refused.

use super::walk::Side;
use super::*;

/// The size of [`CavityScratch::filter`], in 64-bit words.
const FILTER_WORDS: usize = 16;

/// The bit of triangle `t` in [`CavityScratch::filter`]: (word, mask), from a multiplicative
/// hash (neighbouring slots spread over the words).
#[inline(always)]
fn filter_bit(t: TriangleId) -> (usize, u64) {
    let bits = (FILTER_WORDS * 64).trailing_zeros();
    let hash = t.raw().wrapping_mul(0x9E37_79B1) >> (32 - bits);
    ((hash >> 6) as usize, 1 << (hash & 63))
}

/// The cavity's two polygons, each a chain of vertices from one end of the segment to the other
/// (the left one from `a` to `b`, the right one from `b` to `a`), written by index into buffers
/// of `k + 2` entries for `k` crossed edges: the left chain from the front, the right one from
/// the back (it is collected from `a` to `b`, in the reverse of its order). Per chain edge
/// `(v[i], v[i+1])`: `outer[i]`, the half-edge from `v[i]` to `v[i+1]` across the cavity's
/// boundary (it stays), and `inner[i]`, the new half-edge from `v[i+1]` to `v[i]` planned on it.
/// The positions are kept contiguous for the circle tests.
#[derive(Clone, Default)]
struct Chain {
    vertices: Vec<VertexId>,
    points: Vec<Point>,
    outer: Vec<EdgeId>,
    inner: Vec<EdgeId>,
    /// Per chain edge: its segment id (or NONE), read from the cavity's side before the rewrite.
    segments: Vec<u32>,
}

impl Chain {
    /// Room for `len` vertices, to be written by index (the buffers only grow: what is read
    /// was written for this cavity).
    fn make_room(&mut self, len: usize) {
        if self.vertices.len() < len {
            self.vertices.resize(len, GHOST);
            self.points.resize(len, [0.0; 2]);
            self.outer.resize(len, EdgeId::NONE);
            self.inner.resize(len, EdgeId::NONE);
            self.segments.resize(len, NONE);
        }
    }

    #[inline(always)]
    fn set(&mut self, i: usize, vertex: VertexId, point: Point) {
        self.vertices[i] = vertex;
        self.points[i] = point;
    }
}

/// Buffers of the cavity retriangulation, kept from segment to segment.
#[derive(Clone, Default)]
pub(super) struct CavityScratch {
    left: Chain,
    right: Chain,
    /// The triangle slots of the cavity (`k + 1`), reused by its new triangles.
    slots: Vec<TriangleId>,
    /// Sub-polygons of one polygon still to triangulate: (first, last, half-edge to join to the
    /// base).
    tasks: Vec<(u32, u32, EdgeId)>,
    /// The new triangles, one per slot: corners (base origin, base destination, apex) and the
    /// half-edge their base is joined to (`NONE` for the first one, whose base is the segment).
    triangles: Vec<([VertexId; 3], EdgeId)>,
    /// Per triangle slot, the serial number of the last cavity that held it (to tell in O(1)
    /// whether a half-edge lies in the current cavity); grown with the mesh.
    cavity_of: Vec<u32>,
    /// A bit per hash of the current cavity's slots: a clear bit rules a triangle out without
    /// reading `cavity_of` (a cache miss per boundary edge otherwise).
    filter: [u64; FILTER_WORDS],
    /// The serial number of the current cavity (never 0, the mark of no cavity).
    serial: u32,
    /// Triples (new half-edge, old half-edge inside the cavity, its segment id) for boundary
    /// edges with the cavity on both sides; see [`Constrainer::retriangulate_cavity`].
    inner_links: Vec<(EdgeId, EdgeId, u32)>,
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
        let (crossed, beyond) = (&self.scratch.crossed, &self.scratch.beyond);
        let CavityScratch {
            left,
            right,
            slots,
            tasks,
            triangles,
            cavity_of,
            filter,
            serial,
            inner_links,
        } = &mut self.scratch.cavity;
        let mesh = self.inserter.mesh();
        let k = crossed.len();
        debug_assert!(k > 0);
        // The crossed triangles T0 … Tk: T0 = (a, r1, l1) holds the first crossed edge r1 → l1;
        // each later one adds its apex to the left or the right chain; Tk has apex b. A chain
        // edge's outer half-edge is the twin of the cavity triangle's half-edge on it.
        left.make_room(k + 2);
        right.make_room(k + 2);
        if slots.len() < k + 1 {
            slots.resize(k + 1, TriangleId::NONE);
            triangles.resize(k + 1, ([GHOST; 3], EdgeId::NONE));
        }
        let (slots, triangles) = (&mut slots[..k + 1], &mut triangles[..k + 1]);
        let h1 = crossed[0];
        slots[0] = h1.triangle();
        let (pa, l1, r1) = (mesh.point(a), mesh.dest(h1), mesh.origin(h1));
        left.set(0, a, pa);
        left.set(1, l1, mesh.point(l1));
        left.outer[0] = mesh.twin(h1.next()); // a → l1
        left.segments[0] = mesh.segment_of(h1.next());
        // The right chain from the back: a at k + 1, r1 before it.
        right.set(k + 1, a, pa);
        right.set(k, r1, mesh.point(r1));
        right.outer[k] = mesh.twin(h1.prev()); // r1 → a
        right.segments[k] = mesh.segment_of(h1.prev());
        let (mut left_len, mut right_start) = (2, k);
        // The triangles beyond the crossed edges, as the walk recorded them (`Beyond`): each adds
        // its apex to one chain, the last one (apex b) to both.
        debug_assert_eq!(beyond.len(), k);
        for (i, (step, slot)) in beyond.iter().zip(&mut slots[1..]).enumerate() {
            *slot = step.other.triangle();
            let (z, pz) = (step.apex, step.point);
            let (to_left, to_right) = match step.side {
                Side::Left => (step.other, EdgeId::NONE),
                Side::Right => (EdgeId::NONE, step.other),
                Side::End => {
                    let (f_next, f_prev) = Mesh::next_and_prev(step.other);
                    (f_prev, f_next)
                }
            };
            if to_left != EdgeId::NONE {
                debug_assert!(left_len <= i + 2 && i + 2 < k + 2);
                // SAFETY: `left_len ≤ i + 2 < k + 2`, the chain buffers' room (each step adds
                // at most one vertex to the left chain); `to_left` is a half-edge of the mesh
                // (of the triangle beyond a crossed one).
                unsafe {
                    *left.vertices.get_unchecked_mut(left_len) = z;
                    *left.points.get_unchecked_mut(left_len) = pz;
                    // left → z
                    *left.outer.get_unchecked_mut(left_len - 1) = mesh.twin_unchecked(to_left);
                    *left.segments.get_unchecked_mut(left_len - 1) = mesh.segment_of(to_left);
                }
                left_len += 1;
            }
            if to_right != EdgeId::NONE {
                right_start -= 1;
                debug_assert!(right_start >= k - i - 1);
                // SAFETY: `k − i − 1 ≤ right_start < k`, within the chain buffers' room (each
                // step adds at most one vertex to the right chain); `to_right` is a half-edge of
                // the mesh.
                unsafe {
                    *right.vertices.get_unchecked_mut(right_start) = z;
                    *right.points.get_unchecked_mut(right_start) = pz;
                    // z → right
                    *right.outer.get_unchecked_mut(right_start) = mesh.twin_unchecked(to_right);
                    *right.segments.get_unchecked_mut(right_start) = mesh.segment_of(to_right);
                }
            }
        }
        debug_assert!(left.vertices[left_len - 1] == b && right.vertices[right_start] == b);

        // Plan the new triangles, slot `slots[j]` taking the `j`-th: the left polygon first, its
        // first triangle holding the segment a → b; then the right one, whose first triangle's
        // base b → a is that half-edge's twin.
        let mut planned = 0;
        let left_range = 0..left_len;
        let right_range = right_start..k + 2;
        for (chain, range, join) in [
            (&mut *left, left_range.clone(), EdgeId::NONE),
            (&mut *right, right_range.clone(), slots[0].edge(0)),
        ] {
            let (slots, triangles) = (&*slots, &mut *triangles);
            let planner = Planner {
                vertices: &chain.vertices[range.clone()],
                points: &chain.points[range.clone()],
                inner: &mut chain.inner[range],
                slots,
                triangles,
            };
            if !planner.plan::<P>(tasks, &mut planned, join) {
                return false;
            }
        }
        debug_assert_eq!(planned, k + 1);

        // The union of the crossed triangles need not be a simple polygon: the segment can leave
        // the star of a vertex and enter it again, so a chain may visit a vertex twice, and an
        // edge between two crossed triangles that the segment does not cross lies on a chain
        // twice, once in each direction (Shewchuk and Brown 2015 allow the same). Such an edge's
        // "outer" half-edge is in the cavity; its two new half-edges are joined to each other
        // (and its outer half-edge is set to NONE, so that the commit leaves it alone).
        // A new serial number marks this cavity's slots (all marks are cleared when it wraps).
        *serial = match serial.checked_add(1) {
            Some(serial) => serial,
            None => {
                cavity_of.fill(0);
                1
            }
        };
        cavity_of.resize((mesh.triangle_count() as usize).max(cavity_of.len()), 0);
        *filter = [0; FILTER_WORDS];
        for &t in slots.iter() {
            cavity_of[t.index()] = *serial;
            let (word, mask) = filter_bit(t);
            filter[word] |= mask;
        }
        inner_links.clear();
        for (chain, range) in [
            (&mut *left, left_range.clone()),
            (&mut *right, right_range.clone()),
        ] {
            let edges = range.start..range.end - 1;
            for (outer, &inner) in chain.outer[edges.clone()]
                .iter_mut()
                .zip(&chain.inner[edges])
            {
                let t = outer.triangle();
                let (word, mask) = filter_bit(t);
                if filter[word] & mask != 0 && cavity_of[t.index()] == *serial {
                    inner_links.push((inner, *outer, mesh.segment_of(*outer)));
                    *outer = EdgeId::NONE;
                }
            }
        }
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
        // Every cavity vertex is a corner of a new triangle: its outgoing half-edge is refreshed
        // there (the old one may have been in the cavity).
        // SAFETY: the slots are the triangles of crossed half-edges and of the half-edges beyond
        // them; every corner is a chain vertex, whose point was read (checked) from the mesh, so
        // none is the ghost; each join is NONE or a half-edge of a slot.
        unsafe { mesh.rewrite_triangles_unchecked(slots, triangles) };
        for (chain, range) in [(&*left, left_range), (&*right, right_range)] {
            let edges = range.start..range.end - 1;
            // SAFETY: the plan wrote every chain edge's inner half-edge, one of a slot; each
            // outer one is NONE or a twin read from the mesh (a half-edge of it).
            unsafe {
                mesh.link_all_to_outer_unchecked(
                    &chain.inner[edges.clone()],
                    &chain.outer[edges.clone()],
                    &chain.segments[edges],
                )
            };
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

/// Plans the constrained Delaunay triangulation of one polygon of the cavity (its vertices in
/// order, the first and last being the segment's ends): top-down from the base (the segment),
/// each sub-polygon's base joined to the half-edge of its parent triangle (Anglada 1997). A
/// polygon's base makes a triangle with the chain vertex whose circle through the base holds no
/// other chain vertex ([`Predicates::smallest_circle_left`]: the first one when several are
/// cocircular), and the two sub-chains on either side of it recurse.
struct Planner<'a> {
    vertices: &'a [VertexId],
    points: &'a [Point],
    /// Written per chain edge: the new half-edge on it (see [`Chain`]).
    inner: &'a mut [EdgeId],
    slots: &'a [TriangleId],
    triangles: &'a mut [([VertexId; 3], EdgeId)],
}

impl Planner<'_> {
    /// Plans the polygon's triangles into the slots from `*planned` on (advancing it), the
    /// first one's base joined to `join`; false if a triangle would not be counter-clockwise.
    /// The sub-polygons are taken depth first, the one before the apex first.
    // Not inlined into `retriangulate_cavity` (twice): on its own, with the smallest-circle scan
    // inlined, it runs in fewer instructions (callgrind: 0.2% on the star polygon of
    // benches/cdt.rs).
    #[inline(never)]
    fn plan<P: Predicates>(
        self,
        tasks: &mut Vec<(u32, u32, EdgeId)>,
        planned: &mut usize,
        join: EdgeId,
    ) -> bool {
        let Planner {
            vertices: v,
            points,
            inner,
            slots,
            triangles,
        } = self;
        // A stack by index in a buffer of one entry per vertex: pending sub-polygons have
        // disjoint interiors of at least one chain vertex each, so they never outnumber them
        // (and no push needs a capacity check).
        if tasks.len() < v.len() {
            tasks.resize(v.len(), (0, 0, EdgeId::NONE));
        }
        tasks[0] = (0, v.len() as u32 - 1, join);
        let mut pending = 1;
        // The unchecked accesses below rest on three invariants: every task has
        // `first + 2 ≤ last < v.len()` (and `points`, `inner` have the length of `v`), so its apex
        // lies strictly between; `pending ≤ v.len()` (above); and `*planned < slots.len()`,
        // because a polygon of `m` vertices makes `m − 2` triangles and the two chains hold at
        // most `k + 5` vertices for the `k + 1` slots (see `retriangulate_cavity`).
        debug_assert!(v.len() >= 3 && points.len() == v.len() && inner.len() == v.len());
        while pending > 0 {
            pending -= 1;
            // SAFETY: `pending < v.len() ≤ tasks.len()`.
            let (first, last, join) = unsafe { *tasks.get_unchecked(pending) };
            let (first, last) = (first as usize, last as usize);
            debug_assert!(first + 2 <= last && last < v.len());
            // SAFETY: `first < last < points.len()`.
            let (u, w) = unsafe { (*points.get_unchecked(first), *points.get_unchecked(last)) };
            // A triangle's worth of polygon has its apex already: no circle to compare.
            let (apex, left) = if last == first + 2 {
                // SAFETY: `first + 1 < last < points.len()`.
                let c = unsafe { *points.get_unchecked(first + 1) };
                (first + 1, P::orient2d(u, w, c) > 0.0)
            } else {
                // SAFETY: `first + 1 < last ≤ points.len()`.
                let candidates = unsafe { points.get_unchecked(first + 1..last) };
                let (best, left) = P::smallest_circle_left(u, w, candidates);
                (first + 1 + best, left)
            };
            if !left {
                return false;
            }
            debug_assert!(*planned < slots.len() && *planned < triangles.len());
            // SAFETY: `*planned < slots.len() = triangles.len()`; `first < apex < last <
            // v.len()`.
            let t = unsafe {
                let t = *slots.get_unchecked(*planned);
                let corners = [first, last, apex].map(|i| *v.get_unchecked(i));
                *triangles.get_unchecked_mut(*planned) = (corners, join);
                t
            };
            *planned += 1;
            // Triangle (u, w, c): w → c at 3t + 1 faces the sub-polygon (apex … last), c → u at
            // 3t + 2 the sub-polygon (first … apex); a side on the chain is a boundary edge.
            // SAFETY (the writes): `first < apex < v.len() = inner.len()`, and the two pushes
            // keep `pending ≤ v.len()` (pending sub-polygons have disjoint interiors of at
            // least one chain vertex each).
            if last == apex + 1 {
                unsafe { *inner.get_unchecked_mut(apex) = t.edge(1) };
            } else {
                unsafe {
                    *tasks.get_unchecked_mut(pending) = (apex as u32, last as u32, t.edge(1))
                };
                pending += 1;
            }
            if apex == first + 1 {
                unsafe { *inner.get_unchecked_mut(first) = t.edge(2) };
            } else {
                unsafe {
                    *tasks.get_unchecked_mut(pending) = (first as u32, apex as u32, t.edge(2))
                };
                pending += 1;
            }
        }
        true
    }
}
