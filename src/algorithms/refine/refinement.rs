//! The refinement loop: encroached subsegments are split first, then bad triangles, worst first,
//! until none is left or a limit stops it; a split point that would encroach a subsegment is
//! rejected and the subsegment split instead (Ruppert's rule). It owns what a refinement
//! changes — the constrained triangulation (borrowed), the vertices' kinds and attributes, the
//! counts of what it made and left — and the queues.

use std::collections::{HashSet, VecDeque};

use super::attributes::Attributes;
use super::deletion::DiskWalk;
#[cfg(doc)]
use super::encroachment::{splits_faithfully, NEGLIGIBLE_SLIVER};
use super::encroachment::{Cavity, Encroachment, BOUNDARY_SLIVER, GRID_SLIVER};
use super::polling::Polling;
use super::queue::{BadQueue, BadTriangle, QueueOrder};
use super::split_point::AngleBound;
use super::walk::{walk, Walk};

mod improvement; // `Refinement::improve`: decimation, smoothing and polish of the finished mesh
mod sliding; // `Refinement::try_sliding`: a vertex on a segment moved along it
mod subsegments; // encroached subsegments and their splits
use super::{area_bound, inside, Quality, VertexKind};
use crate::algorithms::constrain::Constrainer;
use crate::algorithms::delaunay::Location;
use crate::algorithms::domain::Domain;
use crate::geometry::{frame_coordinates, min_angle_sin2, Grid, Point, Predicates};
use crate::mesh::{EdgeId, Mesh, TriangleId, VertexId, GHOST, NONE};

/// What a refinement works toward, and at what resolution: fixed for all its runs.
pub(super) struct Settings<'r, 'q> {
    pub(super) domain: &'r Domain,
    pub(super) quality: &'r Quality<'q>,
    /// `D`: encroachment by diametral circles, so that the result is truly Delaunay.
    pub(super) conforming: bool,
    /// No edge is made shorter than this (squared): a few units in the last place of the largest
    /// coordinate.
    pub(super) floor2: f64,
    /// A rounded split point may always cut this much (twice the area) off the domain or add it
    /// ([`splits_faithfully`]): [`NEGLIGIBLE_SLIVER`] of the domain.
    pub(super) negligible_sliver: f64,
    /// The domain's extent, squared (the scale of the bad-triangle queue).
    pub(super) extent2: f64,
}

/// How a run of [`Refinement::run`] ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum RunEnd {
    /// No subsegment is encroached and no triangle is bad.
    Finished,
    /// The caller cancelled.
    Cancelled,
    /// The run's limit of Steiner points is reached.
    AtLimit,
}

/// What refinement made and left, for its report.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Tally {
    pub(super) steiner_points: u64,
    /// Bad triangles and segments left alone because splitting them would make too short an edge.
    pub(super) skipped: u64,
    /// Bad triangles left alone because splitting them needs a vertex on a segment that `Y`/`YY`
    /// keep whole.
    pub(super) kept_whole: u64,
}

/// A queued subsegment to split: its ends, the half-edge from `u` to `v` when it was queued
/// (it may be gone by the time it is taken out, and the slot reused), and whether a rejected
/// point encroached it (split regardless).
#[derive(Clone, Copy, Debug)]
struct Encroached {
    u: VertexId,
    v: VertexId,
    edge: EdgeId,
    forced: bool,
}

/// How the insertion of a lattice point went ([`Refinement::insert_seed`]).
pub(super) enum Seeded {
    Inserted(VertexId),
    /// Not inserted: not found in a domain triangle of its tag, or too close to a vertex.
    Skipped,
    /// The caller cancelled: refinement stops.
    Stop,
}

/// A refinement's state kept aside, to be exchanged with the live one
/// ([`Refinement::exchange`]).
pub(super) struct Aside<P: Predicates> {
    cdt: Constrainer<P>,
    attributes: Vec<f64>,
    kinds: Vec<VertexKind>,
    tally: Tally,
    unsplittable: HashSet<(VertexId, VertexId)>,
}

impl<P: Predicates> Aside<P> {
    pub(super) fn steiner_points(&self) -> u64 {
        self.tally.steiner_points
    }
}

/// A Delaunay refinement of a constrained triangulation's domain.
pub(super) struct Refinement<'r, 'q, P: Predicates> {
    cdt: &'r mut Constrainer<P>,
    attributes: Attributes<'r>,
    /// Per vertex.
    kinds: Vec<VertexKind>,
    settings: Settings<'r, 'q>,
    polling: Polling<'q>,
    angle: AngleBound,
    encroachment: Encroachment,
    /// Subsegments to split, first in first out.
    encroached: VecDeque<Encroached>,
    bad: BadQueue,
    /// The order of the skinny triangles in `bad`.
    order: QueueOrder,
    cavity: Cavity,
    /// The walk that finds the free vertices deleted before a subsegment is split.
    disk: DiskWalk,
    /// Subsegments (ends, smaller first) found unsplittable: never tried again.
    unsplittable: HashSet<(VertexId, VertexId)>,
    tally: Tally,
    /// New vertices made in all runs, of every state (the progress reported: it never goes
    /// back when an earlier state is taken up again by [`Self::exchange`]).
    work: u64,
    /// Where the current run stops.
    limit: Option<u64>,
    /// Scratch space: the half-edges around a new vertex.
    around: Vec<EdgeId>,
    /// Scratch space of the improvement, reused from vertex to vertex.
    improving: improvement::Scratch,
    /// Whether new points are rounded to the caller's grid ([`Quality::caller_grid`]) as they
    /// are made: after the mesh was moved onto it.
    on_caller_grid: bool,
}

impl<'r, 'q, P: Predicates> Refinement<'r, 'q, P> {
    /// A refinement of `cdt`'s domain (its triangles outside the domain are tagged [`OUTSIDE`]
    /// (crate::mesh::OUTSIDE)) toward the quality's angle; `kinds` and `attributes` per vertex.
    pub(super) fn new(
        cdt: &'r mut Constrainer<P>,
        attributes: Attributes<'r>,
        kinds: Vec<VertexKind>,
        settings: Settings<'r, 'q>,
        polling: Polling<'q>,
    ) -> Self {
        let degrees = settings.quality.min_angle.unwrap_or(0.0);
        Refinement {
            cdt,
            attributes,
            kinds,
            angle: AngleBound::new(degrees),
            encroachment: Encroachment::new(degrees, settings.conforming),
            settings,
            polling,
            encroached: VecDeque::new(),
            bad: BadQueue::new(),
            order: QueueOrder::ShortestEdge,
            cavity: Cavity::default(),
            disk: DiskWalk::default(),
            unsplittable: HashSet::new(),
            tally: Tally::default(),
            work: 0,
            limit: None,
            around: Vec::new(),
            improving: improvement::Scratch::default(),
            on_caller_grid: false,
        }
    }

    pub(super) fn mesh(&self) -> &Mesh {
        self.cdt.mesh()
    }

    /// New vertices made in all runs (see the field).
    pub(super) fn work(&self) -> u64 {
        self.work
    }

    pub(super) fn tally(&self) -> Tally {
        self.tally
    }

    /// Forgets the bad triangles counted as kept whole (before a run that checks every triangle
    /// again and counts those still left).
    pub(super) fn forget_kept_whole(&mut self) {
        self.tally.kept_whole = 0;
    }

    /// Sets the order of the skinny triangles in the queue (for the runs that follow: it is
    /// empty between runs after an [`Self::exchange`], or before the first).
    pub(super) fn set_order(&mut self, order: QueueOrder) {
        self.order = order;
    }

    /// Sets the angle bound θ (degrees): the bad-angle test, the lens and the off-centre.
    /// The sine squared of the angle bound (0 for none).
    pub(super) fn angle_sin2(&self) -> f64 {
        self.angle.sin2()
    }

    pub(super) fn set_angle(&mut self, degrees: f64) {
        self.angle = AngleBound::new(degrees);
        self.encroachment = Encroachment::new(degrees, self.settings.conforming);
    }

    /// Moves the mesh onto the caller's grid ([`Quality::caller_grid`]) and rounds every later
    /// new point to it; returns whether the mesh could be moved (else it is left as it is).
    pub(super) fn move_onto_caller_grid(&mut self) -> bool {
        let Some(caller) = self.settings.quality.caller_grid else {
            return true;
        };
        let moved = self.cdt.move_onto_grid(caller.grid);
        self.on_caller_grid = moved;
        moved
    }

    /// How much of the triangle beside a boundary subsegment a rounded split point may cut off
    /// or add ([`splits_faithfully`]): [`BOUNDARY_SLIVER`], or [`GRID_SLIVER`] on the caller's
    /// grid in a translated frame.
    fn largest_sliver(&self) -> f64 {
        if self.on_caller_grid {
            GRID_SLIVER
        } else {
            BOUNDARY_SLIVER
        }
    }

    /// The caller's grid once the mesh is on it.
    fn grid(&self) -> Option<&'q dyn Grid> {
        let caller = self.settings.quality.caller_grid?;
        self.on_caller_grid.then_some(caller.grid)
    }

    /// `p` rounded to the caller's grid once the mesh is on it, else `p`.
    fn placed(&self, p: Point) -> Point {
        self.grid().map_or(p, |grid| grid.round(p))
    }

    /// A copy of the state, to [`Self::exchange`] with later.
    pub(super) fn copy_aside(&self) -> Aside<P> {
        Aside {
            cdt: self.cdt.clone(),
            attributes: self.attributes.to_vec(),
            kinds: self.kinds.clone(),
            tally: self.tally,
            unsplittable: self.unsplittable.clone(),
        }
    }

    /// Exchanges the state with the one `aside` holds (moves, no copy), and empties the queues:
    /// the next run finds what is left to do from the mesh.
    pub(super) fn exchange(&mut self, aside: &mut Aside<P>) {
        std::mem::swap(self.cdt, &mut aside.cdt);
        self.attributes.swap(&mut aside.attributes);
        std::mem::swap(&mut self.kinds, &mut aside.kinds);
        std::mem::swap(&mut self.tally, &mut aside.tally);
        std::mem::swap(&mut self.unsplittable, &mut aside.unsplittable);
        self.encroached.clear();
        self.bad.clear();
    }

    /// Refines until no subsegment is encroached and no triangle is bad, or `limit` Steiner
    /// points are made in all, or the caller cancels.
    pub(super) fn run(&mut self, limit: Option<u64>) -> RunEnd {
        self.limit = limit;
        self.refine_all();
        if self.polling.cancelled() {
            RunEnd::Cancelled
        } else if self.bad.is_empty() && self.encroached.is_empty() {
            RunEnd::Finished
        } else {
            RunEnd::AtLimit
        }
    }

    /// Splits encroached subsegments, then bad triangles, until none is left or a limit stops.
    fn refine_all(&mut self) {
        let mesh = self.mesh();
        let segments: Vec<EdgeId> = mesh
            .edges()
            .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
            .collect();
        for e in segments {
            self.check_segment(e);
        }
        self.split_encroached();
        self.bad.clear();
        for t in self.mesh().triangles() {
            if inside(self.mesh(), t) {
                self.check_triangle(t);
            }
        }
        while !self.should_stop() {
            let Some(bad) = self.bad.pop() else { break };
            let Some(t) = self.still_there(bad) else {
                continue; // gone since it was queued
            };
            self.split_triangle(t, bad);
            self.split_encroached();
        }
    }

    /// The triangle a queued bad triangle is now, if it is still there: mostly in the slot it
    /// was queued from (one look, where finding the edge takes a turn around a vertex).
    fn still_there(&self, bad: BadTriangle) -> Option<TriangleId> {
        let mesh = self.mesh();
        if bad.slot.raw() < mesh.triangle_count() && mesh.triangle(bad.slot) == bad.corners {
            return Some(bad.slot);
        }
        let [a, b, c] = bad.corners;
        let e = mesh.find_edge(a, b)?;
        (mesh.apex(e) == c).then_some(e.triangle())
    }

    /// Whether to stop: the caller cancelled (polled now and then), or the limit is reached.
    fn should_stop(&mut self) -> bool {
        let done = self.tally.steiner_points;
        let (bad, encroached) = (&self.bad, &self.encroached);
        if self
            .polling
            .poll(self.work, || bad.len() + encroached.len())
        {
            return true;
        }
        self.limit.is_some_and(|limit| done >= limit)
    }

    /// Drops the deleted vertices from the mesh, the kinds and the attributes, the others
    /// renumbered in order (input vertices come first and keep their numbers): for the end of
    /// refinement, when no queue or state aside holds vertex ids.
    pub(super) fn drop_deleted_vertices(&mut self) {
        if !self.kinds.contains(&VertexKind::Deleted) {
            return;
        }
        let kinds = &self.kinds;
        let new_id = self
            .cdt
            .remove_vertices(|v| kinds[v.index()] != VertexKind::Deleted);
        self.attributes.retain_rows(|v| new_id[v] != NONE);
        self.kinds.retain(|&kind| kind != VertexKind::Deleted);
    }

    /// Queues triangle `t` if it is bad: skinny, too big, or so by the user's test.
    /// What the finished mesh leaves of the bounds: its bad triangles (skinny, too big or
    /// unsuitable, as [`Self::check_triangle`] judges them) and, with `D`, its encroached
    /// subsegments. A split refused where the doubles could not hold it need not leave any
    /// (another split may have mended the triangle since): the warning counts these.
    pub(super) fn unmet_bounds(&self) -> u64 {
        let mesh = self.mesh();
        let bad = mesh
            .triangles()
            .filter(|&t| inside(mesh, t))
            .filter(|&t| {
                let corners = mesh.triangle(t);
                let points = corners.map(|v| mesh.point(v));
                self.angle
                    .skinny(mesh, &self.kinds, &self.cdt.ends, corners, points)
                    .is_some()
                    || self.too_big(t, points)
            })
            .count() as u64;
        let encroached = if self.settings.conforming {
            mesh.edges()
                .filter(|&e| mesh.is_segment(e) && e < mesh.twin(e))
                .filter(|&e| self.encroachment.apex_encroaches(mesh, e))
                .count() as u64
        } else {
            0
        };
        bad + encroached
    }

    fn check_triangle(&mut self, t: TriangleId) {
        let mesh = self.mesh();
        let corners = mesh.triangle(t);
        let [pa, pb, pc] = corners.map(|v| mesh.point(v));
        let skinny = self
            .angle
            .skinny(mesh, &self.kinds, &self.cdt.ends, corners, [pa, pb, pc]);
        let bad = skinny.is_some() || self.too_big(t, [pa, pb, pc]);
        if bad {
            let bucket = match skinny {
                Some(shortest) => match self.order {
                    QueueOrder::ShortestEdge => {
                        BadQueue::skinny_bucket(shortest / self.settings.extent2)
                    }
                    QueueOrder::WorstAngle => {
                        BadQueue::angle_bucket(min_angle_sin2([pa, pb, pc]).sqrt())
                    }
                },
                None => BadQueue::SIZE_BUCKET,
            };
            self.bad.push(BadTriangle {
                bucket,
                corners,
                slot: t,
            });
        }
    }

    /// Whether triangle `t` at `[pa, pb, pc]` is too big for the area bounds (global or its
    /// region's) or bad by the user's test. Inline where there are none (no call then, in the
    /// improvement's loops), out of line where there are.
    #[inline(always)]
    fn too_big(&self, t: TriangleId, points: [Point; 3]) -> bool {
        let quality = self.settings.quality;
        if quality.max_area.is_none() && !quality.variable_area && quality.user_test.is_none() {
            return false;
        }
        self.too_big_by_bounds(t, points)
    }

    /// The area bound of triangle `t` (global or its region's, the smaller), if any.
    pub(super) fn area_bound(&self, t: TriangleId) -> Option<f64> {
        let quality = self.settings.quality;
        let tag = self.mesh().tag(t);
        area_bound(
            quality.max_area,
            quality.variable_area,
            self.settings.domain,
            tag,
        )
    }

    /// [`Self::too_big`] where there are area bounds or a user's test.
    #[inline(never)]
    fn too_big_by_bounds(&self, t: TriangleId, [pa, pb, pc]: [Point; 3]) -> bool {
        let quality = self.settings.quality;
        let area = 0.5 * P::orient2d(pa, pb, pc);
        self.area_bound(t).is_some_and(|bound| area > bound)
            || quality
                .user_test
                .is_some_and(|f| f(pa[0], pa[1], pb[0], pb[1], pc[0], pc[1], area))
    }

    /// Splits bad triangle `t` at its split point, or — when a segment hides the point or the
    /// point would encroach subsegments — splits those instead (Ruppert's rule).
    fn split_triangle(&mut self, t: TriangleId, bad: BadTriangle) {
        let Some((x, frame)) = self.split_point_of(t) else {
            return;
        };
        match walk::<P>(self.mesh(), t, x) {
            Walk::Lost => self.tally.skipped += 1,
            Walk::Blocked(s) => {
                // A segment hides the new point from the triangle: the point may not be
                // inserted, and the segment is split instead (Ruppert's rule; with lenses the
                // point need not lie in its diametral circle).
                let mesh = self.mesh();
                let segment = (mesh.origin(s), mesh.dest(s), s);
                self.split_instead(&[segment], bad);
            }
            Walk::Found(location) => {
                if let Location::OnVertex(_) = location {
                    self.tally.skipped += 1; // precision exhausted here
                    return;
                }
                let mut encroached = self.cavity.encroached_by::<P>(
                    self.cdt.mesh(),
                    &self.encroachment,
                    x,
                    location,
                );
                // Subsegments that `Y`/`YY` keep whole cannot be protected by splitting them, and
                // a point that encroaches one does not go in: the bad triangle stays, as in
                // Triangle. Measured on Triangle's example files, against points that went in
                // where the triangles they made were good enough: `la.poly` with `pqYY` 291
                // triangles (Triangle's 291; was 315, and a 171.5° input angle that Triangle
                // keeps whole was split), with `pqY` 539 (Triangle's 565; was 559), and fewer
                // triangles below θ than Triangle's (109 against 111, 76 against 82).
                let kept_whole = encroached.iter().any(|&(_, _, e)| !self.may_split(e));
                encroached.retain(|&(_, _, e)| self.may_split(e));
                if !encroached.is_empty() {
                    self.split_instead(&encroached, bad);
                    return;
                }
                if kept_whole {
                    self.tally.kept_whole += 1;
                    return;
                }
                if self.too_close(x, location) {
                    self.tally.skipped += 1;
                    return;
                }
                if let Some(vertex) = self.insert_free_vertex(x, t, frame, location) {
                    self.after_insertion(vertex);
                }
            }
        }
    }

    /// The split point of triangle `t` ([`AngleBound::split_point`], rounded to the caller's
    /// grid once the mesh is on it) with its frame coordinates in `t`, where it is finite.
    fn split_point_of(&self, t: TriangleId) -> Option<(Point, (f64, f64))> {
        let points = self.mesh().triangle(t).map(|v| self.mesh().point(v));
        let (x, xi, eta) = self.angle.split_point(points);
        let x = self.placed(x);
        (x[0].is_finite() && x[1].is_finite()).then_some((x, (xi, eta)))
    }

    /// Inserts a free vertex at `x`, found at `location` from triangle `t`, its attributes
    /// interpolated at frame coordinates `(xi, eta)` in `t`. The vertex, unless it fell on
    /// another (then it is deleted again).
    fn insert_free_vertex(
        &mut self,
        x: Point,
        t: TriangleId,
        (xi, eta): (f64, f64),
        location: Location,
    ) -> Option<VertexId> {
        let corners = self.mesh().triangle(t);
        let vertex = self.new_vertex(x, VertexKind::Free);
        self.attributes.push_in_triangle(corners, xi, eta);
        if self.cdt.insert_at(vertex, location).is_err() {
            self.kinds[vertex.index()] = VertexKind::Deleted;
            return None;
        }
        Some(vertex)
    }

    /// Splits the given subsegments (`(origin, dest, half-edge)`) instead of a bad triangle whose
    /// split point encroaches on them, and queues the triangle again to be reconsidered. Only if
    /// some subsegment was split: otherwise the triangle is left as it is, so that every time a
    /// triangle is queued again refinement has made progress.
    fn split_instead(&mut self, subsegments: &[(VertexId, VertexId, EdgeId)], bad: BadTriangle) {
        for &(u, v, e) in subsegments {
            if self.may_split(e) && !self.is_unsplittable(u, v) {
                self.encroached.push_back(Encroached {
                    u,
                    v,
                    edge: e,
                    forced: true,
                });
            }
        }
        if self.split_encroached() > 0 {
            self.bad.push(bad);
        } else if subsegments.iter().all(|&(_, _, e)| !self.may_split(e)) {
            self.tally.kept_whole += 1;
        } else {
            self.tally.skipped += 1;
        }
    }

    /// Whether `x`, at `location`, would make an edge shorter than the floor.
    fn too_close(&self, x: Point, location: Location) -> bool {
        let mesh = self.mesh();
        let triangles = match location {
            Location::InTriangle(t) | Location::Outside(t) => [t, t],
            Location::OnEdge(e) => [e.triangle(), mesh.twin(e).triangle()],
            Location::OnVertex(_) => return true,
        };
        triangles
            .iter()
            .flat_map(|&t| mesh.triangle(t))
            .filter(|&v| v != GHOST)
            .any(|v| {
                let p = mesh.point(v);
                (p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2) < self.settings.floor2
            })
    }

    /// Adds vertex `p` of kind `kind` (its attributes are the caller's to add).
    fn new_vertex(&mut self, p: Point, kind: VertexKind) -> VertexId {
        let vertex = self.cdt.add_point(p);
        self.kinds.push(kind);
        self.tally.steiner_points += 1;
        self.work += 1;
        vertex
    }

    /// Inserts a free vertex at `p` (a lattice point, see [`super::lattice`]) if it lies inside
    /// a domain triangle whose tag is one of the `members` (or on an edge between two that is not
    /// a segment): located by a walk from triangle `hint` if given, else from a triangle at the
    /// first of the vertices `near` from which the walk stays in the triangulation (a concavity
    /// of the boundary may stop one), else from triangle `start`.
    /// Nothing is queued: refinement checks every triangle and subsegment when it starts.
    pub(super) fn insert_seed(
        &mut self,
        p: Point,
        hint: Option<TriangleId>,
        near: &[VertexId],
        start: TriangleId,
        members: &[bool],
    ) -> Seeded {
        if self.should_stop() {
            return Seeded::Stop;
        }
        // The starts in order: `hint`, a triangle at each vertex of `near`, `start`.
        for k in 0..near.len() + 2 {
            let from = match k {
                0 => match hint {
                    Some(t) => t,
                    None => continue,
                },
                k if k <= near.len() => match self.mesh().vertex_edge(near[k - 1]) {
                    Some(e) => e.triangle(),
                    None => continue,
                },
                _ => start,
            };
            let location = self.cdt.locate(p, from);
            let mesh = self.mesh();
            let t = match location {
                Location::Outside(_) => continue,
                Location::OnVertex(_) => return Seeded::Skipped,
                Location::InTriangle(t) => t,
                Location::OnEdge(e) => {
                    let twin = mesh.twin(e).triangle();
                    let member = members.get(mesh.tag(twin) as usize) == Some(&true);
                    if mesh.is_segment(e) || mesh.is_ghost(twin) || !member {
                        return Seeded::Skipped;
                    }
                    e.triangle()
                }
            };
            let member = members.get(mesh.tag(t) as usize) == Some(&true);
            if mesh.is_ghost(t) || !member || self.too_close(p, location) {
                return Seeded::Skipped;
            }
            let corners = mesh.triangle(t);
            // For its attributes.
            let (xi, eta) = frame_coordinates(corners.map(|v| mesh.point(v)), p);
            let vertex = self.new_vertex(p, VertexKind::Seed);
            self.attributes.push_in_triangle(corners, xi, eta);
            let _ = self.cdt.insert_at(vertex, location);
            return Seeded::Inserted(vertex);
        }
        Seeded::Skipped
    }

    /// Queues what a new vertex may have spoiled: bad triangles around it, encroached segments.
    fn after_insertion(&mut self, vertex: VertexId) {
        let mut around = std::mem::take(&mut self.around);
        around.clear();
        around.extend(self.mesh().star(vertex));
        for &e in &around {
            let t = e.triangle();
            let opposite = e.next();
            if self.mesh().is_segment(opposite) {
                self.check_segment(opposite);
            }
            if self.mesh().is_segment(e) {
                self.check_segment(e);
            }
            if inside(self.mesh(), t) {
                self.check_triangle(t);
            }
        }
        self.around = around;
    }
}
