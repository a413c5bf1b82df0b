//! Differential tests against Debian's Triangle 1.6 (`/usr/lib/libtriangle-1.6.so`): for point
//! sets where the Delaunay triangulation is unique, every output of our `triangulate` (through
//! its C ABI) equals Triangle's as sets: counts, which arrays are written, points, attributes,
//! markers, triangles (with orientation), neighbours, hull segments, edges and markers, and the
//! Voronoi diagram (vertices matched through their triangles, compared with a tolerance).
//!
//! Without the reference library these tests print a skip message, and fail in CI.

mod common;

use common::checks::{
    check_delaunay, check_mesh, check_neighbors, check_point_markers, check_voronoi, differences,
    zero_based, Match,
};
use common::examples;
use common::points::{self, Point};
use common::pslg_checks::{pslg_differences, MeshView};
use common::rng::SplitMix64;
use common::{ours, ours_with, reference, MeshInput, Triangulation};

/// Relative to the circumradius: Triangle and we may compute circumcentres differently.
const VORONOI_TOLERANCE: f64 = 1e-9;

fn assert_same(what: &str, switches: &str, ours: &Triangulation, theirs: &Triangulation) {
    assert_same_by(Match::Index, what, switches, ours, theirs);
}

fn assert_same_by(
    mode: Match,
    what: &str,
    switches: &str,
    ours: &Triangulation,
    theirs: &Triangulation,
) {
    let diffs = differences(ours, theirs, mode, VORONOI_TOLERANCE);
    assert!(
        diffs.is_empty(),
        "{what}, switches \"{switches}\": ours differs from Triangle's:\n  {}",
        diffs.join("\n  ")
    );
}

/// Points with two attributes each and markers (mostly 0, some set), reproducible.
fn decorated(points: Vec<Point>, seed: u64) -> MeshInput {
    let mut rng = SplitMix64::new(seed ^ 0xA77);
    let n = points.len();
    MeshInput {
        attributes: (0..2 * n)
            .map(|_| (rng.next_f64() * 100.0).round() / 4.0)
            .collect(),
        attribute_count: 2,
        markers: Some((0..n).map(|_| [0, 0, 0, 2, -3][rng.below(5)]).collect()),
        ..MeshInput::from_points(points)
    }
}

#[test]
fn triangle_sets_match_on_uniform_points() {
    let Some(triangle) = reference() else { return };
    // With `z` the large ones (two threads where there are two cores) take the outputs' path
    // that keeps the corners as they are and fills the ghosts' slots from the end.
    let cases: [(&str, points::Generator, usize, u64, &str); 8] = [
        ("uniform", points::uniform, 10, 1, "Q"),
        ("uniform", points::uniform, 100, 2, "Q"),
        ("uniform", points::uniform, 1000, 3, "Q"),
        ("uniform", points::uniform, 10_000, 4, "Q"),
        ("uniform", points::uniform, 100_000, 5, "Q"),
        ("uniform", points::uniform, 100_000, 5, "Qz"),
        ("clustered", points::clustered, 60_000, 6, "Qz"),
        ("tiny", points::tiny, 30_000, 7, "Qz"),
    ];
    for (name, generate, n, seed, switches) in cases {
        let input = MeshInput::from_points(generate(n, seed));
        let theirs = triangle.triangulate(switches, &input);
        let ours = ours(switches, &input).unwrap_or_else(|e| panic!("{n} points: {e}"));
        assert_eq!(
            theirs.counts.triangles as usize,
            theirs.triangle_triples().len()
        );
        assert!(theirs.counts.triangles > 0);
        assert_same(
            &format!("{n} {name} points (seed {seed})"),
            switches,
            &ours,
            &theirs,
        );
    }
}

/// The benchmark's distributions (issue 38: Kuzmin's, a dense patch in a square, clusters of
/// mixed spreads, ...), where the insertion order has to follow the points' density down many
/// orders of magnitude: the triangle sets are Triangle's, on one thread (below the two-core
/// threshold), on two where there are two cores, and in the order of `i`.
#[test]
fn triangle_sets_match_on_every_distribution() {
    let Some(triangle) = reference() else { return };
    for (name, generate) in points::distributions() {
        for (n, switches) in [(5_000, "Q"), (20_000, "Qz"), (20_000, "Qi")] {
            let input = MeshInput::from_points(generate(n, 38));
            let theirs = triangle.triangulate(switches, &input);
            let ours = ours(switches, &input).unwrap_or_else(|e| panic!("{n} {name}: {e}"));
            assert!(theirs.counts.triangles > 0);
            assert_same(&format!("{n} {name} points"), switches, &ours, &theirs);
        }
    }
}

/// Every switch of this slice, alone and combined, on small inputs in general position.
const SWITCH_SETS: &[&str] = &[
    "Q", "Qz", "Qc", "Qcz", "Qe", "Qez", "Qn", "Qnz", "Qv", "Qvz", "Qzcenv", "Qcenv", "QB", "QcBe",
    "QzcenvB", "QN", "QNcev", "QE", "QEcev", "QP", "QcP", "Qj", "Qjzcenv", "Qi", "Qizcenv", "QF",
    "QFzcenv", "Ql", "Qlzcenv", "QI", "QOzcenv",
];

#[test]
fn all_outputs_match_on_small_inputs() {
    let Some(triangle) = reference() else { return };
    let generators: [(&str, points::Generator); 3] = [
        ("uniform", points::uniform),
        ("clustered", points::clustered),
        ("tiny", points::tiny),
    ];
    for (name, generate) in generators {
        for (n, seed) in [(3, 11), (4, 12), (5, 13), (8, 14), (31, 15), (300, 16)] {
            let input = decorated(generate(n, seed), seed);
            for switches in SWITCH_SETS {
                let theirs = triangle.triangulate(switches, &input);
                let ours = ours(switches, &input)
                    .unwrap_or_else(|e| panic!("{name} {n}, \"{switches}\": {e}"));
                assert_same(
                    &format!("{n} {name} points (seed {seed})"),
                    switches,
                    &ours,
                    &theirs,
                );
            }
        }
    }
}

#[test]
fn outputs_match_without_vorout() {
    let Some(triangle) = reference() else { return };
    let input = decorated(points::uniform(50, 21), 21);
    for switches in ["Q", "Qzcen", "QcenB"] {
        let theirs = triangle.triangulate_with(switches, &input, false);
        let ours = ours_with(switches, &input, false).unwrap();
        assert!(ours.voronoi.is_none());
        assert_same("50 uniform points, NULL vorout", switches, &ours, &theirs);
    }
}

/// Points with duplicates: the same mesh as Triangle's up to which copy of a duplicate is kept
/// (Triangle's default algorithm keeps whichever its sort puts first, so that cannot be matched;
/// its `i` and `F` keep the first copy), and both follow the same marker rule.
#[test]
fn duplicates_match() {
    let Some(triangle) = reference() else { return };
    for (n, seed) in [(6, 31), (30, 32), (400, 33)] {
        let mut rng = SplitMix64::new(seed);
        let points = points::duplicated(n, seed);
        let input = MeshInput {
            // Attributes follow the coordinates, so that every copy of a point carries the same.
            attributes: points
                .iter()
                .flat_map(|p| [p[0] + 2.0 * p[1], 3.0 * p[0]])
                .collect(),
            attribute_count: 2,
            markers: Some((0..n).map(|_| [0, 0, 0, 2, -3][rng.below(5)]).collect()),
            ..MeshInput::from_points(points)
        };
        for switches in ["Q", "Qzcenv", "Qj", "Qjzcenv", "QjB", "Qi", "QF"] {
            let what = format!("{n} points with duplicates (seed {seed})");
            let theirs = triangle.triangulate(switches, &input);
            let ours =
                ours(switches, &input).unwrap_or_else(|e| panic!("{what}, \"{switches}\": {e}"));
            assert_same_by(Match::Coordinates, &what, switches, &ours, &theirs);
            if !switches.contains('j') && !switches.contains('B') {
                check_point_markers(input.markers.as_deref(), &theirs)
                    .unwrap_or_else(|e| panic!("{what}, Triangle \"{switches}\": {e}"));
                check_point_markers(input.markers.as_deref(), &ours)
                    .unwrap_or_else(|e| panic!("{what}, ours \"{switches}\": {e}"));
            }
        }
    }
}

/// All points on one line: no triangle and no error. (Triangle crashes with `c` here, so that
/// switch is not compared.) Triangle's markers are an artefact of its algorithms: the default
/// marks every point 1 except the lexicographically last one, `i` marks all of them 1; we accept
/// either Triangle's markers or all points marked as lying on the (degenerate) hull.
#[test]
fn collinear_inputs_match() {
    let Some(triangle) = reference() else { return };
    let input = decorated(points::collinear(7, 41), 41);
    for switches in ["Q", "Qzenv", "Qienv", "Qj", "QF"] {
        let theirs = triangle.triangulate(switches, &input);
        let ours =
            ours(switches, &input).unwrap_or_else(|e| panic!("collinear, \"{switches}\": {e}"));
        let all_on_hull: Vec<i32> = input
            .markers
            .as_ref()
            .unwrap()
            .iter()
            .map(|&m| if m == 0 { 1 } else { m })
            .collect();
        assert!(
            ours.point_markers == theirs.point_markers || ours.point_markers.as_deref() == Some(&all_on_hull[..]),
            "collinear points, \"{switches}\": markers {:?}; Triangle gives {:?}, all on the hull would be {all_on_hull:?}",
            ours.point_markers,
            theirs.point_markers
        );
        let without_markers = |t: &Triangulation| Triangulation {
            point_markers: None,
            ..t.clone()
        };
        assert_same(
            "collinear points",
            switches,
            &without_markers(&ours),
            &without_markers(&theirs),
        );
    }
    for (name, input) in [
        (
            "nearly collinear",
            decorated(points::nearly_collinear(9, 42), 42),
        ),
        (
            "nearly collinear, large",
            decorated(points::nearly_collinear(200, 43), 43),
        ),
    ] {
        for switches in ["Q", "Qzcenv", "Qicenv", "QFcenv", "Qj"] {
            let theirs = triangle.triangulate(switches, &input);
            let ours =
                ours(switches, &input).unwrap_or_else(|e| panic!("{name}, \"{switches}\": {e}"));
            assert_same(name, switches, &ours, &theirs);
        }
    }
}

#[test]
fn zero_based_and_one_based_differ_by_one() {
    let input = decorated(points::uniform(200, 51), 51);
    let zero = ours("Qzcenv", &input).unwrap();
    let one = ours("Qcenv", &input).unwrap();
    let shift = |v: &[i32]| {
        v.iter()
            .map(|&i| if i == -1 { -1 } else { i + 1 })
            .collect::<Vec<_>>()
    };
    assert_eq!((zero.base, one.base), (0, 1));
    assert_eq!(zero.triangles.as_deref().unwrap().iter().min(), Some(&0));
    assert_eq!(
        shift(zero.triangles.as_deref().unwrap()),
        one.triangles.clone().unwrap()
    );
    assert_eq!(
        shift(zero.neighbors.as_deref().unwrap().as_flattened()),
        one.neighbors.as_deref().unwrap().as_flattened()
    );
    assert_eq!(
        shift(zero.segments.as_deref().unwrap().as_flattened()),
        one.segments.as_deref().unwrap().as_flattened()
    );
    assert_eq!(
        shift(zero.edges.as_deref().unwrap().as_flattened()),
        one.edges.as_deref().unwrap().as_flattened()
    );
    let (vz, vo) = (zero.voronoi.unwrap(), one.voronoi.unwrap());
    assert_eq!(
        shift(vz.edges.as_deref().unwrap().as_flattened()),
        vo.edges.as_deref().unwrap().as_flattened()
    );
    assert_eq!(vz.points, vo.points);
    assert_eq!(zero.point_markers, one.point_markers);
}

/// The property checks of tests/delaunay_properties.rs hold for Triangle's own output: they
/// check Triangle's conventions, not ours.
#[test]
fn reference_satisfies_the_property_checks() {
    let Some(triangle) = reference() else { return };
    for (name, generate) in points::all_generators() {
        for (n, seed) in [(5, 61), (40, 62), (700, 63)] {
            let points = generate(n, seed);
            let input = MeshInput::from_points(points.clone());
            // Triangle crashes on collinear input with `c`.
            let switches = if name == "collinear" {
                "Qzenv"
            } else {
                "Qzcenv"
            };
            let out = triangle.triangulate(switches, &input);
            let triangles = zero_based(&out);
            let context = format!("Triangle on {n} {name} points (seed {seed})");
            let stats =
                check_mesh(&points, &triangles).unwrap_or_else(|e| panic!("{context}: {e}"));
            check_delaunay(&points, &triangles).unwrap_or_else(|e| panic!("{context}: {e}"));
            check_neighbors(&triangles, out.neighbors.as_deref().unwrap(), 0)
                .unwrap_or_else(|e| panic!("{context}: {e}"));
            if !triangles.is_empty() {
                check_voronoi(&points, &triangles, out.voronoi.as_ref().unwrap(), 0)
                    .unwrap_or_else(|e| panic!("{context}: {e}"));
            }
            if !triangles.is_empty() {
                check_point_markers(None, &out).unwrap_or_else(|e| panic!("{context}: {e}"));
            }
            assert_eq!(
                out.counts.segments as usize, stats.boundary_edges,
                "{context}: numberofsegments"
            );
            assert_eq!(
                out.segments.as_ref().map_or(0, |s| s.len()),
                if name == "collinear" {
                    0
                } else {
                    stats.boundary_edges
                }
            );
        }
    }
}

/// Triangle's own example `.node` files (read from the PyPI `triangle` package's data
/// directory; several are grids with cocircular points): the same mesh as Triangle's where the
/// Delaunay triangulation is unique, the same vertices and triangle counts in the ambiguous
/// regions, the same markers, edges and neighbours as far as they are determined; and every
/// output, the Voronoi diagram included, equal where the whole triangulation is unique.
#[test]
fn triangle_example_node_files_match() {
    let Some(triangle) = reference() else { return };
    let mut unique = 0;
    for file in examples::example_files(&examples::data_dir()) {
        // Point sets, and the vertices of the shipped meshes.
        let name = file.name;
        let input = MeshInput::from_points(file.input.points);
        // The large file (greenland, 33 343 vertices) with one switch set: the debug build of
        // the checks is slow.
        let sets: &[&str] = if input.points.len() > 5000 {
            &["Qz"]
        } else {
            &["Q", "Qz", "QzcenQ", "QjzeQ", "QBQ"]
        };
        for switches in sets {
            let theirs = triangle.triangulate(switches, &input);
            let ours =
                ours(switches, &input).unwrap_or_else(|e| panic!("{name}, \"{switches}\": {e}"));
            let diffs = pslg_differences(&input, &ours, &theirs);
            assert!(
                diffs.is_empty(),
                "{name}, \"{switches}\": ours differs from Triangle's:\n  {}",
                diffs.join("\n  ")
            );
        }
        let theirs = triangle.triangulate("Qzcenv", &input);
        let view = MeshView::of(&theirs).unwrap_or_else(|e| panic!("{name}, Triangle's: {e}"));
        if view.cocircular_edges().is_empty() {
            unique += 1;
            let ours = ours("Qzcenv", &input).unwrap();
            assert_same(&name, "Qzcenv", &ours, &theirs);
        }
    }
    assert!(
        unique >= 3,
        "only {unique} example files have a unique triangulation"
    );
}
