//! Checks of quality meshes (Delaunay refinement: `q`, `a`, `u`, `D`, `Y`, `S`) and the calls
//! they need:
//! - [`engine`]: our safe engine entry (`pipeline::triangulate` with [`Hooks`]), converted to a
//!   [`Triangulation`] with the warnings (the C ABI prints them, and not at all with `Q`);
//! - [`ours_reentrant`]: the C ABI's `triangulate_reentrant` (callback, user data, cancel flag);
//! - [`check_angles`]: every angle ≥ θ except in the triangles that small input angles force;
//! - [`check_areas`]: every triangle within its (global or regional) area bound;
//! - [`check_conforming_delaunay`]: every edge locally Delaunay, segments included, and every
//!   circumcentre inside the meshed domain;
//! - [`new_vertices_on_segments`]: the vertices refinement put on input segments (`Y`, `YY`);
//! - [`check_second_order`]: `o2`'s midpoint nodes (exact, opposite their corners, one per edge);
//! - [`normalized`]: a shape scaled by a power of two (exactly) to fit the unit box, so that the
//!   absolute area bounds of the switches mean the same on every shape.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::os::raw::{c_char, c_int, c_void};

use triangle_rs::data::{Hooks, Input, Output};
use triangle_rs::ffi::TriunsuitableUserFn;
use triangle_rs::geometry::diametral_dot;
use triangle_rs::options::{Options, SwitchSource};

use super::call::{ours, run_call, Counts, MeshInput, Triangulation};
use super::checks::{circumcentre, orient2d};
use super::points::Point;
use super::pslg::Pslg;
use super::pslg_checks::{check_locally_delaunay, MeshView};

/// Our engine through its safe Rust entry with `hooks`: the output as the C ABI would write it
/// (without Voronoi), and the warnings.
pub fn engine(
    switches: &str,
    input: &MeshInput,
    hooks: &Hooks<'_>,
) -> Result<(Triangulation, Vec<String>), String> {
    let options = Options::parse(switches, SwitchSource::Library).map_err(|e| e.to_string())?;
    let engine_input = Input {
        points: input.points.as_flattened(),
        point_attributes: &input.attributes,
        point_attribute_count: input.attribute_count,
        point_markers: input.markers.as_deref(),
        triangles: &input.triangles,
        corners: input.corners,
        triangle_attributes: &input.triangle_attributes,
        triangle_attribute_count: input.triangle_attribute_count,
        triangle_areas: input.triangle_areas.as_deref(),
        segments: input.segments.as_flattened(),
        segment_markers: input.segment_markers.as_deref(),
        holes: input.holes.as_flattened(),
        regions: input.regions.as_flattened(),
    };
    let (out, _voronoi) = triangle_rs::pipeline::triangulate(&options, &engine_input, hooks)
        .map_err(|e| e.to_string())?;
    Ok((triangulation_of(&out, options.first_index()), out.warnings))
}

/// Our `triangulate_reentrant` through the C ABI: the `u` test is `callback` with `user_data`,
/// and refinement stops once `*cancel` is non-zero (`cancel` may be NULL).
pub fn ours_reentrant(
    switches: &str,
    input: &MeshInput,
    callback: Option<TriunsuitableUserFn>,
    user_data: *mut c_void,
    cancel: *const c_int,
) -> Result<Triangulation, String> {
    let call = |s: *mut c_char, i, o, v| {
        // SAFETY: valid switches and structs prepared by `run_call`; `user_data` and `cancel` are
        // what the caller passes and keeps alive during the call.
        let rc = unsafe {
            triangle_rs::ffi::triangulate_reentrant(s, i, o, v, callback, user_data, cancel)
        };
        if rc == 0 {
            Ok(())
        } else {
            // SAFETY: the library returns a valid NUL-terminated string.
            let message =
                unsafe { std::ffi::CStr::from_ptr(triangle_rs::ffi::triangulate_last_error()) };
            Err(message.to_string_lossy().into_owned())
        }
    };
    // SAFETY: arrays returned by our `triangulate_reentrant` are freed with our `trifree`.
    let free = |p: *mut c_void| unsafe { triangle_rs::ffi::trifree(p) };
    run_call(&call, &free, switches, input, false)
}

fn rows<T: Copy + Default, const N: usize>(flat: &Option<Vec<T>>) -> Option<Vec<[T; N]>> {
    flat.as_ref().map(|v| {
        v.chunks_exact(N)
            .map(|c| {
                let mut row = [T::default(); N];
                row.copy_from_slice(c);
                row
            })
            .collect()
    })
}

/// The engine's [`Output`] in the shape of a C ABI call's copy.
fn triangulation_of(out: &Output, base: i32) -> Triangulation {
    Triangulation {
        base,
        counts: Counts {
            points: out.point_count as i32,
            point_attributes: out.point_attribute_count as i32,
            triangles: out.triangle_count as i32,
            corners: out.corners as i32,
            triangle_attributes: out.triangle_attribute_count as i32,
            segments: out.segment_count as i32,
            holes: out.hole_count as i32,
            regions: out.region_count as i32,
            edges: out.edge_count as i32,
        },
        points: rows::<f64, 2>(&out.points),
        point_attributes: out.point_attributes.clone(),
        point_markers: out.point_markers.clone(),
        triangles: out.triangles.clone(),
        triangle_attributes: out.triangle_attributes.clone(),
        neighbors: rows::<i32, 3>(&out.neighbors),
        segments: rows::<i32, 2>(&out.segments),
        segment_markers: out.segment_markers.clone(),
        edges: rows::<i32, 2>(&out.edges),
        edge_markers: out.edge_markers.clone(),
        ..Triangulation::default()
    }
}

/// `pslg` scaled by a power of two (so exactly) until its bounding box fits in a unit square;
/// hole and region points scale with it, regional area bounds with its square.
pub fn normalized(mut pslg: Pslg) -> Pslg {
    let extent = pslg
        .input
        .points
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let span = {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &pslg.input.points {
            for i in 0..2 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        (hi[0] - lo[0]).max(hi[1] - lo[1]).max(extent * 1e-3)
    };
    let scale = 2f64.powi(-(span.log2().ceil() as i32));
    let s = |p: &mut Point| *p = p.map(|x| x * scale);
    pslg.input.points.iter_mut().for_each(s);
    pslg.input.holes.iter_mut().for_each(s);
    for r in &mut pslg.input.regions {
        r[0] *= scale;
        r[1] *= scale;
        if r[3] > 0.0 {
            r[3] *= scale * scale;
        }
    }
    for polygon in pslg
        .hole_polygons
        .iter_mut()
        .chain(pslg.islands.iter_mut().map(|(p, _)| p))
    {
        polygon.iter_mut().for_each(s);
    }
    pslg.area = pslg.area.map(|a| a * scale * scale);
    pslg.area_ignoring_holes = pslg.area_ignoring_holes.map(|a| a * scale * scale);
    pslg
}

/// The three angles of triangle `abc` in degrees (at a, b, c).
pub fn angles(a: Point, b: Point, c: Point) -> [f64; 3] {
    let at = |o: Point, p: Point, q: Point| {
        let (u, v) = ([p[0] - o[0], p[1] - o[1]], [q[0] - o[0], q[1] - o[1]]);
        (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1])
            .to_degrees()
    };
    [at(a, b, c), at(b, c, a), at(c, a, b)]
}

/// The smallest angle of the mesh, in degrees (180 without triangles).
pub fn smallest_angle(mesh: &MeshView<'_>) -> f64 {
    mesh.triangles
        .iter()
        .flat_map(|c| {
            let [a, b, d] = c.map(|v| mesh.points[v]);
            angles(a, b, d)
        })
        .fold(180.0, f64::min)
}

/// Two input segments that meet at an output vertex (a shared endpoint, an endpoint on the
/// other segment, or a crossing), with the smallest angle between them there.
#[derive(Clone, Debug)]
pub struct InputAngle {
    pub apex: usize,
    pub degrees: f64,
    /// The chains of the two segments (output vertices, apex included).
    pub chains: [Vec<usize>; 2],
}

/// Every pair of input segments that meet at less than `limit` degrees (`chains` as from
/// [`super::pslg_checks::segment_chains`]).
pub fn input_angles(
    mesh: &MeshView<'_>,
    chains: &BTreeMap<usize, Vec<usize>>,
    limit: f64,
) -> Vec<InputAngle> {
    // The rays of an input segment's pieces leaving its chain vertex v.
    let rays = |chain: &[usize], v: usize| -> Vec<Point> {
        let here = mesh.points[v];
        let toward = |w: usize| [mesh.points[w][0] - here[0], mesh.points[w][1] - here[1]];
        let (first, last) = (chain[0], chain[chain.len() - 1]);
        [first, last]
            .into_iter()
            .filter(|&w| w != v)
            .map(toward)
            .collect()
    };
    let between = |u: Point, w: Point| {
        (u[0] * w[1] - u[1] * w[0])
            .abs()
            .atan2(u[0] * w[0] + u[1] * w[1])
            .to_degrees()
    };
    let list: Vec<&Vec<usize>> = chains.values().collect();
    let mut found = Vec::new();
    for (i, &c1) in list.iter().enumerate() {
        for &c2 in &list[i + 1..] {
            for &v in c1.iter().filter(|v| c2.contains(v)) {
                let degrees = rays(c1, v)
                    .iter()
                    .flat_map(|&r1| rays(c2, v).into_iter().map(move |r2| between(r1, r2)))
                    .fold(180.0, f64::min);
                if degrees < limit {
                    found.push(InputAngle {
                        apex: v,
                        degrees,
                        chains: [c1.clone(), c2.clone()],
                    });
                }
            }
        }
    }
    found
}

/// How the angles of a mesh compare with the bound θ.
#[derive(Clone, Copy, Debug, Default)]
pub struct AngleReport {
    /// The smallest angle of the triangles that no input angle excuses.
    pub smallest_checked: f64,
    /// The smallest angle of all.
    pub smallest: f64,
    /// Triangles excused by an input angle.
    pub excused: usize,
}

/// Tolerance on the angle bound, in degrees: the engine tests angles in floating point.
pub const ANGLE_TOLERANCE: f64 = 1e-6;

/// Which triangles [`check_angles`] lets have angles below θ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exemptions {
    /// Only those that an input angle below θ forces (two input segments meeting at less than
    /// θ): a triangle whose smallest angle is at the vertex where they meet, or is formed by two
    /// output segments (the hull's too, with `c`), or whose three corners all lie on the two
    /// segments (between concentric-shell vertices).
    BelowTheta,
    /// Also the skinny triangles of Shewchuk's concentric-shell rule (2002, §4), which Triangle
    /// applies too: the shortest edge joins two new vertices on two segments that meet at less
    /// than 60° (at an endpoint of both, or where they cross), at equal distances from where
    /// they meet (within 0.2%).
    ShellRule,
}

/// Every angle ≥ `theta` (degrees), except in the triangles that `exemptions` allow. `input` is
/// the zero-based input, `chains` as from [`super::pslg_checks::segment_chains`]. Returns what it
/// found.
pub fn check_angles(
    mesh: &MeshView<'_>,
    input: &MeshInput,
    chains: &BTreeMap<usize, Vec<usize>>,
    theta: f64,
    exemptions: Exemptions,
) -> Result<AngleReport, String> {
    let shells = exemptions == Exemptions::ShellRule;
    let meetings = input_angles(
        mesh,
        chains,
        if shells { 60.0 } else { theta } + ANGLE_TOLERANCE,
    );
    let below_theta: Vec<&InputAngle> = meetings
        .iter()
        .filter(|m| m.degrees < theta + ANGLE_TOLERANCE)
        .collect();
    let apices: HashSet<usize> = below_theta.iter().map(|m| m.apex).collect();
    let input_places: HashSet<[u64; 2]> =
        input.points.iter().map(|p| p.map(f64::to_bits)).collect();
    let is_new = |v: usize| !input_places.contains(&mesh.points[v].map(f64::to_bits));
    let distance2 = |v: usize, w: usize| {
        let (p, q) = (mesh.points[v], mesh.points[w]);
        (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)
    };
    let shell_pair = |u: usize, w: usize| {
        meetings.iter().any(|m| {
            let on = |k: usize, v: usize| m.chains[k].contains(&v) && v != m.apex;
            let (du, dw) = (distance2(u, m.apex), distance2(w, m.apex));
            is_new(u)
                && is_new(w)
                && ((on(0, u) && on(1, w)) || (on(1, u) && on(0, w)))
                && du <= 1.002 * dw
                && dw <= 1.002 * du
        })
    };
    let mut report = AngleReport {
        smallest_checked: 180.0,
        smallest: 180.0,
        excused: 0,
    };
    for c in &mesh.triangles {
        let [a, b, d] = c.map(|v| mesh.points[v]);
        let angle = angles(a, b, d);
        let k = (0..3)
            .min_by(|&i, &j| angle[i].total_cmp(&angle[j]))
            .unwrap();
        let smallest = angle[k];
        report.smallest = report.smallest.min(smallest);
        if smallest >= theta - ANGLE_TOLERANCE {
            report.smallest_checked = report.smallest_checked.min(smallest);
            continue;
        }
        let at_apex = apices.contains(&c[k]);
        let between_segments = below_theta.iter().any(|m| {
            c.iter()
                .all(|v| m.chains[0].contains(v) || m.chains[1].contains(v))
        });
        // The shortest edge is opposite the smallest angle.
        let shell = shells && shell_pair(c[(k + 1) % 3], c[(k + 2) % 3]);
        // Two segments (input ones, or the hull's with `c`) forming the angle.
        let [u, w] = [c[(k + 1) % 3], c[(k + 2) % 3]];
        let segments_at_apex = mesh.is_segment(c[k], u) && mesh.is_segment(c[k], w);
        if at_apex || between_segments || shell || segments_at_apex {
            report.excused += 1;
            continue;
        }
        return Err(format!(
            "triangle {:?} has an angle of {smallest}°, below {theta}°, and no input angle forces it",
            c.map(|v| mesh.points[v]),
        ));
    }
    Ok(report)
}

/// The output points of our unrefined constrained Delaunay triangulation of `pslg` (input
/// vertices and crossings): `Y` and `YY` allow only these on segments.
pub fn unrefined_points(pslg: &Pslg) -> HashSet<[u64; 2]> {
    let out = ours("pzQ", &pslg.input).unwrap_or_else(|e| panic!("{}: {e}", pslg.name));
    out.points
        .unwrap_or_default()
        .iter()
        .map(|p| p.map(f64::to_bits))
        .collect()
}

/// The signed area of `abc` (as the engine computes it, up to rounding).
pub fn area(a: Point, b: Point, c: Point) -> f64 {
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

/// Every triangle `t` has an area ≤ `bound(t)` (`None`: unconstrained). Returns the largest ratio
/// of area to bound.
pub fn check_areas(
    mesh: &MeshView<'_>,
    bound: &dyn Fn(usize) -> Option<f64>,
) -> Result<f64, String> {
    let mut worst: f64 = 0.0;
    for (t, c) in mesh.triangles.iter().enumerate() {
        let Some(limit) = bound(t) else { continue };
        let [a, b, d] = c.map(|v| mesh.points[v]);
        let found = area(a, b, d);
        worst = worst.max(found / limit);
        if found > limit * (1.0 + 1e-12) {
            return Err(format!(
                "triangle {t} {:?} has area {found:e}, above its bound {limit:e}",
                c.map(|v| mesh.points[v])
            ));
        }
    }
    Ok(worst)
}

/// The area bound of each triangle for switches with `a` (global `a<x>` and/or regional `a`),
/// read from the region attribute that `A` appends (the last triangle attribute): regions are
/// recognised by their attribute, which must be unique per region.
pub fn area_bound(
    input: &MeshInput,
    out: &Triangulation,
    global: Option<f64>,
    regional: bool,
) -> impl Fn(usize) -> Option<f64> {
    let width = out.counts.triangle_attributes.max(0) as usize;
    let region_attribute: Vec<f64> = match (&out.triangle_attributes, regional) {
        (Some(attributes), true) if width > 0 => attributes
            .chunks_exact(width)
            .map(|a| a[width - 1])
            .collect(),
        _ => {
            assert!(
                !regional || input.regions.is_empty(),
                "regional area bounds are checked with `A`"
            );
            Vec::new()
        }
    };
    let regions = input.regions.clone();
    for (i, r) in regions.iter().enumerate() {
        assert!(
            regions[..i].iter().all(|q| q[2] != r[2]),
            "region attributes must be unique to find a triangle's region"
        );
    }
    move |t| {
        let local = region_attribute.get(t).and_then(|&attribute| {
            regions
                .iter()
                .find(|r| r[2] == attribute)
                .map(|r| r[3])
                .filter(|&a| a > 0.0)
        });
        match (global, local) {
            (Some(g), Some(l)) => Some(g.min(l)),
            (g, l) => g.or(l),
        }
    }
}

/// Truly Delaunay (`D`): every interior edge, segments included, is locally Delaunay by exact
/// `incircle`; no boundary edge has the apex of its triangle strictly inside its diametral
/// circle (exactly: else that triangle's circumcentre, a Voronoi vertex, lies outside); and
/// every triangle's circumcentre lies in the meshed domain (up to rounding of the circumcentre:
/// within `1e-9` of the domain's extent).
pub fn check_conforming_delaunay(mesh: &MeshView<'_>) -> Result<(), String> {
    check_locally_delaunay(mesh, true)?;
    for (&(a, b), &(t, k)) in &mesh.edges {
        if mesh.edges.contains_key(&(b, a)) {
            continue;
        }
        let apex = mesh.triangles[t][k];
        let [pa, pb, pw] = [a, b, apex].map(|v| mesh.points[v]);
        if diametral_dot(pa, pb, pw) < 0.0 {
            return Err(format!(
                "boundary edge {pa:?}-{pb:?} has vertex {pw:?} strictly inside its diametral circle"
            ));
        }
    }
    let locator = Locator::new(mesh);
    for c in &mesh.triangles {
        let [a, b, d] = c.map(|v| mesh.points[v]);
        let centre = circumcentre(a, b, d);
        if !locator.contains(centre) {
            return Err(format!(
                "the circumcentre {centre:?} of triangle {:?} lies outside the meshed domain",
                [a, b, d]
            ));
        }
    }
    Ok(())
}

/// Point location in a mesh by a uniform grid of triangle bounding boxes.
struct Locator<'m> {
    mesh: &'m MeshView<'m>,
    lo: Point,
    cell: f64,
    side: usize,
    buckets: Vec<Vec<usize>>,
    tolerance: f64,
}

impl<'m> Locator<'m> {
    fn new(mesh: &'m MeshView<'m>) -> Self {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in mesh.triangles.iter().flatten().map(|&v| mesh.points[v]) {
            for i in 0..2 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(f64::MIN_POSITIVE);
        let side = ((mesh.triangles.len() as f64).sqrt().ceil() as usize).max(1);
        let cell = extent / side as f64 * (1.0 + 1e-9);
        let mut locator = Locator {
            mesh,
            lo,
            cell,
            side,
            buckets: vec![Vec::new(); side * side],
            tolerance: 1e-9 * extent,
        };
        for (t, c) in mesh.triangles.iter().enumerate() {
            let ps = c.map(|v| mesh.points[v]);
            let (x0, y0) = locator.cell_of([
                ps.iter().map(|p| p[0]).fold(f64::MAX, f64::min) - locator.tolerance,
                ps.iter().map(|p| p[1]).fold(f64::MAX, f64::min) - locator.tolerance,
            ]);
            let (x1, y1) = locator.cell_of([
                ps.iter().map(|p| p[0]).fold(f64::MIN, f64::max) + locator.tolerance,
                ps.iter().map(|p| p[1]).fold(f64::MIN, f64::max) + locator.tolerance,
            ]);
            for x in x0..=x1 {
                for y in y0..=y1 {
                    locator.buckets[y * side + x].push(t);
                }
            }
        }
        locator
    }

    fn cell_of(&self, p: Point) -> (usize, usize) {
        let index =
            |x: f64, lo: f64| (((x - lo) / self.cell).floor().max(0.0) as usize).min(self.side - 1);
        (index(p[0], self.lo[0]), index(p[1], self.lo[1]))
    }

    /// Whether `p` lies in a triangle, or within the tolerance of one.
    fn contains(&self, p: Point) -> bool {
        let (x, y) = self.cell_of(p);
        self.buckets[y * self.side + x].iter().any(|&t| {
            let c = self.mesh.triangles[t].map(|v| self.mesh.points[v]);
            (0..3).all(|k| {
                let (a, b) = (c[k], c[(k + 1) % 3]);
                if orient2d(a, b, p) >= 0.0 {
                    return true;
                }
                // Distance of p from the line ab, on the outside.
                let length = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
                -2.0 * area(a, b, p) / length <= self.tolerance
            })
        })
    }
}

/// The vertices refinement added on input segments: chain vertices that are not among
/// `allowed` (the vertices of the mesh without refinement: input vertices and crossings).
/// `boundary_only`: only on input segments that bound the domain (an outside triangle on a side
/// of their pieces), as `Y` forbids; else on every input segment, as `YY` forbids.
pub fn new_vertices_on_segments(
    mesh: &MeshView<'_>,
    chains: &BTreeMap<usize, Vec<usize>>,
    allowed: &HashSet<[u64; 2]>,
    boundary_only: bool,
) -> Vec<(usize, Point)> {
    let mut found = Vec::new();
    for (&segment, chain) in chains {
        let on_boundary = chain.windows(2).any(|w| mesh.is_boundary_edge(w[0], w[1]));
        if boundary_only && !on_boundary {
            continue;
        }
        for &v in chain {
            if !allowed.contains(&mesh.points[v].map(f64::to_bits)) {
                found.push((segment, mesh.points[v]));
            }
        }
    }
    found
}

/// `o2`: six nodes per triangle; nodes 4, 5, 6 lie exactly at the midpoints (`0.5 · (p + q)` per
/// coordinate) of the edges opposite corners 1, 2, 3; every edge of the mesh has one midpoint
/// node, shared by the triangles on both sides, which is no corner and no other edge's; every
/// output point is a corner, a midpoint, or an input vertex left out of the mesh (`input_count`
/// input vertices come first); the midpoint of edge a-b has the marker `edge_marker(a, b)` (when
/// markers are written). Returns the number of midpoint nodes.
pub fn check_second_order(
    mesh: &MeshView<'_>,
    input_count: usize,
    edge_marker: &dyn Fn(usize, usize) -> i32,
) -> Result<usize, String> {
    let out = mesh.out;
    if out.counts.corners != 6 {
        return Err(format!(
            "{} corners per triangle, not 6",
            out.counts.corners
        ));
    }
    let nodes = out.triangles.as_deref().unwrap_or_default();
    let base = out.base as usize;
    let mut midpoint_of: HashMap<[usize; 2], usize> = HashMap::new();
    let mut edge_of: HashMap<usize, [usize; 2]> = HashMap::new();
    for (t, row) in nodes.chunks_exact(6).enumerate() {
        let row: Vec<usize> = row
            .iter()
            .map(|&v| (v as usize).wrapping_sub(base))
            .collect();
        if row.iter().any(|&v| v >= mesh.points.len()) {
            return Err(format!("triangle {t} {row:?} has a node out of range"));
        }
        for k in 0..3 {
            let (a, b, m) = (row[(k + 1) % 3], row[(k + 2) % 3], row[3 + k]);
            let (p, q) = (mesh.points[a], mesh.points[b]);
            let expected = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            if mesh.points[m] != expected {
                return Err(format!(
                    "triangle {t} {row:?}: node {} is at {:?}, not at the midpoint {expected:?} of the edge opposite corner {}",
                    4 + k,
                    mesh.points[m],
                    k + 1
                ));
            }
            let edge = [a.min(b), a.max(b)];
            if *midpoint_of.entry(edge).or_insert(m) != m {
                return Err(format!(
                    "edge {edge:?} has two midpoint nodes, {} and {m}",
                    midpoint_of[&edge]
                ));
            }
            if *edge_of.entry(m).or_insert(edge) != edge {
                return Err(format!(
                    "node {m} is the midpoint of edges {:?} and {edge:?}",
                    edge_of[&m]
                ));
            }
        }
    }
    let edge_count = mesh
        .edges
        .keys()
        .filter(|&&(a, b)| a < b || !mesh.edges.contains_key(&(b, a)))
        .count();
    if midpoint_of.len() != edge_count {
        return Err(format!(
            "{} midpoint nodes for {edge_count} edges",
            midpoint_of.len()
        ));
    }
    for (&m, edge) in &edge_of {
        if mesh.in_mesh[m] {
            return Err(format!(
                "the midpoint node {m} of edge {edge:?} is a corner too"
            ));
        }
        if let Some(markers) = &out.point_markers {
            let expected = edge_marker(edge[0], edge[1]);
            if markers[m] != expected {
                return Err(format!(
                    "the midpoint node {m} of edge {edge:?}: marker {}, expected {expected}",
                    markers[m]
                ));
            }
        }
    }
    for v in 0..mesh.points.len() {
        if !mesh.in_mesh[v] && !edge_of.contains_key(&v) && v >= input_count {
            return Err(format!(
                "output point {v} {:?} is neither a corner, a midpoint nor an input vertex",
                mesh.points[v]
            ));
        }
    }
    Ok(midpoint_of.len())
}
