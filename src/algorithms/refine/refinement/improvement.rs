//! Improvement of a finished refinement: one pass of decimation, one of smoothing, then a
//! polish of the worst triangles. Each is local and bounded: a vertex is tried once, with a search of at most
//! [`SEARCH`] evaluations per vertex moved. Only with our switch `R`: it takes 2–4× the time of
//! the refinement for 0.65–0.86× Triangle's triangles (refinement alone: 0.84–1.00×), and where
//! time and economy conflict the default keeps the time (issue 36; README's frontier).
//!
//! Delaunay refinement puts each vertex where a bad triangle was, and never moves it; later
//! vertices nearby (a split subsegment, a neighbour's off-centre) often leave an earlier one
//! superfluous: without it, and with its neighbours moved a little, the constrained Delaunay
//! triangulation of the others would meet every bound. So:
//! - *decimation*, once per vertex refinement placed, in the order they were made: a free vertex
//!   (a circumcentre or off-centre; not a lattice seed, which stands for the area bound's own
//!   points) is deleted ([`crate::mesh::Mesh::delete_vertex`]); the deletion stands if the
//!   triangles that fill its star have their smallest angle at least the smallest angle of the
//!   mesh's triangles that meet θ and meet the area bounds, or if moving the free corners of
//!   those that do not (optimization-based smoothing of the smallest angle: Freitag and
//!   Ollivier-Gooch 1997, by a compass search, Kolda, Lewis and Torczon 2003) makes every
//!   triangle around them so; else the moved vertices go back and it goes back in at its
//!   point. With `Y`/`YY`, where refinement leaves the bad triangles that only a vertex on a
//!   segment could mend, a deletion also stands if the triangles around the deleted vertex's
//!   link are no worse than before (smallest angle, number below the floor). A vertex that
//!   refinement put on a segment is deleted the same way when the subsegment its two
//!   subsegments become is not encroached ([`crate::mesh::Mesh::delete_segment_vertex`]; not
//!   with `Y`/`YY`). Measured on Triangle's example files, the deletions that stand are about
//!   half of those tried, and seven in eight of them need the moves; it is what makes the
//!   meshes smaller than Triangle's (0.83× its triangles on geometric mean, 0.99× without).
//!   What is sure to fail is not tried: a deletion whose star covers more than the area bound
//!   times its triangles less two (some triangle of the fewer would be over it: on the
//!   lecture's domain with `pq30a0.001`, 109 of 114 deletions tried failed, all with a triangle
//!   over the bound), a merge of subsegments whose apex, read off the link, would make a bad
//!   triangle or encroach (on `la.poly` with `pq30`, nine merges in ten failed). (Putting back
//!   at once every deletion that leaves a triangle over the bound, without moves, saved another
//!   15 % there, but the moves mend a few: the disk's `pqa` mesh of 100 triangles in the size
//!   sweep went from 100 to 102, Triangle's 100.)
//! - *smoothing*, once per free vertex left: to the centroid of its link or halfway there, if
//!   that raises its star's smallest angle (Laplacian smoothing kept Delaunay: D. A. Field,
//!   1988; accepted only where it helps, Freitag, Jones and Plassmann 1995) — for the mean
//!   radius ratio, at one or two evaluations per vertex;
//! - *polish*: the worst triangle's corners that refinement placed are moved (free ones by the
//!   same search, those on segments along them, [`super::sliding`]) while that raises its
//!   smallest angle, worst triangle first ([`Refinement::polish`]).
//!
//! A move is made only where every triangle of the star stays counter-clockwise, no subsegment
//! of its link is encroached (lens, or circle with `D`) and the area bounds hold; Lawson flips
//! restore the constrained Delaunay property (a flip never lowers the smaller of the two
//! triangles' smallest angles). Input vertices stay. A moved vertex's attributes are
//! interpolated again at its new place. Whatever a reinsertion or a flip leaves bad is the
//! driver's to refine again (the driver: not with `S` or the user's test, and only up to
//! [`IMPROVE_UP_TO`] Steiner vertices).
//!
//! An earlier design smoothed every free vertex and decimated in three rounds, then smoothed
//! again, compared two orders of refinement above 30° and split the worst triangle again
//! while that raised the smallest angle: 0.80× Triangle's triangles, a smallest angle at least
//! Triangle's on all 128 cases of the table, at 27× Triangle's time; this pass: 0.83×, 119 of
//! 128 (the others within 0.4°), at 5.2× (the refinement alone: 1.8×, 0.99× the triangles).

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::f64::consts::FRAC_1_SQRT_2;

use super::Refinement;
use crate::algorithms::delaunay::Location;
use crate::algorithms::refine::{inside, VertexKind};
use crate::geometry::{
    frame_coordinates, min_angle_sin2, min_angle_sin2_given_bc, squared_distance, Point, Predicates,
};
use crate::mesh::{Mesh, TriangleId, VertexId, GHOST};

/// How many of the worst triangles [`Refinement::polish`] may try to improve per 16 Steiner
/// vertices.
const POLISH_STEPS: usize = 4;

/// A deletion must keep the smallest angle's sine squared this fraction above the bound, and a
/// move raise it by [`GAIN`]: so that where rounding differs (the same mesh in another frame,
/// on another grid) the same vertices are moved and deleted, unless an angle falls within that
/// band. A gain, not a margin, for moves: repeated smoothing converges, with ever smaller gains
/// that would all fall within a margin's band.
pub(super) const MARGIN: f64 = 1e-6;
pub(super) const GAIN: f64 = 1e-3;

/// The compass search of [`Refinement::best_place`]: its directions, its last step (as a
/// fraction of the shortest link edge), and its most evaluations per vertex.
const COMPASS: [[f64; 2]; 8] = [
    [1.0, 0.0],
    [FRAC_1_SQRT_2, FRAC_1_SQRT_2],
    [0.0, 1.0],
    [-FRAC_1_SQRT_2, FRAC_1_SQRT_2],
    [-1.0, 0.0],
    [-FRAC_1_SQRT_2, -FRAC_1_SQRT_2],
    [0.0, -1.0],
    [FRAC_1_SQRT_2, -FRAC_1_SQRT_2],
];
const SEARCH_RESOLUTION: f64 = 1.0 / 1024.0;
/// The most evaluations of the search per vertex moved (measured on Triangle's example files:
/// 8 evaluations in the neighbours' search after a deletion give 0.847× Triangle's triangles
/// and 3 of 128 cases above its count, for 17 % less time).
const SEARCH: usize = 32;
/// Meshes with more Steiner vertices than this are left as refined: there (measured with the
/// earlier design of three whole-mesh rounds) the improvement costs many times
/// the refinement (the square with a hole with `pq30a0.0000014`, 320 000
/// vertices, 0.2 s refined, 3.3 s improved, 0.65× → 0.649× Triangle's triangles; the random
/// star polygons of 3000 and 5000 vertices with `pq20`, 16× slower); Triangle's
/// `greenland.ele` with `rq34` (41 000) is improved, in 1.3 s, to 0.85× Triangle's triangles.
const IMPROVE_UP_TO: usize = 1 << 16;

/// Buffers of [`Refinement::try_deleting`], kept between vertices so that an attempt
/// allocates little: the improvement tries nearly every free vertex.
#[derive(Default)]
pub(super) struct Scratch {
    /// The deleted vertex's link.
    neighbours: Vec<VertexId>,
    /// The triangles that fill its old star.
    made: Vec<TriangleId>,
    /// The free corners of the bad triangles a deletion made.
    candidates: Vec<VertexId>,
    /// The vertices moved after a deletion, each with its point before.
    moved: Vec<(VertexId, Point)>,
    /// Their attributes before, a row per moved vertex, in the same order.
    rows: Vec<f64>,
    /// Per link edge of the vertex [`Refinement::best_place`] moves, its squared length.
    sides: Vec<f64>,
}

impl<P: Predicates> Refinement<'_, '_, P> {
    /// Whether the finished mesh is small enough to be improved: at most [`IMPROVE_UP_TO`]
    /// Steiner vertices.
    pub(in crate::algorithms::refine) fn worth_improving(&self) -> bool {
        let steiner = self
            .kinds
            .iter()
            .filter(|k| {
                matches!(
                    k,
                    VertexKind::Free | VertexKind::Seed | VertexKind::OnSegment { .. }
                )
            })
            .count();
        steiner <= IMPROVE_UP_TO
    }

    /// Decimates the finished mesh once and polishes its worst triangles (see the module
    /// documentation).
    pub(in crate::algorithms::refine) fn improve(&mut self) {
        let floor = self.smallest_good_angle_sin2();
        let mut link = Vec::new();
        // Each vertex that refinement placed is tried once, in the order it was made (the
        // lattice seeds are the area bound's own points: a deletion there cannot stand).
        for i in 0..self.kinds.len() {
            let w = VertexId::new(i as u32);
            if self.kinds[i] == VertexKind::Free {
                self.try_deleting(w, floor, &mut link, SEARCH);
            }
        }
        for i in 0..self.kinds.len() {
            let w = VertexId::new(i as u32);
            if matches!(self.kinds[i], VertexKind::OnSegment { .. }) {
                self.try_unsplitting(w, floor);
            }
        }
        // One Laplacian step per free vertex (no search): the mean radius ratio of the
        // meshes of the size sweep 0.80 -> 0.81 at 10^2 triangles, 0.84 -> 0.85 at 10^3, for 4 %
        // more time (a search of 8 evaluations on the smallest angle instead: less of both).
        let floor = self.smallest_good_angle_sin2();
        for i in 0..self.kinds.len() {
            if self.kinds[i] == VertexKind::Free {
                self.try_smoothing(VertexId::new(i as u32), floor, &mut link, 0);
            }
        }
        self.polish(&mut link);
        // What reinsertions queued is found again by the run that follows.
        self.bad.clear();
        self.encroached.clear();
    }

    /// Raises the mesh's smallest angle where that is cheap: the worst triangle's corners
    /// that refinement placed are moved (free ones by [`Self::best_place`], those on segments
    /// along them) while that raises the triangle's angle, worst triangle first, and it stops
    /// at the first worst triangle that no move improves (the mesh's smallest angle stays
    /// there) or after [`POLISH_STEPS`] triangles per 16 Steiner vertices (plus 16). A move
    /// never lowers an angle below the one it raised, and Lawson's flips after it never lower
    /// the smaller of two triangles' smallest angles, so the smallest angle only rises.
    #[inline(never)]
    fn polish(&mut self, link: &mut Vec<(Point, Point, bool)>) {
        // Triangles below θ (those Triangle's rule excuses, or left by `Y`) are not polished,
        // and no move makes a triangle worse than the worst of those that meet θ.
        let floor = self.smallest_good_angle_sin2();
        let theta = self.angle.sin2();
        let mesh = self.mesh();
        let key = |mesh: &Mesh, t: TriangleId| {
            min_angle_sin2(mesh.triangle(t).map(|v| mesh.point(v))).to_bits()
        };
        // Sines squared are non-negative: their bit patterns order as they do.
        let mut heap: BinaryHeap<Reverse<(u64, u32)>> = mesh
            .triangles()
            .filter(|&t| !mesh.is_ghost(t) && inside(mesh, t))
            .map(|t| Reverse((key(mesh, t), t.index() as u32)))
            .filter(|&Reverse((bits, _))| f64::from_bits(bits) >= theta)
            .collect();
        let steiner = self
            .kinds
            .iter()
            .filter(|k| **k != VertexKind::Input)
            .count();
        let mut steps = 16 + POLISH_STEPS * steiner / 16;
        while let Some(Reverse((bits, t))) = heap.pop() {
            let t = TriangleId::new(t);
            let mesh = self.mesh();
            // Moves keep the triangles' slots (flips reuse theirs): an entry whose corners
            // changed is put back at its triangle's present value.
            let now = key(mesh, t);
            if now != bits {
                if now >= theta.to_bits() {
                    heap.push(Reverse((now, t.index() as u32)));
                }
                continue;
            }
            if steps == 0 {
                break;
            }
            steps -= 1;
            let mut raised = false;
            for v in mesh.triangle(t) {
                let moved = match self.kinds[v.index()] {
                    VertexKind::Free | VertexKind::Seed => {
                        self.try_smoothing(v, floor, link, SEARCH)
                    }
                    VertexKind::OnSegment { .. } => self.try_sliding(v, floor, link),
                    _ => false,
                };
                if moved {
                    let mesh = self.mesh();
                    for e in mesh.star(v) {
                        let u = e.triangle();
                        if !mesh.is_ghost(u) && inside(mesh, u) && key(mesh, u) >= theta.to_bits() {
                            heap.push(Reverse((key(mesh, u), u.index() as u32)));
                        }
                    }
                }
                raised |= moved;
            }
            if !raised {
                break;
            }
        }
    }

    /// Fills `link` with vertex `w`'s star (each triangle's edge opposite `w`, and whether that
    /// edge is a segment) and returns one of its triangles (`None` for a vertex in none).
    fn read_link(&self, w: VertexId, link: &mut Vec<(Point, Point, bool)>) -> Option<TriangleId> {
        let mesh = self.mesh();
        link.clear();
        link.extend(mesh.star(w).map(|e| {
            let (a, b) = (mesh.dest(e), mesh.apex(e));
            (mesh.point(a), mesh.point(b), mesh.is_segment(e.next()))
        }));
        mesh.vertex_edge(w).map(|e| e.triangle())
    }

    /// Moves free vertex `w` where its star's smallest angle is larger (see [`Self::best_place`])
    /// if that raises it by [`GAIN`] to at least `floor` (sine squared). `link`: scratch space.
    /// Whether it moved.
    #[inline(never)]
    fn try_smoothing(
        &mut self,
        w: VertexId,
        floor: f64,
        link: &mut Vec<(Point, Point, bool)>,
        search: usize,
    ) -> bool {
        if self.polling.poll(self.work, || 0) || !self.mesh().is_deletable(w) {
            return false;
        }
        let pw = self.mesh().point(w);
        let Some(t) = self.read_link(w, link) else {
            return false;
        };
        let old = star_min_sin2(pw, link);
        let (p, new) = self.best_place(pw, old, t, link, search);
        if new > old * (1.0 + GAIN) && new >= floor * (1.0 + MARGIN) {
            self.move_free_vertex(w, p);
            return true;
        }
        false
    }

    /// Where a free vertex at `pw` (its star's smallest angle's sine squared `old`, in triangle
    /// `t`'s region, with link `link`; at most `search` evaluations) has a larger smallest angle, and that angle's sine
    /// squared: the centroid of the link (Laplacian smoothing) or halfway there, then a compass
    /// search (steps in eight directions from a quarter of the shortest link edge down to
    /// [`SEARCH_RESOLUTION`] of it, halved when no step helps: Kolda, Lewis and Torczon,
    /// "Optimization by direct search", SIAM Review 2003) on the smallest angle, which is what
    /// the move is for (Freitag and Ollivier-Gooch's optimization-based smoothing, 1997).
    /// Every place tried is one [`Self::may_move_to_ccw`] allows, its triangles counter-clockwise.
    fn best_place(
        &mut self,
        pw: Point,
        old: f64,
        t: TriangleId,
        link: &[(Point, Point, bool)],
        search: usize,
    ) -> (Point, f64) {
        // A place's value, computed only as far as it can beat `bar` (-1 where it cannot, or
        // where the move is not allowed): the same comparisons as the full value's, for a
        // fraction of its work, since most places tried are no better. The triangles are
        // tried from the one that last failed (the value does not depend on the order: a
        // failure anywhere is -1, and the minimum is the same in any order), since nearby
        // places tried in turn mostly fail at the same triangle.
        let mut sides = std::mem::take(&mut self.improving.sides);
        sides.clear();
        sides.extend(link.iter().map(|&(a, b, _)| squared_distance(a, b)));
        let this = &*self;
        let mut first = 0;
        let mut value =
            |p: Point, bar: f64| this.place_value(p, bar, pw, t, link, &sides, &mut first);
        let n = link.len() as f64;
        let centroid = link.iter().fold([0.0, 0.0], |c, &(a, _, _)| {
            [c[0] + (a[0] - pw[0]) / n, c[1] + (a[1] - pw[1]) / n]
        });
        let (mut best, mut best_value) = (pw, old);
        for weight in [1.0, 0.5] {
            let p = this.placed([pw[0] + weight * centroid[0], pw[1] + weight * centroid[1]]);
            let v = value(p, best_value);
            if v > best_value {
                (best, best_value) = (p, v);
                break;
            }
        }
        let shortest = shortest_side(link, &sides);
        let (mut step, last) = (0.25 * shortest, SEARCH_RESOLUTION * shortest);
        let mut evaluations = 0;
        while step >= last && evaluations < search {
            let mut moved = false;
            for [dx, dy] in COMPASS {
                let p = this.placed([best[0] + step * dx, best[1] + step * dy]);
                let v = value(p, best_value);
                evaluations += 1;
                if v > best_value {
                    (best, best_value, moved) = (p, v, true);
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        self.improving.sides = sides;
        (best, best_value)
    }

    /// The value of place `p` for [`Self::best_place`] (the vertex at `pw`, in triangle `t`'s
    /// region, with link `link`, whose edges' squared lengths are `sides`): its star's smallest
    /// angle's sine squared, computed only as far as it can beat `bar` (-1 where it cannot, or
    /// where the move is not allowed). The triangles are tried from the `first`, which is set to
    /// the one that fails. Inline in both of the search's loops (no call per place).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn place_value(
        &self,
        p: Point,
        bar: f64,
        pw: Point,
        t: TriangleId,
        link: &[(Point, Point, bool)],
        sides: &[f64],
        first: &mut usize,
    ) -> f64 {
        if p == pw {
            return -1.0;
        }
        let mut smallest = f64::INFINITY;
        // The triangle over link edge `(a, b)` (squared length `side`): whether it can beat
        // `bar`.
        let mut beats = |&(a, b, _): &(Point, Point, bool), side: f64| {
            let s = min_angle_sin2_given_bc([p, a, b], side);
            if s <= bar || P::orient2d_sign_from(p, a, b) <= 0.0 {
                return false;
            }
            // `smallest.min(s)` without its NaN handling: the same value, since `smallest`
            // is never NaN and a NaN `s` is skipped either way.
            if s < smallest {
                smallest = s;
            }
            true
        };
        // From `first` to the end, then from the start to `first`: the slices' iterators
        // rather than an index wrapped around (no bounds checks, no wrap test).
        let start = *first;
        for (i, (edge, &side)) in link[start..].iter().zip(&sides[start..]).enumerate() {
            if !beats(edge, side) {
                *first = start + i;
                return -1.0;
            }
        }
        for (i, (edge, &side)) in link[..start].iter().zip(&sides[..start]).enumerate() {
            if !beats(edge, side) {
                *first = i;
                return -1.0;
            }
        }
        if self.may_move_to_ccw(p, t, link) {
            smallest
        } else {
            -1.0
        }
    }

    /// Whether free vertex of triangle `t`'s region, with link `link`, may be moved to `p`,
    /// where its triangles are counter-clockwise: no subsegment of the link is encroached (by
    /// the test refinement uses: diametral lenses, or circles with `D`), the area bounds hold.
    fn may_move_to_ccw(&self, p: Point, t: TriangleId, link: &[(Point, Point, bool)]) -> bool {
        link.iter().all(|&(a, b, segment)| {
            !((segment && self.encroachment.encroaches(a, b, p)) || self.too_big(t, [p, a, b]))
        })
    }

    /// Moves free vertex `w` to `p` in its star's kernel, its attributes interpolated there
    /// from the star's triangle that holds `p` (none to interpolate: no search for it).
    fn move_free_vertex(&mut self, w: VertexId, p: Point) {
        if self.attributes.count() == 0 {
            self.cdt.move_vertex_in_kernel(w, p);
            return;
        }
        let mesh = self.mesh();
        let holder = mesh.star(w).map(|e| e.triangle()).find(|&t| {
            let [a, b, c] = mesh.triangle(t).map(|v| mesh.point(v));
            P::orient2d(a, b, p) >= 0.0
                && P::orient2d(b, c, p) >= 0.0
                && P::orient2d(c, a, p) >= 0.0
        });
        if let Some(t) = holder {
            let corners = mesh.triangle(t);
            let (xi, eta) = frame_coordinates(corners.map(|v| mesh.point(v)), p);
            self.attributes.set_in_triangle(w, corners, xi, eta);
        }
        self.cdt.move_vertex_in_kernel(w, p);
    }

    /// Deletes free vertex `w` if the triangles that fill its star are good enough (smallest
    /// angle's sine squared at least `floor`, area bounds, user's test); else puts it back.
    /// Whether it stays deleted.
    #[inline(never)]
    fn try_deleting(
        &mut self,
        w: VertexId,
        floor: f64,
        link: &mut Vec<(Point, Point, bool)>,
        search: usize,
    ) -> bool {
        if self.polling.poll(self.work, || 0)
            || !self.mesh().is_deletable(w)
            || self.star_too_big_for_fewer(w, 2.0)
        {
            return false;
        }
        let mut neighbours = std::mem::take(&mut self.improving.neighbours);
        neighbours.clear();
        let mesh = self.mesh();
        neighbours.extend(mesh.star(w).map(|e| mesh.dest(e)).filter(|&v| v != GHOST));
        let mut made = std::mem::take(&mut self.improving.made);
        let deleted = self.try_deleting_around(w, &neighbours, &mut made, floor, link, search);
        self.improving.neighbours = neighbours;
        self.improving.made = made;
        deleted
    }

    /// Whether the `k` triangles around vertex `w` (inside the domain, in one region) cover
    /// more than `k − fewer` times the area bound of their region (the global one or the
    /// region's, the smaller): then some triangle of the `k − fewer` that would fill its star
    /// after a deletion (2 fewer inside, 1 fewer on a segment) is over the bound, and the
    /// deletion would fail (tested before deleting, which costs ten times this).
    fn star_too_big_for_fewer(&self, w: VertexId, fewer: f64) -> bool {
        let mesh = self.mesh();
        let Some(first) = mesh.vertex_edge(w) else {
            return false;
        };
        let Some(bound) = self.area_bound(first.triangle()) else {
            return false;
        };
        let pw = mesh.point(w);
        let tag = mesh.tracks_tags().then(|| mesh.tag(first.triangle()));
        let (mut k, mut doubled_area) = (0.0, 0.0);
        for e in mesh.star(w) {
            let t = e.triangle();
            if mesh.is_ghost(t) || !inside(mesh, t) {
                continue;
            }
            if tag.is_some_and(|tag| mesh.tag(t) != tag) {
                return false; // two regions' bounds: no prediction
            }
            k += 1.0;
            doubled_area += P::orient2d(pw, mesh.point(mesh.dest(e)), mesh.point(mesh.apex(e)));
        }
        0.5 * doubled_area > (k - fewer) * bound
    }

    /// [`Self::try_deleting`] of deletable `w`, whose link is `neighbours`; `made`: scratch
    /// space for the triangles a deletion makes.
    #[inline(never)]
    fn try_deleting_around(
        &mut self,
        w: VertexId,
        neighbours: &[VertexId],
        made: &mut Vec<TriangleId>,
        floor: f64,
        link: &mut Vec<(Point, Point, bool)>,
        search: usize,
    ) -> bool {
        let p = self.mesh().point(w);
        // With `Y`/`YY`, bad triangles that only a vertex on a segment could mend stay: a
        // deletion there need not make every triangle good, only leave the triangles around
        // the deleted vertex's link no worse.
        let before = (self.settings.quality.no_steiner_on_segments > 0)
            .then(|| self.quality_around(neighbours, floor));
        if !self.cdt.delete_vertex_into(w, made) {
            return false;
        }
        let made = &made[..];
        let no_worse = |this: &Self| {
            before.is_some_and(|b| {
                made.iter().all(|&t| {
                    let mesh = this.mesh();
                    mesh.is_ghost(t)
                        || !inside(mesh, t)
                        || !this.too_big(t, mesh.triangle(t).map(|v| mesh.point(v)))
                }) && this.quality_around(neighbours, floor).no_worse_than(b)
            })
        };
        if made.iter().all(|&t| self.good_enough(t, floor))
            || no_worse(self)
            || self.smooth_after_deletion(made, neighbours, floor, link, search, before)
        {
            self.kinds[w.index()] = VertexKind::Deleted;
            return true;
        }
        let start = self
            .mesh()
            .vertex_edge(neighbours[0])
            .map_or(made[0], |e| e.triangle());
        // The mesh is carved (holes, concavities): a plain walk can stop at its boundary.
        let location = self.cdt.locate_thoroughly(p, start);
        if self.cdt.insert_at(w, location).is_err() {
            // On a vertex: cannot be (the point was a vertex's own); it stays out.
            self.kinds[w.index()] = VertexKind::Deleted;
            return true;
        }
        false
    }

    /// After a deletion whose triangles `made` are not all good enough: moves the free corners
    /// of the bad ones where their stars are better (as [`Self::try_smoothing`] would, without
    /// the floor), and whether every triangle around `neighbours` (the deleted vertex's link)
    /// and the moved vertices is good enough then. If not, the moved vertices go back.
    #[inline(never)]
    fn smooth_after_deletion(
        &mut self,
        made: &[TriangleId],
        neighbours: &[VertexId],
        floor: f64,
        link: &mut Vec<(Point, Point, bool)>,
        search: usize,
        before: Option<Around>,
    ) -> bool {
        let mut candidates = std::mem::take(&mut self.improving.candidates);
        let mut moved = std::mem::take(&mut self.improving.moved);
        let mut rows = std::mem::take(&mut self.improving.rows);
        candidates.clear();
        moved.clear();
        rows.clear();
        // A block, so that every way out puts the buffers back.
        let good = 'smoothing: {
            for &t in made {
                if self.good_enough(t, floor) {
                    continue;
                }
                for v in self.mesh().triangle(t) {
                    if matches!(self.kinds[v.index()], VertexKind::Free | VertexKind::Seed)
                        && !candidates.contains(&v)
                    {
                        candidates.push(v);
                    }
                }
            }
            if candidates.is_empty() {
                break 'smoothing false;
            }
            for _ in 0..2 {
                for &x in &candidates {
                    if !self.mesh().is_deletable(x) {
                        continue;
                    }
                    let px = self.mesh().point(x);
                    let Some(t) = self.read_link(x, link) else {
                        continue;
                    };
                    let old = star_min_sin2(px, link);
                    if old >= floor * (1.0 + MARGIN) {
                        continue;
                    }
                    let (q, new) = self.best_place(px, old, t, link, search);
                    if new > old * (1.0 + GAIN) {
                        if !moved.iter().any(|m| m.0 == x) {
                            moved.push((x, px));
                            rows.extend_from_slice(self.attributes.row(x));
                        }
                        self.move_free_vertex(x, q);
                    }
                }
            }
            if moved.is_empty() {
                break 'smoothing false;
            }
            let mesh = self.mesh();
            let good = neighbours
                .iter()
                .copied()
                .chain(moved.iter().map(|m| m.0))
                .all(|v| mesh.star(v).all(|e| self.good_enough(e.triangle(), floor)))
                || before.is_some_and(|b| self.quality_around(neighbours, floor).no_worse_than(b));
            if !good {
                let k = self.attributes.count();
                for (i, &(x, px)) in moved.iter().enumerate().rev() {
                    if self.cdt.place_vertex(x, px) {
                        self.attributes.set_row(x, &rows[i * k..(i + 1) * k]);
                    }
                }
            }
            good
        };
        self.improving.candidates = candidates;
        self.improving.moved = moved;
        self.improving.rows = rows;
        good
    }

    /// Deletes vertex `w`, put on a segment by refinement, if the subsegment its two
    /// subsegments become is not encroached and the triangles that fill its star are good
    /// enough (as for [`Self::try_deleting`]); else puts it back. Whether it stays deleted.
    #[inline(never)]
    fn try_unsplitting(&mut self, w: VertexId, floor: f64) -> bool {
        // Not with `Y`/`YY` (measured: on `la.poly` with `pqY`, merging subsegments of inner
        // segments lost an 88.3° input angle that Triangle keeps whole, for 2.5% fewer
        // triangles).
        if self.polling.poll(self.work, || 0) || self.settings.quality.no_steiner_on_segments > 0 {
            return false;
        }
        let Some([a, b]) = self.mesh().segment_neighbours(w) else {
            return false;
        };
        if self.star_too_big_for_fewer(w, 1.0) || self.merged_subsegment_would_fail(w, a, b, floor)
        {
            return false;
        }
        let Some(made) = self.cdt.delete_segment_vertex(w) else {
            return false;
        };
        let e = self.mesh().find_edge(a, b).expect("the merged subsegment");
        let encroached = self.encroachment.apex_encroaches(self.mesh(), e);
        if !encroached && made.iter().all(|&t| self.good_enough(t, floor)) {
            self.kinds[w.index()] = VertexKind::Deleted;
            return true;
        }
        let _ = self.cdt.insert_at(w, Location::OnEdge(e));
        self.cdt.settle(w);
        false
    }

    /// Whether merging the subsegments `a`–`w` and `w`–`b` would leave, on a side of the
    /// segment inside the domain, the triangle over `a`–`b` bad (below `floor`, over the area
    /// bounds) or its apex encroaching `a`–`b`: that triangle's apex is the vertex of `w`'s
    /// link on that side whose circle through `a` and `b` holds none of the others (the
    /// constrained Delaunay triangulation of the side's polygon; flips across the polygon,
    /// which could change it, are rare). Decided on the link alone, before the mesh is
    /// touched: measured on Triangle's `la.poly` with `pq30`, nine merges in ten fail, most
    /// there.
    fn merged_subsegment_would_fail(
        &self,
        w: VertexId,
        a: VertexId,
        b: VertexId,
        floor: f64,
    ) -> bool {
        let mesh = self.mesh();
        let (pa, pb) = (mesh.point(a), mesh.point(b));
        let mut candidates = [[0.0; 2]; 8];
        // Each side: the link vertices met turning around `w` from one end of the segment to
        // the other, left of the merged subsegment as seen from that first end.
        for (from, to) in [(a, b), (b, a)] {
            let Some(start) = mesh.star(w).find(|&e| mesh.dest(e) == from) else {
                return false;
            };
            let t = start.triangle();
            if mesh.is_ghost(t) || !inside(mesh, t) {
                continue;
            }
            let mut count = 0;
            for e in mesh.star_from(start).skip(1) {
                let v = mesh.dest(e);
                if v == to {
                    break;
                }
                if v == GHOST || count == candidates.len() {
                    return false; // not predicted
                }
                candidates[count] = mesh.point(v);
                count += 1;
            }
            if count == 0 {
                return false;
            }
            let (pu, pv) = (mesh.point(from), mesh.point(to));
            let c = candidates[P::smallest_circle(pv, pu, &candidates[..count])];
            let triangle = [pv, pu, c];
            if P::orient2d(pv, pu, c) <= 0.0 {
                return false;
            }
            if self.encroachment.encroaches(pa, pb, c)
                || min_angle_sin2(triangle) < floor * (1.0 + MARGIN)
                || self.too_big(t, triangle)
            {
                return true;
            }
        }
        false
    }

    /// Whether triangle `t` may be made by a deletion: outside the domain, or its smallest
    /// angle's sine squared at least `floor` (with the margin) and the area bounds kept.
    fn good_enough(&self, t: TriangleId, floor: f64) -> bool {
        let mesh = self.mesh();
        if mesh.is_ghost(t) || !inside(mesh, t) {
            return true;
        }
        let points = mesh.triangle(t).map(|v| mesh.point(v));
        min_angle_sin2(points) >= floor * (1.0 + MARGIN) && !self.too_big(t, points)
    }

    /// The quality of the domain's triangles around `vertices` (each once): the smallest
    /// angle's sine squared, and how many are below `floor`.
    fn quality_around(&self, vertices: &[VertexId], floor: f64) -> Around {
        let mesh = self.mesh();
        let mut triangles: Vec<TriangleId> = vertices
            .iter()
            .flat_map(|&v| mesh.star(v).map(|e| e.triangle()))
            .filter(|&t| !mesh.is_ghost(t) && inside(mesh, t))
            .collect();
        triangles.sort_unstable();
        triangles.dedup();
        let mut around = Around {
            worst: f64::INFINITY,
            below_floor: 0,
        };
        for t in triangles {
            let s = min_angle_sin2(mesh.triangle(t).map(|v| mesh.point(v)));
            around.worst = around.worst.min(s);
            around.below_floor += usize::from(s < floor * (1.0 + MARGIN));
        }
        around
    }

    /// The sine squared of the smallest angle among the domain's triangles whose smallest angle
    /// is at least θ (θ's when there are none).
    fn smallest_good_angle_sin2(&self) -> f64 {
        let mesh = self.mesh();
        let theta = self.angle.sin2();
        mesh.triangles()
            .filter(|&t| inside(mesh, t))
            .map(|t| min_angle_sin2(mesh.triangle(t).map(|v| mesh.point(v))))
            .filter(|&s| s >= theta)
            .fold(f64::INFINITY, f64::min)
            .min(1.0)
            .max(theta)
    }
}

/// The length of the shortest of the edges `(a, b)` of `link`, whose squared lengths are
/// `sides`: the smallest `hypot`, taken only over the edges whose squared length is within a
/// relative 1e-9 of the smallest (the others' lengths are larger, by far more than the
/// rounding of either: the same minimum), unless the squares may have overflowed or lost
/// precision below the normal range.
fn shortest_side(link: &[(Point, Point, bool)], sides: &[f64]) -> f64 {
    let length = |&(a, b, _): &(Point, Point, bool)| (a[0] - b[0]).hypot(a[1] - b[1]);
    let near = sides
        .iter()
        .fold(f64::INFINITY, |m, &s| if s < m { s } else { m });
    if !(1e-280..=1e280).contains(&near) {
        return link.iter().map(length).fold(f64::INFINITY, f64::min);
    }
    let within = near * (1.0 + 1e-9);
    link.iter()
        .zip(sides)
        .filter(|&(_, &s)| s <= within)
        .map(|(edge, _)| length(edge))
        .fold(f64::INFINITY, f64::min)
}

/// The sine squared of the smallest angle of the triangles `(p, a, b)` over the link `link`.
pub(super) fn star_min_sin2(p: Point, link: &[(Point, Point, bool)]) -> f64 {
    link.iter()
        .map(|&(a, b, _)| min_angle_sin2([p, a, b]))
        .fold(f64::INFINITY, f64::min)
}

/// The quality of the triangles around some vertices ([`Refinement::quality_around`]).
#[derive(Clone, Copy)]
struct Around {
    worst: f64,
    below_floor: usize,
}

impl Around {
    /// Whether these triangles are no worse than `before`'s: their smallest angle no smaller,
    /// no more of them below the floor.
    fn no_worse_than(self, before: Around) -> bool {
        self.worst >= before.worst && self.below_floor <= before.below_floor
    }
}
