//! The driver: checks the input, runs the algorithms that the options ask for and assembles the
//! [`Output`] and [`VoronoiOutput`].

use crate::algorithms::constrain::Constrainer;
use crate::algorithms::delaunay::{self, merge, order, InInsertionOrder, Inserter, Triangulation};
use crate::algorithms::domain::{carve, Domain};
use crate::algorithms::reconstruct::reconstruct;
use crate::algorithms::refine::{builtin_unsuitable, refine, CallerGrid, Quality};
use crate::assemble::{self, LaterCopy};
use crate::data::{Hooks, Input, Output, Phase, UnsuitableFn, VoronoiOutput};
use crate::error::Error;
use crate::geometry::{Exact, Inexact, Point, Predicates};
use crate::mesh::{Mesh, VertexId, NONE, OUTSIDE};
use crate::options::{Algorithm, Options};
use crate::scaling::Scaling;

mod checks; // the switches and input before any work, the finished mesh after (`C`)
mod outputs; // the outputs of the finished mesh, in the caller's units

use checks::{check_indices_and_seeds, check_mesh, check_supported, checked_points};

/// Seed of the randomized insertion order (`i`): fixed, so results are reproducible.
const BRIO_SEED: u64 = 0x7269_616E_676C_6521;

/// The Delaunay triangulation of the points, in the caller's numbers; with `in_insertion_order`,
/// when it is built on one thread, numbered in insertion order with the caller's numbers and
/// points beside it (the plain outputs rename as they write).
fn delaunay_with<P: Predicates>(
    options: &Options,
    points: Vec<Point>,
    in_insertion_order: bool,
) -> Delaunay {
    let kind = match options.algorithm {
        Algorithm::Incremental => order::OrderKind::Brio(BRIO_SEED),
        Algorithm::Default | Algorithm::Sweepline => order::OrderKind::Multiscale,
    };
    let mut points = points;
    let two_cores = crate::threads::two_cores();
    if kind == order::OrderKind::Multiscale
        && two_cores
        && points.len() >= merge::PARALLEL_THRESHOLD
    {
        match merge::triangulate_two_halves::<P>(points) {
            Ok(triangulation) => return Delaunay::Renamed(triangulation),
            Err(given_back) => points = given_back,
        }
    }
    let built = delaunay::triangulate_ordered::<P>(delaunay::order_in_room(&points, kind, 0));
    if in_insertion_order {
        Delaunay::InInsertionOrder(built, points)
    } else {
        Delaunay::Renamed(built.into_caller_numbers(points))
    }
}

/// What [`delaunay_with`] gives.
enum Delaunay {
    /// Numbered as the caller's points.
    Renamed(Triangulation),
    /// Numbered in insertion order, with the caller's points.
    InInsertionOrder(InInsertionOrder, Vec<Point>),
}

struct ScaledInput {
    options: Options,
    points: Vec<Point>,
    holes: Vec<f64>,
    regions: Vec<f64>,
    triangle_areas: Option<Vec<f64>>,
}

impl ScaledInput {
    fn new(scaling: Scaling, options: &Options, input: &Input<'_>, mut points: Vec<Point>) -> Self {
        let mut options = options.clone();
        options.max_area = options.max_area.map(|a| scaling.scale_area(a));
        // `limit` bounds the hole and region points alone: without them no scan is needed.
        let mut limit: f64 = 1.0;
        let has_seeds = !(input.holes.is_empty() && input.regions.is_empty());
        if scaling.is_identity() && has_seeds {
            // Finite coordinates: a plain comparison finds the largest magnitude.
            for &x in points.as_flattened() {
                let magnitude = x.abs();
                if magnitude > limit {
                    limit = magnitude;
                }
            }
        } else if !scaling.is_identity() {
            for p in &mut points {
                *p = scaling.to_engine(*p);
                limit = limit.max(p[0].abs()).max(p[1].abs());
            }
        }
        // Beyond every vertex coordinate (a power of two times `limit` is exact).
        limit *= 4.0;
        let seed = |x: f64, y: f64| scaling.seed_to_engine([x, y], limit);
        let holes = input
            .holes
            .chunks_exact(2)
            .flat_map(|h| seed(h[0], h[1]))
            .collect();
        let regions = input
            .regions
            .chunks_exact(4)
            .flat_map(|r| {
                let [x, y] = seed(r[0], r[1]);
                [x, y, r[2], scaling.scale_area(r[3])]
            })
            .collect();
        let triangle_areas = input
            .triangle_areas
            .map(|areas| areas.iter().map(|&a| scaling.scale_area(a)).collect());
        ScaledInput {
            options,
            points,
            holes,
            regions,
            triangle_areas,
        }
    }

    /// `input` with the scaled arrays in place of the caller's (the vertices stay the caller's:
    /// the engine gets the scaled ones separately, and the outputs give these back).
    fn view<'a>(&'a self, input: &Input<'a>) -> Input<'a> {
        Input {
            holes: &self.holes,
            regions: &self.regions,
            triangle_areas: self.triangle_areas.as_deref(),
            ..*input
        }
    }
}

/// Triangulates `input` as the switches in `options` ask. The safe entry point of the engine:
/// the C ABI, the command-line program and Rust callers all come through here. A failed internal
/// invariant is an [`Error::Internal`], not a panic: the algorithms report the ones they check,
/// and any other panic (an index out of range: a bug) is caught here when panics unwind.
///
/// Refinement runs in a frame translated to a local origin where that is exact (see
/// [`crate::scaling`] and [`Frame`]); where rounding its new vertices onto the caller's grid
/// would invert a triangle (refinement went below the caller's rounding), it runs again with
/// its new points on that grid from the start, and failing that (a crossing of segments closer
/// to a vertex than the rounding), in the caller's own frame.
pub fn triangulate(
    options: &Options,
    input: &Input<'_>,
    hooks: &Hooks<'_>,
) -> Result<(Output, VoronoiOutput), Error> {
    check_supported(options)?;
    let mut frame = if options.quality() {
        Frame::Translated
    } else {
        Frame::Caller
    };
    loop {
        if let Some(result) = triangulate_in_frame(options, input, hooks, frame)? {
            return Ok(result);
        }
        frame = match frame {
            Frame::Translated => Frame::TranslatedOnGrid,
            Frame::TranslatedOnGrid => Frame::Caller,
            Frame::Caller => {
                return Err(Error::Internal(
                    "the caller's frame was spoiled by rounding".into(),
                ))
            }
        };
    }
}

/// Where a run meshes (see [`triangulate`]).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Frame {
    /// Translated to a local origin where that is exact: the mesh of the input translated
    /// there, refined, moved onto the caller's grid and refined again on it.
    Translated,
    /// Translated, with the refinement's new points on the caller's grid from the start.
    TranslatedOnGrid,
    /// The caller's own coordinates (still scaled by a power of two where their magnitude
    /// asks for it).
    Caller,
}

/// [`triangulate`] in `frame` (the caller's when no local origin is exact); `None` when
/// rounding onto the caller's grid spoils a translated frame's mesh.
// Out of line: inlined into `triangulate`'s loop over frames, the optimised code tests bytes
// of the options' `None` payloads (uninitialised, from `Options::parse`) that it then ignores,
// which valgrind reports as a jump on uninitialised memory in the C tests.
#[inline(never)]
fn triangulate_in_frame(
    options: &Options,
    input: &Input<'_>,
    hooks: &Hooks<'_>,
    frame: Frame,
) -> Result<Option<(Output, VoronoiOutput)>, Error> {
    let (points, magnitudes) = checked_points(input)?;
    check_indices_and_seeds(options, input)?;
    let translate = frame != Frame::Caller;
    let scaling = Scaling::for_screened_points(&points, magnitudes, translate)?;
    let mut scaled = ScaledInput::new(scaling, options, input, points);
    let points = std::mem::take(&mut scaled.points);
    let options = &scaled.options;
    let input = scaled.view(input);
    // `u` with no test registered: Triangle's built-in one (see `builtin_unsuitable`), which
    // like a registered test sees the caller's coordinates.
    let registered = hooks.unsuitable.or_else(|| {
        options
            .user_test
            .then_some(&builtin_unsuitable as &UnsuitableFn<'_>)
    });
    let user_test = registered.map(|test| scaling.unscaled_test(test));
    let hooks = Hooks {
        unsuitable: user_test.as_ref().map(|t| t as &UnsuitableFn<'_>),
        ..*hooks
    };
    // AssertUnwindSafe: after a panic nothing of the run is used again; the caller's data is
    // only read, and the user test is called, never kept.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        if options.no_exact {
            run::<Inexact>(options, &input, &hooks, points, (scaling, frame))
        } else {
            run::<Exact>(options, &input, &hooks, points, (scaling, frame))
        }
    }))
    .unwrap_or_else(|panic| Err(Error::from_panic(panic)))
}

/// The mesh after every algorithm ran, with what the outputs need to know about it.
struct Meshed {
    mesh: Mesh,
    /// Per vertex (input vertices first, then new ones).
    point_attributes: Vec<f64>,
    point_markers: Vec<i32>,
    /// Per segment id (input segments, then the hull segments of `c`).
    segment_markers: Vec<i32>,
    /// Later copies of segments that gave them their markers (see [`LaterCopy`]).
    later_copies: Vec<LaterCopy>,
    domain: Domain,
    uses_segments: bool,
}

fn run<P: Predicates>(
    options: &Options,
    input: &Input<'_>,
    hooks: &Hooks<'_>,
    points: Vec<Point>,
    (scaling, frame): (Scaling, Frame),
) -> Result<Option<(Output, VoronoiOutput)>, Error> {
    let n = points.len();
    let mut output = Output::default();
    let base = options.first_index();
    hooks.report(Phase::Delaunay, 0, n as u64);
    // The starting mesh: the given triangles (`r`), or the Delaunay triangulation of the points.
    // A plain Delaunay triangulation in the caller's units: its outputs are built from the mesh
    // in place (scaled coordinates go through `write_outputs`, which gives them back unscaled).
    let plain = !options.refine && scaling.is_identity() && assemble::plain_delaunay(options);
    let (mut mesh, duplicates, names) = if options.refine {
        let mesh = reconstruct::<P>(points, input.triangles, input.corners, base)?;
        (mesh, Vec::new(), None)
    } else {
        let (Triangulation { mesh, duplicates }, names) =
            match delaunay_with::<P>(options, points, plain) {
                Delaunay::Renamed(triangulation) => (triangulation, None),
                Delaunay::InInsertionOrder(built, points) => {
                    (built.triangulation, Some((built.names, points)))
                }
            };
        for &(v, u) in &duplicates {
            let v = v as usize;
            // The caller's coordinates (`input.points` are not scaled).
            output.warnings.push(format!(
                "A duplicate vertex at ({}, {}) appeared and was ignored (vertex {} duplicates vertex {}).",
                input.points[2 * v],
                input.points[2 * v + 1],
                v as i32 + base,
                u as i32 + base
            ));
        }
        (mesh, duplicates, names)
    };
    hooks.report(Phase::Delaunay, n as u64, n as u64);
    if plain && mesh.triangle_count() > 0 {
        let slots = mesh.triangle_count();
        return Ok(Some(output_phase(hooks, slots, || {
            assemble::delaunay_outputs(options, input, mesh, names, output)
        })));
    }
    if let Some((names, points)) = names {
        // No triangle: the general path, in the caller's numbers.
        mesh.rename_vertices(|v| VertexId::new(names[v.index()]));
        drop(mesh.replace_points(points));
    }
    let k = input.point_attribute_count;
    let mut meshed = Meshed {
        point_attributes: input.point_attributes.to_vec(),
        point_markers: input
            .point_markers
            .map_or_else(|| vec![0; n], <[i32]>::to_vec),
        segment_markers: Vec::new(),
        later_copies: Vec::new(),
        domain: Domain::default(),
        uses_segments: options.uses_segments(),
        mesh,
    };
    let degenerate = meshed.mesh.triangle_count() == 0;
    if !degenerate && (options.pslg || options.convex_hull || options.quality() || options.refine) {
        let mut cdt = Constrainer::new(Inserter::<P>::new(std::mem::take(&mut meshed.mesh)));
        cdt.split_segments = options.split_segments;
        if options.pslg {
            // Per vertex: the copy in the mesh of a duplicate, NONE for the others.
            let mut duplicate_of = vec![NONE; n];
            for &(v, u) in &duplicates {
                duplicate_of[v as usize] = u;
            }
            meshed.later_copies = insert_segments(
                &mut cdt,
                input,
                &duplicate_of,
                base,
                hooks,
                &mut output.warnings,
            )?;
        }
        if options.convex_hull || options.refine || !options.pslg {
            // `c`, the boundary of a mesh being refined (`r`), or refinement of a point set: the
            // boundary edges are segments (marker 1).
            cdt.mark_hull(1);
        }
        for c in &cdt.crossings {
            // New vertices where segments cross: attributes interpolated along the crossed one.
            let (from, to) = (c.from.index() * k, c.to.index() * k);
            for i in 0..k {
                let (a, b) = (
                    meshed.point_attributes[from + i],
                    meshed.point_attributes[to + i],
                );
                meshed.point_attributes.push(a + c.t * (b - a));
            }
        }
        let holes: &[f64] = if options.ignore_holes {
            &[]
        } else {
            input.holes
        };
        meshed.domain = if options.refine {
            let areas = if options.variable_area {
                input.triangle_areas
            } else {
                None
            };
            Domain::per_triangle(
                cdt.mesh_mut(),
                input.triangle_count(),
                input.triangle_attributes,
                areas,
            )
        } else if options.pslg {
            carve(&mut cdt, options.convex_hull, holes, input.regions)
        } else {
            Domain::whole(cdt.mesh_mut())
        };
        if options.quality() {
            if options.pslg && !options.refine {
                // Refinement works inside the domain only: the eaten triangles go, and ghosts
                // cover the domain's boundary (made of segments), as after `r`. Left in place,
                // slivers outside could not be split with a boundary segment without inverting.
                let tag = cdt.mesh().tags().to_vec();
                cdt.retain_triangles(|t| tag[t.index()] != OUTSIDE);
            }
            let quality = Quality {
                min_angle: options.min_angle,
                max_area: options.max_area,
                variable_area: options.variable_area,
                user_test: if options.user_test {
                    hooks.unsuitable
                } else {
                    None
                },
                no_steiner_on_segments: options.no_steiner_on_segments,
                max_steiner: options.max_steiner,
                reduce: options.reduce,
                // Per-triangle bounds (`r` with `a`) vary from triangle to triangle: no lattice.
                area_lattice: !(options.refine && options.variable_area),
                cancel: hooks.cancel,
                progress: hooks.progress,
                caller_grid: scaling.translates().then_some(CallerGrid {
                    grid: &scaling,
                    from_the_start: frame == Frame::TranslatedOnGrid,
                }),
            };
            hooks.report(Phase::Refinement, 0, 0);
            let report = refine(
                &mut cdt,
                &meshed.domain,
                &quality,
                options.conforming_delaunay,
                &mut meshed.point_attributes,
                k,
            );
            hooks.report(Phase::Refinement, report.work, report.work);
            if report.off_grid {
                return Ok(None); // meshed again in the caller's frame
            }
            output
                .warnings
                .extend(report.warnings.iter().map(ToString::to_string));
        }
        // New vertices (crossings, Steiner points) onto the caller's grid: the outputs give
        // them back exactly (refinement in a translated frame did so already).
        if !scaling.is_identity() && !cdt.move_onto_grid(&scaling) {
            if scaling.translates() {
                return Ok(None);
            }
            return Err(Error::CoordinateRange(
                "The mesh needs new vertices closer together than floating-point numbers can be at the \
                 magnitude of these coordinates (below the smallest normal number, 2^-1022): given back \
                 in the caller's units they would invert a triangle. Scale the input up."
                    .into(),
            ));
        }
        meshed.segment_markers = std::mem::take(&mut cdt.markers);
        meshed.mesh = cdt.into_mesh();
        // New vertices (crossings, Steiner points) have no input marker.
        meshed
            .point_markers
            .resize(meshed.mesh.vertex_count() as usize, 0);
    } else {
        meshed.domain = Domain::whole(&mut meshed.mesh);
    }
    if options.check {
        let check = check_mesh::<P>(&meshed);
        output.warnings.extend(check.warning());
        output.mesh_check = Some(check);
    }
    if options.pslg && !options.output.no_poly_output {
        output.alias_holes_and_regions = true;
        output.hole_count = input.hole_count();
        output.region_count = input.region_count();
    }
    let slots = meshed.mesh.triangle_count();
    output_phase(hooks, slots, || {
        outputs::write_outputs(options, input, meshed, output, scaling)
    })
    .map(Some)
}

/// Builds the outputs of a mesh of `slots` triangle slots, reporting the output phase.
fn output_phase<T>(hooks: &Hooks<'_>, slots: u32, build: impl FnOnce() -> T) -> T {
    hooks.report(Phase::Output, 0, u64::from(slots));
    let outputs = build();
    hooks.report(Phase::Output, u64::from(slots), u64::from(slots));
    outputs
}

/// Inserts the input segments (skipping those whose two endpoints are one vertex, with a warning).
/// A segment given again (the same two vertices, either way round) is inserted once: a second
/// insertion would find the first one's chain, which `s` builds from midpoints that rounding
/// may put an ulp off the line, so that the second copy would cross it at slivers; where markers
/// differ, a later non-zero marker replaces a zero one, as for overlapping segments, and the
/// copies that did so are returned for the vertex markers ([`LaterCopy`]).
fn insert_segments<P: Predicates>(
    cdt: &mut Constrainer<P>,
    input: &Input<'_>,
    duplicate_of: &[u32],
    base: i32,
    hooks: &Hooks<'_>,
    warnings: &mut Vec<String>,
) -> Result<Vec<LaterCopy>, Error> {
    let m = (input.segments.len() / 2) as u64;
    let mut later_copies = Vec::new();
    hooks.report(Phase::Segments, 0, m);
    // A duplicate vertex is not in the triangulation: use the copy that is. In range:
    // `check_indices_and_seeds` refused the input otherwise.
    let ends = |i: usize| {
        [input.segments[2 * i], input.segments[2 * i + 1]].map(|v| {
            let v = (v - base) as u32;
            if duplicate_of[v as usize] == NONE {
                v
            } else {
                duplicate_of[v as usize]
            }
        })
    };
    let mut copy_of = first_copies(m as usize, duplicate_of.len(), ends);
    cdt.reserve_segments(m as usize);
    for i in 0..m as usize {
        let marker = input.segment_markers.map_or(0, |m| m[i]);
        let [a, b] = ends(i);
        if a == b {
            let s = &input.segments[2 * i..2 * i + 2];
            warnings.push(format!(
                "Endpoints of segment {} are coincident ({} {}); the segment was skipped.",
                i as i32 + base,
                s[0],
                s[1]
            ));
            continue;
        }
        if copy_of[i] != NONE {
            // The first copy was inserted before this one: its id is in its entry.
            let id = copy_of[(copy_of[i] & !COPY) as usize];
            if cdt.markers[id as usize] == 0 && marker != 0 {
                cdt.markers[id as usize] = marker;
                let order =
                    (((cdt.markers.len() - 1) as u64) << 32) | (later_copies.len() as u64 + 1);
                later_copies.push(LaterCopy { id, order, marker });
            }
            continue;
        }
        let id = cdt.new_segment_id(marker, VertexId::new(a), VertexId::new(b));
        copy_of[i] = id;
        cdt.insert_segment(VertexId::new(a), VertexId::new(b), id)?;
        if i % 4096 == 4095 {
            hooks.report(Phase::Segments, i as u64 + 1, m);
        }
    }
    hooks.report(Phase::Segments, m, m);
    Ok(later_copies)
}

/// The mark of a later copy in [`first_copies`]' answer.
const COPY: u32 = 1 << 31;

/// Per segment `i` of `count` (ends `ends(i)`, vertices below `vertex_count`): `COPY | j` when
/// an earlier segment `j` joins the same two vertices (either way round; `j` the first such),
/// else `NONE` (which the caller overwrites with a first copy's segment id once inserted).
/// Found by bucketing the segments by their smaller end (a counting sort: two passes over the
/// segments, a few bytes per vertex and segment, where a hash table of the pairs cost 2% of a
/// constrained triangulation of 10^5 segments in its inserts and page faults); the segments of
/// one bucket are in input order, compared pairwise, or sorted by their other end when a vertex
/// has many.
fn first_copies(count: usize, vertex_count: usize, ends: impl Fn(usize) -> [u32; 2]) -> Vec<u32> {
    /// Above this many segments at one vertex, its bucket is sorted rather than compared
    /// pairwise.
    const PAIRWISE: usize = 16;
    let mut copy_of = vec![NONE; count];
    if count < 2 || count > COPY as usize {
        return copy_of;
    }
    let smaller = |i: usize| {
        let [a, b] = ends(i);
        a.min(b) as usize
    };
    let mut start = vec![0u32; vertex_count + 1];
    for i in 0..count {
        start[smaller(i) + 1] += 1;
    }
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    // Filled bucket by bucket in input order; `start[v]` advances to the end of bucket `v`,
    // which is where bucket `v + 1` starts.
    let mut by_vertex = vec![0u32; count];
    for i in 0..count {
        let slot = &mut start[smaller(i)];
        by_vertex[*slot as usize] = i as u32;
        *slot += 1;
    }
    let larger = |i: u32| {
        let [a, b] = ends(i as usize);
        a.max(b)
    };
    let mut bucket_start = 0;
    for v in 0..vertex_count {
        let bucket = &mut by_vertex[bucket_start..start[v] as usize];
        bucket_start = start[v] as usize;
        if bucket.len() <= PAIRWISE {
            for (k, &i) in bucket.iter().enumerate() {
                if let Some(&j) = bucket[..k].iter().find(|&&j| larger(j) == larger(i)) {
                    // `j` is the first earlier one with these ends: it is no copy itself.
                    copy_of[i as usize] = COPY | j;
                }
            }
        } else {
            bucket.sort_unstable_by_key(|&i| (larger(i), i));
            for pair in bucket.windows(2) {
                if larger(pair[0]) == larger(pair[1]) {
                    let first = copy_of[pair[0] as usize];
                    copy_of[pair[1] as usize] = if first == NONE { COPY | pair[0] } else { first };
                }
            }
        }
    }
    copy_of
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::MeshCheck;
    use crate::options::SwitchSource;

    /// `first_copies` against the quadratic definition, on random segments over few vertices
    /// (many copies, both ways round, and buckets above the pairwise limit).
    #[test]
    fn first_copies_are_the_first_earlier_segments_with_the_same_ends() {
        let mut state = 5u64;
        for (count, vertices) in [(0, 1), (1, 2), (40, 6), (300, 12), (3000, 40), (500, 3)] {
            let segments: Vec<[u32; 2]> = (0..count)
                .map(|_| [0, 1].map(|_| (order::splitmix64(&mut state) % vertices as u64) as u32))
                .collect();
            let same = |s: [u32; 2], t: [u32; 2]| s == t || s == [t[1], t[0]];
            let expected: Vec<u32> = (0..count)
                .map(|i| {
                    (0..i)
                        .find(|&j| same(segments[j], segments[i]))
                        .map_or(NONE, |j| COPY | j as u32)
                })
                .collect();
            assert_eq!(
                first_copies(count, vertices, |i| segments[i]),
                expected,
                "{count} segments over {vertices} vertices"
            );
        }
    }

    /// The plain outputs (renamed from insertion order as they are written) are the general
    /// path's: triangles, hull markers, counts and duplicate warnings, with copies of points
    /// before and after the first one, for both insertion orders and both first indices.
    #[test]
    fn plain_outputs_match_the_general_path() {
        let mut state = 17u64;
        let mut points: Vec<f64> = (0..2 * 3000)
            .map(|_| (order::splitmix64(&mut state) % 1_000_000) as f64 * 1e-6)
            .collect();
        // 100, 7 and 8 at one position (the copy in the middle inserted first, or not).
        for (from, to) in [(10, 2999), (2500, 3), (100, 7), (7, 8)] {
            points[2 * to] = points[2 * from];
            points[2 * to + 1] = points[2 * from + 1];
        }
        let input = Input {
            points: &points,
            ..Input::default()
        };
        let canonical = |output: &Output| {
            let mut triangles: Vec<[i32; 3]> = output
                .triangles
                .as_ref()
                .expect("triangles")
                .chunks_exact(3)
                .map(|t| {
                    let k = (0..3).min_by_key(|&i| t[i]).unwrap();
                    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
                })
                .collect();
            triangles.sort_unstable();
            triangles
        };
        for switches in ["Q", "Qz", "Qi", "Qzi"] {
            let run = |switches: &str| {
                let options = Options::parse(switches, SwitchSource::Library).expect("switches");
                triangulate(&options, &input, &Hooks::default())
                    .expect("triangulated")
                    .0
            };
            let plain = run(switches);
            // Edges are not among the plain outputs: this run takes the general path.
            let general = run(&format!("{switches}e"));
            assert_eq!(canonical(&plain), canonical(&general), "{switches}");
            assert_eq!(plain.point_markers, general.point_markers, "{switches}");
            assert_eq!(plain.points, general.points, "{switches}");
            assert_eq!(plain.warnings, general.warnings, "{switches}");
            assert_eq!(plain.warnings.len(), 4, "{switches}");
            assert_eq!(
                (plain.triangle_count, plain.edge_count, plain.segment_count),
                (
                    general.triangle_count,
                    general.edge_count,
                    general.segment_count
                ),
                "{switches}"
            );
        }
    }

    /// `C` on a mesh that passes: a result, not a warning (other warnings stay).
    #[test]
    fn a_passing_mesh_check_is_no_warning() {
        let points = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.3, 0.4, 0.3, 0.4];
        let segments = [1, 2, 2, 3, 3, 4, 4, 1];
        let input = Input {
            points: &points,
            segments: &segments,
            ..Input::default()
        };
        for switches in ["QC", "QCe", "QpC", "QpqC", "QcCV"] {
            let options = Options::parse(switches, SwitchSource::Library).expect("switches");
            let output = triangulate(&options, &input, &Hooks::default())
                .expect("triangulated")
                .0;
            assert_eq!(output.mesh_check, Some(MeshCheck::Passed), "{switches}");
            // The duplicate of vertex 5 is the only warning.
            assert_eq!(
                output.warnings.len(),
                1,
                "{switches}: {:?}",
                output.warnings
            );
            assert!(output.warnings[0].contains("duplicate"), "{switches}");
        }
        let options = Options::parse("Q", SwitchSource::Library).expect("switches");
        let output = triangulate(&options, &input, &Hooks::default()).expect("triangulated");
        assert_eq!(output.0.mesh_check, None, "no check without C");
    }
}
