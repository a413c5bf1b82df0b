//! From a finished mesh to Triangle's outputs: numbering (1-based unless `z`, `j` renumbering),
//! boundary markers, triangles, neighbours, segments and edges, in the flat layouts of
//! [`Output`].
//!
//! Marker rules (Triangle's documentation): a vertex gets its input marker if non-zero, else the
//! marker of a non-zero segment it lies on, else 1 on a boundary, else 0; a segment or edge gets its
//! segment's marker, else 1 on a boundary, else 0.

use crate::data::Output;
use crate::mesh::{triangle_of, Mesh, NONE};
use crate::options::Options;

/// A finished mesh with the per-vertex and per-edge facts the outputs need.
pub struct FinishedMesh<'a> {
    pub mesh: &'a Mesh,
    /// `point_attribute_count` values per vertex.
    pub point_attributes: &'a [f64],
    pub point_attribute_count: usize,
    /// The caller's marker per vertex (0 where none was given).
    pub input_point_markers: &'a [i32],
    /// Per vertex: whether it is a vertex of the mesh (duplicates are not; `j` drops them).
    pub vertex_in_mesh: &'a [bool],
    /// Whether the triangle in a slot is part of the output (real and not deleted).
    pub triangle_in_mesh: &'a dyn Fn(u32) -> bool,
    /// The marker of the segment along half-edge `e`, if `e` is (part of) a segment.
    pub segment_marker: &'a dyn Fn(u32) -> Option<i32>,
    /// Whether the mesh has segments at all (Triangle's `usesegments`); without them, hull edges
    /// are the boundary and `numberofsegments` counts them.
    pub uses_segments: bool,
}

/// Output numbering of vertices and triangles.
pub struct Numbering {
    /// Per vertex: its output index (0-based), or [`NONE`] when jettisoned.
    pub vertex: Vec<u32>,
    /// Per triangle slot: its output index (0-based), or [`NONE`].
    pub triangle: Vec<u32>,
    /// Output triangles in order (slot indices).
    pub triangles: Vec<u32>,
    pub vertex_count: usize,
}

impl FinishedMesh<'_> {
    fn is_boundary(&self, e: u32) -> bool {
        !(self.triangle_in_mesh)(triangle_of(self.mesh.twin(e)))
    }

    /// Output half-edges, each undirected edge once: the half-edge of an output triangle whose
    /// twin is outside the mesh or has a larger index.
    pub fn edges(&self, numbering: &Numbering) -> Vec<u32> {
        let mut edges = Vec::with_capacity(numbering.triangles.len() * 3 / 2 + 8);
        for &t in &numbering.triangles {
            for e in 3 * t..3 * t + 3 {
                let f = self.mesh.twin(e);
                if e < f || self.is_boundary(e) {
                    edges.push(e);
                }
            }
        }
        edges
    }

    pub fn numbering(&self, jettison: bool) -> Numbering {
        let mut triangle = vec![NONE; self.mesh.triangle_count() as usize];
        let mut triangles = Vec::with_capacity(self.mesh.triangle_count() as usize);
        for t in 0..self.mesh.triangle_count() {
            if (self.triangle_in_mesh)(t) {
                triangle[t as usize] = triangles.len() as u32;
                triangles.push(t);
            }
        }
        let mut vertex = vec![NONE; self.mesh.points.len()];
        let mut count = 0u32;
        for (v, slot) in vertex.iter_mut().enumerate() {
            if !jettison || self.vertex_in_mesh[v] {
                *slot = count;
                count += 1;
            }
        }
        Numbering { vertex, triangle, triangles, vertex_count: count as usize }
    }

    /// Final vertex markers: input marker, else a non-zero segment's, else 1 on the boundary.
    fn vertex_markers(&self, numbering: &Numbering) -> Vec<i32> {
        let n = self.mesh.points.len();
        let mut from_segment = vec![0i32; n];
        let mut on_boundary = vec![false; n];
        for &t in &numbering.triangles {
            for e in 3 * t..3 * t + 3 {
                let (a, b) = (self.mesh.origin(e) as usize, self.mesh.dest(e) as usize);
                if let Some(m) = (self.segment_marker)(e) {
                    if m != 0 {
                        from_segment[a] = if from_segment[a] == 0 { m } else { from_segment[a] };
                        from_segment[b] = if from_segment[b] == 0 { m } else { from_segment[b] };
                    }
                }
                if self.is_boundary(e) {
                    on_boundary[a] = true;
                    on_boundary[b] = true;
                }
            }
        }
        (0..n)
            .map(|v| {
                if !self.vertex_in_mesh[v] {
                    0
                } else if self.input_point_markers[v] != 0 {
                    self.input_point_markers[v]
                } else if from_segment[v] != 0 {
                    from_segment[v]
                } else {
                    i32::from(on_boundary[v])
                }
            })
            .collect()
    }

    fn edge_marker(&self, e: u32) -> i32 {
        match (self.segment_marker)(e) {
            Some(m) if m != 0 => m,
            _ => i32::from(self.is_boundary(e)),
        }
    }

    /// Fills the output arrays that the options ask for.
    pub fn write(&self, options: &Options, numbering: &Numbering, output: &mut Output) {
        let base = options.first_index();
        let vid = |v: u32| numbering.vertex[v as usize] as i32 + base;
        let markers = !options.no_boundary_markers;

        output.point_count = numbering.vertex_count;
        output.point_attribute_count = self.point_attribute_count;
        if !options.no_node_output {
            let kept = |v: &usize| numbering.vertex[*v] != NONE;
            let n = self.mesh.points.len();
            output.points = Some((0..n).filter(kept).flat_map(|v| self.mesh.points[v]).collect());
            if self.point_attribute_count > 0 {
                let k = self.point_attribute_count;
                output.point_attributes =
                    Some((0..n).filter(kept).flat_map(|v| &self.point_attributes[v * k..v * k + k]).copied().collect());
            }
            if markers {
                let all = self.vertex_markers(numbering);
                output.point_markers = Some((0..n).filter(kept).map(|v| all[v]).collect());
            }
        }

        output.triangle_count = numbering.triangles.len();
        output.corners = 3;
        if !options.no_element_output {
            let mut tris = Vec::with_capacity(3 * numbering.triangles.len());
            for &t in &numbering.triangles {
                tris.extend(self.mesh.triangle(t).map(vid));
            }
            output.triangles = Some(tris);
        }
        if options.neighbors {
            // Neighbour i lies opposite corner i, across the half-edge from corner i+1 to i+2.
            let mut neighbors = Vec::with_capacity(3 * numbering.triangles.len());
            for &t in &numbering.triangles {
                for i in 0..3 {
                    let e = 3 * t + (i + 1) % 3;
                    let other = numbering.triangle[triangle_of(self.mesh.twin(e)) as usize];
                    neighbors.push(if other == NONE { -1 } else { other as i32 + base });
                }
            }
            output.neighbors = Some(neighbors);
        }

        let edges = self.edges(numbering);
        output.edge_count = edges.len();
        if options.edges {
            output.edges = Some(edges.iter().flat_map(|&e| [vid(self.mesh.origin(e)), vid(self.mesh.dest(e))]).collect());
            if markers {
                output.edge_markers = Some(edges.iter().map(|&e| self.edge_marker(e)).collect());
            }
        }

        // Segments: the subsegments of the mesh, or (without segments) the hull edges, which
        // Triangle counts although it writes no list.
        let segments: Vec<u32> = if self.uses_segments {
            edges.iter().copied().filter(|&e| (self.segment_marker)(e).is_some()).collect()
        } else {
            edges.iter().copied().filter(|&e| self.is_boundary(e)).collect()
        };
        output.segment_count = segments.len();
        if self.uses_segments && (options.pslg || options.convex_hull) && !options.no_poly_output {
            // Written from the outside, as Triangle writes hull segments.
            output.segments = Some(
                segments
                    .iter()
                    .flat_map(|&e| [vid(self.mesh.dest(e)), vid(self.mesh.origin(e))])
                    .collect(),
            );
            if markers {
                output.segment_markers = Some(segments.iter().map(|&e| self.edge_marker(e)).collect());
            }
        }
    }
}
