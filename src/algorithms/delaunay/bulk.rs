//! The bulk Delaunay build: the points of a point set inserted one after another, in the order
//! they are given (a spatially coherent order: [`super::order`]), by a visibility walk from the
//! previous point, a split and Lawson flips — the algorithm of [`super::Inserter`], with the
//! work that a plain point set never needs taken out of the loop that runs once per point: no
//! segments, tags or vertex links to keep, ghosts tested only on the rare edges that touch them,
//! and no bounds checks on the mesh arrays, whose indices the mesh's invariants keep in range.
//!
//! The result is the same mesh as [`super::Inserter`] builds (same triangles, same slots).

use super::{location_in_triangle, Location};
use crate::geometry::{Point, Predicates};
use crate::mesh::{next, triangle_of, Mesh, GHOST, NONE};

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
    let capacity = 3 * capacity.max(2 * points.len() + 2);
    let mut mesh = Mesh {
        points,
        corners: Vec::with_capacity(capacity),
        twins: Vec::with_capacity(capacity),
        ..Mesh::default()
    };
    // Seed triangle: the first point, the first point distinct from it, and the first point not
    // collinear with those two.
    if n == 0 {
        return (mesh, duplicate_of);
    }
    let pa = mesh.point(0);
    let Some(b) = (1..n).find(|&v| mesh.point(v) != pa) else {
        return (mesh, duplicate_of);
    };
    let pb = mesh.point(b);
    let Some(c) = (b + 1..n).find(|&v| P::orient2d(pa, pb, mesh.point(v)) != 0.0) else {
        return (mesh, duplicate_of);
    };
    if P::orient2d(pa, pb, mesh.point(c)) > 0.0 {
        mesh.init_triangle(0, b, c);
    } else {
        mesh.init_triangle(0, c, b);
    }
    let mut builder = Builder::<P> {
        mesh,
        last: 0,
        rng: 0x9E37_79B9,
        stack: Vec::with_capacity(64),
        _predicates: Default::default(),
    };
    for v in 1..n {
        if v == b || v == c {
            continue;
        }
        if let Err(u) = builder.insert(v) {
            duplicate_of[v as usize] = u;
        }
    }
    (builder.mesh, duplicate_of)
}

/// The slot after and before each slot of a triangle.
const NEXT_SLOT: [usize; 3] = [1, 2, 0];
const PREV_SLOT: [usize; 3] = [2, 0, 1];
/// The three slots starting from each one.
const ROTATED: [[usize; 3]; 3] = [[0, 1, 2], [1, 2, 0], [2, 0, 1]];

struct Builder<P: Predicates> {
    mesh: Mesh,
    /// A triangle incident to the last inserted vertex: where the next walk starts.
    last: u32,
    rng: u32,
    stack: Vec<u32>,
    _predicates: std::marker::PhantomData<P>,
}

impl<P: Predicates> Builder<P> {
    #[inline(always)]
    fn corner(&self, e: u32) -> u32 {
        debug_assert!((e as usize) < self.mesh.corners.len());
        // SAFETY: every half-edge id handled here is one of the mesh's (`< corners.len()`):
        // they come from `twins` (mutual, complete) or from triangles just made.
        unsafe { *self.mesh.corners.get_unchecked(e as usize) }
    }

    #[inline(always)]
    fn twin(&self, e: u32) -> u32 {
        debug_assert!((e as usize) < self.mesh.twins.len());
        // SAFETY: as in `corner`; `twins` has the length of `corners`.
        unsafe { *self.mesh.twins.get_unchecked(e as usize) }
    }

    #[inline(always)]
    fn point(&self, v: u32) -> Point {
        debug_assert!((v as usize) < self.mesh.points.len());
        // SAFETY: `v` is a corner other than GHOST, so a vertex id: `< points.len()`.
        unsafe { *self.mesh.points.get_unchecked(v as usize) }
    }

    #[inline(always)]
    fn set_corners(&mut self, t: u32, corners: [u32; 3]) {
        let i = 3 * t as usize;
        debug_assert!(i + 3 <= self.mesh.corners.len());
        // SAFETY: `t` is a triangle of the mesh, so its three slots are in range.
        unsafe {
            self.mesh
                .corners
                .get_unchecked_mut(i..i + 3)
                .copy_from_slice(&corners)
        };
    }

    /// Appends two triangles (corners given, twins to be linked); returns the first one's index.
    #[inline(always)]
    fn add_two_triangles(&mut self, corners: [u32; 6]) -> u32 {
        let mesh = &mut self.mesh;
        let len = mesh.corners.len();
        if mesh.corners.capacity() - len < 6 || mesh.twins.capacity() - len < 6 {
            // Not reached: n points make at most 2n - 2 triangle slots, and 2n + 2 are reserved.
            mesh.corners.reserve(6);
            mesh.twins.reserve(6);
        }
        // SAFETY: both vectors have room for 6 more items (checked above); every new item is
        // written before the length covers it.
        unsafe {
            std::ptr::copy_nonoverlapping(corners.as_ptr(), mesh.corners.as_mut_ptr().add(len), 6);
            std::ptr::write_bytes(mesh.twins.as_mut_ptr().add(len), 0xff, 6);
            mesh.corners.set_len(len + 6);
            mesh.twins.set_len(len + 6);
        }
        (len / 3) as u32
    }

    /// Pushes two half-edges on the flip stack.
    #[inline(always)]
    fn push_two(&mut self, a: u32, b: u32) {
        let len = self.stack.len();
        if self.stack.capacity() - len < 2 {
            self.stack.reserve(64);
        }
        // SAFETY: room for two more (checked above), written before the length covers them.
        unsafe {
            let top = self.stack.as_mut_ptr().add(len);
            top.write(a);
            top.add(1).write(b);
            self.stack.set_len(len + 2);
        }
    }

    #[inline(always)]
    fn link(&mut self, a: u32, b: u32) {
        debug_assert!((a.max(b) as usize) < self.mesh.twins.len());
        // SAFETY: as in `corner`: both are half-edges of the mesh.
        unsafe {
            *self.mesh.twins.get_unchecked_mut(a as usize) = b;
            *self.mesh.twins.get_unchecked_mut(b as usize) = a;
        }
    }

    /// Inserts vertex `v`, walking from the last insertion. `Err(u)` if `v` lies on vertex `u`.
    #[inline(always)]
    fn insert(&mut self, v: u32) -> Result<(), u32> {
        let p = self.point(v);
        let location = self.locate(p);
        let grows_hull = matches!(location, Location::Outside(_));
        match location {
            Location::OnVertex(u) => return Err(u),
            Location::InTriangle(t) | Location::Outside(t) => self.split_triangle(t, v),
            Location::OnEdge(e) => {
                let ts = self.mesh.split_edge(e, v);
                self.stack.extend(ts.iter().map(|&t| 3 * t));
            }
        }
        self.legalize(p, grows_hull);
        Ok(())
    }

    /// The visibility walk of [`super::Inserter::locate`] (stochastic: the first edge tested
    /// varies, so the walk cannot cycle), from the last insertion.
    #[inline(always)]
    fn locate(&mut self, p: Point) -> Location {
        let mut t = self.last;
        if self.mesh.is_ghost(t) {
            // Start from the real triangle across the ghost's hull edge.
            for e in 3 * t..3 * t + 3 {
                if self.corner(e) != GHOST && self.corner(next(e)) != GHOST {
                    t = triangle_of(self.twin(e));
                    break;
                }
            }
        }
        let mut entry = NONE;
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
            let base = 3 * t;
            // The three corners and their points, read once; edge `k` runs from corner `k` to
            // corner `k + 1`.
            let corners = [
                self.corner(base),
                self.corner(base + 1),
                self.corner(base + 2),
            ];
            let mut zeros = [NONE; 2];
            let mut zero_count = 0;
            for &slot in &ROTATED[offset] {
                let e = base + slot as u32;
                if e == entry {
                    continue;
                }
                let (a, b) = (corners[slot], corners[NEXT_SLOT[slot]]);
                let o = P::orient2d(self.point(a), self.point(b), p);
                if o < 0.0 {
                    let f = self.twin(e);
                    let (t_f, slot_f) = (f / 3, (f % 3) as usize);
                    if self.corner(3 * t_f + PREV_SLOT[slot_f] as u32) == GHOST {
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
                |e| (self.corner(e), self.corner(next(e))),
                |v| self.point(v),
            );
        }
    }

    /// The general inserter's scan, for the walk that inexact arithmetic can send in circles.
    #[cold]
    fn locate_fallback(&mut self, p: Point) -> Location {
        let mut inserter = super::Inserter::<P>::new(std::mem::take(&mut self.mesh));
        let location = inserter.locate(p, 0);
        self.mesh = inserter.mesh;
        location
    }

    /// [`Mesh::split_triangle`] without the tracking: `(a, b, c)` becomes `(a, b, p)`,
    /// `(b, c, p)`, `(c, a, p)`; their slot-0 edges (opposite `p`) go on the flip stack.
    #[inline(always)]
    fn split_triangle(&mut self, t: u32, p: u32) {
        let base = 3 * t;
        let [a, b, c] = [
            self.corner(base),
            self.corner(base + 1),
            self.corner(base + 2),
        ];
        let [tw_ab, tw_bc, tw_ca] = [self.twin(base), self.twin(base + 1), self.twin(base + 2)];
        let t1 = self.add_two_triangles([b, c, p, c, a, p]);
        let t2 = t1 + 1;
        self.set_corners(t, [a, b, p]);
        self.link(base, tw_ab);
        self.link(3 * t1, tw_bc);
        self.link(3 * t2, tw_ca);
        self.link(base + 1, 3 * t1 + 2);
        self.link(3 * t1 + 1, 3 * t2 + 2);
        self.link(3 * t2 + 1, base + 2);
        self.stack.push(base);
        self.push_two(3 * t1, 3 * t2);
    }

    /// Lawson's flips around the new vertex at `p` (see [`super::Inserter`]'s `legalize`): each
    /// stacked half-edge is slot 0 of a triangle `(a, b, p)`; its edge is flipped while `p` lies
    /// strictly inside the circumcircle of the triangle `(b, a, d)` across it.
    #[inline(always)]
    fn legalize(&mut self, p: Point, grows_hull: bool) {
        while let Some(e) = self.stack.pop() {
            let f = self.twin(e);
            let (t_f, slot_f) = (f / 3, (f % 3) as usize);
            let (a, b) = (self.corner(e), self.corner(e + 1));
            let d = self.corner(3 * t_f + PREV_SLOT[slot_f] as u32);
            let illegal = if a != GHOST && b != GHOST && d != GHOST {
                P::incircle(self.point(b), self.point(a), self.point(d), p) > 0.0
            } else if a == GHOST || b == GHOST {
                // An edge to the vertex at infinity: flipped only to grow the hull around a
                // point outside it, when `p` lies beyond the hull edge of the ghost across.
                grows_hull && {
                    let [x, y] = if a == GHOST { [d, b] } else { [a, d] };
                    P::orient2d(self.point(x), self.point(y), p) > 0.0
                }
            } else {
                // A hull edge: `p` never lies beyond it.
                P::orient2d(self.point(b), self.point(a), p) > 0.0
            };
            if illegal {
                self.flip(e, t_f, slot_f, [a, b, d]);
            } else {
                self.last = triangle_of(e);
            }
        }
    }

    /// [`Mesh::flip`] without the tracking: `(a, b, p)` at `e` (slot 0) and `(b, a, q)` with its
    /// half-edge `b → a` in slot `slot_f` of triangle `t2` become `(a, q, p)` and `(q, b, p)`
    /// (slot 0 opposite `p`), whose slot-0 edges are stacked.
    #[inline(always)]
    fn flip(&mut self, e: u32, t2: u32, slot_f: usize, [a, b, q]: [u32; 3]) {
        let t1 = triangle_of(e);
        let p = self.corner(e + 2);
        let (tw_bp, tw_pa) = (self.twin(e + 1), self.twin(e + 2));
        let base_f = 3 * t2;
        let (tw_aq, tw_qb) = (
            self.twin(base_f + NEXT_SLOT[slot_f] as u32),
            self.twin(base_f + PREV_SLOT[slot_f] as u32),
        );
        self.set_corners(t1, [a, q, p]);
        self.set_corners(t2, [q, b, p]);
        let (g1, g2) = (3 * t1, 3 * t2);
        self.link(g1, tw_aq);
        self.link(g1 + 2, tw_pa);
        self.link(g2, tw_qb);
        self.link(g2 + 1, tw_bp);
        self.link(g1 + 1, g2 + 2);
        self.push_two(g1, g2);
    }
}
