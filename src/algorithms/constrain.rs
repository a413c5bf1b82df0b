//! Constrained Delaunay triangulation: inserting segments into a Delaunay triangulation.
//!
//! Each segment is recovered by walking from one endpoint toward the other and collecting the
//! edges it crosses. A vertex lying on the segment splits it there; a segment crossed by another
//! gets a new vertex at the crossing, which splits both. The crossing edges are removed by
//! flipping (Sloan, "A fast algorithm for generating constrained Delaunay triangulations", 1993):
//! flip an edge when its quadrilateral is convex, re-queue it otherwise; then the new edges are
//! made locally Delaunay by Lawson flips that never cross a segment, which yields the constrained
//! Delaunay triangulation (Chew 1989; Lee and Lin 1986).

use std::collections::VecDeque;

use crate::algorithms::delaunay::{Inserter, Location};
use crate::geometry::{Point, Predicates};
use crate::mesh::{next, prev, triangle_of, GHOST, NONE};

/// A vertex created where two segments cross: it lies on the edge from `from` to `to` at
/// parameter `t` (for interpolating attributes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    pub vertex: u32,
    pub from: u32,
    pub to: u32,
    pub t: f64,
}

/// Crossings closer than this (relative to the lengths involved) to a vertex snap to it.
const SNAP_RELATIVE: f64 = 1e-12;

/// Where two segments cross.
enum CrossingPoint {
    /// A new vertex.
    New(u32),
    /// An endpoint of the crossed segment (the crossing rounds onto it).
    Existing(u32),
    /// Another vertex, which the crossed segment passes through in floating point.
    ThroughVertex(u32),
}

/// What the walk from a segment's endpoint finds.
enum Walk {
    /// The edge `e` from the start runs along the segment to a vertex on it (possibly the end).
    Along(u32),
    /// The segment crosses these edges (as vertex pairs right, left of the segment) and then
    /// reaches `stop`, a vertex on it (possibly the end).
    Crosses(Vec<(u32, u32)>, u32),
    /// The segment crosses the segment edge `e` (after the crossings before it).
    HitsSegment(u32),
}

#[derive(Clone)]
pub struct Constrainer<P: Predicates> {
    pub inserter: Inserter<P>,
    /// Vertices created at crossings, in creation order.
    pub crossings: Vec<Crossing>,
    /// The marker of each segment id (the ids that [`Mesh::segment`](crate::mesh::Mesh) holds).
    pub markers: Vec<i32>,
    /// The endpoints of each segment id, as given (before crossings split it).
    pub ends: Vec<(u32, u32)>,
    /// `s`: recover segments by inserting midpoints (a conforming triangulation) instead of
    /// flipping crossing edges away.
    pub split_segments: bool,
}

impl<P: Predicates> Constrainer<P> {
    /// Prepares `inserter`'s mesh (a Delaunay triangulation with ghosts) for segments.
    pub fn new(mut inserter: Inserter<P>) -> Self {
        inserter.mesh.track_vertex_edges();
        inserter.mesh.track_segments();
        Constrainer { inserter, crossings: Vec::new(), markers: Vec::new(), ends: Vec::new(), split_segments: false }
    }

    fn pt(&self, v: u32) -> Point {
        self.inserter.mesh.point(v)
    }

    fn orient(&self, a: u32, b: u32, c: u32) -> f64 {
        P::orient2d(self.pt(a), self.pt(b), self.pt(c))
    }

    /// Registers a segment from `a` to `b` (or `NONE`s for a family of segments) with its
    /// marker; returns the new segment's id.
    pub fn new_segment_id(&mut self, marker: i32, a: u32, b: u32) -> u32 {
        self.markers.push(marker);
        self.ends.push((a, b));
        (self.markers.len() - 1) as u32
    }

    /// Inserts the segment from vertex `a` to vertex `b` with id `id` (from
    /// [`Self::new_segment_id`]). Both must be vertices of the triangulation.
    pub fn insert_segment(&mut self, a: u32, b: u32, id: u32) {
        let mut work = vec![(a, b, id)];
        // `s` splits a segment at midpoints until its pieces are edges; a piece that would need
        // more splits than this (it grazes a vertex) is recovered by flips instead.
        let mut midpoints_left = 64u32;
        while let Some((a, b, id)) = work.pop() {
            if a == b {
                continue;
            }
            match self.walk(a, b) {
                Walk::Along(e) => {
                    let mesh = &mut self.inserter.mesh;
                    let c = mesh.dest(e);
                    // Where segments overlap, a later non-zero marker replaces a zero one, as in
                    // Triangle.
                    let old = mesh.segment_of(e);
                    if old == NONE || (self.markers[old as usize] == 0 && self.markers[id as usize] != 0) {
                        mesh.set_segment(e, id);
                    }
                    work.push((c, b, id));
                }
                Walk::Crosses(crossed, stop) => {
                    work.push((stop, b, id));
                    let split = self.split_segments && midpoints_left > 0;
                    match split.then(|| self.insert_midpoint(a, stop)).flatten() {
                        Some(m) => {
                            midpoints_left -= 1;
                            work.push((m, stop, id));
                            work.push((a, m, id));
                        }
                        None => self.remove_crossings(a, stop, crossed, id),
                    }
                }
                Walk::HitsSegment(e) => {
                    // Read the crossed segment now: making the crossing vertex may rewrite `e`.
                    let mesh = &self.inserter.mesh;
                    let (u, v, other) = (mesh.origin(e), mesh.dest(e), mesh.segment_of(e));
                    match self.split_at_crossing(a, b, e) {
                        CrossingPoint::New(p) | CrossingPoint::Existing(p) => {
                            // The two pieces bend slightly at the rounded crossing point.
                            work.push((p, b, id));
                            work.push((a, p, id));
                        }
                        CrossingPoint::ThroughVertex(w) => {
                            // The crossed segment passes through `w` (in floating point): it is
                            // re-inserted as two pieces meeting at `w`, then this one is retried.
                            if let Some(crossed) = self.inserter.mesh.find_edge(u, v) {
                                self.inserter.mesh.clear_segment(crossed);
                                self.restore_delaunay(vec![(u, v)]);
                            }
                            work.push((a, b, id));
                            work.push((w, v, other));
                            work.push((u, w, other));
                        }
                    }
                },
            }
        }
    }

    /// After inserting a vertex at a rounded position (a crossing, a midpoint), which may lie
    /// off the edge it split by an ulp: the edges around it are made locally Delaunay too (Lawson
    /// checks only the edges opposite a new vertex, which suffices only for exact positions).
    pub fn settle(&mut self, vertex: u32) {
        let mesh = &self.inserter.mesh;
        let start = mesh.vertex_edge[vertex as usize];
        let mut e = start;
        let mut edges = Vec::new();
        loop {
            let w = mesh.dest(e);
            if w != GHOST {
                edges.push((vertex, w));
            }
            e = mesh.twin(prev(e));
            if e == start {
                break;
            }
        }
        self.restore_delaunay(edges);
    }

    /// `s`: inserts the midpoint of `a`–`b` as a vertex (recorded with the crossings, for its
    /// attributes); `None` when it cannot be told apart from the ends.
    fn insert_midpoint(&mut self, a: u32, b: u32) -> Option<u32> {
        let (pa, pb) = (self.pt(a), self.pt(b));
        let m = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
        if m == pa || m == pb {
            return None;
        }
        let start = triangle_of(self.inserter.mesh.vertex_edge[a as usize]);
        let location = self.inserter.locate(m, start);
        if let Location::OnVertex(_) = location {
            return None;
        }
        let vertex = self.inserter.mesh.add_point(m);
        let _ = self.inserter.insert_at(vertex, location);
        self.settle(vertex);
        self.crossings.push(Crossing { vertex, from: a, to: b, t: 0.5 });
        Some(vertex)
    }

    /// Walks from `a` toward `b`.
    fn walk(&self, a: u32, b: u32) -> Walk {
        let mesh = &self.inserter.mesh;
        let (pa, pb) = (self.pt(a), self.pt(b));
        // Find the triangle (a, x, y) around `a` whose wedge holds the direction to `b`.
        let start = mesh.vertex_edge[a as usize];
        let mut e = start;
        let (mut right, mut left);
        loop {
            let (x, y) = (mesh.dest(e), mesh.apex(e));
            if x != GHOST {
                let ox = P::orient2d(pa, self.pt(x), pb);
                if ox == 0.0 && along(pa, self.pt(x), pb) {
                    return Walk::Along(e);
                }
                if y != GHOST && ox > 0.0 && P::orient2d(pa, self.pt(y), pb) < 0.0 {
                    right = x;
                    left = y;
                    break;
                }
            }
            e = mesh.twin(prev(e));
            assert!(e != start, "no triangle around vertex {a} faces vertex {b}");
        }
        // Cross edges until a vertex on the segment is reached.
        let mut crossed = Vec::new();
        let mut h = next(e); // right → left, with the segment crossing it
        loop {
            if mesh.is_segment(h) {
                return Walk::HitsSegment(h);
            }
            crossed.push((right, left));
            let f = mesh.twin(h); // left → right in the next triangle
            let z = mesh.apex(f);
            let oz = P::orient2d(pa, pb, self.pt(z));
            if oz == 0.0 {
                return Walk::Crosses(crossed, z);
            } else if oz > 0.0 {
                left = z;
                h = next(f); // right → z
            } else {
                right = z;
                h = prev(f); // z → left
            }
        }
    }

    /// Finds or makes the vertex where the segment from `a` to `b` crosses the segment edge `e`.
    fn split_at_crossing(&mut self, a: u32, b: u32, e: u32) -> CrossingPoint {
        let mesh = &self.inserter.mesh;
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        let (pu, pv) = (self.pt(u), self.pt(v));
        // Parameter along u → v of the crossing with the line a → b.
        let du = self.orient(a, b, u);
        let dv = self.orient(a, b, v);
        let t = du / (du - dv);
        let p = [pu[0] + t * (pv[0] - pu[0]), pu[1] + t * (pv[1] - pu[1])];
        // A crossing within rounding distance of a vertex is that vertex: three segments through
        // one point, or a segment through a vertex that the exact test finds off by an ulp. A new
        // vertex there would create a feature far smaller than the input's, which refinement
        // could only resolve with a cascade of tiny triangles.
        let (pa, pb) = (self.pt(a), self.pt(b));
        let dist2 = |q: Point| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
        let scale2 = dist2(pu).max(dist2(pv)).max(dist2(pa)).max(dist2(pb));
        let snap2 = scale2 * SNAP_RELATIVE * SNAP_RELATIVE;
        for (w, at_crossed_end) in [(u, true), (v, true), (a, false), (b, false)] {
            if dist2(self.pt(w)) <= snap2 {
                return if at_crossed_end { CrossingPoint::Existing(w) } else { CrossingPoint::ThroughVertex(w) };
            }
        }
        let (c, d) = (mesh.apex(e), mesh.apex(mesh.twin(e)));
        let (pc, pd) = (self.pt(c), self.pt(d));
        let splits_cleanly = P::orient2d(pc, pu, p) > 0.0
            && P::orient2d(pv, pc, p) > 0.0
            && P::orient2d(pu, pd, p) > 0.0
            && P::orient2d(pd, pv, p) > 0.0;
        if !splits_cleanly {
            // The rounded crossing is not inside the crossed edge's quadrilateral (next to a
            // sliver left by an earlier bent segment): insert it where it is, and let both
            // segments bend through it.
            let start = triangle_of(e);
            return match self.inserter.locate(p, start) {
                Location::OnVertex(w) => CrossingPoint::ThroughVertex(w),
                location => {
                    let vertex = self.inserter.mesh.add_point(p);
                    let _ = self.inserter.insert_at(vertex, location);
                    self.settle(vertex);
                    self.crossings.push(Crossing { vertex, from: u, to: v, t });
                    CrossingPoint::ThroughVertex(vertex)
                }
            };
        }
        let vertex = self.inserter.mesh.add_point(p);
        let _ = self.inserter.insert_at(vertex, Location::OnEdge(e));
        self.settle(vertex);
        self.crossings.push(Crossing { vertex, from: u, to: v, t });
        CrossingPoint::New(vertex)
    }

    /// Removes the edges crossing the new segment `a`–`b` by Sloan's flips, marks the recovered
    /// edge as segment `id`, then restores the constrained Delaunay property around the new edges.
    fn remove_crossings(&mut self, a: u32, b: u32, crossed: Vec<(u32, u32)>, id: u32) {
        let mut queue: VecDeque<(u32, u32)> = crossed.into();
        let mut new_edges = Vec::new();
        let mut stalls = 0usize;
        while let Some((u, v)) = queue.pop_front() {
            let mesh = &self.inserter.mesh;
            let e = mesh.find_edge(u, v).expect("crossing edge exists");
            let f = mesh.twin(e);
            let (p, q) = (mesh.apex(e), mesh.apex(f));
            // The quadrilateral u, q, v, p is strictly convex when p–q crosses u–v.
            let convex = self.orient(p, q, u) * self.orient(p, q, v) < 0.0;
            if !convex {
                queue.push_back((u, v));
                stalls += 1;
                assert!(stalls <= 4 * queue.len() * queue.len() + 16, "segment recovery made no progress");
                continue;
            }
            stalls = 0;
            self.inserter.mesh.flip(e);
            let crosses = {
                let (op, oq) = (self.orient(a, b, p), self.orient(a, b, q));
                p != a && p != b && q != a && q != b && op * oq < 0.0
            };
            if crosses {
                queue.push_back((p, q));
            } else {
                new_edges.push((p, q));
            }
        }
        let e = self.inserter.mesh.find_edge(a, b).expect("segment recovered by flips");
        self.inserter.mesh.set_segment(e, id);
        self.restore_delaunay(new_edges);
    }

    /// Lawson flips from the given edges until every non-segment edge is locally Delaunay.
    pub fn restore_delaunay(&mut self, edges: Vec<(u32, u32)>) {
        let mut stack = edges;
        while let Some((u, v)) = stack.pop() {
            let mesh = &self.inserter.mesh;
            let Some(e) = mesh.find_edge(u, v) else { continue };
            if mesh.is_segment(e) {
                continue;
            }
            let f = mesh.twin(e);
            let (p, q) = (mesh.apex(e), mesh.apex(f));
            if p == GHOST || q == GHOST {
                continue;
            }
            if P::incircle(self.pt(u), self.pt(v), self.pt(p), self.pt(q)) > 0.0 {
                self.inserter.mesh.flip(e);
                stack.extend_from_slice(&[(u, q), (q, v), (v, p), (p, u)]);
            }
        }
    }

    /// Marks every hull edge that is not a segment yet as a segment with marker `marker` (the `c`
    /// switch, the boundary of a mesh being refined, and refinement of a point set). Each is a
    /// segment of its own, ending at its two vertices.
    pub fn mark_hull(&mut self, marker: i32) {
        for e in 0..self.inserter.mesh.corners.len() as u32 {
            let mesh = &self.inserter.mesh;
            let (a, b) = (mesh.origin(e), mesh.dest(e));
            if a != GHOST && b != GHOST && mesh.apex(mesh.twin(e)) == GHOST && mesh.segment_of(e) == NONE {
                let id = self.new_segment_id(marker, a, b);
                self.inserter.mesh.set_segment(e, id);
            }
        }
    }

    /// The triangle containing `p`, if `p` lies in the triangulated area.
    pub fn triangle_at(&mut self, p: Point) -> Option<u32> {
        let start = self.inserter.last_triangle();
        match self.inserter.locate(p, start) {
            Location::InTriangle(t) => Some(t),
            Location::OnEdge(e) => Some(triangle_of(e)),
            Location::OnVertex(v) => {
                let e = self.inserter.mesh.vertex_edge[v as usize];
                (e != NONE).then(|| triangle_of(e)).filter(|&t| !self.inserter.mesh.is_ghost(t))
            }
            Location::Outside(_) => None,
        }
    }
}

/// Whether `x`, collinear with the ray from `a` through `b`, lies on that ray's side of `a`.
fn along(a: Point, x: Point, b: Point) -> bool {
    (x[0] - a[0]) * (b[0] - a[0]) + (x[1] - a[1]) * (b[1] - a[1]) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::delaunay::order::{hilbert_order, splitmix64};
    use crate::geometry::Exact;

    fn rand01(s: &mut u64) -> f64 {
        splitmix64(s) as f64 / u64::MAX as f64
    }

    /// Builds the CDT of random points and random segments between them, checking after each
    /// segment that the mesh is valid, the segment is present and non-segment edges are locally
    /// Delaunay.
    #[test]
    fn random_segments_are_recovered() {
        let seeds: Vec<u64> = match std::env::var("SEED") { Ok(s) => vec![s.parse().unwrap()], Err(_) => (0..3000).collect() };
        for seed in seeds.into_iter().take(1500) {
            let mut s = seed;
            let n = 5 + (splitmix64(&mut s) % 40) as usize;
            let pts: Vec<Point> = (0..n).map(|_| [rand01(&mut s), rand01(&mut s)]).collect();
            let order = hilbert_order(&pts);
            let tri = crate::algorithms::delaunay::triangulate::<Exact>(pts, &order);
            if tri.is_degenerate() {
                continue;
            }
            let mut cdt = Constrainer::new(Inserter::<Exact>::new(tri.mesh));
            // Every other seed recovers segments by splitting (`s`).
            cdt.split_segments = seed % 2 == 1;
            for k in 0..10 {
                let a = (splitmix64(&mut s) % n as u64) as u32;
                let b = (splitmix64(&mut s) % n as u64) as u32;
                let id = cdt.new_segment_id(k as i32 % 3, a, b);
                cdt.insert_segment(a, b, id);
                let m = &cdt.inserter.mesh;
                m.check_topology().unwrap_or_else(|e| panic!("seed {seed}: {e}"));
                for t in m.real_triangles() {
                    let [p, q, r] = m.triangle(t).map(|v| m.point(v));
                    assert!(Exact::orient2d(p, q, r) > 0.0, "seed {seed}: inverted triangle");
                    for e in 3 * t..3 * t + 3 {
                        let o = m.apex(m.twin(e));
                        if o != GHOST && !m.is_segment(e) {
                            assert!(Exact::incircle(p, q, r, m.point(o)) <= 0.0, "seed {seed}: not CDT");
                        }
                    }
                }
                for e in 0..m.corners.len() as u32 {
                    if m.origin(e) != GHOST && m.dest(e) != GHOST {
                        assert_eq!(m.vertex_edge[m.origin(e) as usize] == NONE, false);
                    }
                }
            }
        }
    }
}
