//! Chew's rule: before a subsegment is split, the free vertices strictly inside its diametral
//! circle are deleted (L. P. Chew, "Guaranteed-quality mesh generation for curved surfaces",
//! 1993, and "Guaranteed-quality Delaunay meshing in 3D", 1997; Shewchuk, "Delaunay
//! refinement algorithms for triangular mesh generation", CGTA 2002, §5, where it is Chew's
//! second algorithm). A free vertex is one inserted at a bad triangle's split point
//! ([`VertexKind::Free`]): never an input vertex, a vertex on a segment or a lattice seed. Such
//! a vertex near a subsegment was put there for triangles that the split will remake anyway,
//! and once the subsegment is split it would stand too close to the new vertex on it; deleting
//! it lets the triangles there grow back from the split instead (Triangle does the same, and
//! its meshes of small inputs are that much smaller).
//!
//! Only vertices seen from the subsegment are deleted: those of the triangles met by walking
//! from the subsegment's domain side(s) across edges that meet the disk, never across a
//! segment. The deletion itself is the mesh's ([`crate::mesh::Mesh::delete_vertex`]); the
//! refinement re-checks the triangles it makes and the subsegments around them.
//!
//! At every angle bound, as Triangle: above 30° in shortest-edge order, where a run can cascade
//! (see `super::queue`), deleted vertices are made again, and more (Triangle's `greenland.ele`
//! with `rq34`: the straight run, discarded in the end, makes 847 000 vertices instead of
//! 397 000, 1.8× the time); left out there, the meshes kept over Triangle's examples have 0.06%
//! more triangles on geometric mean, and a smallest angle at least Triangle's on one case fewer.

use super::{inside, VertexKind};
use crate::geometry::Point;
use crate::mesh::{EdgeId, Mesh, TriangleId, VertexId};

/// The walk over the triangles that meet a subsegment's diametral disk (its buffers are reused
/// from subsegment to subsegment).
#[derive(Default)]
pub(super) struct DiskWalk {
    stack: Vec<TriangleId>,
    /// Per triangle slot: the number of the last walk that met it (`generation` for this one).
    stamp: Vec<u32>,
    generation: u32,
    found: Vec<VertexId>,
}

impl DiskWalk {
    /// The free vertices strictly inside the diametral circle of the subsegment of half-edge
    /// `e` that can be deleted (see [`Mesh::is_deletable`]), seen from it: in the domain
    /// triangles reached from the subsegment across non-segment edges that meet the disk.
    pub(super) fn free_vertices_in(
        &mut self,
        mesh: &Mesh,
        kinds: &[VertexKind],
        e: EdgeId,
    ) -> &[VertexId] {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.fill(0);
            self.generation = 1;
        }
        self.stamp.resize(mesh.triangle_count() as usize, 0);
        self.stack.clear();
        self.found.clear();
        let (pu, pv) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
        let centre = [0.5 * (pu[0] + pv[0]), 0.5 * (pu[1] + pv[1])];
        let radius2 = 0.25 * ((pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2));
        let generation = self.generation;
        for h in [e, mesh.twin(e)] {
            let t = h.triangle();
            if !mesh.is_ghost(t) && inside(mesh, t) && self.stamp[t.index()] != generation {
                self.stamp[t.index()] = generation;
                self.stack.push(t);
            }
        }
        while let Some(t) = self.stack.pop() {
            for h in t.edges() {
                let w = mesh.origin(h);
                if kinds[w.index()] == VertexKind::Free
                    && strictly_inside(pu, pv, mesh.point(w))
                    && !self.found.contains(&w)
                    && mesh.is_deletable(w)
                {
                    self.found.push(w);
                }
                if mesh.is_segment(h) {
                    continue;
                }
                let n = mesh.twin(h).triangle();
                if self.stamp[n.index()] == generation || mesh.is_ghost(n) || !inside(mesh, n) {
                    continue;
                }
                let (p, q) = (mesh.point(w), mesh.point(mesh.dest(h)));
                if meets_disk(p, q, centre, radius2) {
                    self.stamp[n.index()] = generation;
                    self.stack.push(n);
                }
            }
        }
        &self.found
    }
}

/// Whether `w` lies strictly inside the circle with diameter `pu`–`pv`: the subsegment subtends
/// more than a right angle at `w` (the test of `Encroachment` with circles).
fn strictly_inside(pu: Point, pv: Point, w: Point) -> bool {
    let (a, b) = ([pu[0] - w[0], pu[1] - w[1]], [pv[0] - w[0], pv[1] - w[1]]);
    a[0] * b[0] + a[1] * b[1] < 0.0
}

/// Whether the edge from `p` to `q` meets the open disk (with a little slack: a walk that goes
/// one triangle too far only looks at more vertices, each tested exactly as above). The
/// squared distance from the centre to the edge, times the edge's squared length, against the
/// radius squared times the same: no division.
fn meets_disk(p: Point, q: Point, centre: Point, radius2: f64) -> bool {
    let d = [q[0] - p[0], q[1] - p[1]];
    let c = [centre[0] - p[0], centre[1] - p[1]];
    let along = c[0] * d[0] + c[1] * d[1];
    let to_p = c[0] * c[0] + c[1] * c[1];
    let slack = radius2 * (1.0 + 1e-9);
    if along <= 0.0 {
        return to_p < slack; // nearest to p
    }
    let length2 = d[0] * d[0] + d[1] * d[1];
    if along >= length2 {
        let to_q = (centre[0] - q[0]).powi(2) + (centre[1] - q[1]).powi(2);
        return to_q < slack; // nearest to q
    }
    // |c|²·|d|² − (c·d)² = (c × d)², the squared distance times |d|².
    let cross = c[0] * d[1] - c[1] * d[0];
    cross * cross < slack * length2
}
