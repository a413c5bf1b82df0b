//! Delaunay refinement: quality meshing with angle, area and user constraints.
//!
//! Ruppert's algorithm ("A Delaunay refinement algorithm for quality 2-dimensional mesh
//! generation", 1995) as refined by Shewchuk ("Delaunay refinement algorithms for triangular mesh
//! generation", 2002):
//! - a subsegment is *encroached* when a vertex lies strictly inside its diametral circle; in a
//!   constrained Delaunay triangulation it suffices to look at the two apices beside it. Encroached
//!   subsegments are split first, at their midpoints, or — next to an input vertex shared with
//!   another segment — at a power-of-two distance from it ("concentric shells", Shewchuk §4.1),
//!   which keeps small input angles from causing endless splitting;
//! - a bad triangle (an angle below θ, an area above the bound, or the user's test) is split at its
//!   circumcentre or, when that is closer to the shortest edge, at Üngör's off-centre ("Off-centers:
//!   a new type of Steiner points for computing size-optimal quality-guaranteed Delaunay
//!   triangulations", 2004), which needs fewer vertices;
//! - a new point that would encroach a subsegment is rejected, and the subsegment is split instead
//!   (Ruppert's rule); the bad triangle is queued again.
//!
//! Worst triangles go first. Termination: for θ ≤ 28.6° the algorithm terminates (Shewchuk
//! 2002); beyond, it may not, so every split checks that it makes an edge no shorter than a floor
//! far above the floating-point resolution of the domain, skips (and reports) a triangle or
//! segment it cannot split, and stops at the Steiner-point budget (`S`) or when cancelled.

use std::collections::{HashSet, VecDeque};

use crate::algorithms::constrain::{along, before, Constrainer};
use crate::algorithms::delaunay::Location;
use crate::algorithms::domain::Domain;
use crate::data::{Phase, Progress, ProgressFn, UnsuitableFn};
use crate::geometry::{circumcenter, Point, Predicates};
use crate::mesh::{next, prev, triangle_of, GHOST, NONE, OUTSIDE};

/// The largest minimum angle for which Delaunay refinement is proven to terminate.
pub const GUARANTEED_ANGLE: f64 = 28.6;
/// Above that angle, refinement first runs straight toward it with a budget of this many new
/// vertices per triangle of the unrefined mesh (plus what the area bound asks for).
const STRAIGHT_BUDGET_PER_TRIANGLE: u64 = 64;
/// If that is not enough, the straight run may go on to this many new vertices per triangle of
/// the mesh refined to the guaranteed angle.
const GUARANTEED_MULTIPLE: u64 = 4;
/// A refinement is stopped as a runaway beyond this many new vertices per triangle of the
/// unrefined mesh plus what the area bounds ask for (inputs with many tiny angles need about 100),
/// and not below this many in all (a few seconds of work).
const RUNAWAY_PER_TRIANGLE: u64 = 1000;
const RUNAWAY_MINIMUM: u64 = 1_000_000;
/// Failing that, the mesh refined to the guaranteed angle goes on toward the asked one with a
/// budget of this many new vertices per triangle it has (plus a few).
const UNGUARANTEED_BUDGET_PER_TRIANGLE: u64 = 2;
/// Two distances from a corner are equal (for the small-angle exemption of vertices not on one
/// concentric shell: midpoints, or shells around two corners) within this fraction. Measured:
/// a tolerance of 10^-9 (rounding only) makes 10% more triangles than Triangle near input angles
/// of hundredths of a degree (random star polygons), 10^-3 as many as Triangle.
const EQUAL_DISTANCE_TOLERANCE: f64 = 1e-3;

/// What makes a triangle bad, and what may be done about it.
pub struct Quality<'a> {
    /// Minimum angle in degrees (`q`).
    pub min_angle: Option<f64>,
    /// Global maximum area (`a<x>`).
    pub max_area: Option<f64>,
    /// Regional / per-triangle maximum areas (`a`), from the domain's tags.
    pub variable_area: bool,
    /// The user's test (`u`).
    pub user_test: Option<&'a UnsuitableFn<'a>>,
    /// `Y` (1): no Steiner points on boundary segments; `YY` (2): on any segment.
    pub no_steiner_on_segments: u8,
    /// `S`: the Steiner-point budget.
    pub max_steiner: Option<u64>,
    /// Polled now and then; `true` stops refinement with a valid mesh.
    pub cancel: Option<&'a (dyn Fn() -> bool + Sync + 'a)>,
    /// Told of the work done and waiting where `cancel` is polled.
    pub progress: Option<&'a ProgressFn<'a>>,
}

/// How a vertex came to be: it decides where segments next to it are split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexKind {
    /// An input vertex (or a crossing of input segments).
    Input,
    /// A vertex inserted on a segment by refinement; `corner`: the input vertex it was put at a
    /// power-of-two distance from (concentric shells), or [`NONE`] (a midpoint); `shell`: that
    /// distance's exponent (the distance is 2^shell; 0 for a midpoint).
    OnSegment { corner: u32, shell: i32 },
    /// A vertex inserted inside the domain by refinement.
    Free,
}

/// A queued bad triangle: its corners (it may be gone by the time it is taken out).
#[derive(Clone, Copy, Debug, PartialEq)]
struct BadTriangle {
    /// Queue bucket: higher goes first.
    bucket: usize,
    corners: [u32; 3],
}

/// Bad triangles in buckets (a bucket queue: constant time per operation, where a binary heap
/// of millions of triangles costs a cache miss per level). Skinny triangles come first, by the
/// length of their shortest edge, shortest first: splitting the small ones first settles the
/// fine parts of the mesh (near small features and small input angles) before the coarse
/// triangles around them are split, so that fewer coarse splits are made that later refinement
/// would have made anyway; measured, it gives fewer vertices than worst-angle-first or FIFO
/// order. Triangles bad only by their size (area, user test) come last, first in first out:
/// ordering them by size too (either way) made as many vertices on large meshes and took half
/// again as long on a million triangles (more flips, longer walks and cavities).
#[derive(Default)]
struct BadQueue {
    buckets: Vec<VecDeque<[u32; 3]>>,
    /// No bucket above this one holds anything.
    top: usize,
}

/// Buckets of the skinny triangles, above bucket 0 (which holds the triangles bad only by their
/// size): one per halving of the squared shortest edge relative to the domain's extent, shorter
/// first (the precision floor, 2⁻⁴⁰ of the extent, is reached at bucket 81).
const EDGE_BUCKETS: usize = 96;

impl BadQueue {
    fn new() -> Self {
        BadQueue {
            buckets: (0..=EDGE_BUCKETS).map(|_| VecDeque::new()).collect(),
            top: 0,
        }
    }
    /// The bucket of a skinny triangle whose shortest edge, squared, is `relative` times the
    /// domain's extent squared.
    fn skinny_bucket(relative: f64) -> usize {
        // ⌊−log2 relative⌋ from the exponent bits.
        let exponent = ((relative.to_bits() >> 52) & 0x7ff) as i64 - 1023;
        1 + ((-exponent).max(0) as usize).min(EDGE_BUCKETS - 1)
    }
    /// The bucket of the triangles bad only by their size.
    const SIZE_BUCKET: usize = 0;
    fn push(&mut self, bad: BadTriangle) {
        self.buckets[bad.bucket].push_back(bad.corners);
        self.top = self.top.max(bad.bucket);
    }
    fn pop(&mut self) -> Option<BadTriangle> {
        loop {
            if let Some(corners) = self.buckets[self.top].pop_front() {
                return Some(BadTriangle {
                    bucket: self.top,
                    corners,
                });
            }
            if self.top == 0 {
                return None;
            }
            self.top -= 1;
        }
    }
    fn clear(&mut self) {
        self.buckets.iter_mut().for_each(VecDeque::clear);
        self.top = 0;
    }
    fn len(&self) -> usize {
        self.buckets.iter().map(VecDeque::len).sum()
    }
    fn is_empty(&self) -> bool {
        self.buckets.iter().all(VecDeque::is_empty)
    }
}

/// How a budgeted refinement run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Outcome {
    Finished,
    Cancelled,
    /// The `S` budget is spent.
    UserBudget,
    /// The budget of the run is spent.
    OutOfBudget,
}

/// The state of a refinement, to come back to.
struct Snapshot<P: Predicates> {
    cdt: Constrainer<P>,
    attributes: Vec<f64>,
    kinds: Vec<VertexKind>,
    steiner_points: u64,
    skipped: u64,
    kept_whole: u64,
    unsplittable: HashSet<(u32, u32)>,
}

/// Where the straight walk from a bad triangle toward its new point ends.
enum Walk {
    /// The point lies in (or on the boundary of) the domain at this location.
    Found(Location),
    /// A segment (this half-edge) separates the point from the triangle.
    Blocked(u32),
    /// The point lies outside the domain (or the walk could not settle).
    Lost,
}

/// The outcome of a refinement run.
#[derive(Debug, Default)]
pub struct Report {
    pub steiner_points: u64,
    pub warnings: Vec<String>,
}

pub struct Refiner<'r, 'q, P: Predicates> {
    cdt: &'r mut Constrainer<P>,
    domain: &'r Domain,
    quality: &'r Quality<'q>,
    /// Per vertex.
    pub kinds: Vec<VertexKind>,
    /// Per vertex, `attribute_count` values (new vertices are interpolated).
    pub attributes: &'r mut Vec<f64>,
    attribute_count: usize,
    cos2_min_angle: f64,
    /// cos² of the lens angle 180° − 2θ; `None`: diametral circles (`D`).
    lens_cos2: Option<f64>,
    /// `D`: encroachment by diametral circles, so that the result is truly Delaunay.
    conforming: bool,
    /// Off-centre distance from the shortest edge, as a multiple of its length.
    off_center: f64,
    /// No edge is made shorter than this (squared): far above the resolution of doubles here.
    floor2: f64,
    /// The domain's extent, squared (the scale of the bad-triangle queue).
    extent2: f64,
    /// Subsegments to split: ends, and whether a rejected point encroached it (split regardless).
    encroached: VecDeque<(u32, u32, bool)>,
    /// Where refinement stops (the `S` budget, or the budget beyond the guaranteed angle).
    steiner_limit: Option<u64>,
    bad: BadQueue,
    /// Scratch space for the cavity search.
    cavity: Vec<u32>,
    cavity_stack: Vec<u32>,
    unsplittable: HashSet<(u32, u32)>,
    report: Report,
    /// Bad triangles and segments left alone because splitting them would make too short an edge.
    skipped: u64,
    /// Bad triangles left alone because splitting them needs a vertex on a segment that `Y`/`YY`
    /// keep whole.
    kept_whole: u64,
    cancelled: bool,
    /// Where a run is stopped as a runaway (see [`Self::run`]), and whether it was.
    runaway_limit: Option<u64>,
    ran_away: bool,
    polls: u32,
}

impl<'r, 'q, P: Predicates> Refiner<'r, 'q, P> {
    pub fn new(
        conforming: bool,
        cdt: &'r mut Constrainer<P>,
        domain: &'r Domain,
        quality: &'r Quality<'q>,
        kinds: Vec<VertexKind>,
        attributes: &'r mut Vec<f64>,
        attribute_count: usize,
    ) -> Self {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &cdt.inserter.mesh.points {
            for i in 0..2 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        let extent = (hi[0] - lo[0])
            .abs()
            .max((hi[1] - lo[1]).abs())
            .max(lo[0].abs().max(hi[0].abs()) * 1e-3)
            .max(f64::MIN_POSITIVE);
        let floor = extent * 2f64.powi(-40);
        let mut refiner = Refiner {
            cdt,
            domain,
            quality,
            kinds,
            attributes,
            attribute_count,
            cos2_min_angle: 2.0,
            lens_cos2: None,
            conforming,
            off_center: f64::INFINITY,
            floor2: floor * floor,
            extent2: extent * extent,
            steiner_limit: quality.max_steiner,
            encroached: VecDeque::new(),
            bad: BadQueue::new(),
            cavity: Vec::new(),
            cavity_stack: Vec::new(),
            unsplittable: HashSet::new(),
            report: Report::default(),
            skipped: 0,
            kept_whole: 0,
            cancelled: false,
            runaway_limit: None,
            ran_away: false,
            polls: 0,
        };
        refiner.set_angle(quality.min_angle.unwrap_or(0.0));
        refiner
    }

    fn pt(&self, v: u32) -> Point {
        self.cdt.inserter.mesh.point(v)
    }

    fn inside(&self, t: u32) -> bool {
        self.cdt.inserter.mesh.tag[t as usize] != OUTSIDE
    }

    /// Refines until no subsegment is encroached and no triangle is bad (or a limit stops it).
    pub fn run(mut self) -> Report {
        // Without the user's own test or budget: a run that makes far more vertices than the
        // input and the area bounds account for is stopped (an input a hair's breadth wide, such
        // as nearly collinear points with `c`, needs about length/width triangles: billions).
        if self.quality.user_test.is_none() && self.quality.max_steiner.is_none() {
            let expected =
                RUNAWAY_PER_TRIANGLE * self.inside_triangle_count() + self.size_estimate();
            self.runaway_limit = Some(expected.max(RUNAWAY_MINIMUM));
        }
        self.snap_vertices_onto_segments();
        match self.quality.min_angle {
            Some(angle) if angle > GUARANTEED_ANGLE => self.refine_beyond_the_guarantee(angle),
            _ => {
                self.refine_all_within(None);
            }
        }
        if self.ran_away {
            self.report.warnings.push(format!(
                "Refinement stopped after {} Steiner points, far more than this input and its area bounds \
                 account for: some of its features are too thin for the minimum angle (the mesh is valid; \
                 the S switch sets a limit of your own).",
                self.report.steiner_points
            ));
        }
        if self.skipped > 0 {
            self.report.warnings.push(format!(
                "Refinement left {} triangles or segments unsplit: the precision of floating-point numbers is \
                 exhausted near some vertices. The mesh is valid but may have angles below the minimum there.",
                self.skipped
            ));
        }
        if self.kept_whole > 0 {
            self.report.warnings.push(format!(
                "Refinement left {} bad triangles unsplit: that needs new vertices on segments, which the Y switch \
                 forbids. The mesh is valid but may have angles below the minimum or triangles above the maximum area.",
                self.kept_whole
            ));
        }
        self.report
    }

    /// Refinement toward an angle above 28.6°, where it may never end (it can cascade into ever
    /// smaller triangles near small input angles). Usually it ends, and refining straight toward
    /// the angle, as Triangle does, gives the best mesh; so that runs first, with a generous
    /// budget of new vertices. If the budget runs out, the mesh refined to 28.6° (which always
    /// ends) tells how big a mesh the input needs, and the straight run may go on to a multiple
    /// of that. Failing that, the 28.6° mesh is refined toward the angle with a small budget and
    /// whatever that leaves is repaired at 28.6°: the result meets the guaranteed angle, and a
    /// warning says that it does not meet the asked one.
    fn refine_beyond_the_guarantee(&mut self, angle: f64) {
        let start = self.snapshot();
        self.set_angle(angle);
        let budget = STRAIGHT_BUDGET_PER_TRIANGLE * self.inside_triangle_count()
            + self.size_estimate()
            + 1024;
        if self.refine_all_within(Some(self.report.steiner_points + budget)) != Outcome::OutOfBudget
        {
            return;
        }
        let straight = self.snapshot();
        self.restore(start);
        self.set_angle(GUARANTEED_ANGLE);
        if self.refine_all_within(None) != Outcome::Finished {
            return; // cancelled, or stopped by `S`
        }
        let guaranteed_triangles = self.inside_triangle_count();
        let limit = straight.steiner_points.max(self.report.steiner_points)
            + GUARANTEED_MULTIPLE * guaranteed_triangles;
        if straight.steiner_points < limit {
            let guaranteed = self.snapshot();
            self.restore(straight);
            self.set_angle(angle);
            if self.refine_all_within(Some(limit)) != Outcome::OutOfBudget {
                return;
            }
            self.restore(guaranteed);
        }
        self.set_angle(angle);
        let budget = self.report.steiner_points
            + UNGUARANTEED_BUDGET_PER_TRIANGLE * guaranteed_triangles
            + 16;
        if self.refine_all_within(Some(budget)) == Outcome::OutOfBudget {
            self.set_angle(GUARANTEED_ANGLE);
            self.refine_all_within(None);
            self.report.warnings.push(format!(
                "A minimum angle of {angle}° is above {GUARANTEED_ANGLE}°, the largest for which Delaunay \
                 refinement is guaranteed to terminate, and this input needs more: refinement stopped after \
                 {} Steiner points with some angles below {angle}° but none below {GUARANTEED_ANGLE}° (the mesh \
                 is valid).",
                self.report.steiner_points
            ));
        }
    }

    /// Runs [`Self::refine_all`] until it finishes or has made `limit` Steiner points in all (or
    /// fewer under `S`), and says how it ended.
    fn refine_all_within(&mut self, limit: Option<u64>) -> Outcome {
        let lower = |a: Option<u64>, b: Option<u64>| match (a, b) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let (user_limit, runaway_limit) = (self.quality.max_steiner, self.runaway_limit);
        self.steiner_limit = lower(lower(limit, user_limit), runaway_limit);
        self.refine_all();
        if self.cancelled {
            Outcome::Cancelled
        } else if self.bad.is_empty() && self.encroached.is_empty() {
            Outcome::Finished
        } else if user_limit.is_some() && self.steiner_limit == user_limit {
            Outcome::UserBudget
        } else if runaway_limit.is_some() && self.steiner_limit == runaway_limit {
            self.ran_away = true;
            Outcome::UserBudget
        } else {
            Outcome::OutOfBudget
        }
    }

    /// The state of refinement, to come back to.
    fn snapshot(&self) -> Snapshot<P> {
        Snapshot {
            cdt: self.cdt.clone(),
            attributes: self.attributes.clone(),
            kinds: self.kinds.clone(),
            steiner_points: self.report.steiner_points,
            skipped: self.skipped,
            kept_whole: self.kept_whole,
            unsplittable: self.unsplittable.clone(),
        }
    }

    fn restore(&mut self, snapshot: Snapshot<P>) {
        *self.cdt = snapshot.cdt;
        *self.attributes = snapshot.attributes;
        self.kinds = snapshot.kinds;
        self.report.steiner_points = snapshot.steiner_points;
        self.skipped = snapshot.skipped;
        self.kept_whole = snapshot.kept_whole;
        self.unsplittable = snapshot.unsplittable;
        self.encroached.clear();
        self.bad.clear();
    }

    fn inside_triangle_count(&self) -> u64 {
        (0..self.cdt.inserter.mesh.triangle_count())
            .filter(|&t| self.inside(t))
            .count() as u64
    }

    /// About how many vertices the area bounds (global, regional, per triangle) ask for: four
    /// times the number of triangles of the largest allowed areas that cover the domain.
    fn size_estimate(&self) -> u64 {
        let mesh = &self.cdt.inserter.mesh;
        let triangles: f64 = (0..mesh.triangle_count())
            .filter(|&t| self.inside(t))
            .map(|t| {
                let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
                let area = 0.5 * P::orient2d(a, b, c);
                let regional = if self.quality.variable_area {
                    self.domain
                        .max_area
                        .get(mesh.tag[t as usize] as usize)
                        .copied()
                        .filter(|&m| m > 0.0)
                } else {
                    None
                };
                match (self.quality.max_area, regional) {
                    (Some(m), Some(r)) => area / m.min(r),
                    (Some(m), None) | (None, Some(m)) => area / m,
                    (None, None) => 0.0,
                }
            })
            .sum();
        (4.0 * triangles).min(1e12) as u64
    }

    /// Sets the angle bound θ (degrees): the bad-angle test, the lens and the off-centre.
    fn set_angle(&mut self, degrees: f64) {
        let theta = degrees.clamp(0.0, 60.0).to_radians();
        let cos = theta.cos();
        self.cos2_min_angle = if theta > 0.0 { cos * cos } else { 2.0 };
        // With no angle bound the lens is empty: nothing encroaches, as in Triangle (only a
        // segment hiding a new point from its triangle is split then).
        self.lens_cos2 = (theta < std::f64::consts::FRAC_PI_4 && !self.conforming)
            .then(|| (2.0 * theta).cos().powi(2));
        self.off_center = if theta > 0.0 {
            0.475 * ((1.0 + cos) / (1.0 - cos)).sqrt()
        } else {
            f64::INFINITY
        };
    }

    /// Makes every vertex that lies within the floor distance of a subsegment, between its
    /// ends, a vertex of it: the subsegment is flipped away and the two edges to the vertex
    /// become the segment. Such a vertex is on the segment at the resolution refinement works
    /// at (two segments at an angle of 10^-16 radians, which rounding makes of one line through
    /// a vertex): left apart, the vertex encroaches the segment, every split point on it
    /// encroaches back, and refinement would fill the sliver between them with vertices down to
    /// the floor (Triangle stops with "Ran out of precision"). Subsegments on the hull are left
    /// as they are (the runaway limit of [`Self::run`] still bounds the work there).
    fn snap_vertices_onto_segments(&mut self) {
        let floor2 = self.floor2;
        let on_segment = |pu: Point, pv: Point, pw: Point| {
            let length2 = (pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2);
            let height = P::orient2d(pu, pv, pw); // |uv| times w's distance from the line
            let near = |a: Point| (pw[0] - a[0]).powi(2) + (pw[1] - a[1]).powi(2) < floor2;
            height * height < floor2 * length2
                && along(pu, pw, pv)
                && before(pu, pw, pv)
                && !near(pu)
                && !near(pv)
        };
        let mesh = &self.cdt.inserter.mesh;
        // One half-edge per subsegment: the flip looks at the vertices on both sides.
        let mut work: Vec<u32> = (0..mesh.corners.len() as u32)
            .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
            .collect();
        while let Some(e) = work.pop() {
            let mesh = &self.cdt.inserter.mesh;
            let (u, v) = (mesh.origin(e), mesh.dest(e));
            if !mesh.is_segment(e) {
                continue;
            }
            if let Some(w) = self.cdt.flip_edge_onto_vertex(e, on_segment) {
                let mesh = &self.cdt.inserter.mesh;
                work.extend(
                    [(u, w), (w, v)]
                        .into_iter()
                        .filter_map(|(a, b)| mesh.find_edge(a, b)),
                );
            }
        }
    }

    /// Splits encroached subsegments, then bad triangles, until none is left or a limit stops.
    fn refine_all(&mut self) {
        let mesh = &self.cdt.inserter.mesh;
        let segments: Vec<u32> = (0..mesh.corners.len() as u32)
            .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
            .collect();
        for e in segments {
            self.check_segment(e);
        }
        self.split_encroached();
        self.bad.clear();
        for t in 0..self.cdt.inserter.mesh.triangle_count() {
            if self.inside(t) {
                self.check_triangle(t);
            }
        }
        while !self.should_stop() {
            let Some(bad) = self.bad.pop() else { break };
            let [a, b, c] = bad.corners;
            let Some(e) = self.cdt.inserter.mesh.find_edge(a, b) else {
                continue;
            };
            if self.cdt.inserter.mesh.apex(e) != c {
                continue; // gone since it was queued
            }
            self.split_triangle(triangle_of(e), bad);
            self.split_encroached();
        }
    }

    /// Whether to stop: the caller cancelled (polled now and then), or the limit is reached.
    fn should_stop(&mut self) -> bool {
        if self.cancelled {
            return true;
        }
        self.polls = self.polls.wrapping_add(1);
        if self.polls % 1024 == 0 {
            if let Some(progress) = self.quality.progress {
                let done = self.report.steiner_points;
                let waiting = self.bad.len() + self.encroached.len();
                progress(Progress {
                    phase: Phase::Refinement,
                    done,
                    estimate: done + waiting as u64,
                });
            }
        }
        if self.polls % 64 == 0 && self.quality.cancel.is_some_and(|cancelled| cancelled()) {
            self.report
                .warnings
                .push("Refinement was cancelled; the mesh is valid but not refined.".into());
            self.cancelled = true;
            return true;
        }
        self.steiner_limit
            .is_some_and(|limit| self.report.steiner_points >= limit)
    }

    /// Whether the segment of half-edge `e` may receive Steiner points (`Y`, `YY`).
    fn may_split(&self, e: u32) -> bool {
        let mesh = &self.cdt.inserter.mesh;
        match self.quality.no_steiner_on_segments {
            0 => true,
            1 => self.inside(triangle_of(e)) && self.inside(triangle_of(mesh.twin(e))),
            _ => false,
        }
    }

    /// Whether `w` encroaches subsegment `u`–`v`: lies in its diametral lens (without `D`:
    /// `u`–`v` subtends at least 180° − 2θ at `w`, Shewchuk 2002 §3.2, which inserts fewer
    /// vertices; with no angle bound, never), else strictly inside its diametral circle.
    fn encroaches(&self, u: u32, v: u32, w: Point) -> bool {
        let (pu, pv) = (self.pt(u), self.pt(v));
        let (a, b) = ([pu[0] - w[0], pu[1] - w[1]], [pv[0] - w[0], pv[1] - w[1]]);
        let dot = a[0] * b[0] + a[1] * b[1];
        match self.lens_cos2 {
            Some(cos2) => {
                dot < 0.0
                    && dot * dot >= cos2 * (a[0] * a[0] + a[1] * a[1]) * (b[0] * b[0] + b[1] * b[1])
            }
            None => dot < 0.0,
        }
    }

    /// Queues the subsegment of half-edge `e` if an apex beside it encroaches it.
    fn check_segment(&mut self, e: u32) {
        let mesh = &self.cdt.inserter.mesh;
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        for h in [e, mesh.twin(e)] {
            let w = mesh.apex(h);
            if w != GHOST && self.inside(triangle_of(h)) && self.encroaches(u, v, mesh.point(w)) {
                if self.may_split(e) && !self.unsplittable.contains(&(u.min(v), u.max(v))) {
                    self.encroached.push_back((u, v, false));
                }
                return;
            }
        }
    }

    /// Splits the queued subsegments that are still encroached (or were queued `forced`);
    /// returns how many it split.
    fn split_encroached(&mut self) -> usize {
        let mut splits = 0;
        while let Some((u, v, forced)) = self.encroached.pop_front() {
            if self.should_stop() {
                self.encroached.push_front((u, v, forced));
                break;
            }
            let mesh = &self.cdt.inserter.mesh;
            let Some(e) = mesh.find_edge(u, v).filter(|&e| mesh.is_segment(e)) else {
                continue;
            };
            let still = [e, mesh.twin(e)].iter().any(|&h| {
                let w = mesh.apex(h);
                w != GHOST && self.inside(triangle_of(h)) && self.encroaches(u, v, mesh.point(w))
            });
            if (forced || still) && self.split_segment(e) {
                splits += 1;
            }
        }
        splits
    }

    /// Where to split subsegment `u`–`v` (parameter from `u`): at a power-of-two distance from
    /// an end that is an input vertex where segments meet at an acute angle ("concentric shells",
    /// Ruppert 1995 §5, Shewchuk 2002 §4.1), from the sharper one if both are; else the midpoint.
    /// The powers of two are absolute (2^k, k any integer), the same on every segment around a
    /// corner, so that splits on two segments meet on common shells. Returns the parameter and
    /// the kind of the new vertex (the corner and the exponent of its distance).
    fn split_parameter(&self, u: u32, v: u32) -> (f64, VertexKind) {
        let (cu, cv) = (self.sharpest_corner(u), self.sharpest_corner(v));
        let midpoint = VertexKind::OnSegment {
            corner: NONE,
            shell: 0,
        };
        if cu.is_none() && cv.is_none() {
            return (0.5, midpoint);
        }
        let from_u = match (cu, cv) {
            (Some(a), Some(b)) => a >= b,
            (Some(_), None) => true,
            _ => false,
        };
        let (pu, pv) = (self.pt(u), self.pt(v));
        let length = ((pv[0] - pu[0]).powi(2) + (pv[1] - pu[1]).powi(2)).sqrt();
        // The power of two 2^k in [length/3, 2·length/3] (there is one: the interval spans a
        // factor of two), the nearest to the midpoint.
        let mut k = (length * 0.5).log2().round() as i32;
        while 2f64.powi(k) > length * (2.0 / 3.0) {
            k -= 1;
        }
        while 2f64.powi(k) < length / 3.0 {
            k += 1;
        }
        let d = 2f64.powi(k);
        if !(d.is_finite() && d > 0.0) {
            return (0.5, midpoint);
        }
        let (t, corner) = if from_u {
            (d / length, u)
        } else {
            (1.0 - d / length, v)
        };
        (t, VertexKind::OnSegment { corner, shell: k })
    }

    /// For an input vertex `x` where two segments meet at less than 90°: the cosine of the
    /// smallest such angle (larger is sharper). `None` for vertices inserted by refinement and
    /// for vertices whose segments meet at right or obtuse angles only. The smallest angle is
    /// between two segments consecutive around `x`, so one turn around it suffices.
    fn sharpest_corner(&self, x: u32) -> Option<f64> {
        if matches!(self.kinds[x as usize], VertexKind::OnSegment { .. }) {
            return None;
        }
        let mesh = &self.cdt.inserter.mesh;
        let o = mesh.point(x);
        let direction = |e: u32| {
            let p = mesh.point(mesh.dest(e));
            let d = [p[0] - o[0], p[1] - o[1]];
            let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
            [d[0] / length, d[1] / length]
        };
        let start = mesh.vertex_edge[x as usize];
        let (mut e, mut first, mut previous): (u32, Option<Point>, Option<Point>) =
            (start, None, None);
        let mut sharpest: Option<f64> = None;
        let mut consider = |a: Point, b: Point| {
            let cos = a[0] * b[0] + a[1] * b[1];
            if cos > 0.0 && sharpest.is_none_or(|s| cos > s) {
                sharpest = Some(cos);
            }
        };
        loop {
            if mesh.is_segment(e) {
                let d = direction(e);
                match previous {
                    Some(p) => consider(p, d),
                    None => first = Some(d),
                }
                previous = Some(d);
            }
            e = mesh.twin(prev(e));
            if e == start {
                break;
            }
        }
        if let (Some(a), Some(b)) = (first, previous) {
            if a != b {
                consider(b, a);
            }
        }
        sharpest
    }

    /// Splits the subsegment of half-edge `e`; returns whether it did. It does not when the
    /// pieces would be shorter than the floor, or when the rounded split point would fall on or
    /// beyond the line from an end to a vertex beside the subsegment (a vertex within rounding
    /// distance of it): the triangles made would be inverted. Such a subsegment is never tried
    /// again.
    fn split_segment(&mut self, e: u32) -> bool {
        let mesh = &self.cdt.inserter.mesh;
        let (u, v) = (mesh.origin(e), mesh.dest(e));
        let (t, kind) = self.split_parameter(u, v);
        let (pu, pv) = (self.pt(u), self.pt(v));
        let p = [pu[0] + t * (pv[0] - pu[0]), pu[1] + t * (pv[1] - pu[1])];
        let too_short =
            |q: Point, r: Point| (q[0] - r[0]).powi(2) + (q[1] - r[1]).powi(2) < self.floor2;
        let splits_cleanly = [e, mesh.twin(e)].iter().all(|&h| {
            let w = mesh.apex(h);
            let (a, b) = (mesh.point(mesh.origin(h)), mesh.point(mesh.dest(h)));
            w == GHOST
                || (P::orient2d(a, p, mesh.point(w)) > 0.0
                    && P::orient2d(p, b, mesh.point(w)) > 0.0)
        });
        if too_short(p, pu) || too_short(p, pv) || !splits_cleanly {
            self.unsplittable.insert((u.min(v), u.max(v)));
            self.skipped += 1;
            return false;
        }
        let vertex = self.new_vertex(p, kind, |attrs, i| {
            attrs[u as usize * i.1 + i.0]
                + t * (attrs[v as usize * i.1 + i.0] - attrs[u as usize * i.1 + i.0])
        });
        let _ = self.cdt.inserter.insert_at(vertex, Location::OnEdge(e));
        self.cdt.settle(vertex);
        self.after_insertion(vertex);
        true
    }

    /// Adds vertex `p` with attributes `attribute(attrs, (i, k))`.
    fn new_vertex(
        &mut self,
        p: Point,
        kind: VertexKind,
        attribute: impl Fn(&[f64], (usize, usize)) -> f64,
    ) -> u32 {
        let vertex = self.cdt.inserter.mesh.add_point(p);
        let k = self.attribute_count;
        for i in 0..k {
            let value = attribute(self.attributes, (i, k));
            self.attributes.push(value);
        }
        self.kinds.push(kind);
        self.report.steiner_points += 1;
        vertex
    }

    /// Queues what a new vertex may have spoiled: bad triangles around it, encroached segments.
    fn after_insertion(&mut self, vertex: u32) {
        let mesh = &self.cdt.inserter.mesh;
        let start = mesh.vertex_edge[vertex as usize];
        let mut around = Vec::new();
        let mut e = start;
        loop {
            around.push(e);
            e = mesh.twin(prev(e));
            if e == start {
                break;
            }
        }
        for e in around {
            let t = triangle_of(e);
            let opposite = next(e);
            if self.cdt.inserter.mesh.is_segment(opposite) {
                self.check_segment(opposite);
            }
            if self.cdt.inserter.mesh.is_segment(e) {
                self.check_segment(e);
            }
            if self.inside(t) {
                self.check_triangle(t);
            }
        }
    }

    /// Queues triangle `t` if it is bad.
    fn check_triangle(&mut self, t: u32) {
        let mesh = &self.cdt.inserter.mesh;
        let [a, b, c] = mesh.triangle(t);
        let [pa, pb, pc] = [a, b, c].map(|v| mesh.point(v));
        let area = 0.5 * P::orient2d(pa, pb, pc);
        let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let (lab, lbc, lca) = (sq(pa, pb), sq(pb, pc), sq(pc, pa));
        // The shortest edge (u, v), its opposite corner, and the squared lengths of the others.
        let (apex, u, v, l1, l2) = if lab <= lbc && lab <= lca {
            (c, a, b, lca, lbc)
        } else if lbc <= lca {
            (a, b, c, lab, lca)
        } else {
            (b, c, a, lbc, lab)
        };
        let shortest = lab.min(lbc).min(lca);
        // Angle: the smallest angle is the one opposite the shortest edge; compared through cos².
        let skinny = self.cos2_min_angle <= 1.0 && {
            let (o, p, q) = (mesh.point(apex), mesh.point(u), mesh.point(v));
            let dot = (p[0] - o[0]) * (q[0] - o[0]) + (p[1] - o[1]) * (q[1] - o[1]);
            let cos2 = if dot > 0.0 {
                dot * dot / (l1 * l2)
            } else {
                0.0
            };
            cos2 > self.cos2_min_angle && !self.is_excused_by_small_input_angle(u, v)
        };
        let bad = skinny || {
            let regional = if self.quality.variable_area {
                self.domain
                    .max_area
                    .get(mesh.tag[t as usize] as usize)
                    .copied()
                    .unwrap_or(-1.0)
            } else {
                -1.0
            };
            let too_big = self.quality.max_area.is_some_and(|m| area > m)
                || (regional > 0.0 && area > regional);
            too_big
                || self
                    .quality
                    .user_test
                    .is_some_and(|f| f(pa[0], pa[1], pb[0], pb[1], pc[0], pc[1], area))
        };
        if bad {
            let bucket = if skinny {
                BadQueue::skinny_bucket(shortest / self.extent2)
            } else {
                BadQueue::SIZE_BUCKET
            };
            self.bad.push(BadTriangle {
                bucket,
                corners: [a, b, c],
            });
        }
    }

    /// Whether a skinny triangle whose shortest edge is `u`–`v` is excused from splitting by
    /// Triangle's rule for small input angles (its manual on `-q`; Shewchuk 2002, §3.6; the
    /// "seditious edges" of Shewchuk 2000, "Mesh generation for domains with small angles"): `u`
    /// and `v` were put by refinement on two different segments that meet at a common vertex (a
    /// shared endpoint or their crossing) at less than θ, at equal distances from it. That is
    /// what concentric-shell splitting makes around a small input angle; splitting such a
    /// triangle would only cut the angle into ever smaller slivers. Nothing else is excused: a
    /// skinny triangle at an input angle whose sides along the two segments differ gets split,
    /// its split point encroaches the longer side, which is split on a shell until the excused
    /// configuration is reached (Ruppert 1995, §5).
    fn is_excused_by_small_input_angle(&self, u: u32, v: u32) -> bool {
        let (
            VertexKind::OnSegment {
                corner: cu,
                shell: su,
            },
            VertexKind::OnSegment {
                corner: cv,
                shell: sv,
            },
        ) = (self.kinds[u as usize], self.kinds[v as usize])
        else {
            return false;
        };
        let (p, q) = (self.pt(u), self.pt(v));
        // Two segments meeting at `o` at less than θ (which also tells the two segments apart:
        // pieces of one segment on either side of `o` meet at 180°). Around a wider corner the
        // shells need no excuse: the triangles between them can be split (measured on
        // Triangle's behaviour, which refines them too).
        let narrow = |o: Point| {
            let (a, b) = ([p[0] - o[0], p[1] - o[1]], [q[0] - o[0], q[1] - o[1]]);
            let dot = a[0] * b[0] + a[1] * b[1];
            let (dp, dq) = (a[0] * a[0] + a[1] * a[1], b[0] * b[0] + b[1] * b[1]);
            dot > 0.0 && dot * dot > self.cos2_min_angle * dp * dq
        };
        // Both on the same concentric shell around the same corner: the distances are the same
        // power of two by construction, whatever the rounding of the points.
        if cu == cv && cu != NONE && su == sv {
            return narrow(self.pt(cu));
        }
        // Otherwise (midpoints, or shells around different corners), the common vertex of the
        // two segments as given, and equal distances within rounding.
        let (Some(segment_u), Some(segment_v)) = (self.segment_through(u), self.segment_through(v))
        else {
            return false;
        };
        let (ends_u, ends_v) = (
            self.cdt.ends[segment_u as usize],
            self.cdt.ends[segment_v as usize],
        );
        if segment_u == segment_v || ends_u.0 == NONE || ends_v.0 == NONE {
            return false;
        }
        let common = [ends_u.0, ends_u.1]
            .into_iter()
            .find(|&w| w == ends_v.0 || w == ends_v.1)
            .map(|w| self.pt(w))
            .or_else(|| {
                crossing_point(
                    [ends_u.0, ends_u.1].map(|w| self.pt(w)),
                    [ends_v.0, ends_v.1].map(|w| self.pt(w)),
                )
            });
        let Some(o) = common else {
            return false;
        };
        let distance = |x: Point| (x[0] - o[0]).hypot(x[1] - o[1]);
        let (dp, dq) = (distance(p), distance(q));
        (dp - dq).abs() <= EQUAL_DISTANCE_TOLERANCE * dp.max(dq) && narrow(o)
    }

    /// The id of a segment that vertex `v` lies on, if any.
    fn segment_through(&self, v: u32) -> Option<u32> {
        let mesh = &self.cdt.inserter.mesh;
        let start = mesh.vertex_edge[v as usize];
        let mut e = start;
        loop {
            if mesh.is_segment(e) {
                return Some(mesh.segment_of(e));
            }
            e = mesh.twin(prev(e));
            if e == start {
                return None;
            }
        }
    }

    /// The point where a bad triangle is split: its circumcentre, or Üngör's off-centre on the
    /// bisector of its shortest edge when that is nearer to the edge. Also its affine frame
    /// coordinates in the triangle, for interpolating attributes.
    fn split_point(&self, corners: [u32; 3]) -> (Point, f64, f64) {
        let [a, b, c] = corners.map(|v| self.pt(v));
        let (centre, xi, eta) = circumcenter(a, b, c);
        if !self.off_center.is_finite() {
            return (centre, xi, eta);
        }
        let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
        let (p, q) = if sq(a, b) <= sq(b, c) && sq(a, b) <= sq(c, a) {
            (a, b)
        } else if sq(b, c) <= sq(c, a) {
            (b, c)
        } else {
            (c, a)
        };
        let mid = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
        // The bisector toward the triangle (left of p→q, the counter-clockwise side).
        let normal = [-(q[1] - p[1]), q[0] - p[0]];
        let off = [
            mid[0] + self.off_center * normal[0],
            mid[1] + self.off_center * normal[1],
        ];
        if sq(off, mid) < sq(centre, mid) {
            // Frame coordinates of the off-centre in triangle (a, b, c).
            let det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            let (dx, dy) = (off[0] - a[0], off[1] - a[1]);
            let xi = (dx * (c[1] - a[1]) - dy * (c[0] - a[0])) / det;
            let eta = ((b[0] - a[0]) * dy - (b[1] - a[1]) * dx) / det;
            (off, xi, eta)
        } else {
            (centre, xi, eta)
        }
    }

    fn split_triangle(&mut self, t: u32, bad: BadTriangle) {
        let corners = self.cdt.inserter.mesh.triangle(t);
        let (x, xi, eta) = self.split_point(corners);
        if !(x[0].is_finite() && x[1].is_finite()) {
            return;
        }
        match self.walk(t, x) {
            Walk::Lost => self.skipped += 1,
            Walk::Blocked(s) => {
                // A segment hides the new point from the triangle: the point may not be
                // inserted, and the segment is split instead (Ruppert's rule; with lenses the
                // point need not lie in its diametral circle).
                let mesh = &self.cdt.inserter.mesh;
                let segment = (mesh.origin(s), mesh.dest(s), s);
                self.split_instead(&[segment], bad);
            }
            Walk::Found(location) => {
                if let Location::OnVertex(_) = location {
                    self.skipped += 1; // precision exhausted here
                    return;
                }
                let mut encroached = self.encroached_by(x, location);
                // Subsegments that `Y`/`YY` keep whole cannot be protected by splitting them:
                // the point goes in all the same if it makes no triangle worse than the bad one
                // (else the triangles along such a boundary could never improve), and the mesh
                // stays constrained Delaunay.
                let kept_whole = encroached.iter().any(|&(_, _, e)| !self.may_split(e));
                encroached.retain(|&(_, _, e)| self.may_split(e));
                if !encroached.is_empty() {
                    self.split_instead(&encroached, bad);
                    return;
                }
                if kept_whole
                    && self.worst_triangle_made(x) < min_angle_sin2(corners.map(|v| self.pt(v)))
                {
                    self.kept_whole += 1;
                    return;
                }
                if self.too_close(x, location) {
                    self.skipped += 1;
                    return;
                }
                let [a, b, c] = corners;
                let vertex = self.new_vertex(x, VertexKind::Free, |attrs, (i, k)| {
                    let (va, vb, vc) = (
                        attrs[a as usize * k + i],
                        attrs[b as usize * k + i],
                        attrs[c as usize * k + i],
                    );
                    va + xi * (vb - va) + eta * (vc - va)
                });
                let _ = self.cdt.inserter.insert_at(vertex, location);
                self.after_insertion(vertex);
            }
        }
    }

    /// Splits the given subsegments (`(origin, dest, half-edge)`) instead of a bad triangle whose
    /// split point encroaches on them, and queues the triangle again to be reconsidered. Only if
    /// some subsegment was split: otherwise the triangle is left as it is, so that every time a
    /// triangle is queued again refinement has made progress.
    fn split_instead(&mut self, subsegments: &[(u32, u32, u32)], bad: BadTriangle) {
        for &(u, v, e) in subsegments {
            if self.may_split(e) && !self.unsplittable.contains(&(u.min(v), u.max(v))) {
                self.encroached.push_back((u, v, true));
            }
        }
        if self.split_encroached() > 0 {
            self.bad.push(bad);
        } else if subsegments.iter().all(|&(_, _, e)| !self.may_split(e)) {
            self.kept_whole += 1;
        } else {
            self.skipped += 1;
        }
    }

    /// Whether `x`, at `location`, would make an edge shorter than the floor.
    fn too_close(&self, x: Point, location: Location) -> bool {
        let mesh = &self.cdt.inserter.mesh;
        let triangles = match location {
            Location::InTriangle(t) | Location::Outside(t) => [t, t],
            Location::OnEdge(e) => [triangle_of(e), triangle_of(mesh.twin(e))],
            Location::OnVertex(_) => return true,
        };
        triangles
            .iter()
            .flat_map(|&t| mesh.triangle(t))
            .filter(|&v| v != GHOST)
            .any(|v| {
                let p = mesh.point(v);
                (p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2) < self.floor2
            })
    }

    /// Walks in a straight line from the centroid of triangle `t` to `x`, staying in the domain.
    fn walk(&self, t: u32, x: Point) -> Walk {
        let mesh = &self.cdt.inserter.mesh;
        let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
        let g = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
        let mut t = t;
        let mut entry = NONE;
        for _ in 0..mesh.triangle_count() + 3 {
            // The edge through which the ray g→x leaves t (u right of the ray, v left of it).
            let mut exit = NONE;
            for e in 3 * t..3 * t + 3 {
                if e == entry {
                    continue;
                }
                let (u, v) = (mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)));
                if P::orient2d(g, x, u) <= 0.0 && P::orient2d(g, x, v) > 0.0 {
                    exit = e;
                    break;
                }
            }
            if exit == NONE {
                // No edge crosses the ray: it is too short to have a direction (x is the
                // centroid, as for an equilateral triangle's circumcentre), or degenerate.
                return self.walk_ends_in(t, x).unwrap_or(Walk::Lost);
            }
            let (u, v) = (mesh.point(mesh.origin(exit)), mesh.point(mesh.dest(exit)));
            let side = P::orient2d(u, v, x);
            if side > 0.0 {
                return Walk::Found(Location::InTriangle(t));
            }
            if side == 0.0 {
                // On the exit edge (or its line beyond the triangle, which the ray rules out).
                if mesh.is_segment(exit) {
                    return Walk::Blocked(exit);
                }
                for w in [mesh.origin(exit), mesh.dest(exit)] {
                    if mesh.point(w) == x {
                        return Walk::Found(Location::OnVertex(w));
                    }
                }
                return Walk::Found(Location::OnEdge(exit));
            }
            if mesh.is_segment(exit) {
                return Walk::Blocked(exit);
            }
            let f = mesh.twin(exit);
            let next_t = triangle_of(f);
            if !self.inside(next_t) || mesh.is_ghost(next_t) {
                return Walk::Lost;
            }
            t = next_t;
            entry = f;
        }
        Walk::Lost
    }

    /// Where `x` lies in triangle `t`, if it lies in it (closed): in it, on an edge (a segment
    /// hides nothing then, but a point on a segment splits it: `Blocked`), or on a vertex.
    fn walk_ends_in(&self, t: u32, x: Point) -> Option<Walk> {
        let mesh = &self.cdt.inserter.mesh;
        let sides = [0, 1, 2].map(|i| {
            let e = 3 * t + i;
            P::orient2d(mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)), x)
        });
        if sides.iter().any(|&side| side < 0.0) {
            return None;
        }
        let on: Vec<u32> = (0..3)
            .filter(|&i| sides[i as usize] == 0.0)
            .map(|i| 3 * t + i)
            .collect();
        Some(match on[..] {
            [] => Walk::Found(Location::InTriangle(t)),
            [e] if mesh.is_segment(e) => Walk::Blocked(e),
            [e] => Walk::Found(Location::OnEdge(e)),
            // On two edges: at their common corner.
            _ => mesh
                .triangle(t)
                .into_iter()
                .find(|&w| mesh.point(w) == x)
                .map_or(Walk::Lost, |w| Walk::Found(Location::OnVertex(w))),
        })
    }

    /// The subsegments that `x` would encroach if inserted at `location`: those bounding the
    /// triangles whose circumcircles contain `x` (the Bowyer–Watson cavity, which does not cross
    /// segments), with `x` inside their diametral circles.
    fn encroached_by(&mut self, x: Point, location: Location) -> Vec<(u32, u32, u32)> {
        let mut stack = std::mem::take(&mut self.cavity_stack);
        let mut seen = std::mem::take(&mut self.cavity);
        stack.clear();
        seen.clear();
        let mesh = &self.cdt.inserter.mesh;
        match location {
            Location::InTriangle(t) | Location::Outside(t) => stack.push(t),
            Location::OnEdge(e) => {
                stack.extend_from_slice(&[triangle_of(e), triangle_of(mesh.twin(e))])
            }
            Location::OnVertex(_) => {}
        }
        seen.extend_from_slice(&stack);
        let mut found = Vec::new();
        while let Some(t) = stack.pop() {
            for e in 3 * t..3 * t + 3 {
                if mesh.is_segment(e) {
                    let (u, v) = (mesh.origin(e), mesh.dest(e));
                    if self.encroaches(u, v, x)
                        && !found
                            .iter()
                            .any(|&(a, b, _)| (a, b) == (u, v) || (a, b) == (v, u))
                    {
                        found.push((u, v, e));
                    }
                    continue;
                }
                let n = triangle_of(mesh.twin(e));
                if seen.contains(&n) || !self.inside(n) || mesh.is_ghost(n) {
                    continue;
                }
                let [a, b, c] = mesh.triangle(n).map(|v| mesh.point(v));
                if P::incircle(a, b, c, x) > 0.0 {
                    seen.push(n);
                    stack.push(n);
                }
            }
        }
        self.cavity_stack = stack;
        self.cavity = seen;
        found
    }

    /// The quality ([`min_angle_sin2`]) of the worst triangle that inserting `x` makes: `x`
    /// joined to the edges around the cavity that [`Self::encroached_by`] found for it.
    fn worst_triangle_made(&self, x: Point) -> f64 {
        let mesh = &self.cdt.inserter.mesh;
        let mut worst = f64::INFINITY;
        for &t in &self.cavity {
            for e in 3 * t..3 * t + 3 {
                if !mesh.is_segment(e) && self.cavity.contains(&triangle_of(mesh.twin(e))) {
                    continue;
                }
                worst = worst.min(min_angle_sin2([
                    mesh.point(mesh.origin(e)),
                    mesh.point(mesh.dest(e)),
                    x,
                ]));
            }
        }
        worst
    }
}

/// Where segments `a` and `b` cross (in floating point), if they do.
fn crossing_point(a: [Point; 2], b: [Point; 2]) -> Option<Point> {
    let d = [a[1][0] - a[0][0], a[1][1] - a[0][1]];
    let e = [b[1][0] - b[0][0], b[1][1] - b[0][1]];
    let denominator = d[0] * e[1] - d[1] * e[0];
    if denominator == 0.0 {
        return None;
    }
    let f = [b[0][0] - a[0][0], b[0][1] - a[0][1]];
    let s = (f[0] * e[1] - f[1] * e[0]) / denominator;
    let t = (f[0] * d[1] - f[1] * d[0]) / denominator;
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t))
        .then(|| [a[0][0] + s * d[0], a[0][1] + s * d[1]])
}

/// The squared sine of the smallest angle of triangle (a, b, c), which grows with that angle
/// (at most 60°): twice the area over the product of the two longest edges is the sine of the
/// angle between them, the one opposite the shortest edge.
fn min_angle_sin2([a, b, c]: [Point; 3]) -> f64 {
    let sq = |p: Point, q: Point| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2);
    let (ab, bc, ca) = (sq(a, b), sq(b, c), sq(c, a));
    let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let longest_two = ab * bc * ca / ab.min(bc).min(ca);
    if longest_two > 0.0 {
        cross * cross / longest_two
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use crate::data::{Hooks, Input, Output};
    use crate::options::{Options, SwitchSource};
    use crate::pipeline::triangulate;

    fn mesh(switches: &str, points: &[f64], segments: &[i32]) -> Output {
        let options = Options::parse(switches, SwitchSource::Library).unwrap();
        let input = Input {
            points,
            segments,
            ..Input::default()
        };
        triangulate(&options, &input, &Hooks::default()).unwrap().0
    }

    fn smallest_angle(out: &Output) -> f64 {
        let p = out.points.as_ref().unwrap();
        let pt = |v: i32| [p[2 * v as usize], p[2 * v as usize + 1]];
        let mut smallest = 180.0f64;
        for t in out.triangles.as_ref().unwrap().chunks(3) {
            for i in 0..3 {
                let (a, b, c) = (pt(t[i]), pt(t[(i + 1) % 3]), pt(t[(i + 2) % 3]));
                let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
                let angle = (u[0] * v[1] - u[1] * v[0])
                    .abs()
                    .atan2(u[0] * v[0] + u[1] * v[1])
                    .to_degrees();
                smallest = smallest.min(angle);
            }
        }
        smallest
    }

    const SQUARE: [f64; 8] = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    const SQUARE_SEGMENTS: [i32; 8] = [0, 1, 1, 2, 2, 3, 3, 0];
    /// An outline with a notch and a crossbar meeting a slanted stroke.
    const SHAPE: [f64; 18] = [
        0.0, 0.0, 1.0, 0.0, 1.2, 2.0, 1.4, 0.0, 2.4, 0.0, 1.6, 3.0, 0.8, 3.0, 1.1, 1.0, 1.3, 1.0,
    ];
    const SHAPE_SEGMENTS: [i32; 18] = [0, 1, 1, 7, 7, 8, 8, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 0];

    #[test]
    fn area_bound_holds() {
        let out = mesh("pza0.01Q", &SQUARE, &SQUARE_SEGMENTS);
        assert!(out.triangle_count >= 100, "{}", out.triangle_count);
    }

    #[test]
    fn angle_bound_holds_up_to_the_guaranteed_angle_and_beyond() {
        for angle in [20.0, 25.0, 28.6, 30.0, 33.0] {
            let out = mesh(&format!("pzq{angle}Q"), &SHAPE, &SHAPE_SEGMENTS);
            assert!(
                smallest_angle(&out) >= angle - 1e-9,
                "q{angle}: {}",
                smallest_angle(&out)
            );
            assert!(out.warnings.is_empty(), "{:?}", out.warnings);
        }
    }

    #[test]
    fn too_large_an_angle_stops_with_a_warning() {
        let out = mesh("pzq45Q", &SHAPE, &SHAPE_SEGMENTS);
        assert!(
            out.triangle_count > 20 && out.triangle_count < 10_000,
            "{}",
            out.triangle_count
        );
        assert!(
            out.warnings
                .iter()
                .any(|w| w.contains("guaranteed to terminate")),
            "{:?}",
            out.warnings
        );
    }
}
