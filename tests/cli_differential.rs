//! Differential tests: Debian's `/usr/bin/triangle` and `triangle-rs` run on the same files with
//! the same switches, in separate temporary directories, and their files are compared.
//!
//! Where the result is unique (Delaunay triangulations of vertices in general position, CDTs,
//! hulls, edges, neighbours, Voronoi diagrams) the files must agree as sets: triangles are
//! compared by their corners' coordinates, so the order in which each program lists them does
//! not matter, and `.node` files of unrefined inputs must agree line for line. Where it is not
//! unique (quality refinement) the tests compare what must agree: the meshed area, the segment
//! lengths, the area per regional attribute, the angle and area bounds, and counts within a
//! factor. Malformed inputs must fail in both programs.
//!
//! Without /usr/bin/triangle the tests print SKIPPED and pass, unless env `CI` is set.

mod cli_support;

use std::collections::BTreeMap;

use cli_support::*;
use triangle_rs::io::files::{self, EleFile};

/// Both programs' runs on the same inputs.
struct Pair {
    reference: TempDir,
    ours: TempDir,
    reference_run: Run,
    our_run: Run,
    inputs: Vec<String>,
}

/// Runs both programs with `args` on copies of `inputs` (file name, text); `None` when the
/// reference is not installed.
fn run_both(tag: &str, inputs: &[(&str, &str)], args: &[&str]) -> Option<Pair> {
    let reference = reference()?;
    let pair_dirs = (
        TempDir::new(&format!("{tag}-ref")),
        TempDir::new(&format!("{tag}-ours")),
    );
    for dir in [&pair_dirs.0, &pair_dirs.1] {
        for (name, text) in inputs {
            dir.write(name, text);
        }
    }
    let reference_run = run(&reference, pair_dirs.0.path(), args);
    let our_run = run(&ours(), pair_dirs.1.path(), args);
    Some(Pair {
        reference: pair_dirs.0,
        ours: pair_dirs.1,
        reference_run,
        our_run,
        inputs: inputs.iter().map(|(n, _)| n.to_string()).collect(),
    })
}

impl Pair {
    /// Asserts that both programs succeeded.
    fn assert_both_succeeded(&self, what: &str) {
        assert!(
            self.reference_run.ok(),
            "{what}: the reference failed:\n{}{}",
            self.reference_run.stdout,
            self.reference_run.stderr
        );
        assert!(
            self.our_run.ok(),
            "{what}: triangle-rs failed:\n{}",
            self.our_run.stderr
        );
    }

    /// The output files (inputs excluded); both programs must have written the same ones.
    fn outputs(&self, what: &str) -> Vec<String> {
        let strip = |dir: &TempDir| -> Vec<String> {
            dir.files()
                .into_iter()
                .filter(|f| !self.inputs.contains(f))
                .collect()
        };
        let (reference, ours) = (strip(&self.reference), strip(&self.ours));
        assert_eq!(
            ours, reference,
            "{what}: the programs wrote different files"
        );
        ours
    }
}

fn read_ele(dir: &TempDir, name: &str) -> EleFile {
    files::read_ele(&dir.read(name), name).unwrap_or_else(|e| panic!("{e}"))
}

/// Compares every output file of a run whose result is unique.
fn compare_unique(pair: &Pair, base: &str, what: &str, node_in_order: bool) {
    let outputs: Vec<String> = pair
        .outputs(what)
        .into_iter()
        .filter(|f| f.starts_with(&format!("{base}.")))
        .collect();
    let node_name = format!("{base}.node");
    assert!(outputs.contains(&node_name), "{what}: no {node_name}");
    let reference = Results::read(&pair.reference, &node_name);
    let ours = Results::read(&pair.ours, &node_name);
    let reference_ele = read_ele(&pair.reference, &format!("{base}.ele"));
    let our_ele = read_ele(&pair.ours, &format!("{base}.ele"));
    let reference_triangles = reference.triangles(&reference_ele);
    let our_triangles = ours.triangles(&our_ele);
    for name in &outputs {
        let (ref_text, our_text) = (pair.reference.read(name), pair.ours.read(name));
        let (ref_lines, our_lines) = (without_footer(&ref_text), without_footer(&our_text));
        assert_eq!(
            our_lines.first(),
            ref_lines.first(),
            "{what}: {name}: headers differ"
        );
        let extension = name.strip_prefix(base).unwrap();
        match extension {
            ".node" => {
                if node_in_order {
                    assert_eq!(our_lines, ref_lines, "{what}: {name} differs line by line");
                } else {
                    let rows = |r: &Results| {
                        let mut rows: Vec<(Point, Vec<u64>, i32)> = (0..r.node.point_count())
                            .map(|i| {
                                let a = r.node.attribute_count;
                                (
                                    point_key(r.node.points[2 * i], r.node.points[2 * i + 1]),
                                    r.node.attributes[i * a..(i + 1) * a]
                                        .iter()
                                        .map(|v| v.to_bits())
                                        .collect(),
                                    r.node.markers.as_ref().map_or(0, |m| m[i]),
                                )
                            })
                            .collect();
                        rows.sort();
                        rows
                    };
                    assert_eq!(
                        rows(&ours),
                        rows(&reference),
                        "{what}: {name}: vertex sets differ"
                    );
                }
            }
            ".ele" => {
                assert_eq!(
                    triangle_set(&our_triangles),
                    triangle_set(&reference_triangles),
                    "{what}: triangles differ"
                );
                for t in &our_triangles {
                    assert!(
                        signed_area(&t.corners) > 0.0,
                        "{what}: triangle {:?} is not counterclockwise",
                        t.corners
                    );
                }
            }
            ".poly" => {
                let segments = |r: &Results, dir: &TempDir| {
                    let poly = files::read_poly(&dir.read(name), name, true)
                        .unwrap_or_else(|e| panic!("{e}"));
                    let mut segments: Vec<_> = (0..poly.segments.len() / 2)
                        .map(|s| {
                            let key = edge_key(
                                r.point(poly.segments[2 * s]),
                                r.point(poly.segments[2 * s + 1]),
                            );
                            (key, poly.segment_markers.as_ref().map(|m| m[s]))
                        })
                        .collect();
                    segments.sort();
                    (segments, poly.holes, poly.regions)
                };
                assert_eq!(
                    segments(&ours, &pair.ours),
                    segments(&reference, &pair.reference),
                    "{what}: {name} differs"
                );
            }
            ".edge" => {
                let edges = |r: &Results, dir: &TempDir| {
                    let edge =
                        files::read_edge(&dir.read(name), name).unwrap_or_else(|e| panic!("{e}"));
                    let mut edges: Vec<_> = (0..edge.edges.len() / 2)
                        .map(|e| {
                            (
                                edge_key(
                                    r.point(edge.edges[2 * e]),
                                    r.point(edge.edges[2 * e + 1]),
                                ),
                                edge.markers.as_ref().map(|m| m[e]),
                            )
                        })
                        .collect();
                    edges.sort();
                    edges
                };
                assert_eq!(
                    edges(&ours, &pair.ours),
                    edges(&reference, &pair.reference),
                    "{what}: {name} differs"
                );
            }
            ".neigh" => {
                let neighbours = |dir: &TempDir, r: &Results, triangles: &[CanonicalTriangle]| {
                    let neigh =
                        files::read_neigh(&dir.read(name), name).unwrap_or_else(|e| panic!("{e}"));
                    let mut rows: Vec<_> = triangles
                        .iter()
                        .enumerate()
                        .map(|(t, tri)| {
                            // Neighbour k is across from corner k: rotate them with the corners.
                            let across: Vec<Option<[Point; 3]>> = (0..3)
                                .map(|k| {
                                    let n = neigh.neighbors[3 * t + (k + tri.rotation) % 3];
                                    (n != -1).then(|| triangles[(n - r.first_index) as usize].key())
                                })
                                .collect();
                            (tri.key(), across)
                        })
                        .collect();
                    rows.sort();
                    rows
                };
                assert_eq!(
                    neighbours(&pair.ours, &ours, &our_triangles),
                    neighbours(&pair.reference, &reference, &reference_triangles),
                    "{what}: {name} differs"
                );
            }
            ".v.node" | ".v.edge" => {} // Compared together below.
            ".off" => {
                let off = |dir: &TempDir| {
                    files::read_off(&dir.read(name), name).unwrap_or_else(|e| panic!("{e}"))
                };
                let (o, r) = (off(&pair.ours), off(&pair.reference));
                assert_eq!(
                    (o.points.len(), o.triangles.len(), o.edge_count),
                    (r.points.len(), r.triangles.len(), r.edge_count)
                );
                let mut our_points: Vec<u64> = o.points.iter().map(|v| v.to_bits()).collect();
                let mut ref_points: Vec<u64> = r.points.iter().map(|v| v.to_bits()).collect();
                our_points.sort();
                ref_points.sort();
                assert_eq!(our_points, ref_points, "{what}: {name}: vertices differ");
            }
            other => panic!("{what}: unexpected output {other}"),
        }
    }
    if outputs.contains(&format!("{base}.v.node")) {
        compare_voronoi(
            pair,
            base,
            what,
            (&reference, &reference_triangles),
            (&ours, &our_triangles),
        );
    }
}

/// Voronoi vertices are compared per triangle (vertex i is the circumcentre of triangle i) to a
/// relative tolerance, since the programs compute circumcentres with different formulas; edges
/// as pairs of triangles, rays by triangle and direction.
fn compare_voronoi(
    pair: &Pair,
    base: &str,
    what: &str,
    reference: (&Results, &[CanonicalTriangle]),
    ours: (&Results, &[CanonicalTriangle]),
) {
    let tolerance = 1e-9;
    type Ray = ([Point; 3], f64, f64);
    let read = |dir: &TempDir, (results, triangles): (&Results, &[CanonicalTriangle])| {
        let node_name = format!("{base}.v.node");
        let edge_name = format!("{base}.v.edge");
        let nodes =
            files::read_node(&dir.read(&node_name), &node_name).unwrap_or_else(|e| panic!("{e}"));
        let edges = files::read_voronoi_edge(&dir.read(&edge_name), &edge_name)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            nodes.point_count(),
            triangles.len(),
            "{what}: one Voronoi vertex per triangle"
        );
        let triangle_of = |v: i32| triangles[(v - results.first_index) as usize].key();
        let a = nodes.attribute_count;
        let centres: BTreeMap<[Point; 3], Vec<f64>> = (0..nodes.point_count())
            .map(|i| {
                let mut values = vec![nodes.points[2 * i], nodes.points[2 * i + 1]];
                values.extend_from_slice(&nodes.attributes[i * a..(i + 1) * a]);
                (triangles[i].key(), values)
            })
            .collect();
        let mut finite = Vec::new();
        let mut rays: Vec<Ray> = Vec::new();
        for e in 0..edges.edges.len() / 2 {
            let (first, second) = (edges.edges[2 * e], edges.edges[2 * e + 1]);
            if second == -1 {
                rays.push((
                    triangle_of(first),
                    edges.norms[2 * e],
                    edges.norms[2 * e + 1],
                ));
            } else {
                let (p, q) = (triangle_of(first), triangle_of(second));
                finite.push(if p <= q { (p, q) } else { (q, p) });
            }
        }
        finite.sort();
        rays.sort_by(|x, y| {
            x.0.cmp(&y.0)
                .then(x.2.atan2(x.1).total_cmp(&y.2.atan2(y.1)))
        });
        (centres, finite, rays)
    };
    let (ref_centres, ref_finite, ref_rays) = read(&pair.reference, reference);
    let (our_centres, our_finite, our_rays) = read(&pair.ours, ours);
    assert_eq!(our_centres.len(), ref_centres.len());
    for (key, r) in &ref_centres {
        let o = our_centres
            .get(key)
            .unwrap_or_else(|| panic!("{what}: no Voronoi vertex for triangle {key:?}"));
        assert_eq!(o.len(), r.len());
        for (a, b) in o.iter().zip(r) {
            assert!(
                close(*a, *b, tolerance),
                "{what}: Voronoi vertex of {key:?}: {o:?} vs reference {r:?}"
            );
        }
    }
    assert_eq!(
        our_finite, ref_finite,
        "{what}: finite Voronoi edges differ"
    );
    assert_eq!(
        our_rays.len(),
        ref_rays.len(),
        "{what}: numbers of Voronoi rays differ"
    );
    for (o, r) in our_rays.iter().zip(&ref_rays) {
        assert_eq!(o.0, r.0, "{what}: rays start at different triangles");
        assert!(
            close(o.1, r.1, tolerance) && close(o.2, r.2, tolerance),
            "{what}: ray {o:?} vs reference {r:?}"
        );
    }
}

/// The point-set inputs: hand-written and generated.
fn point_sets() -> Vec<(String, String)> {
    vec![
        ("dots.node".into(), data("dots.node")),
        ("zero.node".into(), data("zero.node")),
        ("rand60.node".into(), random_node_file(1, 60, 2, true, 1)),
        ("rand400.node".into(), random_node_file(2, 400, 0, false, 0)),
        ("rand25.node".into(), random_node_file(3, 25, 1, true, 0)),
    ]
}

#[test]
fn delaunay_of_point_sets_matches_the_reference() {
    for (name, text) in point_sets() {
        let base = name.strip_suffix(".node").unwrap();
        for switches in [
            "-Q", "-Qc", "-Qv", "-Qe", "-Qn", "-Qcevn", "-Qcg", "-QcBe", "-Qjz", "-QceI",
        ] {
            let what = format!("{switches} {name}");
            let Some(pair) = run_both(base, &[(&name, &text)], &[switches, &name]) else {
                return;
            };
            pair.assert_both_succeeded(&what);
            if switches.contains('I') {
                // No .node is written over the input: compare with the input's vertices.
                let outputs = pair.outputs(&what);
                assert!(
                    !outputs.iter().any(|f| f.ends_with(".node")),
                    "{what}: {outputs:?}"
                );
                let input = Results::read(&pair.ours, &name);
                let (o, r) = (
                    read_ele(&pair.ours, &format!("{base}.ele")),
                    read_ele(&pair.reference, &format!("{base}.ele")),
                );
                assert_eq!(
                    triangle_set(&input.triangles(&o)),
                    triangle_set(&input.triangles(&r)),
                    "{what}"
                );
                continue;
            }
            compare_unique(&pair, &format!("{base}.1"), &what, true);
        }
    }
}

#[test]
fn second_iteration_reads_the_first() {
    let text = data("dots.node");
    let Some(pair) = run_both("iter", &[("dots.node", &text)], &["-Q", "dots.node"]) else {
        return;
    };
    pair.assert_both_succeeded("-Q dots.node");
    let second = |dir: &TempDir, program: &std::path::Path| {
        run(program, dir.path(), &["-Qcn", "dots.1.node"])
    };
    let (r, o) = (
        second(&pair.reference, &reference().unwrap()),
        second(&pair.ours, &ours()),
    );
    assert!(r.ok() && o.ok(), "{}{}", r.stdout, o.stderr);
    compare_unique(&pair, "dots.2", "-Qcn dots.1.node", true);
}

#[test]
fn second_order_triangles_match_the_reference() {
    for (name, text) in point_sets().into_iter().take(3) {
        let base = name.strip_suffix(".node").unwrap();
        let what = format!("-Qo2e {name}");
        let Some(pair) = run_both(base, &[(&name, &text)], &["-Qo2e", &name]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        // The midpoints are new vertices whose numbering may differ: compare as sets.
        compare_unique(&pair, &format!("{base}.1"), &what, false);
    }
}

fn pslg_inputs() -> Vec<(String, String)> {
    vec![("pslg.poly".into(), data("pslg.poly"))]
}

#[test]
fn constrained_delaunay_matches_the_reference() {
    for (name, text) in pslg_inputs() {
        let base = name.strip_suffix(".poly").unwrap();
        for switches in ["-Qp", "-QpA", "-Qpen", "-QpcA", "-QpO"] {
            let what = format!("{switches} {name}");
            let Some(pair) = run_both(base, &[(&name, &text)], &[switches, &name]) else {
                return;
            };
            pair.assert_both_succeeded(&what);
            compare_unique(&pair, &format!("{base}.1"), &what, true);
        }
    }
    // A .poly without vertices reads the .node file.
    let inputs = [
        ("separate.poly", data("separate.poly")),
        ("separate.node", data("separate.node")),
    ];
    let inputs: Vec<(&str, &str)> = inputs.iter().map(|(n, t)| (*n, t.as_str())).collect();
    for switches in ["-Qp", "-Qpce"] {
        let what = format!("{switches} separate.poly");
        let Some(pair) = run_both("separate", &inputs, &[switches, "separate.poly"]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        compare_unique(&pair, "separate.1", &what, true);
    }
}

/// Measures of a mesh that any valid answer to the same refinement problem shares.
struct MeshMeasures {
    vertices: usize,
    triangles: usize,
    total_area: f64,
    smallest_angle: f64,
    largest_area: f64,
    /// Area per triangle attribute (bits of the first attribute).
    area_by_attribute: BTreeMap<u64, f64>,
    segment_length: f64,
}

fn measure(dir: &TempDir, base: &str) -> MeshMeasures {
    let results = Results::read(dir, &format!("{base}.node"));
    let ele = read_ele(dir, &format!("{base}.ele"));
    let triangles = results.triangles(&ele);
    let mut m = MeshMeasures {
        vertices: results.node.point_count(),
        triangles: triangles.len(),
        total_area: 0.0,
        smallest_angle: 180.0,
        largest_area: 0.0,
        area_by_attribute: BTreeMap::new(),
        segment_length: 0.0,
    };
    for t in &triangles {
        let area = signed_area(&t.corners);
        assert!(
            area > 0.0,
            "{base}: triangle {:?} is not counterclockwise",
            t.corners
        );
        m.total_area += area;
        m.largest_area = m.largest_area.max(area);
        m.smallest_angle = m.smallest_angle.min(smallest_angle(&t.corners));
        if let Some(&a) = t.attributes.first() {
            *m.area_by_attribute.entry(a).or_insert(0.0) += area;
        }
    }
    let poly_name = format!("{base}.poly");
    if dir.exists(&poly_name) {
        let poly = files::read_poly(&dir.read(&poly_name), &poly_name, false)
            .unwrap_or_else(|e| panic!("{e}"));
        for s in poly.segments.chunks_exact(2) {
            let (a, b) = (
                point_value(results.point(s[0])),
                point_value(results.point(s[1])),
            );
            m.segment_length += (a.0 - b.0).hypot(a.1 - b.1);
        }
    }
    m
}

/// Compares two refinements of the same input, which need not be identical.
fn compare_refined(
    pair: &Pair,
    base: &str,
    what: &str,
    min_angle: Option<f64>,
    max_area: Option<f64>,
) {
    pair.outputs(what);
    let (o, r) = (measure(&pair.ours, base), measure(&pair.reference, base));
    assert!(
        close(o.total_area, r.total_area, 1e-9),
        "{what}: meshed areas {} vs {}",
        o.total_area,
        r.total_area
    );
    assert!(
        close(o.segment_length, r.segment_length, 1e-9),
        "{what}: segment lengths {} vs {}",
        o.segment_length,
        r.segment_length
    );
    assert_eq!(
        o.area_by_attribute.len(),
        r.area_by_attribute.len(),
        "{what}: regional attributes differ"
    );
    for ((oa, oarea), (ra, rarea)) in o.area_by_attribute.iter().zip(&r.area_by_attribute) {
        assert_eq!(oa, ra, "{what}: regional attributes differ");
        assert!(
            close(*oarea, *rarea, 1e-9),
            "{what}: area with attribute {}: {oarea} vs {rarea}",
            f64::from_bits(*oa)
        );
    }
    if let Some(angle) = min_angle {
        assert!(
            o.smallest_angle >= angle - 1e-9,
            "{what}: smallest angle {} < {angle}",
            o.smallest_angle
        );
    }
    if let Some(area) = max_area {
        assert!(
            o.largest_area <= area * (1.0 + 1e-12),
            "{what}: largest area {} > {area}",
            o.largest_area
        );
    }
    // Different refinement orders give different counts, but not wildly different ones (the
    // slack of 10 keeps tiny meshes from failing on a few vertices more or less).
    for (label, ours, theirs) in [
        ("vertices", o.vertices, r.vertices),
        ("triangles", o.triangles, r.triangles),
    ] {
        assert!(
            ours <= 2 * theirs + 10 && theirs <= 2 * ours + 10,
            "{what}: {ours} {label}, the reference has {theirs}"
        );
    }
}

#[test]
fn quality_meshes_compare_by_measures() {
    for (name, text) in pslg_inputs() {
        let base = name.strip_suffix(".poly").unwrap();
        let cases: [(&str, Option<f64>, Option<f64>); 5] = [
            ("-Qpq", Some(20.0), None),
            ("-Qpq28", Some(28.0), None),
            ("-Qpa0.3", None, Some(0.3)),
            ("-QpAa", None, None),
            ("-QpAq25a0.2", Some(25.0), Some(0.2)),
        ];
        for (switches, min_angle, max_area) in cases {
            let what = format!("{switches} {name}");
            let Some(pair) = run_both(base, &[(&name, &text)], &[switches, &name]) else {
                return;
            };
            pair.assert_both_succeeded(&what);
            compare_refined(&pair, &format!("{base}.1"), &what, min_angle, max_area);
        }
    }
    // Quality meshing of a point set (the convex hull is the domain).
    let text = random_node_file(4, 40, 1, true, 1);
    let what = "-Qq rand40.node";
    let Some(pair) = run_both(
        "q-points",
        &[("rand40.node", &text)],
        &["-Qq", "rand40.node"],
    ) else {
        return;
    };
    pair.assert_both_succeeded(what);
    compare_refined(&pair, "rand40.1", what, Some(20.0), None);
}

#[test]
fn refinement_of_a_mesh_matches_the_reference() {
    let Some(reference_program) = reference() else {
        return;
    };
    // The mesh to refine is the reference's triangulation of dots.node.
    let setup = TempDir::new("refine-setup");
    setup.write("dots.node", &data("dots.node"));
    assert!(run(&reference_program, setup.path(), &["-Q", "dots.node"]).ok());
    let (node, ele) = (setup.read("dots.1.node"), setup.read("dots.1.ele"));
    let triangle_count = files::read_ele(&ele, "dots.1.ele")
        .unwrap()
        .triangle_count();
    let areas: String = std::iter::once(format!("{triangle_count}\n"))
        .chain(
            (1..=triangle_count).map(|t| format!("{t} {}\n", if t % 2 == 0 { 0.5 } else { -1.0 })),
        )
        .collect();
    let inputs = [
        ("dots.1.node", node.as_str()),
        ("dots.1.ele", ele.as_str()),
        ("dots.1.area", areas.as_str()),
    ];

    // Refinement without constraints keeps the mesh.
    let what = "-Qre dots.1";
    let Some(pair) = run_both("refine", &inputs, &["-Qre", "dots.1"]) else {
        return;
    };
    pair.assert_both_succeeded(what);
    compare_unique(&pair, "dots.2", what, true);
    for (switches, min_angle, max_area) in [
        ("-Qrq", Some(20.0), None),
        ("-Qra", None, None),
        ("-Qra1", None, Some(1.0)),
    ] {
        let what = format!("{switches} dots.1");
        let Some(pair) = run_both("refine", &inputs, &[switches, "dots.1"]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        compare_refined(&pair, "dots.2", &what, min_angle, max_area);
    }
    // An .area input name implies -r and -a.
    let what = "-Q dots.1.area";
    let Some(pair) = run_both("refine-area", &inputs, &["-Q", "dots.1.area"]) else {
        return;
    };
    pair.assert_both_succeeded(what);
    compare_refined(&pair, "dots.2", what, None, None);
}

/// `r` with `p`: the mesh of `x.node`/`x.ele` is refined respecting the segments of `x.poly`
/// (Triangle's own output, without vertices), and the triangles keep their attributes.
#[test]
fn refinement_with_segments_reads_the_poly_file() {
    let Some(reference_program) = reference() else {
        return;
    };
    let setup = TempDir::new("refine-p-setup");
    setup.write("pslg.poly", &data("pslg.poly"));
    assert!(run(&reference_program, setup.path(), &["-QpA", "pslg.poly"]).ok());
    let texts: Vec<(String, String)> = ["pslg.1.node", "pslg.1.ele", "pslg.1.poly"]
        .iter()
        .map(|name| (name.to_string(), setup.read(name)))
        .collect();
    let inputs: Vec<(&str, &str)> = texts
        .iter()
        .map(|(n, t)| (n.as_str(), t.as_str()))
        .collect();
    for (switches, min_angle, max_area) in
        [("-Qrpq", Some(20.0), None), ("-Qrpa0.5", None, Some(0.5))]
    {
        let what = format!("{switches} pslg.1");
        let Some(pair) = run_both("refine-p", &inputs, &[switches, "pslg.1"]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        compare_refined(&pair, "pslg.2", &what, min_angle, max_area);
        let (ours, theirs) = (
            files::read_poly(&pair.ours.read("pslg.2.poly"), "pslg.2.poly", false).unwrap(),
            files::read_poly(&pair.reference.read("pslg.2.poly"), "pslg.2.poly", false).unwrap(),
        );
        assert_eq!(ours.holes, theirs.holes, "{what}: holes");
    }
}

/// `r` on a mesh of six-node triangles (`o2`): both programs use the corners and leave the
/// mid-edge nodes out of the output.
#[test]
fn refinement_of_a_second_order_mesh_drops_the_mid_nodes() {
    let Some(reference_program) = reference() else {
        return;
    };
    let setup = TempDir::new("refine-o2-setup");
    setup.write("pslg.poly", &data("pslg.poly"));
    assert!(run(&reference_program, setup.path(), &["-Qpo2", "pslg.poly"]).ok());
    let (node, ele) = (setup.read("pslg.1.node"), setup.read("pslg.1.ele"));
    let input = files::read_ele(&ele, "pslg.1.ele").unwrap();
    assert_eq!(input.corners, 6);
    let inputs = [("pslg.1.node", node.as_str()), ("pslg.1.ele", ele.as_str())];
    let what = "-Qre pslg.1 (six-node triangles)";
    let Some(pair) = run_both("refine-o2", &inputs, &["-Qre", "pslg.1"]) else {
        return;
    };
    pair.assert_both_succeeded(what);
    // Same vertices, line by line: the corners in input order, without the mid-edge nodes.
    compare_unique(&pair, "pslg.2", what, true);
    let corners: std::collections::BTreeSet<i32> = input
        .triangles
        .chunks_exact(6)
        .flat_map(|t| t[..3].to_vec())
        .collect();
    assert_eq!(
        files::read_node(&pair.ours.read("pslg.2.node"), "n")
            .unwrap()
            .point_count(),
        corners.len()
    );
    let what = "-Qrq pslg.1 (six-node triangles)";
    let Some(pair) = run_both("refine-o2", &inputs, &["-Qrq", "pslg.1"]) else {
        return;
    };
    pair.assert_both_succeeded(what);
    compare_refined(&pair, "pslg.2", what, Some(20.0), None);
}

#[test]
fn malformed_files_fail_in_both_programs() {
    let node = "4\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n";
    let cases: [(&str, Vec<(&str, &str)>); 6] = [
        ("d.node", vec![("d.node", "3 3 0 0\n1 0 0\n2 1 0\n3 0 1\n")]),
        ("s.node", vec![("s.node", "4 2 0 0\n1 0 0\n2 1 0\n3 0 1\n")]),
        ("y.node", vec![("y.node", "3 2 0 0\n1 0 0\n2 1\n3 0 1\n")]),
        ("two.node", vec![("two.node", "2\n1 0 0\n2 1 0\n")]),
        ("h.poly", vec![("h.poly", "3\n1 0 0\n2 1 0\n3 0 1\n0 0\n")]),
        (
            "m.area",
            vec![
                ("m.node", node),
                ("m.ele", "2 3 0\n1 1 2 3\n2 1 3 4\n"),
                ("m.area", "1\n1 0.5\n"),
            ],
        ),
    ];
    for (input, files) in cases {
        let Some(pair) = run_both("bad", &files, &["-Q", input]) else {
            return;
        };
        assert!(!pair.reference_run.ok(), "the reference accepted {input}");
        assert!(!pair.our_run.ok(), "triangle-rs accepted {input}");
        assert!(
            pair.our_run
                .stderr
                .contains(&input[..input.find('.').unwrap()]),
            "{}",
            pair.our_run.stderr
        );
        assert!(
            pair.outputs(input).is_empty(),
            "{input}: outputs were written"
        );
    }
}

/// A UTF-8 byte-order mark before the first line (as some editors save) is skipped by both.
#[test]
fn byte_order_marks_are_skipped_as_the_reference_skips_them() {
    let marked = |text: &str| format!("\u{feff}{text}");
    let node = marked(&data("dots.node"));
    let Some(pair) = run_both("bom", &[("dots.node", &node)], &["-Qcen", "dots.node"]) else {
        return;
    };
    pair.assert_both_succeeded("-Qcen dots.node with a byte-order mark");
    compare_unique(
        &pair,
        "dots.1",
        "-Qcen dots.node with a byte-order mark",
        true,
    );
    let poly = marked(&data("pslg.poly"));
    let Some(pair) = run_both("bom", &[("pslg.poly", &poly)], &["-Qpcen", "pslg.poly"]) else {
        return;
    };
    pair.assert_both_succeeded("-Qpcen pslg.poly with a byte-order mark");
    compare_unique(
        &pair,
        "pslg.1",
        "-Qpcen pslg.poly with a byte-order mark",
        true,
    );
}

/// The counts of a histogram printed as nine rows of two `label: count` columns, the left
/// column first, after the line containing `title`.
fn histogram(stdout: &str, title: &str, rows: usize) -> Vec<usize> {
    let lines: Vec<&str> = stdout
        .lines()
        .skip_while(|l| !l.contains(title))
        .skip(1)
        .take(rows)
        .collect();
    assert_eq!(lines.len(), rows, "no histogram `{title}` in:\n{stdout}");
    let mut left = Vec::new();
    let mut right = Vec::new();
    for line in lines {
        let counts: Vec<usize> = line
            .split(':')
            .skip(1)
            .map(|part| part.split_whitespace().next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(counts.len(), 2, "{line}");
        left.push(counts[0]);
        right.push(counts[1]);
    }
    left.extend(right);
    left
}

#[test]
fn verbose_statistics_match_the_reference() {
    for (name, text) in point_sets().into_iter().take(3) {
        let what = format!("-V {name}");
        let Some(pair) = run_both("verbose", &[(&name, &text)], &["-V", &name]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        let (o, r) = (&pair.our_run.stdout, &pair.reference_run.stdout);
        assert_eq!(
            histogram(o, "Angle histogram", 9),
            histogram(r, "Angle histogram", 9),
            "{what}: angle histograms differ"
        );
        assert_eq!(
            histogram(o, "Triangle aspect ratio histogram", 8),
            histogram(r, "Triangle aspect ratio histogram", 8),
            "{what}: aspect ratio histograms differ"
        );
        for label in ["Mesh vertices", "Mesh triangles", "Mesh edges"] {
            let value = |s: &str| {
                s.lines()
                    .find(|l| l.trim_start().starts_with(label))
                    .map(|l| l.trim().to_string())
            };
            assert_eq!(value(o), value(r), "{what}: {label}");
        }
    }
}

/// The statistic lines of Triangle's stdout: from `Statistics:` on, without its memory and
/// algorithmic statistics (counts of its own data structures and predicates).
fn statistic_lines(stdout: &str) -> Vec<&str> {
    let mut lines = Vec::new();
    let mut section = "";
    for line in stdout.lines() {
        if !line.is_empty() && !line.starts_with(' ') {
            section = line;
        }
        let statistics = section == "Statistics:" || section == "Mesh quality statistics:";
        let check = ["  Checking", "  In my studied", "  By virtue"]
            .iter()
            .any(|p| line.starts_with(p));
        if (statistics && !line.trim().is_empty()) || check {
            lines.push(line);
        }
    }
    lines
}

/// Scripts grep Triangle's stdout: every statistic line it prints (the statistics, with `V`
/// the quality statistics and histograms, with `C` the check's report) is on our stdout word
/// for word, our warnings are on stdout as Triangle's, and stderr holds nothing but, with `V`,
/// our phases (a passing check is no warning).
#[test]
fn statistics_warnings_and_the_check_go_to_stdout_as_the_reference_prints_them() {
    let square = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n";
    let mesh = [("m.node", square), ("m.ele", "2 3 0\n1 1 2 3\n2 1 3 4\n")];
    let dots = data("dots.node");
    let pslg = data("pslg.poly");
    // Large and small measures, which `%.5g` writes with exponents (5.1736e+06, 3.4901e-13).
    let corners: [(f64, f64); 7] = [
        (0.0, 0.0),
        (31.0, 1.2),
        (15.0, 27.0),
        (4.0, 9.0),
        (22.0, 13.0),
        (0.1, 30.0),
        (0.13, 0.2),
    ];
    let scaled = |scale: f64| {
        let mut text = format!("{} 2 0 0\n", corners.len());
        for (i, (x, y)) in corners.iter().enumerate() {
            text.push_str(&format!("{} {} {}\n", i + 1, x * scale, y * scale));
        }
        text
    };
    let (large, small) = (scaled(1e6), scaled(1e-6));
    type Case<'a> = (&'a str, Vec<(&'a str, &'a str)>, &'a str);
    let cases: Vec<Case> = vec![
        ("-C", vec![("dots.node", &dots)], "dots.node"),
        ("-CV", vec![("dots.node", &dots)], "dots.node"),
        ("-cV", vec![("dots.node", &dots)], "dots.node"),
        ("-V", vec![("large.node", &large)], "large.node"),
        ("-V", vec![("small.node", &small)], "small.node"),
        ("-pC", vec![("pslg.poly", &pslg)], "pslg.poly"),
        ("-pcCV", vec![("pslg.poly", &pslg)], "pslg.poly"),
        ("-pOV", vec![("pslg.poly", &pslg)], "pslg.poly"),
        ("-rC", mesh.to_vec(), "m"),
    ];
    for (switches, inputs, input) in cases {
        let what = format!("{switches} {input}");
        let Some(pair) = run_both("stdout", &inputs, &[switches, input]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        let (ours, theirs) = (&pair.our_run, &pair.reference_run);
        let expected = statistic_lines(&theirs.stdout);
        assert!(expected.len() >= 5, "{what}: {}", theirs.stdout);
        if switches.contains('C') {
            assert!(expected.iter().any(|l| l.contains("I declare the mesh")));
        }
        for line in expected {
            assert!(
                ours.stdout.lines().any(|l| l == line),
                "{what}: our stdout lacks Triangle's line `{line}`:\n{}",
                ours.stdout
            );
        }
        let progress = |l: &str| {
            switches.contains('V')
                && [
                    "triangle-rs: Delaunay",
                    "triangle-rs: segment",
                    "triangle-rs: output",
                ]
                .iter()
                .any(|p| l.starts_with(p))
        };
        assert!(
            ours.stderr.lines().all(progress),
            "{what}: stderr holds more than the phases:\n{}",
            ours.stderr
        );
    }

    // Warnings: on stdout, Triangle's words first (ours add which vertex is duplicated).
    let duplicates = "5 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n5 1 1\n";
    let Some(pair) = run_both("warnings", &[("d.node", duplicates)], &["-C", "d.node"]) else {
        return;
    };
    pair.assert_both_succeeded("-C d.node");
    let warnings: Vec<&str> = pair
        .reference_run
        .stdout
        .lines()
        .filter(|l| l.starts_with("Warning:"))
        .collect();
    assert_eq!(warnings.len(), 1, "{}", pair.reference_run.stdout);
    for warning in warnings {
        let words = warning.trim_end_matches('.');
        assert!(
            pair.our_run.stdout.lines().any(|l| l.starts_with(words)),
            "our stdout lacks `{words}`:\n{}",
            pair.our_run.stdout
        );
    }
    assert!(
        pair.our_run.stderr.is_empty(),
        "-C d.node: {}",
        pair.our_run.stderr
    );
}

/// Counts in the header line of each output file.
fn header_counts(dir: &TempDir, name: &str) -> String {
    let text = dir.read(name);
    let header = text
        .lines()
        .find(|l| !l.trim().is_empty() && !l.starts_with('#') && *l != "OFF")
        .unwrap_or("");
    header.to_string()
}

#[test]
fn degenerate_point_sets_agree_on_counts_hull_and_vertices() {
    // A 6 x 4 grid: every cell's corners are cocircular, so the triangulation is not unique, but
    // the counts, the vertex list and the hull are.
    let mut grid = String::from("24 2 0 0\n");
    for i in 0..24 {
        grid.push_str(&format!("{} {} {}\n", i + 1, i % 6, i / 6));
    }
    let Some(pair) = run_both("grid", &[("grid.node", &grid)], &["-Qcevn", "grid.node"]) else {
        return;
    };
    pair.assert_both_succeeded("-Qcevn grid.node");
    for name in pair.outputs("-Qcevn grid.node") {
        assert_eq!(
            header_counts(&pair.ours, &name),
            header_counts(&pair.reference, &name),
            "{name}: counts differ"
        );
    }
    assert_eq!(
        without_footer(&pair.ours.read("grid.1.node")),
        without_footer(&pair.reference.read("grid.1.node"))
    );
    let hull = |dir: &TempDir| {
        let results = Results::read(dir, "grid.1.node");
        let poly = files::read_poly(&dir.read("grid.1.poly"), "grid.1.poly", false).unwrap();
        let mut segments: Vec<_> = poly
            .segments
            .chunks_exact(2)
            .map(|s| edge_key(results.point(s[0]), results.point(s[1])))
            .collect();
        segments.sort();
        segments
    };
    assert_eq!(
        hull(&pair.ours),
        hull(&pair.reference),
        "the hull segments differ"
    );
}

#[test]
fn duplicate_vertices_are_reported_and_kept_out_of_the_mesh() {
    let mut text = random_node_file(5, 30, 1, true, 1);
    // Three copies of earlier vertices, appended (the header count is rewritten).
    let rows: Vec<String> = text.lines().skip(2).map(String::from).collect();
    for (k, source) in [3usize, 10, 3].iter().enumerate() {
        let fields: Vec<&str> = rows[*source].split_whitespace().collect();
        text.push_str(&format!("{} {} {} 0.5 0\n", 31 + k, fields[1], fields[2]));
    }
    let text = text.replacen("30 2 1 1", "33 2 1 1", 1);
    for switches in ["-Qe", "-Qje"] {
        let what = format!("{switches} dups.node");
        let Some(pair) = run_both("dups", &[("dups.node", &text)], &[switches, "dups.node"]) else {
            return;
        };
        pair.assert_both_succeeded(&what);
        // The duplicates' removal keeps the triangulation of the distinct vertices.
        let (o, r) = (
            Results::read(&pair.ours, "dups.1.node"),
            Results::read(&pair.reference, "dups.1.node"),
        );
        assert_eq!(
            o.node.point_count(),
            r.node.point_count(),
            "{what}: vertex counts differ"
        );
        let (oe, re) = (
            read_ele(&pair.ours, "dups.1.ele"),
            read_ele(&pair.reference, "dups.1.ele"),
        );
        let corners = |results: &Results, ele: &EleFile| {
            let mut set: Vec<[Point; 3]> = results.triangles(ele).iter().map(|t| t.key()).collect();
            set.sort();
            set
        };
        assert_eq!(
            corners(&o, &oe),
            corners(&r, &re),
            "{what}: triangles differ"
        );
    }
}
