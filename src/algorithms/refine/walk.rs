//! The straight walk from a bad triangle toward its split point, staying in the domain: it tells
//! where the point lies, or which segment hides it from the triangle (Ruppert's rule then splits
//! that segment instead).

use super::inside;
use crate::algorithms::delaunay::Location;
use crate::geometry::{Point, Predicates};
use crate::mesh::{EdgeId, Mesh, TriangleId};

/// Where the straight walk from a bad triangle toward its new point ends.
pub(super) enum Walk {
    /// The point lies in (or on the boundary of) the domain at this location.
    Found(Location),
    /// A segment (this half-edge) separates the point from the triangle.
    Blocked(EdgeId),
    /// The point lies outside the domain (or the walk could not settle).
    Lost,
}

/// Walks in a straight line from the centroid of triangle `t` to `x`, staying in the domain.
pub(super) fn walk<P: Predicates>(mesh: &Mesh, t: TriangleId, x: Point) -> Walk {
    let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
    let g = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
    let mut t = t;
    let mut entry = EdgeId::NONE;
    for _ in 0..mesh.triangle_count() + 3 {
        // The edge through which the ray g→x leaves t (u right of the ray, v left of it).
        let mut exit = EdgeId::NONE;
        for e in t.edges() {
            if e == entry {
                continue;
            }
            let (u, v) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
            if P::orient2d(g, x, u) <= 0.0 && P::orient2d(g, x, v) > 0.0 {
                exit = e;
                break;
            }
        }
        if exit == EdgeId::NONE {
            // No edge crosses the ray: it is too short to have a direction (x is the centroid,
            // as for an equilateral triangle's circumcentre), or degenerate.
            return walk_ends_in::<P>(mesh, t, x).unwrap_or(Walk::Lost);
        }
        let (u, v) = (mesh.point(mesh.origin(exit)), mesh.point(mesh.dest(exit)));
        let side = P::orient2d(u, v, x);
        if side > 0.0 {
            return Walk::Found(Location::InTriangle(t));
        }
        if side == 0.0 {
            // On the exit edge (or its line beyond the triangle, which the ray rules out).
            if mesh.is_segment(exit) {
                return Walk::Blocked(exit);
            }
            for w in [mesh.origin(exit), mesh.dest(exit)] {
                if mesh.point(w) == x {
                    return Walk::Found(Location::OnVertex(w));
                }
            }
            return Walk::Found(Location::OnEdge(exit));
        }
        if mesh.is_segment(exit) {
            return Walk::Blocked(exit);
        }
        let f = mesh.twin(exit);
        let next_t = f.triangle();
        if !inside(mesh, next_t) || mesh.is_ghost(next_t) {
            return Walk::Lost;
        }
        t = next_t;
        entry = f;
    }
    Walk::Lost
}

/// Where `x` lies in triangle `t`, if it lies in it (closed): in it, on an edge (a segment hides
/// nothing then, but a point on a segment splits it: `Blocked`), or on a vertex.
fn walk_ends_in<P: Predicates>(mesh: &Mesh, t: TriangleId, x: Point) -> Option<Walk> {
    let sides = t
        .edges()
        .map(|e| P::orient2d(mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)), x));
    if sides.iter().any(|&side| side < 0.0) {
        return None;
    }
    let on: Vec<EdgeId> = (0..3)
        .filter(|&i| sides[i as usize] == 0.0)
        .map(|i| t.edge(i))
        .collect();
    Some(match on[..] {
        [] => Walk::Found(Location::InTriangle(t)),
        [e] if mesh.is_segment(e) => Walk::Blocked(e),
        [e] => Walk::Found(Location::OnEdge(e)),
        // On two edges: at their common corner.
        _ => mesh
            .triangle(t)
            .into_iter()
            .find(|&w| mesh.point(w) == x)
            .map_or(Walk::Lost, |w| Walk::Found(Location::OnVertex(w))),
    })
}
