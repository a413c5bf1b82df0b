//! Differential tests of our Delaunay refinement against Debian's Triangle 1.6
//! (`/usr/lib/libtriangle-1.6.so`), on the classic shapes of tests/data/shapes/, random
//! star-shaped polygons with holes and islands (`common::pslg::polygon_with_holes`), the square
//! with a circular hole of benches/refine.rs and random star polygons (`star_polygon`), all in
//! the unit box (`common::quality::normalized`), so that one absolute area bound suits every
//! input.
//!
//! Refinement has no unique answer, so the two meshes are compared by what they achieve. For
//! each input and switches (`pq`, `pq30`, `pa0.01`, `pq30a0.001`, `paA`, `pD`, `pY`, `pYY`,
//! `pqY`, `pqYY`, `po2`, `pqo2`, and `rpa` on the `pqA` mesh of the input made first by Triangle
//! or by us, fed back with its segments, region attributes and a `trianglearealist`):
//! - our triangle count is within ±10% of Triangle's;
//! - with `q`, our smallest angle is at least Triangle's (minus 1e-9°);
//! - every triangle within its area bound: global, regional (`paA`), or per input triangle
//!   (`rpa`: the bounds go by region, some ≤ 0 = unconstrained; the refinement keeps the
//!   regions' segments, so every output triangle lies in one region, known by its attribute);
//! - both meshes are valid meshes of the domain (its area), constrained Delaunay, every input
//!   segment a chain of output segments, and follow Triangle's marker rules;
//! - `D`: truly Delaunay, circumcentres in the domain; `Y` / `YY`: no new vertex on boundary /
//!   any segments; `o2`: midpoint nodes exact, opposite their corners, one per edge, shared.
//!
//! Every check runs on Triangle's output too, which keeps the checks honest. Triangle calls
//! `exit()` on input it rejects and may loop above 28.6°: only inputs it handles are passed.
//! The cases where we differ from Triangle beyond these bounds (or fail a check) are each an
//! `#[ignore]`d test of its own, with the numbers, at the end of this file; the `report` test
//! prints every case's numbers. Without the reference library these tests print a skip
//! message, and fail in CI.

mod common;

use std::collections::HashSet;

use common::call::{MeshInput, Triangulation};
use common::pslg::{self, Pslg};
use common::pslg_checks::{
    check_constrained_delaunay, check_markers, edge_marker_rule, segment_chains, MeshView,
};
use common::quality::{
    area_bound, check_areas, check_conforming_delaunay, check_second_order,
    new_vertices_on_segments, normalized, smallest_angle,
};
use common::reference::Reference;
use common::{ours, reference};

/// Our triangle count must lie within this fraction of Triangle's.
const COUNT_TOLERANCE: f64 = 0.10;

/// Tolerance on the comparison of the smallest angles, in degrees.
const ANGLE_SLACK: f64 = 1e-9;

/// `rpa`: the per-triangle area bound of the previous mesh's triangles in the unit box, by region.
const PREVIOUS_MESH_AREA: f64 = 0.002;

/// An input of the differential tests, scaled into the unit box.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Input {
    /// A classic shape of tests/data/shapes/.
    Shape(&'static str),
    /// `polygon_with_holes(seed)`, with its regional area bounds tightened eightfold so that
    /// `paA` refines the islands (the rest of the polygon stays unconstrained).
    Polygon(u64),
    /// The refinement benchmark's square with a circular hole of this many segments.
    SquareWithHole(usize),
    /// The refinement benchmark's random star-shaped polygon: vertices, seed.
    Star(usize, u64),
}

impl Input {
    fn pslg(self) -> Pslg {
        match self {
            Input::Shape(name) => normalized(pslg::shape(name)),
            Input::Polygon(seed) => {
                let mut pslg = normalized(pslg::polygon_with_holes(seed));
                for region in &mut pslg.input.regions {
                    region[3] /= 8.0;
                }
                pslg
            }
            Input::SquareWithHole(segments) => pslg::square_with_hole(segments),
            Input::Star(n, seed) => normalized(pslg::star_polygon_pslg(n, seed)),
        }
    }
}

/// How an input is meshed.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Run {
    /// One call with these switches (`Q` appended; indices 1-based).
    Switches(&'static str),
    /// `rpa` on the `pqA` mesh of the input, made first by Triangle (`true`) or by us: every
    /// library refines the same previous mesh, with per-triangle bounds by region.
    RefinePrevious { by_triangle: bool },
}

/// The switch sets compared on every input.
const SWITCHES: &[&str] = &[
    "pq", "pq30", "pa0.01", "pq30a0.001", "paA", "pD", "pY", "pYY", "pqY", "pqYY", "po2", "pqo2",
];

fn shapes() -> Vec<Input> {
    pslg::SHAPES.iter().map(|&name| Input::Shape(name)).collect()
}

fn random_polygons() -> Vec<Input> {
    (1..=12).map(Input::Polygon).collect()
}

/// Every switch set and both `rpa` runs on each of `inputs`.
fn all_runs(inputs: &[Input]) -> Vec<(Input, Run)> {
    let runs: Vec<Run> = SWITCHES
        .iter()
        .map(|&s| Run::Switches(s))
        .chain([true, false].map(|by_triangle| Run::RefinePrevious { by_triangle }))
        .collect();
    inputs
        .iter()
        .flat_map(|&input| runs.iter().map(move |&run| (input, run)))
        .collect()
}

/// The number after `a` in `switches`, if any (`pq30a0.001` → 0.001).
fn global_area(switches: &str) -> Option<f64> {
    let at = switches.find('a')?;
    let number: String = switches[at + 1..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    number.parse().ok()
}

/// `a` without a number: regional (`p`) or per-triangle (`r`) bounds.
fn variable_area(switches: &str) -> bool {
    switches
        .char_indices()
        .any(|(i, c)| c == 'a' && !switches[i + 1..].starts_with(|d: char| d.is_ascii_digit() || d == '.'))
}

/// The bound of a previous mesh's triangles with region attribute `attribute` (`None`: the mesh
/// has no regions): some regions unconstrained (−1 and 0), the others at two bounds.
fn region_bound(attribute: Option<f64>) -> f64 {
    match attribute {
        None => PREVIOUS_MESH_AREA,
        Some(a) => [PREVIOUS_MESH_AREA, PREVIOUS_MESH_AREA / 3.0, -1.0, 0.0][a as usize % 4],
    }
}

/// The output points of our unrefined constrained Delaunay triangulation (input vertices and
/// crossings): `Y` and `YY` allow only these on segments.
fn unrefined_points(pslg: &Pslg) -> HashSet<[u64; 2]> {
    let out = ours("pzQ", &pslg.input).unwrap_or_else(|e| panic!("{}: {e}", pslg.name));
    out.points
        .unwrap_or_default()
        .iter()
        .map(|p| p.map(f64::to_bits))
        .collect()
}

/// What a refined mesh achieved.
#[derive(Clone, Copy, Debug)]
struct Measures {
    triangles: usize,
    smallest_angle: f64,
}

/// Checks everything one output (`who`'s) of `pslg` with `switches` must satisfy, whoever made
/// it; panics with the reason otherwise.
fn check_output(
    pslg: &Pslg,
    switches: &str,
    who: &str,
    out: &Triangulation,
    unrefined: &HashSet<[u64; 2]>,
) -> Measures {
    let context = format!("{}, \"{switches}\", {who} mesh", pslg.name);
    let fail = |e: String| -> ! { panic!("{context}: {e}") };
    let mesh = MeshView::of(out).unwrap_or_else(|e| fail(e));
    assert!(!mesh.triangles.is_empty(), "{context}: no triangle");
    check_constrained_delaunay(&mesh).unwrap_or_else(|e| fail(e));
    let input = &pslg.input;
    let chains = segment_chains(input, &mesh, false).unwrap_or_else(|e| fail(e));
    if let Some(expected) = pslg.expected_area(switches) {
        let found = mesh.area();
        assert!(
            (found - expected).abs() <= 1e-9 * expected.abs(),
            "{context}: the triangles' area is {found}, the domain's {expected}"
        );
    }
    let n = input.points.len();
    check_markers(input, &mesh, &chains, &|v| (v < n).then_some(v)).unwrap_or_else(|e| fail(e));

    // Area bounds.
    let global = global_area(switches);
    if switches.starts_with('r') {
        let regions = out.counts.triangle_attributes > 0;
        let attributes = out.triangle_attributes.clone().unwrap_or_default();
        let width = out.counts.triangle_attributes.max(1) as usize;
        let bound = |t: usize| {
            let local = region_bound(regions.then(|| attributes[t * width]));
            (local > 0.0).then_some(local)
        };
        check_areas(&mesh, &bound).unwrap_or_else(|e| fail(e));
    } else if global.is_some() || variable_area(switches) {
        let bound = area_bound(input, out, global, variable_area(switches));
        check_areas(&mesh, &bound).unwrap_or_else(|e| fail(e));
    }

    if switches.contains('D') {
        check_conforming_delaunay(&mesh).unwrap_or_else(|e| fail(e));
    }
    if switches.contains('Y') {
        let both = switches.contains("YY");
        let forbidden = new_vertices_on_segments(&mesh, &chains, unrefined, !both);
        assert!(
            forbidden.is_empty(),
            "{context}: new vertices on {} segments (input segment, place): {forbidden:?}",
            if both { "any" } else { "boundary" }
        );
    }
    if switches.contains("o2") {
        let edge_marker = edge_marker_rule(input, &mesh, &chains);
        check_second_order(&mesh, n, &edge_marker).unwrap_or_else(|e| fail(e));
    }
    Measures {
        triangles: mesh.triangles.len(),
        smallest_angle: smallest_angle(&mesh),
    }
}

/// `pslg`'s `pqA` mesh by Triangle (`by_triangle`) or by us, as the input of `rpa`
/// (zero-based): its vertices with markers and attributes, its segments with markers, its
/// triangles with their region attribute, and per triangle the bound [`region_bound`] of its
/// region.
fn previous_mesh(pslg: &Pslg, by_triangle: bool, triangle: &Reference) -> Pslg {
    let switches = "pqAQ";
    let input = pslg.input_for(switches);
    let (who, first) = if by_triangle {
        ("Triangle", triangle.triangulate(switches, &input))
    } else {
        let out = ours(switches, &input).unwrap_or_else(|e| panic!("{}, \"{switches}\": {e}", pslg.name));
        ("us", out)
    };
    let area = MeshView::of(&first)
        .unwrap_or_else(|e| panic!("{}, \"{switches}\" by {who}: {e}", pslg.name))
        .area();
    let base = first.base;
    let k = first.counts.triangle_attributes.max(0) as usize;
    let attributes = first.triangle_attributes.clone().unwrap_or_default();
    let triangles: Vec<[i32; 3]> = first.triangle_triples();
    let areas = (0..triangles.len())
        .map(|t| region_bound((k > 0).then(|| attributes[t * k])))
        .collect();
    let input = MeshInput {
        points: first.points.clone().unwrap_or_default(),
        attributes: first.point_attributes.clone().unwrap_or_default(),
        attribute_count: first.counts.point_attributes.max(0) as usize,
        markers: first.point_markers.clone(),
        segments: first
            .segments
            .iter()
            .flatten()
            .map(|s| s.map(|v| v - base))
            .collect(),
        segment_markers: first.segment_markers.clone(),
        triangles: triangles.iter().flatten().map(|v| v - base).collect(),
        corners: 3,
        triangle_attributes: attributes,
        triangle_attribute_count: k,
        triangle_areas: Some(areas),
        ..MeshInput::default()
    };
    Pslg {
        area: Some(area),
        ..Pslg::new(format!("{}, its \"pqA\" mesh by {who}", pslg.name), input)
    }
}

/// Ours and Triangle's on `input` meshed by `run`: both checked by [`check_output`] (a failure
/// panics); `Ok` or `Err` (ours differs from Triangle's by more than the differential bounds)
/// with the numbers. `None` without the reference library.
fn differential(input: Input, run: Run) -> Option<Result<String, String>> {
    let triangle = reference()?;
    let (pslg, switches) = match run {
        Run::Switches(switches) => (input.pslg(), switches),
        Run::RefinePrevious { by_triangle } => {
            (previous_mesh(&input.pslg(), by_triangle, triangle), "rpa")
        }
    };
    assert!(!pslg.ours_only, "{}: Triangle cannot take this input", pslg.name);
    let quiet = format!("{switches}Q");
    let raw = pslg.input_for(&quiet);
    let context = format!("{}, \"{quiet}\"", pslg.name);
    let theirs = triangle.triangulate(&quiet, &raw);
    let ours = ours(&quiet, &raw).unwrap_or_else(|e| panic!("{context}: {e}"));
    let unrefined = if switches.contains('Y') {
        unrefined_points(&pslg)
    } else {
        HashSet::new()
    };
    let t = check_output(&pslg, switches, "Triangle's", &theirs, &unrefined);
    let o = check_output(&pslg, switches, "our", &ours, &unrefined);
    let ratio = o.triangles as f64 / t.triangles as f64;
    let numbers = format!(
        "{context}: {} triangles (Triangle {}, ratio {ratio:.3}), smallest angle {:.4}° (Triangle {:.4}°)",
        o.triangles, t.triangles, o.smallest_angle, t.smallest_angle
    );
    let count_ok = (o.triangles as f64 - t.triangles as f64).abs()
        <= COUNT_TOLERANCE * t.triangles as f64;
    let angle_ok = !switches.contains('q') || o.smallest_angle >= t.smallest_angle - ANGLE_SLACK;
    Some(if count_ok && angle_ok {
        Ok(numbers)
    } else {
        Err(numbers)
    })
}

/// Runs [`differential`] on every case but the [`DIVERGENT`] ones, and fails with the list of
/// those that differ.
fn all_match(cases: Vec<(Input, Run)>) {
    let cases: Vec<(Input, Run)> = cases
        .into_iter()
        .filter(|case| !DIVERGENT.contains(case))
        .collect();
    assert!(!cases.is_empty(), "every case is a divergent one: nothing to compare");
    let mut failures = Vec::new();
    for &(input, run) in &cases {
        match differential(input, run) {
            None => return,
            Some(Ok(_)) => {}
            Some(Err(numbers)) => failures.push(numbers),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases differ from Triangle by more than ±{}% triangles or have a smaller smallest angle:\n  {}",
        failures.len(),
        cases.len(),
        COUNT_TOLERANCE * 100.0,
        failures.join("\n  ")
    );
}

/// One case that must match (for the `#[ignore]`d tests of the divergent cases).
fn assert_matches(input: Input, run: Run) {
    if let Some(Err(numbers)) = differential(input, run) {
        panic!("ours differs from Triangle by more than ±{}% triangles or has a smaller smallest angle: {numbers}", COUNT_TOLERANCE * 100.0);
    }
}

#[test]
fn classic_shapes_refine_like_triangle() {
    all_match(all_runs(&shapes()));
}

#[test]
fn random_polygons_refine_like_triangle() {
    all_match(all_runs(&random_polygons()));
}

#[test]
fn the_square_with_a_circular_hole_refines_like_triangle() {
    let mut cases = all_runs(&[Input::SquareWithHole(64)]);
    cases.push((Input::SquareWithHole(256), Run::Switches("pq30a0.0002")));
    all_match(cases);
}

/// The refinement benchmark's polygon, smaller: many small input angles.
fn star_cases() -> Vec<(Input, Run)> {
    let stars = [Input::Star(300, 1), Input::Star(300, 2), Input::Star(1000, 3)];
    stars
        .iter()
        .flat_map(|&star| {
            ["pq20", "pq30a0.001", "pa0.001", "pD"].map(|s| (star, Run::Switches(s)))
        })
        .collect()
}

#[test]
fn random_star_polygons_refine_like_triangle() {
    all_match(star_cases());
}

/// Prints every case's numbers (`cargo test --test refine_differential -- --ignored report
/// --nocapture`), for the numbers in the comments of the divergent cases.
#[test]
#[ignore = "prints a report; asserts nothing beyond the checks of every output"]
fn report() {
    let mut cases = all_runs(&shapes());
    cases.extend(all_runs(&random_polygons()));
    cases.extend(all_runs(&[Input::SquareWithHole(64)]));
    cases.push((Input::SquareWithHole(256), Run::Switches("pq30a0.0002")));
    cases.extend(star_cases());
    for (input, run) in cases {
        let known = if DIVERGENT.contains(&(input, run)) { "known " } else { "" };
        let case = format!("Input::{input:?}, Run::{run:?}");
        match std::panic::catch_unwind(|| differential(input, run)) {
            Ok(None) => return,
            Ok(Some(Ok(numbers))) => println!("{known}ok   | {case} | {numbers}"),
            Ok(Some(Err(numbers))) => println!("{known}DIFF | {case} | {numbers}"),
            Err(panic) => {
                let message = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .unwrap_or_else(|| "a panic".into());
                println!("{known}FAIL | {case} | {message}");
            }
        }
    }
}

/// The divergent cases: each becomes an `#[ignore]`d test of its own (named after input and
/// switches) that asserts what [`all_match`] asserts, and the tests above leave it out
/// ([`DIVERGENT`]). The comment of each gives the numbers (from the `report` test).
macro_rules! divergent {
    ($($(#[doc = $doc:literal])* $name:ident: ($input:expr, $run:expr), $reason:literal;)*) => {
        /// The cases where ours differs from Triangle beyond the bounds, or fails a check.
        const DIVERGENT: &[(Input, Run)] = &[$(($input, $run)),*];
        $(
            $(#[doc = $doc])*
            #[test]
            #[ignore = $reason]
            fn $name() {
                assert_matches($input, $run);
            }
        )*
    };
}

// Ours against Triangle, as measured when these tests were written. Most `pq30` cases give a
// smallest angle just above 30° (often 30.0388°) where Triangle's lies a little higher; the
// random star polygons give about 1.5× Triangle's triangles (the benchmark's polygon too).
divergent! {
    /// 14 triangles, Triangle 14 (ratio 1.000); smallest angle 30.1283°, Triangle 30.7371°.
    letter_a_pq30: (Input::Shape("letter_a"), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 27 triangles, Triangle 23 (ratio 1.174); smallest angle 6.2262°, Triangle 6.2262°.
    letter_a_pa0_01: (Input::Shape("letter_a"), Run::Switches("pa0.01")), "engine: more triangles than Triangle, beyond ±10%";
    /// 231 triangles, Triangle 239 (ratio 0.967); smallest angle 30.1165°, Triangle 30.2418°.
    letter_a_pq30a0_001: (Input::Shape("letter_a"), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// Our mesh has a triangle of area 3.099e-03 above its bound 2e-03 (Triangle's passes).
    letter_a_rpa_on_our_mesh: (Input::Shape("letter_a"), Run::RefinePrevious { by_triangle: false }), "engine: `rpa` leaves a triangle above its area bound";
    /// 89 triangles, Triangle 52 (ratio 1.712); smallest angle 33.6901°, Triangle 33.6901°.
    box_in_box_pq30: (Input::Shape("box_in_box"), Run::Switches("pq30")), "engine: more triangles than Triangle, beyond ±10%";
    /// 46 triangles, Triangle 40 (ratio 1.150); smallest angle 14.0362°, Triangle 14.0362°.
    box_in_box_pa0_01: (Input::Shape("box_in_box"), Run::Switches("pa0.01")), "engine: more triangles than Triangle, beyond ±10%";
    /// 504 triangles, Triangle 449 (ratio 1.122); smallest angle 30.0787°, Triangle 30.0720°.
    double_hexagon_pq30a0_001: (Input::Shape("double_hexagon"), Run::Switches("pq30a0.001")), "engine: more triangles than Triangle, beyond ±10%";
    /// Our mesh has a triangle of area 2.255e-03 above its bound 2e-03 (Triangle's passes).
    double_hexagon_rpa_on_our_mesh: (Input::Shape("double_hexagon"), Run::RefinePrevious { by_triangle: false }), "engine: `rpa` leaves a triangle above its area bound";
    /// 208 triangles, Triangle 183 (ratio 1.137); smallest angle 20.3406°, Triangle 20.0330°.
    square_circular_hole_pq: (Input::Shape("square_circular_hole"), Run::Switches("pq")), "engine: more triangles than Triangle, beyond ±10%";
    /// 458 triangles, Triangle 399 (ratio 1.148); smallest angle 30.0388°, Triangle 30.7423°.
    square_circular_hole_pq30: (Input::Shape("square_circular_hole"), Run::Switches("pq30")), "engine: triangle count beyond ±10% of Triangle's, smaller smallest angle";
    /// 1311 triangles, Triangle 1355 (ratio 0.968); smallest angle 30.0388°, Triangle 30.2173°.
    square_circular_hole_pq30a0_001: (Input::Shape("square_circular_hole"), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 166 triangles, Triangle 168 (ratio 0.988); smallest angle 2.9663°, Triangle 3.4717°.
    square_circular_hole_pqy: (Input::Shape("square_circular_hole"), Run::Switches("pqY")), "engine: smallest angle below Triangle's";
    /// 166 triangles, Triangle 168 (ratio 0.988); smallest angle 2.9663°, Triangle 3.4717°.
    square_circular_hole_pqyy: (Input::Shape("square_circular_hole"), Run::Switches("pqYY")), "engine: smallest angle below Triangle's";
    /// 208 triangles, Triangle 183 (ratio 1.137); smallest angle 20.3406°, Triangle 20.0330°.
    square_circular_hole_pqo2: (Input::Shape("square_circular_hole"), Run::Switches("pqo2")), "engine: more triangles than Triangle, beyond ±10%";
    /// 11 triangles, Triangle 17 (ratio 0.647); smallest angle 30.1522°, Triangle 30.0056°.
    three_regions_pq30: (Input::Shape("three_regions"), Run::Switches("pq30")), "engine: fewer triangles than Triangle, beyond ±10%";
    /// 192 triangles, Triangle 178 (ratio 1.079); smallest angle 30.0031°, Triangle 30.2958°.
    polygon_1_pq30: (Input::Polygon(1), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 976 triangles, Triangle 808 (ratio 1.208); smallest angle 29.2124°, Triangle 29.7374°.
    polygon_1_pq30a0_001: (Input::Polygon(1), Run::Switches("pq30a0.001")), "engine: triangle count beyond ±10% of Triangle's, smaller smallest angle";
    /// 150 triangles, Triangle 149 (ratio 1.007); smallest angle 30.0388°, Triangle 30.4046°.
    polygon_2_pq30: (Input::Polygon(2), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 805 triangles, Triangle 776 (ratio 1.037); smallest angle 28.9341°, Triangle 29.5303°.
    polygon_2_pq30a0_001: (Input::Polygon(2), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 154 triangles, Triangle 152 (ratio 1.013); smallest angle 30.0388°, Triangle 30.0582°.
    polygon_3_pq30: (Input::Polygon(3), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 844 triangles, Triangle 773 (ratio 1.092); smallest angle 30.0388°, Triangle 30.3991°.
    polygon_3_pq30a0_001: (Input::Polygon(3), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 65 triangles, Triangle 67 (ratio 0.970); smallest angle 20.1847°, Triangle 21.0297°.
    polygon_4_pq: (Input::Polygon(4), Run::Switches("pq")), "engine: smallest angle below Triangle's";
    /// 911 triangles, Triangle 882 (ratio 1.033); smallest angle 27.9369°, Triangle 29.0976°.
    polygon_4_pq30a0_001: (Input::Polygon(4), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 65 triangles, Triangle 67 (ratio 0.970); smallest angle 20.1847°, Triangle 21.0297°.
    polygon_4_pqy: (Input::Polygon(4), Run::Switches("pqY")), "engine: smallest angle below Triangle's";
    /// 65 triangles, Triangle 67 (ratio 0.970); smallest angle 20.1847°, Triangle 21.0297°.
    polygon_4_pqyy: (Input::Polygon(4), Run::Switches("pqYY")), "engine: smallest angle below Triangle's";
    /// 65 triangles, Triangle 67 (ratio 0.970); smallest angle 20.1847°, Triangle 21.0297°.
    polygon_4_pqo2: (Input::Polygon(4), Run::Switches("pqo2")), "engine: smallest angle below Triangle's";
    /// 84 triangles, Triangle 92 (ratio 0.913); smallest angle 20.0010°, Triangle 20.3702°.
    polygon_5_pq: (Input::Polygon(5), Run::Switches("pq")), "engine: smallest angle below Triangle's";
    /// 169 triangles, Triangle 166 (ratio 1.018); smallest angle 30.0388°, Triangle 30.4611°.
    polygon_5_pq30: (Input::Polygon(5), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 849 triangles, Triangle 811 (ratio 1.047); smallest angle 30.0388°, Triangle 30.2284°.
    polygon_5_pq30a0_001: (Input::Polygon(5), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 84 triangles, Triangle 92 (ratio 0.913); smallest angle 20.0010°, Triangle 20.3702°.
    polygon_5_pqy: (Input::Polygon(5), Run::Switches("pqY")), "engine: smallest angle below Triangle's";
    /// 84 triangles, Triangle 92 (ratio 0.913); smallest angle 20.0010°, Triangle 20.3702°.
    polygon_5_pqyy: (Input::Polygon(5), Run::Switches("pqYY")), "engine: smallest angle below Triangle's";
    /// 84 triangles, Triangle 92 (ratio 0.913); smallest angle 20.0010°, Triangle 20.3702°.
    polygon_5_pqo2: (Input::Polygon(5), Run::Switches("pqo2")), "engine: smallest angle below Triangle's";
    /// 100 triangles, Triangle 98 (ratio 1.020); smallest angle 20.5974°, Triangle 21.0297°.
    polygon_6_pq: (Input::Polygon(6), Run::Switches("pq")), "engine: smallest angle below Triangle's";
    /// 184 triangles, Triangle 166 (ratio 1.108); smallest angle 30.0019°, Triangle 30.2445°.
    polygon_6_pq30: (Input::Polygon(6), Run::Switches("pq30")), "engine: triangle count beyond ±10% of Triangle's, smaller smallest angle";
    /// 851 triangles, Triangle 810 (ratio 1.051); smallest angle 30.0388°, Triangle 30.7931°.
    polygon_6_pq30a0_001: (Input::Polygon(6), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 100 triangles, Triangle 98 (ratio 1.020); smallest angle 20.5974°, Triangle 21.0297°.
    polygon_6_pqy: (Input::Polygon(6), Run::Switches("pqY")), "engine: smallest angle below Triangle's";
    /// 100 triangles, Triangle 98 (ratio 1.020); smallest angle 20.5974°, Triangle 21.0297°.
    polygon_6_pqyy: (Input::Polygon(6), Run::Switches("pqYY")), "engine: smallest angle below Triangle's";
    /// 100 triangles, Triangle 98 (ratio 1.020); smallest angle 20.5974°, Triangle 21.0297°.
    polygon_6_pqo2: (Input::Polygon(6), Run::Switches("pqo2")), "engine: smallest angle below Triangle's";
    /// 169 triangles, Triangle 144 (ratio 1.174); smallest angle 30.0388°, Triangle 31.0148°.
    polygon_7_pq30: (Input::Polygon(7), Run::Switches("pq30")), "engine: triangle count beyond ±10% of Triangle's, smaller smallest angle";
    /// 870 triangles, Triangle 838 (ratio 1.038); smallest angle 30.0388°, Triangle 30.2107°.
    polygon_7_pq30a0_001: (Input::Polygon(7), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 198 triangles, Triangle 171 (ratio 1.158); smallest angle 13.2764°, Triangle 13.2764°.
    polygon_8_pq30: (Input::Polygon(8), Run::Switches("pq30")), "engine: more triangles than Triangle, beyond ±10%";
    /// 794 triangles, Triangle 750 (ratio 1.059); smallest angle 22.5962°, Triangle 27.6204°.
    polygon_8_pq30a0_001: (Input::Polygon(8), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 67 triangles, Triangle 65 (ratio 1.031); smallest angle 20.0235°, Triangle 20.5112°.
    polygon_9_pq: (Input::Polygon(9), Run::Switches("pq")), "engine: smallest angle below Triangle's";
    /// 117 triangles, Triangle 139 (ratio 0.842); smallest angle 30.0388°, Triangle 30.0392°.
    polygon_9_pq30: (Input::Polygon(9), Run::Switches("pq30")), "engine: triangle count beyond ±10% of Triangle's, smaller smallest angle";
    /// 786 triangles, Triangle 772 (ratio 1.018); smallest angle 30.0388°, Triangle 30.1176°.
    polygon_9_pq30a0_001: (Input::Polygon(9), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 67 triangles, Triangle 65 (ratio 1.031); smallest angle 20.0235°, Triangle 20.5112°.
    polygon_9_pqy: (Input::Polygon(9), Run::Switches("pqY")), "engine: smallest angle below Triangle's";
    /// 67 triangles, Triangle 65 (ratio 1.031); smallest angle 20.0235°, Triangle 20.5112°.
    polygon_9_pqyy: (Input::Polygon(9), Run::Switches("pqYY")), "engine: smallest angle below Triangle's";
    /// 67 triangles, Triangle 65 (ratio 1.031); smallest angle 20.0235°, Triangle 20.5112°.
    polygon_9_pqo2: (Input::Polygon(9), Run::Switches("pqo2")), "engine: smallest angle below Triangle's";
    /// 169 triangles, Triangle 175 (ratio 0.966); smallest angle 30.0388°, Triangle 30.5572°.
    polygon_11_pq30: (Input::Polygon(11), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 863 triangles, Triangle 840 (ratio 1.027); smallest angle 30.0388°, Triangle 30.0627°.
    polygon_11_pq30a0_001: (Input::Polygon(11), Run::Switches("pq30a0.001")), "engine: smallest angle below Triangle's";
    /// 117 triangles, Triangle 117 (ratio 1.000); smallest angle 30.0388°, Triangle 30.0741°.
    polygon_12_pq30: (Input::Polygon(12), Run::Switches("pq30")), "engine: smallest angle below Triangle's";
    /// 234 triangles, Triangle 232 (ratio 1.009); smallest angle 20.4969°, Triangle 21.0297°.
    square_with_hole_64_pq: (Input::SquareWithHole(64), Run::Switches("pq")), "engine: smallest angle below Triangle's";
    /// 562 triangles, Triangle 436 (ratio 1.289); smallest angle 30.0388°, Triangle 30.1735°.
    square_with_hole_64_pq30: (Input::SquareWithHole(64), Run::Switches("pq30")), "engine: triangle count beyond ±10% of Triangle's, smaller smallest angle";
    /// 232 triangles, Triangle 218 (ratio 1.064); smallest angle 3.9915°, Triangle 4.6117°.
    square_with_hole_64_pqy: (Input::SquareWithHole(64), Run::Switches("pqY")), "engine: smallest angle below Triangle's";
    /// 232 triangles, Triangle 218 (ratio 1.064); smallest angle 3.9915°, Triangle 4.6117°.
    square_with_hole_64_pqyy: (Input::SquareWithHole(64), Run::Switches("pqYY")), "engine: smallest angle below Triangle's";
    /// 234 triangles, Triangle 232 (ratio 1.009); smallest angle 20.4969°, Triangle 21.0297°.
    square_with_hole_64_pqo2: (Input::SquareWithHole(64), Run::Switches("pqo2")), "engine: smallest angle below Triangle's";
    /// 4299 triangles, Triangle 2882 (ratio 1.492); smallest angle 0.1882°, Triangle 0.1882°.
    star_300_1_pq20: (Input::Star(300, 1), Run::Switches("pq20")), "engine: more triangles than Triangle, beyond ±10%";
    /// 7283 triangles, Triangle 4898 (ratio 1.487); smallest angle 0.1882°, Triangle 0.1882°.
    star_300_1_pq30a0_001: (Input::Star(300, 1), Run::Switches("pq30a0.001")), "engine: more triangles than Triangle, beyond ±10%";
    /// 6631 triangles, Triangle 4248 (ratio 1.561); smallest angle 0.1882°, Triangle 0.1882°.
    star_300_1_pd: (Input::Star(300, 1), Run::Switches("pD")), "engine: more triangles than Triangle, beyond ±10%";
    /// 5993 triangles, Triangle 3910 (ratio 1.533); smallest angle 0.0629°, Triangle 0.0629°.
    star_300_2_pq20: (Input::Star(300, 2), Run::Switches("pq20")), "engine: more triangles than Triangle, beyond ±10%";
    /// 9766 triangles, Triangle 6536 (ratio 1.494); smallest angle 0.0629°, Triangle 0.0629°.
    star_300_2_pq30a0_001: (Input::Star(300, 2), Run::Switches("pq30a0.001")), "engine: more triangles than Triangle, beyond ±10%";
    /// 9688 triangles, Triangle 5974 (ratio 1.622); smallest angle 0.0629°, Triangle 0.0629°.
    star_300_2_pd: (Input::Star(300, 2), Run::Switches("pD")), "engine: more triangles than Triangle, beyond ±10%";
    /// 58510 triangles, Triangle 38921 (ratio 1.503); smallest angle 0.0109°, Triangle 0.0109°.
    star_1000_3_pq20: (Input::Star(1000, 3), Run::Switches("pq20")), "engine: more triangles than Triangle, beyond ±10%";
    /// 92511 triangles, Triangle 62907 (ratio 1.471); smallest angle 0.0109°, Triangle 0.0109°.
    star_1000_3_pq30a0_001: (Input::Star(1000, 3), Run::Switches("pq30a0.001")), "engine: more triangles than Triangle, beyond ±10%";
    /// 107526 triangles, Triangle 68294 (ratio 1.574); smallest angle 0.0109°, Triangle 0.0109°.
    star_1000_3_pd: (Input::Star(1000, 3), Run::Switches("pD")), "engine: more triangles than Triangle, beyond ±10%";
}
