//! Differential tests of the constrained Delaunay triangulation (`p`) against Debian's Triangle
//! 1.6 (`/usr/lib/libtriangle-1.6.so`), on the classic shapes of tests/data/shapes/ and on random
//! PSLGs, with `p`, `pc`, `pA`, `pj`, `pe`, `pn`, `pO`, `pz` and combinations: the same counts,
//! the same arrays written, the same vertices (new vertices at crossings matched with a small
//! tolerance), the same triangles where the CDT is unique (exact cocircularity detected with
//! `incircle`), the same segments and edges with markers, the same markers on the vertices of
//! the mesh, the same region attribute per triangle.
//!
//! Duplicate vertices referenced by segments are not compared: Triangle has undefined behaviour
//! on them (pslg_properties.rs checks ours). Without the reference library these tests print a
//! skip message, and fail in CI.

mod common;

use std::process::Command;

use common::checks::without_zero_region_column;
use common::examples;
use common::pslg::{self, Pslg};
use common::pslg_checks::{
    bypasses_a_vertex, check_constrained_delaunay, pslg_differences, MeshView,
};
use common::{ours, reference, MeshInput};

const SWITCH_SETS: &[&str] = &[
    "pQ", "pzQ", "pcQ", "pAQ", "pjQ", "peQ", "pnQ", "pOQ", "pzAjenQ", "pcAeQ", "pOAzQ",
];

/// Ours and Triangle's on `pslg` with each of `switch_sets` must not differ.
fn compare(pslg: &Pslg, switch_sets: &[&str]) {
    let Some(triangle) = reference() else { return };
    assert!(
        !pslg.ours_only,
        "{}: Triangle has undefined behaviour on this input",
        pslg.name
    );
    for switches in switch_sets {
        let input = pslg.input_for(switches);
        let theirs = triangle.triangulate(switches, &input);
        let ours =
            ours(switches, &input).unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", pslg.name));
        let theirs_view =
            MeshView::of(&theirs).unwrap_or_else(|e| panic!("{}: Triangle's: {e}", pslg.name));
        let ours_view =
            MeshView::of(&ours).unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", pslg.name));
        if bypasses_a_vertex(&pslg.input, &theirs_view)
            && !bypasses_a_vertex(&pslg.input, &ours_view)
        {
            // Triangle misses a vertex lying on a segment beyond a crossing (its rounded crossing
            // point bends the rest of the segment past the vertex); ours splits the segment there
            // and is checked on its own.
            check_constrained_delaunay(&ours_view)
                .unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", pslg.name));
            continue;
        }
        let ours = without_zero_region_column(&ours, switches, input.regions.len());
        let diffs = pslg_differences(&input, &ours, &theirs);
        assert!(
            diffs.is_empty(),
            "{}, \"{switches}\": ours differs from Triangle's:\n  {}",
            pslg.name,
            diffs.join("\n  ")
        );
    }
}

/// Triangle's own example files (read from the PyPI `triangle` package's data directory): every
/// `.poly` with its vertices, and the segments of the shipped meshes' `.poly` files with their
/// `.node` vertices.
#[test]
fn triangle_example_files_match() {
    let mut compared = 0;
    for file in examples::example_files(&examples::data_dir()) {
        let input = match file.kind {
            examples::Kind::Poly => file.input,
            examples::Kind::Mesh { .. } if !file.input.segments.is_empty() => MeshInput {
                triangles: Vec::new(),
                triangle_attributes: Vec::new(),
                triangle_attribute_count: 0,
                triangle_areas: None,
                ..file.input
            },
            _ => continue,
        };
        compare(&Pslg::new(file.name, input), SWITCH_SETS);
        compared += 1;
    }
    assert!(compared >= 10, "only {compared} example files compared");
}

#[test]
fn classic_shapes_match() {
    for name in pslg::SHAPES {
        compare(&pslg::shape(name), SWITCH_SETS);
    }
}

/// The comparison is not vacuous: the shapes give triangles, and where the CDT is unique it is
/// compared triangle by triangle (box_in_box has cocircular regions; the others none).
#[test]
fn classic_shapes_are_mostly_unique() {
    let Some(triangle) = reference() else { return };
    for name in pslg::SHAPES {
        let shape = pslg::shape(name);
        let theirs = triangle.triangulate("pQ", &shape.input_for("pQ"));
        let view = MeshView::of(&theirs).unwrap_or_else(|e| panic!("{name}, Triangle's mesh: {e}"));
        let cocircular = view.cocircular_edges();
        assert!(
            view.triangles.len() >= 10,
            "{name}: {} triangles",
            view.triangles.len()
        );
        assert_eq!(
            cocircular.is_empty(),
            *name != "box_in_box",
            "{name}: cocircular edges {cocircular:?}"
        );
    }
}

#[test]
fn random_polygons_with_holes_match() {
    for seed in 0..50 {
        compare(&pslg::polygon_with_holes(seed), SWITCH_SETS);
    }
}

#[test]
fn crossing_segments_match() {
    for seed in 0..50 {
        let pslg = pslg::crossing_segments(seed, 5 + seed as usize, 2 + seed as usize / 2);
        // Without `c` the segments rarely enclose anything: often no triangle at all.
        compare(&pslg, &["pcQ", "pczAenQ", "pcjQ", "pQ", "pzeQ"]);
    }
}

#[test]
fn vertices_on_segments_match() {
    for seed in 0..25 {
        let pslg = pslg::vertices_on_segments(seed, 4 + seed as i32 % 5, 3 + seed as usize % 6);
        compare(&pslg, &["pcQ", "pczAenQ", "pcjQ", "pQ"]);
    }
}

#[test]
fn larger_random_pslgs_match() {
    for seed in 0..3 {
        compare(
            &pslg::polygon_with_holes_of(1000 + seed, 2000),
            &["pQ", "pzAjenQ", "pcOAQ"],
        );
        compare(
            &pslg::crossing_segments(1000 + seed, 200, 60),
            &["pcQ", "pczAenjQ"],
        );
    }
    // Not a dense lattice (`vertices_on_segments(1000, 30, 40)`): there Triangle rounds a
    // crossing onto an existing vertex and outputs a degenerate triangle with two corners at one
    // place (ours stays valid: pslg_properties.rs checks it).
}

/// The shapes are readable by Debian's `triangle` program: it meshes each with as many
/// triangles as its library (and ours) does.
#[test]
fn debian_triangle_reads_the_shapes() {
    let program = std::path::Path::new("/usr/bin/triangle");
    if !program.is_file() {
        common::reference_missing("/usr/bin/triangle");
        return;
    }
    let dir = std::env::temp_dir().join(format!("triangle-rs-shapes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in pslg::SHAPES {
        let copy = dir.join(format!("{name}.poly"));
        std::fs::copy(pslg::shape_path(name), &copy).unwrap();
        let status = Command::new(program)
            .arg("-pAQ")
            .arg(&copy)
            .status()
            .expect("run /usr/bin/triangle");
        assert!(status.success(), "{name}: /usr/bin/triangle failed");
        let ele = std::fs::read_to_string(dir.join(format!("{name}.1.ele"))).unwrap();
        let ele = triangle_rs::io::files::read_ele(&ele, name).unwrap();
        let shape = pslg::shape(name);
        let ours = ours("pAQ", &shape.input_for("pAQ")).unwrap();
        assert_eq!(
            ele.triangle_count(),
            ours.counts.triangles as usize,
            "{name}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// With `A` and `numberofregions == 0` Triangle adds no triangle attribute
/// (`numberoftriangleattributes` 0, `triangleattributelist` NULL), although its manual gives
/// every triangle one (zero where no region applies); we follow the manual (issue 12).
#[test]
fn region_switch_without_regions_adds_a_zero_attribute() {
    let Some(triangle) = reference() else { return };
    let mut input =
        common::MeshInput::from_points(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    input.segments = vec![[1, 2], [2, 3], [3, 4], [4, 1]];
    for switches in ["pAQ", "pcAQ"] {
        let theirs = triangle.triangulate(switches, &input);
        assert_eq!(
            (
                theirs.counts.triangle_attributes,
                theirs.triangle_attributes.is_some()
            ),
            (0, false)
        );
        let ours = ours(switches, &input).unwrap();
        assert_eq!(
            (
                ours.counts.triangle_attributes,
                ours.triangle_attributes.as_deref()
            ),
            (1, Some(&[0.0, 0.0][..])),
            "\"{switches}\" on a square without regions"
        );
    }
}

/// A segment given again, with a non-zero marker where the first copy had 0, marks the vertices
/// at its own place in input order: a vertex that a segment given in between marked keeps that
/// marker (Triangle marks vertices while inserting segments in input order, and a copy walks the
/// first copy's pieces). Random edges of a triangulation (so no crossings), many given twice in
/// either direction, random markers, against Triangle: `c` keeps every triangle (where Triangle
/// eats triangles, whether it marks the ends of a segment eaten on both sides depends on the
/// order it eats them in).
#[test]
fn later_copies_of_segments_mark_vertices_in_input_order() {
    let Some(triangle) = reference() else { return };
    let mut rng = common::rng::SplitMix64::new(0x5EED_C0B1);
    for case in 0..60 {
        let n = 4 + rng.below(36);
        // On a coarse grid: cocircular points too (which triangulation the edges come from does
        // not matter, only that they do not cross).
        let points: Vec<[f64; 2]> = (0..n)
            .map(|_| {
                [
                    rng.below(1000) as f64 / 1000.0,
                    rng.below(1000) as f64 / 1000.0,
                ]
            })
            .collect();
        let input = MeshInput::from_points(points.clone());
        let triangulation = ours("zQ", &input).unwrap();
        let mut edges: Vec<[i32; 2]> = triangulation
            .triangles
            .unwrap()
            .chunks_exact(3)
            .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let mut segments = Vec::new();
        for _ in 0..1 + rng.below(edges.len()) {
            let [a, b] = edges[rng.below(edges.len())];
            for _ in 0..1 + usize::from(rng.below(5) < 2) {
                segments.push(if rng.below(2) == 0 {
                    [a + 1, b + 1]
                } else {
                    [b + 1, a + 1]
                });
            }
        }
        for i in (1..segments.len()).rev() {
            segments.swap(i, rng.below(i + 1));
        }
        let markers = (0..segments.len())
            .map(|_| [0, 0, 3, 5, 9][rng.below(5)])
            .collect();
        let input = MeshInput {
            segments,
            segment_markers: Some(markers),
            ..MeshInput::from_points(points)
        };
        for switches in ["pcQ", "pceQ"] {
            let theirs = triangle.triangulate(switches, &input);
            let ours = ours(switches, &input).unwrap();
            let diffs = pslg_differences(&input, &ours, &theirs);
            assert!(
                diffs.is_empty(),
                "case {case}, \"{switches}\": ours differs from Triangle's:\n  {}",
                diffs.join("\n  ")
            );
        }
    }
}

/// When several input segments cover the same edge (a segment repeated, or collinear segments
/// overlapping), Triangle gives the edge the first non-zero marker among them (a later segment's
/// marker replaces a 0), and the vertices on it get that marker too; so do we.
#[test]
fn repeated_segments_take_the_first_nonzero_marker() {
    let Some(triangle) = reference() else { return };
    // A square with its diagonal 1-3; the bottom side and the diagonal are given twice, first
    // with marker 0, then with markers 5 and 7; a collinear segment overlaps the top side.
    let mut input = common::MeshInput::from_points(vec![
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [-1.0, 1.0],
    ]);
    input.segments = vec![
        [1, 2],
        [2, 3],
        [3, 4],
        [4, 1],
        [1, 3],
        [2, 1],
        [3, 1],
        [3, 5],
        [5, 1],
    ];
    input.segment_markers = Some(vec![0, 0, 0, 0, 0, 5, 7, 8, 0]);
    for switches in ["pQ", "pcQ", "peQ"] {
        let theirs = triangle.triangulate(switches, &input);
        let ours = ours(switches, &input).unwrap();
        let ours = without_zero_region_column(&ours, switches, input.regions.len());
        let diffs = pslg_differences(&input, &ours, &theirs);
        assert!(
            diffs.is_empty(),
            "\"{switches}\": ours differs from Triangle's:\n  {}",
            diffs.join("\n  ")
        );
    }
}

/// A domain its holes eat whole leaves no triangle and no segment to mark vertices by; a segment
/// given again with a marker (a later copy) once made our output writer index the markers of
/// segments the empty mesh no longer has ("Internal error": found by the fuzz driver). Ours must
/// give an empty mesh, as Triangle does, with and without refinement.
#[test]
fn a_domain_eaten_whole_with_a_segment_given_again_gives_an_empty_mesh() {
    let Some(triangle) = reference() else { return };
    let input = MeshInput {
        segments: vec![[1, 2], [2, 3], [3, 1], [2, 1]],
        segment_markers: Some(vec![0, 2, 2, 7]),
        holes: vec![[0.4, 0.3]],
        ..MeshInput::from_points(vec![[0.0, 0.0], [1.0, 0.1], [0.2, 0.9]])
    };
    for switches in ["pQ", "pqQ", "pa0.01Q", "pq30a0.01Q", "pDQ", "pcQ"] {
        let theirs = triangle.triangulate(switches, &input);
        let ours = ours(switches, &input).unwrap_or_else(|e| panic!("\"{switches}\": {e}"));
        let count =
            |t: &common::call::Triangulation| t.triangles.as_ref().map_or(0, |t| t.len() / 3);
        assert_eq!(count(&ours), count(&theirs), "\"{switches}\"");
        assert_eq!(count(&ours), 0, "\"{switches}\"");
    }
}
