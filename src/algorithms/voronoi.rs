//! The Voronoi diagram as the dual of the triangulation: one vertex per triangle (its
//! circumcentre), one edge per triangulation edge, and a ray for each boundary edge.
//!
//! As in Triangle, the diagram is meaningful only for a true Delaunay triangulation; vertex
//! attributes are interpolated linearly at the circumcentres (extrapolated when the centre lies
//! outside its triangle).

use crate::data::VoronoiDiagram;
use crate::geometry::circumcenter;
use crate::mesh::raw::triangle_of;
use crate::mesh::{Mesh, NONE};

/// Which triangles and edges of a mesh the diagram is the dual of, in the output's order (the
/// numbering is the output assembly's: the diagram's vertices are numbered as the triangles).
pub struct DualOf<'a> {
    /// Output triangles in order (triangle slots).
    pub triangles: &'a [u32],
    /// Per triangle slot: its output index (0-based), or [`NONE`] when it is not output.
    pub triangle_index: &'a [u32],
    /// Output edges in order (one half-edge each, of an output triangle).
    pub edges: &'a [u32],
    /// `point_attribute_count` values per vertex, interpolated at the circumcentres.
    pub point_attributes: &'a [f64],
    pub point_attribute_count: usize,
    /// The numbering base of the output (0 or 1).
    pub base: i32,
}

pub fn voronoi_diagram(mesh: &Mesh, dual: &DualOf<'_>) -> VoronoiDiagram {
    let mesh = mesh.raw(); // the dual's lists are in the output's raw numbering
    let (k, base) = (dual.point_attribute_count, dual.base);
    let attrs = |v: u32| &dual.point_attributes[v as usize * k..v as usize * k + k];
    let mut points = Vec::with_capacity(2 * dual.triangles.len());
    let mut point_attributes = Vec::with_capacity(k * dual.triangles.len());
    for &t in dual.triangles {
        let [o, d, a] = mesh.triangle(t);
        let (centre, xi, eta) = circumcenter(mesh.point(o), mesh.point(d), mesh.point(a));
        points.extend_from_slice(&centre);
        let (ao, ad, aa) = (attrs(o), attrs(d), attrs(a));
        point_attributes
            .extend((0..k).map(|i| ao[i] + xi * (ad[i] - ao[i]) + eta * (aa[i] - ao[i])));
    }
    let mut edges = Vec::with_capacity(2 * dual.edges.len());
    let mut norms = Vec::with_capacity(2 * dual.edges.len());
    for &e in dual.edges {
        let here = dual.triangle_index[triangle_of(e) as usize] as i32 + base;
        let there = dual.triangle_index[triangle_of(mesh.twin(e)) as usize];
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
