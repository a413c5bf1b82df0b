//! Vertices moved onto a grid: the points that the caller's coordinates can hold.
//!
//! The engine may mesh in a frame of its own (translated to a local origin and scaled, see
//! `crate::scaling`), where a new vertex can have coordinates that the caller's doubles cannot
//! hold; given back rounded, it would make the caller's mesh another one than the engine
//! checked. So before the outputs every vertex is moved, in the engine's frame, to the point
//! the caller will receive ([`Grid::round`]), the mesh is checked with those coordinates and
//! made Delaunay again by Lawson flips: what the caller gets is exactly what the engine
//! checked. Rounding moves a vertex by half a unit in the last place of the caller's
//! coordinates; the move is refused only where it would invert a triangle (vertices closer
//! than the caller's rounding), and the shapes it spoils are the refinement's to mend.

use super::*;
use crate::geometry::Grid;
use crate::mesh::OUTSIDE;

impl<P: Predicates> Constrainer<P> {
    /// Moves every vertex `v` to `grid.round(v)` (see the module documentation) and restores
    /// the constrained Delaunay property by flips; returns whether it did. It does not, and
    /// leaves the mesh as it is, when a domain triangle (not a ghost, not tagged outside)
    /// would invert or flatten.
    pub fn move_onto_grid(&mut self, grid: &dyn Grid) -> bool {
        let mesh = self.inserter.mesh();
        let on_grid: Vec<Point> = mesh.points().iter().map(|&p| grid.round(p)).collect();
        let moved: Vec<VertexId> = (0..on_grid.len())
            .filter(|&i| on_grid[i] != mesh.points()[i])
            .map(|i| VertexId::new(i as u32))
            .collect();
        if moved.is_empty() {
            return true;
        }
        let at = |v: VertexId| on_grid[v.index()];
        for t in mesh.triangles() {
            let corners = mesh.triangle(t);
            if corners.contains(&GHOST)
                || (mesh.tracks_tags() && mesh.tag(t) == OUTSIDE)
                || corners.iter().all(|&v| at(v) == mesh.point(v))
            {
                continue;
            }
            let [a, b, c] = corners.map(at);
            if P::orient2d(a, b, c) <= 0.0 {
                return false;
            }
        }
        self.inserter.mesh_mut().replace_points(on_grid);
        // Lawson flips (no segment is flipped): exactly Delaunay again with the moved vertices.
        // A moved vertex changes the circumcircles of the triangles around it, so both its
        // edges and the edges of its link are checked (as `move_vertex` does): its edges alone
        // missed a link edge between two vertices that stayed, which the move put a vertex
        // just inside the circle of (a random equilateral triangle with `pa0.02S14`, whose
        // budget ends refinement before any later split could flip it).
        let mesh = self.inserter.mesh();
        let mut edges = Vec::new();
        for v in moved {
            for e in mesh.star(v) {
                let (a, b) = (mesh.dest(e), mesh.apex(e));
                if a != GHOST {
                    edges.push((v, a));
                    if b != GHOST {
                        edges.push((a, b));
                    }
                }
            }
        }
        self.restore_delaunay(edges);
        true
    }

    /// Moves vertex `v` to `p` if each of its real triangles stays strictly counter-clockwise
    /// there (`p` in the kernel of its star; beside the vertex at infinity, the caller keeps the
    /// boundary where it was, as a vertex moved along a hull segment does), and restores the
    /// constrained Delaunay property by flips from its star and link; returns whether it moved.
    pub fn move_vertex(&mut self, v: VertexId, p: Point) -> bool {
        self.shift_vertex::<true>(v, p)
    }

    /// [`Self::move_vertex`] where the caller has checked that `p` is in the kernel of `v`'s
    /// star: every triangle `(p, a, b)` over its link, `a` and `b` not the vertex at infinity,
    /// has `orient2d` positive (the improvement's search checks each place it tries so).
    pub fn move_vertex_in_kernel(&mut self, v: VertexId, p: Point) {
        let moved = self.shift_vertex::<{ cfg!(debug_assertions) }>(v, p);
        debug_assert!(moved, "{p:?} is not in the kernel of {v}'s star");
    }

    /// [`Self::move_vertex`], which checks the kernel only with `CHECK`.
    #[inline(always)]
    fn shift_vertex<const CHECK: bool>(&mut self, v: VertexId, p: Point) -> bool {
        let mut edges = self.take_lawson_stack();
        let mesh = self.inserter.mesh();
        for e in mesh.star(v) {
            let (a, b) = (mesh.dest(e), mesh.apex(e));
            if a == GHOST || b == GHOST {
                continue;
            }
            if CHECK && P::orient2d(p, mesh.point(a), mesh.point(b)) <= 0.0 {
                self.scratch.lawson = edges;
                return false;
            }
            edges.push((v, a, e));
            edges.push((a, b, e.next()));
        }
        self.inserter.mesh_mut().move_point(v, p);
        self.legalize_stack(edges);
        true
    }

    /// Moves vertex `v`, inside the domain on no segment, to `p` (a point of its region): as
    /// [`Self::move_vertex`] where `p` is in its star's kernel, else by deleting it and
    /// inserting it again at `p`. Returns whether it is at `p` (it stays where it was when it
    /// cannot be deleted, or `p` is another vertex's point).
    pub fn place_vertex(&mut self, v: VertexId, p: Point) -> bool {
        if self.move_vertex(v, p) {
            return true;
        }
        let from = self.inserter.mesh().point(v);
        let Some(made) = self.delete_vertex(v) else {
            return false;
        };
        for q in [p, from] {
            self.inserter.mesh_mut().move_point(v, q);
            let location = self.inserter.locate_thoroughly(q, made[0]);
            if self.inserter.insert_at(v, location).is_ok() {
                return q == p;
            }
        }
        false
    }
}
