//! Delaunay triangulation by incremental insertion with Lawson flips.
//!
//! Each point is located by a walk from the previously inserted one, inserted by splitting the
//! triangle (or edge) that contains it, and the Delaunay property is restored by flipping edges
//! that fail the in-circle test (Lawson 1977; Guibas, Knuth and Sharir 1992 for the randomized
//! analysis). Points outside the hull land in ghost triangles (see [`crate::mesh`]), whose
//! "circumcircle" is the half-plane beyond their hull edge, so hull growth is ordinary flipping.
//!
//! The default order is multiscale: random rounds growing eightfold, each along a Hilbert curve
//! ([`order::multiscale_order`]); `i` uses rounds that double, a biased randomized insertion
//! order ([`order::brio_order`]). Both give the same triangulation, as does the two-core merge
//! ([`merge`]), for any points: every in-circle decision is [`Predicates::incircle_positive`],
//! exact, with ties (cocircular points) broken by a symbolic perturbation that depends only on
//! the points' coordinates, so the Delaunay triangulation is unique.

mod bulk;
mod hilbert;
pub mod merge;
pub mod order;

use bulk::triangulate_in_order;

use crate::geometry::{Point, Predicates};
use crate::mesh::{
    Deletion, EdgeId, Ghosts, Lawson, Mesh, Quad, TriangleId, VertexId, GHOST, NONE,
};

/// Where a point lies in the current triangulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// Strictly inside real triangle `t`.
    InTriangle(TriangleId),
    /// On the interior of the edge of half-edge `e`.
    OnEdge(EdgeId),
    /// At the position of vertex `v`.
    OnVertex(VertexId),
    /// Outside the hull, strictly beyond the hull edge of ghost triangle `t`.
    Outside(TriangleId),
}

/// The location of `p` in triangle `t`, where a walk found it on no edge's far side and on the
/// edges `zeros` (half-edges of `t`, at most two; `ends` gives a half-edge's origin and
/// destination): inside, on the one edge, or at the vertex the two share.
#[inline(always)]
fn location_in_triangle(
    t: TriangleId,
    zeros: &[EdgeId],
    p: Point,
    ends: impl Fn(EdgeId) -> (VertexId, VertexId),
    point: impl Fn(VertexId) -> Point,
) -> Location {
    match *zeros {
        [] => Location::InTriangle(t),
        [e] => Location::OnEdge(e),
        [e1, e2, ..] => {
            let ((o1, _), (o2, d2)) = (ends(e1), ends(e2));
            let v = if o1 == d2 { o1 } else { o2 };
            if point(v) == p {
                Location::OnVertex(v)
            } else {
                // Inexact arithmetic only: treat as on the first edge.
                Location::OnEdge(e1)
            }
        }
    }
}

/// The result of triangulating a point set.
#[derive(Clone, Debug, Default)]
pub struct Triangulation {
    pub mesh: Mesh,
    /// The input vertices left out as duplicates, by increasing vertex: (vertex, the vertex at
    /// the same position that is in the triangulation). A list rather than one entry per
    /// vertex: duplicates are rare, and an array as long as the input costs a pass and its
    /// fresh pages.
    pub duplicates: Vec<(u32, u32)>,
}

impl Triangulation {
    /// True when no triangle could be formed (fewer than three distinct, non-collinear points).
    pub fn is_degenerate(&self) -> bool {
        self.mesh.triangle_count() == 0
    }

    /// Per input vertex: [`NONE`] if it is a vertex of the triangulation, else the vertex at the
    /// same position that was inserted instead.
    pub fn duplicate_of(&self) -> Vec<u32> {
        let mut duplicate_of = vec![NONE; self.mesh.vertex_count() as usize];
        for &(v, u) in &self.duplicates {
            duplicate_of[v as usize] = u;
        }
        duplicate_of
    }

    /// Makes the first copy (smallest index) of every duplicated point the one in the mesh, as
    /// Triangle's documentation of `j` says, whichever copy the insertion order met first: the
    /// copies have the same coordinates, so the survivor's id is swapped for the first copy's.
    pub fn keep_first_copies(&mut self) {
        let mut first_copy: std::collections::HashMap<u32, u32> = std::collections::HashMap::new();
        for &(v, u) in &self.duplicates {
            if v < u && first_copy.get(&u).is_none_or(|&w| v < w) {
                first_copy.insert(u, v);
            }
        }
        if first_copy.is_empty() {
            return;
        }
        self.mesh
            .rename_vertices(|c| first_copy.get(&c.raw()).map_or(c, |&w| VertexId::new(w)));
        for (&u, &w) in &first_copy {
            self.mesh
                .swap_vertex_edges(VertexId::new(u), VertexId::new(w));
        }
        // The first copy `w` of survivor `u` takes its place: `u` becomes a duplicate of `w`,
        // and so does every other copy.
        for (v, u) in self.duplicates.iter_mut() {
            if let Some(&w) = first_copy.get(u) {
                if *v == w {
                    *v = *u;
                }
                *u = w;
            }
        }
        self.duplicates.sort_unstable();
    }
}

/// The insertion engine: a mesh plus the state of the walk and of the flip stack.
#[derive(Clone)]
pub struct Inserter<P: Predicates> {
    mesh: Mesh,
    /// A triangle incident to the last inserted vertex: where the next walk starts.
    last: TriangleId,
    rng: u64,
    stack: Vec<EdgeId>,
    /// The buffers of vertex deletion.
    deletion: Deletion,
    _predicates: std::marker::PhantomData<P>,
}

impl<P: Predicates> Inserter<P> {
    pub fn new(mesh: Mesh) -> Self {
        Inserter {
            mesh,
            last: TriangleId::new(0),
            rng: 0x2545_F491_4F6C_DD1D,
            stack: Vec::with_capacity(64),
            deletion: Deletion::default(),
            _predicates: Default::default(),
        }
    }

    /// The mesh.
    #[inline(always)]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The mesh, for operations that keep it a valid triangulation (tracking, segments, tags).
    #[inline(always)]
    pub fn mesh_mut(&mut self) -> &mut Mesh {
        &mut self.mesh
    }

    /// The mesh, consuming the inserter.
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }

    #[inline(always)]
    fn random_bit(&mut self) -> u32 {
        // xorshift: only used to vary which edge the walk tests first (a stochastic walk cannot
        // cycle, Devillers, Pion and Teillaud 2002).
        self.rng ^= self.rng << 13;
        self.rng ^= self.rng >> 7;
        self.rng ^= self.rng << 17;
        (self.rng >> 32) as u32
    }

    /// A real triangle near `t` (itself, or across the hull edge of a ghost).
    fn real_near(&self, t: TriangleId) -> TriangleId {
        if !self.mesh.is_ghost(t) {
            return t;
        }
        for e in t.edges() {
            if self.mesh.origin(e) != GHOST && self.mesh.dest(e) != GHOST {
                return self.mesh.twin(e).triangle();
            }
        }
        t
    }

    /// Keeps only the triangles for which `keep` holds (see [`Mesh::retain_triangles`]).
    pub fn retain_triangles(&mut self, keep: impl Fn(TriangleId) -> bool) {
        self.mesh.retain_triangles(keep);
        self.last = TriangleId::new(0);
    }

    /// Deletes vertex `v` (see [`Mesh::delete_vertex`]); the next walk starts in the triangles
    /// made (the one it would have started from may have moved to another slot).
    pub fn delete_vertex(&mut self, v: VertexId) -> Option<Vec<TriangleId>> {
        let mut made = Vec::new();
        self.delete_vertex_into(v, &mut made).then_some(made)
    }

    /// [`Self::delete_vertex`] into `made` (cleared first): whether `v` was deleted. Allocates
    /// nothing once the buffers have grown.
    pub fn delete_vertex_into(&mut self, v: VertexId, made: &mut Vec<TriangleId>) -> bool {
        if !self
            .mesh
            .delete_vertex_with::<P>(v, &mut self.deletion, made)
        {
            return false;
        }
        self.last = made[0];
        true
    }

    /// Deletes vertex `v` between two subsegments of one segment (see
    /// [`Mesh::delete_segment_vertex`]); the next walk starts in the triangles made.
    pub fn delete_segment_vertex(&mut self, v: VertexId) -> Option<Vec<TriangleId>> {
        let made = self.mesh.delete_segment_vertex::<P>(v)?;
        self.last = made[0];
        Some(made)
    }

    /// Removes the vertices deleted by [`Self::delete_vertex`] for which `keep` is false (see
    /// [`Mesh::remove_vertices`]); returns each old vertex's new id.
    pub fn remove_vertices(&mut self, keep: impl Fn(VertexId) -> bool) -> Vec<u32> {
        self.mesh.remove_vertices(keep)
    }

    /// A triangle near the last insertion: a good start for a walk.
    pub fn last_triangle(&self) -> TriangleId {
        self.last
    }

    /// Locates `p` by a visibility walk from `start` (any triangle). The walk is stochastic, so
    /// it terminates in any triangulation, constrained ones included.
    pub fn locate(&mut self, p: Point, start: TriangleId) -> Location {
        let mesh_triangles = self.mesh.triangle_count();
        let mut t = self.real_near(start);
        let mut entry = EdgeId::NONE; // the half-edge of `t` we came through (p is strictly left of it)
        let mut steps: u32 = 0;
        'walk: loop {
            steps += 1;
            if steps > 4 * mesh_triangles + 64 {
                // Only reachable with inexact predicates on hard input: fall back to a scan.
                return self.locate_by_scan(p);
            }
            let offset = self.random_bit() % 3;
            let mut zeros = [EdgeId::NONE; 2];
            let mut zero_count = 0;
            for k in 0..3 {
                let e = t.edge((offset + k) % 3);
                if e == entry {
                    continue;
                }
                let (a, b) = (self.mesh.origin(e), self.mesh.dest(e));
                let o = P::orient2d(self.mesh.point(a), self.mesh.point(b), p);
                if o < 0.0 {
                    let f = self.mesh.twin(e);
                    let next_t = f.triangle();
                    if self.mesh.apex(f) == GHOST {
                        return Location::Outside(next_t);
                    }
                    t = next_t;
                    entry = f;
                    continue 'walk;
                }
                if o == 0.0 && zero_count < 2 {
                    zeros[zero_count] = e;
                    zero_count += 1;
                }
            }
            let m = &self.mesh;
            return location_in_triangle(
                t,
                &zeros[..zero_count],
                p,
                |e| (m.origin(e), m.dest(e)),
                |v| m.point(v),
            );
        }
    }

    /// As [`Self::locate`], for a mesh that need not be convex (holes or concavities carved
    /// out): a walk can stop at the boundary before reaching `p` (it only knows that `p` is
    /// beyond that boundary edge's line), so an `Outside` walk is followed by a scan of every
    /// triangle. `Outside` only when `p` is in no triangle.
    pub fn locate_thoroughly(&mut self, p: Point, start: TriangleId) -> Location {
        match self.locate(p, start) {
            Location::Outside(_) => self.locate_by_scan(p),
            location => location,
        }
    }

    fn locate_by_scan(&self, p: Point) -> Location {
        for t in self.mesh.triangles() {
            if self.mesh.is_ghost(t) {
                continue;
            }
            let [a, b, c] = self.mesh.triangle(t).map(|v| self.mesh.point(v));
            for v in self.mesh.triangle(t) {
                if self.mesh.point(v) == p {
                    return Location::OnVertex(v);
                }
            }
            let o = [
                P::orient2d(a, b, p),
                P::orient2d(b, c, p),
                P::orient2d(c, a, p),
            ];
            if o.iter().all(|&x| x >= 0.0) {
                return match o.iter().position(|&x| x == 0.0) {
                    Some(i) => Location::OnEdge(t.edge(i as u32)),
                    None => Location::InTriangle(t),
                };
            }
        }
        for t in self.mesh.triangles() {
            if self.mesh.is_ghost(t) && self.conflicts(t, p) {
                return Location::Outside(t);
            }
        }
        Location::InTriangle(self.real_near(TriangleId::new(0)))
    }

    /// Whether `p` lies strictly inside the circumcircle of triangle `t`; for a ghost, strictly
    /// beyond its hull edge.
    #[inline(always)]
    fn conflicts(&self, t: TriangleId, p: Point) -> bool {
        let [a, b, c] = self.mesh.triangle(t);
        let m = &self.mesh;
        if a == GHOST {
            P::orient2d(m.point(b), m.point(c), p) > 0.0
        } else if b == GHOST {
            P::orient2d(m.point(c), m.point(a), p) > 0.0
        } else if c == GHOST {
            P::orient2d(m.point(a), m.point(b), p) > 0.0
        } else {
            P::incircle_positive(m.point(a), m.point(b), m.point(c), p)
        }
    }

    /// Inserts vertex `v` (already in `mesh.points`), walking from the last insertion. Returns
    /// `Err(u)` if `v` lies on the existing vertex `u` (and was not inserted).
    pub fn insert(&mut self, v: VertexId) -> Result<(), VertexId> {
        let p = self.mesh.point(v);
        let location = self.locate(p, self.last);
        self.insert_at(v, location)
    }

    /// Inserts vertex `v` at a known location and restores the Delaunay property.
    pub fn insert_at(&mut self, v: VertexId, location: Location) -> Result<(), VertexId> {
        let grows_hull = matches!(location, Location::Outside(_));
        match location {
            Location::OnVertex(u) => return Err(u),
            Location::InTriangle(t) | Location::Outside(t) => {
                let ts = self.mesh.split_triangle(t, v);
                self.stack.extend(ts.iter().map(|&t| t.edge(0)));
            }
            Location::OnEdge(e) => {
                let ts = self.mesh.split_edge(e, v);
                self.stack.extend(ts.iter().map(|&t| t.edge(0)));
            }
        }
        let mut stack = std::mem::take(&mut self.stack);
        let mut star = AroundVertex::<true> {
            ghosts: if grows_hull {
                Ghosts::GrowHull
            } else {
                Ghosts::HullEdges
            },
            last: &mut self.last,
        };
        self.mesh.legalize::<P, _>(&mut stack, &mut star);
        self.stack = stack;
        Ok(())
    }
}

/// The Lawson policy of insertion (Lawson 1977; the flips that restore the Delaunay property
/// around a new vertex): the stack holds the edges opposite the new vertex (slot 0 of its
/// triangles, [`Mesh::split_triangle`] and [`Mesh::split_edge`] leave them there) and each flip
/// stacks the two new ones; segments are never flipped (the result is then constrained
/// Delaunay, Chew 1989); the triangle of each edge kept is where the next walk starts.
/// `TRACKED` is false for the bulk build, whose mesh has no segments and no tracking.
///
/// An edge between two ghosts is flipped only when the vertex was inserted outside the hull
/// ([`Ghosts::GrowHull`]): that is how the hull grows around it. A vertex inserted inside or on
/// the boundary never lies strictly beyond a boundary edge in exact terms, except when the
/// boundary is not convex (a carved domain, a mesh given with `r`) or when the vertex was
/// rounded onto a boundary edge; flipping there would wrap a triangle around the outside.
pub(crate) struct AroundVertex<'a, const TRACKED: bool> {
    pub ghosts: Ghosts,
    pub last: &'a mut TriangleId,
}

impl<const TRACKED: bool> Lawson for AroundVertex<'_, TRACKED> {
    type Item = EdgeId;
    const TRACKED: bool = TRACKED;
    const SLOT_ZERO: bool = true;

    #[inline(always)]
    fn edge(&self, _mesh: &Mesh, e: EdgeId) -> Option<EdgeId> {
        Some(e)
    }

    #[inline(always)]
    fn is_fixed(&self, mesh: &Mesh, e: EdgeId) -> bool {
        TRACKED && mesh.is_segment(e)
    }

    #[inline(always)]
    fn ghosts(&self) -> Ghosts {
        self.ghosts
    }

    #[inline(always)]
    fn after_flip(&mut self, _quad: &Quad, [t1, t2]: [TriangleId; 2], stack: &mut Vec<EdgeId>) {
        stack.extend_from_slice(&[t1.edge(0), t2.edge(0)]);
    }

    #[inline(always)]
    fn kept(&mut self, e: EdgeId) {
        *self.last = e.triangle();
    }
}

/// Triangulates `points` inserting them in `order` (a permutation of their indices).
///
/// The mesh is built over a copy of the points stored in insertion order, so that a point and
/// its recently inserted neighbours are close in memory as well as in the plane (this halves the
/// time at 10^6 points, which is dominated by cache misses); the vertex ids are mapped back to the
/// caller's indices at the end.
pub fn triangulate<P: Predicates>(points: Vec<Point>, order: &[u32]) -> Triangulation {
    let sorted: Vec<Point> = order.iter().map(|&v| points[v as usize]).collect();
    triangulate_sorted::<P>(points, order.to_vec(), sorted)
}

/// [`triangulate`] given the points in insertion order as well (`sorted[i]` is
/// `points[order[i]]`), as [`order::multiscale_order_and_points`] gives them.
pub fn triangulate_sorted<P: Predicates>(
    points: Vec<Point>,
    order: Vec<u32>,
    sorted: Vec<Point>,
) -> Triangulation {
    triangulate_in_insertion_order::<P>(order, sorted).into_caller_numbers(points)
}

/// A triangulation whose vertices are numbered in insertion order, with the caller's number of
/// each: the outputs of a plain triangulation rename the corners as they write them, which
/// spares a pass over the mesh.
pub struct InInsertionOrder {
    /// The mesh over the points in insertion order; `duplicates` in the caller's numbers.
    pub triangulation: Triangulation,
    /// The caller's number of each vertex of the mesh: the insertion order, with each
    /// duplicated point's first copy (smallest number) standing for the copy that was inserted,
    /// as [`Triangulation::keep_first_copies`] makes it.
    pub names: Vec<u32>,
}

impl InInsertionOrder {
    /// The triangulation in the caller's numbers, over the caller's `points`.
    pub fn into_caller_numbers(self, points: Vec<Point>) -> Triangulation {
        let InInsertionOrder {
            mut triangulation,
            names,
        } = self;
        let mesh = &mut triangulation.mesh;
        mesh.rename_vertices(|v| VertexId::new(names[v.index()]));
        drop(mesh.replace_points(points));
        triangulation
    }
}

/// Points in insertion order ([`order_in_room`]), with the allocation of the twin array to be.
pub struct Ordered {
    /// The caller's number of each point, in insertion order.
    pub order: Vec<u32>,
    /// The points in insertion order.
    pub sorted: Vec<Point>,
    twins: Vec<u32>,
    corners: Vec<u32>,
    capacity: usize,
}

impl Ordered {
    /// Where the mesh's corner array to be lies: the address range of its whole capacity (for
    /// [`crate::memory::prefault_while`] by another thread).
    pub fn corners_extent(&self) -> std::ops::Range<usize> {
        let start = self.corners.as_ptr() as usize;
        start..start + 4 * self.corners.capacity()
    }
}

/// Orders `points` (`kind`) for a mesh with room for `capacity` triangle slots (at least the
/// `2n + 2` the build may use): the order's sort works in the room of the mesh's twin array,
/// which [`triangulate_ordered`] then gives the mesh. The pages the sort touches are pages the
/// twins fill later, where separate buffers would be fresh pages twice (a fresh page costs
/// microseconds).
pub fn order_in_room(points: &[Point], kind: order::OrderKind, capacity: usize) -> Ordered {
    in_room(points.len(), capacity, |room| {
        kind.order_and_points(points, Some(room))
    })
}

/// [`order_in_room`] in the default order of the points of `points` that `keep` accepts (one
/// side of a split), numbered as in `points` (see [`order::multiscale_order_and_points_where`]).
pub fn order_where_in_room(
    points: &[Point],
    keep: impl Fn(Point) -> bool,
    capacity: usize,
) -> Ordered {
    in_room(points.len(), capacity, |room| {
        order::multiscale_order_and_points_where(points, keep, Some(room))
    })
}

/// The mesh's twin and corner arrays to be, with room for `capacity` triangle slots (at least
/// `2n + 2` for `n` points), and the order that `sort` computes in the twins' spare room of two
/// words per point.
fn in_room(
    n: usize,
    capacity: usize,
    sort: impl FnOnce(&mut [std::mem::MaybeUninit<u64>]) -> (Vec<u32>, Vec<Point>),
) -> Ordered {
    let capacity = capacity.max(2 * n + 2);
    let mut twins: Vec<u32> = crate::memory::with_capacity_on_huge_pages(3 * capacity);
    let corners: Vec<u32> = crate::memory::with_capacity_on_huge_pages(3 * capacity);
    let (order, sorted) = sort(words_in_room_of(&mut twins, 2 * n));
    Ordered {
        order,
        sorted,
        twins,
        corners,
        capacity,
    }
}

/// Triangulates ordered points, inserting them in their order (see [`InInsertionOrder`]).
pub fn triangulate_ordered<P: Predicates>(ordered: Ordered) -> InInsertionOrder {
    let Ordered {
        order,
        sorted,
        twins,
        corners,
        capacity,
    } = ordered;
    triangulate_with_arrays::<P>(order, sorted, capacity, [twins, corners])
}

/// Up to `count` words (uninitialized) in the spare room of `v` (fewer, or none, when it has
/// less): the sort writes only the words it uses, so the pages beyond them stay untouched.
fn words_in_room_of(v: &mut Vec<u32>, count: usize) -> &mut [std::mem::MaybeUninit<u64>] {
    let room = v.spare_capacity_mut();
    // SAFETY: a `MaybeUninit<u64>` may hold any bits, so viewing the aligned middle of the room
    // as such is sound; `align_to_mut` keeps the alignment of `u64`.
    let (_, words, _) = unsafe { room.align_to_mut::<std::mem::MaybeUninit<u64>>() };
    let count = count.min(words.len());
    &mut words[..count]
}

/// Triangulates the points `sorted`, inserting them in their order, `order` giving the
/// caller's number of each (`sorted[i]` is the caller's point `order[i]`).
pub fn triangulate_in_insertion_order<P: Predicates>(
    order: Vec<u32>,
    sorted: Vec<Point>,
) -> InInsertionOrder {
    triangulate_with_arrays::<P>(order, sorted, 0, [Vec::new(), Vec::new()])
}

/// [`triangulate_in_insertion_order`] with room for `capacity` triangle slots, the twin array
/// in `twins`' allocation.
fn triangulate_with_arrays<P: Predicates>(
    order: Vec<u32>,
    sorted: Vec<Point>,
    capacity: usize,
    [twins, corners]: [Vec<u32>; 2],
) -> InInsertionOrder {
    debug_assert_eq!(sorted.len(), order.len());
    let (mesh, sorted_duplicates) = triangulate_in_order::<P>(sorted, capacity, twins, corners);
    let mut names = order;
    // The first copy of each inserted point (by the caller's numbers) takes its place.
    let mut first_copy: std::collections::HashMap<u32, u32> = std::collections::HashMap::new();
    for &(v, u) in &sorted_duplicates {
        let (copy, kept) = (names[v as usize], names[u as usize]);
        if copy < kept && first_copy.get(&u).is_none_or(|&w| copy < w) {
            first_copy.insert(u, copy);
        }
    }
    let mut duplicates: Vec<(u32, u32)> = sorted_duplicates
        .iter()
        .map(|&(v, u)| {
            let (copy, kept) = (names[v as usize], names[u as usize]);
            match first_copy.get(&u) {
                // The inserted copy becomes a duplicate of the first, which takes its place.
                Some(&w) if w == copy => (kept, w),
                Some(&w) => (copy, w),
                None => (copy, kept),
            }
        })
        .collect();
    duplicates.sort_unstable();
    for (&u, &w) in &first_copy {
        names[u as usize] = w;
    }
    InInsertionOrder {
        triangulation: Triangulation { mesh, duplicates },
        names,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Exact;

    fn check_delaunay(tri: &Triangulation) {
        let m = &tri.mesh;
        m.check_topology().unwrap();
        for t in m.real_triangles() {
            let [a, b, c] = m.triangle(t).map(|v| m.point(v));
            assert!(
                Exact::orient2d(a, b, c) > 0.0,
                "triangle {t} is not counter-clockwise"
            );
            for e in t.edges() {
                let q = m.apex(m.twin(e));
                if q != GHOST {
                    assert!(
                        Exact::incircle(a, b, c, m.point(q)) <= 0.0,
                        "edge {e} is not Delaunay"
                    );
                }
            }
        }
    }

    #[test]
    fn square_with_centre() {
        let pts = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
        let order: Vec<u32> = (0..5).collect();
        let t = triangulate::<Exact>(pts, &order);
        check_delaunay(&t);
        assert_eq!(t.mesh.real_triangles().count(), 4);
    }

    #[test]
    fn random_points_both_orders() {
        let mut s = 1;
        let pts: Vec<Point> = (0..2000)
            .map(|_| {
                [
                    order::splitmix64(&mut s) as f64 / 1e19,
                    order::splitmix64(&mut s) as f64 / 1e19,
                ]
            })
            .collect();
        for ord in [
            order::hilbert_order(&pts),
            order::brio_order(&pts, 3),
            order::multiscale_order(&pts),
        ] {
            let t = triangulate::<Exact>(pts.clone(), &ord);
            check_delaunay(&t);
            // Euler: for n points with h on the hull, 2n - 2 - h triangles.
            let hull = t.mesh.triangles().filter(|&t2| t.mesh.is_ghost(t2)).count();
            assert_eq!(t.mesh.real_triangles().count(), 2 * 2000 - 2 - hull);
        }
    }

    #[test]
    fn grid_collinear_and_duplicates() {
        let mut pts: Vec<Point> = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                pts.push([i as f64, j as f64]);
            }
        }
        pts.push([3.0, 3.0]);
        pts.push([0.0, 0.0]);
        // Inserted last copy first: the first copy survives all the same.
        let mut ord: Vec<u32> = order::hilbert_order(&pts);
        ord.reverse();
        let t = triangulate::<Exact>(pts, &ord);
        check_delaunay(&t);
        assert_eq!(t.mesh.real_triangles().count(), 2 * 81);
        let duplicate_of = t.duplicate_of();
        assert_eq!(duplicate_of[100], 33);
        assert_eq!(duplicate_of[101], 0);
        assert!(duplicate_of[33] == NONE && duplicate_of[0] == NONE);
        assert!(t.mesh.raw_corners().contains(&33) && !t.mesh.raw_corners().contains(&100));
        let line: Vec<Point> = (0..10).map(|i| [i as f64, 2.0 * i as f64]).collect();
        let ord = order::hilbert_order(&line);
        assert!(triangulate::<Exact>(line, &ord).is_degenerate());
    }
}
