//! Vertices moved onto a grid: the points that the caller's coordinates can hold.
//!
//! The engine may mesh in a frame of its own (translated to a local origin and scaled, see
//! `crate::scaling`), where a new vertex can have coordinates that the caller's doubles cannot
//! hold; given back rounded, it would make the caller's mesh another one than the engine
//! checked. So before the outputs every vertex is moved, in the engine's frame, to the point
//! the caller will receive, the mesh is checked with those coordinates and made Delaunay again
//! by Lawson flips: what the caller gets is exactly what the engine checked. Rounding moves a
//! vertex by half a unit in the last place of the caller's coordinates, far below the features
//! of a mesh whose vertices are more than a few units apart. Where they are not (a domain
//! thinner than its coordinates' rounding), the move changes the shape of some triangle by more
//! than [`LARGEST_SHAPE_CHANGE`] and is not made.

use super::*;
use crate::mesh::OUTSIDE;

/// The largest relative change of a triangle's area that moving its corners onto the grid may
/// make: only a triangle within some four units in the last place of flat changes more, so
/// beyond it the mesh would no longer be the one the engine made (a domain thinner than its
/// rounding would widen or narrow by a large fraction).
pub const LARGEST_SHAPE_CHANGE: f64 = 1.0 / 8.0;

impl<P: Predicates> Constrainer<P> {
    /// Moves every vertex `v` to `grid(v)` (see the module documentation) and restores the
    /// constrained Delaunay property by flips; returns whether it did. It does not, and leaves
    /// the mesh as it is, when a domain triangle (not a ghost, not tagged outside) would
    /// invert or change its area by more than [`LARGEST_SHAPE_CHANGE`].
    pub fn move_onto_grid(&mut self, grid: &dyn Fn(Point) -> Point) -> bool {
        let mesh = self.inserter.mesh();
        let on_grid: Vec<Point> = mesh.points().iter().map(|&p| grid(p)).collect();
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
            let [a, b, c] = corners.map(|v| mesh.point(v));
            let [ma, mb, mc] = corners.map(at);
            let (area, after) = (P::orient2d(a, b, c), P::orient2d(ma, mb, mc));
            if after <= 0.0 || (after - area).abs() > LARGEST_SHAPE_CHANGE * area {
                return false;
            }
        }
        self.inserter.mesh_mut().replace_points(on_grid);
        // Lawson flips (no segment is flipped): exactly Delaunay again with the moved vertices.
        for v in moved {
            self.settle(v);
        }
        true
    }
}
