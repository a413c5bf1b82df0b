//! Fuzz cases shared by the cargo-fuzz targets (`fuzz/fuzz_targets/`) and the seeded driver that
//! `cargo test` runs on stable Rust (`tests/fuzz_driver.rs`). Each case takes arbitrary bytes,
//! decodes an input from them, runs the library and panics when the result breaks a rule:
//! - [`triangulate`]: a PSLG (points with attributes and markers, segments with indices that may
//!   be out of range, holes, regions, a triangle list for `r`) and a switch string, through the
//!   C ABI's `triangulate`. An error must come with a message and not be an internal error (a
//!   panic the boundary caught: the library's bug, whatever the input); a success must be a valid mesh
//!   (corners in range, counter-clockwise by exact orientation, manifold, no two used vertices at
//!   one place, every boundary edge a segment, every output segment an edge), with every input
//!   segment present as a chain of output segments, and in-range Voronoi edges; with `D`, truly
//!   Delaunay by exact predicates unless the call warned why not.
//! - [`read_files`]: every reader of Triangle's file formats on arbitrary text: an error or a
//!   value, never a panic or a runaway allocation; a `.node` that reads writes back to the same.
//! - [`parse_switches`]: `Options::parse` on arbitrary strings: an error or options that keep
//!   their invariants.
//!
//! The including crate must also include `tests/common` as `mod common` at its root.

use super::common::checks::convex_hull;
use super::common::pslg_checks::{segment_chains, MeshView};
use super::common::quality::check_conforming_delaunay;
use super::common::{ours_with, MeshInput, Triangulation};

use triangle_rs::io::files;
use triangle_rs::options::{Options, SwitchSource};

/// Reads the case's bytes front to back; zeros once they run out (so every prefix decodes).
pub struct Bytes<'a> {
    data: &'a [u8],
    position: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, position: 0 }
    }

    fn byte(&mut self) -> u8 {
        let b = self.data.get(self.position).copied().unwrap_or(0);
        self.position += 1;
        b
    }

    fn below(&mut self, n: usize) -> usize {
        self.byte() as usize % n
    }

    fn f64_bits(&mut self) -> f64 {
        f64::from_bits(u64::from_le_bytes(std::array::from_fn(|_| self.byte())))
    }
}

/// Switch tokens a case combines (after `Q`). Left out: `u` (needs a callback), `X` (without
/// exact arithmetic an invalid mesh is allowed), `V` (prints), `w`/`W` (refused; tested apart).
const TOKENS: &[&str] = &[
    "p", "p", "p", "c", "q", "q30", "q10", "a", "A", "D", "Y", "YY", "S7", "e", "n", "v", "z", "z",
    "j", "o2", "s", "C", "i", "F", "q33", "AREA", "R",
];

/// How coordinates are drawn: a coarse lattice (duplicates, collinear and cocircular sets), the
/// lattice scaled by a power of two, raw bit patterns (NaN, infinities, huge and subnormal
/// numbers), or points a few ulps off a line.
fn coordinate(bytes: &mut Bytes<'_>, mode: usize, scale: f64) -> f64 {
    match mode {
        0..=3 => (bytes.below(16) as f64) - 8.0,
        4 => ((bytes.byte() as i8) as f64) * scale,
        5 => bytes.f64_bits(),
        _ => unreachable!(),
    }
}

fn decode_points(bytes: &mut Bytes<'_>, n: usize, extreme: bool) -> Vec<[f64; 2]> {
    let mode = bytes.below(if extreme { 7 } else { 5 });
    let scale = (2.0f64).powi(bytes.below(81) as i32 - 40);
    if mode == 6 {
        // Near-collinear: on the line y = 0.3 x, each coordinate moved by a few ulps.
        return (0..n)
            .map(|_| {
                let x = bytes.below(64) as f64 * 0.37;
                let y = 0.3 * x;
                let nudge = |v: f64, k: u8| {
                    f64::from_bits((v.to_bits() as i64 + (k as i64 % 5 - 2)) as u64)
                };
                [x, nudge(y, bytes.byte())]
            })
            .collect();
    }
    (0..n)
        .map(|_| {
            [
                coordinate(bytes, mode, scale),
                coordinate(bytes, mode, scale),
            ]
        })
        .collect()
}

/// One decoded call: its switch string and input.
pub struct Case {
    pub switches: String,
    pub input: MeshInput,
}

/// Decodes a case. With `extreme`, coordinates may be any bit pattern and near-collinear sets.
pub fn decode(data: &[u8], extreme: bool) -> Case {
    let mut bytes = Bytes::new(data);
    let mut switches = String::from("Q");
    for _ in 0..bytes.below(7) {
        switches.push_str(TOKENS[bytes.below(TOKENS.len())]);
    }
    let zero_based = switches.contains('z');
    let base = if zero_based { 0 } else { 1 };
    let most = if bytes.below(4) == 0 { 64 } else { 16 };
    let n = bytes.below(most);
    let points = decode_points(&mut bytes, n, extreme);
    // A global area bound relative to the extent (an absolute one could legitimately ask for
    // billions of triangles), written with an exponent.
    let extent = points
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let area = (extent * extent / (20 + bytes.below(200)) as f64).max(f64::MIN_POSITIVE);
    let mut switches = switches.replace("AREA", &format!("a{area:e}"));
    // A domain a hair's breadth wide (the extreme cases' near-collinear points with `q`) refines
    // until the runaway limit (10^6 vertices, seconds): bound each extreme case's work with a
    // Steiner budget instead (the limit itself is tested in refine_properties). Without an angle
    // bound refinement only meets the area bounds (relative to the extent: a few hundred
    // triangles), so no budget then (unless `D`, whose conforming splits also follow small
    // features). Lattice points make no such domain, and a budget would turn off what runs
    // after an unbudgeted refinement (lattice seeding, the improvement of the finished mesh, the
    // raise of its smallest angle: measured, 217 000 lattice cases without it in 240 s, none
    // slower than a second): no budget for them.
    if extreme && !switches.contains('S') && (switches.contains('q') || switches.contains('D')) {
        switches.push_str("S20000");
    }

    let attribute_count = bytes.below(3);
    let attributes = (0..n * attribute_count)
        .map(|_| bytes.below(9) as f64 - 4.0)
        .collect();
    let markers =
        (bytes.below(2) == 1).then(|| (0..n).map(|_| bytes.below(5) as i32 - 1).collect());
    // Mostly in range (so that most cases get meshed); one in 64 is -1 or n (an error).
    let index = |bytes: &mut Bytes<'_>| {
        let b = bytes.byte() as usize;
        if b % 64 == 0 {
            [-1, n as i32][b / 64 % 2] + base
        } else {
            (b / 2 % n.max(1)) as i32 + base
        }
    };
    let segments: Vec<[i32; 2]> = (0..bytes.below(if n > 16 { 40 } else { 12 }))
        .map(|_| [index(&mut bytes), index(&mut bytes)])
        .collect();
    let segment_markers =
        (bytes.below(2) == 1).then(|| segments.iter().map(|_| bytes.below(4) as i32).collect());
    let place =
        |bytes: &mut Bytes<'_>| [bytes.below(16) as f64 - 7.5, bytes.below(16) as f64 - 7.5];
    let holes = (0..bytes.below(3)).map(|_| place(&mut bytes)).collect();
    let regions = (0..bytes.below(3))
        .map(|_| {
            let [x, y] = place(&mut bytes);
            [
                x,
                y,
                bytes.below(5) as f64,
                bytes.below(4) as f64 * area - area,
            ]
        })
        .collect();
    let (triangles, triangle_attributes, triangle_areas) = if switches.contains('r') {
        let count = bytes.below(10);
        let triangles: Vec<i32> = (0..3 * count).map(|_| index(&mut bytes)).collect();
        let areas = (bytes.below(2) == 1).then(|| {
            (0..count)
                .map(|_| bytes.below(3) as f64 * area - area)
                .collect()
        });
        (triangles, Vec::new(), areas)
    } else {
        (Vec::new(), Vec::new(), None)
    };
    Case {
        switches,
        input: MeshInput {
            points,
            attributes,
            attribute_count,
            markers,
            segments,
            segment_markers,
            holes,
            regions,
            corners: 3,
            triangles,
            triangle_attributes,
            triangle_attribute_count: 0,
            triangle_areas,
        },
    }
}

/// The input renumbered from zero (the checks' numbering).
fn zero_based_input(input: &MeshInput, base: i32) -> MeshInput {
    let mut zero = input.clone();
    for s in &mut zero.segments {
        *s = s.map(|v| v - base);
    }
    zero
}

/// Checks one call's result against the rules of the module doc; `Err` names the broken rule.
///
/// With `extreme` inputs the segment chains are not checked: in a set of points all within
/// rounding of one line, every vertex is "on" every segment within rounding, and which of them
/// a chain passes through is a choice (the mesh is still checked for validity).
pub fn check(
    case: &Case,
    result: &Result<Triangulation, String>,
    warning: &str,
    extreme: bool,
) -> Result<(), String> {
    let out = match result {
        Err(message) if message.trim().is_empty() => {
            return Err("an error without a message".into())
        }
        // A panic caught at the boundary is a bug, whatever the input.
        Err(message) if message.starts_with("Internal error") => return Err(message.clone()),
        Err(_) => return Ok(()),
        Ok(out) => out,
    };
    let mesh = MeshView::of(out)?;
    let o = Options::parse(&case.switches, SwitchSource::Library).map_err(|e| e.to_string())?;
    if let Some(voronoi) = &out.voronoi {
        if let Some(edges) = &voronoi.edges {
            for (i, e) in edges.iter().enumerate() {
                let in_range =
                    |v: i32| v == -1 || (v >= out.base && v < out.base + voronoi.points_count);
                if !in_range(e[0]) || !in_range(e[1]) || e[0] == -1 {
                    return Err(format!("Voronoi edge {i} {e:?} is out of range"));
                }
            }
        }
    }
    // With `c` and nothing eaten (no holes), the mesh covers the convex hull of the vertices
    // exactly once: its area is the hull's (a fold or overlap would add area). Checked in floating
    // point, so only where the hull is not a sliver (where rounding could decide).
    if o.convex_hull && case.input.holes.is_empty() && !o.refine && !extreme {
        let finite: Vec<[f64; 2]> = case.input.points.clone();
        let hull = convex_hull(&finite);
        if hull.len() >= 3 {
            let o0 = hull[0];
            let hull_area: f64 = (1..hull.len() - 1)
                .map(|i| {
                    let (b, c) = (hull[i], hull[i + 1]);
                    0.5 * ((b[0] - o0[0]) * (c[1] - o0[1]) - (b[1] - o0[1]) * (c[0] - o0[0]))
                })
                .sum();
            let extent2 = hull
                .iter()
                .map(|p| (p[0] - o0[0]).powi(2) + (p[1] - o0[1]).powi(2))
                .fold(0.0, f64::max);
            let area = mesh.area();
            if hull_area > 1e-6 * extent2 && (area - hull_area).abs() > 1e-9 * hull_area {
                return Err(format!(
                    "the mesh's area {area:e} is not the convex hull's {hull_area:e}"
                ));
            }
        }
    }
    // Every input segment is kept (as a chain) when nothing is eaten: with `c` and no holes
    // (without `c`, segments outside the domain go with the eaten triangles, as in Triangle); `j`
    // renumbers, and `r` refines a mesh whose triangles need not cover the segments.
    if !extreme
        && o.pslg
        && o.convex_hull
        && !o.refine
        && !o.jettison
        && case.input.holes.is_empty()
        && out.triangles.as_ref().is_some_and(|t| !t.is_empty())
    {
        let zero = zero_based_input(&case.input, out.base);
        segment_chains(&zero, &mesh, o.convex_hull)?;
    }
    // `D` is truly Delaunay (exact predicates: no vertex even a rounding inside a boundary
    // edge's diametral circle), unless the call said why not (the precision of the doubles, a
    // budget, the runaway limit), `Y` kept an encroached segment whole, or `X` gave up exactness.
    if o.conforming_delaunay
        && !extreme
        && o.no_steiner_on_segments == 0
        && !o.no_exact
        && warning.is_empty()
        && !mesh.triangles.is_empty()
    {
        check_conforming_delaunay(&mesh)?;
    }
    Ok(())
}

/// The warnings of the last call on this thread (`triangulate_last_warning`).
fn last_warning() -> String {
    let text = triangle_rs::ffi::triangulate_last_warning();
    // SAFETY: the library returns a NUL-terminated string that stays valid until the next call
    // on this thread, and no call comes between.
    unsafe { std::ffi::CStr::from_ptr(text) }
        .to_string_lossy()
        .into_owned()
}

/// Decodes `data`, runs it through the C ABI and panics on a broken rule.
pub fn triangulate(data: &[u8], extreme: bool) {
    let case = decode(data, extreme);
    let result = ours_with(&case.switches, &case.input, case.switches.contains('v'));
    let warning = last_warning();
    if let Err(broken) = check(&case, &result, &warning, extreme) {
        panic!(
            "switches {:?}, input {:?}: {broken}",
            case.switches, case.input
        );
    }
}

/// Every file reader on `data` as text: an error or a value, never a panic. A `.node` that reads
/// is written back and must read back to the same vertices.
pub fn read_files(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let name = "fuzz";
    let _ = files::read_ele(&text, name);
    let _ = files::read_poly(&text, name, true);
    let _ = files::read_poly(&text, name, false);
    let _ = files::read_area(&text, name);
    let _ = files::read_edge(&text, name);
    let _ = files::read_voronoi_edge(&text, name);
    let _ = files::read_neigh(&text, name);
    let _ = files::read_off(&text, name);
    if let Ok(node) = files::read_node(&text, name) {
        let mut written = Vec::new();
        let data = files::NodeData {
            points: &node.points,
            attribute_count: node.attribute_count,
            attributes: &node.attributes,
            markers: node.markers.as_deref(),
        };
        let first = node.first_number.unwrap_or(0) as i32;
        files::write_node(&mut written, &data, first, None).expect("writing to memory");
        let again = files::read_node(&String::from_utf8_lossy(&written), name)
            .unwrap_or_else(|e| panic!("a written .node does not read back: {e}"));
        let same = |a: &[f64], b: &[f64]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(x, y)| x.to_bits() == y.to_bits() || x.is_nan() && y.is_nan())
        };
        assert!(
            same(&node.points, &again.points)
                && same(&node.attributes, &again.attributes)
                && node.markers == again.markers,
            "a .node does not survive writing and reading: {text:?}"
        );
    }
}

/// `Options::parse` on `data` as a switch string, from both sources.
pub fn parse_switches(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    for source in [SwitchSource::Library, SwitchSource::CommandLine] {
        if let Ok(o) = Options::parse(&text, source) {
            if let Some(a) = o.max_area {
                assert!(a > 0.0, "area bound {a} from {text:?}");
            }
            if let Some(q) = o.min_angle {
                assert!(q.is_finite() && q >= 0.0, "minimum angle {q} from {text:?}");
            }
            assert!(
                o.no_steiner_on_segments <= 2 && o.weighted <= 2,
                "{o:?} from {text:?}"
            );
        }
    }
}
