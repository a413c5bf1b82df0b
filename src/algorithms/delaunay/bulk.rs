//! The bulk Delaunay build: the points of a point set inserted one after another, in the order
//! they are given (a spatially coherent order: [`super::order`]), by a visibility walk from the
//! previous point, a split and Lawson flips — the algorithm of [`super::Inserter`], with the
//! work that a plain point set never needs taken out of the loop that runs once per point: no
//! segments, tags or vertex links to keep, ghosts tested only on the rare edges that touch them,
//! and no bounds checks on the mesh arrays (the mesh's unchecked accessors, whose safety rests on
//! its invariants). The flips are the one Lawson loop, [`Mesh::legalize_unchecked`], compiled for
//! the untracked policy [`AroundVertex`]`<false>`.
//!
//! The result is the same mesh as [`super::Inserter`] builds (same triangles, same slots).

use super::{location_in_triangle, AroundVertex, Location};
use crate::geometry::{Point, Predicates};
use crate::mesh::{EdgeId, Ghosts, Mesh, TriangleId, VertexId, GHOST, NONE};

/// Triangulates `points` inserting them in index order; returns the mesh and, per vertex, the
/// vertex it duplicates (or [`NONE`]). The mesh's arrays have room for `capacity` triangle
/// slots (at least the `2n + 2` that the build may use): a caller that appends more triangles
/// later asks for them here, so that no array is reallocated (and copied) on the way.
pub(super) fn triangulate_in_order<P: Predicates>(
    points: Vec<Point>,
    capacity: usize,
) -> (Mesh, Vec<u32>) {
    let n = points.len() as u32;
    let mut duplicate_of = vec![NONE; n as usize];
    let capacity = capacity.max(2 * points.len() + 2);
    let mut mesh = Mesh::with_capacity(points, capacity);
    // Seed triangle: the first point, the first point distinct from it, and the first point not
    // collinear with those two.
    if n == 0 {
        return (mesh, duplicate_of);
    }
    let v = VertexId::new;
    let pa = mesh.point(v(0));
    let Some(b) = (1..n).map(v).find(|&u| mesh.point(u) != pa) else {
        return (mesh, duplicate_of);
    };
    let pb = mesh.point(b);
    let Some(c) = (b.raw() + 1..n)
        .map(v)
        .find(|&u| P::orient2d(pa, pb, mesh.point(u)) != 0.0)
    else {
        return (mesh, duplicate_of);
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
        stack: Vec::with_capacity(64),
        _predicates: Default::default(),
    };
    for u in (1..n).map(v) {
        if u == b || u == c {
            continue;
        }
        if let Err(w) = builder.insert(u) {
            duplicate_of[u.index()] = w.raw();
        }
    }
    (builder.mesh, duplicate_of)
}

/// The slot after and before each slot of a triangle.
const NEXT_SLOT: [u32; 3] = [1, 2, 0];
const PREV_SLOT: [u32; 3] = [2, 0, 1];
/// The three slots starting from each one.
const ROTATED: [[u32; 3]; 3] = [[0, 1, 2], [1, 2, 0], [2, 0, 1]];

struct Builder<P: Predicates> {
    mesh: Mesh,
    /// A triangle incident to the last inserted vertex: where the next walk starts.
    last: TriangleId,
    rng: u32,
    stack: Vec<EdgeId>,
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

    #[inline(always)]
    fn link(&mut self, a: EdgeId, b: EdgeId) {
        // SAFETY: as in `corner`: both are half-edges of the mesh.
        unsafe { self.mesh.link_unchecked(a, b) }
    }

    /// Inserts vertex `v`, walking from the last insertion. `Err(u)` if `v` lies on vertex `u`.
    #[inline(always)]
    fn insert(&mut self, v: VertexId) -> Result<(), VertexId> {
        let p = self.point(v);
        let location = self.locate(p);
        let grows_hull = matches!(location, Location::Outside(_));
        match location {
            Location::OnVertex(u) => return Err(u),
            Location::InTriangle(t) | Location::Outside(t) => self.split_triangle(t, v),
            Location::OnEdge(e) => {
                let ts = self.mesh.split_edge(e, v);
                self.stack.extend(ts.iter().map(|&t| t.edge(0)));
            }
        }
        let mut star = AroundVertex::<false> {
            ghosts: if grows_hull {
                Ghosts::GrowHull
            } else {
                Ghosts::HullEdges
            },
            last: &mut self.last,
        };
        // SAFETY: the stack holds slot 0 of triangles of the mesh, and the flips stack slot 0 of
        // the two they rewrite; the twins are complete (every triangle is linked before the
        // flips); corners are vertex ids or GHOST.
        unsafe {
            self.mesh
                .legalize_unchecked::<P, _>(&mut self.stack, &mut star)
        };
        Ok(())
    }

    /// The visibility walk of [`super::Inserter::locate`] (stochastic: the first edge tested
    /// varies, so the walk cannot cycle), from the last insertion.
    #[inline(always)]
    fn locate(&mut self, p: Point) -> Location {
        let mut t = self.last;
        if self.mesh.is_ghost(t) {
            // Start from the real triangle across the ghost's hull edge.
            for e in t.edges() {
                if self.corner(e) != GHOST && self.corner(e.next()) != GHOST {
                    t = self.twin(e).triangle();
                    break;
                }
            }
        }
        let mut entry = EdgeId::NONE;
        let mut steps: u32 = 0;
        let step_limit = 4 * self.mesh.triangle_count() + 64;
        'walk: loop {
            steps += 1;
            if steps > step_limit {
                // Only reachable with inexact predicates on hard input.
                return self.locate_fallback(p);
            }
            self.rng ^= self.rng << 13;
            self.rng ^= self.rng >> 17;
            self.rng ^= self.rng << 5;
            let offset = (self.rng % 3) as usize;
            // The three corners and their points, read once; edge `k` runs from corner `k` to
            // corner `k + 1`.
            let corners = t.edges().map(|e| self.corner(e));
            let mut zeros = [EdgeId::NONE; 2];
            let mut zero_count = 0;
            for &slot in &ROTATED[offset] {
                let e = t.edge(slot);
                if e == entry {
                    continue;
                }
                let (a, b) = (
                    corners[slot as usize],
                    corners[NEXT_SLOT[slot as usize] as usize],
                );
                let o = P::orient2d(self.point(a), self.point(b), p);
                if o < 0.0 {
                    let f = self.twin(e);
                    let t_f = f.triangle();
                    if self.corner(t_f.edge(PREV_SLOT[f.slot() as usize])) == GHOST {
                        return Location::Outside(t_f);
                    }
                    t = t_f;
                    entry = f;
                    continue 'walk;
                }
                if o == 0.0 && zero_count < 2 {
                    zeros[zero_count] = e;
                    zero_count += 1;
                }
            }
            return location_in_triangle(
                t,
                &zeros[..zero_count],
                p,
                |e| (self.corner(e), self.corner(e.next())),
                |v| self.point(v),
            );
        }
    }

    /// The general inserter's scan, for the walk that inexact arithmetic can send in circles.
    #[cold]
    fn locate_fallback(&mut self, p: Point) -> Location {
        let mut inserter = super::Inserter::<P>::new(std::mem::take(&mut self.mesh));
        let location = inserter.locate(p, TriangleId::new(0));
        self.mesh = inserter.into_mesh();
        location
    }

    /// [`Mesh::split_triangle`] without the tracking: `(a, b, c)` becomes `(a, b, p)`,
    /// `(b, c, p)`, `(c, a, p)`; their slot-0 edges (opposite `p`) go on the flip stack.
    #[inline(always)]
    fn split_triangle(&mut self, t: TriangleId, p: VertexId) {
        let [a, b, c] = t.edges().map(|e| self.corner(e));
        let [tw_ab, tw_bc, tw_ca] = t.edges().map(|e| self.twin(e));
        let t1 = self.mesh.push_two_triangles([b, c, p, c, a, p]);
        let t2 = TriangleId::new(t1.raw() + 1);
        // SAFETY: `t` is a triangle of the mesh (a walk found it).
        unsafe { self.mesh.set_corners_unchecked(t, [a, b, p]) };
        self.link(t.edge(0), tw_ab);
        self.link(t1.edge(0), tw_bc);
        self.link(t2.edge(0), tw_ca);
        self.link(t.edge(1), t1.edge(2));
        self.link(t1.edge(1), t2.edge(2));
        self.link(t2.edge(1), t.edge(2));
        self.stack
            .extend_from_slice(&[t.edge(0), t1.edge(0), t2.edge(0)]);
    }
}
