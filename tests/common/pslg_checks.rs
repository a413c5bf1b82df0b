//! Checks of constrained Delaunay triangulations of PSLGs (the `p` switch), on one output or
//! between ours and Triangle's:
//! - [`MeshView::of`]: a valid mesh of a domain (corners in range, counter-clockwise by exact
//!   `orient2d`, manifold, no two used vertices at one place, every boundary edge a segment);
//! - [`check_constrained_delaunay`]: every interior edge that is not a segment is locally
//!   Delaunay by exact `incircle`;
//! - [`segment_chains`]: every input segment is a chain of output segments, split at the vertices
//!   on it and where other segments cross it;
//! - [`check_markers`]: Triangle's marker rules for vertices, segments and edges;
//! - [`pslg_differences`]: ours against Triangle's, vertices matched by coordinates (new vertices
//!   at crossings with a small tolerance), triangles compared where the CDT is unique.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};

use super::call::{MeshInput, Triangulation};
use super::checks::{canonical_triangle, directed_edges, incircle, orient2d, zero_based, Directed};
use super::points::Point;

fn bits(p: Point) -> [u64; 2] {
    p.map(f64::to_bits)
}

fn sorted_pair(a: usize, b: usize) -> [usize; 2] {
    [a.min(b), a.max(b)]
}

/// A zero-based view of one output, checked for validity on construction.
pub struct MeshView<'a> {
    pub out: &'a Triangulation,
    pub points: &'a [Point],
    pub triangles: Vec<[usize; 3]>,
    /// Output segments (zero-based, as written).
    pub segments: Vec<[usize; 2]>,
    /// Sorted output segment → its index in `segments`.
    pub segment_index: HashMap<[usize; 2], usize>,
    /// Directed edge → (triangle, corner opposite it).
    pub edges: Directed,
    /// Per output vertex: a corner of an output triangle.
    pub in_mesh: Vec<bool>,
    /// Per output vertex: an endpoint of a boundary edge of the mesh.
    pub on_boundary: Vec<bool>,
}

impl<'a> MeshView<'a> {
    /// Checks that `out` is a valid mesh of a domain bounded by its segments.
    pub fn of(out: &'a Triangulation) -> Result<MeshView<'a>, String> {
        let points = out.points.as_deref().ok_or("no output points")?;
        let triangles = zero_based(out);
        let base = out.base as usize;
        let segments: Vec<[usize; 2]> = out
            .segments
            .as_deref()
            .unwrap_or_default()
            .iter()
            .map(|s| s.map(|v| (v as usize).wrapping_sub(base)))
            .collect();
        for (t, c) in triangles.iter().enumerate() {
            if c.iter().any(|&v| v >= points.len()) {
                return Err(format!("triangle {t} {c:?} has a corner out of range"));
            }
            if orient2d(points[c[0]], points[c[1]], points[c[2]]) <= 0.0 {
                return Err(format!(
                    "triangle {t} {c:?} is not counter-clockwise: {:?}",
                    c.map(|v| points[v])
                ));
            }
        }
        let mut segment_index = HashMap::new();
        for (i, s) in segments.iter().enumerate() {
            if s.iter().any(|&v| v >= points.len()) || s[0] == s[1] {
                return Err(format!(
                    "output segment {i} {s:?} is degenerate or out of range"
                ));
            }
            if segment_index.insert(sorted_pair(s[0], s[1]), i).is_some() {
                return Err(format!("output segment {s:?} appears twice"));
            }
        }
        let edges = directed_edges(&triangles)?;
        let mut in_mesh = vec![false; points.len()];
        let mut at: HashMap<[u64; 2], usize> = HashMap::new();
        for &v in triangles.iter().flatten() {
            in_mesh[v] = true;
            if let Some(&other) = at.get(&bits(points[v])) {
                if other != v {
                    return Err(format!(
                        "vertices {other} and {v} coincide at {:?} and are both in the mesh",
                        points[v]
                    ));
                }
            }
            at.insert(bits(points[v]), v);
        }
        let mut on_boundary = vec![false; points.len()];
        for &(a, b) in edges.keys() {
            if !edges.contains_key(&(b, a)) {
                on_boundary[a] = true;
                on_boundary[b] = true;
                if out.segments.is_some() && !segment_index.contains_key(&sorted_pair(a, b)) {
                    return Err(format!(
                        "boundary edge {a}-{b} {:?} is not a segment",
                        [points[a], points[b]]
                    ));
                }
            }
        }
        for (i, s) in segments.iter().enumerate() {
            if !edges.contains_key(&(s[0], s[1])) && !edges.contains_key(&(s[1], s[0])) {
                return Err(format!(
                    "output segment {i} {s:?} is not an edge of an output triangle"
                ));
            }
        }
        Ok(MeshView {
            out,
            points,
            triangles,
            segments,
            segment_index,
            edges,
            in_mesh,
            on_boundary,
        })
    }

    pub fn is_segment(&self, a: usize, b: usize) -> bool {
        self.segment_index.contains_key(&sorted_pair(a, b))
    }

    pub fn is_boundary_edge(&self, a: usize, b: usize) -> bool {
        self.edges.contains_key(&(a, b)) != self.edges.contains_key(&(b, a))
    }

    /// The total area of the triangles.
    pub fn area(&self) -> f64 {
        let Some(&o) = self.points.first() else {
            return 0.0;
        };
        let rel = |p: Point| [p[0] - o[0], p[1] - o[1]];
        self.triangles
            .iter()
            .map(|c| {
                let [a, b, d] = c.map(|v| rel(self.points[v]));
                0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]))
            })
            .sum()
    }

    /// Interior non-segment edges whose two triangles' corners are exactly cocircular: there the
    /// constrained Delaunay triangulation is not unique (sorted pairs).
    pub fn cocircular_edges(&self) -> HashSet<[usize; 2]> {
        let mut found = HashSet::new();
        for (&(a, b), &(t, k)) in &self.edges {
            let Some(&(u, l)) = self.edges.get(&(b, a)) else {
                continue;
            };
            if a < b && !self.is_segment(a, b) {
                let (apex, opposite) = (self.triangles[t][k], self.triangles[u][l]);
                if incircle(
                    self.points[a],
                    self.points[b],
                    self.points[apex],
                    self.points[opposite],
                ) == 0.0
                {
                    found.insert([a, b]);
                }
            }
        }
        found
    }

    /// Whether triangle `t` has a cocircular edge (it lies in a region where the CDT is not
    /// unique).
    pub fn is_ambiguous(&self, t: usize, cocircular: &HashSet<[usize; 2]>) -> bool {
        let c = self.triangles[t];
        (0..3).any(|k| cocircular.contains(&sorted_pair(c[k], c[(k + 1) % 3])))
    }

    /// The output vertex at `p` that is in the mesh (or any output vertex there).
    pub fn vertex_at(&self, p: Point) -> Option<usize> {
        let mut found = None;
        for (v, &q) in self.points.iter().enumerate() {
            if bits(q) == bits(p) {
                if self.in_mesh[v] {
                    return Some(v);
                }
                found = found.or(Some(v));
            }
        }
        found
    }
}

/// Every interior edge that is not a segment is locally Delaunay: the opposite vertex is not
/// strictly inside the circumcircle (exact `incircle`).
pub fn check_constrained_delaunay(mesh: &MeshView<'_>) -> Result<(), String> {
    check_locally_delaunay(mesh, false)
}

/// Every interior edge (segments too if `segments_too`) is locally Delaunay, by exact `incircle`.
pub fn check_locally_delaunay(mesh: &MeshView<'_>, segments_too: bool) -> Result<(), String> {
    for (&(a, b), &(t, k)) in &mesh.edges {
        let Some(&(u, l)) = mesh.edges.get(&(b, a)) else {
            continue;
        };
        let segment = mesh.is_segment(a, b);
        if a > b || (segment && !segments_too) {
            continue;
        }
        let (apex, opposite) = (mesh.triangles[t][k], mesh.triangles[u][l]);
        if incircle(
            mesh.points[a],
            mesh.points[b],
            mesh.points[apex],
            mesh.points[opposite],
        ) > 0.0
        {
            return Err(format!(
                "edge {a}-{b} ({}a segment) is not locally Delaunay: vertex {opposite} lies inside the circumcircle of {:?}",
                if segment { "" } else { "not " },
                mesh.triangles[t].map(|v| mesh.points[v])
            ));
        }
    }
    Ok(())
}

/// Whether an output segment of `mesh` passes by an input vertex within rounding distance
/// (1e-12 of its length) without ending at it: Triangle's segments do so beyond a rounded
/// crossing point, ours do not.
pub fn bypasses_a_vertex(input: &MeshInput, mesh: &MeshView<'_>) -> bool {
    mesh.segments
        .iter()
        .any(|&s| bypassed_vertices(input, mesh.points, s).next().is_some())
}

/// The input vertices that output segment `s` passes by within 10^-12 of its length, strictly
/// between its endpoints (see [`bypasses_a_vertex`]).
pub fn bypassed_vertices<'a>(
    input: &'a MeshInput,
    points: &[Point],
    s: [usize; 2],
) -> impl Iterator<Item = Point> + 'a {
    let (pu, pw) = (points[s[0]], points[s[1]]);
    let d = [pw[0] - pu[0], pw[1] - pu[1]];
    let length2 = d[0] * d[0] + d[1] * d[1];
    input.points.iter().copied().filter(move |&p| {
        let e = [p[0] - pu[0], p[1] - pu[1]];
        let along = e[0] * d[0] + e[1] * d[1];
        let across = e[0] * d[1] - e[1] * d[0];
        along > 0.0 && along < length2 && across.abs() <= 1e-12 * length2 && p != pu && p != pw
    })
}

/// The input segments that Triangle inserts (zero-based, endpoints in range and distinct
/// coordinates), with their index in the input.
pub fn effective_segments(input: &MeshInput) -> Vec<(usize, [usize; 2])> {
    let n = input.points.len();
    input
        .segments
        .iter()
        .enumerate()
        .filter_map(|(i, s)| {
            let [a, b] = s.map(|v| v as usize);
            (a < n && b < n && bits(input.points[a]) != bits(input.points[b]))
                .then_some((i, [a, b]))
        })
        .collect()
}

/// Relative tolerance for vertices created at crossings: they lie on the crossed segment only
/// up to rounding.
const NEW_VERTEX_TOLERANCE: f64 = 1e-9;

/// Input vertices on a chain need not lie exactly on the segment: one within rounding of it
/// is a vertex of its chain (closer than 10^-12 of the segment's length with `p`, than 2^-40
/// of the domain's extent with refinement).
const SNAPPED_RELATIVE_TO_SEGMENT: f64 = 1e-12;
const SNAPPED_RELATIVE_TO_EXTENT: f64 = 1.0 / (1u64 << 40) as f64;

/// For each input segment (of a zero-based `input`) that is inserted, the chain of output
/// vertices along it, from its first to its second endpoint: consecutive chain vertices are
/// output segments, input vertices on the chain lie exactly on the segment (or within rounding
/// of it: [`SNAPPED_RELATIVE_TO_SEGMENT`]), new vertices (not at
/// any input vertex's place) within a small tolerance of it. Checks as well that every input
/// vertex lying on a segment is on its chain, that segments that cross share a chain vertex, and
/// that every output segment lies on a chain (or, with `hull_segments`, on the mesh boundary).
pub fn segment_chains(
    input: &MeshInput,
    mesh: &MeshView<'_>,
    hull_segments: bool,
) -> Result<BTreeMap<usize, Vec<usize>>, String> {
    let input_places: HashSet<[u64; 2]> = input.points.iter().map(|&p| bits(p)).collect();
    let extent = extent(&input.points);
    let mut adjacent: HashMap<usize, Vec<usize>> = HashMap::new();
    for s in &mesh.segments {
        adjacent.entry(s[0]).or_default().push(s[1]);
        adjacent.entry(s[1]).or_default().push(s[0]);
    }
    let segments = effective_segments(input);
    let mut chains = BTreeMap::new();
    for &(i, [a, b]) in &segments {
        let (pa, pb) = (input.points[a], input.points[b]);
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let length2 = d[0] * d[0] + d[1] * d[1];
        let param = |p: Point| ((p[0] - pa[0]) * d[0] + (p[1] - pa[1]) * d[1]) / length2;
        let on_line = |p: Point| {
            let cross = (p[0] - pa[0]) * d[1] - (p[1] - pa[1]) * d[0];
            if input_places.contains(&bits(p)) {
                let snap = (SNAPPED_RELATIVE_TO_SEGMENT * length2.sqrt())
                    .max(SNAPPED_RELATIVE_TO_EXTENT * extent);
                orient2d(pa, pb, p) == 0.0 || cross.abs() <= 1.001 * snap * length2.sqrt()
            } else {
                cross.abs() <= NEW_VERTEX_TOLERANCE * length2
            }
        };
        let what = |detail: String| {
            format!(
                "input segment {i} {:?} ({pa:?} to {pb:?}): {detail}",
                input.segments[i]
            )
        };
        let start = mesh
            .vertex_at(pa)
            .ok_or_else(|| what("its first endpoint is not an output vertex".into()))?;
        let end = mesh
            .vertex_at(pb)
            .ok_or_else(|| what("its second endpoint is not an output vertex".into()))?;
        // The chain by depth-first search, closest to the line first: near an endpoint, at the
        // scale of refinement's smallest shells, another segment leaving the same vertex lies
        // within the tolerance of this one's line too, and a greedy walk may take it.
        let off_line = |p: Point| ((p[0] - pa[0]) * d[1] - (p[1] - pa[1]) * d[0]).abs();
        let steps_from = |current: usize| -> Vec<usize> {
            let t = param(mesh.points[current]);
            let mut steps: Vec<usize> = adjacent
                .get(&current)
                .into_iter()
                .flatten()
                .copied()
                .filter(|&w| param(mesh.points[w]) > t && on_line(mesh.points[w]))
                .collect();
            // Popped from the back: the farthest from the line first in the list.
            steps.sort_by(|&x, &y| {
                let (px, py) = (mesh.points[x], mesh.points[y]);
                off_line(py)
                    .total_cmp(&off_line(px))
                    .then(param(py).total_cmp(&param(px)))
            });
            steps
        };
        let mut path: Vec<(usize, Vec<usize>)> = vec![(start, steps_from(start))];
        let mut longest: Vec<usize> = vec![start];
        let mut overshot = false;
        let chain: Vec<usize> = loop {
            let Some((current, steps)) = path.last_mut() else {
                return Err(what(if overshot {
                    format!("its chain {longest:?} overshoots the endpoint")
                } else {
                    format!(
                        "no output segment continues its chain {longest:?} at {:?}",
                        mesh.points[*longest.last().expect("starts with a vertex")]
                    )
                }));
            };
            if *current == end {
                break path.iter().map(|(v, _)| *v).collect();
            }
            match steps.pop() {
                Some(next) if param(mesh.points[next]) > 1.0 => overshot = true,
                Some(next) => {
                    path.push((next, steps_from(next)));
                    if path.len() > longest.len() {
                        longest = path.iter().map(|(v, _)| *v).collect();
                    }
                }
                None => {
                    path.pop();
                }
            }
        };
        // Input vertices lying on the segment split it, unless the chain bends around them at
        // a new vertex (a rounded crossing: Triangle inserts the rest of the segment from there;
        // ours does not, which `bypasses_a_vertex` checks).
        for (v, &p) in input.points.iter().enumerate() {
            let t = param(p);
            if t > 0.0 && t < 1.0 && orient2d(pa, pb, p) == 0.0 {
                let w = mesh.vertex_at(p).ok_or_else(|| {
                    what(format!("input vertex {v} on it is not an output vertex"))
                })?;
                let piece = chain
                    .windows(2)
                    .find(|piece| param(mesh.points[piece[1]]) >= t)
                    .expect("the chain ends at t = 1");
                let bent = piece
                    .iter()
                    .any(|&u| !input_places.contains(&bits(mesh.points[u])));
                if !chain.contains(&w) && !bent {
                    return Err(what(format!(
                        "input vertex {v} {p:?} lies on it but its chain {chain:?} misses it"
                    )));
                }
            }
        }
        chains.insert(i, chain);
    }
    // Segments that cross share a chain vertex.
    for (x, &(i, [a, b])) in segments.iter().enumerate() {
        for &(j, [c, d]) in &segments[x + 1..] {
            let p = |v: usize| input.points[v];
            let crosses = orient2d(p(a), p(b), p(c)) * orient2d(p(a), p(b), p(d)) < 0.0
                && orient2d(p(c), p(d), p(a)) * orient2d(p(c), p(d), p(b)) < 0.0;
            if crosses && !chains[&i].iter().any(|v| chains[&j].contains(v)) {
                return Err(format!("input segments {i} and {j} cross, but their chains {:?} and {:?} share no vertex", chains[&i], chains[&j]));
            }
        }
    }
    let covered: HashSet<[usize; 2]> = chains
        .values()
        .flat_map(|c| c.windows(2).map(|w| sorted_pair(w[0], w[1])))
        .collect();
    for s in &mesh.segments {
        let on_hull = hull_segments && mesh.is_boundary_edge(s[0], s[1]);
        if !covered.contains(&sorted_pair(s[0], s[1])) && !on_hull {
            return Err(format!("output segment {s:?} lies on no input segment"));
        }
    }
    Ok(chains)
}

/// Every new vertex (at no input vertex's place) on the chain of an input segment lies on that
/// segment to rounding: its distance from the segment's line (`robust`'s orientation over the
/// length) is at most `ulps` units in the last place of the largest coordinate magnitude of the
/// segment's ends and the vertex, plus the chain's bend: the largest distance from the line of
/// the chain's anchors, the input vertices within rounding of the segment that it passes through
/// and the new vertices on three or more chains (a crossing the engine merged others into), the
/// pieces after which are straight from there. A vertex on three or more chains is such a merged
/// crossing: it lies within `merged_relative` times the longest input segment of each segment
/// through it (plus the bend). A crossing vertex, on two chains, is checked on both segments.
/// Returns the largest distance of a vertex on two chains beyond its chain's bend, in ulps.
pub fn check_new_vertices_on_chains(
    input: &MeshInput,
    mesh: &MeshView<'_>,
    chains: &BTreeMap<usize, Vec<usize>>,
    ulps: f64,
    merged_relative: f64,
) -> Result<f64, String> {
    let input_places: HashSet<[u64; 2]> = input.points.iter().map(|&p| bits(p)).collect();
    let mut on_chains: HashMap<usize, usize> = HashMap::new();
    for chain in chains.values() {
        for &v in chain {
            *on_chains.entry(v).or_default() += 1;
        }
    }
    let longest = chains
        .keys()
        .map(|&i| {
            let [a, b] = input.segments[i].map(|v| input.points[v as usize]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .fold(0.0f64, f64::max);
    let mut worst = 0.0f64;
    for (&i, chain) in chains {
        let [a, b] = input.segments[i].map(|v| v as usize);
        let (pa, pb) = (input.points[a], input.points[b]);
        let length = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        // Unscaled (coordinates of ordinary magnitude): `robust`'s adaptive value is the
        // determinant to within its last bits.
        let c = |q: Point| robust::Coord { x: q[0], y: q[1] };
        let distance = |p: Point| robust::orient2d(c(pa), c(pb), c(p)).abs() / length;
        let is_new = |v: usize| !input_places.contains(&bits(mesh.points[v]));
        let bend = chain
            .iter()
            .filter(|&&v| !is_new(v) || on_chains[&v] >= 3)
            .map(|&v| distance(mesh.points[v]))
            .fold(0.0f64, f64::max);
        for &v in chain.iter().filter(|&&v| is_new(v)) {
            let p = mesh.points[v];
            let magnitude = [pa, pb, p]
                .iter()
                .flat_map(|q| q.iter())
                .fold(0.0f64, |m, x| m.max(x.abs()));
            let ulp = f64::EPSILON * magnitude;
            let (merged, allowed) = if on_chains[&v] >= 3 {
                (true, merged_relative * longest + ulps * ulp)
            } else {
                (false, bend + ulps * ulp)
            };
            let d = distance(p);
            if !merged {
                worst = worst.max((d - bend).max(0.0) / ulp);
            }
            if d > allowed {
                return Err(format!(
                    "new vertex {v} {p:?} on {} chains, on that of input segment {i} {:?} ({pa:?} to {pb:?}), is {d:e} from it: {:.1} ulps of {magnitude:e}, the chain's bend {bend:e}",
                    on_chains[&v],
                    input.segments[i],
                    d / ulp
                ));
            }
        }
    }
    Ok(worst)
}

/// Triangle's marker of the edge between output vertices `a` and `b` (zero-based): the first
/// non-zero marker of the input segments whose chains contain it; else 1 on the mesh boundary;
/// else 0 (`chains` as from [`segment_chains`]).
pub fn edge_marker_rule<'m>(
    input: &MeshInput,
    mesh: &'m MeshView<'_>,
    chains: &BTreeMap<usize, Vec<usize>>,
) -> impl Fn(usize, usize) -> i32 + 'm {
    let mut piece_rule: HashMap<[usize; 2], i32> = HashMap::new();
    for (&i, chain) in chains {
        let marker = input.segment_markers.as_ref().map_or(0, |m| m[i]);
        if marker == 0 {
            continue;
        }
        for w in chain.windows(2) {
            piece_rule.entry(sorted_pair(w[0], w[1])).or_insert(marker);
        }
    }
    move |a: usize, b: usize| {
        piece_rule
            .get(&sorted_pair(a, b))
            .copied()
            .unwrap_or(i32::from(mesh.is_boundary_edge(a, b)))
    }
}

/// Triangle's marker rules, on an output with markers:
/// - a vertex in the mesh: its input marker if non-zero; else the marker of the first segment
///   (in input order) with a non-zero marker whose chain passes through it; else 1 on the mesh
///   boundary; else 0 (vertices left outside the mesh are not checked: their markers depend on
///   the order in which Triangle eats triangles);
/// - a segment: the first non-zero marker of the input segments whose chains contain it; else 1
///   on the boundary; else 0;
/// - an edge (`e`): the same for segments, else 1 on the boundary, else 0.
///
/// `input_vertex` maps an output vertex to the input vertex it is (`None` for new vertices).
pub fn check_markers(
    input: &MeshInput,
    mesh: &MeshView<'_>,
    chains: &BTreeMap<usize, Vec<usize>>,
    input_vertex: &dyn Fn(usize) -> Option<usize>,
) -> Result<(), String> {
    let out = mesh.out;
    let segment_marker = |i: usize| input.segment_markers.as_ref().map_or(0, |m| m[i]);
    let mut vertex_rule: HashMap<usize, i32> = HashMap::new();
    for (&i, chain) in chains {
        let marker = segment_marker(i);
        if marker == 0 {
            continue;
        }
        for &v in chain {
            vertex_rule.entry(v).or_insert(marker);
        }
    }
    let edge_rule = edge_marker_rule(input, mesh, chains);
    let markers = out.point_markers.as_deref().ok_or("no point markers")?;
    for v in (0..mesh.points.len()).filter(|&v| mesh.in_mesh[v]) {
        let given = input_vertex(v)
            .and_then(|i| input.markers.as_ref().map(|m| m[i]))
            .unwrap_or(0);
        let expected = if given != 0 {
            given
        } else {
            vertex_rule
                .get(&v)
                .copied()
                .unwrap_or(i32::from(mesh.on_boundary[v]))
        };
        if markers[v] != expected {
            return Err(format!(
                "vertex {v} {:?} (input marker {given}, {}on the boundary, on segments with markers {:?}): marker {}, expected {expected}",
                mesh.points[v],
                if mesh.on_boundary[v] { "" } else { "not " },
                chains.iter().filter(|(_, c)| c.contains(&v)).map(|(&i, _)| segment_marker(i)).collect::<Vec<_>>(),
                markers[v]
            ));
        }
    }
    if let Some(segment_markers) = &out.segment_markers {
        for (s, &marker) in mesh.segments.iter().zip(segment_markers) {
            let expected = edge_rule(s[0], s[1]);
            if marker != expected {
                return Err(format!(
                    "output segment {s:?}: marker {marker}, expected {expected}"
                ));
            }
        }
    }
    if let (Some(edges), Some(edge_markers)) = (&out.edges, &out.edge_markers) {
        for (e, &marker) in edges.iter().zip(edge_markers) {
            let [a, b] = e.map(|v| (v - out.base) as usize);
            let expected = edge_rule(a, b);
            if marker != expected {
                return Err(format!(
                    "edge {a}-{b}: marker {marker}, expected {expected}"
                ));
            }
        }
    }
    Ok(())
}

/// Where the two outputs' vertices are matched: exactly by coordinates, or (vertices created at
/// crossings) within a small tolerance relative to the input's extent.
pub const SNAP_TOLERANCE: f64 = 1e-9;

/// The larger side of the bounding box of `points`.
fn extent(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for p in points {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    (hi[0] - lo[0]).max(hi[1] - lo[1])
}

/// Every difference between our output and Triangle's for the same PSLG and switches:
/// counts, which arrays are written, vertices (matched by coordinates, snapped), vertex markers
/// (of vertices in the mesh) and attributes, triangles (where the CDT is unique; elsewhere the
/// ambiguous regions must have the same vertices and triangle counts), region attributes per
/// triangle, segments and edges with their markers, and neighbours (each consistent with its own
/// triangles).
pub fn pslg_differences(
    input: &MeshInput,
    ours: &Triangulation,
    theirs: &Triangulation,
) -> Vec<String> {
    let input_places: HashSet<[u64; 2]> = input.points.iter().map(|&p| bits(p)).collect();
    let mut diffs = Vec::new();
    if ours.counts != theirs.counts {
        diffs.push(format!(
            "counts: ours {:?}, Triangle's {:?}",
            ours.counts, theirs.counts
        ));
    }
    let written = |t: &Triangulation| {
        [
            t.points.is_some(),
            t.point_attributes.is_some(),
            t.point_markers.is_some(),
            t.triangles.is_some(),
            t.triangle_attributes.is_some(),
            t.neighbors.is_some(),
            t.segments.is_some(),
            t.segment_markers.is_some(),
            t.edges.is_some(),
            t.edge_markers.is_some(),
            t.holes_alias_input,
            t.regions_alias_input,
            t.triangle_areas_written,
            t.norms_written,
        ]
    };
    if written(ours) != written(theirs) {
        diffs.push(format!(
            "arrays written (points, attributes, markers, triangles, attributes, neighbours, segments, markers, edges, markers, holes, regions, areas, norms): ours {:?}, Triangle's {:?}",
            written(ours),
            written(theirs)
        ));
    }
    let (a, b) = match (MeshView::of(ours), MeshView::of(theirs)) {
        (Ok(a), Ok(b)) => (a, b),
        (a, b) => {
            diffs.push(format!(
                "invalid mesh: ours {:?}, Triangle's {:?}",
                a.err(),
                b.err()
            ));
            return diffs;
        }
    };
    for (who, view) in [("ours", &a), ("Triangle's", &b)] {
        if let Some(neighbors) = &view.out.neighbors {
            if let Err(e) =
                super::checks::check_neighbors(&view.triangles, neighbors, view.out.base)
            {
                diffs.push(format!("{who} neighbours: {e}"));
            }
        }
    }

    // Vertices: ours → Triangle's.
    let extent = b
        .points
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let mut theirs_at: HashMap<[u64; 2], Vec<usize>> = HashMap::new();
    for (v, &p) in b.points.iter().enumerate() {
        theirs_at.entry(bits(p)).or_default().push(v);
    }
    let mut taken = vec![false; b.points.len()];
    let mut map = vec![usize::MAX; a.points.len()];
    let mut snapped = vec![false; a.points.len()];
    for (v, &p) in a.points.iter().enumerate() {
        if let Some(&w) = theirs_at
            .get(&bits(p))
            .into_iter()
            .flatten()
            .find(|&&w| !taken[w])
        {
            map[v] = w;
            taken[w] = true;
        }
    }
    for (v, &p) in a.points.iter().enumerate() {
        if map[v] != usize::MAX {
            continue;
        }
        let distance = |w: usize| {
            (b.points[w][0] - p[0])
                .abs()
                .max((b.points[w][1] - p[1]).abs())
        };
        let nearest = (0..b.points.len())
            .filter(|&w| !taken[w])
            .min_by(|&x, &y| distance(x).total_cmp(&distance(y)));
        match nearest {
            Some(w) if distance(w) <= SNAP_TOLERANCE * extent => {
                map[v] = w;
                taken[w] = true;
                snapped[v] = true;
            }
            _ => diffs.push(format!(
                "our vertex {v} {p:?} is not among Triangle's vertices"
            )),
        }
    }
    if !diffs.is_empty() {
        return diffs;
    }
    for (v, &w) in map.iter().enumerate() {
        if a.in_mesh[v] != b.in_mesh[w] {
            diffs.push(format!(
                "vertex {:?}: in our mesh {}, in Triangle's {}",
                a.points[v], a.in_mesh[v], b.in_mesh[w]
            ));
        }
    }
    if let (Some(ma), Some(mb)) = (&ours.point_markers, &theirs.point_markers) {
        for v in (0..a.points.len()).filter(|&v| a.in_mesh[v]) {
            if ma[v] != mb[map[v]] {
                diffs.push(format!(
                    "marker of vertex {v} {:?} (in the mesh): ours {}, Triangle's {}",
                    a.points[v], ma[v], mb[map[v]]
                ));
            }
        }
    }
    if let (Some(xa), Some(xb)) = (&ours.point_attributes, &theirs.point_attributes) {
        let k = ours.counts.point_attributes.max(0) as usize;
        for v in 0..a.points.len() {
            let (x, y) = (&xa[v * k..v * k + k], &xb[map[v] * k..map[v] * k + k]);
            // Input vertices keep their attributes; new ones are interpolated, maybe differently.
            let same = if input_places.contains(&bits(a.points[v])) {
                x == y
            } else {
                x.iter()
                    .zip(y)
                    .all(|(p, q)| (p - q).abs() <= 1e-9 * p.abs().max(q.abs()).max(1.0))
            };
            if !same {
                diffs.push(format!(
                    "attributes of vertex {v} {:?}: ours {x:?}, Triangle's {y:?}",
                    a.points[v]
                ));
            }
        }
    }

    // Triangles, where unique; region attributes per triangle.
    let (cocircular_a, cocircular_b) = (a.cocircular_edges(), b.cocircular_edges());
    let attribute_count = ours.counts.triangle_attributes.max(0) as usize;
    let attributes = |t: &Triangulation, i: usize| -> Vec<u64> {
        t.triangle_attributes.as_deref().map_or(Vec::new(), |x| {
            x[i * attribute_count..(i + 1) * attribute_count]
                .iter()
                .map(|v| v.to_bits())
                .collect()
        })
    };
    let mut unique_a = BTreeMap::new();
    let mut ambiguous_a = (0usize, BTreeSet::new(), Vec::new());
    for (i, c) in a.triangles.iter().enumerate() {
        let key = canonical_triangle(c.map(|v| map[v]));
        if a.is_ambiguous(i, &cocircular_a) {
            ambiguous_a.0 += 1;
            ambiguous_a.1.extend(key);
            ambiguous_a.2.push(attributes(ours, i));
        } else {
            unique_a.insert(key, attributes(ours, i));
        }
    }
    let mut unique_b = BTreeMap::new();
    let mut ambiguous_b = (0usize, BTreeSet::new(), Vec::new());
    for (i, c) in b.triangles.iter().enumerate() {
        let key = canonical_triangle(*c);
        if b.is_ambiguous(i, &cocircular_b) {
            ambiguous_b.0 += 1;
            ambiguous_b.1.extend(key);
            ambiguous_b.2.push(attributes(theirs, i));
        } else {
            unique_b.insert(key, attributes(theirs, i));
        }
    }
    ambiguous_a.2.sort();
    ambiguous_b.2.sort();
    if unique_a != unique_b {
        let only_a: Vec<_> = unique_a
            .iter()
            .filter(|&(k, v)| unique_b.get(k) != Some(v))
            .take(5)
            .collect();
        let only_b: Vec<_> = unique_b
            .iter()
            .filter(|&(k, v)| unique_a.get(k) != Some(v))
            .take(5)
            .collect();
        diffs.push(format!(
            "triangles where the CDT is unique (with attributes): {} vs {}; ours only (first 5, Triangle's numbering): {only_a:?}; Triangle's only: {only_b:?}",
            unique_a.len(),
            unique_b.len()
        ));
    }
    if ambiguous_a != ambiguous_b {
        diffs.push(format!(
            "cocircular regions: ours {} triangles on {} vertices, Triangle's {} on {} (or their attributes differ)",
            ambiguous_a.0,
            ambiguous_a.1.len(),
            ambiguous_b.0,
            ambiguous_b.1.len()
        ));
    }

    // Segments and edges with markers (edges inside cocircular regions aside).
    let pairs = |view: &MeshView<'_>,
                 list: Option<&[[i32; 2]]>,
                 markers: Option<&[i32]>,
                 to_theirs: &dyn Fn(usize) -> usize,
                 cocircular: &HashSet<[usize; 2]>| {
        list.unwrap_or_default()
            .iter()
            .enumerate()
            .filter_map(|(i, s)| {
                let [x, y] = s.map(|v| (v - view.out.base) as usize);
                (!cocircular.contains(&sorted_pair(x, y))).then(|| {
                    (
                        sorted_pair(to_theirs(x), to_theirs(y)),
                        markers.map(|m| m[i]),
                    )
                })
            })
            .collect::<BTreeMap<_, _>>()
    };
    let ours_to_theirs = |v: usize| map[v];
    let identity = |v: usize| v;
    for (what, la, ma, lb, mb) in [
        (
            "segments",
            ours.segments.as_deref(),
            ours.segment_markers.as_deref(),
            theirs.segments.as_deref(),
            theirs.segment_markers.as_deref(),
        ),
        (
            "edges",
            ours.edges.as_deref(),
            ours.edge_markers.as_deref(),
            theirs.edges.as_deref(),
            theirs.edge_markers.as_deref(),
        ),
    ] {
        let sa = pairs(&a, la, ma, &ours_to_theirs, &cocircular_a);
        let sb = pairs(&b, lb, mb, &identity, &cocircular_b);
        if sa != sb {
            let only_a: Vec<_> = sa
                .iter()
                .filter(|&(k, v)| sb.get(k) != Some(v))
                .take(5)
                .collect();
            let only_b: Vec<_> = sb
                .iter()
                .filter(|&(k, v)| sa.get(k) != Some(v))
                .take(5)
                .collect();
            diffs.push(format!(
                "{what} with markers (Triangle's numbering, zero-based): {} vs {}; ours only (first 5): {only_a:?}; Triangle's only: {only_b:?}",
                sa.len(),
                sb.len()
            ));
        }
    }
    diffs
}
