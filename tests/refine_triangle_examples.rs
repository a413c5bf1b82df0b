//! Differential tests of quality meshing (issue 11) on Triangle's own example files — every
//! `.poly`, `.node` and `.ele` (with its `.area`) in the data directory of the PyPI `triangle`
//! package, read from there at test time (`TRIANGLE_DATA_DIR`, else
//! `.venv/lib/python3*/site-packages/triangle/data`; `bash scripts/setup-python.sh` installs it;
//! the files are not copied into this repository) — and on wedges of 1°, 5°, 10°, 15° and 25°
//! between two segments and a fan of segments from one vertex, against Debian's Triangle 1.6.
//!
//! For each input and switch set (`q q30 q33` on the vertices of every `.node` and `.poly`;
//! `pq pq30 pq33 pq30a<x> pqAa pqs pcq30 pqD pqY` on every `.poly`; `rpq30 rpqa<x> rpqD rpYq`,
//! and `rpqa` with an `.area` file, on every mesh), both outputs, ours and Triangle's, must be
//! valid constrained Delaunay meshes with every input segment a chain of output segments, and:
//! - every angle ≥ θ, except in triangles that Triangle's small-angle rule excuses: the shortest
//!   edge joins two vertices on two different input segments (or hull edges with `c` and for
//!   point sets, or
//!   boundary edges of the mesh with `r`) that share a vertex, at distances from it equal within
//!   1% (the rule of `AngleBound::is_excused_by_small_input_angle` in `refine::split_point`).
//!   With `Y`, where boundary segments cannot be split, our smallest unexcused angle is at least
//!   half of θ and of Triangle's;
//! - every triangle within its area bound (global `a<x>`, regional `a` by flooding from the
//!   region points across non-segment edges, per triangle of the previous mesh with `rpqa`);
//! - our triangles cover the same area as Triangle's, and number at most 2× Triangle's (fewer is
//!   no fault when every bound above holds: with the improvement of the finished mesh, `A.poly`
//!   with `q33` has 134 triangles where Triangle's cascade at 33° makes 290).
//!
//! Orientation, validity and the Delaunay property are decided with exact predicates; angles are
//! compared with θ in floating point within 10^-6°. Inputs Triangle does not finish (the
//! Greenland coastline's vertices with `q`: Triangle loops) are meshed by us alone, which must
//! return a valid mesh of the convex hull. Without the data directory or the reference library these
//! tests fail (they must not be skipped).

mod common;

use std::collections::{HashMap, HashSet};

use common::call::{MeshInput, Triangulation};
use common::checks::{convex_hull, orient2d};
use common::examples::{area_switch, data_dir, example_files, example_named, ExampleFile, Kind};
use common::points::Point;
use common::pslg::{polygon_area, with_hull_segments};
use common::pslg_checks::{check_constrained_delaunay, segment_chains, MeshView};
use common::quality::{angles, check_areas, check_conforming_delaunay, engine, ANGLE_TOLERANCE};
use common::reference::{Reference, REFERENCE_LIBRARY};
use common::{ours, reference};
use triangle_rs::data::Hooks;

/// Our triangle count may be at most this factor of Triangle's. There is no lower bound: the
/// angle and area bounds are checked on every triangle, and a smaller mesh meeting them is better.
const MOST_COUNT_RATIO: f64 = 2.0;
/// Two distances from a common vertex count as equal within this fraction (the test of the
/// excused configuration; the engine's is tighter).
const EQUAL_DISTANCE: f64 = 0.01;
/// Inputs that Triangle does not finish with `q` (it loops on the Greenland coastline's
/// vertices, some a rounding apart; the mesh of them it refines): meshed by us alone.
const TRIANGLE_LOOPS_ON: &[&str] = &["greenland.node"];

/// One input of the tests with its switch sets (without `z` and `Q`, which are appended).
struct Example {
    name: String,
    input: MeshInput,
    switches: Vec<String>,
}

/// Every example file of Triangle's with the switch sets of the issue for its kind.
fn examples() -> Vec<Example> {
    let point_sets = ["q", "q30", "q33"];
    example_files(&data_dir())
        .into_iter()
        .map(|file| {
            let mut switches: Vec<String> = Vec::new();
            match file.kind {
                Kind::Points => switches.extend(point_sets.map(String::from)),
                Kind::Poly => {
                    switches.extend(point_sets.map(String::from));
                    switches.extend(
                        ["pq", "pq30", "pq33", "pqs", "pcq30", "pqD", "pqY"].map(String::from),
                    );
                    switches.push(format!("pq30{}", area_switch(&file.input.points)));
                    if !file.input.regions.is_empty() {
                        switches.push("pqAa".into());
                    }
                }
                Kind::Mesh { areas } => {
                    switches.extend(["rpq30", "rpqD", "rpYq"].map(String::from));
                    switches.push(format!("rpq{}", area_switch(&file.input.points)));
                    if areas {
                        switches.push("rpqa".into());
                    }
                }
            }
            Example {
                name: file.name,
                input: file.input,
                switches,
            }
        })
        .collect()
}

/// The angle bound of `q` in `switches` (`q` alone: 20°).
fn min_angle(switches: &str) -> f64 {
    let at = switches.find('q').expect("a q switch");
    let number: String = switches[at + 1..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    number.parse().unwrap_or(20.0)
}

/// The number after `a`, if any.
fn global_area(switches: &str) -> Option<f64> {
    let at = switches.find('a')?;
    let number: String = switches[at + 1..]
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    number.parse().ok()
}

/// The edges of a triangle list that only one triangle has: the boundary of a previous mesh,
/// whose edges `r` keeps as segments.
fn boundary_edges(triangles: &[i32], corners: usize) -> Vec<[i32; 2]> {
    let mut directed = HashSet::new();
    for t in triangles.chunks_exact(corners) {
        for i in 0..3 {
            directed.insert((t[i], t[(i + 1) % 3]));
        }
    }
    let mut edges: Vec<[i32; 2]> = directed
        .iter()
        .filter(|&&(a, b)| !directed.contains(&(b, a)))
        .map(|&(a, b)| [a, b])
        .collect();
    edges.sort();
    edges
}

/// The segments whose angles the output may keep: the input's, the hull's with `c`, the
/// previous mesh's boundary with `r`.
fn segments_of_the_domain(input: &MeshInput, switches: &str) -> MeshInput {
    if switches.contains('r') {
        let mut with_boundary = MeshInput {
            segments: if switches.contains('p') {
                input.segments.clone()
            } else {
                Vec::new()
            },
            segment_markers: None,
            ..input.clone()
        };
        let known: HashSet<[i32; 2]> = with_boundary
            .segments
            .iter()
            .map(|s| [s[0].min(s[1]), s[0].max(s[1])])
            .collect();
        with_boundary.segments.extend(
            boundary_edges(&input.triangles, input.corners)
                .into_iter()
                .filter(|s| !known.contains(&[s[0].min(s[1]), s[0].max(s[1])])),
        );
        with_boundary
    } else if switches.contains('c') {
        with_hull_segments(input)
    } else {
        input.clone()
    }
}

/// Whether the triangle `corners`, whose smallest angle is below θ, is excused by Triangle's
/// small-angle rule: its shortest edge (or one as short within rounding) joins two vertices on
/// two different segment chains that share a vertex, at equal distances from it.
fn excused(
    mesh: &MeshView<'_>,
    chains_of: &HashMap<usize, Vec<usize>>,
    chains: &[HashSet<usize>],
    corners: [usize; 3],
) -> bool {
    let p = |v: usize| mesh.points[v];
    let length2 = |a: usize, b: usize| (p(a)[0] - p(b)[0]).powi(2) + (p(a)[1] - p(b)[1]).powi(2);
    let edges = [0, 1, 2].map(|i| (corners[i], corners[(i + 1) % 3]));
    let shortest = edges
        .iter()
        .map(|&(a, b)| length2(a, b))
        .fold(f64::INFINITY, f64::min);
    let no_chains = Vec::new();
    edges
        .iter()
        .filter(|&&(a, b)| length2(a, b) <= shortest * (1.0 + 1e-9))
        .any(|&(u, v)| {
            let (cu, cv) = (
                chains_of.get(&u).unwrap_or(&no_chains),
                chains_of.get(&v).unwrap_or(&no_chains),
            );
            cu.iter().any(|&i| {
                cv.iter().filter(|&&j| j != i).any(|&j| {
                    chains[i].intersection(&chains[j]).any(|&o| {
                        if o == u || o == v {
                            return false;
                        }
                        let (du, dv) = (length2(o, u).sqrt(), length2(o, v).sqrt());
                        du.max(dv) <= (1.0 + EQUAL_DISTANCE) * du.min(dv)
                    })
                })
            })
        })
}

/// What one output achieved.
#[derive(Clone, Copy, Debug)]
struct Measures {
    triangles: usize,
    area: f64,
    smallest_angle: f64,
    /// The smallest angle of the triangles the small-angle rule does not excuse.
    smallest_unexcused: f64,
    excused: usize,
}

/// The regional bound of each triangle: flooding from each region point's triangle across
/// non-segment edges (a later region overrides an earlier one, as in Triangle).
fn regional_bounds(mesh: &MeshView<'_>, regions: &[[f64; 4]]) -> Vec<Option<f64>> {
    let mut bound = vec![None; mesh.triangles.len()];
    let mut triangle_of_edge = HashMap::new();
    for (t, c) in mesh.triangles.iter().enumerate() {
        for i in 0..3 {
            triangle_of_edge.insert((c[i], c[(i + 1) % 3]), t);
        }
    }
    for r in regions {
        let x = [r[0], r[1]];
        let Some(start) = mesh.triangles.iter().position(|c| {
            (0..3).all(|i| orient2d(mesh.points[c[i]], mesh.points[c[(i + 1) % 3]], x) >= 0.0)
        }) else {
            continue;
        };
        let mut seen = HashSet::from([start]);
        let mut stack = vec![start];
        while let Some(t) = stack.pop() {
            bound[t] = (r[3] > 0.0).then_some(r[3]);
            let c = mesh.triangles[t];
            for i in 0..3 {
                let (a, b) = (c[i], c[(i + 1) % 3]);
                if mesh.is_segment(a, b) {
                    continue;
                }
                if let Some(&n) = triangle_of_edge.get(&(b, a)) {
                    if seen.insert(n) {
                        stack.push(n);
                    }
                }
            }
        }
    }
    bound
}

/// The bound of each output triangle with `rpqa` and per-triangle bounds: the largest bound of
/// the previous mesh's triangles whose bounding boxes overlap its own, or none if one of them is
/// unconstrained (refinement passes a triangle's bound on to the triangles made from it, and
/// flips move edges across the old ones, so an output triangle may straddle old ones).
fn previous_mesh_bounds(mesh: &MeshView<'_>, input: &MeshInput, areas: &[f64]) -> Vec<Option<f64>> {
    let boxes = |corners: [Point; 3]| {
        let xs = corners.map(|p| p[0]);
        let ys = corners.map(|p| p[1]);
        let min = |v: [f64; 3]| v.into_iter().fold(f64::INFINITY, f64::min);
        let max = |v: [f64; 3]| v.into_iter().fold(f64::NEG_INFINITY, f64::max);
        [min(xs), min(ys), max(xs), max(ys)]
    };
    let old: Vec<[f64; 4]> = input
        .triangles
        .chunks_exact(input.corners)
        .map(|t| boxes([0, 1, 2].map(|i| input.points[t[i] as usize])))
        .collect();
    mesh.triangles
        .iter()
        .map(|c| {
            let b = boxes(c.map(|v| mesh.points[v]));
            let mut bound = Some(0.0f64);
            for (t, o) in old.iter().enumerate() {
                let overlap = o[0] < b[2] && b[0] < o[2] && o[1] < b[3] && b[1] < o[3];
                if overlap {
                    bound = bound.filter(|_| areas[t] > 0.0).map(|m| m.max(areas[t]));
                }
            }
            bound.filter(|&m| m > 0.0)
        })
        .collect()
}

/// For a point set (no segments but the hull's): the output vertices on each edge of the
/// input's convex hull (within rounding: refinement splits them), ends included.
fn hull_chains(mesh: &MeshView<'_>, input: &MeshInput) -> Vec<HashSet<usize>> {
    let hull = convex_hull(&input.points);
    (0..hull.len())
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let length2 = d[0] * d[0] + d[1] * d[1];
            (0..mesh.points.len())
                .filter(|&v| mesh.in_mesh[v])
                .filter(|&v| {
                    let p = mesh.points[v];
                    let along = (p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1];
                    let across = (p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0];
                    (0.0..=length2).contains(&along) && across.abs() <= 1e-9 * length2
                })
                .collect()
        })
        .collect()
}

/// Checks one output of `example` with `switches` (whoever made it); panics with the reason.
fn check_output(example: &Example, switches: &str, who: &str, out: &Triangulation) -> Measures {
    let strict = !switches.contains('Y');
    check_output_at(example, switches, min_angle(switches), strict, who, out)
}

/// [`check_output`] with the angle bound `theta`; an angle below it that the small-angle rule
/// does not excuse fails only when `strict` (else it is measured).
fn check_output_at(
    example: &Example,
    switches: &str,
    theta: f64,
    strict: bool,
    who: &str,
    out: &Triangulation,
) -> Measures {
    let context = format!("{}, \"{switches}\", {who} mesh", example.name);
    let fail = |e: String| -> ! { panic!("{context}: {e}") };
    let mesh = MeshView::of(out).unwrap_or_else(|e| fail(e));
    if mesh.triangles.is_empty() {
        return Measures {
            triangles: 0,
            area: 0.0,
            smallest_angle: 180.0,
            smallest_unexcused: 180.0,
            excused: 0,
        };
    }
    check_constrained_delaunay(&mesh).unwrap_or_else(|e| fail(e));
    let chain_sets: Vec<HashSet<usize>> = if switches.contains('p') || switches.contains('r') {
        let domain = segments_of_the_domain(&example.input, switches);
        segment_chains(&domain, &mesh, switches.contains('c'))
            .unwrap_or_else(|e| fail(e))
            .values()
            .map(|c| c.iter().copied().collect())
            .collect()
    } else {
        hull_chains(&mesh, &example.input)
    };
    let mut chains_of: HashMap<usize, Vec<usize>> = HashMap::new();
    for (i, c) in chain_sets.iter().enumerate() {
        for &v in c {
            chains_of.entry(v).or_default().push(i);
        }
    }

    // Angles.
    let mut measures = Measures {
        triangles: mesh.triangles.len(),
        area: mesh.area(),
        smallest_angle: 180.0,
        smallest_unexcused: 180.0,
        excused: 0,
    };
    let mut worst_unexcused = None;
    for &c in &mesh.triangles {
        let [a, b, d] = c.map(|v| mesh.points[v]);
        let smallest = angles(a, b, d).into_iter().fold(180.0, f64::min);
        measures.smallest_angle = measures.smallest_angle.min(smallest);
        if smallest >= theta - ANGLE_TOLERANCE {
            continue;
        }
        if excused(&mesh, &chains_of, &chain_sets, c) {
            measures.excused += 1;
        } else if smallest < measures.smallest_unexcused {
            measures.smallest_unexcused = smallest;
            worst_unexcused = Some([a, b, d]);
        }
    }
    if strict {
        if let Some(t) = worst_unexcused {
            fail(format!(
                "triangle {t:?} has an angle of {}°, below {theta}°, and Triangle's small-angle \
                 rule does not excuse it",
                measures.smallest_unexcused
            ));
        }
    }

    // Area bounds.
    let bounds: Vec<Option<f64>> = if switches.contains('r') && switches.ends_with("qa") {
        let areas = example
            .input
            .triangle_areas
            .as_deref()
            .expect("an .area file");
        previous_mesh_bounds(&mesh, &example.input, areas)
    } else if switches.contains("Aa") {
        regional_bounds(&mesh, &example.input.regions)
    } else {
        vec![global_area(switches); mesh.triangles.len()]
    };
    check_areas(&mesh, &|t| bounds[t]).unwrap_or_else(|e| fail(e));
    measures
}

/// Ours and Triangle's on `example` with `switches`, both checked; then the differential bounds.
fn compare(example: &Example, switches: &str, triangle: &Reference) -> String {
    let full = format!("{switches}zQ");
    let context = format!("{}, \"{full}\"", example.name);
    let theirs = triangle.triangulate(&full, &example.input);
    let ours = ours(&full, &example.input).unwrap_or_else(|e| panic!("{context}: {e}"));
    let t = check_output(example, switches, "Triangle's", &theirs);
    let o = check_output(example, switches, "our", &ours);
    let numbers = format!(
        "{context}: {} triangles (Triangle {}), smallest angle {:.4}° (Triangle {:.4}°), \
         smallest unexcused {:.4}° (Triangle {:.4}°)",
        o.triangles,
        t.triangles,
        o.smallest_angle,
        t.smallest_angle,
        o.smallest_unexcused,
        t.smallest_unexcused
    );
    assert!(
        (o.area - t.area).abs() <= 1e-9 * t.area.abs().max(f64::MIN_POSITIVE),
        "{context}: our triangles cover {}, Triangle's {}",
        o.area,
        t.area
    );
    if t.triangles == 0 {
        assert_eq!(o.triangles, 0, "{numbers}");
    } else {
        let ratio = o.triangles as f64 / t.triangles as f64;
        assert!(
            ratio <= MOST_COUNT_RATIO,
            "{numbers}: {ratio:.3}× Triangle's triangles, more than {MOST_COUNT_RATIO}×"
        );
    }
    if switches.contains('Y') {
        // Splitting the segments that may be split next to one that may not can make a worse
        // triangle against the latter (the 1° wedge: 0.67°, Triangle 1°).
        let theta = min_angle(switches);
        assert!(
            o.smallest_unexcused >= 0.5 * theta.min(t.smallest_unexcused),
            "{numbers}: with Y our smallest unexcused angle is below half of θ and of Triangle's"
        );
    }
    numbers
}

fn reference_or_fail() -> &'static Reference {
    reference().unwrap_or_else(|| {
        panic!("{REFERENCE_LIBRARY} is missing: install Debian's libtriangle-dev (.ci/run does)")
    })
}

fn run_examples(filter: impl Fn(&Example) -> bool) {
    let triangle = reference_or_fail();
    let examples: Vec<Example> = examples().into_iter().filter(|e| filter(e)).collect();
    assert!(!examples.is_empty(), "no example files of this kind");
    for example in &examples {
        let loops = TRIANGLE_LOOPS_ON.contains(&example.name.as_str());
        for switches in &example.switches {
            if loops {
                ours_alone(example, switches);
            } else {
                let numbers = compare(example, switches, triangle);
                println!("{numbers}");
            }
        }
    }
}

/// An input Triangle does not finish: ours must return a valid mesh of the same domain.
fn ours_alone(example: &Example, switches: &str) {
    let full = format!("{switches}zQ");
    let context = format!("{}, \"{full}\"", example.name);
    let out = ours(&full, &example.input).unwrap_or_else(|e| panic!("{context}: {e}"));
    let mesh = MeshView::of(&out).unwrap_or_else(|e| panic!("{context}: {e}"));
    check_constrained_delaunay(&mesh).unwrap_or_else(|e| panic!("{context}: {e}"));
    if !switches.contains('p') && !switches.contains('r') {
        let hull = polygon_area(&convex_hull(&example.input.points));
        assert!(
            (mesh.area() - hull).abs() <= 1e-9 * hull,
            "{context}: the triangles cover {}, the convex hull {hull}",
            mesh.area()
        );
    }
    println!(
        "{context}: {} triangles (Triangle does not finish)",
        mesh.triangles.len()
    );
}

#[test]
fn triangles_polys_refine_like_triangle() {
    run_examples(|e| e.switches.iter().any(|s| s.starts_with('p')));
}

#[test]
fn triangles_point_sets_refine_like_triangle() {
    run_examples(|e| {
        e.switches
            .iter()
            .all(|s| !s.starts_with('p') && !s.starts_with('r'))
    });
}

#[test]
fn triangles_meshes_refine_like_triangle() {
    run_examples(|e| e.switches.iter().any(|s| s.starts_with('r')));
}

/// `D` is truly Delaunay on every example file, point sets (`D`, `cD`) and PSLGs (`pD`, `pcD`,
/// `pqD`), decided by exact predicates (`check_conforming_delaunay`): no vertex even a rounding
/// inside a boundary subsegment's diametral circle. (`diamond_02_00009.node` with `D` put
/// (0.6, 0.3) some 10^-18 inside the circle of the hull edge (0.375, 0)–(1, 0).)
#[test]
fn conforming_delaunay_on_every_example_file_by_exact_predicates() {
    let mut checked = 0;
    for file in example_files(&data_dir()) {
        let switches: &[&str] = match file.kind {
            Kind::Points => &["D", "cD"],
            Kind::Poly => &["D", "cD", "pD", "pcD", "pqD"],
            _ => continue,
        };
        for s in switches {
            let full = format!("{s}zQ");
            let context = format!("{}, \"{full}\"", file.name);
            let (out, warnings) = engine(&full, &file.input, &Hooks::default())
                .unwrap_or_else(|e| panic!("{context}: {e}"));
            let mesh = MeshView::of(&out).unwrap_or_else(|e| panic!("{context}: {e}"));
            if mesh.triangles.is_empty() {
                continue;
            }
            // Only where the doubles cannot hold the split (greenland.node: vertices within
            // 10^-11 of hull edges; Triangle stops, "ran out of precision") may a subsegment stay
            // encroached, and then the warning says so.
            if let Err(e) = check_conforming_delaunay(&mesh) {
                assert!(
                    warnings.iter().any(|w| w.contains("precision")),
                    "{context}: {e}, and no warning"
                );
                println!("{context}: {e} (precision exhausted, warned)");
            }
            checked += 1;
        }
    }
    assert!(checked > 20, "only {checked} example meshes checked");
}

/// The square of the issue, 10 × 10, with segments from (0, 0) to the right side at the given
/// angles above the bottom side (degrees).
fn fan(angles: &[f64]) -> Example {
    let mut input = MeshInput {
        points: vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
        segments: vec![[0, 1], [2, 3], [3, 0]],
        ..MeshInput::default()
    };
    let mut right = vec![1];
    for &degrees in angles {
        let y = 10.0 * degrees.to_radians().tan();
        input.points.push([10.0, y]);
        let v = input.points.len() as i32 - 1;
        input.segments.push([0, v]);
        right.push(v);
    }
    right.push(2);
    input
        .segments
        .extend(right.windows(2).map(|w| [w[0], w[1]]));
    let switches = ["pq", "pq25", "pq30", "pqY", "pq30a1"]
        .map(String::from)
        .to_vec();
    Example {
        name: format!("square with segments at {angles:?}°"),
        input,
        switches,
    }
}

#[test]
fn wedges_and_a_fan_refine_like_triangle() {
    let triangle = reference_or_fail();
    let mut cases: Vec<Example> = [1.0, 5.0, 10.0, 15.0, 25.0].map(|a| fan(&[a])).into();
    cases.push(fan(&[5.0, 10.0]));
    cases.push(fan(&[3.0, 8.0, 20.0, 30.0, 42.0]));
    for example in &cases {
        for switches in &example.switches {
            println!("{}", compare(example, switches, triangle));
        }
    }
}

/// The issue's example: a 10 × 10 square with two 5° wedges at the origin, which `q` used to
/// leave as the four triangles of the CDT.
#[test]
fn the_issues_five_degree_wedges_are_refined() {
    let triangle = reference_or_fail();
    let mut example = fan(&[]);
    example.input.points.extend([[10.0, 0.875], [10.0, 1.763]]);
    example.input.segments = vec![
        [0, 1],
        [1, 4],
        [4, 5],
        [5, 2],
        [2, 3],
        [3, 0],
        [0, 4],
        [0, 5],
    ];
    for switches in ["pq", "pq30", "pqY"] {
        println!("{}", compare(&example, switches, triangle));
    }
    let out = ours("pqzQ", &example.input).unwrap();
    assert!(
        out.counts.triangles > 20,
        "{} triangles",
        out.counts.triangles
    );
}

/// Above 28.6° Triangle may not finish (`la.poly` with `q35`, `A.poly` with `q40`): ours returns
/// a valid mesh in which no angle the small-angle rule does not excuse is below 28.6°, and says
/// in a warning when it stopped short of θ. Up to 28.6° every example finishes at θ (the tests
/// above).
#[test]
fn beyond_the_guaranteed_angle_triangles_examples_end_at_28_6_degrees_or_better() {
    let files = example_files(&data_dir());
    for (name, switches) in [("la.poly", "pq35"), ("A.poly", "pq40")] {
        let file = example_named(&files, name);
        let example = Example {
            name: name.to_string(),
            input: file.input.clone(),
            switches: Vec::new(),
        };
        let (out, warnings) = engine(
            &format!("{switches}zQ"),
            &example.input,
            &Default::default(),
        )
        .unwrap_or_else(|e| panic!("{name}, \"{switches}\": {e}"));
        let guaranteed = check_output_at(&example, switches, 28.6, true, "our", &out);
        let at_theta = check_output_at(&example, switches, min_angle(switches), false, "our", &out);
        let reached = at_theta.smallest_unexcused >= min_angle(switches) - ANGLE_TOLERANCE;
        assert!(
            reached || warnings.iter().any(|w| w.contains("28.6")),
            "{name}, \"{switches}\": angles below θ and no warning: {warnings:?}"
        );
        println!(
            "{name}, \"{switches}\": {} triangles, smallest unexcused angle {:.4}°, {}",
            guaranteed.triangles,
            guaranteed.smallest_unexcused,
            if reached {
                "θ reached"
            } else {
                "stopped at 28.6° (warned)"
            }
        );
    }
}

/// Example file `name` as an example without switch sets of its own, and Triangle's and our
/// outputs on it with `switches` (and `zQ`).
fn both_on_file(
    files: &[ExampleFile],
    name: &str,
    switches: &str,
    triangle: &Reference,
) -> (Example, Triangulation, Triangulation) {
    let example = Example {
        name: name.to_string(),
        input: example_named(files, name).input.clone(),
        switches: Vec::new(),
    };
    let full = format!("{switches}zQ");
    let theirs = triangle.triangulate(&full, &example.input);
    let ours = ours(&full, &example.input).unwrap_or_else(|e| panic!("{name}, {full}: {e}"));
    (example, theirs, ours)
}

/// Above 30° every split of a skinny triangle makes an edge shorter than its shortest, so
/// refinement can cascade far from any input feature: on the Greenland mesh with `rq34` it once
/// made 5.4× Triangle's triangles, all in the interior (issue 24). Ours must be valid, reach θ,
/// and be no larger than Triangle's on these cases, the issue's and others of the same kind
/// (refining a mesh, a domain or a point set at 33° and 34°; not all such cases are: spiral.q.1
/// with `rq34` makes 98 triangles where Triangle makes 77).
#[test]
fn above_30_degrees_refinement_does_not_cascade_where_triangles_does_not() {
    let triangle = reference_or_fail();
    let files = example_files(&data_dir());
    let cases = [
        ("greenland.ele", "rq34"),
        ("greenland.ele", "rq33"),
        ("double_hex.2.ele", "rq34"),
        ("box.2.ele", "rq34"),
        ("face.1.ele", "rpq34"),
        ("dots.node", "q34"),
        ("la.poly", "pq34"),
        ("face.poly", "pq34"),
    ];
    for (name, switches) in cases {
        let (example, theirs, ours) = both_on_file(&files, name, switches, triangle);
        let full = format!("{switches}zQ");
        // Only ours is checked whole: without `p`, Triangle's output with `r` lists no
        // segments for the mesh's boundary (the check of the chains needs them).
        let theirs = MeshView::of(&theirs).unwrap_or_else(|e| panic!("{name}, {full}: {e}"));
        let o = check_output(&example, switches, "our", &ours);
        let t = theirs.triangles.len();
        println!(
            "{name}, \"{switches}\": {} triangles (Triangle {t})",
            o.triangles
        );
        assert!(
            o.triangles <= t,
            "{name}, \"{switches}\": {} triangles, Triangle {t}",
            o.triangles
        );
    }
}

/// With `Y`/`YY`, a bad triangle that only a vertex on a segment kept whole could mend stays
/// (a point that would encroach such a segment does not go in), as in Triangle, and the
/// improvement (`R`) may delete a vertex where the triangles around it are no worse. Ours must
/// be valid and leave no more triangles below θ than Triangle's; with `R` also no larger than
/// Triangle's (issue 24: `la.poly` with `pqYY` made 1.08× Triangle's triangles,
/// `double_hex3.poly` with `pqY` 1.17×), by default within [`Y_COUNT_RATIO`] of it.
#[test]
fn with_y_bad_triangles_stay_as_in_triangle_and_no_more() {
    let triangle = reference_or_fail();
    let files = example_files(&data_dir());
    let below = |mesh: &MeshView<'_>, theta: f64| {
        mesh.triangles
            .iter()
            .filter(|c| {
                let [a, b, d] = c.map(|v| mesh.points[v]);
                angles(a, b, d).into_iter().fold(180.0, f64::min) < theta
            })
            .count()
    };
    for name in [
        "la.poly",
        "double_hex3.poly",
        "A.poly",
        "face.poly",
        "double_hex.poly",
    ] {
        for switches in ["pqY", "pqYY", "pqYR", "pqYYR"] {
            let (example, theirs, ours) = both_on_file(&files, name, switches, triangle);
            let context = format!("{name}, \"{switches}zQ\"");
            check_output(&example, switches, "Triangle's", &theirs);
            check_output(&example, switches, "our", &ours);
            let theirs = MeshView::of(&theirs).unwrap_or_else(|e| panic!("{context}: {e}"));
            let ours = MeshView::of(&ours).unwrap_or_else(|e| panic!("{context}: {e}"));
            let (o, t) = (ours.triangles.len(), theirs.triangles.len());
            let (ob, tb) = (below(&ours, 20.0), below(&theirs, 20.0));
            println!("{context}: {o} triangles, {ob} below 20° (Triangle {t}, {tb})");
            let most = if switches.ends_with('R') {
                t as f64
            } else {
                Y_COUNT_RATIO * t as f64
            };
            assert!(o as f64 <= most, "{context}: {o} triangles, Triangle {t}");
            assert!(
                ob <= tb,
                "{context}: {ob} triangles below 20°, Triangle's {tb}"
            );
        }
    }
}

/// With `Y`/`YY` and without `R`, our count may be at most this factor of Triangle's (the
/// order of work decides a few vertices of these small meshes: `double_hex3.poly` with `pqY`
/// has 26 triangles, Triangle's 24).
const Y_COUNT_RATIO: f64 = 1.1;

/// How far below Triangle's our polished mesh's smallest angle may be (degrees).
const POLISHED_ANGLE_SLACK: f64 = 0.5;

/// With `R`, decimation keeps the mesh's smallest angle, and the polish after it raises it where moving
/// the worst triangle's corners can (issue 36: one bounded pass; the whole-mesh rounds and the
/// raise that lifted the smallest angle past Triangle's on every case cost four times the
/// time). Ours must be valid and no larger than Triangle's, and its smallest angle at most
/// [`POLISHED_ANGLE_SLACK`] below Triangle's on the issue's case (`double_hex2.poly` with `pq`:
/// 66 triangles at 20.64° where Triangle's 68 have 21.03°) and others where the mesh's worst
/// triangle is one refinement made (issue 24).
#[test]
fn improved_meshes_keep_triangles_smallest_angle_with_no_more_triangles() {
    let triangle = reference_or_fail();
    let files = example_files(&data_dir());
    let cases = [
        ("double_hex2.poly", "pq"),
        ("double_hex2.poly", "pqD"),
        ("double_hex2.poly", "pqY"),
        ("double_hex2.poly", "pq30"),
        ("double_hex.poly", "pq"),
        ("double_hex3.poly", "pq30"),
        ("A.poly", "pqD"),
        ("face.poly", "pq34"),
        ("dots.node", "q34"),
        ("square_circle_hole.poly", "pq30a0.03125"),
    ];
    for (name, switches) in cases {
        let switches = &format!("{switches}R");
        let (example, theirs, ours) = both_on_file(&files, name, switches, triangle);
        let context = format!("{name}, \"{switches}zQ\"");
        let t = check_output(&example, switches, "Triangle's", &theirs);
        let o = check_output(&example, switches, "our", &ours);
        println!(
            "{context}: {} triangles at {:.4}° (Triangle {} at {:.4}°)",
            o.triangles, o.smallest_angle, t.triangles, t.smallest_angle
        );
        assert!(
            o.triangles <= t.triangles,
            "{context}: {} triangles, Triangle {}",
            o.triangles,
            t.triangles
        );
        assert!(
            o.smallest_angle >= t.smallest_angle - POLISHED_ANGLE_SLACK,
            "{context}: smallest angle {}°, Triangle's {}°",
            o.smallest_angle,
            t.smallest_angle
        );
    }
}
