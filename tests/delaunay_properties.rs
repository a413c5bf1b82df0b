//! Properties of our Delaunay triangulation and Voronoi diagram (through the C ABI) on every
//! point generator: uniform, clustered, cocircular grid, collinear, nearly collinear, duplicated,
//! 1e-12-scale and 1e12-offset points. Each output must be a valid mesh of the convex hull
//! (counter-clockwise, manifold, area = hull area, Euler), Delaunay by exact `incircle`, with
//! consistent neighbours, markers, hull segments and edges, and the Voronoi diagram its dual.

mod common;

use std::collections::BTreeSet;

use common::checks::{
    check_delaunay, check_mesh, check_neighbors, check_point_markers, check_voronoi, triangle_set,
    zero_based,
};
use common::points::{self, Point};
use common::{ours, MeshInput};

const SIZES: &[(usize, u64)] = &[
    (3, 1),
    (4, 2),
    (5, 3),
    (10, 4),
    (57, 5),
    (500, 6),
    (3000, 7),
];

fn check_everything(name: &str, points: &[Point], switches: &str) {
    let context = format!("{} {name} points, \"{switches}\"", points.len());
    let input = MeshInput::from_points(points.to_vec());
    let out = ours(switches, &input).unwrap_or_else(|e| panic!("{context}: {e}"));
    assert_eq!(out.base, 0, "the property tests use z");
    let fail = |e: String| -> ! { panic!("{context}: {e}") };
    assert_eq!(
        out.points.as_deref(),
        Some(points),
        "{context}: output points are the input points"
    );
    let triangles = zero_based(&out);
    let stats = check_mesh(points, &triangles).unwrap_or_else(|e| fail(e));
    check_delaunay(points, &triangles).unwrap_or_else(|e| fail(e));
    check_neighbors(&triangles, out.neighbors.as_deref().unwrap_or_default(), 0)
        .unwrap_or_else(|e| fail(e));
    if triangles.is_empty() {
        // Collinear input: no triangle, no edge, no error.
        assert_eq!(
            (out.counts.triangles, out.counts.edges),
            (0, 0),
            "{context}"
        );
        return;
    }
    check_point_markers(None, &out).unwrap_or_else(|e| fail(e));
    let voronoi = out.voronoi.as_ref().unwrap();
    check_voronoi(points, &triangles, voronoi, 0).unwrap_or_else(|e| fail(e));

    // c: the hull edges as segments, marker 1; e: every edge once, marker 1 exactly on the hull.
    let boundary: BTreeSet<[usize; 2]> = boundary_edges(&triangles);
    let segments: BTreeSet<[usize; 2]> = out
        .segments
        .as_ref()
        .unwrap()
        .iter()
        .map(|&[a, b]| sorted(a as usize, b as usize))
        .collect();
    assert_eq!(segments, boundary, "{context}: hull segments");
    assert_eq!(
        out.segments.as_ref().unwrap().len(),
        boundary.len(),
        "{context}: a hull segment twice"
    );
    assert!(
        out.segment_markers
            .as_ref()
            .unwrap()
            .iter()
            .all(|&m| m == 1),
        "{context}: segment markers"
    );
    let edges = out.edges.as_ref().unwrap();
    assert_eq!(
        edges.len(),
        stats.interior_edges + stats.boundary_edges,
        "{context}: edge count"
    );
    let distinct: BTreeSet<[usize; 2]> = edges
        .iter()
        .map(|&[a, b]| sorted(a as usize, b as usize))
        .collect();
    assert_eq!(
        distinct.len(),
        edges.len(),
        "{context}: an edge listed twice"
    );
    for (&[a, b], &marker) in edges.iter().zip(out.edge_markers.as_ref().unwrap()) {
        let on_hull = boundary.contains(&sorted(a as usize, b as usize));
        assert_eq!(marker, on_hull as i32, "{context}: marker of edge {a}-{b}");
    }
}

fn sorted(a: usize, b: usize) -> [usize; 2] {
    [a.min(b), a.max(b)]
}

fn boundary_edges(triangles: &[[usize; 3]]) -> BTreeSet<[usize; 2]> {
    let directed: BTreeSet<(usize, usize)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .collect();
    directed
        .iter()
        .filter(|&&(a, b)| !directed.contains(&(b, a)))
        .map(|&(a, b)| sorted(a, b))
        .collect()
}

#[test]
fn default_algorithm_on_every_generator() {
    for (name, generate) in points::all_generators() {
        for &(n, seed) in SIZES {
            check_everything(name, &generate(n, seed), "Qzcenv");
        }
    }
}

#[test]
fn incremental_algorithm_on_every_generator() {
    for (name, generate) in points::all_generators() {
        for &(n, seed) in SIZES {
            check_everything(name, &generate(n, seed), "Qizcenv");
        }
    }
}

#[test]
fn algorithms_agree_in_general_position() {
    // The Delaunay triangulation of points in general position is unique.
    let generators: [(&str, points::Generator); 3] = [
        ("uniform", points::uniform),
        ("clustered", points::clustered),
        ("tiny", points::tiny),
    ];
    for (name, generate) in generators {
        for &(n, seed) in SIZES {
            let input = MeshInput::from_points(generate(n, seed));
            let default = triangle_set(&ours("Qz", &input).unwrap());
            for switches in ["Qzi", "QzF", "Qzl"] {
                let other = triangle_set(&ours(switches, &input).unwrap());
                assert!(
                    default == other,
                    "{n} {name} points: \"{switches}\" differs from the default algorithm"
                );
            }
        }
    }
}

#[test]
fn counts_are_set_without_the_switches_that_write_the_lists() {
    // Triangle sets numberofsegments (hull edges), numberofedges and vorout's counts even
    // when c, e and v are absent, and writes none of those arrays.
    let points = points::uniform(200, 9);
    let input = MeshInput::from_points(points.clone());
    let out = ours("Qz", &input).unwrap();
    let triangles = zero_based(&out);
    let stats = check_mesh(&points, &triangles).unwrap();
    assert_eq!(out.counts.segments as usize, stats.boundary_edges);
    assert_eq!(
        out.counts.edges as usize,
        stats.boundary_edges + stats.interior_edges
    );
    assert!(out.segments.is_none() && out.edges.is_none() && out.neighbors.is_none());
    let voronoi = out.voronoi.unwrap();
    assert_eq!(voronoi.points_count as usize, triangles.len());
    assert_eq!(voronoi.edges_count, out.counts.edges);
    assert!(voronoi.points.is_none() && voronoi.edges.is_none() && voronoi.norms.is_none());
}

/// The checks above can fail: each rejects a deliberately broken copy of a valid output.
#[test]
fn checks_reject_broken_outputs() {
    let points = points::uniform(40, 77);
    let out = ours("Qzcenv", &MeshInput::from_points(points.clone())).unwrap();
    let triangles = zero_based(&out);
    let neighbors = out.neighbors.clone().unwrap();
    let voronoi = out.voronoi.clone().unwrap();
    check_mesh(&points, &triangles).unwrap();
    check_delaunay(&points, &triangles).unwrap();
    check_neighbors(&triangles, &neighbors, 0).unwrap();
    check_voronoi(&points, &triangles, &voronoi, 0).unwrap();

    // Flipping an interior edge of a convex quadrilateral keeps a valid mesh but breaks the
    // Delaunay property.
    let flip = |t: usize, k: usize| {
        let u = neighbors[t][k] as usize;
        let (a, b, c) = (
            triangles[t][k],
            triangles[t][(k + 1) % 3],
            triangles[t][(k + 2) % 3],
        );
        let d = *triangles[u].iter().find(|&&v| v != b && v != c).unwrap();
        let mut flipped = triangles.clone();
        flipped[t] = [a, b, d];
        flipped[u] = [a, d, c];
        flipped
    };
    let flipped = (0..triangles.len())
        .flat_map(|t| (0..3).map(move |k| (t, k)))
        .filter(|&(t, k)| neighbors[t][k] != -1)
        .map(|(t, k)| flip(t, k))
        .find(|flipped| check_mesh(&points, flipped).is_ok())
        .expect("some interior edge can be flipped");
    assert!(
        check_delaunay(&points, &flipped).is_err(),
        "a flipped edge passed the Delaunay check"
    );
    let (t, k) = (0..triangles.len())
        .flat_map(|t| (0..3).map(move |k| (t, k)))
        .find(|&(t, k)| neighbors[t][k] != -1)
        .unwrap();
    let mut reversed = triangles.clone();
    reversed[3].swap(0, 1);
    assert!(
        check_mesh(&points, &reversed).is_err(),
        "a clockwise triangle passed"
    );
    let mut missing = triangles.clone();
    missing.pop();
    assert!(
        check_mesh(&points, &missing).is_err(),
        "a missing triangle passed"
    );
    let mut wrong_neighbors = neighbors.clone();
    wrong_neighbors[t][k] = -1;
    assert!(
        check_neighbors(&triangles, &wrong_neighbors, 0).is_err(),
        "a missing neighbour passed"
    );
    let mut moved = voronoi.clone();
    moved.points.as_mut().unwrap()[5][0] += 1e-3;
    assert!(
        check_voronoi(&points, &triangles, &moved, 0).is_err(),
        "a moved Voronoi vertex passed"
    );
    let mut turned = voronoi.clone();
    let ray = turned
        .edges
        .as_ref()
        .unwrap()
        .iter()
        .position(|e| e[1] == -1)
        .unwrap();
    let norm = &mut turned.norms.as_mut().unwrap()[ray];
    *norm = [-norm[0], -norm[1]];
    assert!(
        check_voronoi(&points, &triangles, &turned, 0).is_err(),
        "a reversed ray passed"
    );
    let mut rewired = voronoi;
    let finite = rewired
        .edges
        .as_ref()
        .unwrap()
        .iter()
        .position(|e| e[1] != -1)
        .unwrap();
    rewired.edges.as_mut().unwrap()[finite][1] =
        (rewired.edges.as_ref().unwrap()[finite][1] + 1) % triangles.len() as i32;
    assert!(
        check_voronoi(&points, &triangles, &rewired, 0).is_err(),
        "a rewired Voronoi edge passed"
    );
}

/// The plain outputs (points, triangles, markers: no `c`, `e`, `n`, `v`), which are built from
/// the mesh in place, on every generator at a size that the two-core merge takes (where two
/// cores are free), with the first index 0 (`z`: the corners copied as they are) and 1.
#[test]
fn plain_outputs_of_large_inputs_on_every_generator() {
    for (name, generate) in points::all_generators() {
        let points = generate(30_000, 17);
        for switches in ["Qz", "Q"] {
            let context = format!("{} {name} points, \"{switches}\"", points.len());
            let input = MeshInput::from_points(points.clone());
            let out = ours(switches, &input).unwrap_or_else(|e| panic!("{context}: {e}"));
            let fail = |e: String| -> ! { panic!("{context}: {e}") };
            assert_eq!(
                out.points.as_deref(),
                Some(&points[..]),
                "{context}: points"
            );
            let triangles = zero_based(&out);
            check_mesh(&points, &triangles).unwrap_or_else(|e| fail(e));
            check_delaunay(&points, &triangles).unwrap_or_else(|e| fail(e));
            if !triangles.is_empty() {
                check_point_markers(None, &out).unwrap_or_else(|e| fail(e));
            }
        }
    }
}
