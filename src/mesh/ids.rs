//! Typed ids of the mesh's vertices, half-edges and triangles: `u32` indices that the type system
//! keeps apart (a half-edge id passed where a vertex id is expected does not compile). Each is
//! `#[repr(transparent)]`, so the mesh's arrays and hot loops see plain `u32`s.
//!
//! Triangle `t` owns the half-edges `3t`, `3t + 1` and `3t + 2` (its *slots*); half-edge `e`
//! starts at corner `e % 3` of its triangle and ends at the next corner.

use std::fmt;

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[repr(transparent)]
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
        pub struct $name(u32);

        impl $name {
            /// The id with index `raw` (no check: ids are checked where they are used).
            #[inline(always)]
            pub const fn new(raw: u32) -> Self {
                $name(raw)
            }

            /// The raw index.
            #[inline(always)]
            pub const fn raw(self) -> u32 {
                self.0
            }

            /// The raw index, for indexing per-item arrays.
            #[inline(always)]
            pub const fn index(self) -> usize {
                self.0 as usize
            }
        }

        /// Prints the raw index, as messages did before ids were typed.
        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                self.0.fmt(f)
            }
        }
    };
}

id_type!(
    /// A vertex: the index of its point. [`VertexId::GHOST`] is the vertex at infinity.
    VertexId
);
id_type!(
    /// A half-edge: slot `e % 3` of triangle `e / 3`.
    EdgeId
);
id_type!(
    /// A triangle (real or ghost): the owner of half-edges `3t .. 3t + 3`.
    TriangleId
);

impl VertexId {
    /// The vertex at infinity, a corner of every ghost triangle.
    pub const GHOST: VertexId = VertexId(u32::MAX);
    /// "No vertex".
    pub const NONE: VertexId = VertexId(u32::MAX);
}

impl EdgeId {
    /// "No half-edge" (an unlinked twin, an untracked vertex edge).
    pub const NONE: EdgeId = EdgeId(u32::MAX);

    /// The half-edge after this one in its triangle (counter-clockwise).
    #[inline(always)]
    pub const fn next(self) -> EdgeId {
        EdgeId(if self.0 % 3 == 2 {
            self.0 - 2
        } else {
            self.0 + 1
        })
    }

    /// The half-edge before this one in its triangle.
    #[inline(always)]
    pub const fn prev(self) -> EdgeId {
        EdgeId(if self.0 % 3 == 0 {
            self.0 + 2
        } else {
            self.0 - 1
        })
    }

    /// The triangle that owns this half-edge.
    #[inline(always)]
    pub const fn triangle(self) -> TriangleId {
        TriangleId(self.0 / 3)
    }

    /// Which of its triangle's three slots this half-edge is (0, 1 or 2).
    #[inline(always)]
    pub const fn slot(self) -> u32 {
        self.0 % 3
    }
}

impl TriangleId {
    /// "No triangle".
    pub const NONE: TriangleId = TriangleId(u32::MAX);

    /// The half-edge in slot `k` (0, 1 or 2) of this triangle.
    #[inline(always)]
    pub const fn edge(self, k: u32) -> EdgeId {
        EdgeId(3 * self.0 + k)
    }

    /// The three half-edges of this triangle, slot 0 first.
    #[inline(always)]
    pub const fn edges(self) -> [EdgeId; 3] {
        [self.edge(0), self.edge(1), self.edge(2)]
    }
}
