//! Two-core Delaunay triangulation: split the points by a vertical or a horizontal line through
//! their median (by count), triangulate the halves on two threads, and merge.
//!
//! The merge follows the divide-and-conquer scheme of Guibas and Stolfi (1985) and Dwyer (1987):
//! find the lower and upper common tangents of the two convex hulls, fill the region between the
//! hulls by "zipping" up from the lower tangent (at each step the candidate whose triangle has the
//! empty circumcircle, as in Guibas–Stolfi), then restore the Delaunay property with Lawson flips
//! seeded with the new edges. The flips delete exactly the edges of the halves that Guibas–Stolfi
//! delete (an edge of the final triangulation is locally Delaunay in any triangulation, so it is
//! never flipped), which keeps the merge near the seam.
//!
//! The ghost triangles along the two facing hull chains are reused as the zipped triangles: the
//! chains have as many edges as the zip makes triangles, and two new ghosts close the hull at the
//! tangents.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

use super::{order_where_in_room, triangulate_ordered, InInsertionOrder, Triangulation};
use crate::geometry::{Point, Predicates};
use crate::memory::prefault_while;
use crate::mesh::{EdgeId, Ghosts, Lawson, Mesh, Quad, TriangleId, VertexId, GHOST};

/// Below this many points one thread is faster than two.
pub const PARALLEL_THRESHOLD: usize = 20_000;

/// The merge's Lawson flips stop past one per this many points (plus 4096), and the caller
/// triangulates on one thread instead. The zip joins the two hulls' facing chains, and the flips
/// then make what Guibas and Stolfi's merge would have: near the seam, some thousands at 10^6
/// points on every distribution of the Delaunay benchmark (3 300 uniform, 7 100 on a jittered
/// grid). But where the points lie on curves around empty space (a plate's outline and the
/// outlines of its holes, the input of a quality mesh), the facing chains are a few long edges,
/// the zipped triangles span the domain, and the flips that mend them sweep the halves: 54
/// million for 341 000 points, 3 s against 0.26 s on one thread.
const POINTS_PER_MERGE_FLIP: usize = 8;

/// One half: its vertices' global ids in insertion order and its mesh in global ids.
struct Half {
    mesh: Mesh,
    duplicate_of: Vec<(u32, u32)>,
    /// The half's insertion order, no longer needed, but freed only when that cannot stall the
    /// other thread: freeing a large array unmaps it, which waits for the other thread's
    /// faults (measured: a 2 MB free in the right half's thread took 5–8 ms while the left
    /// prefaulted).
    names: Vec<u32>,
}

impl Half {
    /// Frees what the half no longer needs (its points: the merged mesh takes all the points;
    /// its order) before its thread faults in the room, so that the room's pages take their
    /// place in the peak memory: done by the half finished first, while the other builds.
    fn free_for_the_room(&mut self) {
        drop(self.mesh.replace_points(Vec::new()));
        drop(std::mem::take(&mut self.names));
    }
}

/// Triangulates the points on one side of `split` (its point's copies on the left) in a mesh
/// with room for `capacity` triangle slots, numbered as in `points`; `None` when the side has
/// fewer than three points or all of them collinear. `corners` is told where the mesh's corner
/// array lies as soon as it exists.
fn triangulate_half<P: Predicates>(
    points: &[Point],
    split: Split,
    left: bool,
    capacity: usize,
    corners: impl FnOnce(Range<usize>),
) -> Option<Half> {
    let on_side = |p: Point| split.is_left(p) == left;
    let ordered = order_where_in_room(points, on_side, capacity);
    corners(ordered.corners_extent());
    if ordered.sorted.len() < 3 {
        return None;
    }
    let InInsertionOrder {
        triangulation,
        names,
    } = triangulate_ordered::<P>(ordered);
    let Triangulation {
        mut mesh,
        duplicates,
    } = triangulation;
    if mesh.triangle_count() == 0 {
        return None;
    }
    mesh.rename_vertices(|v| VertexId::new(names[v.index()]));
    Some(Half {
        mesh,
        duplicate_of: duplicates,
        names,
    })
}

/// Faults in the pages of the corner array at `corners` (its address range) beyond its first
/// `slots` triangle slots (three `u32` corners each) while `keep_going()`: see
/// [`prefault_while`].
fn prefault_corners_beyond(corners: &Range<usize>, slots: usize, keep_going: impl Fn() -> bool) {
    let from = (corners.start + 3 * std::mem::size_of::<u32>() * slots).min(corners.end);
    prefault_while(from..corners.end, keep_going);
}

/// Which line splits the points: the halves are the points before and after `at` in the
/// lexicographic order of (x, y) for a vertical line, of (y, −x) for a horizontal one. (y, −x)
/// are the coordinates turned a quarter clockwise, a rotation: the merge, whose decisions are
/// orientations and in-circle tests, works in either frame unchanged.
///
/// The comparisons are written out rather than made on the turned point `[p[1], -p[0]]`: with
/// rustc 1.95.0 at opt-level 2 and 3, a `keep` closure building that array, inlined into the
/// loop of the insertion order's words (`order::sorted_words`), made the loop's Hilbert keys
/// wrong (safe code; the order stays a permutation, but a poor one: 7× the walks).
#[derive(Clone, Copy, Debug)]
struct Split {
    at: Point,
    horizontal: bool,
}

impl Split {
    /// The coordinate across the split line (ascending from the left half to the right).
    fn across(horizontal: bool, p: Point) -> f64 {
        p[usize::from(horizontal)]
    }

    /// The coordinate along the split line (up to its sign).
    fn along(horizontal: bool, p: Point) -> f64 {
        p[usize::from(!horizontal)]
    }

    /// Whether `p` belongs to the left half (the split point's copies do).
    fn is_left(&self, p: Point) -> bool {
        let a = self.at;
        if self.horizontal {
            p[1] < a[1] || (p[1] == a[1] && p[0] >= a[0])
        } else {
            p[0] < a[0] || (p[0] == a[0] && p[1] <= a[1])
        }
    }

    /// The lexicographic order of (x, y), or of (y, −x) for a horizontal line.
    fn compare(horizontal: bool, p: &Point, q: &Point) -> std::cmp::Ordering {
        if horizontal {
            p[1].total_cmp(&q[1]).then(q[0].total_cmp(&p[0]))
        } else {
            p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
        }
    }
}

/// The split of the points: near the median of an evenly spaced sample (the halves need not be
/// equal, only both large; the result does not depend on the split), by the line that crosses
/// fewer Delaunay edges by the sample's estimate. A line through points of density ρ crosses
/// about L·√ρ edges over a length L; among the sample's [`BAND`] points nearest the median on
/// each axis, their spread along the line stands for L and the spread across it for their
/// count over ρ·L, so (spread along / spread across) is the square of the estimate up to a
/// common factor. The spread across is the smaller of the two on either side of the median:
/// points piled on the median's line, or two lines of points on either side of it (the seam
/// between them crosses an edge per point), count as none. On uniform points in a square the
/// two lines are alike (the vertical one is kept); where the points crowd along a line (a line
/// singularity, a few vertical lines of points) the line across them crosses far fewer edges.
fn split_of(points: &[Point]) -> Split {
    const SAMPLE: usize = 4095;
    /// Sample points in the band around the median whose spreads are measured.
    const BAND: usize = 64;
    let step = (points.len() / SAMPLE).max(1);
    let mut sample: Vec<Point> = points.iter().step_by(step).copied().collect();
    let mid = sample.len() / 2;
    // For each line, the squared estimate and the median.
    let choices = [false, true].map(|horizontal| {
        let compare = |p: &Point, q: &Point| Split::compare(horizontal, p, q);
        let (_, &mut at, _) = sample.select_nth_unstable_by(mid, compare);
        // The band: the sample's points ranked from..=to around the median, moved there.
        let band = (BAND / 2).min(mid);
        let (from, to) = (mid - band, (mid + band).min(sample.len() - 1));
        if from < mid {
            sample[..mid].select_nth_unstable_by(from, compare);
        }
        if to > mid {
            sample[mid..].select_nth_unstable_by(to - mid, compare);
        }
        let mut along = [f64::MAX, f64::MIN];
        for &p in &sample[from..=to] {
            let k = Split::along(horizontal, p);
            along = [along[0].min(k), along[1].max(k)];
        }
        let median = Split::across(horizontal, at);
        let across = |rank: usize| (Split::across(horizontal, sample[rank]) - median).abs();
        let cost = (along[1] - along[0]) / across(from).min(across(to));
        (if cost.is_nan() { f64::INFINITY } else { cost }, at)
    });
    // The horizontal line only where it crosses clearly fewer edges (√2 fewer).
    let horizontal = choices[1].0 < 0.5 * choices[0].0;
    Split {
        at: choices[usize::from(horizontal)].1,
        horizontal,
    }
}

/// Triangulates with two threads; gives the points back when the split does not give two proper
/// halves (too few points, or a half with all points collinear) or the merge passes its flip
/// budget (`POINTS_PER_MERGE_FLIP`): the caller then triangulates sequentially.
pub fn triangulate_two_halves<P: Predicates>(
    points: Vec<Point>,
) -> Result<Triangulation, Vec<Point>> {
    let n = points.len();
    // Every left point precedes every right point strictly (copies of the split point go left).
    let split = split_of(&points);
    // The left mesh gets room for both halves' triangles (2n - 4 slots, and the two ghosts of
    // the merge): the right half's are appended without reallocating. Each thread orders its
    // side straight from all the points.
    // Whichever half is done first faults in the pages of the left mesh's corner room that the
    // right half's triangles are appended into (`prefault_while`), rather than wait. Not the
    // twins' room too: with both halves' arrays alive, that would add 12 bytes per vertex to
    // the peak memory.
    let left_corners: OnceLock<Range<usize>> = OnceLock::new();
    let left_done = AtomicBool::new(false);
    let (l, r) = std::thread::scope(|scope| {
        let right_job = scope.spawn(|| {
            let mut r = triangulate_half::<P>(&points, split, false, 0, |_| {});
            if let (Some(r), Some(corners)) = (&mut r, left_corners.get()) {
                if !left_done.load(Ordering::Relaxed) {
                    // The left half has the other points; its triangle slots (2 per point,
                    // less 2) end before this.
                    let left_points = n - r.mesh.vertex_count() as usize;
                    r.free_for_the_room();
                    prefault_corners_beyond(corners, (2 * left_points).saturating_sub(2), || {
                        !left_done.load(Ordering::Relaxed)
                    });
                }
            }
            r
        });
        let mut l = triangulate_half::<P>(&points, split, true, 2 * n + 4, |corners| {
            let _ = left_corners.set(corners);
        });
        left_done.store(true, Ordering::Relaxed);
        if let (Some(l), Some(corners)) = (&mut l, left_corners.get()) {
            if !right_job.is_finished() {
                let slots = l.mesh.triangle_count() as usize;
                l.free_for_the_room();
                prefault_corners_beyond(corners, slots, || !right_job.is_finished());
            }
        }
        // A panic in the right half's thread (a bug) is not hidden behind a sequential retry:
        // it goes on to `pipeline::triangulate`, which reports it as `Error::Internal`.
        let r = right_job
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (l, r)
    });
    let (Some(l), Some(mut r)) = (l, r) else {
        return Err(points);
    };
    let mut duplicates: Vec<(u32, u32)> = l
        .duplicate_of
        .iter()
        .chain(&r.duplicate_of)
        .copied()
        .collect();
    duplicates.sort_unstable();
    // One mesh: the right half's triangles after the left half's.
    let right_start = TriangleId::new(l.mesh.triangle_count());
    let mut mesh = l.mesh;
    drop(mesh.replace_points(points));
    mesh.append_on_two_threads(std::mem::take(&mut r.mesh));
    let mut merger = Merger::<P> {
        mesh,
        horizontal: split.horizontal,
        _p: Default::default(),
    };
    if !merger.merge(right_start) {
        return Err(merger.mesh.take_points());
    }
    let mut triangulation = Triangulation {
        mesh: merger.mesh,
        duplicates,
    };
    triangulation.keep_first_copies();
    Ok(triangulation)
}

/// The hull of one half, read off its ghost triangles: its vertices counter-clockwise, each
/// with the ghost triangle of the hull edge leaving it. Positions in the ring stand for the
/// vertices in the merge's walks (no map from vertex to neighbours: a hull may hold every
/// point, as on a circle's arc).
struct Hull {
    ring: Vec<(VertexId, TriangleId)>,
}

impl Hull {
    /// Walks the ring of ghost triangles of the half in `triangles` (each ghost's neighbour
    /// across its half-edge from the vertex at infinity is the ghost of the next hull edge
    /// counter-clockwise), from the first ghost in the range: O(hull) after that search, not a
    /// scan of the whole half.
    fn read(mesh: &Mesh, triangles: std::ops::Range<u32>) -> Hull {
        let slots = triangles.len();
        let first = triangles
            .map(TriangleId::new)
            .find(|&t| ghost_edge(mesh, t).is_some())
            .expect("a triangulated half has a hull");
        let mut ring = Vec::new();
        let mut ghost = first;
        for _ in 0..slots {
            let c = mesh.triangle(ghost);
            let k = c.iter().position(|&v| v == GHOST).expect("a ghost");
            // Hull edge y → x (the ghost's finite half-edge is x → y); the next ghost's edge
            // starts at x.
            ring.push((c[(k + 2) % 3], ghost));
            ghost = mesh.twin(ghost.edge(k as u32)).triangle();
            if ghost == first {
                break;
            }
        }
        Hull { ring }
    }
    fn vertex(&self, i: usize) -> VertexId {
        self.ring[i].0
    }
    fn succ(&self, i: usize) -> usize {
        if i + 1 == self.ring.len() {
            0
        } else {
            i + 1
        }
    }
    fn pred(&self, i: usize) -> usize {
        if i == 0 {
            self.ring.len() - 1
        } else {
            i - 1
        }
    }
    fn ghost_out(&self, i: usize) -> TriangleId {
        self.ring[i].1
    }
    fn ghost_in(&self, i: usize) -> TriangleId {
        self.ring[self.pred(i)].1
    }
}

/// For a ghost triangle `t`, its finite half-edge `x → y` (with the ghost vertex following `y`);
/// the hull runs counter-clockwise from `y` to `x`. `None` for a real triangle.
fn ghost_edge(mesh: &Mesh, t: TriangleId) -> Option<(VertexId, VertexId)> {
    let c = mesh.triangle(t);
    let k = c.iter().position(|&v| v == GHOST)?;
    Some((c[(k + 1) % 3], c[(k + 2) % 3]))
}

/// The half-edge of ghost triangle `t` that starts at `from` and ends at `to` (either may be GHOST).
fn half_edge(mesh: &Mesh, t: TriangleId, from: VertexId, to: VertexId) -> EdgeId {
    t.edges()
        .into_iter()
        .find(|&e| mesh.origin(e) == from && mesh.dest(e) == to)
        .expect("half-edge in ghost")
}

struct Merger<P: Predicates> {
    mesh: Mesh,
    /// The halves lie below and above a horizontal line (see [`Split`]).
    horizontal: bool,
    _p: std::marker::PhantomData<P>,
}

impl<P: Predicates> Merger<P> {
    fn pt(&self, v: VertexId) -> Point {
        self.mesh.point(v)
    }

    fn orient(&self, a: VertexId, b: VertexId, c: VertexId) -> f64 {
        P::orient2d(self.pt(a), self.pt(b), self.pt(c))
    }

    /// Whether `s`, collinear with `a → b`, lies strictly between `a` and `b`.
    fn strictly_between(&self, a: VertexId, b: VertexId, s: VertexId) -> bool {
        let (pa, pb, ps) = (self.pt(a), self.pt(b), self.pt(s));
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        let t = (ps[0] - pa[0]) * d[0] + (ps[1] - pa[1]) * d[1];
        t > 0.0 && t < d[0] * d[0] + d[1] * d[1]
    }

    /// Whether `s` is below the tangent candidate `a → b` (strictly right of it, or on it
    /// between the two), so that the tangent must move to `s`.
    fn below(&self, a: VertexId, b: VertexId, s: VertexId) -> bool {
        let o = self.orient(a, b, s);
        o < 0.0 || (o == 0.0 && self.strictly_between(a, b, s))
    }

    /// Merges the halves; whether it finished within the flip budget (if not, the mesh is
    /// not Delaunay and is to be thrown away).
    fn merge(&mut self, right_start: TriangleId) -> bool {
        let total = self.mesh.triangle_count();
        let left_hull = Hull::read(&self.mesh, 0..right_start.raw());
        let right_hull = Hull::read(&self.mesh, right_start.raw()..total);
        // The extreme points facing the other half, in the split's frame (ring positions).
        let extreme = |h: &Hull, largest: bool| {
            let order = |&a: &usize, &b: &usize| {
                let (p, q) = (self.pt(h.vertex(a)), self.pt(h.vertex(b)));
                Split::compare(self.horizontal, &p, &q)
            };
            let positions = 0..h.ring.len();
            if largest {
                positions.max_by(order)
            } else {
                positions.min_by(order)
            }
            .expect("a hull")
        };
        let (l0, r0) = (extreme(&left_hull, true), extreme(&right_hull, false));
        let (lv, rv) = (|i| left_hull.vertex(i), |i| right_hull.vertex(i));

        // Lower tangent lb → rb: every point on its left. Move l clockwise and r counter-clockwise
        // while a hull neighbour lies below.
        let (mut lb, mut rb) = (l0, r0);
        loop {
            if self.below(lv(lb), rv(rb), lv(left_hull.pred(lb))) {
                lb = left_hull.pred(lb);
            } else if self.below(lv(lb), rv(rb), rv(right_hull.succ(rb))) {
                rb = right_hull.succ(rb);
            } else {
                break;
            }
        }
        // Upper tangent rt → lt.
        let (mut lt, mut rt) = (l0, r0);
        loop {
            if self.below(rv(rt), lv(lt), lv(left_hull.succ(lt))) {
                lt = left_hull.succ(lt);
            } else if self.below(rv(rt), lv(lt), rv(right_hull.pred(rt))) {
                rt = right_hull.pred(rt);
            } else {
                break;
            }
        }

        // The facing chains: left from lb counter-clockwise to lt, right from rb clockwise to rt.
        // For each chain edge, the real half-edge on the inner side, and the ghost slot to reuse.
        // Where both tangents touch a half at one vertex (lb = lt: the other half's far points
        // swallow all of this one's hull but that vertex, as Kuzmin's distribution does), its
        // chain is the whole hull, once around.
        let mut free_slots: Vec<TriangleId> = Vec::new();
        let mut left_chain: Vec<(VertexId, EdgeId)> = Vec::new(); // (next vertex, real half-edge l→next)
        let mut i = lb;
        loop {
            let g = left_hull.ghost_out(i);
            let w = left_hull.succ(i);
            let ghost_half = half_edge(&self.mesh, g, lv(w), lv(i));
            left_chain.push((lv(w), self.mesh.twin(ghost_half)));
            free_slots.push(g);
            i = w;
            if i == lt {
                break;
            }
        }
        let mut right_chain: Vec<(VertexId, EdgeId)> = Vec::new(); // (next vertex, real half-edge next→r)
        let mut i = rb;
        loop {
            let g = right_hull.ghost_in(i);
            let w = right_hull.pred(i);
            let ghost_half = half_edge(&self.mesh, g, rv(i), rv(w));
            right_chain.push((rv(w), self.mesh.twin(ghost_half)));
            free_slots.push(g);
            i = w;
            if i == rt {
                break;
            }
        }
        let (left_whole, right_whole) = (lb == lt, rb == rt);
        // Ghost half-edges that the two new ghosts attach to (none on a half whose chain is its
        // whole hull: its ghosts all become zipped triangles, and the new ghosts meet).
        let inf_to_lb = half_edge(&self.mesh, left_hull.ghost_in(lb), GHOST, lv(lb));
        let rb_to_inf = half_edge(&self.mesh, right_hull.ghost_out(rb), rv(rb), GHOST);
        let inf_to_rt = half_edge(&self.mesh, right_hull.ghost_in(rt), GHOST, rv(rt));
        let lt_to_inf = half_edge(&self.mesh, left_hull.ghost_out(lt), lv(lt), GHOST);
        let (lb, rb, lt, rt) = (lv(lb), rv(rb), lv(lt), rv(rt));

        // Zip. Each new triangle is (l, r, x) with slot 0 the base l→r.
        let (mut l, mut r) = (lb, rb);
        let (mut li, mut ri) = (0usize, 0usize);
        let mut below_half = EdgeId::NONE; // the half-edge r→l (reversed base) of the previous triangle
        let bottom_ghost = self.mesh.add_triangle(rb, lb, GHOST);
        let mut slots = free_slots.into_iter();
        let mut new_edges: Vec<EdgeId> = Vec::new();
        while li < left_chain.len() || ri < right_chain.len() {
            let left_candidate = left_chain.get(li).map(|&(w, _)| w);
            let right_candidate = right_chain.get(ri).map(|&(w, _)| w);
            let left_ok = left_candidate.is_some_and(|w| self.orient(l, r, w) > 0.0);
            let right_ok = right_candidate.is_some_and(|w| self.orient(l, r, w) > 0.0);
            let take_right = match (left_ok, right_ok) {
                (true, true) => {
                    let (lc, rc) = (left_candidate.unwrap(), right_candidate.unwrap());
                    P::incircle_positive(self.pt(l), self.pt(r), self.pt(lc), self.pt(rc))
                }
                (false, true) => true,
                (true, false) => false,
                // Collinear leftovers (cannot happen for separated convex hulls in exact
                // arithmetic): take whichever chain still has edges.
                (false, false) => left_candidate.is_none(),
            };
            let t = slots.next().expect("one ghost slot per chain edge");
            let base = t.edge(0);
            if take_right {
                let (w, real) = right_chain[ri];
                ri += 1;
                // (l, r, w): r→w replaces the right ghost; w→l is the next reversed base.
                self.mesh.set_corners(t, [l, r, w]);
                self.mesh.link(t.edge(1), real);
                self.link_base(base, below_half, bottom_ghost);
                below_half = t.edge(2);
                r = w;
            } else {
                let (w, real) = left_chain[li];
                li += 1;
                // (l, r, w): w→l replaces the left ghost; r→w is the next reversed base.
                self.mesh.set_corners(t, [l, r, w]);
                self.mesh.link(t.edge(2), real);
                self.link_base(base, below_half, bottom_ghost);
                below_half = t.edge(1);
                l = w;
            }
            new_edges.extend_from_slice(&t.edges());
        }
        debug_assert!(l == lt && r == rt);
        let top_ghost = self.mesh.add_triangle(lt, rt, GHOST);
        // The bottom ghost (rb, lb, ∞): rb→lb, lb→∞, ∞→rb; the top ghost (lt, rt, ∞): lt→rt,
        // rt→∞, ∞→lt. Each chain has an edge, so a zipped triangle lies between them.
        let (bg, tg) = (bottom_ghost, top_ghost);
        self.mesh.link(tg.edge(0), below_half);
        if left_whole {
            self.mesh.link(bg.edge(1), tg.edge(2));
        } else {
            self.mesh.link(bg.edge(1), inf_to_lb);
            self.mesh.link(tg.edge(2), lt_to_inf);
        }
        if right_whole {
            self.mesh.link(bg.edge(2), tg.edge(1));
        } else {
            self.mesh.link(bg.edge(2), rb_to_inf);
            self.mesh.link(tg.edge(1), inf_to_rt);
        }
        // Lawson's flips from the new edges until every edge is locally Delaunay; hull and
        // ghost edges stay (the hull is already convex).
        let mut lawson = AcrossTheSeam {
            flips: 0,
            budget: self.mesh.vertex_count() as usize / POINTS_PER_MERGE_FLIP + 4096,
            exceeded: false,
        };
        self.mesh.legalize::<P, _>(&mut new_edges, &mut lawson);
        !lawson.exceeded
    }

    /// Links the base l→r of a zipped triangle to the triangle below it, or to the bottom ghost.
    fn link_base(&mut self, base: EdgeId, below_half: EdgeId, bottom_ghost: TriangleId) {
        if below_half == EdgeId::NONE {
            self.mesh.link(base, bottom_ghost.edge(0));
        } else {
            self.mesh.link(base, below_half);
        }
    }
}

/// The Lawson policy of the merge: any stacked half-edge; edges with a ghost on either side stay;
/// a flip stacks its quadrilateral's four outer edges, which it may have spoiled. Past `budget`
/// flips it stops (the stack emptied, `exceeded` set): see [`POINTS_PER_MERGE_FLIP`].
struct AcrossTheSeam {
    flips: usize,
    budget: usize,
    exceeded: bool,
}

impl Lawson for AcrossTheSeam {
    type Item = EdgeId;

    fn edge(&self, _mesh: &Mesh, e: EdgeId) -> Option<EdgeId> {
        Some(e)
    }

    fn is_fixed(&self, _mesh: &Mesh, _e: EdgeId) -> bool {
        false
    }

    fn ghosts(&self) -> Ghosts {
        Ghosts::Fixed
    }

    fn after_flip(&mut self, _quad: &Quad, [t1, t2]: [TriangleId; 2], stack: &mut Vec<EdgeId>) {
        self.flips += 1;
        if self.flips > self.budget {
            self.exceeded = true;
            stack.clear();
            return;
        }
        // (a, d, c) and (d, b, c): their four outer edges may now be illegal.
        stack.extend_from_slice(&[t1.edge(0), t1.edge(2), t2.edge(0), t2.edge(1)]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algorithms::delaunay::order::splitmix64;
    use crate::geometry::Exact;

    /// Valid, Delaunay, and with the triangle count Euler's formula gives for its hull.
    fn check(points: Vec<Point>) {
        let distinct = {
            let mut v: Vec<(u64, u64)> = points
                .iter()
                .map(|p| (p[0].to_bits(), p[1].to_bits()))
                .collect();
            v.sort_unstable();
            v.dedup();
            v.len()
        };
        let t = triangulate_two_halves::<Exact>(points).unwrap_or_else(|_| panic!("no split"));
        let m = &t.mesh;
        m.check_topology().unwrap();
        let mut ghosts = 0;
        for tri in m.triangles() {
            if m.is_ghost(tri) {
                ghosts += 1;
                continue;
            }
            let [a, b, c] = m.triangle(tri).map(|v| m.point(v));
            assert!(Exact::orient2d(a, b, c) > 0.0);
            for e in tri.edges() {
                let q = m.apex(m.twin(e));
                if q != GHOST {
                    assert!(Exact::incircle(a, b, c, m.point(q)) <= 0.0, "not Delaunay");
                }
            }
        }
        let real = m.triangle_count() as usize - ghosts;
        assert_eq!(real, 2 * distinct - 2 - ghosts);
        // The boundary passes each of its vertices once and turns left there: it is the convex
        // hull.
        let mut hull = std::collections::HashMap::new();
        for (x, y) in m.triangles().filter_map(|t| ghost_edge(m, t)) {
            assert!(
                hull.insert(y, x).is_none(),
                "a vertex twice on the boundary"
            );
        }
        for (&a, &b) in &hull {
            let c = hull[&b];
            assert!(
                Exact::orient2d(m.point(a), m.point(b), m.point(c)) >= 0.0,
                "not convex"
            );
        }
        assert_eq!(t.duplicates.len(), m.vertex_count() as usize - distinct);
        for &(v, u) in &t.duplicates {
            assert_eq!(m.point(VertexId::new(v)), m.point(VertexId::new(u)));
            assert!(u < v, "the first copy is the one in the mesh");
        }
    }

    fn uniform(n: usize, seed: u64) -> Vec<Point> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                [
                    splitmix64(&mut s) as f64 / u64::MAX as f64,
                    splitmix64(&mut s) as f64 / u64::MAX as f64,
                ]
            })
            .collect()
    }

    #[test]
    fn outlines_around_empty_space_go_back_to_one_thread() {
        // A plate's outline and four round holes' (the points of a quality mesh's input): the
        // halves' facing chains are two long edges, and mending the zip would sweep the halves
        // (the flips grow with the square of the points); past the budget the points come back.
        let mut points = Vec::new();
        let per_side = 4000;
        for k in 0..per_side {
            let t = k as f64 / per_side as f64;
            points.extend([[t, 0.0], [1.0, t], [1.0 - t, 1.0], [0.0, 1.0 - t]]);
        }
        for (cx, cy, r) in [(0.27, 0.30, 0.12), (0.71, 0.28, 0.10), (0.30, 0.72, 0.09)] {
            for k in 0..5000 {
                let a = std::f64::consts::TAU * k as f64 / 5000.0;
                points.push([cx + r * a.cos(), cy + r * a.sin()]);
            }
        }
        let given = points.clone();
        match triangulate_two_halves::<Exact>(points) {
            Err(back) => assert_eq!(back, given, "the points come back as given"),
            Ok(_) => panic!("the merge was expected to give up"),
        }
    }

    #[test]
    fn uniform_points() {
        for seed in 0..4 {
            check(uniform(3000 + 17 * seed as usize, seed));
        }
    }

    #[test]
    fn grid_with_collinear_seams_and_duplicates() {
        let mut pts = Vec::new();
        for i in 0..60 {
            for j in 0..50 {
                pts.push([i as f64, j as f64]);
            }
        }
        // Copies of the points on the split column, so that copies straddle the median.
        let copies: Vec<Point> = pts.iter().filter(|p| p[0] == 30.0).copied().collect();
        pts.extend(copies);
        check(pts);
    }

    #[test]
    fn few_vertical_lines_and_a_circle() {
        let mut s = 9;
        let mut pts: Vec<Point> = (0..4000)
            .map(|i| [(i % 4) as f64, (splitmix64(&mut s) % 100_000) as f64 * 1e-3])
            .collect();
        check(pts.clone());
        pts.clear();
        for i in 0..2048 {
            let a = i as f64 * std::f64::consts::TAU / 2048.0;
            pts.push([a.cos(), a.sin()]);
        }
        pts.push([0.0, 0.0]);
        check(pts);
    }

    /// The split line: vertical on uniform points, horizontal across points crowding along a
    /// vertical line or on a few vertical lines (one split per case also merged and checked).
    #[test]
    fn the_split_crosses_the_crowding() {
        let square = uniform(30_000, 8);
        assert!(!split_of(&square).horizontal);
        let mut s = 4;
        let mut unit = || splitmix64(&mut s) as f64 / u64::MAX as f64;
        let singular: Vec<Point> = (0..30_000)
            .map(|_| [1e-3 / (1e-3 + unit()), unit()])
            .collect();
        let lines: Vec<Point> = (0..30_000).map(|i| [(i % 4) as f64, unit()]).collect();
        for points in [singular, lines] {
            assert!(split_of(&points).horizontal);
            check(points.clone());
            // Turned a quarter: the crowding is across the other line.
            let turned: Vec<Point> = points.iter().map(|p| [p[1], p[0]]).collect();
            assert!(!split_of(&turned).horizontal);
        }
    }

    /// Far points on one side swallow the other half's whole hull but one vertex (both tangents
    /// touch it there, as on Kuzmin's distribution): that half's chain is its whole hull.
    #[test]
    fn a_half_whose_hull_all_faces_the_other() {
        let mut s = 3;
        let mut unit = || splitmix64(&mut s) as f64 / u64::MAX as f64;
        let mut points: Vec<Point> = Vec::new();
        for c in [-1.0, 1.0] {
            for _ in 0..1000 {
                points.push([c + 0.2 * (unit() - 0.5), 0.2 * (unit() - 0.5)]);
            }
        }
        points.extend([[-1e4, 0.0], [1e4, 1e4], [1e4, -1e4]]);
        check(points.clone());
        // The mirror image: the right half is swallowed.
        check(points.iter().map(|p| [-p[0], p[1]]).collect());
    }

    #[test]
    fn clustered_and_tiny_scale() {
        let mut s = 5;
        let mut pts = Vec::new();
        for c in 0..20 {
            let (cx, cy) = ((c % 5) as f64 * 10.0, (c / 5) as f64 * 10.0);
            for _ in 0..200 {
                let r = splitmix64(&mut s) as f64 / u64::MAX as f64 * 1e-3;
                let a = splitmix64(&mut s) as f64 / u64::MAX as f64 * std::f64::consts::TAU;
                pts.push([cx + r * a.cos(), cy + r * a.sin()]);
            }
        }
        check(pts);
        check(
            uniform(2000, 77)
                .iter()
                .map(|p| [1e12 + p[0] * 1e-3, -1e12 + p[1] * 1e-3])
                .collect(),
        );
    }
}
