//! Snapping: vertices within a distance of a subsegment, between its ends, become vertices of
//! it. A pass over a finished constrained Delaunay triangulation, run before refinement at the
//! precision floor refinement works at.

use super::*;

impl<P: Predicates> Constrainer<P> {
    /// Makes every vertex that lies within `floor2.sqrt()` of a subsegment, between its ends
    /// (and not that close to either end), a vertex of it: the subsegment is flipped away and the
    /// two edges to the vertex become the segment ([`Self::flip_edge_onto_vertex`]). Such a
    /// vertex is on the segment at the resolution refinement works at (two segments at an angle
    /// of 10^-16 radians, which rounding makes of one line through a vertex): left apart, the
    /// vertex encroaches the segment, every split point on it encroaches back, and refinement
    /// would fill the sliver between them with vertices down to its floor (Triangle stops with
    /// "Ran out of precision"). Subsegments on the hull are left as they are (refinement's
    /// runaway limit still bounds the work there).
    pub fn snap_vertices_onto_segments(&mut self, floor2: f64) {
        let on_segment = |pu: Point, pv: Point, pw: Point| {
            let length2 = (pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2);
            let height = P::orient2d(pu, pv, pw); // |uv| times w's distance from the line
            let near = |a: Point| (pw[0] - a[0]).powi(2) + (pw[1] - a[1]).powi(2) < floor2;
            height * height < floor2 * length2
                && along(pu, pw, pv)
                && before(pu, pw, pv)
                && !near(pu)
                && !near(pv)
        };
        let mesh = self.mesh();
        // One half-edge per subsegment: the flip looks at the vertices on both sides.
        let mut work: Vec<EdgeId> = mesh
            .edges()
            .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
            .collect();
        while let Some(e) = work.pop() {
            let mesh = self.mesh();
            let (u, v) = (mesh.origin(e), mesh.dest(e));
            if !mesh.is_segment(e) {
                continue;
            }
            if let Some(w) = self.flip_edge_onto_vertex(e, on_segment) {
                let mesh = self.mesh();
                work.extend(
                    [(u, w), (w, v)]
                        .into_iter()
                        .filter_map(|(a, b)| mesh.find_edge(a, b)),
                );
            }
        }
    }
}
