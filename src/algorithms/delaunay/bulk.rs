//! The bulk Delaunay build: the points of a point set inserted one after another, in the order
//! they are given (a spatially coherent order: [`super::order`]), by a visibility walk from the
//! previous point, a split and Lawson flips — the algorithm of [`super::Inserter`], with the
//! work that a plain point set never needs taken out of the loop that runs once per point: no
//! segments, tags or vertex links to keep, ghosts tested only on the rare edges that touch them,
//! and no bounds checks on the mesh arrays (the mesh's unchecked accessors, whose safety rests on
//! its invariants). The flips check the edges around the new vertex in one counter-clockwise
//! turn ([`Mesh::legalize_around_unchecked`]) rather than from a stack; the walk carries the
//! points of the edge it crossed into the next triangle.
//!
//! The result is the mesh [`super::Inserter`] builds, cocircular points included: every flip
//! asks [`Predicates::incircle_positive`], whose tie rule depends on the points alone, so the
//! Delaunay triangulation is unique.

use super::{location_in_triangle, Location};
use crate::geometry::{Point, Predicates};
use crate::mesh::{EdgeId, Ghosts, Mesh, TriangleId, VertexId, GHOST};

/// Triangulates `points` inserting them in index order; returns the mesh and the vertices left
/// out as duplicates, by increasing vertex: (vertex, the vertex at its position in the mesh). The mesh's arrays have room for `capacity` triangle
/// slots (at least the `2n + 2` that the build may use): a caller that appends more triangles
/// later asks for them here, so that no array is reallocated (and copied) on the way. The twin
/// and corner arrays are `twins`' and `corners`' allocations (see
/// [`Mesh::with_capacity_reusing`]).
pub(super) fn triangulate_in_order<P: Predicates>(
    points: Vec<Point>,
    capacity: usize,
    twins: Vec<u32>,
    corners: Vec<u32>,
) -> (Mesh, Vec<(u32, u32)>) {
    let n = points.len() as u32;
    let mut duplicates = Vec::new();
    let capacity = capacity.max(2 * points.len() + 2);
    let mut mesh = Mesh::with_capacity_reusing(points, capacity, [twins, corners]);
    // Seed triangle: the first point, the first point distinct from it, and the first point not
    // collinear with those two.
    if n == 0 {
        return (mesh, duplicates);
    }
    let v = VertexId::new;
    let pa = mesh.point(v(0));
    let Some(b) = (1..n).map(v).find(|&u| mesh.point(u) != pa) else {
        return (mesh, duplicates);
    };
    let pb = mesh.point(b);
    let Some(c) = (b.raw() + 1..n)
        .map(v)
        .find(|&u| P::orient2d(pa, pb, mesh.point(u)) != 0.0)
    else {
        return (mesh, duplicates);
    };
    if P::orient2d(pa, pb, mesh.point(c)) > 0.0 {
        mesh.init_triangle(v(0), b, c);
    } else {
        mesh.init_triangle(v(0), c, b);
    }
    let mut builder = Builder::<P> {
        mesh,
        last: TriangleId::new(0),
        rng: 0x9E37_79B9,
        // At least 4 steps per triangle the build can make (`capacity` bounds them).
        step_limit: u32::try_from(4 * capacity as u64 + 64).unwrap_or(u32::MAX),
        _predicates: Default::default(),
    };
    for u in (1..n).map(v) {
        if u == b || u == c {
            continue;
        }
        if let Err(w) = builder.insert(u) {
            duplicates.push((u.raw(), w.raw()));
        }
    }
    (builder.mesh, duplicates)
}

/// The slot after and before each slot of a triangle.
const NEXT_SLOT: [u32; 3] = [1, 2, 0];
const PREV_SLOT: [u32; 3] = [2, 0, 1];

struct Builder<P: Predicates> {
    mesh: Mesh,
    /// A triangle incident to the last inserted vertex: where the next walk starts.
    last: TriangleId,
    rng: u32,
    /// Steps after which a walk is taken to circle (inexact predicates) and the scan is asked.
    step_limit: u32,
    _predicates: std::marker::PhantomData<P>,
}

impl<P: Predicates> Builder<P> {
    #[inline(always)]
    fn corner(&self, e: EdgeId) -> VertexId {
        // SAFETY: every half-edge id handled here is one of the mesh's (`< edge_count()`): they
        // come from the twins (mutual, complete) or from triangles just made.
        unsafe { self.mesh.corner_unchecked(e) }
    }

    #[inline(always)]
    fn twin(&self, e: EdgeId) -> EdgeId {
        // SAFETY: as in `corner`.
        unsafe { self.mesh.twin_unchecked(e) }
    }

    #[inline(always)]
    fn point(&self, v: VertexId) -> Point {
        // SAFETY: `v` is a corner other than GHOST, so a vertex id: `< vertex_count()`.
        unsafe { self.mesh.point_unchecked(v) }
    }

    /// Inserts vertex `v`, walking from the last insertion. `Err(u)` if `v` lies on vertex `u`.
    #[inline(always)]
    fn insert(&mut self, v: VertexId) -> Result<(), VertexId> {
        let p = self.point(v);
        // A triangle with `v` in slot 2, and how the flips treat the hull.
        let (start, ghosts) = match self.locate(p) {
            Location::OnVertex(u) => return Err(u),
            Location::InTriangle(t) => (self.split_triangle(t, v), Ghosts::HullEdges),
            Location::Outside(t) => (self.split_triangle(t, v), Ghosts::GrowHull),
            Location::OnEdge(e) => (self.mesh.split_edge(e, v)[0], Ghosts::HullEdges),
        };
        // SAFETY: the splits leave `v` in slot 2 of every triangle around it, linked (twins
        // complete and mutual); the mesh tracks nothing; corners are vertex ids or GHOST.
        self.last = unsafe { self.mesh.legalize_around_unchecked::<P>(start, ghosts) };
        Ok(())
    }

    /// The visibility walk of [`super::Inserter::locate`] from the last insertion: all three
    /// edges of the first triangle are tested, then, in each triangle entered, the two edges
    /// other than the one crossed, in random order (a stochastic walk cannot cycle, Devillers,
    /// Pion and Teillaud 2002), with the two points of the crossed edge carried over.
    #[inline(always)]
    fn locate(&mut self, p: Point) -> Location {
        let mut t = self.last;
        if t.edges().iter().any(|&e| self.corner(e) == GHOST) {
            // Start from the real triangle across the ghost's hull edge.
            for e in t.edges() {
                if self.corner(e) != GHOST && self.corner(e.next()) != GHOST {
                    t = self.twin(e).triangle();
                    break;
                }
            }
        }
        let ends = |b: &Self, e: EdgeId| (b.corner(e), b.corner(e.next()));
        let points = t.edges().map(|e| self.point(self.corner(e)));
        let mut zeros = [EdgeId::NONE; 2];
        let mut zero_count = 0;
        let mut crossed = None;
        for k in 0..3 {
            let (qa, qb) = (points[k], points[NEXT_SLOT[k] as usize]);
            let o = P::orient2d(qa, qb, p);
            if o < 0.0 {
                crossed = Some((t.edge(k as u32), qa, qb));
                break;
            }
            if o == 0.0 && zero_count < 2 {
                zeros[zero_count] = t.edge(k as u32);
                zero_count += 1;
            }
        }
        let Some((e, qa, qb)) = crossed else {
            return location_in_triangle(
                t,
                &zeros[..zero_count],
                p,
                |e| ends(self, e),
                |v| self.point(v),
            );
        };
        // `f`: the half-edge entered through, from `q0` to `q1` (`p` strictly left of it). The
        // coin's generator lives in a register for the walk, stored back once.
        let mut rng = self.rng;
        let walked = self.walk(self.twin(e), qb, qa, p, &mut rng);
        self.rng = rng;
        match walked {
            Some(location) => location,
            // Only reachable with inexact predicates on hard input.
            None => self.locate_fallback(p),
        }
    }

    /// The walk of [`Self::locate`] past its first triangle, entered through `f` (from `q0` to
    /// `q1`, `p` strictly left of it); `None` after [`Self::step_limit`] steps. Through raw
    /// pointers to the mesh's arrays held in registers, as the flips are
    /// ([`Mesh::legalize_around_unchecked`]).
    #[inline(always)]
    fn walk(
        &self,
        f: EdgeId,
        mut q0: Point,
        mut q1: Point,
        p: Point,
        rng: &mut u32,
    ) -> Option<Location> {
        let (corners, twins, points) = self.mesh.raw_arrays();
        let mut f = f.raw();
        let mut coin = *rng;
        let mut steps_left = self.step_limit;
        let location = loop {
            if steps_left == 0 {
                *rng = coin;
                return None;
            }
            steps_left -= 1;
            // By table, not by branches on the slot (which would be mispredicted).
            let (slot, base) = (f % 3, f / 3 * 3);
            let (e1, e2) = (
                base + NEXT_SLOT[slot as usize],
                base + PREV_SLOT[slot as usize],
            );
            // SAFETY: `f` is a half-edge of the mesh (a twin), so are `e1` and `e2` (of its
            // triangle); corners other than GHOST are vertex ids.
            let x = unsafe { *corners.add(e2 as usize) };
            if x == GHOST.raw() {
                break Location::Outside(TriangleId::new(f / 3));
            }
            // SAFETY: as above.
            let q2 = unsafe { *points.add(x as usize) };
            // A linear congruential step (Numerical Recipes' constants); its top bit is the coin
            // (the low bits of such a generator have short periods, the top one does not).
            coin = coin.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            // Edge e1 runs q1 → q2, e2 runs q2 → q0.
            let (o1, o2) = if coin >> 31 == 0 {
                let o1 = P::orient2d(q1, q2, p);
                if o1 < 0.0 {
                    // SAFETY: as above.
                    (f, q0) = (unsafe { *twins.add(e1 as usize) }, q2);
                    continue;
                }
                let o2 = P::orient2d(q2, q0, p);
                if o2 < 0.0 {
                    // SAFETY: as above.
                    (f, q1) = (unsafe { *twins.add(e2 as usize) }, q2);
                    continue;
                }
                (o1, o2)
            } else {
                let o2 = P::orient2d(q2, q0, p);
                if o2 < 0.0 {
                    // SAFETY: as above.
                    (f, q1) = (unsafe { *twins.add(e2 as usize) }, q2);
                    continue;
                }
                let o1 = P::orient2d(q1, q2, p);
                if o1 < 0.0 {
                    // SAFETY: as above.
                    (f, q0) = (unsafe { *twins.add(e1 as usize) }, q2);
                    continue;
                }
                (o1, o2)
            };
            let u = TriangleId::new(f / 3);
            let (e1, e2) = (EdgeId::new(e1), EdgeId::new(e2));
            let zeros = match (o1 == 0.0, o2 == 0.0) {
                (false, false) => break Location::InTriangle(u),
                (true, false) => [e1, EdgeId::NONE],
                (false, true) => [e2, EdgeId::NONE],
                (true, true) => [e1, e2],
            };
            let count = if zeros[1] == EdgeId::NONE { 1 } else { 2 };
            break location_in_triangle(
                u,
                &zeros[..count],
                p,
                |e| (self.corner(e), self.corner(e.next())),
                |v| self.point(v),
            );
        };
        *rng = coin;
        Some(location)
    }

    /// The general inserter's scan, for the walk that inexact arithmetic can send in circles.
    #[cold]
    fn locate_fallback(&mut self, p: Point) -> Location {
        let mut inserter = super::Inserter::<P>::new(std::mem::take(&mut self.mesh));
        let location = inserter.locate(p, TriangleId::new(0));
        self.mesh = inserter.into_mesh();
        location
    }

    /// [`Mesh::split_triangle_untracked`]: `t` becomes `(a, b, p)`, returned (`p` in slot 2).
    #[inline(always)]
    fn split_triangle(&mut self, t: TriangleId, p: VertexId) -> TriangleId {
        // SAFETY: `t` is a triangle of the mesh (a walk found it), its twins half-edges of the
        // mesh (complete and mutual); the bulk build's mesh tracks nothing.
        unsafe { self.mesh.split_triangle_untracked(t, p) }
    }
}
