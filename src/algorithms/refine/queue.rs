//! The bad-triangle queue: skinny triangles by their shortest edge's length relative to the
//! domain (shortest first) or by their smallest angle (worst first), then those that are only
//! too large, first in first out.

use std::collections::VecDeque;

use crate::mesh::{TriangleId, VertexId};

/// A queued bad triangle: its corners, and the slot it had when queued (it may be gone by the
/// time it is taken out, and the slot reused).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct BadTriangle {
    /// Queue bucket: higher goes first.
    pub(super) bucket: usize,
    pub(super) corners: [VertexId; 3],
    pub(super) slot: TriangleId,
}

/// Bad triangles in buckets (a bucket queue: constant time per operation, where a binary heap
/// of millions of triangles costs a cache miss per level). Skinny triangles come first, by the
/// length of their shortest edge, shortest first: splitting the small ones first settles the
/// fine parts of the mesh (near small features and small input angles) before the coarse
/// triangles around them are split, so that fewer coarse splits are made that later refinement
/// would have made anyway; measured over Triangle's example files, it gives fewer vertices than
/// worst-angle-first or FIFO order. Above 30° it can cascade away from any input feature,
/// though: every split of a skinny triangle makes an edge shorter than its shortest
/// (circumradius l / (2 sin α) < l for α > 30°), which shortest-first takes next; worst-angle
/// order ([`QueueOrder::WorstAngle`]) does not feed on its own splits that way, and the driver
/// falls back to it when a straight run cascades. Triangles bad only by their size (area, user test) come last, first in first out:
/// ordering them by size too (either way) made as many vertices on large meshes and took half
/// again as long on a million triangles (more flips, longer walks and cavities).
#[derive(Default)]
pub(super) struct BadQueue {
    buckets: Vec<VecDeque<([VertexId; 3], TriangleId)>>,
    /// No bucket above this one holds anything.
    top: usize,
}

/// Buckets of the skinny triangles, above bucket 0 (which holds the triangles bad only by their
/// size): one per halving of the squared shortest edge relative to the domain's extent, shorter
/// first (the precision floor, 2⁻⁴⁰ of the extent, is reached at bucket 81).
pub(super) const EDGE_BUCKETS: usize = 96;

/// The order of the skinny triangles in the queue.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) enum QueueOrder {
    /// Shortest edge first ([`BadQueue::skinny_bucket`]).
    #[default]
    ShortestEdge,
    /// Smallest angle first ([`BadQueue::angle_bucket`]).
    WorstAngle,
}

impl BadQueue {
    pub(super) fn new() -> Self {
        BadQueue {
            buckets: (0..=EDGE_BUCKETS).map(|_| VecDeque::new()).collect(),
            top: 0,
        }
    }
    /// The bucket of a skinny triangle whose shortest edge, squared, is `relative` times the
    /// domain's extent squared.
    pub(super) fn skinny_bucket(relative: f64) -> usize {
        // ⌊−log2 relative⌋ from the exponent bits.
        let exponent = ((relative.to_bits() >> 52) & 0x7ff) as i64 - 1023;
        1 + ((-exponent).max(0) as usize).min(EDGE_BUCKETS - 1)
    }
    /// The bucket of a skinny triangle whose smallest angle has sine `sin`: one per 1/95 of the
    /// sine, smaller first.
    pub(super) fn angle_bucket(sin: f64) -> usize {
        let worse = ((1.0 - sin.clamp(0.0, 1.0)) * (EDGE_BUCKETS - 1) as f64) as usize;
        1 + worse.min(EDGE_BUCKETS - 1)
    }
    /// The bucket of the triangles bad only by their size.
    pub(super) const SIZE_BUCKET: usize = 0;
    pub(super) fn push(&mut self, bad: BadTriangle) {
        self.buckets[bad.bucket].push_back((bad.corners, bad.slot));
        self.top = self.top.max(bad.bucket);
    }
    pub(super) fn pop(&mut self) -> Option<BadTriangle> {
        loop {
            if let Some((corners, slot)) = self.buckets[self.top].pop_front() {
                return Some(BadTriangle {
                    bucket: self.top,
                    corners,
                    slot,
                });
            }
            if self.top == 0 {
                return None;
            }
            self.top -= 1;
        }
    }
    pub(super) fn clear(&mut self) {
        self.buckets.iter_mut().for_each(VecDeque::clear);
        self.top = 0;
    }
    pub(super) fn len(&self) -> usize {
        self.buckets.iter().map(VecDeque::len).sum()
    }
    pub(super) fn is_empty(&self) -> bool {
        self.buckets.iter().all(VecDeque::is_empty)
    }
}
