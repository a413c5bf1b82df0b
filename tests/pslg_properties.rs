//! Properties of our constrained Delaunay triangulation (`p`, through the C ABI) on random PSLGs
//! (star-shaped polygons with holes and islands, crossing segments, vertices on segments,
//! duplicate vertices referenced by segments) and on the classic shapes of tests/data/shapes/:
//! - a valid mesh (counter-clockwise, manifold, bounded by segments);
//! - constrained Delaunay: every non-segment edge locally Delaunay by exact `incircle`;
//! - every input segment present as a chain of output segments, split at the vertices on it and
//!   where other segments cross it;
//! - the meshed area: polygon area − hole areas (the convex hull's with `c`);
//! - Triangle's marker rules; region attributes; attributes interpolated at new vertices;
//! - what `j`, `e`, `n`, `O` and `z` promise.
//!
//! Triangle itself has undefined behaviour on duplicates referenced by segments, so those are
//! checked here only; everything else is also compared with Triangle in pslg_differential.rs.

mod common;

use std::collections::{BTreeSet, HashMap};

use common::checks::check_neighbors;
use common::points::Point;
use common::pslg::{self, affine_attribute, Pslg};
use common::pslg_checks::{
    bypasses_a_vertex, check_constrained_delaunay, check_markers, segment_chains, MeshView,
};
use common::{ours, Triangulation};

/// Runs ours on `pslg` with `switches` and checks every property that applies; returns the
/// output.
fn check(pslg: &Pslg, switches: &str) -> Triangulation {
    let context = format!("{}, \"{switches}\"", pslg.name);
    let input = pslg.input_for(switches);
    let out = ours(switches, &input).unwrap_or_else(|e| panic!("{context}: {e}"));
    let fail = |e: String| -> ! { panic!("{context}: {e}") };
    let mesh = MeshView::of(&out).unwrap_or_else(|e| fail(e));
    assert!(!mesh.triangles.is_empty(), "{context}: no triangle");
    check_constrained_delaunay(&mesh).unwrap_or_else(|e| fail(e));
    let chains =
        segment_chains(&pslg.input, &mesh, switches.contains('c')).unwrap_or_else(|e| fail(e));
    assert!(
        !bypasses_a_vertex(&pslg.input, &mesh),
        "{context}: an output segment passes by an input vertex lying on it"
    );

    if let Some(expected) = pslg.expected_area(switches) {
        let area = mesh.area();
        assert!(
            (area - expected).abs() <= 1e-9 * expected.abs(),
            "{context}: the triangles' area is {area}, the domain's {expected}"
        );
    }

    // Output vertex → input vertex: the same index without `j` (whichever copy of a duplicate
    // is in the mesh, its own input marker counts), by coordinates with `j` (no duplicates).
    let n = pslg.input.points.len();
    let first_at: HashMap<[u64; 2], usize> = pslg
        .input
        .points
        .iter()
        .enumerate()
        .rev()
        .map(|(i, p)| (p.map(f64::to_bits), i))
        .collect();
    let jettison = switches.contains('j');
    let input_vertex = |v: usize| {
        if jettison {
            first_at.get(&mesh.points[v].map(f64::to_bits)).copied()
        } else {
            (v < n).then_some(v)
        }
    };
    if switches.contains('B') {
        assert!(
            out.point_markers.is_none()
                && out.segment_markers.is_none()
                && out.edge_markers.is_none(),
            "{context}: `B` writes no markers"
        );
    } else {
        check_markers(&pslg.input, &mesh, &chains, &input_vertex).unwrap_or_else(|e| fail(e));
    }

    if jettison {
        let left_out = (0..mesh.points.len()).filter(|&v| !mesh.in_mesh[v]).count();
        assert_eq!(
            left_out, 0,
            "{context}: `j` keeps {left_out} vertices outside the mesh"
        );
    } else {
        assert_eq!(
            &mesh.points[..n],
            &pslg.input.points[..],
            "{context}: the input vertices come first, in order"
        );
    }
    if pslg.affine_attributes {
        let attributes = out.point_attributes.as_deref().expect("point attributes");
        for (v, (&p, &x)) in mesh.points.iter().zip(attributes).enumerate() {
            let expected = affine_attribute(p);
            assert!(
                (x - expected).abs() <= 1e-9 * expected.abs().max(1.0),
                "{context}: vertex {v} {p:?} has attribute {x}; interpolation gives {expected}"
            );
        }
    }
    if switches.contains('A') && (!pslg.islands.is_empty() || pslg.outer_attribute != 0.0) {
        let attributes = out
            .triangle_attributes
            .as_deref()
            .expect("triangle attributes");
        assert_eq!(out.counts.triangle_attributes, 1, "{context}");
        for (t, c) in mesh.triangles.iter().enumerate() {
            let [a, b, d] = c.map(|v| mesh.points[v]);
            let centroid: Point = [(a[0] + b[0] + d[0]) / 3.0, (a[1] + b[1] + d[1]) / 3.0];
            assert_eq!(
                attributes[t],
                pslg.attribute_at(centroid),
                "{context}: region attribute of triangle {t} {c:?}"
            );
        }
    }
    if switches.contains('e') {
        let edges: BTreeSet<[usize; 2]> = out
            .edges
            .as_deref()
            .expect("edges")
            .iter()
            .map(|e| {
                let [a, b] = e.map(|v| (v - out.base) as usize);
                [a.min(b), a.max(b)]
            })
            .collect();
        let expected: BTreeSet<[usize; 2]> = mesh
            .edges
            .keys()
            .map(|&(a, b)| [a.min(b), a.max(b)])
            .collect();
        assert_eq!(
            edges, expected,
            "{context}: the edge list is every edge of the mesh"
        );
        assert_eq!(
            out.counts.edges as usize,
            expected.len(),
            "{context}: an edge listed twice"
        );
    }
    if switches.contains('n') {
        check_neighbors(
            &mesh.triangles,
            out.neighbors.as_deref().expect("neighbours"),
            out.base,
        )
        .unwrap_or_else(|e| fail(e));
    }
    assert_eq!(
        out.holes_alias_input,
        !pslg.input.holes.is_empty(),
        "{context}: out.holelist aliases the input's"
    );
    out
}

const POLYGON_SWITCHES: &[&str] = &[
    "pzQ", "pQ", "pAzQ", "pjzQ", "pezQ", "pnzQ", "pOzQ", "pAjenOQ", "pBzQ",
];

#[test]
fn random_polygons_with_holes_and_islands() {
    for seed in 0..60 {
        let pslg = pslg::polygon_with_holes(seed);
        for switches in POLYGON_SWITCHES {
            check(&pslg, switches);
        }
    }
}

/// Without `c` the domain is what the segments enclose: ours with `pc` on the same polygon
/// keeps more triangles (the pockets between the polygon and its hull), and the same ones
/// inside.
#[test]
fn convex_hull_switch_keeps_the_pockets() {
    for seed in 100..110 {
        let pslg = pslg::polygon_with_holes(seed);
        let inside = check(&pslg, "pzQ");
        let hull = ours("pczQ", &pslg.input_for("pczQ")).unwrap();
        let hull_view = MeshView::of(&hull).unwrap();
        check_constrained_delaunay(&hull_view).unwrap();
        let hull_area = pslg::polygon_area(&common::checks::convex_hull(&pslg.input.points));
        let holes = pslg.area_ignoring_holes.unwrap() - pslg.area.unwrap();
        assert!(
            ((hull_view.area() - (hull_area - holes)) / hull_area).abs() < 1e-9,
            "seed {seed}"
        );
        let triangles =
            |t: &Triangulation| -> BTreeSet<[i32; 3]> { common::checks::triangle_set(t) };
        assert!(
            triangles(&inside).is_subset(&triangles(&hull)),
            "seed {seed}: `c` changed triangles inside the polygon"
        );
    }
}

#[test]
fn crossing_segments_are_split_where_they_cross() {
    for seed in 0..50 {
        let pslg = pslg::crossing_segments(seed, 5 + seed as usize, 2 + seed as usize / 2);
        for switches in ["pczQ", "pcAejnQ", "pcQ"] {
            check(&pslg, switches);
        }
    }
}

#[test]
fn vertices_on_segments_split_them() {
    for seed in 0..30 {
        let pslg = pslg::vertices_on_segments(seed, 4 + seed as i32 % 5, 3 + seed as usize % 6);
        for switches in ["pczQ", "pcjezQ", "pcnQ"] {
            check(&pslg, switches);
        }
    }
}

#[test]
fn duplicates_referenced_by_segments_use_the_surviving_copy() {
    for seed in 0..20 {
        for pslg in [
            pslg::with_duplicates(pslg::polygon_with_holes(seed), seed),
            pslg::with_duplicates(pslg::crossing_segments(seed, 8, 5), seed),
            pslg::with_duplicates(pslg::vertices_on_segments(seed, 5, 4), seed),
        ] {
            let switches: &[&str] = if pslg.convex {
                &["pczQ", "pcAenzQ"]
            } else {
                &["pzQ", "pAenQ", "pOzQ"]
            };
            for switches in switches {
                check(&pslg, switches);
            }
        }
    }
}

#[test]
fn larger_random_pslgs() {
    for seed in 0..3 {
        let polygon = pslg::polygon_with_holes_of(1000 + seed, 2000);
        for switches in ["pzQ", "pAjenQ"] {
            check(&polygon, switches);
        }
        let crossing = pslg::crossing_segments(1000 + seed, 200, 60);
        for switches in ["pczQ", "pcAenQ"] {
            check(&crossing, switches);
        }
    }
    // Dense lattices (`vertices_on_segments(1000 + seed, 30, 40)`) are in
    // `segments_crossing_near_bent_segments_keep_their_course`.
}

/// A segment crossing a piece of another segment that was bent at a rounded crossing, within
/// rounding of a vertex lying on it (a sliver triangle beside the piece): the crossing cannot be
/// split cleanly into the crossed edge, so it is inserted where it is and both segments bend
/// through it. Below, the segment (4, 4.5)–(13, 4.25) must stay on its course (Triangle splits
/// it at (10.887, 4.309) and (11.243, 4.299)). Dense lattices of segments hit this often
/// (Triangle itself crashes with "Topological inconsistency after splitting a segment" on some).
#[test]
fn segments_crossing_near_bent_segments_keep_their_course() {
    let input = common::MeshInput {
        points: vec![
            [12.0, 5.75],
            [9.0, 0.0],
            [12.5, 5.0],
            [5.5, 2.0],
            [9.0, 3.5],
            [4.0, 4.5],
            [13.0, 4.25],
        ],
        segments: vec![[0, 1], [2, 3], [5, 6]],
        ..common::MeshInput::default()
    };
    check(
        &Pslg {
            convex: true,
            ..Pslg::new("7 vertices, 3 segments".into(), input)
        },
        "pczQ",
    );
    for seed in 0..4 {
        let mut lattice = pslg::vertices_on_segments(1000 + seed, 30, 40);
        // Here several segments share pieces between near-coincident crossings, where the bug
        // of pslg_differential.rs's `repeated_segments_take_the_first_nonzero_marker` would
        // show as well: non-zero markers only.
        for marker in lattice.input.segment_markers.iter_mut().flatten() {
            if *marker == 0 {
                *marker = 12;
            }
        }
        check(&lattice, "pczenQ");
    }
}

/// The random generators produce what the tests above rely on: holes and islands, free vertices
/// that holes eat (`j` drops them), crossings (new vertices), input vertices inside segments, and
/// segments that reference duplicate vertices.
#[test]
fn generators_cover_their_cases() {
    let (mut holes, mut islands, mut eaten, mut crossings, mut on_segments, mut to_duplicates) =
        (0, 0, 0, 0, 0, 0);
    for seed in 0..30 {
        let polygon = pslg::polygon_with_holes(seed);
        holes += polygon.input.holes.len();
        islands += polygon.islands.len();
        let kept = ours("pjzQ", &polygon.input_for("pjzQ")).unwrap();
        eaten += polygon.input.points.len() - kept.counts.points as usize;
        let crossing = pslg::crossing_segments(seed, 5 + seed as usize, 2 + seed as usize / 2);
        let out = ours("pczQ", &crossing.input_for("pczQ")).unwrap();
        crossings += out.counts.points as usize - crossing.input.points.len();
        let lattice = pslg::vertices_on_segments(seed, 4 + seed as i32 % 5, 3 + seed as usize % 6);
        for [a, b] in lattice
            .input
            .segments
            .iter()
            .map(|s| s.map(|v| lattice.input.points[v as usize]))
        {
            on_segments += lattice
                .input
                .points
                .iter()
                .filter(|&&p| p != a && p != b && common::checks::orient2d(a, b, p) == 0.0)
                .filter(|&&p| (p[0] - a[0]) * (p[0] - b[0]) + (p[1] - a[1]) * (p[1] - b[1]) < 0.0)
                .count();
        }
        let duplicated = pslg::with_duplicates(pslg::polygon_with_holes(seed), seed);
        let originals = pslg::polygon_with_holes(seed).input.points.len() as i32;
        to_duplicates += duplicated
            .input
            .segments
            .iter()
            .flatten()
            .filter(|&&v| v >= originals)
            .count();
    }
    for (what, count) in [
        ("holes", holes),
        ("islands", islands),
        ("vertices eaten with holes", eaten),
        ("crossings", crossings),
        ("vertices inside segments", on_segments),
        ("segment ends at duplicates", to_duplicates),
    ] {
        assert!(count >= 10, "only {count} {what} over 30 seeds");
    }
}

#[test]
fn classic_shapes() {
    for name in pslg::SHAPES {
        let shape = pslg::shape(name);
        for switches in ["pQ", "pzAQ", "pzjenQ", "pcQ", "pOQ"] {
            check(&shape, switches);
        }
    }
}

/// The shapes' known properties: triangle counts of a polygon (n − 2 + 2h for a polygon with
/// h polygonal holes and no free vertex), regions, markers given on vertices.
#[test]
fn classic_shapes_have_the_expected_meshes() {
    let count = |name: &str, switches: &str| {
        let shape = pslg::shape(name);
        ours(switches, &shape.input_for(switches)).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    // A polygon with n vertices and h holes (all vertices on the boundary): n + 2h − 2 triangles.
    for (name, n, h) in [
        ("letter_a", 11, 1),
        ("spiral", 82, 0),
        ("square_circular_hole", 68, 1),
    ] {
        assert_eq!(count(name, "pQ").counts.triangles, n + 2 * h - 2, "{name}");
    }
    let regions = count("three_regions", "pAQ");
    let attributes: BTreeSet<u64> = regions
        .triangle_attributes
        .unwrap()
        .iter()
        .map(|a| a.to_bits())
        .collect();
    assert_eq!(
        attributes,
        [1.0f64, 2.0, 3.0].iter().map(|a| a.to_bits()).collect(),
        "three regions"
    );
    let hexagons = count("double_hexagon", "pAQ");
    let attributes: BTreeSet<u64> = hexagons
        .triangle_attributes
        .unwrap()
        .iter()
        .map(|a| a.to_bits())
        .collect();
    assert_eq!(
        attributes,
        [10.0f64, 20.0].iter().map(|a| a.to_bits()).collect(),
        "double hexagon"
    );
    // The free vertex on the inner box's side takes that side's marker (12).
    let boxes = count("box_in_box", "pQ");
    assert_eq!(
        boxes.point_markers.as_ref().unwrap()[14],
        12,
        "box in box: vertex on a segment"
    );
}

/// Nearly collinear points (within 1e-9 of a line) with segments that overlap and cross at tiny
/// angles. Regression: the rounded crossing points bent the segments across each other again
/// and again, and segment insertion never ended.
#[test]
fn nearly_collinear_crossing_segments_terminate() {
    let xs = [
        0.633788, 0.662119, 0.361759, 0.105775, 0.966813, 0.503565, 0.429944, 0.824995, 0.049885,
        0.966744, 0.160581, 0.808613, 0.812349, 0.652578, 0.330774, 0.29776, 0.809759, 0.43568,
    ];
    // y = x / 2 plus up to 1e-9.
    let offsets = [
        6.02891e-10,
        1.97213e-10,
        5.63818e-10,
        5.07482e-10,
        4.73215e-10,
        4.34623e-10,
        1.33595e-10,
        3.2711e-11,
        9.94037e-10,
        7.13291e-10,
        1.81811e-10,
        7.5719e-11,
        6.90371e-10,
        2.5255e-11,
        2.30275e-10,
        9.14682e-10,
        2.03213e-10,
        9.37895e-10,
    ];
    let points: Vec<[f64; 2]> = xs
        .iter()
        .zip(offsets)
        .map(|(&x, o)| [x, 0.5 * x + o])
        .collect();
    let segments = vec![
        [12, 5],
        [15, 14],
        [10, 5],
        [11, 16],
        [6, 3],
        [6, 3],
        [11, 17],
        [15, 3],
        [16, 0],
        [15, 15],
        [15, 4],
        [13, 4],
        [16, 3],
        [13, 16],
        [14, 0],
        [4, 4],
        [11, 13],
        [8, 10],
    ];
    let input = common::MeshInput {
        segments,
        ..common::MeshInput::from_points(points)
    };
    for switches in ["pzQ", "pczQ"] {
        let out = ours(switches, &input).unwrap_or_else(|e| panic!("\"{switches}\": {e}"));
        let mesh = MeshView::of(&out).unwrap_or_else(|e| panic!("\"{switches}\": {e}"));
        check_constrained_delaunay(&mesh).unwrap_or_else(|e| panic!("\"{switches}\": {e}"));
    }
}

/// A segment given twice (either way round, as PSLGs assembled from polygons often have) is
/// one segment: the mesh is the one of the PSLG without the repeats, with `s` (whose midpoints
/// may lie an ulp off the line, so that a second insertion would cross the first's chain at
/// slivers) and with refinement (which ran away on such slivers).
#[test]
fn repeated_segments_are_inserted_once() {
    for seed in 0..20 {
        for pslg in [
            pslg::polygon_with_holes(seed),
            pslg::crossing_segments(seed, 8, 5),
        ] {
            let mut repeated = pslg.clone();
            let input = &mut repeated.input;
            let count = input.segments.len();
            for s in 0..count {
                if s % 2 == 0 {
                    let [a, b] = input.segments[s];
                    input
                        .segments
                        .push(if s % 4 == 0 { [b, a] } else { [a, b] });
                    if let Some(markers) = input.segment_markers.as_mut() {
                        markers.push(markers[s]);
                    }
                }
            }
            repeated.name = format!("{} with repeated segments", pslg.name);
            let c = if pslg.convex { "c" } else { "" };
            for switches in ["pszQ", "pzQ", "psq25zQ"] {
                let switches = format!("p{c}{}", &switches[1..]);
                let once = ours(&switches, &pslg.input_for(&switches)).unwrap();
                let twice = check(&repeated, &switches);
                assert_eq!(
                    common::checks::triangle_set(&once),
                    common::checks::triangle_set(&twice),
                    "{}, \"{switches}\": the repeats changed the mesh",
                    repeated.name
                );
            }
        }
    }
}

/// Segments that overlap or pass through vertices only within rounding (lattice coordinates
/// such as 0.2 are inexact): a vertex within rounding of a segment is on it, so that no third
/// segment crosses the two at points an ulp apart.
#[test]
fn segments_meeting_within_rounding_share_their_vertices() {
    let pslg = pslg::lattice_with_overlaps();
    // Not yet with `s`: a midpoint that lands within rounding of another segment is not put on
    // it, and the two overlapping chains stay apart there.
    for switches in ["pczQ", "pcjezQ"] {
        let out = check(&pslg, switches);
        let mesh = MeshView::of(&out).unwrap();
        // No two vertices closer than the lattice's scale allows (crossings are at least 1/30
        // apart here).
        for (i, p) in mesh.points.iter().enumerate() {
            for q in &mesh.points[i + 1..] {
                let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
                assert!(
                    d == 0.0 || d > 1e-3,
                    "\"{switches}\": vertices {p:?} and {q:?} are {d:e} apart"
                );
            }
        }
    }
}

/// A segment that overlaps a shorter one goes on through the shorter one's end, even where a
/// rounded crossing point makes that end lie an ulp off the rest of its course.
#[test]
fn an_overlapping_segment_continues_through_the_end_of_the_shorter_one() {
    let pslg = pslg::overlap_past_a_rounded_crossing();
    for switches in ["pczQ", "pczqQ", "pcszQ"] {
        check(&pslg, switches);
    }
}
