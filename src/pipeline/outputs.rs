//! The outputs of the finished mesh (numbering, markers, Voronoi) in the caller's units.

use super::Meshed;
use crate::algorithms::voronoi::{voronoi_diagram, DualOf};
use crate::assemble::{FinishedMesh, Numbering};
use crate::data::{Input, Output, VoronoiOutput};
use crate::error::Error;
use crate::mesh::{TriangleId, GHOST, NONE, OUTSIDE};
use crate::options::Options;
use crate::scaling::Scaling;

pub(super) fn write_outputs(
    options: &Options,
    input: &Input<'_>,
    mut meshed: Meshed,
    mut output: Output,
    scaling: Scaling,
) -> Result<(Output, VoronoiOutput), Error> {
    let mesh = &meshed.mesh;
    // With no triangle at all (all points on a line) no vertex is left out, as in Triangle.
    let all_collinear = mesh.triangle_count() == 0 && !meshed.uses_segments;
    let triangle_in_mesh: Vec<bool> = mesh.tags().iter().map(|&tag| tag != OUTSIDE).collect();
    // Only `j` asks which vertices are corners of output triangles.
    let mut vertex_in_mesh = Vec::new();
    if options.jettison {
        vertex_in_mesh = vec![all_collinear; mesh.vertex_count() as usize];
        for (t, &inside) in triangle_in_mesh.iter().enumerate() {
            if inside {
                for v in mesh.triangle(TriangleId::new(t as u32)) {
                    if v != GHOST {
                        vertex_in_mesh[v.index()] = true;
                    }
                }
            }
        }
    }
    // `r` with six-node triangles: as in Triangle, the input's mid-edge nodes (listed only after
    // the three corners) are left out of the output, with or without `j`.
    let mut jettison = options.jettison;
    if options.refine && input.corners > 3 && !options.jettison {
        let base = i64::from(options.first_index());
        let n = mesh.vertex_count() as usize;
        let mut mid_node_only = vec![false; n];
        let index = |v: i32| usize::try_from(i64::from(v) - base).ok().filter(|&i| i < n);
        for t in input.triangles.chunks_exact(input.corners) {
            for &v in &t[3..] {
                if let Some(i) = index(v) {
                    mid_node_only[i] = true;
                }
            }
        }
        for t in input.triangles.chunks_exact(input.corners) {
            for &v in &t[..3] {
                if let Some(i) = index(v) {
                    mid_node_only[i] = false;
                }
            }
        }
        if mid_node_only.contains(&true) {
            jettison = true;
            // With `jettison` set, `vertex_in_mesh` says which vertices are kept.
            vertex_in_mesh = mid_node_only.iter().map(|&mid| !mid).collect();
        }
    }
    // The output points are the mesh's own, moved out once nothing reads them any more (a copy
    // would touch as many fresh pages again), unless some are left out, scaled back or followed
    // by `o2`'s mid-edge nodes.
    let move_points = scaling.is_identity()
        && !options.output.no_node_output
        && !jettison
        && !options.second_order;
    let finished = FinishedMesh {
        mesh,
        points_moved_in_later: move_points,
        point_attributes: &meshed.point_attributes,
        point_attribute_count: input.point_attribute_count,
        input_point_markers: &meshed.point_markers,
        all_collinear,
        vertex_in_mesh: &vertex_in_mesh,
        triangle_in_mesh: &triangle_in_mesh,
        segment_markers: mesh
            .tracks_segments()
            .then_some(&meshed.segment_markers[..]),
        later_copies: &meshed.later_copies,
        uses_segments: meshed.uses_segments,
    };
    let numbering = finished.numbering(options, jettison);
    finished.write(options, &numbering, &mut output);
    // Triangle attributes: with `r` the input triangles' (inherited by their pieces), with `A`
    // (and regions) the region's (0 outside every region).
    let domain = &meshed.domain;
    // `A` without regions: a column of zeros, as Triangle's manual says (Triangle itself
    // writes no column then).
    if (options.refine || options.region_attributes) && domain.attribute_count > 0 {
        let attributes = numbering
            .triangles
            .iter()
            .flat_map(|&t| domain.attributes_of(mesh.tags()[t as usize]))
            .copied()
            .collect();
        output.triangle_attribute_count = domain.attribute_count;
        output.triangle_attributes = (!options.output.no_element_output).then_some(attributes);
    }
    let base = options.first_index();
    let mut voronoi = VoronoiOutput {
        point_count: output.triangle_count,
        point_attribute_count: input.point_attribute_count,
        edge_count: output.edge_count,
        diagram: None,
    };
    if options.output.voronoi {
        let dual = DualOf {
            triangles: &numbering.triangles,
            triangle_index: &numbering.triangle,
            edges: &numbering.edges,
            point_attributes: finished.point_attributes,
            point_attribute_count: finished.point_attribute_count,
            base,
        };
        voronoi.diagram = Some(voronoi_diagram(finished.mesh, &dual));
    }
    if !scaling.is_identity() {
        unscale_outputs(scaling, input.points, &numbering, &mut output, &mut voronoi);
    }
    if move_points {
        output.points = Some(meshed.mesh.take_points().into_flattened());
    }
    Ok((output, voronoi))
}

/// Gives the outputs back in the caller's units: input vertices as the caller gave them, bit for
/// bit, new vertices (exact: they are on the caller's grid, see [`super::grid`]), Voronoi
/// points (rounded) and ray directions (scaled back only).
fn unscale_outputs(
    scaling: Scaling,
    caller_points: &[f64],
    numbering: &Numbering,
    output: &mut Output,
    voronoi: &mut VoronoiOutput,
) {
    let to_caller = |xy: &mut [f64]| {
        let [x, y] = scaling.to_caller([xy[0], xy[1]]);
        xy.copy_from_slice(&[x, y]);
    };
    if let Some(points) = output.points.as_mut() {
        points.chunks_exact_mut(2).for_each(to_caller);
        let n = caller_points.len() / 2;
        for v in 0..n {
            let i = numbering.vertex_index(v as u32);
            if i != NONE {
                let i = i as usize;
                points[2 * i..2 * i + 2].copy_from_slice(&caller_points[2 * v..2 * v + 2]);
            }
        }
    }
    if let Some(diagram) = voronoi.diagram.as_mut() {
        diagram.points.chunks_exact_mut(2).for_each(to_caller);
        for x in diagram.norms.iter_mut() {
            *x = scaling.unscale(*x);
        }
    }
}
