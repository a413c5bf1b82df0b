//! The Voronoi diagram as the dual of the triangulation: one vertex per triangle (its
//! circumcentre), one edge per triangulation edge, and a ray for each boundary edge.
//!
//! As in Triangle, the diagram is meaningful only for a true Delaunay triangulation; vertex
//! attributes are interpolated linearly at the circumcentres (extrapolated when the centre lies
//! outside its triangle).

use crate::assemble::{FinishedMesh, Numbering};
use crate::data::VoronoiDiagram;
use crate::geometry::circumcenter;
use crate::mesh::{triangle_of, NONE};

pub fn voronoi_diagram(
    finished: &FinishedMesh<'_>,
    numbering: &Numbering,
    base: i32,
) -> VoronoiDiagram {
    let mesh = finished.mesh;
    let k = finished.point_attribute_count;
    let attrs = |v: u32| &finished.point_attributes[v as usize * k..v as usize * k + k];
    let mut points = Vec::with_capacity(2 * numbering.triangles.len());
    let mut point_attributes = Vec::with_capacity(k * numbering.triangles.len());
    for &t in &numbering.triangles {
        let [o, d, a] = mesh.triangle(t);
        let (centre, xi, eta) = circumcenter(mesh.point(o), mesh.point(d), mesh.point(a));
        points.extend_from_slice(&centre);
        let (ao, ad, aa) = (attrs(o), attrs(d), attrs(a));
        point_attributes
            .extend((0..k).map(|i| ao[i] + xi * (ad[i] - ao[i]) + eta * (aa[i] - ao[i])));
    }
    let mut edges = Vec::with_capacity(2 * numbering.edges.len());
    let mut norms = Vec::with_capacity(2 * numbering.edges.len());
    for &e in &numbering.edges {
        let here = numbering.triangle[triangle_of(e) as usize] as i32 + base;
        let there = numbering.triangle[triangle_of(mesh.twin(e)) as usize];
        if there != NONE {
            edges.extend_from_slice(&[here, there as i32 + base]);
            norms.extend_from_slice(&[0.0, 0.0]);
        } else {
            // A ray from the circumcentre, outward across the boundary edge (the right-hand
            // normal of the edge, whose triangle lies on its left).
            let (p, q) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
            edges.extend_from_slice(&[here, -1]);
            norms.extend_from_slice(&[q[1] - p[1], p[0] - q[0]]);
        }
    }
    VoronoiDiagram {
        points,
        point_attributes,
        edges,
        norms,
    }
}
