//! The driver: checks the input, runs the algorithms that the options ask for and assembles the
//! [`Output`] and [`VoronoiOutput`].

use crate::assemble::FinishedMesh;
use crate::data::{Hooks, Input, Output, VoronoiOutput};
use crate::delaunay::{self, merge, order, Triangulation};
use crate::error::Error;
use crate::geometry::{Exact, Inexact, Point, Predicates};
use crate::mesh::{triangle_of, NONE};
use crate::options::{Algorithm, Options};
use crate::voronoi::voronoi_diagram;

/// Seed of the randomized insertion order (`i`): fixed, so results are reproducible.
const BRIO_SEED: u64 = 0x7269_616E_676C_6521;

/// Rejects the switches whose features have not landed yet, with a clear message.
fn check_supported(options: &Options) -> Result<(), Error> {
    let unsupported = [
        (options.pslg, "The `p` switch (planar straight line graphs)"),
        (options.refine, "The `r` switch (refining a mesh)"),
        (options.min_angle.is_some(), "The `q` switch (quality meshing)"),
        (options.max_area.is_some() || options.variable_area, "The `a` switch (area constraints)"),
        (options.user_test, "The `u` switch (user refinement test)"),
        (options.conforming_delaunay, "The `D` switch (conforming Delaunay)"),
        (options.second_order, "The `o2` switch (second-order triangles)"),
        (options.split_segments, "The `s` switch (segment splitting)"),
        (options.weighted != 0, "The `w`/`W` switches (weighted triangulation)"),
    ];
    match unsupported.iter().find(|(on, _)| *on) {
        Some((_, what)) => Err(Error::Unsupported(what)),
        None => Ok(()),
    }
}

/// Checks the parts of the input that every run reads and collects the points.
fn checked_points(input: &Input<'_>) -> Result<Vec<Point>, Error> {
    let n = input.point_count();
    if n < 3 {
        return Err(Error::TooFewPoints);
    }
    if input.point_attributes.len() != n * input.point_attribute_count {
        return Err(Error::BadCount { field: "numberofpointattributes", value: input.point_attribute_count as i64 });
    }
    let points: Vec<Point> = input.points.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    if let Some(i) = points.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return Err(Error::NonFinite { what: "Vertex", index: i });
    }
    Ok(points)
}

fn delaunay_triangulation(options: &Options, points: Vec<Point>) -> Triangulation {
    if options.no_exact {
        delaunay_with::<Inexact>(options, points)
    } else {
        delaunay_with::<Exact>(options, points)
    }
}

fn delaunay_with<P: Predicates>(options: &Options, mut points: Vec<Point>) -> Triangulation {
    match options.algorithm {
        Algorithm::Incremental => {
            let order = order::brio_order(&points, BRIO_SEED);
            delaunay::triangulate::<P>(points, &order)
        }
        Algorithm::Default | Algorithm::Sweepline => {
            let two_cores = std::thread::available_parallelism().is_ok_and(|n| n.get() >= 2);
            if two_cores && points.len() >= merge::PARALLEL_THRESHOLD {
                match merge::triangulate_two_halves::<P>(points) {
                    Ok(triangulation) => return triangulation,
                    Err(given_back) => points = given_back,
                }
            }
            let order = order::hilbert_order(&points);
            delaunay::triangulate::<P>(points, &order)
        }
    }
}

/// Triangulates `input` as the switches in `options` ask. The safe entry point of the engine:
/// the C ABI, the command-line program and Rust callers all come through here.
pub fn triangulate(options: &Options, input: &Input<'_>, _hooks: &Hooks<'_>) -> Result<(Output, VoronoiOutput), Error> {
    check_supported(options)?;
    let points = checked_points(input)?;
    let n = points.len();
    let triangulation = delaunay_triangulation(options, points);

    let mut output = Output::default();
    let base = options.first_index();
    for (v, &u) in triangulation.duplicate_of.iter().enumerate() {
        if u != NONE {
            let p = triangulation.mesh.points[v];
            output.warnings.push(format!(
                "A duplicate vertex at ({}, {}) appeared and was ignored (vertex {} duplicates vertex {}).",
                p[0],
                p[1],
                v as i32 + base,
                u as i32 + base
            ));
        }
    }
    let vertex_in_mesh: Vec<bool> = if triangulation.is_degenerate() {
        vec![false; n]
    } else {
        triangulation.duplicate_of.iter().map(|&u| u == NONE).collect()
    };
    let mesh = &triangulation.mesh;
    let triangle_in_mesh: Vec<bool> = (0..mesh.triangle_count()).map(|t| !mesh.is_ghost(t)).collect();
    // With `c` the hull edges are segments with marker 1, as Triangle's convex hull segments.
    let hull_segment = |e: u32| (!triangle_in_mesh[triangle_of(mesh.twin(e)) as usize]).then_some(1);
    let finished = FinishedMesh {
        mesh,
        point_attributes: input.point_attributes,
        point_attribute_count: input.point_attribute_count,
        input_point_markers: input.point_markers,
        vertex_in_mesh: &vertex_in_mesh,
        triangle_in_mesh: &triangle_in_mesh,
        segment_marker: if options.convex_hull { Some(&hull_segment) } else { None },
        uses_segments: options.uses_segments(),
    };
    let numbering = finished.numbering(options.jettison);
    finished.write(options, &numbering, &mut output);

    let mut voronoi = VoronoiOutput {
        point_count: output.triangle_count,
        point_attribute_count: input.point_attribute_count,
        edge_count: output.edge_count,
        diagram: None,
    };
    if options.voronoi {
        voronoi.diagram = Some(voronoi_diagram(&finished, &numbering, base));
    }
    Ok((output, voronoi))
}
