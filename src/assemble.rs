//! From a finished mesh to Triangle's outputs: numbering (1-based unless `z`, `j` renumbering),
//! boundary markers, triangles, neighbours, segments and edges, in the flat layouts of
//! [`Output`].
//!
//! Marker rules (Triangle's documentation): a vertex gets its input marker if non-zero, else the
//! marker of a non-zero segment it lies on, else 1 on a boundary, else 0; a segment or edge gets its
//! segment's marker, else 1 on a boundary, else 0.

use crate::data::{Input, Output, VoronoiOutput};
use crate::geometry::Point;
use crate::mesh::raw::{triangle_of, RawMesh, GHOST};
use crate::mesh::{Mesh, TriangleId, NONE};
use crate::options::Options;

/// Whether the outputs of a Delaunay triangulation of the input points can be built by
/// [`delaunay_outputs`]: no segments, no refinement and no output that needs edges, neighbours,
/// a renumbering or the checked mesh.
pub fn plain_delaunay(options: &Options) -> bool {
    !(options.uses_segments()
        || options.output.edges
        || options.output.neighbors
        || options.output.voronoi
        || options.second_order
        || options.jettison
        || options.check)
}

/// The outputs of a Delaunay triangulation (with [`plain_delaunay`] options and at least one
/// triangle), built from the mesh it consumes: what [`FinishedMesh::write`] gives for it,
/// without the per-triangle tags and lists that the general path needs, and in place: the
/// output triangles are the real triangles' corners compacted in the corner array (the twins
/// are freed first), and the output points are the mesh's points. This keeps the peak memory of
/// a large triangulation to the mesh and the output markers.
///
/// Every edge of the mesh's hull has one ghost triangle across it, so with `T` real
/// triangles and `h` ghosts there are `(3T + h) / 2` edges and `h` boundary edges, which
/// Triangle counts as segments, and the hull vertices are the ghosts' finite corners.
///
/// With `names` (the caller's number of each vertex of the mesh, and the caller's points), the
/// mesh is numbered otherwise (in insertion order) and the corners are renamed as they are
/// written: one pass over the corner array for both.
pub fn delaunay_outputs(
    options: &Options,
    input: &Input<'_>,
    mesh: Mesh,
    names: Option<(Vec<u32>, Vec<Point>)>,
    mut output: Output,
) -> (Output, VoronoiOutput) {
    let n = mesh.vertex_count() as usize;
    let k = input.point_attribute_count;
    let write_nodes = !options.output.no_node_output;
    let mut markers = (write_nodes && !options.output.no_boundary_markers).then(|| {
        input
            .point_markers
            .map_or_else(|| vec![0; n], <[i32]>::to_vec)
    });
    // The ghosts found by walking their ring (a valid mesh with a triangle has one; else by
    // a scan), the real triangles between them are moved down run by run: no test per
    // triangle, and the triangles keep their order (that of the general outputs, so that a
    // scaled input lists the same triangles).
    let ghosts = mesh
        .ghost_ring()
        .unwrap_or_else(|| mesh.triangles().filter(|&t| mesh.is_ghost(t)).collect());
    let parts = mesh.into_corners_and_points();
    let (mut corners, mut points) = (parts.corners, Some(parts.points));
    let names = names.map(|(names, caller_points)| {
        drop(points.replace(caller_points));
        names
    });
    let (kept, ghosts) = compact(
        &mut corners,
        ghosts,
        options,
        &mut markers,
        names.as_deref(),
    );
    corners.truncate(kept);
    let triangle_count = kept / 3;
    output.point_count = n;
    output.point_attribute_count = k;
    if write_nodes {
        output.points = points.take().map(Vec::into_flattened);
        if k > 0 {
            output.point_attributes = Some(input.point_attributes.to_vec());
        }
        output.point_markers = markers;
    }
    output.triangle_count = triangle_count;
    output.corners = 3;
    if !options.output.no_element_output {
        output.triangles = Some(into_i32(corners));
    }
    output.edge_count = (3 * triangle_count + ghosts) / 2;
    output.segment_count = ghosts;
    let voronoi = VoronoiOutput {
        point_count: triangle_count,
        point_attribute_count: k,
        edge_count: output.edge_count,
        diagram: None,
    };
    (output, voronoi)
}

/// Compacts the real triangles' corners to the front of `corners`, the `ghosts` (each once)
/// left out: the runs of real triangles between ghost slots are moved down whole (in place:
/// written at or before the slot being read), each corner `v` written as `names[v]` (or `v`
/// without names) plus the first index — plain copies without names and with the first index
/// 0, as after the two-core merge with `z` — without a test per triangle. Marks the boundary
/// vertices (the ghosts' finite corners) without an input marker with 1. Returns the number of
/// corners kept and the number of ghosts.
fn compact(
    corners: &mut [u32],
    ghosts: Vec<TriangleId>,
    options: &Options,
    markers: &mut Option<Vec<i32>>,
    names: Option<&[u32]>,
) -> (usize, usize) {
    let name = |v: u32| names.map_or(v, |names| names[v as usize]);
    let ghosts = in_slot_order(ghosts, corners.len() / 3);
    if let Some(markers) = markers.as_mut() {
        for &g in &ghosts {
            for &v in &corners[3 * g..3 * g + 3] {
                if v != GHOST && markers[name(v) as usize] == 0 {
                    markers[name(v) as usize] = 1;
                }
            }
        }
    }
    let base = options.first_index();
    let mut kept = 0;
    let mut run_start = 0;
    for end in ghosts.iter().copied().chain([corners.len() / 3]) {
        let run = 3 * run_start..3 * end;
        let len = run.len();
        // Forward, in place: each corner is written `down` slots before the one read.
        let down = 3 * run_start - kept;
        match names {
            Some(names) => {
                for i in run {
                    corners[i - down] = names[corners[i] as usize].wrapping_add_signed(base);
                }
            }
            None if base != 0 => {
                for i in run {
                    corners[i - down] = corners[i].wrapping_add_signed(base);
                }
            }
            None => corners.copy_within(run, kept),
        }
        kept += len;
        run_start = end + 1;
    }
    (kept, ghosts.len())
}

/// The slots of `ghosts` (distinct, below `slots`) in increasing order, by a bitmap of the
/// slots rather than a sort: where every vertex is on the hull (points on a circle's arc) the
/// ghosts are half the triangles, and sorting them took half the output's time.
fn in_slot_order(ghosts: Vec<TriangleId>, slots: usize) -> Vec<usize> {
    let mut bitmap = vec![0u64; slots.div_ceil(64)];
    for g in &ghosts {
        bitmap[g.index() / 64] |= 1 << (g.index() % 64);
    }
    let mut sorted = Vec::with_capacity(ghosts.len());
    for (i, &word) in bitmap.iter().enumerate() {
        let mut word = word;
        while word != 0 {
            sorted.push(64 * i + word.trailing_zeros() as usize);
            word &= word - 1;
        }
    }
    debug_assert_eq!(sorted.len(), ghosts.len(), "ghosts are distinct");
    sorted
}

/// The same array as `i32` values (vertex numbers below 2^31 keep their value), without a pass
/// over it: the allocation changes hands.
fn into_i32(values: Vec<u32>) -> Vec<i32> {
    let mut values = std::mem::ManuallyDrop::new(values);
    let (ptr, len, capacity) = (values.as_mut_ptr(), values.len(), values.capacity());
    // SAFETY: `u32` and `i32` have the same size and alignment, so the allocation (made for
    // `capacity` `u32`s by the global allocator, no longer owned by `values`) is one for
    // `capacity` `i32`s; its first `len` items are initialized, and every bit pattern is an i32.
    unsafe { Vec::from_raw_parts(ptr.cast::<i32>(), len, capacity) }
}

/// A later copy of segment `id` (the same two vertices) whose non-zero marker replaced the
/// first copy's zero. Triangle marks vertices while it inserts segments in input order, each
/// vertex keeping the first non-zero marker it gets: the copy's marker counts at the copy's
/// place in that order, not at the first copy's. `order` places it: segment id `i` is at
/// `i << 32`, a copy given after `count` ids at `(count − 1) << 32 | k` for the `k`-th such
/// copy (from 1), so that copies given between the same two segments keep their order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaterCopy {
    pub id: u32,
    pub order: u64,
    pub marker: i32,
}

/// A finished mesh with the per-vertex and per-edge facts the outputs need.
pub struct FinishedMesh<'a> {
    pub mesh: &'a Mesh,
    /// The caller moves the mesh's points in as the output points after the other outputs
    /// ([`Mesh::take_points`]): [`Self::write`] leaves them out. Only without jettisoned
    /// vertices (every vertex keeps its index).
    pub points_moved_in_later: bool,
    /// `point_attribute_count` values per vertex.
    pub point_attributes: &'a [f64],
    pub point_attribute_count: usize,
    /// The caller's marker per vertex (0 where none was given).
    pub input_point_markers: &'a [i32],
    /// All vertices lie on one line (no triangle): every vertex counts as on the hull.
    pub all_collinear: bool,
    /// Per vertex: whether it is a corner of an output triangle (`j` drops the others). Only
    /// read with `j`; may be empty otherwise.
    pub vertex_in_mesh: &'a [bool],
    /// Per triangle slot: whether the triangle is part of the output (real and not deleted).
    pub triangle_in_mesh: &'a [bool],
    /// The marker of each segment id of [`Mesh::segment`]; `None` when no segments are tracked.
    pub segment_markers: Option<&'a [i32]>,
    /// The later copies of segments that gave them their markers, in input order.
    pub later_copies: &'a [LaterCopy],
    /// Whether segments take part (Triangle's `usesegments`); without them `numberofsegments`
    /// counts the boundary (hull) edges, although no list is written.
    pub uses_segments: bool,
}

/// Output numbering of vertices, triangles and edges.
pub struct Numbering {
    /// Per vertex: its output index (0-based), or [`NONE`] when jettisoned; `None` when every
    /// vertex keeps its index.
    pub vertex: Option<Vec<u32>>,
    pub vertex_count: usize,
    /// Per triangle slot: its output index (0-based), or [`NONE`]. Filled only when the outputs
    /// need it (neighbours, Voronoi diagram); empty otherwise.
    pub triangle: Vec<u32>,
    /// Output triangles in order (slot indices).
    pub triangles: Vec<u32>,
    /// Output edges in order: the half-edge of an output triangle whose twin is outside the mesh
    /// or has a larger index, so each undirected edge appears once. Filled only when the outputs
    /// list edges (`e`, `o2`, `v`); empty otherwise.
    pub edges: Vec<u32>,
    /// The number of output edges (always counted).
    pub edge_count: usize,
    /// The output edges on the boundary of the mesh (the twin's triangle is not output), in
    /// the order of `edges`.
    pub boundary_edges: Vec<u32>,
    /// The output edges that lie on segments, in the order of `edges` (empty without segments).
    pub segment_edges: Vec<u32>,
}

impl Numbering {
    #[inline(always)]
    pub fn vertex_index(&self, v: u32) -> u32 {
        match &self.vertex {
            Some(map) => map[v as usize],
            None => v,
        }
    }
}

impl<'a> FinishedMesh<'a> {
    /// The mesh in raw `u32` ids: the output numbering is in raw indices.
    #[inline(always)]
    fn m(&self) -> RawMesh<'a> {
        self.mesh.raw()
    }

    #[inline(always)]
    fn is_boundary(&self, e: u32) -> bool {
        !self.triangle_in_mesh[triangle_of(self.m().twin(e)) as usize]
    }

    fn segment_marker_of(&self, e: u32) -> Option<i32> {
        let markers = self.segment_markers?;
        let id = self.m().segment_of(e);
        (id != NONE).then(|| markers[id as usize])
    }

    /// Numbers vertices (with `jettison`, those `vertex_in_mesh` leaves out are dropped: `j`, or
    /// the mid-edge nodes of six-node input with `r`), triangles and edges, building
    /// only the per-slot and per-edge lists that `options` ask for: at 10^6 triangles each list is
    /// megabytes of memory traffic.
    pub fn numbering(&self, options: &Options, jettison: bool) -> Numbering {
        let slots = self.m().triangle_count() as usize;
        let mut triangles = Vec::with_capacity(slots);
        triangles.extend((0..slots as u32).filter(|&t| self.triangle_in_mesh[t as usize]));
        let mut triangle = Vec::new();
        if options.output.neighbors || options.output.voronoi {
            triangle = vec![NONE; slots];
            for (i, &t) in triangles.iter().enumerate() {
                triangle[t as usize] = i as u32;
            }
        }
        let list_edges = options.output.edges || options.second_order || options.output.voronoi;
        // Written at the running count and kept by advancing it: `e < f` is a coin toss per
        // half-edge, and a branch on it would be mispredicted half the time.
        let mut edges = if list_edges {
            vec![0; 3 * triangles.len()]
        } else {
            Vec::new()
        };
        // Room for one edge per segment id: with segments, the boundary is made of them, and
        // pieces outnumber them only where segments were split (growing from empty would copy
        // and fault in fresh pages at every doubling).
        let segment_ids = self.segment_markers.map_or(0, <[i32]>::len);
        let mut boundary_edges = Vec::with_capacity(segment_ids);
        let mut segment_edges = Vec::with_capacity(segment_ids);
        let mut edge_count = 0;
        let segments = self.mesh.raw_segments();
        let (twins, in_mesh) = (self.mesh.raw_twins(), self.triangle_in_mesh);
        for &t in &triangles {
            for e in 3 * t..3 * t + 3 {
                let f = twins[e as usize];
                // Each edge once: from the smaller half-edge, or from the only output one.
                let boundary = !in_mesh[triangle_of(f) as usize];
                let keep = (e < f) | boundary;
                if list_edges {
                    edges[edge_count] = e;
                }
                if boundary {
                    boundary_edges.push(e);
                }
                if !segments.is_empty() && segments[e as usize] != NONE && keep {
                    segment_edges.push(e);
                }
                edge_count += keep as usize;
            }
        }
        edges.truncate(edge_count);
        let n = self.mesh.vertex_count() as usize;
        let (vertex, vertex_count) = if jettison {
            let mut map = vec![NONE; n];
            let mut count = 0u32;
            for (v, slot) in map.iter_mut().enumerate() {
                if self.vertex_in_mesh[v] {
                    *slot = count;
                    count += 1;
                }
            }
            (Some(map), count as usize)
        } else {
            (None, n)
        };
        Numbering {
            vertex,
            vertex_count,
            triangle,
            triangles,
            edges,
            edge_count,
            boundary_edges,
            segment_edges,
        }
    }

    /// Final vertex markers: the input marker; else, as Triangle assigns them while inserting
    /// segments, the first non-zero marker (in input order) of a segment that the vertex is an
    /// endpoint of a piece of, where a segment given again counts with its own marker at its own
    /// place ([`LaterCopy`]); else 1 on the boundary of the mesh; else 0. (A duplicate left out
    /// of the mesh keeps its input marker, as in Triangle.)
    fn vertex_markers(&self, numbering: &Numbering) -> Vec<i32> {
        let n = self.mesh.vertex_count() as usize;
        // Per vertex, the place in input order of the first segment that marks it (see
        // `LaterCopy::order`; u64::MAX: none).
        let mut first = vec![u64::MAX; n];
        // On the boundary: an edge of the mesh with the outside on one side, or (as Triangle marks
        // them before eating triangles) a piece of a segment on the convex hull. (Where both sides
        // of a segment are eaten, Triangle marks its ends or not by the order it eats them in.)
        let mut on_boundary = vec![false; n];
        for &e in &numbering.boundary_edges {
            on_boundary[self.m().origin(e) as usize] = true;
            on_boundary[self.m().dest(e) as usize] = true;
        }
        let markers = self.segment_markers.unwrap_or(&[]);
        // Per segment id, 1 + the index of its later copy (0: none); only when there are any.
        let mut copy_of_id = Vec::new();
        // (No markers: a mesh eaten whole by its holes tracks no segments.)
        if self.segment_markers.is_some() && !self.later_copies.is_empty() {
            copy_of_id = vec![0u32; markers.len()];
            for (k, copy) in self.later_copies.iter().enumerate() {
                copy_of_id[copy.id as usize] = k as u32 + 1;
            }
        }
        if self.segment_markers.is_some() {
            // One pass over the segment ids; only half-edges on segments are looked at further.
            for (e, &id) in self.mesh.raw_segments().iter().enumerate() {
                if id == NONE {
                    continue;
                }
                let e = e as u32;
                let (a, b) = (self.m().origin(e), self.m().dest(e));
                // The segment's own place, or (its given marker was 0) its later copy's.
                let order = match copy_of_id.get(id as usize) {
                    Some(&k) if k != 0 => self.later_copies[k as usize - 1].order,
                    _ if markers[id as usize] != 0 => u64::from(id) << 32,
                    _ => u64::MAX,
                };
                if a != GHOST && order < first[a as usize] {
                    first[a as usize] = order;
                }
                if a != GHOST && b != GHOST && self.m().apex(e) == GHOST {
                    on_boundary[a as usize] = true;
                    on_boundary[b as usize] = true;
                }
            }
        }
        (0..n)
            .map(|v| {
                let input = self.input_point_markers[v];
                let order = first[v];
                if input != 0 {
                    input
                } else if order != u64::MAX {
                    match order as u32 {
                        0 => markers[(order >> 32) as usize],
                        k => self.later_copies[k as usize - 1].marker,
                    }
                } else {
                    i32::from(on_boundary[v] || self.all_collinear)
                }
            })
            .collect()
    }

    /// `o2`: a node at the midpoint of every edge, appended to the points (attributes averaged,
    /// the edge's marker), and six nodes per triangle: the corners, then the midpoints opposite
    /// corners 1, 2 and 3.
    fn write_second_order(&self, options: &Options, numbering: &Numbering, output: &mut Output) {
        let base = options.first_index();
        let first = numbering.vertex_count as u32;
        let mut node_of_half_edge = vec![NONE; self.mesh.edge_count() as usize];
        for (i, &e) in numbering.edges.iter().enumerate() {
            node_of_half_edge[e as usize] = first + i as u32;
            node_of_half_edge[self.m().twin(e) as usize] = first + i as u32;
        }
        output.point_count += numbering.edges.len();
        output.corners = 6;
        let ends = |e: u32| (self.m().origin(e) as usize, self.m().dest(e) as usize);
        if let Some(points) = output.points.as_mut() {
            for &e in &numbering.edges {
                let (a, b) = ends(e);
                let (p, q) = (self.mesh.points()[a], self.mesh.points()[b]);
                points.extend_from_slice(&[0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
            }
        }
        if let Some(attributes) = output.point_attributes.as_mut() {
            let k = self.point_attribute_count;
            for &e in &numbering.edges {
                let (a, b) = ends(e);
                attributes.extend((0..k).map(|i| {
                    0.5 * (self.point_attributes[a * k + i] + self.point_attributes[b * k + i])
                }));
            }
        }
        if let Some(markers) = output.point_markers.as_mut() {
            markers.extend(numbering.edges.iter().map(|&e| self.edge_marker(e)));
        }
        if !options.output.no_element_output {
            let mut tris = Vec::with_capacity(6 * numbering.triangles.len());
            for &t in &numbering.triangles {
                tris.extend(
                    self.m()
                        .triangle(t)
                        .map(|v| numbering.vertex_index(v) as i32 + base),
                );
                for slot in [1, 2, 0] {
                    tris.push(node_of_half_edge[(3 * t + slot) as usize] as i32 + base);
                }
            }
            output.triangles = Some(tris);
        }
    }

    fn edge_marker(&self, e: u32) -> i32 {
        match self.segment_marker_of(e) {
            Some(m) if m != 0 => m,
            _ => i32::from(self.is_boundary(e)),
        }
    }

    /// Fills the output arrays that the options ask for.
    pub fn write(&self, options: &Options, numbering: &Numbering, output: &mut Output) {
        let base = options.first_index();
        let vid = |v: u32| numbering.vertex_index(v) as i32 + base;
        let markers = !options.output.no_boundary_markers;
        let n = self.mesh.vertex_count() as usize;
        let kept = |v: &usize| numbering.vertex.as_ref().is_none_or(|map| map[*v] != NONE);

        output.point_count = numbering.vertex_count;
        output.point_attribute_count = self.point_attribute_count;
        if !options.output.no_node_output {
            output.points = match &numbering.vertex {
                None if self.points_moved_in_later => None,
                None => Some(self.mesh.points().as_flattened().to_vec()),
                Some(_) => Some(
                    (0..n)
                        .filter(kept)
                        .flat_map(|v| self.mesh.points()[v])
                        .collect(),
                ),
            };
            if self.point_attribute_count > 0 {
                let k = self.point_attribute_count;
                output.point_attributes = Some(
                    (0..n)
                        .filter(kept)
                        .flat_map(|v| &self.point_attributes[v * k..v * k + k])
                        .copied()
                        .collect(),
                );
            }
            if markers {
                let all = self.vertex_markers(numbering);
                output.point_markers = Some(match &numbering.vertex {
                    None => all,
                    Some(_) => (0..n).filter(kept).map(|v| all[v]).collect(),
                });
            }
        }

        output.triangle_count = numbering.triangles.len();
        output.corners = 3;
        if options.second_order {
            self.write_second_order(options, numbering, output);
        } else if !options.output.no_element_output {
            let mut tris = Vec::with_capacity(3 * numbering.triangles.len());
            match &numbering.vertex {
                None => {
                    // Output triangles are never ghosts: every corner is a vertex id.
                    for &t in &numbering.triangles {
                        let i = 3 * t as usize;
                        let corners = self.mesh.raw_corners();
                        let [a, b, c] = [corners[i], corners[i + 1], corners[i + 2]];
                        tris.extend_from_slice(&[
                            a as i32 + base,
                            b as i32 + base,
                            c as i32 + base,
                        ]);
                    }
                }
                Some(_) => {
                    for &t in &numbering.triangles {
                        tris.extend(self.m().triangle(t).map(vid));
                    }
                }
            }
            output.triangles = Some(tris);
        }
        if options.output.neighbors {
            // Neighbour i lies opposite corner i, across the half-edge from corner i+1 to i+2.
            let mut neighbors = Vec::with_capacity(3 * numbering.triangles.len());
            for &t in &numbering.triangles {
                for i in 0..3 {
                    let e = 3 * t + (i + 1) % 3;
                    let other = numbering.triangle[triangle_of(self.m().twin(e)) as usize];
                    neighbors.push(if other == NONE {
                        -1
                    } else {
                        other as i32 + base
                    });
                }
            }
            output.neighbors = Some(neighbors);
        }

        let edges = &numbering.edges;
        output.edge_count = numbering.edge_count;
        if options.output.edges {
            output.edges = Some(
                edges
                    .iter()
                    .flat_map(|&e| [vid(self.m().origin(e)), vid(self.m().dest(e))])
                    .collect(),
            );
            if markers {
                output.edge_markers = Some(edges.iter().map(|&e| self.edge_marker(e)).collect());
            }
        }

        // Segments: the subsegments of the mesh, or (without segments) the hull edges, which
        // Triangle counts although it writes no list.
        let segments: &[u32] = if self.uses_segments {
            if self.segment_markers.is_some() {
                &numbering.segment_edges
            } else {
                &[]
            }
        } else {
            &numbering.boundary_edges
        };
        output.segment_count = segments.len();
        if self.uses_segments && !options.output.no_poly_output {
            // Written from the outside, as Triangle writes hull segments.
            output.segments = Some(
                segments
                    .iter()
                    .flat_map(|&e| [vid(self.m().dest(e)), vid(self.m().origin(e))])
                    .collect(),
            );
            if markers {
                output.segment_markers =
                    Some(segments.iter().map(|&e| self.edge_marker(e)).collect());
            }
        }
    }
}
