use crate::data::{Hooks, Input, Output};
use crate::options::{Options, SwitchSource};
use crate::pipeline::triangulate;

fn mesh(switches: &str, points: &[f64], segments: &[i32]) -> Output {
    let options = Options::parse(switches, SwitchSource::Library).unwrap();
    let input = Input {
        points,
        segments,
        ..Input::default()
    };
    triangulate(&options, &input, &Hooks::default()).unwrap().0
}

fn smallest_angle(out: &Output) -> f64 {
    let p = out.points.as_ref().unwrap();
    let pt = |v: i32| [p[2 * v as usize], p[2 * v as usize + 1]];
    let mut smallest = 180.0f64;
    for t in out.triangles.as_ref().unwrap().chunks(3) {
        for i in 0..3 {
            let (a, b, c) = (pt(t[i]), pt(t[(i + 1) % 3]), pt(t[(i + 2) % 3]));
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
            let angle = (u[0] * v[1] - u[1] * v[0])
                .abs()
                .atan2(u[0] * v[0] + u[1] * v[1])
                .to_degrees();
            smallest = smallest.min(angle);
        }
    }
    smallest
}

const SQUARE: [f64; 8] = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
const SQUARE_SEGMENTS: [i32; 8] = [0, 1, 1, 2, 2, 3, 3, 0];
/// An outline with a notch and a crossbar meeting a slanted stroke.
const SHAPE: [f64; 18] = [
    0.0, 0.0, 1.0, 0.0, 1.2, 2.0, 1.4, 0.0, 2.4, 0.0, 1.6, 3.0, 0.8, 3.0, 1.1, 1.0, 1.3, 1.0,
];
const SHAPE_SEGMENTS: [i32; 18] = [0, 1, 1, 7, 7, 8, 8, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 0];

#[test]
fn area_bound_holds() {
    let out = mesh("pza0.01Q", &SQUARE, &SQUARE_SEGMENTS);
    assert!(out.triangle_count >= 100, "{}", out.triangle_count);
}

#[test]
fn angle_bound_holds_up_to_the_guaranteed_angle_and_beyond() {
    for angle in [20.0, 25.0, 28.6, 30.0, 33.0] {
        let out = mesh(&format!("pzq{angle}Q"), &SHAPE, &SHAPE_SEGMENTS);
        assert!(
            smallest_angle(&out) >= angle - 1e-9,
            "q{angle}: {}",
            smallest_angle(&out)
        );
        assert!(out.warnings.is_empty(), "{:?}", out.warnings);
    }
}

#[test]
fn too_large_an_angle_stops_with_a_warning() {
    let out = mesh("pzq45Q", &SHAPE, &SHAPE_SEGMENTS);
    assert!(
        out.triangle_count > 20 && out.triangle_count < 10_000,
        "{}",
        out.triangle_count
    );
    assert!(
        out.warnings
            .iter()
            .any(|w| w.contains("guaranteed to terminate")),
        "{:?}",
        out.warnings
    );
}

#[test]
fn warnings_read_as_they_always_have() {
    use super::Warning;
    // The texts the library, the C ABI and the command line have always printed.
    let cases = [
        (Warning::Cancelled, "Refinement was cancelled; the mesh is valid but not refined."),
        (
            Warning::AngleNotReached {
                angle: 40.0,
                steiner_points: 438,
            },
            "A minimum angle of 40° is above 28.6°, the largest for which Delaunay refinement is guaranteed \
             to terminate, and this input needs more: refinement stopped after 438 Steiner points with some \
             angles below 40° but none below 28.6° (the mesh is valid).",
        ),
        (
            Warning::AngleNotReached {
                angle: 33.5,
                steiner_points: 7,
            },
            "A minimum angle of 33.5° is above 28.6°, the largest for which Delaunay refinement is guaranteed \
             to terminate, and this input needs more: refinement stopped after 7 Steiner points with some \
             angles below 33.5° but none below 28.6° (the mesh is valid).",
        ),
        (
            Warning::Runaway {
                steiner_points: 1_000_000,
            },
            "Refinement stopped after 1000000 Steiner points, far more than this input and its area bounds \
             account for: some of its features are too thin for the minimum angle (the mesh is valid; the S \
             switch sets a limit of your own).",
        ),
        (
            Warning::PrecisionExhausted { unsplit: 16 },
            "Refinement left 16 triangles or segments unsplit: the precision of floating-point numbers is \
             exhausted near some vertices. The mesh is valid but may have angles below the minimum there.",
        ),
        (
            Warning::BudgetSpent {
                limit: 5,
                unmet: 12,
            },
            "The S budget of 5 Steiner points was spent with 12 triangles or segments below the bounds left; \
             the mesh is valid but may have angles below the minimum or triangles above the maximum area.",
        ),
        (
            Warning::SegmentsKeptWhole { unsplit: 10 },
            "Refinement left 10 bad triangles unsplit: that needs new vertices on segments, which the Y \
             switch forbids. The mesh is valid but may have angles below the minimum or triangles above the \
             maximum area.",
        ),
    ];
    for (warning, text) in cases {
        assert_eq!(warning.to_string(), text);
    }
}
