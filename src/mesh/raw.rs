//! Below the typed API: unchecked access for the bulk Delaunay build's inner loop, whose safety
//! rests on the mesh's invariants, and the `u32` view ([`RawMesh`]) with the `u32` half-edge
//! arithmetic ([`next`], [`prev`], [`triangle_of`]) for code that works in raw indices: the
//! output numbering (`assemble`, `voronoi`), whose lists are indexed by raw half-edges and
//! triangles, and the half-edge arithmetic inside `ops`.

use super::{EdgeId, Mesh, TriangleId, VertexId};
use crate::geometry::Point;

/// The vertex at infinity as a raw `u32`.
pub const GHOST: u32 = u32::MAX;

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

impl Mesh {
    /// The corner half-edge `e` starts at, without a bounds check.
    ///
    /// # Safety
    /// `e` is a half-edge of the mesh (`< edge_count()`).
    #[inline(always)]
    pub unsafe fn corner_unchecked(&self, e: EdgeId) -> VertexId {
        debug_assert!(e.index() < self.corners.len());
        // SAFETY: by the contract.
        VertexId::new(unsafe { *self.corners.get_unchecked(e.index()) })
    }

    /// The twin of `e`, without a bounds check.
    ///
    /// # Safety
    /// `e` is a half-edge of the mesh.
    #[inline(always)]
    pub unsafe fn twin_unchecked(&self, e: EdgeId) -> EdgeId {
        debug_assert!(e.index() < self.twins.len());
        // SAFETY: by the contract; `twins` has the length of `corners`.
        EdgeId::new(unsafe { *self.twins.get_unchecked(e.index()) })
    }

    /// The point of `v`, without a bounds check.
    ///
    /// # Safety
    /// `v` is a vertex of the mesh (not [`super::GHOST`]).
    #[inline(always)]
    pub unsafe fn point_unchecked(&self, v: VertexId) -> Point {
        debug_assert!(v.index() < self.points.len());
        // SAFETY: by the contract.
        unsafe { *self.points.get_unchecked(v.index()) }
    }

    /// Base pointers of the corner, twin and point arrays, for a read-only loop that keeps them
    /// in registers (the bulk build's walk): valid while the mesh is not changed.
    #[inline(always)]
    pub fn raw_arrays(&self) -> (*const u32, *const u32, *const Point) {
        (
            self.corners.as_ptr(),
            self.twins.as_ptr(),
            self.points.as_ptr(),
        )
    }

    /// [`Mesh::set_corners`] without a bounds check.
    ///
    /// # Safety
    /// `t` is a triangle of the mesh.
    #[inline(always)]
    pub unsafe fn set_corners_unchecked(&mut self, t: TriangleId, corners: [VertexId; 3]) {
        let i = 3 * t.index();
        debug_assert!(i + 3 <= self.corners.len());
        // SAFETY: by the contract, the three slots of `t` are in range.
        unsafe {
            self.corners
                .get_unchecked_mut(i..i + 3)
                .copy_from_slice(&corners.map(VertexId::raw))
        };
    }

    /// [`Mesh::link`] without bounds checks.
    ///
    /// # Safety
    /// `a` and `b` are half-edges of the mesh.
    #[inline(always)]
    pub unsafe fn link_unchecked(&mut self, a: EdgeId, b: EdgeId) {
        debug_assert!(a.index().max(b.index()) < self.twins.len());
        // SAFETY: by the contract.
        unsafe {
            *self.twins.get_unchecked_mut(a.index()) = b.raw();
            *self.twins.get_unchecked_mut(b.index()) = a.raw();
        }
    }

    /// [`Mesh::split_triangle`] for a mesh that tracks nothing (the bulk build), without bounds
    /// checks: `(a, b, c)` becomes `(a, b, p)` in `t`, `(b, c, p)` and `(c, a, p)` are appended,
    /// all linked. Returns `t` (`p` in slot 2). Through raw pointers held in registers, as the
    /// flips around `p` are ([`Mesh::legalize_around_unchecked`]).
    ///
    /// # Safety
    /// `t` is a triangle of the mesh, its twins half-edges of the mesh; the mesh tracks nothing.
    #[inline(always)]
    pub unsafe fn split_triangle_untracked(&mut self, t: TriangleId, p: VertexId) -> TriangleId {
        debug_assert!(
            self.segment.is_empty() && self.vertex_edge.is_empty() && self.tag.is_empty()
        );
        let len = self.corners.len();
        if self.corners.capacity() - len < 6 || self.twins.capacity() - len < 6 {
            // Not reached in the bulk build: n points make at most 2n - 2 triangle slots, and
            // 2n + 2 are reserved.
            self.corners.reserve(6);
            self.twins.reserve(6);
        }
        let (corners, twins) = (self.corners.as_mut_ptr(), self.twins.as_mut_ptr());
        // The new triangles' first half-edges: (b, c, p) from `n`, (c, a, p) from `n + 3`.
        let (e, n, p) = (3 * t.index(), len as u32, p.raw());
        // SAFETY: `e .. e + 3` and the twins read there are half-edges of the mesh (the
        // contract); both arrays have room for 6 more items (checked above), each written before
        // the length covers it.
        unsafe {
            let [a, b, c] = [0, 1, 2].map(|k| *corners.add(e + k));
            let (tw_bc, tw_ca) = (*twins.add(e + 1), *twins.add(e + 2));
            let new_corners = [b, c, p, c, a, p];
            let (e1, e2) = (e as u32 + 1, e as u32 + 2);
            let new_twins = [tw_bc, n + 5, e1, tw_ca, e2, n + 1];
            std::ptr::copy_nonoverlapping(new_corners.as_ptr(), corners.add(len), 6);
            std::ptr::copy_nonoverlapping(new_twins.as_ptr(), twins.add(len), 6);
            self.corners.set_len(len + 6);
            self.twins.set_len(len + 6);
            *corners.add(e + 2) = p;
            *twins.add(e + 1) = n + 2;
            *twins.add(e + 2) = n + 4;
            *twins.add(tw_bc as usize) = n;
            *twins.add(tw_ca as usize) = n + 3;
        }
        t
    }

    /// [`Mesh::with_capacity`] whose twin and corner arrays are `twins`' and `corners`'
    /// allocations (emptied, grown to the room needed): allocated earlier by the caller (the
    /// twins' room used as scratch, whose pages are then already in place; the arrays' place
    /// known to another thread).
    pub fn with_capacity_reusing(
        points: Vec<Point>,
        triangles: usize,
        [mut twins, mut corners]: [Vec<u32>; 2],
    ) -> Mesh {
        for v in [&mut twins, &mut corners] {
            v.clear();
            if v.capacity() < 3 * triangles {
                *v = crate::memory::with_capacity_on_huge_pages(3 * triangles);
            }
        }
        Mesh {
            points,
            corners,
            twins,
            segment: Vec::new(),
            vertex_edge: Vec::new(),
            tag: Vec::new(),
        }
    }

    /// [`Mesh::append`] with each array copied on two threads: the copies' cost is mostly the
    /// fresh pages they write, which two cores fault in twice as fast (the merge of two halves,
    /// whose appended half is as large as the mesh). One array at a time, each of `other`'s
    /// freed once copied, as `append` does: the peak memory stays that of one extra array.
    pub fn append_on_two_threads(&mut self, other: Mesh) {
        debug_assert!(
            self.segment.is_empty() && self.vertex_edge.is_empty() && self.tag.is_empty()
        );
        let offset = self.edge_count();
        let Mesh {
            points,
            corners,
            twins,
            ..
        } = other;
        drop(points);
        extend_on_two_threads(&mut self.corners, corners, 0);
        extend_on_two_threads(&mut self.twins, twins, offset);
    }

    /// The `u32` view of the mesh (see the module docs).
    #[inline(always)]
    pub fn raw(&self) -> RawMesh<'_> {
        RawMesh(self)
    }
}

/// The mesh read through raw `u32` ids, for the output numbering (see the module docs).
#[derive(Clone, Copy)]
pub struct RawMesh<'a>(&'a Mesh);

impl<'a> RawMesh<'a> {
    #[inline(always)]
    pub fn origin(self, e: u32) -> u32 {
        self.0.corners[e as usize]
    }
    #[inline(always)]
    pub fn dest(self, e: u32) -> u32 {
        self.0.corners[next(e) as usize]
    }
    #[inline(always)]
    pub fn apex(self, e: u32) -> u32 {
        self.0.corners[prev(e) as usize]
    }
    #[inline(always)]
    pub fn twin(self, e: u32) -> u32 {
        self.0.twins[e as usize]
    }
    #[inline(always)]
    pub fn point(self, v: u32) -> Point {
        self.0.points[v as usize]
    }
    #[inline(always)]
    pub fn triangle(self, t: u32) -> [u32; 3] {
        self.0.triangle(TriangleId::new(t)).map(VertexId::raw)
    }
    #[inline(always)]
    pub fn triangle_count(self) -> u32 {
        self.0.triangle_count()
    }
    #[inline(always)]
    pub fn segment_of(self, e: u32) -> u32 {
        self.0.segment_of(EdgeId::new(e))
    }
    #[inline(always)]
    pub fn is_segment(self, e: u32) -> bool {
        self.0.is_segment(EdgeId::new(e))
    }
}

/// Appends `added` to `to`, each item plus `offset`, in two halves on two threads; frees `added`.
fn extend_on_two_threads(to: &mut Vec<u32>, added: Vec<u32>, offset: u32) {
    let (len, count) = (to.len(), added.len());
    to.reserve(count);
    let room = &mut to.spare_capacity_mut()[..count];
    let (room_low, room_high) = room.split_at_mut(count / 2);
    let (low, high) = added.split_at(count / 2);
    let copy = |room: &mut [std::mem::MaybeUninit<u32>], from: &[u32]| {
        for (slot, &x) in room.iter_mut().zip(from) {
            slot.write(x + offset);
        }
    };
    std::thread::scope(|scope| {
        scope.spawn(|| copy(room_high, high));
        copy(room_low, low);
    });
    // SAFETY: the two halves wrote all `count` items after the first `len`, within capacity.
    unsafe { to.set_len(len + count) };
}
