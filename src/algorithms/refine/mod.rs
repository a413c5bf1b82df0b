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
use crate::mesh::raw::{next, prev, triangle_of, GHOST, NONE};
use crate::mesh::{EdgeId, TriangleId, VertexId, OUTSIDE};

// The parts: this file is the driver (strategy above the guaranteed angle, budgets, the runaway
// limit, cancel and progress, snapping, the refinement loop, insertion bookkeeping).
mod queue; // the bad-triangle queue
mod segments; // encroachment and where subsegments are split
#[cfg(test)]
mod tests;
mod triangles; // bad triangles, split points, Ruppert's rejection rule

use queue::{BadQueue, BadTriangle};

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
        for p in cdt.mesh().points() {
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
        self.cdt.mesh().raw().point(v)
    }

    fn inside(&self, t: u32) -> bool {
        self.cdt.mesh().raw().tag(t) != OUTSIDE
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
        (0..self.cdt.mesh().raw().triangle_count())
            .filter(|&t| self.inside(t))
            .count() as u64
    }

    /// About how many vertices the area bounds (global, regional, per triangle) ask for: four
    /// times the number of triangles of the largest allowed areas that cover the domain.
    fn size_estimate(&self) -> u64 {
        let mesh = self.cdt.mesh().raw();
        let triangles: f64 = (0..mesh.triangle_count())
            .filter(|&t| self.inside(t))
            .map(|t| {
                let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
                let area = 0.5 * P::orient2d(a, b, c);
                let regional = if self.quality.variable_area {
                    self.domain
                        .max_area
                        .get(mesh.tag(t) as usize)
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
        let mesh = self.cdt.mesh().raw();
        // One half-edge per subsegment: the flip looks at the vertices on both sides.
        let mut work: Vec<u32> = (0..mesh.edge_count())
            .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
            .collect();
        while let Some(e) = work.pop() {
            let mesh = self.cdt.mesh().raw();
            let (u, v) = (mesh.origin(e), mesh.dest(e));
            if !mesh.is_segment(e) {
                continue;
            }
            if let Some(w) = self
                .cdt
                .flip_edge_onto_vertex(EdgeId::new(e), on_segment)
                .map(VertexId::raw)
            {
                let mesh = self.cdt.mesh().raw();
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
        let mesh = self.cdt.mesh().raw();
        let segments: Vec<u32> = (0..mesh.edge_count())
            .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
            .collect();
        for e in segments {
            self.check_segment(e);
        }
        self.split_encroached();
        self.bad.clear();
        for t in 0..self.cdt.mesh().raw().triangle_count() {
            if self.inside(t) {
                self.check_triangle(t);
            }
        }
        while !self.should_stop() {
            let Some(bad) = self.bad.pop() else { break };
            let [a, b, c] = bad.corners;
            let Some(e) = self.cdt.mesh().raw().find_edge(a, b) else {
                continue;
            };
            if self.cdt.mesh().raw().apex(e) != c {
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

    /// Adds vertex `p` with attributes `attribute(attrs, (i, k))`.
    fn new_vertex(
        &mut self,
        p: Point,
        kind: VertexKind,
        attribute: impl Fn(&[f64], (usize, usize)) -> f64,
    ) -> u32 {
        let vertex = self.cdt.add_point(p).raw();
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
        let mesh = self.cdt.mesh().raw();
        let start = mesh.vertex_edge(vertex);
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
            if self.cdt.mesh().raw().is_segment(opposite) {
                self.check_segment(opposite);
            }
            if self.cdt.mesh().raw().is_segment(e) {
                self.check_segment(e);
            }
            if self.inside(t) {
                self.check_triangle(t);
            }
        }
    }
}
