//! Fidelity at the edges and safe input (issue 12), through the C ABI:
//! 1. `r` with `p` gives `out` the input's holes and regions, as Triangle does;
//! 2. `A` without regions gives every triangle an attribute (zero);
//! 3. coordinates of any magnitude give a valid mesh (by exact orientation) or a clear error,
//!    input vertices come back bit for bit, and the result does not depend on a power-of-two
//!    scale of the input;
//! 4. indices out of range, non-finite hole or region points, a NaN region area and a
//!    `numberofcorners` other than 3 or 6 are errors.
//!
//! The same through the command-line program at the end (`cli_*` tests).

mod cli_support;
mod common;

use common::call::{MeshInput, Triangulation};
use common::checks::{check_delaunay, check_mesh, zero_based};
use common::points::{uniform, Point};
use common::pslg_checks::MeshView;
use common::{ours, reference};

/// A square with a square hole, a region, and a point inside: the `-p` test domain.
fn square_with_hole() -> MeshInput {
    MeshInput {
        points: vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            [1.0, 1.0],
            [3.0, 1.0],
            [3.0, 3.0],
            [1.0, 3.0],
        ],
        segments: vec![
            [0, 1],
            [1, 2],
            [2, 3],
            [3, 0],
            [4, 5],
            [5, 6],
            [6, 7],
            [7, 4],
        ],
        holes: vec![[2.0, 2.0]],
        regions: vec![[0.5, 0.5, 7.0, 0.5]],
        ..MeshInput::default()
    }
}

/// The output of a `p` run as the input of an `r` run, with the holes and regions of `pslg`.
fn refine_input(previous: &Triangulation, pslg: &MeshInput) -> MeshInput {
    MeshInput {
        points: previous.points.clone().unwrap(),
        triangles: previous.triangles.clone().unwrap(),
        corners: previous.counts.corners as usize,
        triangle_attributes: previous.triangle_attributes.clone().unwrap_or_default(),
        triangle_attribute_count: previous.counts.triangle_attributes as usize,
        segments: previous.segments.clone().unwrap(),
        segment_markers: previous.segment_markers.clone(),
        holes: pslg.holes.clone(),
        regions: pslg.regions.clone(),
        ..MeshInput::default()
    }
}

// --- 1. holes and regions with `rp` -----------------------------------------------------------

#[test]
fn refining_with_p_lists_the_holes_and_regions_like_triangle() {
    let pslg = square_with_hole();
    let first = ours("pzAQ", &pslg).unwrap();
    let input = refine_input(&first, &pslg);
    for switches in ["rpzQ", "rpzq30Q", "rpza0.1Q", "rpzqDQ", "rpzenQ", "rpzcjQ"] {
        let out = ours(switches, &input).unwrap_or_else(|e| panic!("{switches}: {e}"));
        assert_eq!((out.counts.holes, out.counts.regions), (1, 1), "{switches}");
        assert!(
            out.holes_alias_input && out.regions_alias_input,
            "{switches}"
        );
        // Refinement carves nothing; the hole is not in the mesh being refined.
        MeshView::of(&out).unwrap_or_else(|e| panic!("{switches}: {e}"));
        if let Some(triangle) = reference() {
            let theirs = triangle.triangulate(switches, &input);
            assert_eq!(
                (out.counts.holes, out.counts.regions),
                (theirs.counts.holes, theirs.counts.regions),
                "{switches} against Triangle"
            );
            assert_eq!(
                (out.holes_alias_input, out.regions_alias_input),
                (theirs.holes_alias_input, theirs.regions_alias_input),
                "{switches} against Triangle"
            );
        }
    }
    // `r` without `p`, and `P`, list none (as Triangle).
    for switches in ["rzQ", "rpzPQ"] {
        let out = ours(switches, &input).unwrap();
        assert_eq!((out.counts.holes, out.counts.regions), (0, 0), "{switches}");
        assert!(!out.holes_alias_input, "{switches}");
    }
}

/// The directory of Triangle's example files that the PyPI `triangle` package ships (installed
/// in `.venv` by scripts/setup-python.sh), or `None` after a skip message (a failure in CI).
fn shipped_data() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(".venv/lib/python3.11/site-packages/triangle/data");
    if dir.is_dir() {
        Some(dir)
    } else {
        common::reference::reference_missing(&dir.display().to_string());
        None
    }
}

/// A shipped `NAME.1` mesh (`.node`, `.ele`, `.poly`) as the input of `r` (1-based, as written).
fn shipped_mesh(dir: &std::path::Path, name: &str) -> MeshInput {
    use triangle_rs::io::files;
    let read = |ext: &str| {
        let path = dir.join(format!("{name}.1.{ext}"));
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    };
    let node = files::read_node(&read("node"), "node").unwrap();
    let ele = files::read_ele(&read("ele"), "ele").unwrap();
    let poly = files::read_poly(&read("poly"), "poly", false).unwrap();
    assert_eq!(node.first_number, Some(1), "{name}: 1-based files");
    MeshInput {
        points: node.points.chunks_exact(2).map(|p| [p[0], p[1]]).collect(),
        attributes: node.attributes.clone(),
        attribute_count: node.attribute_count,
        markers: node.markers.clone(),
        triangles: ele.triangles.clone(),
        corners: ele.corners,
        triangle_attributes: ele.attributes.clone(),
        triangle_attribute_count: ele.attribute_count,
        segments: poly
            .segments
            .chunks_exact(2)
            .map(|s| [s[0], s[1]])
            .collect(),
        segment_markers: poly.segment_markers.clone(),
        holes: poly.holes.chunks_exact(2).map(|h| [h[0], h[1]]).collect(),
        ..MeshInput::default()
    }
}

#[test]
fn refining_triangles_shipped_meshes_with_p_lists_their_holes() {
    let Some(dir) = shipped_data() else { return };
    for name in ["A", "box", "double_hex2"] {
        let input = shipped_mesh(&dir, name);
        assert!(!input.holes.is_empty(), "{name} has holes");
        for switches in ["rpq30Q", "rpa0.05Q", "rpqDQ", "rpenQ", "rpcjQ"] {
            let out = ours(switches, &input).unwrap_or_else(|e| panic!("{name} {switches}: {e}"));
            assert_eq!(
                out.counts.holes as usize,
                input.holes.len(),
                "{name} {switches}"
            );
            assert!(out.holes_alias_input, "{name} {switches}");
            MeshView::of(&out).unwrap_or_else(|e| panic!("{name} {switches}: {e}"));
            if let Some(triangle) = reference() {
                let theirs = triangle.triangulate(switches, &input);
                assert_eq!(out.counts.holes, theirs.counts.holes, "{name} {switches}");
                assert_eq!(
                    out.holes_alias_input, theirs.holes_alias_input,
                    "{name} {switches}"
                );
            }
        }
    }
}

// --- 2. `A` without regions -------------------------------------------------------------------

#[test]
fn region_attributes_without_regions_are_a_column_of_zeros() {
    let mut pslg = square_with_hole();
    pslg.regions.clear();
    for switches in ["pzAQ", "pzAq25Q", "pzcAQ", "pzAa0.5Q"] {
        let out = ours(switches, &pslg).unwrap();
        assert_eq!(out.counts.triangle_attributes, 1, "{switches}");
        let attributes = out.triangle_attributes.as_deref().unwrap();
        assert_eq!(
            attributes.len(),
            out.counts.triangles as usize,
            "{switches}"
        );
        assert!(attributes.iter().all(|&a| a == 0.0), "{switches}");
    }
    // With a region, its attribute inside and zero elsewhere, as before.
    let out = ours("pzAQ", &square_with_hole()).unwrap();
    let attributes = out.triangle_attributes.unwrap();
    assert!(attributes.contains(&7.0) && attributes.iter().all(|&a| a == 7.0 || a == 0.0));
    // Without `A`, no column.
    pslg.regions.clear();
    assert_eq!(ours("pzQ", &pslg).unwrap().counts.triangle_attributes, 0);
}

// --- 3. extreme coordinates -------------------------------------------------------------------

/// `x · 2^k`, exact unless the result leaves the normal range.
fn times_power_of_two(x: f64, k: i32) -> f64 {
    let half = k / 2;
    x * 2f64.powi(half) * 2f64.powi(k - half)
}

/// The output points multiplied by the power of two that brings the largest magnitude near 1, so
/// that the (exact, but overflow-prone) orientation tests of the checks apply: a power of two
/// changes no orientation.
fn normalized(out: &Triangulation) -> Triangulation {
    let points = out.points.as_deref().unwrap();
    let largest = points.iter().flatten().fold(0.0f64, |m, &x| m.max(x.abs()));
    if largest == 0.0 {
        return out.clone();
    }
    let k = -(largest.log2().floor() as i32);
    let mut scaled = out.clone();
    scaled.points = Some(
        points
            .iter()
            .map(|p| p.map(|x| times_power_of_two(x, k)))
            .collect(),
    );
    scaled
}

/// Points of magnitude about `scale` (random, full mantissas) and the corners of the square
/// `[0, scale]²`, with the square's four sides as segments and a hole-free domain.
fn cloud(scale: f64, seed: u64) -> MeshInput {
    let mut points: Vec<Point> = vec![[0.0, 0.0], [scale, 0.0], [scale, scale], [0.0, scale]];
    points.extend(
        uniform(16, seed)
            .into_iter()
            .map(|[x, y]| [0.05 + 0.9 * x, 0.05 + 0.9 * y].map(|c| c * scale)),
    );
    MeshInput {
        points,
        segments: vec![[0, 1], [1, 2], [2, 3], [3, 0]],
        ..MeshInput::default()
    }
}

/// Checks one result: a valid mesh by exact orientation (after an exact power-of-two scaling),
/// the input vertices bit for bit, and for `''` the Delaunay triangulation of the points.
fn check_result(name: &str, switches: &str, input: &MeshInput, out: &Triangulation) {
    let context = format!("{name} with {switches}");
    let points = out.points.as_deref().unwrap();
    for (v, p) in input.points.iter().enumerate() {
        assert_eq!(
            p.map(f64::to_bits),
            points[v].map(f64::to_bits),
            "{context}: input vertex {v} changed"
        );
    }
    assert!(
        points.iter().flatten().all(|x| x.is_finite()),
        "{context}: a vertex is not finite"
    );
    let scaled = normalized(out);
    MeshView::of(&scaled).unwrap_or_else(|e| panic!("{context}: {e}"));
    if !switches.contains('p') && !switches.contains('r') && !switches.contains('q') {
        let scaled_points = scaled.points.as_deref().unwrap();
        let triangles = zero_based(&scaled);
        check_mesh(scaled_points, &triangles).unwrap_or_else(|e| panic!("{context}: {e}"));
        check_delaunay(scaled_points, &triangles).unwrap_or_else(|e| panic!("{context}: {e}"));
    }
    if let Some(voronoi) = &out.voronoi {
        // Voronoi points may lie far outside (thin hull triangles) but are numbers.
        assert!(
            voronoi
                .points
                .iter()
                .flatten()
                .flatten()
                .all(|x| !x.is_nan()),
            "{context}: a Voronoi point is NaN"
        );
    }
}

const EVERY_ALGORITHM: [&str; 6] = ["zQ", "zvQ", "pzQ", "pzqQ", "pzDQ", "pzq25eQ"];

/// Runs every algorithm on `input` (and `r` on the `p` mesh); each result must be valid or an
/// error about the coordinates' range. Returns how many runs succeeded.
fn every_algorithm(name: &str, input: &MeshInput) -> usize {
    let mut successes = 0;
    let mut judge = |switches: &str, input: &MeshInput| -> Option<Triangulation> {
        match ours(switches, input) {
            Ok(out) => {
                check_result(name, switches, input, &out);
                successes += 1;
                Some(out)
            }
            Err(e) => {
                assert!(
                    e.contains("binary orders of magnitude")
                        || e.contains("floating-point numbers"),
                    "{name} with {switches}: unexpected error {e}"
                );
                None
            }
        }
    };
    for switches in EVERY_ALGORITHM {
        judge(switches, input);
    }
    if let Some(out) = judge("pzQ", input) {
        let again = refine_input(&out, input);
        judge("rpzqQ", &again);
        judge("rzQ", &again);
    }
    successes
}

#[test]
fn coordinates_of_every_magnitude_give_a_valid_mesh() {
    for (k, scale) in [1e300, 1e-300, 1e150, 1e-150, 1e-310, f64::MAX / 2.0]
        .into_iter()
        .enumerate()
    {
        let input = cloud(scale, 40 + k as u64);
        let runs = every_algorithm(&format!("cloud of size {scale:e}"), &input);
        // These have at most 60 bits between the largest magnitude and the finest bit: scaling
        // makes them safe, so nothing is refused.
        assert_eq!(
            runs,
            EVERY_ALGORITHM.len() + 3,
            "size {scale:e}: some run refused"
        );
    }
    // Twenty points near 1e300 (the case: Triangle crashes, triangle-rs gave clockwise
    // triangles before scaling).
    let points: Vec<Point> = uniform(20, 12)
        .into_iter()
        .map(|[x, y]| [1e300 * (1.0 + x), 1e300 * (1.0 + y)])
        .collect();
    let out = ours("zQ", &MeshInput::from_points(points.clone())).unwrap();
    check_result(
        "20 points near 1e300",
        "zQ",
        &MeshInput::from_points(points),
        &out,
    );
}

#[test]
fn a_large_offset_with_fine_spacing_gives_a_valid_mesh() {
    // A 1e12 offset with 1e-3 spacing: a grid (cocircular everywhere) jittered in the last bits.
    let mut input = MeshInput::default();
    for i in 0..6 {
        for j in 0..6 {
            input
                .points
                .push([1e12 + 1e-3 * i as f64, 1e12 + 1e-3 * j as f64]);
        }
    }
    input.segments = vec![[0, 5], [5, 35], [35, 30], [30, 0]];
    assert_eq!(every_algorithm("1e12 offset, 1e-3 spacing", &input), 9);
}

#[test]
fn mixed_magnitudes_are_valid_or_refused_with_the_bound() {
    // 1e30 and 1e-30: about 300 binary orders from the top to the finest bit, within the bound
    // of 340 once the top is scaled to 2^60: valid.
    let mut input = cloud(1e30, 7);
    input.points.push([1e-30, 3e-30]);
    assert_eq!(every_algorithm("1e30 with 1e-30", &input), 9);
    // 1e300 with 1e-300: far beyond; every algorithm refuses with the bound in the message.
    let mut input = cloud(1e300, 8);
    input.points.push([1e-300, 2e-300]);
    assert_eq!(every_algorithm("1e300 with 1e-300", &input), 0);
    let message = ours("zQ", &input).unwrap_err();
    assert!(message.contains("at most 340"), "{message}");
    // A vertex at 1e-80 among unit ones (lowest bit 2^-318): within the bound (a top at 2^78).
    let mut input = cloud(1.0, 9);
    input.points.push([0.5, 1e-80]);
    assert_eq!(every_algorithm("1e-80 among unit points", &input), 9);
}

#[test]
fn a_power_of_two_scale_changes_nothing_but_the_scale() {
    let input = cloud(1.0, 3);
    for k in [995, -990, 300, -300] {
        let mut scaled_input = input.clone();
        for p in &mut scaled_input.points {
            *p = p.map(|x| times_power_of_two(x, k));
        }
        for switches in ["zQ", "pzq30Q", "pzDQ", "pzq25a0.01Q"] {
            // The area bound scales with the square (where that is a normal number).
            let scaled_area = times_power_of_two(0.01, 2 * k);
            let scaled_switches = match switches.find('a') {
                Some(_) if !scaled_area.is_normal() => continue,
                Some(_) => format!("pzq25a{scaled_area:e}Q"),
                None => switches.to_string(),
            };
            let unit = ours(switches, &input).unwrap();
            let big = ours(&scaled_switches, &scaled_input).unwrap();
            assert_eq!(unit.triangles, big.triangles, "2^{k}, {switches}");
            let expected: Vec<Point> = unit
                .points
                .unwrap()
                .iter()
                .map(|p| p.map(|x| times_power_of_two(x, k)))
                .collect();
            assert_eq!(big.points.unwrap(), expected, "2^{k}, {switches}");
        }
    }
}

/// The `u` test of [`the_user_test_sees_the_callers_coordinates`]: records its arguments in the
/// `Vec` behind `user_data` and asks to split triangles whose area overflows, in its first 30
/// calls (every triangle of a 1e300 input overflows: a bound on calls keeps the mesh small).
extern "C" fn record_and_split_infinite(
    ox: f64,
    oy: f64,
    dx: f64,
    dy: f64,
    ax: f64,
    ay: f64,
    area: f64,
    user_data: *mut std::os::raw::c_void,
) -> std::os::raw::c_int {
    // SAFETY: `user_data` is the `Vec` the test passes, alive and used by this call only.
    let seen = unsafe { &mut *(user_data as *mut Vec<[f64; 7]>) };
    seen.push([ox, oy, dx, dy, ax, ay, area]);
    (area.is_infinite() && seen.len() <= 30) as std::os::raw::c_int
}

#[test]
fn the_user_test_sees_the_callers_coordinates() {
    let input = cloud(1e300, 5);
    let mut seen: Vec<[f64; 7]> = Vec::new();
    let out = common::quality::ours_reentrant(
        "pzuQ",
        &input,
        Some(record_and_split_infinite),
        &mut seen as *mut Vec<[f64; 7]> as *mut std::os::raw::c_void,
        std::ptr::null(),
    )
    .unwrap();
    check_result("user test at 1e300", "pzuQ", &input, &out);
    let inputs: std::collections::HashSet<[u64; 2]> =
        input.points.iter().map(|p| p.map(f64::to_bits)).collect();
    // The first tests see input triangles: every corner is an input vertex, in the caller's
    // units, and the area is the caller's (about 1e599 here: infinite in f64).
    let first = seen[0];
    for corner in [
        [first[0], first[1]],
        [first[2], first[3]],
        [first[4], first[5]],
    ] {
        assert!(inputs.contains(&corner.map(f64::to_bits)), "{corner:?}");
    }
    assert!(first[6].is_infinite());
    assert!(out.counts.points as usize > input.points.len());
    // Every test saw coordinates of the caller's magnitude.
    assert!(seen.iter().all(|t| t[..6]
        .iter()
        .all(|x| x.abs() <= 1e300 && (*x == 0.0 || x.abs() > 1e250))));
}

// --- 4. indices and seeds -----------------------------------------------------------------------

fn error_of(switches: &str, input: &MeshInput) -> String {
    ours(switches, input).expect_err("the input must be refused")
}

#[test]
fn segment_endpoints_out_of_range_are_errors() {
    let mut input = square_with_hole();
    // 1-based segments given with `z`: vertex 8 does not exist.
    for s in &mut input.segments {
        *s = s.map(|v| v + 1);
    }
    let message = error_of("pzQ", &input);
    assert!(
        message.contains("Segment 6 has endpoint 8") && message.contains("numbered 0 to 7"),
        "{message}"
    );
    // The same list without `z` is right (1-based).
    MeshView::of(&ours("pQ", &input).unwrap()).unwrap();
    // 0-based segments without `z`: vertex 0 does not exist.
    let message = error_of("pQ", &square_with_hole());
    assert!(
        message.contains("Segment 1 has endpoint 0") && message.contains("numbered 1 to 8"),
        "{message}"
    );
    let mut input = square_with_hole();
    input.segments[2] = [-1, 2];
    assert!(error_of("pzQ", &input).contains("endpoint -1"));
    // Without `p`, segments are not read (as in Triangle).
    ours("zQ", &input).unwrap();
}

#[test]
fn triangle_corners_out_of_range_and_bad_corner_counts_are_errors() {
    let pslg = square_with_hole();
    let first = ours("pzQ", &pslg).unwrap();
    let mut input = refine_input(&first, &pslg);
    input.triangles[4] = 8;
    let message = error_of("rzQ", &input);
    assert!(
        message.contains("Triangle 1 has corner 8") && message.contains("numbered 0 to 7"),
        "{message}"
    );
    let mut input = refine_input(&first, &pslg);
    input.triangles[0] = -3;
    assert!(error_of("rzQ", &input).contains("corner -3"));
    // numberofcorners 4 (or 5, 7): neither 3 nor 6.
    for corners in [4, 5, 7] {
        let mut input = refine_input(&first, &pslg);
        let t = &first.triangles.as_deref().unwrap()[..3];
        input.triangles = [t, &vec![t[0]; corners - 3]].concat();
        input.corners = corners;
        let message = error_of("rzQ", &input);
        assert!(message.contains("3 or 6"), "{message}");
    }
}

#[test]
fn non_finite_seeds_and_nan_areas_are_errors() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut input = square_with_hole();
        input.holes[0][1] = bad;
        let message = error_of("pzQ", &input);
        assert!(message.contains("Hole 0"), "{message}");
        // `O` ignores holes: nothing to refuse.
        MeshView::of(&ours("pzOQ", &input).unwrap()).unwrap();
        let mut input = square_with_hole();
        input.regions[0][0] = bad;
        assert!(error_of("pzAQ", &input).contains("Region 0"));
    }
    let mut input = square_with_hole();
    input.regions[0][3] = f64::NAN;
    let message = error_of("pzAaQ", &input);
    assert!(
        message.contains("Region 0 has a maximum area that is NaN"),
        "{message}"
    );
    // An infinite area is no constraint, as a negative one.
    input.regions[0][3] = f64::INFINITY;
    MeshView::of(&ours("pzAaQ", &input).unwrap()).unwrap();
}

// --- the command-line program -------------------------------------------------------------------

use cli_support::{run as run_program, TempDir};
use triangle_rs::io::files;

/// `x.1.node` and `x.1.ele` written by the program: points, and zero-based triangles.
fn read_mesh(dir: &TempDir, base: &str) -> (Vec<Point>, Vec<[usize; 3]>, files::EleFile) {
    let node = files::read_node(&dir.read(&format!("{base}.node")), "node").unwrap();
    let ele = files::read_ele(&dir.read(&format!("{base}.ele")), "ele").unwrap();
    let first = node.first_number.unwrap() as i32;
    let points = node.points.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
    let triangles = ele
        .triangles
        .chunks_exact(ele.corners)
        .map(|t| [t[0], t[1], t[2]].map(|v| (v - first) as usize))
        .collect();
    (points, triangles, ele)
}

/// A valid mesh by exact orientation (after an exact power-of-two scaling) and manifold.
fn check_files_mesh(context: &str, points: &[Point], triangles: &[[usize; 3]]) {
    let out = Triangulation {
        base: 0,
        points: Some(points.to_vec()),
        ..Triangulation::default()
    };
    let scaled = normalized(&out);
    let scaled_points = scaled.points.as_deref().unwrap();
    for (t, c) in triangles.iter().enumerate() {
        assert!(
            c.iter().all(|&v| v < points.len()),
            "{context}: triangle {t}"
        );
        let [a, b, d] = c.map(|v| scaled_points[v]);
        assert!(
            common::checks::orient2d(a, b, d) > 0.0,
            "{context}: triangle {t} {c:?} is not counter-clockwise"
        );
    }
    common::checks::directed_edges(triangles).unwrap_or_else(|e| panic!("{context}: {e}"));
}

/// `x.node` and `x.poly` (the square's sides as segments) of [`cloud`] at `scale`.
fn cloud_files(dir: &TempDir, scale: f64, seed: u64) -> MeshInput {
    let input = cloud(scale, seed);
    let n = input.points.len();
    let mut node = format!("{n} 2 0 0\n");
    for (i, p) in input.points.iter().enumerate() {
        node.push_str(&format!("{} {:e} {:e}\n", i + 1, p[0], p[1]));
    }
    let mut poly = node.clone();
    poly.push_str(&format!("{} 0\n", input.segments.len()));
    for (i, s) in input.segments.iter().enumerate() {
        poly.push_str(&format!("{} {} {}\n", i + 1, s[0] + 1, s[1] + 1));
    }
    poly.push_str("0\n");
    dir.write("x.node", &node);
    dir.write("x.poly", &poly);
    input
}

#[test]
fn cli_coordinates_of_every_magnitude_give_a_valid_mesh() {
    let program = cli_support::ours();
    for (k, scale) in [1e300, 1e-300, 1e150, 1e-150].into_iter().enumerate() {
        for (args, base) in [
            (vec!["-Q", "x.node"], "x.1"),
            (vec!["-Qv", "x.node"], "x.1"),
            (vec!["-Q", "x.poly"], "x.1"),
            (vec!["-Qq", "x.poly"], "x.1"),
            (vec!["-QD", "x.poly"], "x.1"),
        ] {
            let dir = TempDir::new("fidelity-magnitude");
            let input = cloud_files(&dir, scale, 60 + k as u64);
            let context = format!("size {scale:e}, {args:?}");
            let r = run_program(&program, dir.path(), &args);
            assert!(r.ok(), "{context}: {}", r.stderr);
            let (points, triangles, _) = read_mesh(&dir, base);
            for (v, p) in input.points.iter().enumerate() {
                assert_eq!(
                    p.map(f64::to_bits),
                    points[v].map(f64::to_bits),
                    "{context}"
                );
            }
            check_files_mesh(&context, &points, &triangles);
            // `r` on the written mesh, with the segments of the written .poly if any.
            let refine = if args[1] == "x.poly" { "-Qrpq" } else { "-Qrq" };
            let r = run_program(&program, dir.path(), &[refine, "x.1"]);
            assert!(r.ok(), "{context}, then {refine}: {}", r.stderr);
            let (points, triangles, _) = read_mesh(&dir, "x.2");
            check_files_mesh(&format!("{context}, then {refine}"), &points, &triangles);
        }
    }
}

#[test]
fn cli_refuses_mixed_magnitudes_beyond_the_bound() {
    let dir = TempDir::new("fidelity-mixed");
    dir.write(
        "m.node",
        "4 2 0 0\n1 0 0\n2 1e300 0\n3 0 1e300\n4 1e-300 2e-300\n",
    );
    let before = dir.files();
    let r = run_program(&cli_support::ours(), dir.path(), &["-Q", "m.node"]);
    assert_eq!(r.status, Some(1));
    assert!(
        r.stderr.contains("binary orders of magnitude") && r.stderr.contains("at most 340"),
        "{}",
        r.stderr
    );
    assert_eq!(dir.files(), before, "no output file is written");
}

#[test]
fn cli_region_attributes_without_regions_are_a_column_of_zeros() {
    let square = "4 2 0 0\n1 0 0\n2 4 0\n3 4 4\n4 0 4\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n";
    // Without a region section (Triangle stops at the end of the file) and with 0 regions.
    for (name, text) in [
        ("none", square.to_string()),
        ("zero", format!("{square}0\n")),
    ] {
        let dir = TempDir::new("fidelity-attributes");
        dir.write(&format!("{name}.poly"), &text);
        for args in [vec!["-QA"], vec!["-QAq"], vec!["-QAa1"]] {
            let mut args = args;
            let file = format!("{name}.poly");
            args.push(&file);
            let r = run_program(&cli_support::ours(), dir.path(), &args);
            assert!(r.ok(), "{name} {args:?}: {}", r.stderr);
            let (_, triangles, ele) = read_mesh(&dir, &format!("{name}.1"));
            assert_eq!(ele.attribute_count, 1, "{name} {args:?}");
            assert_eq!(ele.attributes.len(), triangles.len(), "{name} {args:?}");
            assert!(ele.attributes.iter().all(|&a| a == 0.0), "{name} {args:?}");
            let header = dir.read(&format!("{name}.1.ele"));
            assert!(
                header.lines().next().unwrap().ends_with("3  1"),
                "{name} {args:?}: {header}"
            );
        }
    }
}

#[test]
fn cli_refining_triangles_shipped_meshes_with_p_writes_their_holes() {
    let Some(data) = shipped_data() else { return };
    for name in ["A", "box", "double_hex2"] {
        let dir = TempDir::new("fidelity-shipped");
        for ext in ["node", "ele", "poly"] {
            let text = std::fs::read_to_string(data.join(format!("{name}.1.{ext}"))).unwrap();
            dir.write(&format!("{name}.1.{ext}"), &text);
        }
        let r = run_program(
            &cli_support::ours(),
            dir.path(),
            &["-Qrpq30", &format!("{name}.1")],
        );
        assert!(r.ok(), "{name}: {}", r.stderr);
        let read = |file: &str| files::read_poly(&dir.read(file), file, false).unwrap();
        let (before, after) = (
            read(&format!("{name}.1.poly")),
            read(&format!("{name}.2.poly")),
        );
        assert!(!before.holes.is_empty());
        assert_eq!(after.holes, before.holes, "{name}");
    }
}

#[test]
fn cli_refuses_non_finite_holes_and_bad_corner_counts() {
    let program = cli_support::ours();
    let dir = TempDir::new("fidelity-cli-errors");
    let square = "4 2 0 0\n1 0 0\n2 4 0\n3 4 4\n4 0 4\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n";
    dir.write("h.poly", &format!("{square}1\n1 inf 2\n"));
    let r = run_program(&program, dir.path(), &["-Q", "h.poly"]);
    assert_eq!(r.status, Some(1), "{}", r.stdout);
    // The file reader refuses it (a number that is not finite is malformed), naming the hole.
    assert!(r.stderr.to_lowercase().contains("hole 1"), "{}", r.stderr);
    dir.write("c.node", "4 2 0 0\n1 0 0\n2 4 0\n3 4 4\n4 0 4\n");
    dir.write("c.ele", "1 4 0\n1 1 2 3 4\n");
    let r = run_program(&program, dir.path(), &["-Qr", "c"]);
    assert_eq!(r.status, Some(1));
    assert!(r.stderr.contains("3 or 6"), "{}", r.stderr);
}
