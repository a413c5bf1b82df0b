//! Planar straight line graphs for the constrained Delaunay tests and benchmark: the classic
//! shapes of tests/data/shapes/ (read with our `.poly` reader), seeded random PSLGs (polygons
//! with holes and islands, crossing segments, vertices on segments, duplicates referenced by
//! segments), the random star-shaped polygon of benches/cdt.rs and benches/refine.rs, and the
//! square with a circular hole of benches/refine.rs.
//!
//! A [`Pslg`] keeps its input zero-based; [`Pslg::input_for`] shifts the segment (and triangle)
//! indices to the base the switches ask for. It also carries what its generator knows about the answer (the
//! meshed area, which region covers which point), for the property tests.

use std::f64::consts::TAU;

use triangle_rs::io::files::read_poly;

use super::call::MeshInput;
use super::checks::{convex_hull, orient2d};
use super::examples::poly_input;
use super::points::Point;
use super::rng::SplitMix64;

/// A PSLG and what its generator knows about the mesh of it.
#[derive(Clone, Debug)]
pub struct Pslg {
    pub name: String,
    /// Segment indices zero-based.
    pub input: MeshInput,
    /// The area meshed with `p` (holes eaten), when the generator knows it.
    pub area: Option<f64>,
    /// The area meshed with `pO` (holes ignored).
    pub area_ignoring_holes: Option<f64>,
    /// Meant for `c`: the domain is the convex hull (its area is the hull's).
    pub convex: bool,
    /// Polygons with their own region attribute; elsewhere the mesh has `outer_attribute`.
    pub islands: Vec<(Vec<Point>, f64)>,
    pub outer_attribute: f64,
    /// The polygons around hole points: with `O` they are meshed, with no region attribute (0).
    pub hole_polygons: Vec<Vec<Point>>,
    /// The vertices have one attribute, [`affine_attribute`] of their coordinates.
    pub affine_attributes: bool,
    /// Holds input Triangle has undefined behaviour on (duplicates referenced by segments):
    /// property-test it on ours only.
    pub ours_only: bool,
}

impl Pslg {
    /// A PSLG that nothing is known about but its input (zero-based).
    pub fn new(name: String, input: MeshInput) -> Pslg {
        Pslg {
            name,
            input,
            area: None,
            area_ignoring_holes: None,
            convex: false,
            islands: Vec::new(),
            outer_attribute: 0.0,
            hole_polygons: Vec::new(),
            affine_attributes: false,
            ours_only: false,
        }
    }

    /// The input with segment (and, for `r`, triangle) indices in the numbering of `switches`
    /// (0-based with `z`).
    pub fn input_for(&self, switches: &str) -> MeshInput {
        let base = i32::from(!switches.contains('z'));
        let mut input = self.input.clone();
        for s in &mut input.segments {
            *s = s.map(|v| v + base);
        }
        for v in &mut input.triangles {
            *v += base;
        }
        input
    }

    /// The region attribute expected at `p` (inside an island, a hole meshed with `O`, or
    /// neither).
    pub fn attribute_at(&self, p: Point) -> f64 {
        if self
            .hole_polygons
            .iter()
            .any(|polygon| contains(polygon, p))
        {
            return 0.0;
        }
        self.islands
            .iter()
            .find(|(polygon, _)| contains(polygon, p))
            .map_or(self.outer_attribute, |(_, a)| *a)
    }

    /// The area meshed with `switches`, when known.
    pub fn expected_area(&self, switches: &str) -> Option<f64> {
        if self.convex {
            Some(polygon_area(&convex_hull(&self.input.points)))
        } else if switches.contains('O') {
            self.area_ignoring_holes
        } else {
            self.area
        }
    }
}

/// The signed area of a closed polygon (positive counter-clockwise), summed
/// relative to its first vertex.
pub fn polygon_area(polygon: &[Point]) -> f64 {
    let Some(&o) = polygon.first() else {
        return 0.0;
    };
    let mut twice = 0.0;
    for i in 1..polygon.len().saturating_sub(1) {
        let (a, b) = (polygon[i], polygon[i + 1]);
        twice += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    }
    0.5 * twice
}

/// Whether `p` lies inside the simple polygon (even-odd rule; points on the boundary are not
/// expected).
pub fn contains(polygon: &[Point], p: Point) -> bool {
    let mut inside = false;
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            // Crossing of the horizontal line through p, left of p?
            let side = orient2d(a, b, p);
            if (side > 0.0) == (b[1] > a[1]) {
                inside = !inside;
            }
        }
    }
    inside
}

/// The classic shapes' file names (without `.poly`), in tests/data/shapes/.
pub const SHAPES: &[&str] = &[
    "letter_a",
    "box_in_box",
    "double_hexagon",
    "spiral",
    "square_circular_hole",
    "three_regions",
    "pinched",
    "bow_tie",
];

/// The path of a shape's `.poly` file.
pub fn shape_path(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/shapes")
        .join(format!("{name}.poly"))
}

/// A classic shape read with our `.poly` reader (regions included), zero-based.
pub fn shape(name: &str) -> Pslg {
    let path = shape_path(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let poly = read_poly(&text, &path.to_string_lossy(), true).unwrap_or_else(|e| panic!("{e}"));
    Pslg::new(name.to_string(), poly_input(&poly))
}

/// Vertex markers: mostly 0, some positive, one negative value.
fn vertex_marker(rng: &mut SplitMix64) -> i32 {
    [0, 0, 0, 0, 2, 6, -3][rng.below(7)]
}

/// Segment markers: some 0 (then 1 on the boundary or 0 inside), the rest varied.
fn segment_marker(rng: &mut SplitMix64) -> i32 {
    [0, 0, 1, 4, 5, 9, -2][rng.below(7)]
}

/// A star-shaped polygon of `n` vertices around `centre`: angles jittered around equal steps
/// (every gap below 1.8 · 2π/n), radii uniform in [`r_min`, `r_max`], counter-clockwise.
fn star(rng: &mut SplitMix64, centre: Point, n: usize, r_min: f64, r_max: f64) -> Vec<Point> {
    let phase = rng.next_f64() * TAU;
    (0..n)
        .map(|i| {
            let angle = phase + TAU * (i as f64 + 0.8 * rng.next_f64()) / n as f64;
            let r = r_min + (r_max - r_min) * rng.next_f64();
            [centre[0] + r * angle.cos(), centre[1] + r * angle.sin()]
        })
        .collect()
}

/// Appends a closed loop of vertices and its segments.
fn push_loop(input: &mut MeshInput, rng: &mut SplitMix64, polygon: &[Point]) {
    let first = input.points.len() as i32;
    let n = polygon.len() as i32;
    for &p in polygon {
        input.points.push(p);
        input
            .markers
            .get_or_insert_with(Vec::new)
            .push(vertex_marker(rng));
    }
    for k in 0..n {
        input.segments.push([first + k, first + (k + 1) % n]);
        input
            .segment_markers
            .get_or_insert_with(Vec::new)
            .push(segment_marker(rng));
    }
}

/// One attribute per vertex, an affine function of its coordinates: the attributes Triangle
/// interpolates at new vertices must follow the same function.
pub fn affine_attribute(p: Point) -> f64 {
    1.0 + 2.0 * p[0] - 3.0 * p[1]
}

fn add_affine_attributes(input: &mut MeshInput) {
    input.attribute_count = 1;
    input.attributes = input.points.iter().map(|&p| affine_attribute(p)).collect();
}

/// A random star-shaped polygon (6 to 40 vertices, radius 0.6 to 1, so it contains the disc of
/// radius 0.35) with up to four inner star-shaped polygons in the cells of a 2 × 2 grid inside
/// that disc: each is a hole (a hole point at its centre, and a free vertex inside it that the
/// holes eat) or an island (a region point at its centre). A region point outside the inner
/// polygons gives the rest attribute 1. A few free vertices lie in the meshed ring.
pub fn polygon_with_holes(seed: u64) -> Pslg {
    let corners = 6 + SplitMix64::new(!seed).below(35);
    polygon_with_holes_of(seed, corners)
}

/// As [`polygon_with_holes`], with `corners` (at least 6) outer vertices.
pub fn polygon_with_holes_of(seed: u64, corners: usize) -> Pslg {
    assert!(
        corners >= 6,
        "the outer polygon contains the inner ones from 6 corners on"
    );
    let mut rng = SplitMix64::new(seed);
    let mut input = MeshInput::default();
    let outer = star(&mut rng, [0.0, 0.0], corners, 0.6, 1.0);
    push_loop(&mut input, &mut rng, &outer);
    let mut area = polygon_area(&outer);
    let area_ignoring_holes = area;
    let mut islands = Vec::new();
    let mut hole_polygons = Vec::new();
    let mut free = Vec::new();
    for cell in 0..4 {
        if rng.below(5) == 0 {
            continue;
        }
        let centre = [
            if cell % 2 == 0 { -0.115 } else { 0.115 } + 0.01 * (rng.next_f64() - 0.5),
            if cell / 2 == 0 { -0.115 } else { 0.115 } + 0.01 * (rng.next_f64() - 0.5),
        ];
        // At least 5 vertices: every gap is below π and the centre is well inside.
        let corners = 5 + rng.below(4);
        let polygon = star(&mut rng, centre, corners, 0.04, 0.1);
        push_loop(&mut input, &mut rng, &polygon);
        if rng.below(2) == 0 {
            input.holes.push(centre);
            area -= polygon_area(&polygon);
            free.push([centre[0] + 0.01, centre[1] + 0.004]);
            hole_polygons.push(polygon);
        } else {
            let attribute = 2.0 + cell as f64;
            input
                .regions
                .push([centre[0], centre[1], attribute, 0.01 * (cell + 1) as f64]);
            islands.push((polygon, attribute));
        }
    }
    input.regions.push([0.0, 0.34, 1.0, -1.0]);
    // Free vertices in the ring between the inner polygons (radius < 0.27) and the outer
    // polygon (radius > 0.35).
    for _ in 0..rng.below(4) {
        let (angle, r) = (rng.next_f64() * TAU, 0.28 + 0.06 * rng.next_f64());
        free.push([r * angle.cos(), r * angle.sin()]);
    }
    for p in free {
        input.points.push(p);
        input
            .markers
            .get_or_insert_with(Vec::new)
            .push(vertex_marker(&mut rng));
    }
    add_affine_attributes(&mut input);
    Pslg {
        area: Some(area),
        area_ignoring_holes: Some(area_ignoring_holes),
        islands,
        hole_polygons,
        outer_attribute: 1.0,
        affine_attributes: true,
        ..Pslg::new(
            format!("polygon of {corners} corners with holes (seed {seed})"),
            input,
        )
    }
}

/// `n` uniform random vertices and `m` segments between random pairs of them: the segments
/// cross each other (new vertices). Meant for `c` (the domain is the convex hull).
/// `input` with the edges of its convex hull added as segments: with `c` they are segments of
/// the output, and the angles they make with the input segments are angles of the input.
pub fn with_hull_segments(input: &MeshInput) -> MeshInput {
    let index = |p: Point| {
        input
            .points
            .iter()
            .position(|&q| q == p)
            .expect("a hull point is an input point")
    };
    let hull: Vec<i32> = convex_hull(&input.points)
        .into_iter()
        .map(|p| index(p) as i32)
        .collect();
    let mut segments = input.segments.clone();
    segments.extend((0..hull.len()).map(|i| [hull[i], hull[(i + 1) % hull.len()]]));
    let segment_markers = input.segment_markers.clone().map(|mut markers| {
        markers.resize(segments.len(), 1);
        markers
    });
    MeshInput {
        segments,
        segment_markers,
        ..input.clone()
    }
}

pub fn crossing_segments(seed: u64, n: usize, m: usize) -> Pslg {
    let mut rng = SplitMix64::new(seed);
    let mut input = MeshInput::default();
    for _ in 0..n {
        input.points.push([rng.next_f64(), rng.next_f64()]);
        input
            .markers
            .get_or_insert_with(Vec::new)
            .push(vertex_marker(&mut rng));
    }
    let mut joined = std::collections::HashSet::new();
    while input.segments.len() < m.min(n * (n - 1) / 2) {
        let a = rng.below(n);
        let b = (a + 1 + rng.below(n - 1)) % n;
        // Each pair once: a repeated segment with another marker is a separate case (see
        // tests/pslg_differential.rs, `repeated_segments_take_the_first_nonzero_marker`).
        if !joined.insert([a.min(b), a.max(b)]) {
            continue;
        }
        input.segments.push([a as i32, b as i32]);
        input
            .segment_markers
            .get_or_insert_with(Vec::new)
            .push(segment_marker(&mut rng));
    }
    add_affine_attributes(&mut input);
    Pslg {
        convex: true,
        affine_attributes: true,
        ..Pslg::new(
            format!("{n} vertices, {m} crossing segments (seed {seed})"),
            input,
        )
    }
}

/// Vertices on a small integer lattice and segments between them, with (some of) the lattice
/// points each segment passes through added as vertices, so vertices lie exactly on segments,
/// segments overlap, cross at vertices and between them. One segment has equal endpoints
/// (skipped). Exactly cocircular vertices abound: the constrained Delaunay triangulation is
/// not unique. Meant for `c`.
pub fn vertices_on_segments(seed: u64, side: i32, m: usize) -> Pslg {
    let mut rng = SplitMix64::new(seed);
    let mut input = MeshInput::default();
    let mut index_of = std::collections::HashMap::new();
    let mut vertex = |input: &mut MeshInput, rng: &mut SplitMix64, p: [i32; 2]| -> i32 {
        *index_of.entry(p).or_insert_with(|| {
            input.points.push([p[0] as f64 * 0.5, p[1] as f64 * 0.25]);
            input
                .markers
                .get_or_insert_with(Vec::new)
                .push(vertex_marker(rng));
            input.points.len() as i32 - 1
        })
    };
    let lattice = |rng: &mut SplitMix64| {
        [
            rng.below(side as usize + 1) as i32,
            rng.below(side as usize + 1) as i32,
        ]
    };
    for _ in 0..m {
        let (a, b) = (lattice(&mut rng), lattice(&mut rng));
        let (ia, ib) = (
            vertex(&mut input, &mut rng, a),
            vertex(&mut input, &mut rng, b),
        );
        input.segments.push([ia, ib]);
        input
            .segment_markers
            .get_or_insert_with(Vec::new)
            .push(segment_marker(&mut rng));
        // The lattice points strictly inside the segment.
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let steps = gcd(dx.abs(), dy.abs());
        for k in 1..steps {
            if rng.below(3) != 0 {
                vertex(
                    &mut input,
                    &mut rng,
                    [a[0] + k * dx / steps, a[1] + k * dy / steps],
                );
            }
        }
    }
    // A few free lattice vertices, so that the hull is not just the segments' hull.
    for _ in 0..3 {
        let p = lattice(&mut rng);
        vertex(&mut input, &mut rng, p);
    }
    let repeated = input.segments[0][0];
    input.segments.push([repeated, repeated]);
    input.segment_markers.get_or_insert_with(Vec::new).push(3);
    add_affine_attributes(&mut input);
    Pslg {
        convex: true,
        affine_attributes: true,
        ..Pslg::new(
            format!("lattice {side}, {m} segments with vertices on them (seed {seed})"),
            input,
        )
    }
}

fn gcd(a: i32, b: i32) -> i32 {
    if b == 0 {
        a.max(1)
    } else {
        gcd(b, a % b)
    }
}

/// `pslg` with copies of some segment endpoints appended (same coordinates and attributes,
/// their own markers) and some segments redirected to the copies. Triangle has undefined
/// behaviour on such input: ours keeps one copy and maps segment endpoints to it.
pub fn with_duplicates(mut pslg: Pslg, seed: u64) -> Pslg {
    let mut rng = SplitMix64::new(seed);
    let input = &mut pslg.input;
    let originals = input.points.len();
    for s in 0..input.segments.len() {
        if rng.below(3) != 0 {
            continue;
        }
        let end = rng.below(2);
        let v = input.segments[s][end] as usize;
        if v >= originals {
            continue;
        }
        input.points.push(input.points[v]);
        let k = input.attribute_count;
        let copied: Vec<f64> = input.attributes[v * k..v * k + k].to_vec();
        input.attributes.extend(copied);
        input
            .markers
            .get_or_insert_with(Vec::new)
            .push(vertex_marker(&mut rng));
        input.segments[s][end] = input.points.len() as i32 - 1;
    }
    // A duplicate of a free-standing vertex, referenced by nobody, and a duplicate of a copy.
    let last = input.points.len() - 1;
    for v in [0, last] {
        input.points.push(input.points[v]);
        let k = input.attribute_count;
        let copied: Vec<f64> = input.attributes[v * k..v * k + k].to_vec();
        input.attributes.extend(copied);
        input
            .markers
            .get_or_insert_with(Vec::new)
            .push(vertex_marker(&mut rng));
    }
    pslg.name = format!("{} with duplicates referenced by segments", pslg.name);
    pslg.ours_only = true;
    pslg
}

/// The benchmark's polygon: `n` vertices at sorted uniform random angles, radius uniform in
/// [0.1, 1], consecutive vertices joined and the last to the first (zero-based segments).
pub fn star_polygon(n: usize, seed: u64) -> (Vec<Point>, Vec<[i32; 2]>) {
    let mut rng = SplitMix64::new(seed);
    let mut angles: Vec<f64> = (0..n).map(|_| rng.next_f64() * TAU).collect();
    angles.sort_by(f64::total_cmp);
    let points = angles
        .iter()
        .map(|&a| {
            let r = 0.1 + 0.9 * rng.next_f64();
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    let segments = (0..n).map(|i| [i as i32, ((i + 1) % n) as i32]).collect();
    (points, segments)
}

/// [`star_polygon`] as a [`Pslg`] (zero-based), with its area.
pub fn star_polygon_pslg(n: usize, seed: u64) -> Pslg {
    let (points, segments) = star_polygon(n, seed);
    let area = polygon_area(&points);
    Pslg {
        area: Some(area),
        area_ignoring_holes: Some(area),
        ..Pslg::new(
            format!("star polygon of {n} vertices (seed {seed})"),
            MeshInput {
                segments,
                ..MeshInput::from_points(points)
            },
        )
    }
}

/// The refinement benchmark's domain: the unit square (segment marker 1) with a circular hole of
/// centre (0.5, 0.5) and radius 0.2 (`circle_segments` segments, marker 2, a hole point at the
/// centre) and four short free-standing segments between the circle and the corners (marker 3,
/// placed a little asymmetrically, so that few vertices are cocircular).
pub fn square_with_hole(circle_segments: usize) -> Pslg {
    assert!(circle_segments >= 3, "a circle of at least three segments");
    let (centre, radius) = ([0.5, 0.5], 0.2);
    let mut input = MeshInput::default();
    let add_loop = |input: &mut MeshInput, polygon: &[Point], marker: i32| {
        let first = input.points.len() as i32;
        let n = polygon.len() as i32;
        input.points.extend_from_slice(polygon);
        for k in 0..n {
            input.segments.push([first + k, first + (k + 1) % n]);
            input
                .segment_markers
                .get_or_insert_with(Vec::new)
                .push(marker);
        }
    };
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    add_loop(&mut input, &square, 1);
    let circle: Vec<Point> = (0..circle_segments)
        .map(|k| {
            let angle = TAU * k as f64 / circle_segments as f64;
            [
                centre[0] + radius * angle.cos(),
                centre[1] + radius * angle.sin(),
            ]
        })
        .collect();
    add_loop(&mut input, &circle, 2);
    for [a, b] in [
        [[0.10, 0.12], [0.20, 0.17]],
        [[0.82, 0.10], [0.90, 0.21]],
        [[0.85, 0.80], [0.93, 0.87]],
        [[0.08, 0.83], [0.17, 0.90]],
    ] {
        let first = input.points.len() as i32;
        input.points.extend([a, b]);
        input.segments.push([first, first + 1]);
        input.segment_markers.get_or_insert_with(Vec::new).push(3);
    }
    input.holes.push(centre);
    let area = 1.0 - polygon_area(&circle);
    Pslg {
        area: Some(area),
        area_ignoring_holes: Some(1.0),
        hole_polygons: vec![circle],
        ..Pslg::new(
            format!("unit square with a hole of {circle_segments} segments"),
            input,
        )
    }
}

/// Points of the lattice with spacing 0.2 on the unit square, and segments between them that
/// overlap or cross at lattice points. In doubles 0.2, 0.6 and 0.8 are not exact, so the
/// segment (0, 0.8)–(0.8, 0) misses the lattice points (0.6, 0.2) and (0.2, 0.6) on it by an
/// ulp, the segment between those overlaps it within rounding, and (0, 1)–(0.6, 0) crosses both
/// at (0.3, 0.5) at two points an ulp apart (Triangle: "Topological inconsistency after
/// splitting a segment"). Duplicate points and a segment with equal ends included.
pub fn lattice_with_overlaps() -> Pslg {
    let lattice = [
        [1, 1],
        [4, 2],
        [2, 4],
        [3, 1],
        [5, 5],
        [0, 2],
        [4, 0],
        [2, 3],
        [3, 0],
        [5, 3],
        [4, 2],
        [0, 4],
        [5, 0],
        [5, 1],
        [2, 5],
        [2, 4],
        [3, 0],
        [2, 5],
        [1, 3],
        [0, 5],
        [3, 1],
        [4, 2],
        [5, 1],
    ];
    let segments = vec![
        [0, 18],
        [7, 10],
        [3, 2],
        [19, 1],
        [6, 3],
        [3, 18],
        [21, 21],
        [5, 20],
        [11, 6],
        [19, 8],
        [20, 1],
        [20, 7],
        [14, 7],
        [1, 0],
        [0, 1],
        [9, 18],
        [14, 21],
        [10, 2],
        [20, 2],
        [6, 16],
        [13, 10],
        [13, 6],
        [16, 21],
        [3, 5],
        [15, 20],
    ];
    let points = lattice
        .iter()
        .map(|p| [p[0] as f64 / 5.0, p[1] as f64 / 5.0])
        .collect();
    let input = MeshInput {
        segments,
        ..MeshInput::from_points(points)
    };
    Pslg {
        convex: true,
        ours_only: true,
        ..Pslg::new("lattice with overlapping segments".into(), input)
    }
}

/// Found by the fuzz driver: two overlapping segments from one vertex, the longer one going on
/// past the shorter one's end (on the line y = x - 3), and a third segment crossing both where
/// the crossing point rounds an ulp off that line. The longer segment's piece from the crossing
/// point must pass through the shorter one's end, not by it.
pub fn overlap_past_a_rounded_crossing() -> Pslg {
    let points: Vec<Point> = [
        [-6, 1],
        [-4, -8],
        [1, -5],
        [4, -1],
        [-2, -5],
        [-6, -4],
        [-4, -6],
        [-3, -6],
        [7, 2],
        [-3, 5],
        [-4, -4],
        [-2, -6],
        [6, -2],
        [-2, -2],
        [7, 4],
    ]
    .iter()
    .map(|p| [p[0] as f64, p[1] as f64])
    .collect();
    let input = MeshInput {
        segments: vec![[9, 5], [0, 3], [14, 4], [14, 7], [2, 8]],
        ..MeshInput::from_points(points)
    };
    Pslg {
        convex: true,
        ours_only: true,
        ..Pslg::new("overlap past a rounded crossing".into(), input)
    }
}
