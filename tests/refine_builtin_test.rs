//! Switch `u` with no test registered (issue 37, point 3): Triangle then applies its built-in
//! test, which Debian's library and program and the PyPI package all compile in, and so do we
//! (the C ABI's `triangulate` with no callback set, `triangulate_reentrant` with a NULL one, the
//! command line). The test, as observed on the reference: a triangle is unsuitable when its
//! longest edge, squared, exceeds `0.02 + 0.05 (ox² + oy²)`, `(ox, oy)` being its origin (the
//! first vertex the test is given; with `r`, an input triangle's first corner).
//!
//! - One input triangle refined with `ru`, its longest edge a few units in the last place either
//!   side of the threshold, for several origins and each rotation of its corners: ours splits it
//!   exactly when Triangle does (the threshold agrees bit for bit, and the origin is the first
//!   corner in both).
//! - `pu` and `pqu` on squares (unit, shifted, scaled, centred on the origin, far from it), an
//!   L-shape and a triangle: every output triangle of both programs passes the test with one of
//!   its corners as origin (which corner Triangle gives as origin when it tests a triangle is its
//!   own affair), both meshes cover the domain, and our count lies within 20% of Triangle's.
//!   The counts are not equal: refinement order and which corner is a triangle's origin differ
//!   (measured, `pu`: unit square Triangle 117, ours 137; ×3 square 275 / 325; [-1, 1]² 492 /
//!   566; L-shape 195 / 221; triangle 129 / 118; [-3, -1] × [-2, 0] 100 / 104; the square at
//!   (2, 1) 16 / 14; at (10, -5) 2 / 2).
//! - The global callback: set, it replaces the built-in test; cleared, the built-in test is back.
//! - The command line: `-pu` refines, as the library does.
//!
//! Without the reference library or program these tests print a skip message (and fail in CI).

mod cli_support;
mod common;

use common::call::{MeshInput, Triangulation};
use common::points::Point;
use common::quality::ours_reentrant;
use common::reference;

/// Our count must lie within this fraction of Triangle's.
const COUNT_TOLERANCE: f64 = 0.20;

/// The built-in test as observed on the reference (written here on its own, not the library's).
fn unsuitable(origin: Point, dest: Point, apex: Point) -> bool {
    let square = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    let longest = square(origin, dest)
        .max(square(dest, apex))
        .max(square(apex, origin));
    longest > 0.05 * square(origin, [0.0, 0.0]) + 0.02
}

/// A closed polygon as a PSLG (0-based, for switches with `z`).
fn polygon(points: &[Point]) -> MeshInput {
    let n = points.len() as i32;
    MeshInput {
        segments: (0..n).map(|i| [i, (i + 1) % n]).collect(),
        ..MeshInput::from_points(points.to_vec())
    }
}

fn square(x: f64, y: f64, side: f64) -> Vec<Point> {
    vec![[x, y], [x + side, y], [x + side, y + side], [x, y + side]]
}

fn domains() -> Vec<(&'static str, Vec<Point>)> {
    vec![
        ("unit square", square(0.0, 0.0, 1.0)),
        ("square at (2, 1)", square(2.0, 1.0, 1.0)),
        ("square of side 3", square(0.0, 0.0, 3.0)),
        ("square [-1, 1]²", square(-1.0, -1.0, 2.0)),
        ("square [-3, -1] × [-2, 0]", square(-3.0, -2.0, 2.0)),
        ("square at (10, -5)", square(10.0, -5.0, 1.0)),
        (
            "L-shape",
            vec![
                [0.0, 0.0],
                [2.0, 0.0],
                [2.0, 1.0],
                [1.0, 1.0],
                [1.0, 2.0],
                [0.0, 2.0],
            ],
        ),
        ("triangle", vec![[0.0, 0.0], [2.0, 0.0], [0.7, 1.5]]),
    ]
}

fn polygon_area(points: &[Point]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|i| {
            let (p, q) = (points[i], points[(i + 1) % n]);
            p[0] * q[1] - p[1] * q[0]
        })
        .sum::<f64>()
}

fn corners(mesh: &Triangulation) -> Vec<[Point; 3]> {
    let points = mesh.points.as_deref().unwrap_or_default();
    mesh.triangle_triples()
        .iter()
        .map(|t| t.map(|v| points[(v - mesh.base) as usize]))
        .collect()
}

/// Every triangle is counter-clockwise, passes the built-in test with one of its corners as
/// origin, and the triangles cover `area`.
fn check(context: &str, mesh: &Triangulation, area: f64) {
    let mut total = 0.0;
    for [a, b, c] in corners(mesh) {
        let twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert!(
            twice > 0.0,
            "{context}: triangle {a:?} {b:?} {c:?} is not counter-clockwise"
        );
        total += 0.5 * twice;
        assert!(
            !(unsuitable(a, b, c) && unsuitable(b, c, a) && unsuitable(c, a, b)),
            "{context}: triangle {a:?} {b:?} {c:?} fails the built-in test from every corner"
        );
    }
    assert!(
        (total - area).abs() <= 1e-12 * area,
        "{context}: the triangles cover {total}, the domain {area}"
    );
}

#[test]
fn one_triangle_splits_exactly_where_triangle_splits_it() {
    let Some(triangle) = reference() else { return };
    let mut cases = 0;
    for origin in [
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 0.3],
        [-2.7, 1.1],
        [0.37, -5.3],
        [13.1, 7.7],
    ] {
        let [ox, oy] = origin;
        let threshold = (0.05 * (ox * ox + oy * oy) + 0.02_f64).sqrt();
        for ulps in -6i64..=6 {
            let h = f64::from_bits((threshold.to_bits() as i64 + ulps) as u64);
            // The longest edge goes up from the origin; the apex, left of it, is nearer.
            let points = vec![[ox, oy], [ox, oy + h], [ox - 0.05 * h, oy + 0.5 * h]];
            for rotation in 0..3 {
                let order: Vec<i32> = (0..3).map(|k| (rotation + k) % 3).collect();
                let input = MeshInput {
                    triangles: order.clone(),
                    corners: 3,
                    ..MeshInput::from_points(points.clone())
                };
                let theirs = triangle.triangulate("ruzQ", &input);
                let ours =
                    ours_reentrant("ruzQ", &input, None, std::ptr::null_mut(), std::ptr::null())
                        .unwrap_or_else(|e| panic!("{points:?}: {e}"));
                let first = points[order[0] as usize];
                let (dest, apex) = (points[order[1] as usize], points[order[2] as usize]);
                let expected = unsuitable(first, dest, apex);
                let split = |mesh: &Triangulation| mesh.counts.triangles > 1;
                assert_eq!(
                    split(&theirs),
                    expected,
                    "Triangle on {points:?} ({ulps} ulps, first corner {first:?})"
                );
                assert_eq!(
                    split(&ours),
                    expected,
                    "ours on {points:?} ({ulps} ulps, first corner {first:?})"
                );
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 6 * 13 * 3);
}

#[test]
fn u_without_a_test_refines_like_triangle() {
    let Some(triangle) = reference() else { return };
    let mut failures = Vec::new();
    for (name, points) in domains() {
        let input = polygon(&points);
        let area = polygon_area(&points);
        for switches in ["puzQ", "pquzQ"] {
            let context = format!("{name}, \"{switches}\"");
            let theirs = triangle.triangulate(switches, &input);
            let ours = ours_reentrant(
                switches,
                &input,
                None,
                std::ptr::null_mut(),
                std::ptr::null(),
            )
            .unwrap_or_else(|e| panic!("{context}: {e}"));
            check(&format!("{context}, Triangle"), &theirs, area);
            check(&format!("{context}, ours"), &ours, area);
            let (t, o) = (theirs.counts.triangles, ours.counts.triangles);
            println!("{context}: {o} triangles (Triangle {t})");
            if (o as f64 - t as f64).abs() > COUNT_TOLERANCE * t as f64 {
                failures.push(format!("{context}: {o} triangles, Triangle {t}"));
            }
        }
    }
    assert!(failures.is_empty(), "counts apart: {failures:#?}");
}

extern "C" fn never_unsuitable(_: f64, _: f64, _: f64, _: f64, _: f64, _: f64, _: f64) -> i32 {
    0
}

/// The only test of this file that touches the global callback (the others pass theirs per call).
#[test]
fn the_global_callback_replaces_the_built_in_test_and_clearing_it_restores_it() {
    let input = polygon(&square(0.0, 0.0, 1.0));
    let per_call =
        ours_reentrant("puzQ", &input, None, std::ptr::null_mut(), std::ptr::null()).expect("pu");
    assert!(per_call.counts.triangles > 100, "{:?}", per_call.counts);
    let global =
        |label: &str| common::ours("puzQ", &input).unwrap_or_else(|e| panic!("{label}: {e}"));
    let before = global("no callback set");
    assert_eq!(before.points, per_call.points);
    assert_eq!(before.triangles, per_call.triangles);
    triangle_rs::ffi::triunsuitable_callback(Some(never_unsuitable));
    let registered = global("a callback set");
    triangle_rs::ffi::triunsuitable_callback(None);
    assert_eq!(
        registered.counts.triangles, 2,
        "the registered test finds nothing unsuitable"
    );
    let after = global("the callback cleared");
    assert_eq!(after.triangles, per_call.triangles);
}

#[test]
fn the_command_line_applies_the_built_in_test() {
    let square_poly = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n";
    let triangles = |program: &std::path::Path| {
        let dir = cli_support::TempDir::new("builtin-u");
        dir.write("square.poly", square_poly);
        let run = cli_support::run(program, dir.path(), &["-puQ", "square.poly"]);
        assert!(run.ok(), "{}: {}", program.display(), run.stderr);
        let ele = dir.read("square.1.ele");
        let first: usize = ele
            .split_whitespace()
            .next()
            .and_then(|n| n.parse().ok())
            .expect("a triangle count");
        first
    };
    let ours = triangles(&cli_support::ours());
    // The program is the library: the same mesh as the C ABI's.
    let library = ours_reentrant(
        "puzQ",
        &polygon(&square(0.0, 0.0, 1.0)),
        None,
        std::ptr::null_mut(),
        std::ptr::null(),
    )
    .expect("pu");
    assert_eq!(ours, library.counts.triangles as usize);
    let Some(reference) = cli_support::reference() else {
        return;
    };
    let theirs = triangles(&reference);
    assert_eq!(theirs, 117, "Triangle's -pu on the unit square");
    assert!(
        (ours as f64 - theirs as f64).abs() <= COUNT_TOLERANCE * theirs as f64,
        "ours {ours}, Triangle {theirs}"
    );
}
