//! Lawson's flip algorithm (Lawson 1977): flip every stacked edge whose quadrilateral fails the
//! in-circle test, stacking the edges a flip may have spoiled, until none is left. One loop for
//! every user, with a policy ([`Lawson`]) for what differs: what a stack entry is (a half-edge,
//! or a vertex pair where other flips would renumber half-edges), which edges must stay
//! (segments: the result is then constrained Delaunay, Chew 1989), how edges next to the
//! outside are treated ([`Ghosts`]), what to stack after a flip, and what to tell the caller
//! (the last triangle kept, where the next walk starts). The policy is a type parameter, so
//! each user's loop is compiled for it: the bulk build's has no segment test and no tracking.

use super::{EdgeId, Mesh, TriangleId, VertexId, GHOST};
use crate::geometry::{Point, Predicates};

/// An edge and its two triangles: `e` from `a` to `b` in `(a, b, c)`, its twin `f` from `b` to
/// `a` in `(b, a, d)`. A flip makes them `(a, d, c)` and `(d, b, c)`.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    pub e: EdgeId,
    pub f: EdgeId,
    pub a: VertexId,
    pub b: VertexId,
    pub c: VertexId,
    pub d: VertexId,
}

/// How a Lawson pass treats edges with a ghost on either side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ghosts {
    /// Never flipped: the hull is convex already (the merge, the constrained restore).
    Fixed,
    /// Around a vertex `c` inserted inside or on the hull: a hull edge is flipped when `c` lies
    /// strictly beyond it (only after rounding, or in a non-convex boundary); an edge to the
    /// vertex at infinity is not (flipping there would wrap a triangle around the outside).
    HullEdges,
    /// Around a vertex `c` inserted outside the hull: also edges to the vertex at infinity, when
    /// `c` lies beyond the hull edge of the ghost across: that is how the hull grows around it.
    GrowHull,
}

/// What differs between the users of [`Mesh::legalize`].
pub trait Lawson {
    /// A stack entry.
    type Item: Copy;
    /// Whether flips keep the optional tracking (segments, vertex edges, tags) up to date; false
    /// only for a mesh that tracks nothing (the bulk Delaunay build), whose flips skip it.
    const TRACKED: bool = true;
    /// Whether every stacked half-edge is slot 0 of its triangle (so are insertion's: the edges
    /// opposite the new vertex), which spares the loop the slot arithmetic.
    const SLOT_ZERO: bool = false;
    /// The half-edge an entry stands for now; `None` to skip it (an edge flipped away since).
    fn edge(&self, mesh: &Mesh, item: Self::Item) -> Option<EdgeId>;
    /// Whether the edge of `e` must stay as it is (a segment).
    fn is_fixed(&self, mesh: &Mesh, e: EdgeId) -> bool;
    /// How edges next to the outside are treated.
    fn ghosts(&self) -> Ghosts;
    /// Stacks the edges to check after `quad` was flipped into the triangles `flipped`
    /// (`(a, d, c)` and `(d, b, c)`, slot 0 of each opposite `c`).
    fn after_flip(&mut self, quad: &Quad, flipped: [TriangleId; 2], stack: &mut Vec<Self::Item>);
    /// Told of each edge checked and left as it is (a walk may start next to it).
    #[inline(always)]
    fn kept(&mut self, _e: EdgeId) {}
}

/// The Lawson policy of the constrained restore: the stack holds vertex pairs (flips renumber
/// half-edges, an edge is found again by its ends, [`Mesh::find_edge_hinted`], each with the
/// half-edge it was when stacked, or [`EdgeId::NONE`]), segments stay, edges next to the outside
/// stay, and a flip stacks its quadrilateral's four outer edges (Lawson flips that never cross
/// a segment give the constrained Delaunay triangulation: Chew 1989; Lee and Lin 1986). Used by
/// constrain's restore and by vertex deletion ([`Mesh::delete_vertex`]), which also wants the
/// triangles flipped (`record`).
#[derive(Default)]
pub struct BetweenSegments {
    /// Whether to record the triangles of every flip in `flipped`.
    pub record: bool,
    /// The two triangles of each flip, where `record` asks for them.
    pub flipped: Vec<TriangleId>,
}

impl Lawson for BetweenSegments {
    type Item = (VertexId, VertexId, EdgeId);

    #[inline(always)]
    fn edge(&self, mesh: &Mesh, (u, v, hint): (VertexId, VertexId, EdgeId)) -> Option<EdgeId> {
        mesh.find_edge_hinted(u, v, hint)
    }

    fn is_fixed(&self, mesh: &Mesh, e: EdgeId) -> bool {
        mesh.is_segment(e)
    }

    fn ghosts(&self) -> Ghosts {
        Ghosts::Fixed
    }

    fn after_flip(
        &mut self,
        quad: &Quad,
        flipped: [TriangleId; 2],
        stack: &mut Vec<(VertexId, VertexId, EdgeId)>,
    ) {
        let Quad { a, b, c, d, .. } = *quad;
        // (a, d, c) and (d, b, c), slot 0 opposite `c`.
        let [t1, t2] = flipped;
        stack.extend_from_slice(&[
            (a, d, t1.edge(0)),
            (d, b, t2.edge(0)),
            (b, c, t2.edge(1)),
            (c, a, t1.edge(2)),
        ]);
        if self.record {
            self.flipped.extend_from_slice(&flipped);
        }
    }
}

impl Mesh {
    /// Runs Lawson's flips from the entries on `stack` until it is empty.
    ///
    /// An edge whose quadrilateral has no ghost is flipped when `c` lies strictly inside the
    /// circle through `b`, `a`, `d`; edges next to the outside as `lawson.ghosts()` says.
    #[inline(always)]
    pub fn legalize<P: Predicates, L: Lawson>(&mut self, stack: &mut Vec<L::Item>, lawson: &mut L) {
        // SAFETY: CHECKED = true reads and writes with bounds checks only.
        unsafe { self.run_lawson::<P, L, true>(stack, lawson) }
    }

    /// [`Self::legalize`] without bounds checks, for the bulk Delaunay build's inner loop.
    ///
    /// # Safety
    /// Every entry on `stack` and every entry `lawson.after_flip` stacks must resolve to a
    /// half-edge of the mesh; every half-edge's twin must be a half-edge of the mesh; every
    /// corner must be [`GHOST`] or a vertex with a point.
    #[inline(always)]
    pub unsafe fn legalize_unchecked<P: Predicates, L: Lawson>(
        &mut self,
        stack: &mut Vec<L::Item>,
        lawson: &mut L,
    ) {
        // SAFETY: the caller's contract is the one `run_lawson` needs without checks.
        unsafe { self.run_lawson::<P, L, false>(stack, lawson) }
    }

    /// The loop of both. Safe with `CHECKED`; without, under [`Self::legalize_unchecked`]'s
    /// contract.
    #[inline(always)]
    unsafe fn run_lawson<P: Predicates, L: Lawson, const CHECKED: bool>(
        &mut self,
        stack: &mut Vec<L::Item>,
        lawson: &mut L,
    ) {
        let ghosts = lawson.ghosts();
        while let Some(item) = stack.pop() {
            let Some(e) = lawson.edge(self, item) else {
                continue;
            };
            if lawson.is_fixed(self, e) {
                lawson.kept(e);
                continue;
            }
            debug_assert!(!L::SLOT_ZERO || e.slot() == 0);
            // SAFETY: `e` is a half-edge of the mesh (checked, or by the contract).
            let quad = unsafe { self.quad::<CHECKED>(e, L::SLOT_ZERO) };
            // SAFETY: the quad's corners are GHOST or vertices (checked, or by the contract).
            if unsafe { self.is_illegal::<P, CHECKED>(&quad, ghosts) } {
                let flipped = if L::TRACKED {
                    self.flip(e)
                } else {
                    // SAFETY: the quad's half-edges and their twins are half-edges of the mesh.
                    unsafe { self.flip_untracked::<CHECKED>(&quad, L::SLOT_ZERO) }
                };
                lawson.after_flip(&quad, flipped, stack);
            } else {
                lawson.kept(e);
            }
        }
    }

    /// Lawson's flips around the vertex `p` just inserted, in one turn around it instead of from
    /// a stack: every triangle around `p` has `p` in slot 2 (the splits and the flips leave it
    /// there), so the edges to check are the slot-0 edges of the ring, and a flip replaces the
    /// one being checked by two, the first of them in the same triangle. Each ring edge is
    /// checked once, after it appears; edges to `p` are never flipped (Lawson 1977; the order
    /// of Guibas, Knuth and Sharir 1992), so the turn ends at the vertex it started from.
    /// Returns a triangle around `p` (where the next walk starts).
    ///
    /// The bulk build's loop: no tracking, no segments, no bounds checks.
    ///
    /// # Safety
    /// `start` is a triangle of the mesh with the new vertex in slot 2, and so is every triangle
    /// around that vertex; the mesh tracks nothing; the twins are complete and mutual; every
    /// corner is [`GHOST`] or a vertex with a point.
    #[inline(always)]
    pub unsafe fn legalize_around_unchecked<P: Predicates>(
        &mut self,
        start: TriangleId,
        ghosts: Ghosts,
    ) -> TriangleId {
        debug_assert!(self.segment.is_empty() && self.vertex_edge.is_empty());
        // The arrays through raw pointers held in registers: through `self`, each store into
        // them would make the compiler reload the vectors' pointers (it cannot tell they do not
        // alias), some ten loads per edge checked.
        let points = self.points.as_ptr();
        let corners = self.corners.as_mut_ptr();
        let twins = self.twins.as_mut_ptr();
        // SAFETY (all reads and writes below): half-edges of triangles of the ring and of their
        // neighbours, by the contract, so indices below the arrays' lengths; points are read
        // only for corners other than GHOST, vertices with points by the contract.
        unsafe {
            let corner = |e: u32| *corners.add(e as usize);
            let twin = |e: u32| *twins.add(e as usize);
            let point = |v: u32| *points.add(v as usize);
            let link = |x: u32, y: u32| {
                *twins.add(x as usize) = y;
                *twins.add(y as usize) = x;
            };
            // The ring's triangle is (a, b, c), its slot-0 half-edge `e` from a to b checked next;
            // `a` and `b` are carried from one check to the next (a flip makes `b` the vertex `d`
            // across, a kept edge makes `b` the next triangle's `a`).
            let mut e = 3 * start.raw();
            let c = corner(e + 2);
            let first = corner(e);
            let pc = point(c);
            let (mut a, mut b) = (first, corner(e + 1));
            loop {
                let f = twin(e);
                // `f`'s predecessor in its triangle, from a divisibility test (`f % 3 == 0`
                // compiles to a multiplication and a comparison) instead of a division.
                let f_prev = if f % 3 == 0 { f + 2 } else { f - 1 };
                let d = corner(f_prev);
                let illegal = if a != GHOST.raw() && b != GHOST.raw() && d != GHOST.raw() {
                    P::incircle_positive(point(b), point(a), point(d), pc)
                } else {
                    let v = VertexId::new;
                    let quad = Quad {
                        e: EdgeId::new(e),
                        f: EdgeId::new(f),
                        a: v(a),
                        b: v(b),
                        c: v(c),
                        d: v(d),
                    };
                    self.is_illegal_near_ghost::<P>(&quad, ghosts)
                };
                if illegal {
                    // (a, b, c) and (b, a, d) become (a, d, c) here and (d, b, c) in f's
                    // triangle, whose slot 0 is `g`; the half-edge c → a keeps its slot and its
                    // twin.
                    // (`g` from `f_prev`, of the same triangle: divided, `f` would turn the test
                    // above into a division too.)
                    let g = f_prev / 3 * 3;
                    let f_next = if f - g == 2 { g } else { f + 1 };
                    let tw_ad = twin(f_next);
                    let tw_db = twin(f_prev);
                    let tw_bc = twin(e + 1);
                    *corners.add(e as usize + 1) = d;
                    *corners.add(g as usize) = d;
                    *corners.add(g as usize + 1) = b;
                    *corners.add(g as usize + 2) = c;
                    link(e, tw_ad);
                    link(e + 1, g + 2);
                    link(g, tw_db);
                    link(g + 1, tw_bc);
                    b = d;
                    continue;
                }
                if b == first {
                    return EdgeId::new(e).triangle();
                }
                // The next triangle counter-clockwise around `c`: across b → c, whose twin
                // c → b is its slot 2, two after its slot 0.
                e = twin(e + 1) - 2;
                a = b;
                b = corner(e + 1);
            }
        }
    }

    /// # Safety
    /// Without `CHECKED`: `e` and its twin are half-edges of the mesh.
    #[inline(always)]
    unsafe fn read_corner<const CHECKED: bool>(&self, e: EdgeId) -> VertexId {
        if CHECKED {
            self.origin(e)
        } else {
            // SAFETY: by the caller's contract.
            unsafe { self.corner_unchecked(e) }
        }
    }

    /// # Safety
    /// Without `CHECKED`: `e` is a half-edge of the mesh.
    #[inline(always)]
    unsafe fn read_twin<const CHECKED: bool>(&self, e: EdgeId) -> EdgeId {
        if CHECKED {
            self.twin(e)
        } else {
            // SAFETY: by the caller's contract.
            unsafe { self.twin_unchecked(e) }
        }
    }

    /// # Safety
    /// Without `CHECKED`: `v` is a vertex of the mesh.
    #[inline(always)]
    unsafe fn read_point<const CHECKED: bool>(&self, v: VertexId) -> Point {
        if CHECKED {
            self.point(v)
        } else {
            // SAFETY: by the caller's contract.
            unsafe { self.point_unchecked(v) }
        }
    }

    /// # Safety
    /// Without `CHECKED`: `e` and its twin are half-edges of the mesh.
    #[inline(always)]
    unsafe fn quad<const CHECKED: bool>(&self, e: EdgeId, slot_zero: bool) -> Quad {
        let (e_next, e_prev) = next_and_prev(e, slot_zero);
        // SAFETY (all reads): `e`, its twin, and the other slots of their triangles.
        unsafe {
            let f = self.read_twin::<CHECKED>(e);
            Quad {
                e,
                f,
                a: self.read_corner::<CHECKED>(e),
                b: self.read_corner::<CHECKED>(e_next),
                c: self.read_corner::<CHECKED>(e_prev),
                d: self.read_corner::<CHECKED>(next_and_prev(f, false).1),
            }
        }
    }

    /// [`Self::is_illegal`] for a quad with a ghost corner, out of the ring's loop (rare: only
    /// edges at the hull), with bounds checks.
    #[cold]
    #[inline(never)]
    fn is_illegal_near_ghost<P: Predicates>(&self, quad: &Quad, ghosts: Ghosts) -> bool {
        // SAFETY: CHECKED = true reads with bounds checks only.
        unsafe { self.is_illegal::<P, true>(quad, ghosts) }
    }

    /// Whether the edge of `quad` must be flipped.
    ///
    /// # Safety
    /// Without `CHECKED`: the quad's finite corners are vertices of the mesh.
    #[inline(always)]
    unsafe fn is_illegal<P: Predicates, const CHECKED: bool>(
        &self,
        quad: &Quad,
        ghosts: Ghosts,
    ) -> bool {
        let Quad { a, b, c, d, .. } = *quad;
        // SAFETY: only finite corners are read, vertices by the contract.
        let point = |v: VertexId| unsafe { self.read_point::<CHECKED>(v) };
        if a != GHOST && b != GHOST && c != GHOST && d != GHOST {
            P::incircle_positive(point(b), point(a), point(d), point(c))
        } else if ghosts == Ghosts::Fixed || c == GHOST {
            false
        } else if a == GHOST || b == GHOST {
            // An edge to the vertex at infinity: flipped only to grow the hull around `c`
            // outside it, when `c` lies beyond the hull edge of the ghost across.
            ghosts == Ghosts::GrowHull && {
                let [x, y] = if a == GHOST { [d, b] } else { [a, d] };
                P::orient2d(point(x), point(y), point(c)) > 0.0
            }
        } else {
            // A hull edge, the ghost `d` across: `c` lies beyond it only after rounding.
            P::orient2d(point(b), point(a), point(c)) > 0.0
        }
    }

    /// [`Mesh::flip`] without the tracking (and, without `CHECKED`, without bounds checks):
    /// `(a, b, c)` and `(b, a, d)` become `(a, d, c)` and `(d, b, c)`, slot 0 opposite `c`.
    ///
    /// # Safety
    /// Without `CHECKED`: the quad's half-edges, and every twin of their triangles' half-edges,
    /// are half-edges of the mesh.
    #[inline(always)]
    unsafe fn flip_untracked<const CHECKED: bool>(
        &mut self,
        quad: &Quad,
        slot_zero: bool,
    ) -> [TriangleId; 2] {
        let Quad { e, f, a, b, c, d } = *quad;
        let (t1, t2) = (e.triangle(), f.triangle());
        let ((e_next, e_prev), (f_next, f_prev)) =
            (next_and_prev(e, slot_zero), next_and_prev(f, false));
        // SAFETY (all accesses): half-edges of the two triangles and their twins.
        unsafe {
            let (tw_bc, tw_ca) = (
                self.read_twin::<CHECKED>(e_next),
                self.read_twin::<CHECKED>(e_prev),
            );
            let (tw_ad, tw_db) = (
                self.read_twin::<CHECKED>(f_next),
                self.read_twin::<CHECKED>(f_prev),
            );
            if CHECKED {
                self.set_corners(t1, [a, d, c]);
                self.set_corners(t2, [d, b, c]);
                self.link(t1.edge(0), tw_ad);
                self.link(t1.edge(2), tw_ca);
                self.link(t2.edge(0), tw_db);
                self.link(t2.edge(1), tw_bc);
                self.link(t1.edge(1), t2.edge(2));
            } else {
                self.set_corners_unchecked(t1, [a, d, c]);
                self.set_corners_unchecked(t2, [d, b, c]);
                self.link_unchecked(t1.edge(0), tw_ad);
                self.link_unchecked(t1.edge(2), tw_ca);
                self.link_unchecked(t2.edge(0), tw_db);
                self.link_unchecked(t2.edge(1), tw_bc);
                self.link_unchecked(t1.edge(1), t2.edge(2));
            }
        }
        [t1, t2]
    }
}

/// The half-edges after and before `e` in its triangle, from one division by 3 (or none, when
/// `e` is known to be slot 0).
#[inline(always)]
fn next_and_prev(e: EdgeId, slot_zero: bool) -> (EdgeId, EdgeId) {
    const NEXT_SLOT: [u32; 3] = [1, 2, 0];
    const PREV_SLOT: [u32; 3] = [2, 0, 1];
    if slot_zero {
        (EdgeId::new(e.raw() + 1), EdgeId::new(e.raw() + 2))
    } else {
        let (t, slot) = (e.triangle(), e.slot() as usize);
        (t.edge(NEXT_SLOT[slot]), t.edge(PREV_SLOT[slot]))
    }
}
