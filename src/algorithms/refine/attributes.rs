//! The attributes of new vertices: interpolated linearly from the vertices of the segment or the
//! triangle they are put on.

use crate::mesh::VertexId;

/// Per vertex, `count` values (the caller's array, which new vertices are appended to).
pub(super) struct Attributes<'a> {
    values: &'a mut Vec<f64>,
    count: usize,
}

impl<'a> Attributes<'a> {
    pub(super) fn new(values: &'a mut Vec<f64>, count: usize) -> Self {
        Attributes { values, count }
    }

    /// Appends the attributes of a vertex at parameter `t` from `u` to `v`.
    pub(super) fn push_on_segment(&mut self, u: VertexId, v: VertexId, t: f64) {
        if let Some(w) = self.push_row() {
            self.set_on_segment(w, u, v, t);
        }
    }

    /// Appends the attributes of a vertex at affine frame coordinates `(xi, eta)` in triangle
    /// `(a, b, c)`: `a + xi·(b − a) + eta·(c − a)`.
    pub(super) fn push_in_triangle(&mut self, corners: [VertexId; 3], xi: f64, eta: f64) {
        if let Some(w) = self.push_row() {
            self.set_in_triangle(w, corners, xi, eta);
        }
    }

    /// Appends a row for a new vertex (to be set), and returns the vertex; none without
    /// attributes.
    fn push_row(&mut self) -> Option<VertexId> {
        let k = self.count;
        if k == 0 {
            return None;
        }
        let w = VertexId::new((self.values.len() / k) as u32);
        self.values.resize(self.values.len() + k, 0.0);
        Some(w)
    }

    /// Sets the attributes of vertex `w` to those at parameter `t` from `u` to `v`.
    pub(super) fn set_on_segment(&mut self, w: VertexId, u: VertexId, v: VertexId, t: f64) {
        let k = self.count;
        for i in 0..k {
            let (at_u, at_v) = (
                self.values[u.index() * k + i],
                self.values[v.index() * k + i],
            );
            self.values[w.index() * k + i] = at_u + t * (at_v - at_u);
        }
    }

    /// Sets the attributes of vertex `w` to those at affine frame coordinates `(xi, eta)` in
    /// triangle `(a, b, c)` (`w` may be a corner: a vertex moved within its star).
    pub(super) fn set_in_triangle(
        &mut self,
        w: VertexId,
        [a, b, c]: [VertexId; 3],
        xi: f64,
        eta: f64,
    ) {
        let k = self.count;
        for i in 0..k {
            let (va, vb, vc) = (
                self.values[a.index() * k + i],
                self.values[b.index() * k + i],
                self.values[c.index() * k + i],
            );
            self.values[w.index() * k + i] = va + xi * (vb - va) + eta * (vc - va);
        }
    }

    /// The attributes of vertex `w` (empty without attributes).
    pub(super) fn row(&self, w: VertexId) -> &[f64] {
        let k = self.count;
        &self.values[w.index() * k..(w.index() + 1) * k]
    }

    /// How many attributes each vertex has.
    pub(super) fn count(&self) -> usize {
        self.count
    }

    /// Sets the attributes of vertex `w` to `row` (as [`Self::row`] gave them).
    pub(super) fn set_row(&mut self, w: VertexId, row: &[f64]) {
        let k = self.count;
        self.values[w.index() * k..(w.index() + 1) * k].copy_from_slice(row);
    }

    /// Keeps the rows of the vertices `v` for which `keep(v)` holds, in order.
    pub(super) fn retain_rows(&mut self, keep: impl Fn(usize) -> bool) {
        let k = self.count;
        if k == 0 {
            return;
        }
        let mut kept = 0;
        for v in 0..self.values.len() / k {
            if keep(v) {
                self.values.copy_within(v * k..(v + 1) * k, kept * k);
                kept += 1;
            }
        }
        self.values.truncate(kept * k);
    }

    /// Exchanges the values with `other` (a refinement state set aside).
    pub(super) fn swap(&mut self, other: &mut Vec<f64>) {
        std::mem::swap(self.values, other);
    }

    /// A copy of the values.
    pub(super) fn to_vec(&self) -> Vec<f64> {
        self.values.clone()
    }
}
