//! Order-independent views of an output (triangle, segment, edge and Voronoi sets), the comparison
//! of two outputs, and the validity checks of a triangulation: counter-clockwise and manifold,
//! boundary = convex hull, area = hull area, Euler's formula, Delaunay by exact `incircle`,
//! neighbours, and Voronoi duality.

use std::collections::{BTreeMap, BTreeSet, HashMap};

use robust::Coord;

use super::call::{Triangulation, Voronoi};
use super::points::Point;

fn coord(p: Point) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

/// The points scaled by one power of two so that the largest coordinate lies in [1, 2): exact,
/// and the sign of a predicate is unchanged, while `robust`'s products of coordinate differences
/// neither overflow (coordinates near 1e300) nor underflow (near 1e-300), where its adaptive
/// arithmetic is exact no more. (Inputs spanning more binary orders than that are refused by the
/// library.)
fn normalized<const N: usize>(points: [Point; N]) -> [Point; N] {
    let largest = points.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest == 0.0 || !largest.is_finite() {
        return points;
    }
    // largest = m · 2^e with m in [1, 2) (subnormals included: frexp by hand).
    let mut e = ((largest.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    if e == -1023 {
        e = -1023 - (largest.to_bits() & ((1u64 << 52) - 1)).leading_zeros() as i32 + 12;
    }
    // Multiply by 2^-e in steps that stay within the exponent range.
    let mut k = -e;
    let mut scaled = points;
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        let factor = f64::from_bits(((step + 1023) as u64) << 52);
        for p in &mut scaled {
            *p = p.map(|v| v * factor);
        }
        k -= step;
    }
    scaled
}

pub fn orient2d(a: Point, b: Point, c: Point) -> f64 {
    let [a, b, c] = normalized([a, b, c]);
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Positive when `d` is strictly inside the circle through the counter-clockwise `a`, `b`, `c`.
pub fn incircle(a: Point, b: Point, c: Point, d: Point) -> f64 {
    let [a, b, c, d] = normalized([a, b, c, d]);
    robust::incircle(coord(a), coord(b), coord(c), coord(d))
}

/// How two outputs' vertices are matched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Match {
    /// By index: both number the same points the same way (points, attributes and markers are
    /// compared item by item).
    Index,
    /// By coordinates: for inputs with duplicates, where the two may keep different copies of a
    /// duplicate (and `j` then numbers differently). Points are compared as multisets; markers
    /// and point attributes are left to rule checks.
    Coordinates,
}

/// A vertex as a comparable key: its index, or its coordinates' bits.
pub type Key = [u64; 2];

fn keyer(t: &Triangulation, mode: Match) -> impl Fn(i32) -> Key + '_ {
    move |i| match mode {
        Match::Index => [i as i64 as u64, 0],
        Match::Coordinates => t
            .points
            .as_ref()
            .and_then(|p| p.get((i - t.base) as usize))
            .map_or([u64::MAX, i as i64 as u64], |p| p.map(f64::to_bits)),
    }
}

/// A triangle rotated so that its smallest corner comes first: orientation is kept, so two
/// triangles are equal exactly when they have the same corners in the same cyclic order.
pub fn canonical_triangle<T: Ord + Copy>(t: [T; 3]) -> [T; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap();
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

pub fn triangle_set(t: &Triangulation) -> BTreeSet<[i32; 3]> {
    t.triangle_triples()
        .into_iter()
        .map(canonical_triangle)
        .collect()
}

fn keyed_triangles(t: &Triangulation, mode: Match) -> Vec<[Key; 3]> {
    let key = keyer(t, mode);
    t.triangle_triples()
        .into_iter()
        .map(|c| canonical_triangle(c.map(&key)))
        .collect()
}

/// Undirected pairs with their markers (`None` without a marker list).
fn pair_set(
    t: &Triangulation,
    pairs: Option<&[[i32; 2]]>,
    markers: Option<&[i32]>,
    mode: Match,
) -> BTreeMap<[Key; 2], Option<i32>> {
    let key = keyer(t, mode);
    pairs
        .unwrap_or_default()
        .iter()
        .enumerate()
        .map(|(i, &[a, b])| {
            let (a, b) = (key(a), key(b));
            ([a.min(b), a.max(b)], markers.map(|m| m[i]))
        })
        .collect()
}

/// (triangle, corner) → the neighbour across the edge opposite that corner (`None` for −1).
fn neighbor_map(t: &Triangulation, mode: Match) -> BTreeMap<([Key; 3], Key), Option<[Key; 3]>> {
    let key = keyer(t, mode);
    let triangles = t.triangle_triples();
    let keyed = keyed_triangles(t, mode);
    let mut map = BTreeMap::new();
    if let Some(neighbors) = &t.neighbors {
        for ((tri, nbrs), tri_key) in triangles.iter().zip(neighbors).zip(&keyed) {
            for k in 0..3 {
                let across = (nbrs[k] != -1).then(|| keyed[(nbrs[k] - t.base) as usize]);
                map.insert((*tri_key, key(tri[k])), across);
            }
        }
    }
    map
}

/// The numbering base of an output (0 with `z`, else 1).
pub fn index_base(t: &Triangulation) -> i32 {
    t.base
}

/// Zero-based corner triples.
pub fn zero_based(t: &Triangulation) -> Vec<[usize; 3]> {
    t.triangle_triples()
        .into_iter()
        .map(|c| c.map(|i| (i - t.base) as usize))
        .collect()
}

fn close(a: f64, b: f64, scale: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * scale.max(a.abs()).max(b.abs()).max(f64::MIN_POSITIVE)
}

/// Every difference between two outputs, as sets (Triangle's output order is an artefact of its
/// implementation). `voronoi_tolerance` is relative to the circumradius.
pub fn differences(
    ours: &Triangulation,
    reference: &Triangulation,
    mode: Match,
    voronoi_tolerance: f64,
) -> Vec<String> {
    let mut diffs = Vec::new();
    let mut same = |what: &str, equal: bool, detail: &dyn Fn() -> String| {
        if !equal {
            diffs.push(format!("{what}: {}", detail()));
        }
    };
    same("counts", ours.counts == reference.counts, &|| {
        format!("ours {:?}, Triangle's {:?}", ours.counts, reference.counts)
    });
    macro_rules! presence {
        ($($field:ident),*) => {$(
            same(concat!("written: ", stringify!($field)), ours.$field.is_some() == reference.$field.is_some(), &|| {
                format!("ours {}, Triangle's {}", ours.$field.is_some(), reference.$field.is_some())
            });
        )*};
    }
    presence!(
        points,
        point_attributes,
        point_markers,
        triangles,
        triangle_attributes,
        neighbors,
        segments,
        segment_markers,
        edges,
        edge_markers
    );
    for (what, a, b) in [
        (
            "holelist aliased",
            ours.holes_alias_input,
            reference.holes_alias_input,
        ),
        (
            "regionlist aliased",
            ours.regions_alias_input,
            reference.regions_alias_input,
        ),
        (
            "trianglearealist written",
            ours.triangle_areas_written,
            reference.triangle_areas_written,
        ),
        (
            "out.normlist written",
            ours.norms_written,
            reference.norms_written,
        ),
    ] {
        same(what, a == b, &|| format!("ours {a}, Triangle's {b}"));
    }
    match mode {
        Match::Index => {
            same("points", ours.points == reference.points, &|| {
                first_difference(&ours.points, &reference.points)
            });
            same(
                "point attributes",
                ours.point_attributes == reference.point_attributes,
                &|| first_difference(&ours.point_attributes, &reference.point_attributes),
            );
            same(
                "point markers",
                ours.point_markers == reference.point_markers,
                &|| first_difference(&ours.point_markers, &reference.point_markers),
            );
        }
        Match::Coordinates => {
            let sorted = |t: &Triangulation| {
                let mut p: Vec<Key> = t
                    .points
                    .iter()
                    .flatten()
                    .map(|p| p.map(f64::to_bits))
                    .collect();
                p.sort_unstable();
                p
            };
            same(
                "points (as a multiset)",
                sorted(ours) == sorted(reference),
                &|| "differ".into(),
            );
        }
    }
    let (a, b) = (
        keyed_triangles(ours, mode)
            .into_iter()
            .collect::<BTreeSet<_>>(),
        keyed_triangles(reference, mode)
            .into_iter()
            .collect::<BTreeSet<_>>(),
    );
    same("triangle set", a == b, &|| set_difference(&a, &b));
    same(
        "triangle attributes (sorted)",
        sorted_floats(&ours.triangle_attributes) == sorted_floats(&reference.triangle_attributes),
        &|| "differ".into(),
    );
    let (a, b) = (neighbor_map(ours, mode), neighbor_map(reference, mode));
    same("neighbours", a == b, &|| map_difference(&a, &b));
    let (a, b) = (
        pair_set(
            ours,
            ours.segments.as_deref(),
            ours.segment_markers.as_deref(),
            mode,
        ),
        pair_set(
            reference,
            reference.segments.as_deref(),
            reference.segment_markers.as_deref(),
            mode,
        ),
    );
    same("segments", a == b, &|| map_difference(&a, &b));
    let (a, b) = (
        pair_set(
            ours,
            ours.edges.as_deref(),
            ours.edge_markers.as_deref(),
            mode,
        ),
        pair_set(
            reference,
            reference.edges.as_deref(),
            reference.edge_markers.as_deref(),
            mode,
        ),
    );
    same("edges", a == b, &|| map_difference(&a, &b));
    match (&ours.voronoi, &reference.voronoi) {
        (Some(a), Some(b)) => diffs.extend(voronoi_differences(
            ours,
            a,
            reference,
            b,
            mode,
            voronoi_tolerance,
        )),
        (None, None) => {}
        _ => diffs.push("one call had a vorout, the other not (test bug)".into()),
    }
    diffs
}

fn sorted_floats(v: &Option<Vec<f64>>) -> Option<Vec<u64>> {
    v.as_ref().map(|v| {
        let mut bits: Vec<u64> = v.iter().map(|x| x.to_bits()).collect();
        bits.sort_unstable();
        bits
    })
}

fn first_difference<T: PartialEq + std::fmt::Debug>(
    a: &Option<Vec<T>>,
    b: &Option<Vec<T>>,
) -> String {
    match (a, b) {
        (Some(a), Some(b)) if a.len() == b.len() => {
            let i = a.iter().zip(b).position(|(x, y)| x != y).unwrap_or(0);
            format!("first at item {i}: ours {:?}, Triangle's {:?}", a[i], b[i])
        }
        (Some(a), Some(b)) => format!("lengths {} and {}", a.len(), b.len()),
        _ => format!("written: ours {}, Triangle's {}", a.is_some(), b.is_some()),
    }
}

fn set_difference<T: Ord + std::fmt::Debug>(a: &BTreeSet<T>, b: &BTreeSet<T>) -> String {
    let only_a: Vec<_> = a.difference(b).take(5).collect();
    let only_b: Vec<_> = b.difference(a).take(5).collect();
    format!(
        "{} vs {} items; only ours (first 5): {only_a:?}; only Triangle's: {only_b:?}",
        a.len(),
        b.len()
    )
}

fn map_difference<K: Ord + std::fmt::Debug, V: PartialEq + std::fmt::Debug>(
    a: &BTreeMap<K, V>,
    b: &BTreeMap<K, V>,
) -> String {
    let only_a: Vec<_> = a
        .iter()
        .filter(|(k, v)| b.get(k) != Some(v))
        .take(5)
        .collect();
    let only_b: Vec<_> = b
        .iter()
        .filter(|(k, v)| a.get(k) != Some(v))
        .take(5)
        .collect();
    format!(
        "{} vs {} items; ours only (first 5): {only_a:?}; Triangle's only: {only_b:?}",
        a.len(),
        b.len()
    )
}

/// A Voronoi diagram keyed by the triangles its vertices belong to.
struct KeyedVoronoi {
    /// canonical triangle → (circumcentre, attributes, circumradius)
    vertices: BTreeMap<[Key; 3], (Point, Vec<f64>, f64)>,
    /// finite edges as unordered pairs of triangles
    finite: BTreeSet<[[Key; 3]; 2]>,
    /// rays as (triangle, direction bits), with multiplicity
    rays: BTreeMap<([Key; 3], [u64; 2]), usize>,
}

fn key_voronoi(t: &Triangulation, v: &Voronoi, mode: Match) -> Option<KeyedVoronoi> {
    let triangles = keyed_triangles(t, mode);
    let corners = t.triangle_triples();
    let points = v.points.as_ref()?;
    if triangles.len() != points.len() {
        return None;
    }
    let width = v.attribute_count.max(0) as usize;
    let attributes = v.point_attributes.clone().unwrap_or_default();
    // The scale of a circumcentre's rounding error: the circumradius R, times R / (the shortest
    // edge) for thin triangles, whose centre is ill-conditioned (a sliver's centre lies far
    // away, and rounding its corners' differences moves it by about eps·R²/edge; Triangle's and
    // ours then differ by that much, and both from the exact centre).
    let radius = |i: usize| {
        let corner = |k: usize| {
            t.points
                .as_ref()
                .and_then(|p| p.get((corners[i][k] - t.base) as usize))
                .copied()
                .unwrap_or([f64::NAN; 2])
        };
        let distance = |p: Point, q: Point| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
        let r = distance(corner(0), points[i]);
        let shortest = (0..3)
            .map(|k| distance(corner(k), corner((k + 1) % 3)))
            .fold(f64::INFINITY, f64::min);
        r * (r / shortest).max(1.0)
    };
    let vertices = triangles
        .iter()
        .enumerate()
        .map(|(i, &key)| {
            (
                key,
                (
                    points[i],
                    attributes
                        .get(i * width..(i + 1) * width)
                        .unwrap_or_default()
                        .to_vec(),
                    radius(i),
                ),
            )
        })
        .collect();
    let mut finite = BTreeSet::new();
    let mut rays = BTreeMap::new();
    let norms = v.norms.clone().unwrap_or_default();
    for (i, &[a, b]) in v.edges.as_deref().unwrap_or_default().iter().enumerate() {
        let ta = *triangles.get((a - t.base) as usize)?;
        if b == -1 {
            let n = norms.get(i).copied().unwrap_or([f64::NAN; 2]);
            *rays.entry((ta, n.map(f64::to_bits))).or_insert(0) += 1;
        } else {
            let tb = *triangles.get((b - t.base) as usize)?;
            finite.insert(if ta < tb { [ta, tb] } else { [tb, ta] });
        }
    }
    Some(KeyedVoronoi {
        vertices,
        finite,
        rays,
    })
}

fn voronoi_differences(
    ours: &Triangulation,
    a: &Voronoi,
    reference: &Triangulation,
    b: &Voronoi,
    mode: Match,
    tolerance: f64,
) -> Vec<String> {
    let mut diffs = Vec::new();
    if (a.points_count, a.attribute_count, a.edges_count)
        != (b.points_count, b.attribute_count, b.edges_count)
    {
        diffs.push(format!(
            "Voronoi counts: ours {:?}, Triangle's {:?}",
            (a.points_count, a.attribute_count, a.edges_count),
            (b.points_count, b.attribute_count, b.edges_count)
        ));
    }
    let written = |v: &Voronoi| {
        (
            v.points.is_some(),
            v.point_attributes.is_some(),
            v.edges.is_some(),
            v.norms.is_some(),
            v.point_markers_written,
            v.edge_markers_written,
        )
    };
    if written(a) != written(b) {
        diffs.push(format!("Voronoi arrays written (points, attributes, edges, norms, markers, edge markers): ours {:?}, Triangle's {:?}", written(a), written(b)));
    }
    let (Some(ka), Some(kb)) = (key_voronoi(ours, a, mode), key_voronoi(reference, b, mode)) else {
        // Without triangles (E) or points (N) the vertices cannot be matched through their
        // triangles: compare them as sorted lists.
        let sorted = |v: &Voronoi| {
            let mut p = v.points.clone().unwrap_or_default();
            p.sort_by(|x, y| x.partial_cmp(y).unwrap());
            p
        };
        let (pa, pb) = (sorted(a), sorted(b));
        if pa.len() != pb.len()
            || pa.iter().zip(&pb).any(|(x, y)| {
                !close(x[0], y[0], 0.0, tolerance) || !close(x[1], y[1], 0.0, tolerance)
            })
        {
            diffs.push("Voronoi vertices (unmatched, sorted) differ".into());
        }
        return diffs;
    };
    let keys_a: BTreeSet<_> = ka.vertices.keys().collect();
    let keys_b: BTreeSet<_> = kb.vertices.keys().collect();
    if keys_a != keys_b {
        diffs.push("Voronoi vertices belong to different triangles".into());
    }
    let mut worst = (1.0, None);
    for (key, (pa, attr_a, _)) in &ka.vertices {
        let Some((pb, attr_b, radius)) = kb.vertices.get(key) else {
            continue;
        };
        let error = (pa[0] - pb[0]).abs().max((pa[1] - pb[1]).abs());
        // Without output points (N) the circumradius is unknown: scale by the coordinates.
        let scale = if radius.is_finite() {
            *radius
        } else {
            pb[0].abs().max(pb[1].abs())
        };
        let allowed = tolerance * scale + 4.0 * f64::EPSILON * pb[0].abs().max(pb[1].abs());
        // Written so that a NaN error counts as a failure.
        let ratio = error / allowed;
        if (error.is_nan() || error > allowed) && (ratio.is_nan() || ratio > worst.0) {
            worst = (ratio, Some((*pa, *pb)));
        }
        let attribute_scale = attr_b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        if attr_a.len() != attr_b.len()
            || attr_a
                .iter()
                .zip(attr_b)
                .any(|(x, y)| !close(*x, *y, attribute_scale, 1e-6))
        {
            diffs.push(format!(
                "Voronoi attributes of a triangle: ours {attr_a:?}, Triangle's {attr_b:?}"
            ));
        }
    }
    if let (ratio, Some((pa, pb))) = worst {
        diffs.push(format!(
            "circumcentre: ours {pa:?}, Triangle's {pb:?} ({ratio:.1}× the tolerance)"
        ));
    }
    if ka.finite != kb.finite {
        diffs.push(format!(
            "finite Voronoi edges: {} vs {} edges differ",
            ka.finite.len(),
            kb.finite.len()
        ));
    }
    if ka.rays != kb.rays {
        let only_a: Vec<_> = ka
            .rays
            .iter()
            .filter(|(k, v)| kb.rays.get(k) != Some(v))
            .map(|((_, n), _)| n.map(f64::from_bits))
            .take(5)
            .collect();
        let only_b: Vec<_> = kb
            .rays
            .iter()
            .filter(|(k, v)| ka.rays.get(k) != Some(v))
            .map(|((_, n), _)| n.map(f64::from_bits))
            .take(5)
            .collect();
        diffs.push(format!(
            "Voronoi rays differ: directions only ours {only_a:?}, only Triangle's {only_b:?}"
        ));
    }
    diffs
}

/// What a valid triangulation looked like.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MeshStats {
    pub triangles: usize,
    pub used_vertices: usize,
    pub hull_vertices: usize,
    pub interior_edges: usize,
    pub boundary_edges: usize,
    /// Vertices on the boundary (zero-based).
    pub boundary: BTreeSet<usize>,
}

pub type Directed = HashMap<(usize, usize), (usize, usize)>;

/// Directed edge (a, b) → (triangle, corner opposite it); fails on a repeated directed edge.
pub fn directed_edges(triangles: &[[usize; 3]]) -> Result<Directed, String> {
    let mut edges = HashMap::with_capacity(triangles.len() * 3);
    for (t, c) in triangles.iter().enumerate() {
        for k in 0..3 {
            if edges
                .insert((c[(k + 1) % 3], c[(k + 2) % 3]), (t, k))
                .is_some()
            {
                return Err(format!(
                    "directed edge {}→{} appears twice (not manifold)",
                    c[(k + 1) % 3],
                    c[(k + 2) % 3]
                ));
            }
        }
    }
    Ok(edges)
}

fn bits(p: Point) -> [u64; 2] {
    p.map(f64::to_bits)
}

/// The convex hull of `points` counter-clockwise, keeping points that lie on hull edges
/// (Andrew's monotone chain with exact orientation). Empty when all points are collinear.
pub fn convex_hull(points: &[Point]) -> Vec<Point> {
    let mut sorted: Vec<Point> = points.to_vec();
    sorted.sort_by(|a, b| a.partial_cmp(b).unwrap());
    sorted.dedup();
    if sorted.len() < 3 || sorted.windows(3).all(|w| orient2d(w[0], w[1], w[2]) == 0.0) {
        return Vec::new();
    }
    let chain = |iter: &mut dyn Iterator<Item = Point>| {
        let mut h: Vec<Point> = Vec::new();
        for p in iter {
            while h.len() >= 2 && orient2d(h[h.len() - 2], h[h.len() - 1], p) < 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
        h
    };
    let mut hull = chain(&mut sorted.iter().copied());
    hull.extend(chain(&mut sorted.iter().rev().copied()));
    hull
}

/// Validity of a triangulation of `points` (all of them, duplicates aside): corners in range,
/// counter-clockwise (exact), manifold, every distinct point used exactly once, boundary = the
/// convex hull, area = hull area, Euler's formula. Collinear input must give no triangle.
pub fn check_mesh(points: &[Point], triangles: &[[usize; 3]]) -> Result<MeshStats, String> {
    let hull = convex_hull(points);
    if hull.is_empty() {
        return if triangles.is_empty() {
            Ok(MeshStats::default())
        } else {
            Err("collinear input has triangles".into())
        };
    }
    for (t, c) in triangles.iter().enumerate() {
        if c.iter().any(|&i| i >= points.len()) {
            return Err(format!("triangle {t} {c:?} has a vertex out of range"));
        }
        if orient2d(points[c[0]], points[c[1]], points[c[2]]) <= 0.0 {
            return Err(format!(
                "triangle {t} {c:?} is not counter-clockwise ({:?})",
                c.map(|i| points[i])
            ));
        }
    }
    let edges = directed_edges(triangles)?;
    let mut used: HashMap<[u64; 2], usize> = HashMap::new();
    for c in triangles {
        for &i in c {
            if let Some(&other) = used.get(&bits(points[i])) {
                if other != i {
                    return Err(format!("points {other} and {i} coincide and are both used"));
                }
            }
            used.insert(bits(points[i]), i);
        }
    }
    let distinct: BTreeSet<[u64; 2]> = points.iter().map(|&p| bits(p)).collect();
    if used.len() != distinct.len() {
        let missing: Vec<_> = points
            .iter()
            .enumerate()
            .filter(|(_, p)| !used.contains_key(&bits(**p)))
            .map(|(i, _)| i)
            .take(5)
            .collect();
        return Err(format!(
            "{} of {} distinct points are used; missing e.g. {missing:?}",
            used.len(),
            distinct.len()
        ));
    }
    let boundary: Vec<(usize, usize)> = edges
        .keys()
        .filter(|&&(a, b)| !edges.contains_key(&(b, a)))
        .copied()
        .collect();
    let boundary_coords: BTreeSet<[[u64; 2]; 2]> = boundary
        .iter()
        .map(|&(a, b)| [bits(points[a]), bits(points[b])])
        .collect();
    let hull_coords: BTreeSet<[[u64; 2]; 2]> = (0..hull.len())
        .map(|i| [bits(hull[i]), bits(hull[(i + 1) % hull.len()])])
        .collect();
    if boundary_coords != hull_coords {
        return Err(format!(
            "the boundary ({} edges) is not the convex hull ({} edges, collinear points kept)",
            boundary_coords.len(),
            hull_coords.len()
        ));
    }
    let origin = hull[0];
    let rel = |p: Point| [p[0] - origin[0], p[1] - origin[1]];
    let area_of = |a: Point, b: Point, c: Point| {
        let (a, b, c) = (rel(a), rel(b), rel(c));
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    };
    let mesh_area: f64 = triangles
        .iter()
        .map(|c| area_of(points[c[0]], points[c[1]], points[c[2]]))
        .sum();
    let hull_area: f64 = (1..hull.len() - 1)
        .map(|i| area_of(hull[0], hull[i], hull[i + 1]))
        .sum();
    if !close(mesh_area, hull_area, 0.0, 1e-9) {
        return Err(format!(
            "triangle areas sum to {mesh_area:e}, the hull's area is {hull_area:e}"
        ));
    }
    let boundary_vertices: BTreeSet<usize> = boundary.iter().map(|&(a, _)| a).collect();
    let (v, h, t) = (used.len(), boundary_vertices.len(), triangles.len());
    if t + 2 + h != 2 * v {
        return Err(format!(
            "Euler: {t} triangles, {v} vertices, {h} on the hull (expected 2v - 2 - h)"
        ));
    }
    Ok(MeshStats {
        triangles: t,
        used_vertices: v,
        hull_vertices: h,
        interior_edges: (edges.len() - boundary.len()) / 2,
        boundary_edges: boundary.len(),
        boundary: boundary_vertices,
    })
}

/// The empty-circle property by exact `incircle` across every interior edge.
pub fn check_delaunay(points: &[Point], triangles: &[[usize; 3]]) -> Result<(), String> {
    let edges = directed_edges(triangles)?;
    for (&(a, b), &(t, k)) in &edges {
        if a > b {
            continue;
        }
        let Some(&(u, l)) = edges.get(&(b, a)) else {
            continue;
        };
        let apex = triangles[t][k];
        let opposite = triangles[u][l];
        let inside = incircle(points[a], points[b], points[apex], points[opposite]);
        if inside > 0.0 {
            return Err(format!("edge {a}-{b} is not Delaunay: point {opposite} lies inside the circumcircle of {:?}", triangles[t]));
        }
    }
    Ok(())
}

/// `neighbors[t][k]` is the triangle across the edge opposite corner k of t, −1 exactly on the
/// boundary.
pub fn check_neighbors(
    triangles: &[[usize; 3]],
    neighbors: &[[i32; 3]],
    base: i32,
) -> Result<(), String> {
    if neighbors.len() != triangles.len() {
        return Err(format!(
            "{} neighbour rows for {} triangles",
            neighbors.len(),
            triangles.len()
        ));
    }
    let edges = directed_edges(triangles)?;
    for (t, c) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (c[(k + 1) % 3], c[(k + 2) % 3]);
            let expected = edges.get(&(b, a)).map_or(-1, |&(u, _)| u as i32 + base);
            if neighbors[t][k] != expected {
                return Err(format!(
                    "triangle {t} {c:?}: neighbour {k} is {}, expected {expected}",
                    neighbors[t][k]
                ));
            }
        }
    }
    Ok(())
}

/// The circumcentre of a triangle, computed relative to its first corner.
pub fn circumcentre(a: Point, b: Point, c: Point) -> Point {
    let (bx, by) = (b[0] - a[0], b[1] - a[1]);
    let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    [
        a[0] + (cy * b2 - by * c2) / d,
        a[1] + (bx * c2 - cx * b2) / d,
    ]
}

/// Voronoi duality: one vertex per triangle at its circumcentre, one finite edge per interior
/// edge joining the two triangles, one ray per hull edge o→d starting at its triangle with
/// direction exactly (d.y − o.y, o.x − d.x), and (0, 0) as the direction of finite edges.
pub fn check_voronoi(
    points: &[Point],
    triangles: &[[usize; 3]],
    voronoi: &Voronoi,
    base: i32,
) -> Result<(), String> {
    let vertices = voronoi.points.as_ref().ok_or("no Voronoi points")?;
    let vedges = voronoi.edges.as_ref().ok_or("no Voronoi edges")?;
    let norms = voronoi.norms.as_ref().ok_or("no Voronoi normlist")?;
    if vertices.len() != triangles.len() || voronoi.points_count as usize != triangles.len() {
        return Err(format!(
            "{} Voronoi vertices for {} triangles",
            vertices.len(),
            triangles.len()
        ));
    }
    for (t, c) in triangles.iter().enumerate() {
        let [a, b, d] = c.map(|i| points[i]);
        let expected = circumcentre(a, b, d);
        let radius = ((a[0] - expected[0]).powi(2) + (a[1] - expected[1]).powi(2)).sqrt();
        let error = (vertices[t][0] - expected[0])
            .abs()
            .max((vertices[t][1] - expected[1]).abs());
        let allowed = 1e-6 * radius + 8.0 * f64::EPSILON * expected[0].abs().max(expected[1].abs());
        if error.is_nan() || error > allowed {
            return Err(format!(
                "Voronoi vertex {t} is {:?}, the circumcentre of {c:?} is {expected:?}",
                vertices[t]
            ));
        }
    }
    let edges = directed_edges(triangles)?;
    let mut unmatched: HashMap<(usize, usize), (usize, usize)> = edges
        .iter()
        .filter(|(&(a, b), _)| a < b || !edges.contains_key(&(b, a)))
        .map(|(&e, &v)| (e, v))
        .collect();
    if vedges.len() != unmatched.len() || voronoi.edges_count as usize != unmatched.len() {
        return Err(format!(
            "{} Voronoi edges for {} triangulation edges",
            vedges.len(),
            unmatched.len()
        ));
    }
    for (i, &[p, q]) in vedges.iter().enumerate() {
        let t = (p - base) as usize;
        if t >= triangles.len() {
            return Err(format!("Voronoi edge {i} starts at {p}"));
        }
        let c = triangles[t];
        let found = if q == -1 {
            (0..3)
                .map(|k| (c[(k + 1) % 3], c[(k + 2) % 3]))
                .find(|&(o, d)| {
                    !edges.contains_key(&(d, o))
                        && unmatched.contains_key(&(o, d))
                        && norms[i] == [points[d][1] - points[o][1], points[o][0] - points[d][0]]
                })
        } else {
            if norms[i] != [0.0, 0.0] {
                return Err(format!(
                    "finite Voronoi edge {i} has direction {:?}",
                    norms[i]
                ));
            }
            let u = (q - base) as usize;
            (0..3)
                .map(|k| (c[(k + 1) % 3], c[(k + 2) % 3]))
                .find(|&(o, d)| {
                    edges.get(&(d, o)).is_some_and(|&(v, _)| v == u)
                        && unmatched.contains_key(&(o.min(d), o.max(d)))
                })
                .map(|(o, d)| (o.min(d), o.max(d)))
        };
        match found {
            Some(e) => {
                unmatched.remove(&e);
            }
            None => return Err(format!("Voronoi edge {i} ({p}, {q}, direction {:?}) is not dual to an unmatched edge of triangle {c:?}", norms[i])),
        }
    }
    Ok(())
}

/// Triangle's vertex-marker rule for a point set without `j`, checked on one output: a vertex in
/// the mesh gets its input marker if non-zero, else 1 on the boundary, else 0; a duplicate left
/// out of the mesh keeps its input marker (0 when there is none).
pub fn check_point_markers(
    input_markers: Option<&[i32]>,
    out: &Triangulation,
) -> Result<(), String> {
    let markers = out.point_markers.as_ref().ok_or("no point markers")?;
    let triangles = zero_based(out);
    let points = out.points.as_ref().ok_or("no points")?;
    let used: BTreeSet<usize> = triangles.iter().flatten().copied().collect();
    let stats = if triangles.is_empty() {
        MeshStats::default()
    } else {
        check_mesh(points, &triangles)?
    };
    for (i, &marker) in markers.iter().enumerate() {
        let given = input_markers.map_or(0, |m| m[i]);
        let expected = match (given, used.contains(&i)) {
            (0, true) => stats.boundary.contains(&i) as i32,
            (given, _) => given,
        };
        if marker != expected {
            return Err(format!(
                "point {i} {:?} (input marker {given}, {}): marker {marker}, expected {expected}",
                points[i],
                if used.contains(&i) {
                    "in the mesh"
                } else {
                    "left out"
                }
            ));
        }
    }
    Ok(())
}

/// `A` without regions: Triangle adds no triangle attribute, we add a column of zeros (the
/// manual's rule; a documented deviation). Checks that column on `ours` and returns `ours`
/// without it, for comparison with Triangle's output; other outputs are returned unchanged.
pub fn without_zero_region_column(
    ours: &Triangulation,
    switches: &str,
    region_count: usize,
) -> Triangulation {
    let region_switch = switches.contains('A') && switches.contains('p') && !switches.contains('r');
    if !region_switch || region_count > 0 {
        return ours.clone();
    }
    assert_eq!(
        ours.counts.triangle_attributes, 1,
        "\"{switches}\" without regions: one attribute per triangle"
    );
    if let Some(attributes) = &ours.triangle_attributes {
        assert!(
            attributes.iter().all(|&a| a == 0.0),
            "\"{switches}\" without regions: the attributes must be zero"
        );
    }
    let mut stripped = ours.clone();
    stripped.counts.triangle_attributes = 0;
    stripped.triangle_attributes = None;
    stripped
}
